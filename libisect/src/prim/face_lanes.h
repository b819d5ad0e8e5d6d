/* SPDX-License-Identifier: Apache-2.0 */
/*
 * face_lanes.h — the signs of the sheared-frame test of triangles and
 * polygons (isect.h, "Tie-breaking"; core/frame_signs.h for the exact
 * semantics), in plain double with a forward error bound per sign, LANE_W
 * rays at once. A sign is certified when its computed value lies beyond
 * its bound: then it is the exact sign for the given doubles, nonzero, and
 * the symbolic perturbation is not consulted (it only breaks exact zeros).
 * A sign within its bound is left to core/frame_signs.c, one ray at a time.
 * Every sign depends only on its edge (or vertex) and the ray, so two faces
 * sharing an edge get the same verdict for it whichever path each takes.
 *
 * Quantities, with A = fl(v - o) per coordinate and m_d = max_k |d_k|:
 *   X = A x d                     (three products' differences),
 *   y = X[kx]                     (|d[kz]| times the projected y),
 *   w = P . (Q x d)               (= d . (P x Q), the edge p -> q's
 *                                  orientation times |d[kz]|).
 * Bounds (u = 2^-53, a rounding per operation, Higham's gamma_k <= k u
 * (1 + O(u))): with exact A_bar = v - o, |A_k - A_bar_k| <= u |A_bar_k|;
 *   |y - y_exact| <= gamma_3 (|A_j d_k| + |A_k d_j|) <= 3u m_d |A|_1,
 *   |w - w_exact| <= (gamma_3 + gamma_4 + gamma_3 gamma_4) sum_i |P_i|
 *                    (|Q_j d_k| + |Q_k d_j|) <= 7u (1 + 8u) m_d |P|_1 |Q|_1
 * (Shewchuk's orient3d bound, 7u times the permanent, which is at most
 * m_d |P|_1 |Q|_1). The bounds are evaluated as 4u m_d n_A and 8u m_d n_P
 * n_Q (n = |.|_1 computed): the slack covers the rounding of A against
 * A_bar and of the bound's own three or four operations. Underflow adds at
 * most 2^-1075 per product, times |P|_1 < 2^203 where it feeds w, and the
 * bound's own products may lose as much: ETA = 2^-860 absolute covers both.
 *
 * Range (checked by the callers): every coordinate of the face and of the
 * origin within 2^200, 2^-200 <= m_d <= 2^200, so nothing overflows (n_P
 * < 2^203, w < 2^610).
 */
#ifndef ISECT_FACE_LANES_H
#define ISECT_FACE_LANES_H

#include "prim/prim_lanes.h"

#include <stddef.h>

#define FACE_LANES_Y_C      0x1p-51 /* 4u */
#define FACE_LANES_ORIENT_C 0x1p-50 /* 8u */
#define FACE_LANES_ETA      0x1p-860

/* A vertex seen from the ray: A = v - o (rounded), |A|_1. */
typedef struct face_rel {
    vd a[3];
    vd n1;
} face_rel;

static ALWAYS_INLINE void face_rel_make(const vd v[3], const lane_ray *r, face_rel *fv)
{
    for (int k = 0; k < 3; k++)
        fv->a[k] = vd_sub(v[k], r->org[k]);
    fv->n1 = vd_add(vd_add(vd_abs(fv->a[0]), vd_abs(fv->a[1])), vd_abs(fv->a[2]));
}

/* x = a x d. */
static ALWAYS_INLINE void face_cross_d(const vd a[3], const vd d[3], vd x[3])
{
    x[0] = vd_sub(vd_mul(a[1], d[2]), vd_mul(a[2], d[1]));
    x[1] = vd_sub(vd_mul(a[2], d[0]), vd_mul(a[0], d[2]));
    x[2] = vd_sub(vd_mul(a[0], d[1]), vd_mul(a[1], d[0]));
}

/* p . x, in this order (the bound above assumes it). */
static ALWAYS_INLINE vd face_dot(const vd p[3], const vd x[3])
{
    return vd_add(vd_add(vd_mul(p[0], x[0]), vd_mul(p[1], x[1])), vd_mul(p[2], x[2]));
}

