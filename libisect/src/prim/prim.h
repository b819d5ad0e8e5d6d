/* SPDX-License-Identifier: Apache-2.0 */
/*
 * prim.h — what the primitive files provide and share.
 *
 * Each family of primitives lives in its own file and provides, per shape
 * type, three functions over the isect_shape descriptor:
 *
 *   int  X_check(const isect_shape *s);
 *        Validate s->data / s->n / s->flags for this type (the dispatcher
 *        has already checked type, reserved, data != NULL and that n/flags
 *        are 0 for types that do not use them). Returns ISECT_OK or an error:
 *        ISECT_E_NONFINITE for NaN/Inf, ISECT_E_ARG for a negative radius,
 *        bad count, bad rule or flag. Degenerate geometry is ISECT_OK.
 *
 *   int  X_hits(const isect_shape *s, const isect_ray *ray,
 *               const isect_params *prm, isect_hit out[ISECT_MAX_HITS]);
 *        All intersections of the ray's whole LINE with the surface (any t;
 *        the dispatcher keeps tmin <= t <= tmax, applies ISECT_CULL_BACK and
 *        sorts by (t, prim)). The ray is valid (finite org/dir, dir != 0) and
 *        in object space. Each hit has t, point, unit normal, uv, prim, kind
 *        filled (hit_set() does the common part). Returns the count
 *        (0..ISECT_MAX_HITS). Must never fail.
 *
 *   int  X_contains(const isect_shape *s, const double p[3]);
 *        Solids only: 1 inside (closed set), 0 outside; p is finite and in
 *        object space. NULL in the table for thin surfaces.
 *
 * The public isect_ray_X functions (api/scalar.c) build a descriptor and run
 * it through the dispatcher, so validation, filtering, sorting and the
 * snprintf-style copy are written once.
 */
#ifndef ISECT_PRIM_H
#define ISECT_PRIM_H

#include "core/core.h"

/* The most hits an analytic primitive can have along one line. */
#define ISECT_MAX_HITS 4

/* Fill h: t, point = org + t*dir, normal (copied; must be unit), uv = 0,
 * prim, kind. */
void hit_set(isect_hit *h, const isect_ray *ray, double t, const double normal[3],
             int32_t prim, int32_t kind);

/* hit_set for a crossing decided to lie in [tmin, tmax] whose parameter is
 * known as the double-double t_hi + t_lo (world units): t is t_hi clamped
 * into [tmin, tmax] (which its rounding may have left by an ulp), the point
 * org + (t_hi + t_lo) dir with one rounding per coordinate (error-free
 * products and sums), so within half an ulp plus |dir| |t error| of the
 * exact crossing point even when |org| is far larger than the point. */
void hit_set_dd(isect_hit *h, const isect_ray *ray, double t_hi, double t_lo,
                const double normal[3], int32_t prim, int32_t kind);

/* The hits of a line from a fast kernel that decided its two crossings in
 * part (prim_lanes.h: lane_pair), in kernel order: crossing i is rec[i]
 * where decided[i] (reported when in[i]), else the exact path's hits of
 * kind[i] (exact[0 .. exact_count); not read when both are decided). The
 * exact path decides exactly as the kernel does where both decide, so the
 * two agree on which crossings exist. Returns the count written to out. */
int hits_merge(const isect_hit rec[2], const int decided[2], const int in[2],
               const int32_t kind[2], const isect_hit *exact, int exact_count,
               isect_hit out[ISECT_MAX_HITS]);

/* ENTER/EXIT from the sign of dir.normal (normal outward or front-facing). */
int32_t hit_kind_from_normal(const double dir[3], const double normal[3]);

/* A batch record for a ray with no hit (ISECT_MISS: t = +inf) or a bad ray
 * (ISECT_INVALID: t = NaN); prim -1, everything else 0. */
void hit_set_miss(isect_hit *h, int32_t kind);

/* Keep the hits with tmin <= t <= tmax (and, for a thin surface under
 * ISECT_CULL_BACK, drop EXIT hits), sort by (t, prim); returns how many are
 * kept, compacted to the front of h. */
int hits_finish(isect_hit *h, int count, const isect_ray *ray, const isect_params *prm,
                int thin);

