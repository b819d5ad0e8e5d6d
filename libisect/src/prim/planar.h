/*
 * planar.h — ray/face tests in a precomputed sheared frame, shared by the
 * triangle and polygon primitives and (later) the mesh BVH, so that the
 * exactly-once logic at shared edges and vertices is written once.
 *
 * Both tests report the hit of the ray's whole line (any t; the caller
 * filters [tmin, tmax] and culls), with a unit normal by the right-hand rule
 * over the vertex order, kind ENTER when dir.normal < 0 else EXIT, prim -1.
 * A face parallel to the ray by the epsilon policy (|n.d| <= eps |n| |d|)
 * or of zero area is never hit. Whether the line crosses the face is decided
 * exactly at the frame's 2D origin, perturbed by (-e^2, -e) (predicates.h),
 * so a triangle and the same triangle given as a polygon agree on every ray.
 */
#ifndef ISECT_PLANAR_H
#define ISECT_PLANAR_H

#include "prim/prim.h"
#include "core/ray_frame.h"

/* Triangle a, b, c: 1 and *out (uv = barycentric weights of b and c, t
 * interpolated from the sheared z of the vertices) or 0. f is the frame of
 * ray. */
int triangle_hit_framed(const ray_frame *f, const isect_ray *ray, const isect_params *prm,
                        const double a[3], const double b[3], const double c[3],
                        isect_hit *out);

/* The plane triangle_hit_framed computes for a, b, c, for callers that
 * keep it per face (a mesh): the unit normal of (b - a) x (c - a) and 1,
 * with *nonzero 1 when the exact cross product is certainly nonzero (else
 * 0: the test then decides collinearity exactly); or 0 for a rounded cross
 * product of zero, a triangle triangle_hit_framed never hits. */
int triangle_plane(const double a[3], const double b[3], const double c[3], double normal[3],
                   int *nonzero);

/* The plane of the polygon whose i-th vertex is v + 3*idx[i] (idx NULL:
 * v + 3*i; the caller has checked every idx[i]), n >= 3: unit Newell normal with vertices taken relative to the
 * centroid, and the centroid. 1, or 0 (normal and centroid zero) for a
 * polygon of zero area: all vertices exactly collinear, or a zero normal. */
int polygon_plane(const double *v, const int32_t *idx, int n, double normal[3],
                  double centroid[3]);

/* Polygon with a plane from polygon_plane (for callers that keep it per
 * face), f the frame of ray: 1 and *out or 0. rule ISECT_EVEN_ODD (odd winding number) or
 * ISECT_NONZERO. t from the plane through the centroid; uv = 0. */
int polygon_hit_plane_framed(const ray_frame *f, const isect_ray *ray,
                             const isect_params *prm, const double *v, const int32_t *idx,
                             int n, int rule, const double normal[3],
                             const double centroid[3], isect_hit *out);

/* The same, computing the plane first; 0 for a zero-area polygon. */
int polygon_hit_framed(const ray_frame *f, const isect_ray *ray, const isect_params *prm,
                       const double *v, const int32_t *idx, int n, int rule,
                       isect_hit *out);

#endif /* ISECT_PLANAR_H */