/* The bound of an orientation p . (q x d), from |p|_1, |q|_1 and m_d. */
static ALWAYS_INLINE vd face_orient_bound(vd m_d, vd n_p, vd n_q)
{
    return vd_add(vd_mul(vd_mul(vd_mul(vd_set1(FACE_LANES_ORIENT_C), m_d), n_p), n_q),
                  vd_set1(FACE_LANES_ETA));
}

/* The bound of y, from |a|_1 and m_d. */
static ALWAYS_INLINE vd face_y_bound(vd m_d, vd n_a)
{
    return vd_add(vd_mul(vd_mul(vd_set1(FACE_LANES_Y_C), m_d), n_a), vd_set1(FACE_LANES_ETA));
}

/*
 * A triangle's three orientations, the unnormalised barycentric weights
 * w[0] = d . (B x C), w[1] = d . (C x A), w[2] = d . (A x B) of a, b, c,
 * from two cross products: with X_A = A x d and X_B = B x d,
 * w[2] = A . X_B, w[0] = -(C . X_B), w[1] = C . X_A (each an orientation
 * in the form the bound above covers). The frame origin lies in the
 * triangle iff the three have one sign (isect.h: +1 back side, -1 front).
 *   in:  all three certified, one sign;
 *   out: two certified with opposite signs (the third cannot matter);
 *   neither: the exact signs decide (frame_orient_exact per uncertain edge).
 * sure[k]: w[k] certified (for the scalar path's per-edge fallback).
 */
typedef struct tri_signs {
    vd w[3];
    vm sure[3];
    vm in, out;
} tri_signs;

static ALWAYS_INLINE void tri_signs_make(const vd a[3], const vd b[3], const vd c[3],
                                         const lane_ray *r, tri_signs *ts)
{
    face_rel A, B, C;
    face_rel_make(a, r, &A);
    face_rel_make(b, r, &B);
    face_rel_make(c, r, &C);
    vd xa[3], xb[3];
    face_cross_d(A.a, r->dir, xa);
    face_cross_d(B.a, r->dir, xb);
    ts->w[0] = vd_neg(face_dot(C.a, xb));
    ts->w[1] = face_dot(C.a, xa);
    ts->w[2] = face_dot(A.a, xb);
    vd m_d = lane_max_abs3(r->dir[0], r->dir[1], r->dir[2]);
    vd e[3] = { face_orient_bound(m_d, C.n1, B.n1), face_orient_bound(m_d, C.n1, A.n1),
                face_orient_bound(m_d, A.n1, B.n1) };
    vm pos = vm_true(), neg = vm_true(), any_pos = vm_false(), any_neg = vm_false();
    for (int k = 0; k < 3; k++) {
        vm p = vd_gt(ts->w[k], e[k]), n = vd_lt(ts->w[k], vd_neg(e[k]));
        ts->sure[k] = vm_or(p, n);
        pos = vm_and(pos, p);
        neg = vm_and(neg, n);
        any_pos = vm_or(any_pos, p);
        any_neg = vm_or(any_neg, n);
    }
    ts->in = vm_or(pos, neg);
    ts->out = vm_and(any_pos, any_neg);
}

/* The barycentric (u, v) of b and c from the three weights (of one sign,
 * or zero where an exact tie gave the sign): one division, shared. */
static ALWAYS_INLINE void tri_weights_uv(const vd w[3], vd *u, vd *v)
{
    vd inv = vd_div(vd_set1(1.0), vd_add(vd_add(w[0], w[1]), w[2]));
    *u = vd_mul(w[1], inv);
    *v = vd_mul(w[2], inv);
}

/*
 * The ray's frame axis kx as three lane masks (exactly one set per lane):
 * kz = the axis of the largest |d_k|, lowest index on ties, kx its
 * successor, or its predecessor when d[kz] < 0 (core/ray_frame.c makes
 * the same choice with the same comparisons).
 */
typedef struct face_axes {
    vm kx0, kx1;  /* kx == 0, kx == 1 (else 2) */
    vd m_d;       /* max |d_k| */
} face_axes;

