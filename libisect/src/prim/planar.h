/* SPDX-License-Identifier: Apache-2.0 */
/*
 * planar.h — what triangles, polygons and mesh faces share: their planes,
 * the crossing record, the exact crossing parameters, and the polygon test
 * in a precomputed sheared frame (the triangle's is triangle_test.h), so
 * that the exactly-once logic at shared edges and vertices is written once.
 *
 * Whether a ray crosses a face is decided exactly for the given doubles at
 * the 2D origin of the ray's sheared frame, on the exact projection of the
 * vertices, perturbed by (-e^2, -e) (isect.h, "Tie-breaking";
 * core/frame_signs.h), with no eps (revision 2), so a triangle and the same
 * triangle given as a polygon agree on every ray. Only crossings in [tmin,
 * tmax] (decided exactly) are reported, with a unit normal by the
 * right-hand rule over the vertex order, kind ENTER when dir.N < 0 exactly
 * else EXIT, prim -1; the caller culls. A face of zero area is never hit.
 */
#ifndef ISECT_PLANAR_H
#define ISECT_PLANAR_H

#include "prim/prim.h"
#include "core/ray_frame.h"
#include "core/expansion.h"
#include "core/scaling.h"

/* Scales the n expansions x[0..n) up by one power of two 2^k so that their
 * largest part lies in [0.5, 1), and returns k; nothing (0) when that
 * would scale down or by more than 2^limit. Exact: every part only grows
 * and stays below 1. A face's vectors — its edges, its normal, the vertex
 * minus the ray origin — are differences of coordinates scaled by 2^-e for
 * the largest coordinate; for a face far smaller than its coordinates
 * (extent 1 at 2^540) or an origin very near it they are tiny, and their
 * products of degree 2 and 3 would fall below the underflow threshold,
 * where expansions are no longer exact. Brought near 1 first, they keep
 * every product exact while each vector's own components lie within about
 * 2^300 of its largest. The normal's scale cancels in its direction and
 * in num/den; a scaled A = a - o is matched by scaling den alike. */
static inline int xp_normalize_up(xp *x, int n, int limit)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < x[i].n; j++)
            m = fmax(m, fabs(x[i].p[j]));
    int k = m > 0.0 ? -pow2_exponent(m) : 0;
    if (k <= 0 || k > limit)
        return 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < x[i].n; j++)
            x[i].p[j] = pow2_scale(x[i].p[j], k);
    return k;
}

/* The largest shift xp_normalize_up takes for A = a - o: den (at most a
 * few units) scaled by as much stays far below the overflow threshold. */
#define XP_SHIFT_LIMIT 1000

/* The unit normal of (b - a) x (c - a), accurate to about an ulp (the
 * cross product as a double-double from exact edges), for callers that
 * keep it per face (a mesh): 1, with *nonzero 1 when the exact cross product
 * is certainly nonzero (else 0: the test then decides collinearity
 * exactly); or 0 when the cross product is zero to double-double precision
 * (then collinear3 decides whether the triangle has any area). */
int triangle_plane(const double a[3], const double b[3], const double c[3], double normal[3],
                   int *nonzero);

/* The record of a ray that the exact side test sends through triangle
 * a, b, c: its crossing with the plane, decided exactly against [tmin,
 * tmax] (triangle_lanes.h's bound, else triangle.c's exact path); 1 with
 * *out (t clamped into the interval, the point o + t d placed from t as a
 * double-double, the normal — the given unit one, or computed — ENTER when
 * dir.N < 0 exactly, uv = (u, v), prim -1), or 0: no crossing in range
 * (or, exactly parallel, none at all). */
int triangle_record(const isect_ray *ray, const double a[3], const double b[3], const double c[3],
                    const double *normal, double u, double v, isect_hit *out);

/* The crossing of the line of ray with the plane of triangle a, b, c
 * (triangle_crossing_xp) or of a polygon (its Newell plane through the
 * vertex centroid; polygon_crossing_xp) as t = (num/den) 2^(e - e_dir),
 * num and den exact expansions: positions (the origin and every vertex)
 * scaled by 2^-e, the direction by 2^-e_dir. The caller picks e and e_dir
 * (pow2_exponent of the largest magnitudes: exact scalings, no overflow),
 * so that crossings with different faces can be compared exactly with one
 * scaling (core/ratio.c: ratio_cmp). */
void triangle_crossing_xp(const isect_ray *ray, const double a[3], const double b[3],
                          const double c[3], int e, int e_dir, xp *num, xp *den);
void polygon_crossing_xp(const isect_ray *ray, const double *v, const int32_t *idx, int n,
                         int e, int e_dir, xp *num, xp *den);

/* A polygon's plane (the golden reference's: Newell's normal N = sum_i v_i
 * x v_{i+1} through the vertex centroid m), as double-doubles: N scaled by
 * a power of two to a largest component in [0.5, 1) (its direction is all
 * that matters), within n_err per component; m within m_err per
 * coordinate; and N/|N| to about an ulp. */
typedef struct poly_plane {
    double n_hi[3], n_lo[3], n_err[3];
    double m_hi[3], m_lo[3], m_err;
    double unit[3];
} poly_plane;

/* The plane of the polygon whose i-th vertex is v + 3*idx[i] (idx NULL:
 * v + 3*i; the caller has checked every idx[i]), n >= 3: 1, or 0 when the
 * polygon has no area (N == 0, decided exactly: collinear vertices, or a
 * self-intersecting polygon whose signed areas cancel). Fast where the
 * double-double fan is certain, exact otherwise. */
int polygon_plane(const double *v, const int32_t *idx, int n, poly_plane *pp);

/* The same, always from the exact expansions (errors of a few u^2): for a
 * mesh, once per face at creation. */
int polygon_plane_exact_dd(const double *v, const int32_t *idx, int n, poly_plane *pp);

/* Polygon with its plane, f the frame of ray: 1 and *out or 0. rule
 * ISECT_EVEN_ODD (odd winding number) or ISECT_NONZERO, decided exactly in
 * the sheared frame with no epsilon (revision 2); then the crossing with
 * the plane, decided exactly against [tmin, tmax] (the triangle's
 * double-double bound, else the exact expansions), the point placed from t
 * as a double-double, the unit normal, ENTER when dir.N < 0 exactly, uv 0,
 * prim -1. */
int polygon_hit_plane_framed(const ray_frame *f, const isect_ray *ray, const double *v,
                             const int32_t *idx, int n, int rule, const poly_plane *pp,
                             isect_hit *out);

/* The same, computing the plane first; 0 for a zero-area polygon. */
int polygon_hit_framed(const ray_frame *f, const isect_ray *ray, const double *v,
                       const int32_t *idx, int n, int rule, isect_hit *out);

#endif /* ISECT_PLANAR_H */
