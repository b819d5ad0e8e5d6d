/* SPDX-License-Identifier: Apache-2.0 */
/*
 * core.h — what every layer of the library shares: resolved options, the
 * checks every entry point makes on rays and numbers, and the affine
 * transforms of rays, points and hits.
 *
 * Layers, each using only those below it:
 *   core/  numbers and geometry with no notion of a shape: vector math,
 *          exact predicates, error-free arithmetic, root finding, the
 *          sheared ray frame, transforms, argument checks;
 *   prim/  one file per family of primitives, each a set of kernels over
 *          the isect_shape descriptor (prim.h);
 *   mesh/  polygon meshes and their BVH, on the planar face tests of prim/;
 *   api/   the dispatcher over isect_shape, the batch loops and the public
 *          per-primitive entry points.
 */
#ifndef ISECT_CORE_H
#define ISECT_CORE_H

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

/* Transforms without argument checks (xform.c). */
void xform_ray_unchecked(const isect_xform *x, const isect_ray *in, isect_ray *out);
void xform_point_to_object(const isect_xform *x, const double p[3], double out[3]);
void xform_vector_to_object(const isect_xform *x, const double v[3], double out[3]);
void xform_point_to_world(const isect_xform *x, const double p[3], double out[3]);
/* 1 when x's linear part is a similarity (a rotation or mirror times one
 * scale factor, to a relative 2^-40): angles, and so solid angles, are the
 * same in object and world space. */
int xform_is_similarity(const isect_xform *x);
void xform_hits_unchecked(const isect_xform *x, isect_hit *hits, int n);
/* The sign of the determinant of x's linear part, exactly: -1 for a
 * mirroring transform (it turns a surface's orientation inside out). */
int xform_orientation(const isect_xform *x);

/* The object-space ray of a valid world-space ray under x (NULL: none), as
 * every query sees it: ISECT_OK with *r = ray (no transform) or tmp (the
 * transformed ray), or the ray_check status of the transformed ray (a huge
 * inverse can take a fine ray out of the finite doubles). */
static inline int xform_object_ray(const isect_xform *x, const isect_ray *ray, isect_ray *tmp,
                                   const isect_ray **r)
{
    *r = ray;
    if (x == NULL)
        return ISECT_OK;
    xform_ray_unchecked(x, ray, tmp);
    *r = tmp;
    return ray_check(tmp);
}

/* n object-space records under x (NULL: none) to world space. */
static inline void xform_hits_to_world(const isect_xform *x, isect_hit *hits, int64_t n)
{
    if (x != NULL)
        xform_hits_unchecked(x, hits, (int)n);
}

#endif /* ISECT_CORE_H */
