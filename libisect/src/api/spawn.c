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
#include "mesh/mesh.h"
#include "core/dyadic_sum.h"
#include "core/scaling.h"

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

/* 1 when q (a point off hit->point) is strictly on side want of the
 * surface and, for a closed mesh, strictly inside (want < 0) or outside it
 * by the exact crossing count: a point on another face (through an edge of
 * the hit face) is on neither side, and a ray from it would meet that face
 * at t = 0. 0 when not; or a negative status. */
static int spawn_origin_ok(const shape_family *f, const isect_shape *shape, const isect_hit *hit,
                           const double q[3], int want, int closed_mesh)
{
    if (q[0] == hit->point[0] && q[1] == hit->point[1] && q[2] == hit->point[2])
        return 0;
    int side = shape_point_side(f, shape, q, hit->prim);
    if (side == ISECT_E_NONFINITE)
        return side; /* the transform left the doubles */
    if (side != want)
        return 0;
    if (!closed_mesh)
        return 1;
    double object_q[3];
    const double *p = q;
    if (shape->xform != NULL) {
        xform_point_to_object(shape->xform, q, object_q);
        p = object_q; /* finite: the side test above took the same image */
    }
    int64_t crossings;
    if (mesh_crossing_count(shape->mesh, p, &crossings))
        return 0; /* on the surface */
    return (crossings & 1) == (want < 0);
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
    /* a closed mesh's containment by its exact crossing parity, whatever
     * rule the descriptor carries, must agree with the face's side test */
    int closed_mesh = shape->type == ISECT_MESH && shape_is_solid(f, shape);
    /* Two offsets per step: along the normal alone, then, where that fails,
     * along want*normal + dir/max|dir_k|. The second is for a hit on an
     * edge or corner of a solid (a box, a convex polyhedron, a capped
     * cylinder's rim, a mesh's edge) when dir points into the solid: moving
     * along the hit face's inward normal keeps the point on the other
     * face through that edge, at every step, and no step would ever be
     * strictly inside; a direction strictly inside the solid's tangent cone
     * plus a vector on its boundary is strictly inside it. On a smooth
     * surface or a face's interior the first offset wins, as before. */
    double step = ulp_of(v3_max_abs(hit->point));
    /* dir scaled by a power of two to a largest component in [0.5, 1): exact,
     * even for a subnormal direction (1/max|dir_k| could overflow) */
    double along[3];
    int dir_exp = pow2_exponent(v3_max_abs(dir));
    for (int k = 0; k < 3; k++)
        along[k] = want * hit->normal[k] + pow2_scale(dir[k], -dir_exp);
    double q[3];
    for (;;) {
        int found = 0;
        for (int tries = 0; tries < 2 && !found; tries++) {
            const double *off = tries == 0 ? hit->normal : along;
            double sign = tries == 0 ? want : 1.0;
            for (int k = 0; k < 3; k++)
                q[k] = hit->point[k] + sign * step * off[k];
            if (!all_finite(q, 3))
                return ISECT_E_DEGENERATE; /* the surface could not be left */
            found = spawn_origin_ok(f, shape, hit, q, want, closed_mesh);
            if (found < 0)
                return found;
        }
        if (found)
            break;
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