static ALWAYS_INLINE void face_axes_make(const lane_ray *r, face_axes *fa)
{
    vd a0 = vd_abs(r->dir[0]), a1 = vd_abs(r->dir[1]), a2 = vd_abs(r->dir[2]);
    vm z1 = vd_gt(a1, a0);
    vd a01 = vd_sel(z1, a1, a0);
    vm z2 = vd_gt(a2, a01);
    vm kz1 = vm_andnot(z1, z2), kz0 = vm_not(vm_or(z1, z2));
    vd dz = vd_sel(z2, r->dir[2], vd_sel(z1, r->dir[1], r->dir[0]));
    vm neg = vd_lt(dz, vd_zero());
    /* kz 0: kx = 1 (2 if neg); kz 1: kx = 2 (0 if neg); kz 2: kx = 0 (1 if neg) */
    fa->kx0 = vm_or(vm_and(kz1, neg), vm_andnot(z2, neg));
    fa->kx1 = vm_or(vm_andnot(kz0, neg), vm_and(z2, neg));
    fa->m_d = vd_max(a0, vd_max(a1, a2));
}

/*
 * The winding number of the perturbed frame origin around the polygon
 * whose i-th vertex is v + 3 idx[i] (idx NULL: v + 3 i), n >= 3, by the
 * half-open rule of predicates.h's winding_edge on the exact projections:
 * a vertex is above the test line when y >= 0; an edge from below to above
 * adds +1 when the origin is on its left (orientation > 0), one from above
 * to below -1 when it is on its right. `certain` clears the lanes where any
 * sign the count used (every vertex's y, the orientation of every edge that
 * crosses the line) was within its bound; their counts mean nothing.
 * odd: the count's parity (1.0 or 0.0), for the even-odd rule.
 */
typedef struct face_winding {
    vd winding, odd;
    vm certain;
} face_winding;

/* One vertex for the winding loop: A, |A|_1, X = A x d, and whether it is
 * above the line (with its certainty). */
typedef struct face_wrel {
    face_rel p;
    vd x[3];
    vm above, sure;
} face_wrel;

static ALWAYS_INLINE void face_wrel_make(const double *vert, const lane_ray *r,
                                            const face_axes *fa, face_wrel *wv)
{
    const vd v[3] = { vd_set1(vert[0]), vd_set1(vert[1]), vd_set1(vert[2]) };
    face_rel_make(v, r, &wv->p);
    face_cross_d(wv->p.a, r->dir, wv->x);
    vd y = vd_sel(fa->kx0, wv->x[0], vd_sel(fa->kx1, wv->x[1], wv->x[2]));
    vd e = face_y_bound(fa->m_d, wv->p.n1);
    wv->above = vd_ge(y, vd_zero());
    wv->sure = vd_gt(vd_abs(y), e);
}

static ALWAYS_INLINE const double *face_corner(const double *v, const int32_t *idx, int i)
{
    return v + 3 * (ptrdiff_t)(idx != NULL ? idx[i] : i);
}

static ALWAYS_INLINE void face_winding_lanes(const double *v, const int32_t *idx, int n,
                                             const lane_ray *r, const face_axes *fa,
                                             face_winding *fw)
{
    face_wrel last, prev, cur;
    face_wrel_make(face_corner(v, idx, n - 1), r, fa, &last);
    prev = last;
    vd winding = vd_zero(), odd = vd_zero();
    vm certain = last.sure;
    const vd one = vd_set1(1.0);
    for (int i = 0; i < n; i++) {
        if (i < n - 1) {
            face_wrel_make(face_corner(v, idx, i), r, fa, &cur);
            certain = vm_and(certain, cur.sure);
        } else {
            cur = last;
        }
        vd w = face_dot(prev.p.a, cur.x); /* d . (P x Q): the edge prev -> cur */
        vd e = face_orient_bound(fa->m_d, prev.p.n1, cur.p.n1);
        vm up = vm_andnot(cur.above, prev.above), down = vm_andnot(prev.above, cur.above);
        vm left = vd_gt(w, e), right = vd_lt(w, vd_neg(e));
        vm plus = vm_and(up, left), minus = vm_and(down, right);
        certain = vm_andnot(certain, vm_andnot(vm_or(up, down), vm_or(left, right)));
        winding = vd_add(winding, vd_sub(vd_sel(plus, one, vd_zero()), vd_sel(minus, one, vd_zero())));
        odd = vd_sel(vm_or(plus, minus), vd_sub(one, odd), odd);
        prev = cur;
    }
    fw->winding = winding;
    fw->odd = odd;
    fw->certain = certain;
}

#endif /* ISECT_FACE_LANES_H */
