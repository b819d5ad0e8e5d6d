/* SPDX-License-Identifier: Apache-2.0 */
/*
 * dispatch.h — the dispatcher over the isect_shape descriptor (shape.c) and
 * what the batch loops (batch.c) and the public entry points share with it.
 * A shape_family is a type's row of the family table: its prim/ kernels,
 * or the mesh's queries.
 */
#ifndef ISECT_DISPATCH_H
#define ISECT_DISPATCH_H

#include "prim/prim.h"

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

/* 1 when the shape has an inside (its hits are ENTER/EXIT of a solid), 0
 * for thin surfaces (open meshes included). */
int shape_is_solid(const shape_family *f, const isect_shape *s);

/* 1 when isect_contains applies: a solid, or a mesh whose containment rule
 * (flags) it meets. */
int shape_can_contain(const shape_family *f, const isect_shape *s);

/* 1/0 for a finite world-space point of a solid, or ISECT_E_NONFINITE if the
 * transform takes it out of the finite doubles. */
int shape_point_inside(const shape_family *f, const isect_shape *s, const double p[3]);

/* The exact side (prim/prim.h) of a finite world-space point, in the
 * shape's object space: -1, 0, +1, or ISECT_E_NONFINITE if the transform
 * takes it out of the finite doubles. */
int shape_point_side(const shape_family *f, const isect_shape *s, const double p[3],
                     int32_t prim);

/* The exact side (prim/prim.h: X_tangent_side) of a finite world-space
 * direction against the plane of a flat prim, in the shape's object space
 * (the direction mapped as every query maps it): -1, 0, +1, SIDE_CURVED for
 * a prim that is not flat, or ISECT_E_NONFINITE. */
int shape_direction_side(const shape_family *f, const isect_shape *s, const double d[3],
                         int32_t prim);

/* 1 when prim names a part of s that a hit can have (a mesh face). */
int shape_prim_valid(const isect_shape *s, int32_t prim);

/* n object-space records of shape s to world space (nothing without a
 * transform). */
static inline void shape_hits_to_world(const isect_shape *s, isect_hit *hits, int64_t n)
{
    xform_hits_to_world(s->xform, hits, n);
}

/* The object-space ray of a valid world-space ray (xform_object_ray under
 * the shape's transform). */
static inline int shape_object_ray(const isect_shape *s, const isect_ray *ray, isect_ray *tmp,
                                   const isect_ray **r)
{
    return xform_object_ray(s->xform, ray, tmp, r);
}

#endif /* ISECT_DISPATCH_H */
