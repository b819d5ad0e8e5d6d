/* SPDX-License-Identifier: Apache-2.0 */
/*
 * triangle_lanes.h — the crossing parameter of a triangle's plane, in the
 * lane vocabulary: plain double-double arithmetic with a forward error
 * bound, deferring to triangle.c's exact path where that bound cannot
 * certify the result (prim_lanes.h states the contract). Whether the ray
 * crosses the triangle at all is the exact sheared-frame test of
 * triangle_test.h; this is only where along the ray.
 *
 * t = N.(a - o) / N.dir with N = (b - a) x (c - a). The edges and a - o
 * are exact as two doubles each (TwoSum); N is a double-double per
 * component (exact products of the edges' heads, the low-part terms
 * rounded, the products of two low parts left out):
 *     E_N_k <= 32u^2 SN_k,  SN_k = |e1_i e2_j| + |e1_j e2_i|;
 * then num = N.(a - o) and den = N.dir as double-doubles (lane_dot3_dd plus
 * the low parts' first-order terms):
 *     E_num <= 32u^2 sum |N_k A_k| + sum E_N_k |A_k| (+ sum |N_k| times the
 *              anchor's error, for a polygon's centroid),  E_den likewise,
 * and t = num/den (dd_mul_inv_dd) errs by at most |t| (u + 40u^2 +
 * E_den/|den|) + E_num/|den|. Why N must be this good: an error dN moves t
 * by ((a - P).dN)/(N.dir), P the hit point, which for a ray starting near
 * the triangle is as large as |dN|/|N| relative — far beyond 4 ulp for the
 * plain cross product of a sliver. A ray's crossing is reported from here
 * when the bound is at most 3.5u|t| and its interval decision holds for
 * every value within it; a face exactly parallel to the ray (den == 0) has
 * no crossing point: the exact path says so.
 *
 * Range: every coordinate of a, b, c, o within 2^200, 2^-200 <= max|dir_k|
 * <= 2^200 (the caller checks the triangle; lane_ray_in_range the ray).
 *
 * tri_lanes_first is the triangle's whole fast kernel (the batch's, and the
 * scalar call's at LANE_W = 1): the inside test from face_lanes.h's
 * certified signs, this crossing, the record. Everything that depends on
 * the triangle alone is prepared once (triangle_prepare, triangle.c).
 */
#ifndef ISECT_TRIANGLE_LANES_H
#define ISECT_TRIANGLE_LANES_H

#include "prim/prim_lanes.h"
#include "prim/face_lanes.h"

#define TRI_LANES_U   0x1p-53
#define TRI_LANES_U2  0x1p-106
#define TRI_LANES_ETA 0x1p-960

/* A triangle's plane as double-doubles: N = (b - a) x (c - a) and the
 * bound terms SN (32u^2 SN_k bounds each component's error). */
typedef struct tri_plane {
    vdd n[3];
    vd  err[3]; /* E_N_k */
} tri_plane;

/* One component e1_i e2_j - e1_j e2_i of edges given exactly as hi + lo. */
static ALWAYS_INLINE vdd tri_cross_comp(vdd e1_i, vdd e1_j, vdd e2_i, vdd e2_j, vd *err)
{
    vdd x = two_prod(e1_i.hi, e2_j.hi), y = two_prod(e1_j.hi, e2_i.hi);
    vdd s = two_sum(x.hi, vd_neg(y.hi));
    vd cross = vd_sub(vd_add(vd_mul(e1_i.hi, e2_j.lo), vd_mul(e1_i.lo, e2_j.hi)),
                      vd_add(vd_mul(e1_j.hi, e2_i.lo), vd_mul(e1_j.lo, e2_i.hi)));
    vd lo = vd_add(vd_add(s.lo, vd_sub(x.lo, y.lo)), cross);
    *err = vd_add(vd_mul(vd_set1(32.0 * TRI_LANES_U2), vd_add(vd_abs(x.hi), vd_abs(y.hi))),
                  vd_set1(TRI_LANES_ETA));
    return two_sum(s.hi, lo);
}

static ALWAYS_INLINE void tri_plane_make(const vd a[3], const vd b[3], const vd c[3], tri_plane *tp)
{
    vdd e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = two_sum(b[k], vd_neg(a[k]));
        e2[k] = two_sum(c[k], vd_neg(a[k]));
    }
    tp->n[0] = tri_cross_comp(e1[1], e1[2], e2[1], e2[2], &tp->err[0]);
    tp->n[1] = tri_cross_comp(e1[2], e1[0], e2[2], e2[0], &tp->err[1]);
    tp->n[2] = tri_cross_comp(e1[0], e1[1], e2[0], e2[1], &tp->err[2]);
}