/* The batch record of a ray whose query returned found (a first-hit
 * query's result, or ray_check's status): 1 for a hit (the record already
 * written), else the record becomes ISECT_MISS (0) or ISECT_INVALID (< 0)
 * and 0. */
static inline int64_t batch_record(isect_hit *rec, int found)
{
    if (found > 0)
        return 1;
    hit_set_miss(rec, found < 0 ? ISECT_INVALID : ISECT_MISS);
    return 0;
}

/* The shape families. */
#define ISECT_DECLARE_SHAPE(X)                                                   \
    int X##_check(const isect_shape *s);                                         \
    int X##_hits(const isect_shape *s, const isect_ray *ray,                     \
                 const isect_params *prm, isect_hit out[ISECT_MAX_HITS]);        \
    int X##_contains(const isect_shape *s, const double p[3]);

ISECT_DECLARE_SHAPE(plane)        /* plane.c    (contains: unused, thin)     */
ISECT_DECLARE_SHAPE(sphere)       /* sphere.c                                */
ISECT_DECLARE_SHAPE(ellipsoid)    /* ellipsoid.c                             */
ISECT_DECLARE_SHAPE(aabb)         /* box.c                                   */
ISECT_DECLARE_SHAPE(triangle)     /* triangle.c (contains: unused, thin)     */
ISECT_DECLARE_SHAPE(polygon)      /* polygon.c  (contains: unused, thin)     */
ISECT_DECLARE_SHAPE(convex)       /* convex.c                                */
ISECT_DECLARE_SHAPE(cylinder)     /* cylinder.c (contains: capped only)      */
ISECT_DECLARE_SHAPE(cylinder_inf) /* cylinder.c                              */
ISECT_DECLARE_SHAPE(quadric)      /* quadric.c                               */

/* Exact side tests, for spawning rays off a surface (api/spawn.c) and for
 * containment: the sign of the shape's implicit function at p (object
 * space), evaluated exactly (expansion.h): -1 strictly inside, or behind
 * a thin surface's own normal; +1 strictly outside, or in front of it; 0
 * on the surface. prim picks the part of a thin surface with several (a
 * mesh face); solids ignore it. Degenerate shapes (never hit) answer +1. */
int sphere_side(const double *data, const double p[3]);
#define ISECT_DECLARE_SIDE(X) int X##_side_test(const isect_shape *s, const double p[3], int32_t prim);
ISECT_DECLARE_SIDE(plane)
ISECT_DECLARE_SIDE(sphere)
ISECT_DECLARE_SIDE(ellipsoid)
ISECT_DECLARE_SIDE(aabb)
ISECT_DECLARE_SIDE(triangle)
ISECT_DECLARE_SIDE(polygon)
ISECT_DECLARE_SIDE(convex)
ISECT_DECLARE_SIDE(cylinder)
ISECT_DECLARE_SIDE(cylinder_inf)
ISECT_DECLARE_SIDE(quadric)

/* Exact side of a direction d (object space) against the plane of a flat
 * surface at prim, for spawning rays off it (api/spawn.c): +1 when d points
 * to the side X_side_test calls +1, -1 to the other, 0 along the plane. A
 * hit's rounded unit normal cannot decide a nearly tangent d: the exact
 * plane can lean the other way by an ulp. SIDE_CURVED when prim has no
 * single plane (the caller then takes the hit's normal as the surface's). */
#define SIDE_CURVED 2
#define ISECT_DECLARE_TANGENT(X) \
    int X##_tangent_side(const isect_shape *s, const double d[3], int32_t prim);
ISECT_DECLARE_TANGENT(plane)
ISECT_DECLARE_TANGENT(triangle)
ISECT_DECLARE_TANGENT(polygon)
ISECT_DECLARE_TANGENT(convex)

/* The exact side of p (w = 1), or of the direction p (w = 0), against the
 * plane through the polygon whose i-th vertex is v + 3*idx[i] (idx NULL:
 * v + 3*i), n >= 3: the plane through the vertex centroid with Newell's
 * normal, both exact (the polygon's plane as the golden reference defines
 * it; a triangle's Newell normal is (b - a) x (c - a)). +1 in front of the
 * normal. */
int polygon_plane_sign(const double *v, const int32_t *idx, int n, const double p[3], int w);

#endif /* ISECT_PRIM_H */
