/*
 * isect_internal.h — what the primitive files share with the dispatcher.
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
 * The public isect_ray_X functions are thin wrappers that build a descriptor
 * and call scalar_intersect() in shape.c, so validation, filtering, sorting
 * and the snprintf-style copy are written once.
 */
#ifndef ISECT_INTERNAL_H
#define ISECT_INTERNAL_H

#include "isect.h"

#include <math.h>

/* The most hits an analytic primitive can have along one line. */
#define ISECT_MAX_HITS 4

/* Options resolved from a possibly NULL / short isect_opts. */
typedef struct isect_params {
    uint32_t flags;
    double   eps;
} isect_params;

/* opts -> params (NULL means defaults); ISECT_OK or an error. */
int params_from_opts(const isect_opts *opts, isect_params *prm);

/* ISECT_OK, ISECT_E_NONFINITE (NaN/Inf in org/dir, NaN in tmin/tmax) or
 * ISECT_E_DEGENERATE (dir == 0). */
int ray_check(const isect_ray *ray);

/* 1 when all n numbers are finite. */
int all_finite(const double *x, int64_t n);

/* Fill h: t, point = org + t*dir, normal (copied; must be unit), uv = 0,
 * prim, kind. */
void hit_set(isect_hit *h, const isect_ray *ray, double t, const double normal[3],
             int32_t prim, int32_t kind);

/* ENTER/EXIT from the sign of dir.normal (normal outward or front-facing). */
int32_t hit_kind_from_normal(const double dir[3], const double normal[3]);

/* Build the descriptor of a scalar call and run it through the shared path. */
int scalar_intersect(const isect_shape *s, const isect_ray *ray, const isect_opts *opts,
                     isect_hit *hits, int cap);

/* The shape families. */
#define ISECT_DECLARE_SHAPE(X)                                                   \
    int X##_check(const isect_shape *s);                                         \
    int X##_hits(const isect_shape *s, const isect_ray *ray,                     \
                 const isect_params *prm, isect_hit out[ISECT_MAX_HITS]);        \
    int X##_contains(const isect_shape *s, const double p[3]);

ISECT_DECLARE_SHAPE(plane)        /* plane.c    (contains: unused, thin)     */
ISECT_DECLARE_SHAPE(sphere)       /* sphere.c                                */
ISECT_DECLARE_SHAPE(ellipsoid)    /* sphere.c: the unit sphere, scaled       */
ISECT_DECLARE_SHAPE(aabb)         /* box.c                                   */
ISECT_DECLARE_SHAPE(triangle)     /* triangle.c (contains: unused, thin)     */
ISECT_DECLARE_SHAPE(polygon)      /* polygon.c  (contains: unused, thin)     */
ISECT_DECLARE_SHAPE(convex)       /* convex.c                                */
ISECT_DECLARE_SHAPE(cylinder)     /* cylinder.c (contains: capped only)      */
ISECT_DECLARE_SHAPE(cylinder_inf) /* cylinder.c                              */
ISECT_DECLARE_SHAPE(quadric)      /* quadric.c                               */

#endif /* ISECT_INTERNAL_H */
