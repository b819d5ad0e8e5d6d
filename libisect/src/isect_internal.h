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

/* For code written once and compiled into several specialised copies (a
 * constant argument, or a caller built for another instruction set, as
 * mesh_query.c's FMA leaf loop): inlined where GCC and clang can be told. */
#if defined(__GNUC__) || defined(__clang__)
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE inline
#endif

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
 * ISECT_E_DEGENERATE (dir == 0). Inline: every ray of a batch passes here.
 * x - x is 0 for finite x and NaN for +-Inf or NaN, and a NaN survives any
 * sum, so one tree of additions (depth 3, not a serial chain of six) tests
 * all six coordinates. */
static inline int ray_check(const isect_ray *ray)
{
    const double *o = ray->org, *d = ray->dir;
    double probe = ((o[0] - o[0]) + (o[1] - o[1])) + ((o[2] - o[2]) + (d[0] - d[0]))
                 + ((d[1] - d[1]) + (d[2] - d[2]));
    if (probe != 0.0 || isnan(ray->tmin) || isnan(ray->tmax))
        return ISECT_E_NONFINITE;
    if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0)
        return ISECT_E_DEGENERATE;
    return ISECT_OK;
}

/* 1 when all n numbers are finite. */
int all_finite(const double *x, int64_t n);

/* Fill h: t, point = org + t*dir, normal (copied; must be unit), uv = 0,
 * prim, kind. */
void hit_set(isect_hit *h, const isect_ray *ray, double t, const double normal[3],
             int32_t prim, int32_t kind);

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

/* A validated shape: its family's functions and whether it is a solid. */
typedef struct shape_family shape_family;

/* Validate s (type, reserved, data, n/flags, xform, geometry); returns its
 * family, or NULL with *status set to the error. */
const shape_family *shape_prepare(const isect_shape *s, int *status);

/* The options, then the shape, of a ray query (the order every entry point
 * checks them in): the family, or NULL with *status set. */
const shape_family *query_prepare(const isect_shape *s, const isect_opts *opts,
                                  isect_params *prm, int *status);

/* All hits of a valid world-space ray with a prepared shape in [tmin, tmax],
 * sorted, the first min(count, cap) written in world space; returns count,
 * or ISECT_E_NONFINITE if the transform takes the ray out of the finite
 * doubles. */
int64_t shape_ray_hits(const shape_family *f, const isect_shape *s, const isect_ray *ray,
                       const isect_params *prm, isect_hit *hits, int64_t cap);

/* The first of those hits alone (bit for bit the record shape_ray_hits
 * would write first; any hit under ISECT_ANY_HIT): 1 and *out, 0, or
 * ISECT_E_NONFINITE as above. */
int shape_ray_first(const shape_family *f, const isect_shape *s, const isect_ray *ray,
                    const isect_params *prm, isect_hit *out);

/* isect_intersect_batch's work after the argument checks, for a family
 * that runs many rays at once (the mesh: several traversals in flight):
 * closest[i] and the count of rays hit exactly as batch.c's per-ray loop
 * over ray_check and shape_ray_first writes them. */
typedef int64_t (*first_batch_fn)(const shape_family *f, const isect_shape *s,
                                  const isect_ray *rays, int64_t n, const isect_params *prm,
                                  isect_hit *closest);

/* The family's first_batch, or NULL (then the per-ray loop runs). */
first_batch_fn shape_first_batch(const shape_family *f);

/* The object-space ray of a valid world-space ray, as every query sees it:
 * ISECT_OK with *r = ray (no transform) or tmp (the transformed ray), or
 * the ray_check status of the transformed ray (a huge inverse can take a
 * fine ray out of the finite doubles). */
int shape_object_ray(const isect_shape *s, const isect_ray *ray, isect_ray *tmp,
                     const isect_ray **r);

/* The batch record of a ray whose query returned found (shape_ray_first's
 * result, or ray_check's status): 1 for a hit (the record already written),
 * else the record becomes ISECT_MISS (0) or ISECT_INVALID (< 0) and 0. */
static inline int64_t batch_record(isect_hit *rec, int found)
{
    if (found > 0)
        return 1;
    hit_set_miss(rec, found < 0 ? ISECT_INVALID : ISECT_MISS);
    return 0;
}

/* 1 when the shape has an inside (contains() applies), 0 for thin surfaces. */
int shape_is_solid(const shape_family *f, const isect_shape *s);

/* 1/0 for a finite world-space point of a solid, or ISECT_E_NONFINITE if the
 * transform takes it out of the finite doubles. */
int shape_point_inside(const shape_family *f, const isect_shape *s, const double p[3]);

/* Transforms without argument checks, for the dispatcher (xform.c). */
void xform_ray_unchecked(const isect_xform *x, const isect_ray *in, isect_ray *out);
void xform_point_to_object(const isect_xform *x, const double p[3], double out[3]);
void xform_hits_unchecked(const isect_xform *x, isect_hit *hits, int n);

/* n object-space records of shape s to world space (nothing without a
 * transform). */
static inline void shape_hits_to_world(const isect_shape *s, isect_hit *hits, int64_t n)
{
    if (s->xform != NULL)
        xform_hits_unchecked(s->xform, hits, (int)n);
}

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