/* The crossing with the plane of tp through the point a_hi + a_lo (a
 * triangle's vertex: a_lo = 0; a polygon's centroid as a double-double,
 * known to within a_err per coordinate): t as a double-double and the
 * verdicts: in (report: in [tmin, tmax] and within 3.5u|t|), out
 * (certainly outside [tmin, tmax]), and enter (den < 0, certain where in
 * or out is). A ray parallel or nearly so is neither: undecided, like any
 * lane that is neither in nor out. */
typedef struct tri_crossing {
    vdd t;
    vm  in, out, enter;
} tri_crossing;

static ALWAYS_INLINE void tri_crossing_solve(const tri_plane *tp, const vd a_hi[3], const vd a_lo[3],
                                             vd a_err, const lane_ray *ray, tri_crossing *tc)
{
    const vd u2 = vd_set1(TRI_LANES_U2), eta = vd_set1(TRI_LANES_ETA);
    const vd *d = ray->dir;
    vdd A[3];
    for (int k = 0; k < 3; k++) {
        A[k] = two_sum(a_hi[k], vd_neg(ray->org[k]));
        A[k].lo = vd_add(A[k].lo, a_lo[k]);
    }
    const vdd *n = tp->n;

    vdd num = lane_dot3_dd(n[0].hi, n[1].hi, n[2].hi, A[0].hi, A[1].hi, A[2].hi);
    vd num_first = vd_add(vd_add(vd_add(vd_mul(n[0].hi, A[0].lo), vd_mul(n[0].lo, A[0].hi)),
                                 vd_add(vd_mul(n[1].hi, A[1].lo), vd_mul(n[1].lo, A[1].hi))),
                          vd_add(vd_mul(n[2].hi, A[2].lo), vd_mul(n[2].lo, A[2].hi)));
    num.lo = vd_add(num.lo, num_first);
    num = dd_renorm(num);
    vd mag_num = vd_add(vd_add(vd_abs(vd_mul(n[0].hi, A[0].hi)), vd_abs(vd_mul(n[1].hi, A[1].hi))),
                        vd_abs(vd_mul(n[2].hi, A[2].hi)));
    vd prop_num = vd_add(vd_add(vd_mul(tp->err[0], vd_abs(A[0].hi)), vd_mul(tp->err[1], vd_abs(A[1].hi))),
                         vd_mul(tp->err[2], vd_abs(A[2].hi)));
    vd n_sum = vd_add(vd_add(vd_abs(n[0].hi), vd_abs(n[1].hi)), vd_abs(n[2].hi));
    vd e_num = vd_add(vd_add(vd_mul(vd_set1(32.0), vd_mul(u2, mag_num)),
                             vd_mul(vd_add(prop_num, vd_mul(n_sum, a_err)),
                                    vd_set1(1.0 + 4.0 * TRI_LANES_U))),
                      eta);

    vdd den = lane_dot3_dd(n[0].hi, n[1].hi, n[2].hi, d[0], d[1], d[2]);
    den.lo = vd_add(den.lo, vd_add(vd_add(vd_mul(n[0].lo, d[0]), vd_mul(n[1].lo, d[1])),
                                   vd_mul(n[2].lo, d[2])));
    den = dd_renorm(den);
    vd mag_den = vd_add(vd_add(vd_abs(vd_mul(n[0].hi, d[0])), vd_abs(vd_mul(n[1].hi, d[1]))),
                        vd_abs(vd_mul(n[2].hi, d[2])));
    vd prop_den = vd_add(vd_add(vd_mul(tp->err[0], vd_abs(d[0])), vd_mul(tp->err[1], vd_abs(d[1]))),
                         vd_mul(tp->err[2], vd_abs(d[2])));
    vd e_den = vd_add(vd_add(vd_mul(vd_set1(32.0), vd_mul(u2, mag_den)),
                             vd_mul(prop_den, vd_set1(1.0 + 4.0 * TRI_LANES_U))),
                      eta);

    vd inv = vd_div(vd_set1(1.0), den.hi);
    tc->t = dd_mul_inv_dd(num, den, inv);
    vd up = vd_set1(1.0 + 8.0 * TRI_LANES_U);
    vd inv_abs = vd_mul(vd_abs(inv), up);
    /* a den within its error of 0 leaves t unbounded: the exact path */
    vm den_sure = vd_gt(vd_abs(den.hi), vd_mul(vd_add(e_den, vd_mul(vd_set1(TRI_LANES_U), vd_abs(den.hi))),
                                              vd_set1(2.0)));
    vd err = vd_mul(vd_add(vd_mul(vd_abs(tc->t.hi), vd_add(vd_set1(TRI_LANES_U + 40.0 * TRI_LANES_U2),
                                                            vd_mul(e_den, inv_abs))),
                           vd_mul(e_num, inv_abs)),
                    up);
    tc->in = vm_and(den_sure, vm_and(lane_certainly_in(tc->t.hi, err, ray),
                                     vd_le(err, vd_mul(vd_set1(3.5 * TRI_LANES_U), vd_abs(tc->t.hi)))));
    tc->out = vm_and(den_sure, lane_certainly_out(tc->t.hi, err, ray));
    tc->enter = vd_lt(den.hi, vd_zero());
}

