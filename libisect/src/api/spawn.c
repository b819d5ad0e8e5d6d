/* SPDX-License-Identifier: Apache-2.0 */
/*
 * spawn.c — isect_spawn_ray: a ray that leaves a surface at a hit without
 * meeting that surface again at t ~ 0 (pbrt's OffsetRayOrigin, made exact).
 *
 * A reported hit point is within a few ulps of the surface, on either side
 * of it. The spawned origin is the point moved along the hit's normal, to
 * the side the new direction points into, by whole ulps of the point's
 * largest coordinate: 1, 2, 4, ... until the shape's exact side test
 * (prim/prim.h, in object space for a transformed shape) puts it strictly
 * on that side — and, for a closed mesh, the exact containment test agrees
 * (near a concave edge the hit face's plane alone could leave the origin
 * inside the solid). The kernels decide tmin = 0 exactly, so a crossing of
 * the surface the ray leaves, now strictly behind the origin, is never
 * reported; the offset is the smallest of those steps, so a second surface
 * more than a few ulps away is never skipped.
 */
#include "api/dispatch.h"
#include "core/dyadic_sum.h"

#include "core/vec3.h"

#include <float.h>

/* 2^(exponent of m - 52): the spacing of the doubles at m (m > 0 normal),
 * the smallest subnormal below. */
static double ulp_of(double m)
{
    if (!(m >= DBL_MIN))
        return 0x1p-1074;
    int e;
    (void)frexp(m, &e);
    return ldexp(1.0, e - 53);
}

/*
 * The exact sign of dir against the surface at the hit. A flat prim (plane,
 * triangle, polygon, convex face, mesh face) answers against its exact plane
 * (shape_direction_side): the hit's unit normal is that plane's rounded, up
 * to ~4u off in direction, and a direction within that of the plane (found
 * by fuzz_spawn: the rounded normal of a 45-degree triangle exactly
 * perpendicular to dir, the exact plane not) would start the ray on the
 * side it then crosses back from. Untransformed, the plain dot product with
 * the normal decides first where it clears that error and its own rounding
 * (8u |dir| <= 2^-48 max|dir_k| covers both; 2^-46 leaves a margin; 2^-1000
 * covers products that underflowed). A curved prim's surface direction is
 * the hit's normal itself: its dot product's exact sign (dyadic_sum: a
 * subnormal direction's plain product can underflow to -0).
 */
static int direction_side(const shape_family *f, const isect_shape *shape, const isect_hit *hit,
                          const double dir[3])
{
    double dot_plain = v3_dot(dir, hit->normal);
    if (shape->xform == NULL && fabs(dot_plain) > 0x1p-46 * v3_max_abs(dir) + 0x1p-1000)
        return dot_plain > 0.0 ? 1 : -1;
    int side = shape_direction_side(f, shape, dir, hit->prim);
    if (side != SIDE_CURVED)
        return side;
    dyadic_sum dot;
    dyadic_init(&dot);
    for (int k = 0; k < 3; k++)
        dyadic_add3(&dot, 1.0, dir[k], hit->normal[k], 1.0);
    return dyadic_sign(&dot);
}

ISECT_API int isect_spawn_ray(const isect_shape *shape, const isect_hit *hit, const double dir[3],
                              isect_ray *out)
{
    int status;
    const shape_family *f = shape_prepare(shape, &status);
    if (f == NULL)
        return status;
    if (hit == NULL || dir == NULL || out == NULL)
        return ISECT_E_ARG;
    if (hit->kind != ISECT_ENTER && hit->kind != ISECT_EXIT && hit->kind != ISECT_TOUCH)
        return ISECT_E_ARG;
    if (!shape_prim_valid(shape, hit->prim))
        return ISECT_E_ARG;
    if (!all_finite(hit->point, 3) || !all_finite(hit->normal, 3) || !all_finite(dir, 3))
        return ISECT_E_NONFINITE;
    if (dir[0] == 0.0 && dir[1] == 0.0 && dir[2] == 0.0)
        return ISECT_E_DEGENERATE;
    if (hit->normal[0] == 0.0 && hit->normal[1] == 0.0 && hit->normal[2] == 0.0)
        return ISECT_E_ARG; /* not a record of a hit */

    /* The side dir points into: in front of the surface (outside a solid),
     * or behind it; a direction along the tangent plane leaves in front. */
    int dot_sign = direction_side(f, shape, hit, dir);
    if (dot_sign == ISECT_E_NONFINITE)
        return dot_sign; /* the transform left the doubles */
    int want = dot_sign >= 0 ? 1 : -1;
    int closed_solid = shape->type == ISECT_MESH && shape_is_solid(f, shape);
    /* a closed mesh's containment by crossing parity, whatever rule the
     * descriptor carries: exact, and what the side test must agree with */
    isect_shape parity = *shape;
    parity.flags = ISECT_EVEN_ODD;
    double step = ulp_of(v3_max_abs(hit->point));
    double q[3];
    for (;;) {
        for (int k = 0; k < 3; k++)
            q[k] = hit->point[k] + want * step * hit->normal[k];
        if (!all_finite(q, 3))
            return ISECT_E_DEGENERATE; /* the surface could not be left */
        if (q[0] != hit->point[0] || q[1] != hit->point[1] || q[2] != hit->point[2]) {
            int side = shape_point_side(f, shape, q, hit->prim);
            if (side == ISECT_E_NONFINITE)
                return side; /* the transform left the doubles */
            if (side == want) {
                if (!closed_solid)
                    break;
                int inside = shape_point_inside(f, &parity, q);
                if (inside < 0)
                    return inside;
                if (inside == (want < 0))
                    break;
            }
        }
        step *= 2.0;
    }
    for (int k = 0; k < 3; k++) {
        out->org[k] = q[k];
        out->dir[k] = dir[k];
    }
    out->tmin = 0.0;
    out->tmax = INFINITY;
    return ISECT_OK;
}
