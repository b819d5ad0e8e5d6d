/* SPDX-License-Identifier: Apache-2.0 */
/*
 * triangle_test.h — the watertight ray/triangle test (Woop, Benthin & Wald
 * 2013) decided exactly for the given doubles, one ray at a time, as
 * static inline functions: the signs certified in plain double
 * (face_lanes.h at LANE_W = 1), the uncertain ones exactly
 * (core/frame_signs.c).
 *
 * triangle.c builds the lone triangle's exact path on it; the mesh
 * traversal (mesh_query.c) includes it too, so that its leaf loop can be
 * compiled a second time for CPUs with FMA (x86-64 without -mfma otherwise
 * calls libm for the fma of the exact parts). fma is correctly rounded
 * either way, so both copies give the same bits.
 */
#ifndef ISECT_TRIANGLE_TEST_H
#define ISECT_TRIANGLE_TEST_H

#include "prim/planar.h"
#include "prim/face_lanes.h"
#include "core/scaling.h"
#include "core/frame_signs.h"

/*
 * Whether the ray of frame f crosses triangle a, b, c, and where in it: 1
 * with the barycentric weights (u, v) of b and c, or 0. The inside test is
 * the sheared-frame test on the exact projections: the three edge
 * orientations (with the symbolic perturbation for exact zeros) have one
 * sign. Each edge's sign is the fast one where certified, else
 * frame_orient_exact: a function of that edge and the ray alone, so a
 * neighbour sharing the edge (tested as q -> p, the opposite sign) never
 * claims the same ray. No triangle with collinear vertices and no ray
 * parallel to the plane ever passes: the three perturbed orientations sum
 * to twice the projected area, which is then zero, so they cannot share a
 * sign.
 *
 * The weights are the fast orientations when all three were certified
 * (bit for bit what the lane kernel computes), else the exact ones rounded
 * (ties: 0), so the weights are never of mixed signs and never all zero
 * (their exact sum is d.N != 0).
 */
static ALWAYS_INLINE int triangle_inside(const ray_frame *f, const lane_ray *lr,
                                         int fast_range, const double a[3], const double b[3],
                                         const double c[3], double *u, double *v)
{
    tri_signs ts;
    const vd av[3] = { vd_set1(a[0]), vd_set1(a[1]), vd_set1(a[2]) };
    const vd bv[3] = { vd_set1(b[0]), vd_set1(b[1]), vd_set1(b[2]) };
    const vd cv[3] = { vd_set1(c[0]), vd_set1(c[1]), vd_set1(c[2]) };
    tri_signs_make(av, bv, cv, lr, &ts);
    if (fast_range && ts.out)
        return 0;
    vd w[3] = { ts.w[0], ts.w[1], ts.w[2] };
    if (!(fast_range && ts.in)) {
        /* edge k is the one opposite vertex k: (b, c), (c, a), (a, b) */
        const double *p[3] = { b, c, a }, *q[3] = { c, a, b };
        int s[3];
        for (int k = 0; k < 3; k++) {
            if (fast_range && ts.sure[k])
                s[k] = ts.w[k] > 0.0 ? 1 : -1;
            else
                s[k] = frame_orient_exact(f, p[k], q[k]);
            if (s[k] == 0 || s[k] != s[0])
                return 0;
        }
        frame_triangle_weights_exact(f, a, b, c, w);
    }
    tri_weights_uv(w, u, v);
    return 1;
}

/* 1 when the fast signs' range holds for this ray and triangle (see
 * face_lanes.h): coordinates within 2^200, 2^-200 <= max|d_k| <= 2^200. */
static ALWAYS_INLINE int triangle_fast_range(const lane_ray *lr, const double a[3],
                                             const double b[3], const double c[3])
{
    double m = fmax_nan(max_abs3(a), fmax_nan(max_abs3(b), max_abs3(c)));
    return m <= 0x1p200 && lane_ray_in_range(lr, 0x1p200);
}

/* The test: the exact inside test (triangle_inside) decides whether the
 * ray crosses the triangle — no epsilon (revision 2); then triangle_record
 * finds where (the crossing parameter to within 4 ulp, decided exactly
 * against [tmin, tmax]) and writes the record. lr: the ray as one lane;
 * fast_range: triangle_fast_range of it (a mesh knows it for all its
 * faces at once); normal: the face's unit normal if the caller keeps it
 * (a mesh, a batch), or NULL. */
static ALWAYS_INLINE int triangle_hit(const ray_frame *f, const isect_ray *ray,
                                      const lane_ray *lr, int fast_range, const double a[3],
                                      const double b[3], const double c[3],
                                      const double *normal, isect_hit *out)
{
    double u, v;
    if (!triangle_inside(f, lr, fast_range, a, b, c, &u, &v))
        return 0;
    return triangle_record(ray, a, b, c, normal, u, v, out);
}

#endif /* ISECT_TRIANGLE_TEST_H */