/* A triangle's constants for the fast kernel, the same bits in every
 * instruction set (computed once, by triangle_prepare in triangle.c). */
typedef struct tri_prep {
    double v[9];                           /* a, b, c */
    double n_hi[3], n_lo[3], n_err[3];     /* tri_plane_make's N and bounds */
    double normal[3];                      /* triangle_plane's unit normal */
    int    in_range;                       /* every coordinate within 2^200 */
    int    degenerate;                     /* no area: never hit */
} tri_prep;

void triangle_prepare(const double *data, tri_prep *tp);

static ALWAYS_INLINE void tri_prep_vertices(const tri_prep *tp, vd a[3], vd b[3], vd c[3])
{
    for (int k = 0; k < 3; k++) {
        a[k] = vd_set1(tp->v[k]);
        b[k] = vd_set1(tp->v[3 + k]);
        c[k] = vd_set1(tp->v[6 + k]);
    }
}

/* The lanes not certainly outside triangle a, b, c by the certified signs
 * (the caller has checked face_lanes.h's range). */
static ALWAYS_INLINE vm tri_lanes_inside_maybe(const double a[3], const double b[3],
                                               const double c[3], const lane_ray *ray)
{
    const vd av[3] = { vd_set1(a[0]), vd_set1(a[1]), vd_set1(a[2]) };
    const vd bv[3] = { vd_set1(b[0]), vd_set1(b[1]), vd_set1(b[2]) };
    const vd cv[3] = { vd_set1(c[0]), vd_set1(c[1]), vd_set1(c[2]) };
    tri_signs ts;
    tri_signs_make(av, bv, cv, ray, &ts);
    return vm_not(ts.out);
}

/* The batch's screen: the lanes not certainly outside the triangle (the
 * certified signs alone; a lane it clears is one tri_lanes_first would
 * report as no hit without deferring). Crossings are solved for the
 * rest only. */
static ALWAYS_INLINE vm tri_lanes_screen(const tri_prep *tp, const lane_ray *ray)
{
    if (tp->degenerate)
        return vm_false();
    vd a[3], b[3], c[3];
    tri_prep_vertices(tp, a, b, c);
    tri_signs ts;
    tri_signs_make(a, b, c, ray, &ts);
    vm ok = tp->in_range ? lane_ray_in_range(ray, 0x1p200) : vm_false();
    return vm_not(vm_and(ok, ts.out));
}

/*
 * The first (only) hit of LANE_W rays. A lane is found when the certified
 * signs put the frame origin inside and the crossing is certified in
 * [tmin, tmax]; neither (no hit) when the signs put it outside or the
 * crossing is certainly out of range; slow otherwise (an uncertain sign or
 * crossing, or a ray outside the range): triangle.c's exact path, which
 * starts from the same signs and the same crossing.
 */
static ALWAYS_INLINE void tri_lanes_first(const tri_prep *tp, const lane_ray *ray, lane_hit *h)
{
    vd a[3], b[3], c[3];
    tri_prep_vertices(tp, a, b, c);
    tri_signs ts;
    tri_signs_make(a, b, c, ray, &ts);
    tri_plane pl;
    for (int k = 0; k < 3; k++) {
        pl.n[k].hi = vd_set1(tp->n_hi[k]);
        pl.n[k].lo = vd_set1(tp->n_lo[k]);
        pl.err[k] = vd_set1(tp->n_err[k]);
    }
    const vd zero[3] = { vd_zero(), vd_zero(), vd_zero() };
    tri_crossing tc;
    tri_crossing_solve(&pl, a, zero, vd_zero(), ray, &tc);

    vm ok = tp->in_range ? lane_ray_in_range(ray, 0x1p200) : vm_false();
    vm decided = vm_or(ts.out, vm_and(ts.in, vm_or(tc.in, tc.out)));
    h->slow = tp->degenerate ? vm_false() : vm_not(vm_and(ok, decided));
    h->found = tp->degenerate ? vm_false() : vm_andnot(vm_and(ts.in, tc.in), h->slow);

    h->t = vd_add(lane_clamp_t(tc.t.hi, ray), vd_zero());
    lane_point_on_ray(ray, tc.t, h->point);
    for (int k = 0; k < 3; k++)
        h->normal[k] = vd_set1(tp->normal[k]);
    tri_weights_uv(ts.w, &h->uv[0], &h->uv[1]);
    h->prim = vd_set1(-1.0);
    h->kind = vd_sel(tc.enter, vd_set1((double)ISECT_ENTER), vd_set1((double)ISECT_EXIT));
}

#endif /* ISECT_TRIANGLE_LANES_H */
