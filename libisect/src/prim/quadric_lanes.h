/* SPDX-License-Identifier: Apache-2.0 */
/*
 * quadric_lanes.h — the general quadric's fast kernel, LANE_W rays at once
 * (prim_lanes.h states the contract; quadric.c holds the exact path it
 * defers to).
 *
 * Q(x) = Ax^2 + By^2 + Cz^2 + Dxy + Exz + Fyz + Gx + Hy + Iz + J = x.Mx +
 * 2 g.x + J (M symmetric: the squares' coefficients on its diagonal, the
 * products' halves off it; g = (G, H, I)/2: halving is exact). Along the
 * line, Q(o + t d) = a t^2 + 2b t + c with a = d.Md, b = (Mo + g).d = o.y +
 * g.d (y = Md), c = Q(o); quadric.c's rules: linear when |a| <= eps S |d|^2
 * (S = max(|A|..|F|)), TOUCH when |b^2 - ac| <= eps (b^2 + |ac|), else two
 * crossings, the entry where Q' < 0 (for a < 0 the upper one).
 *
 * 1. Plain solve: y, a, b, c and G = b^2 - ac in doubles, each with a
 *    forward bound from the coefficients' and coordinates' maxima (crude,
 *    a constant factor above the componentwise one: it only widens the
 *    bands where the kernel defers); certainly not linear, and G away from
 *    the tangency band, or the exact path decides. No identity removes the
 *    cancellation of b^2 - ac for a ray from afar in general: such rays
 *    (beyond ~2^20 of the quadric's size) defer.
 * 2. Refinement: x = o + t0 d as xh + xl (TwoProduct, TwoSum: xl is the
 *    exact remainder, rounded once), Q(x) from the monomials' heads
 *    c xh_i xh_j, each exact as two TwoProducts, summed by a cascade of
 *    TwoSums (Ogita, Rump & Oishi's Sum2), every low part to first order;
 *    P = (Mx + g).d = xh.y + g.d; one Newton step certified by Kantorovich's
 *    bound (lane_newton_certify): the root, its error and its kind.
 * 3. Record: t, the point o + t d from t as a double-double, the normal
 *    from the half-gradient Mx + g at the root, certified (its rounding and
 *    the root's error below 5u of its length), else the exact path.
 *
 * Range: max|A..J| within [2^-200, 2^200] and every nonzero one above
 * 2^-600; |o| <= 2^100, 2^-100 <= max|d_k| <= 2^100 (so that b^2 and ac
 * stay below 2^1000); ETA = 2^-960 in every bound. All ten zero:
 * degenerate (never hit).
 */
#ifndef ISECT_QUADRIC_LANES_H
#define ISECT_QUADRIC_LANES_H

#include "prim/prim_lanes.h"

#define QUAD_LANES_U   0x1p-53
#define QUAD_LANES_U2  0x1p-106
#define QUAD_LANES_ETA 0x1p-960

/* The quadric's constants, prepared once per call or batch. */
typedef struct quadric_prep {
    double m[3][3];     /* M */
    double m_abs[3][3]; /* |M| */
    double m_sum[3];    /* sum_j |M_kj| */
    double g[3];        /* (G, H, I)/2 */
    double mono[9];     /* the monomials' coefficients: A, B, C, D, E, F, G, H, I */
    double j;
    double q_max;       /* S = max(|A|..|F|) */
    double g_max;       /* max|g_k| */
    double m_sum_max;   /* max_k sum_j |M_kj| */
    double c_sum;       /* sum |A..F| */
    double g_sum;       /* sum |G, H, I| */
    double eps;
    int    in_range;
    int    degenerate;
} quadric_prep;

/* The monomials x_i x_j of mono[0..5] (quadric.c's order). */
static const int quadric_lanes_var[6][2] = { { 0, 0 }, { 1, 1 }, { 2, 2 }, { 0, 1 }, { 0, 2 }, { 1, 2 } };

static inline void quadric_prepare(const double *q, double eps, quadric_prep *qp)
{
    double top = 0.0, low = INFINITY;
    for (int i = 0; i < 10; i++) {
        double a = fabs(q[i]);
        top = a > top ? a : top;
        low = a > 0.0 && a < low ? a : low;
    }
    qp->degenerate = top == 0.0;
    qp->in_range = top >= 0x1p-200 && top <= 0x1p200 && low >= 0x1p-600;
    for (int i = 0; i < 9; i++)
        qp->mono[i] = q[i];
    qp->j = q[9];
    qp->m[0][0] = q[0];
    qp->m[1][1] = q[1];
    qp->m[2][2] = q[2];
    qp->m[0][1] = qp->m[1][0] = 0.5 * q[3];
    qp->m[0][2] = qp->m[2][0] = 0.5 * q[4];
    qp->m[1][2] = qp->m[2][1] = 0.5 * q[5];
    qp->q_max = qp->c_sum = qp->g_sum = qp->g_max = qp->m_sum_max = 0.0;
    for (int i = 0; i < 6; i++) {
        qp->q_max = fabs(q[i]) > qp->q_max ? fabs(q[i]) : qp->q_max;
        qp->c_sum += fabs(q[i]);
    }
    for (int k = 0; k < 3; k++) {
        qp->g[k] = 0.5 * q[6 + k];
        qp->g_sum += fabs(q[6 + k]);
        qp->g_max = fabs(qp->g[k]) > qp->g_max ? fabs(qp->g[k]) : qp->g_max;
        qp->m_sum[k] = 0.0;
        for (int i = 0; i < 3; i++) {
            qp->m_abs[k][i] = fabs(qp->m[k][i]);
            qp->m_sum[k] += qp->m_abs[k][i];
        }
        qp->m_sum_max = qp->m_sum[k] > qp->m_sum_max ? qp->m_sum[k] : qp->m_sum_max;
    }
    qp->eps = eps;
}

/* The plain quantities shared by the refinements. */
typedef struct quadric_plain {
    lane_pair_plain pp;   /* slow: linear, maybe tangent, out of range */
    vd  y[3];             /* Md */
    vd  gd;               /* g.d */
    vd  a;                /* a */
    vd  e_y, y_max;       /* |y_k - (M d)_k| <= e_y; max|y_k| */
    vm  miss;             /* no crossing, certainly */
} quadric_plain;

/*
 * Bounds (qm = max|A..F| >= max|M_kj|, sum_j |M_kj| <= 2 qm, gm = max|g_k|,
 * dm, om the coordinates' maxima; each dot product of three terms errs by
 * at most 3u sum|terms| plus its inputs' errors):
 *   y_k  within e_y = 8u qm dm,
 *   a    within e_a = 64u qm dm^2        (18u + 24u counted),
 *   b    within e_b = 64u (qm om + gm) dm,
 *   c    within e_c = 64u (qm om^2 + gm om) + 4u |J|,
 *   G    within e_G = (2|b| + e_b) e_b + |a| e_c + |c| e_a + e_a e_c +
 *        3u (b^2 + |ac|) + ETA.
 * The tangency threshold eps (b*^2 + |a* c*|) is below eps ((|b| + e_b)^2 +
 * (|a| + e_a)(|c| + e_c)) (1 + 2^-48); not linear when |a| - e_a > eps S
 * |d|^2 (1 + 2^-47).
 */
static ALWAYS_INLINE void quadric_lanes_plain(const quadric_prep *qp, const lane_ray *ray,
                                              quadric_plain *pl)
{
    const vd *o = ray->org, *d = ray->dir;
    const vd u = vd_set1(QUAD_LANES_U);
    vd z[3];
    for (int k = 0; k < 3; k++) {
        vd mk0 = vd_set1(qp->m[k][0]), mk1 = vd_set1(qp->m[k][1]), mk2 = vd_set1(qp->m[k][2]);
        pl->y[k] = vd_add(vd_add(vd_mul(mk0, d[0]), vd_mul(mk1, d[1])), vd_mul(mk2, d[2]));
        z[k] = vd_add(vd_add(vd_mul(mk0, o[0]), vd_mul(mk1, o[1])), vd_mul(mk2, o[2]));
        z[k] = vd_add(z[k], vd_add(vd_set1(qp->g[k]), vd_set1(qp->g[k])));
    }
    const vd *y = pl->y;
    vd g0 = vd_set1(qp->g[0]), g1 = vd_set1(qp->g[1]), g2 = vd_set1(qp->g[2]);
    pl->gd = vd_add(vd_add(vd_mul(g0, d[0]), vd_mul(g1, d[1])), vd_mul(g2, d[2]));
    vd a = vd_add(vd_add(vd_mul(d[0], y[0]), vd_mul(d[1], y[1])), vd_mul(d[2], y[2]));
    vd b = vd_add(vd_add(vd_add(vd_mul(o[0], y[0]), vd_mul(o[1], y[1])), vd_mul(o[2], y[2])), pl->gd);
    vd c = vd_add(vd_add(vd_add(vd_mul(o[0], z[0]), vd_mul(o[1], z[1])), vd_mul(o[2], z[2])),
                  vd_set1(qp->j));
    vd g = vd_sub(vd_mul(b, b), vd_mul(a, c));

    vd dm = lane_max_abs3(d[0], d[1], d[2]), om = lane_max_abs3(o[0], o[1], o[2]);
    vd qm = vd_set1(qp->q_max), gm = vd_set1(qp->g_max);
    vd c64 = vd_mul(vd_set1(64.0), u);
    vd e_a = vd_mul(vd_mul(c64, qm), vd_mul(dm, dm));
    vd e_b = vd_mul(vd_mul(c64, vd_add(vd_mul(qm, om), gm)), dm);
    vd e_c = vd_add(vd_mul(vd_mul(c64, om), vd_add(vd_mul(qm, om), gm)),
                    vd_mul(vd_mul(vd_set1(4.0), u), vd_set1(fabs(qp->j))));
    vd a_abs = vd_abs(a), b_abs = vd_abs(b), c_abs = vd_abs(c);
    vd e_g = vd_add(vd_add(vd_mul(vd_add(vd_add(b_abs, b_abs), e_b), e_b),
                           vd_add(vd_mul(a_abs, e_c), vd_mul(c_abs, e_a))),
                    vd_add(vd_add(vd_mul(e_a, e_c), vd_mul(vd_mul(vd_set1(3.0), u),
                                                           vd_add(vd_mul(b, b), vd_mul(a_abs, c_abs)))),
                           vd_set1(QUAD_LANES_ETA)));
    vd b_up = vd_add(b_abs, e_b);
    vd band = vd_add(vd_mul(vd_set1(qp->eps * (1.0 + 0x1p-48)),
                            vd_add(vd_mul(b_up, b_up), vd_mul(vd_add(a_abs, e_a), vd_add(c_abs, e_c)))),
                     e_g);
    vd dd = vd_add(vd_add(vd_mul(d[0], d[0]), vd_mul(d[1], d[1])), vd_mul(d[2], d[2]));
    vm not_linear = vd_gt(vd_sub(a_abs, e_a),
                          vd_mul(vd_set1(qp->eps * qp->q_max * (1.0 + 0x1p-47)), dd));
    vm ok = qp->in_range ? vm_and(vm_and(vd_le(om, vd_set1(0x1p100)), vd_ge(dm, vd_set1(0x1p-100))),
                                  vm_and(vd_le(dm, vd_set1(0x1p100)), not_linear))
                         : vm_false();
    pl->pp.cross = vm_and(ok, vd_gt(g, band));
    pl->miss = vm_and(ok, vd_lt(g, vd_neg(band)));
    pl->pp.slow = vm_not(vm_or(pl->pp.cross, pl->miss));
    pl->pp.none = qp->degenerate ? vm_true() : vm_false();
    pl->pp.lo_enter = vd_gt(a, vd_zero());
    pl->pp.g_low = vd_sub(g, e_g);
    pl->pp.a_up = vd_mul(vd_add(a_abs, e_a), vd_set1(1.0 + 2.0 * QUAD_LANES_U));
    pl->a = a;
    pl->e_y = vd_mul(vd_mul(vd_set1(8.0), u), vd_mul(qm, dm));
    pl->y_max = lane_max_abs3(y[0], y[1], y[2]);
    vd t_enter, t_exit;
    lane_quad_starts(a, b, c, g, &t_enter, &t_exit);
    pl->pp.t_lo = vd_sel(pl->pp.lo_enter, t_enter, t_exit);
    pl->pp.t_hi = vd_sel(pl->pp.lo_enter, t_exit, t_enter);
}

/* The lanes that may meet the quadric: all but the certain misses of the
 * plain solve (the kernel repeats it for the others). */
static ALWAYS_INLINE vm quadric_lanes_screen(const quadric_prep *qp, const lane_ray *ray)
{
    quadric_plain pl;
    quadric_lanes_plain(qp, ray, &pl);
    return vm_not(pl.miss);
}

/*
 * One certified Newton step from t0. With F = max|o| + |t0| max|d|, X =
 * sum|xh_k|, L = sum|xl_k| (<= 6uF), H = |J| + sum of the heads' magnitudes:
 *   x   = xh + xl: within u|xl| <= 2u^2 F per component;
 *   R   = Q(x): the heads exact, summed by TwoSums (the cascade's own error
 *         <= 81u^2 H), each monomial's low parts c (P.lo + xh_i xl_j + xl_i
 *         xh_j) and g xl rounded, c xl_i xl_j and x's error dropped: E_R <=
 *         128u^2 H + 32u^2 sum|A..F| F^2 + 8u^2 sum|G, H, I| F + u|R| + ETA;
 *   P   = xh.y + g.d: E_P <= 4u (sum|xh_k y_k| + |g.d|) + (X + L) e_y + L
 *         max|y| + 4u sum|G, H, I| max|d| + ETA;
 *   a   within e_a: a_up = (|a| + e_a)(1 + 2u).
 * The normal is left to the record (quadric_lanes_record), which only the
 * reported crossing needs.
 */
static ALWAYS_INLINE void quadric_lanes_refine(const void *prep, const lane_ray *ray,
                                               const void *plain, vd t0, lane_root *rt)
{
    const quadric_prep *qp = prep;
    const quadric_plain *pl = plain;
    const vd *o = ray->org, *d = ray->dir;
    const vd u = vd_set1(QUAD_LANES_U), u2 = vd_set1(QUAD_LANES_U2);
    vd xh[3], xl[3];
    const vdd org[3] = { { o[0], vd_zero() }, { o[1], vd_zero() }, { o[2], vd_zero() } };
    lane_offset_at(org, t0, d, xh, xl);
    vd acc = vd_set1(qp->j), lows = vd_zero(), heads = vd_set1(fabs(qp->j));
    for (int m = 0; m < 9; m++) {
        double coef = qp->mono[m];
        if (coef == 0.0)
            continue;
        vd c = vd_set1(coef);
        vdd h;
        vd low;
        if (m < 6) {
            int i = quadric_lanes_var[m][0], j = quadric_lanes_var[m][1];
            vdd p = two_prod(xh[i], xh[j]);
            h = two_prod(c, p.hi);
            low = vd_mul(c, vd_add(p.lo, vd_add(vd_mul(xh[i], xl[j]), vd_mul(xl[i], xh[j]))));
        } else {
            h = two_prod(c, xh[m - 6]);
            low = vd_mul(c, xl[m - 6]);
        }
        vdd s = two_sum(acc, h.hi);
        acc = s.hi;
        lows = vd_add(lows, vd_add(vd_add(s.lo, h.lo), low));
        heads = vd_add(heads, vd_abs(h.hi));
    }
    vd r = vd_add(acc, lows);

    vd dm = lane_max_abs3(d[0], d[1], d[2]);
    vd big_f = vd_add(lane_max_abs3(o[0], o[1], o[2]), vd_mul(vd_abs(t0), dm));
    vd e_r = vd_add(vd_add(vd_mul(vd_mul(vd_set1(128.0), u2), heads),
                           vd_mul(vd_mul(u2, big_f),
                                  vd_add(vd_mul(vd_set1(32.0 * qp->c_sum), big_f),
                                         vd_set1(8.0 * qp->g_sum)))),
                    vd_add(vd_mul(u, vd_abs(r)), vd_set1(QUAD_LANES_ETA)));

    vd q0 = vd_mul(xh[0], pl->y[0]), q1 = vd_mul(xh[1], pl->y[1]), q2 = vd_mul(xh[2], pl->y[2]);
    vd pp = vd_add(vd_add(vd_add(q0, q1), q2), pl->gd);
    vd x_sum = vd_add(vd_add(vd_abs(xh[0]), vd_abs(xh[1])), vd_abs(xh[2]));
    vd l_sum = vd_add(vd_add(vd_abs(xl[0]), vd_abs(xl[1])), vd_abs(xl[2]));
    vd e_p = vd_add(vd_add(vd_mul(vd_mul(vd_set1(4.0), u),
                                  vd_add(vd_add(vd_add(vd_abs(q0), vd_abs(q1)), vd_abs(q2)), vd_abs(pl->gd))),
                           vd_mul(vd_add(x_sum, l_sum), pl->e_y)),
                    vd_add(vd_add(vd_mul(vd_mul(l_sum, pl->y_max), vd_set1(1.0 + 0x1p-40)),
                                  vd_mul(vd_set1(4.0 * 0x1p-53 * qp->g_sum), dm)),
                           vd_set1(QUAD_LANES_ETA)));
    lane_newton nt;
    lane_root_newton(t0, r, e_r, pp, e_p, pl->a, pl->pp.a_up, &nt, rt);

    rt->v[0] = rt->v[1] = rt->v[2] = vd_zero();
}

/*
 * The record of a refined crossing, and whether its normal is certified:
 * the point from the double-double t; the normal from the half-gradient
 * v = Mx + g at x = o + t d, x as xh + xl (TwoProduct, TwoSum; xl rounded,
 * within 3u^2 F), each v_k from exact products of the heads summed by
 * TwoSums, the low parts to first order: |v_k - exact| <= u|v_k| + 20u^2
 * (sum_j |M_kj xh_j| + |g_k|) + sum_j |M_kj| (rho max|d| + 48u^2 F) (the
 * lows' tree of depth 4, x's rounding, the double-double t's own error
 * rho). Certified when the part beyond u|v_k| is below u
 * of |v| (so the normal is within ~3u rad of the exact one, its
 * normalisation included); else the caller defers the crossing. prim -1,
 * the kind its root says.
 */
static ALWAYS_INLINE vm quadric_lanes_record(const quadric_prep *qp, const lane_ray *ray,
                                             const lane_root *rt, lane_hit *h)
{
    const vd *o = ray->org, *d = ray->dir;
    const vd u2 = vd_set1(QUAD_LANES_U2);
    vd xh[3], xl[3];
    lane_point_on_ray_dd(ray, rt->t_dd, xh, xl);
    for (int k = 0; k < 3; k++)
        h->point[k] = vd_add(xh[k], xl[k]);
    vd dm = lane_max_abs3(d[0], d[1], d[2]);
    vd big_f = vd_add(lane_max_abs3(o[0], o[1], o[2]), vd_mul(vd_abs(rt->t_dd.hi), dm));
    vd delta = vd_add(vd_mul(rt->rho, dm), vd_mul(vd_mul(vd_set1(48.0), u2), big_f));
    vd v[3], gg = vd_zero(), ee = vd_zero();
    for (int k = 0; k < 3; k++) {
        vd m0 = vd_set1(qp->m[k][0]), m1 = vd_set1(qp->m[k][1]), m2 = vd_set1(qp->m[k][2]);
        vdd p0 = two_prod(m0, xh[0]), p1 = two_prod(m1, xh[1]), p2 = two_prod(m2, xh[2]);
        vdd s1 = two_sum(p0.hi, p1.hi);
        vdd s2 = two_sum(s1.hi, p2.hi);
        vdd s3 = two_sum(s2.hi, vd_set1(qp->g[k]));
        vd lo = vd_add(vd_add(vd_add(s1.lo, s2.lo), vd_add(s3.lo, vd_add(p0.lo, vd_add(p1.lo, p2.lo)))),
                       vd_add(vd_add(vd_mul(m0, xl[0]), vd_mul(m1, xl[1])), vd_mul(m2, xl[2])));
        v[k] = vd_add(s3.hi, lo);
        vd abs_sum = vd_add(vd_add(vd_abs(p0.hi), vd_abs(p1.hi)),
                            vd_add(vd_abs(p2.hi), vd_set1(fabs(qp->g[k]))));
        vd e = vd_add(vd_mul(vd_mul(vd_set1(20.0), u2), abs_sum), vd_mul(vd_set1(qp->m_sum[k]), delta));
        gg = vd_add(gg, vd_mul(v[k], v[k]));
        ee = vd_add(ee, vd_mul(e, e));
    }
    lane_unit_scaled(v, vd_div(vd_set1(1.0), vd_sqrt(gg)), h->normal);
    h->t = rt->t;
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = vd_set1(-1.0);
    h->kind = vd_sel(rt->enter, vd_set1((double)ISECT_ENTER), vd_set1((double)ISECT_EXIT));
    return vm_and(vd_le(ee, vd_mul(vd_set1(QUAD_LANES_U2 * (1.0 - 0x1p-40)), gg)),
                  vd_gt(gg, vd_set1(0x1p-900)));
}

/* The crossings' verdicts (prim_lanes.h: lane_pair_solve). */
typedef struct quadric_lanes {
    lane_pair pr;
    lane_root root[2];
    vm lo_enter;
} quadric_lanes;

static ALWAYS_INLINE void quadric_lanes_solve(const quadric_prep *qp, const lane_ray *ray, int first,
                                              quadric_lanes *ql)
{
    quadric_plain pl;
    quadric_lanes_plain(qp, ray, &pl);
    lane_pair_solve(quadric_lanes_refine, qp, &pl, NULL, NULL, &pl.pp, ray, first, ql->root,
                    &ql->pr);
    ql->lo_enter = pl.pp.lo_enter;
}

/* The first hit in [tmin, tmax], for lanes the screen passed. */
static ALWAYS_INLINE void quadric_lanes_first(const quadric_prep *qp, const lane_ray *ray,
                                              lane_hit *h)
{
    quadric_lanes ql;
    quadric_lanes_solve(qp, ray, 1, &ql);
    lane_root rt;
    (void)lane_pair_first(&ql.pr, ql.root, &rt, h);
    vm normal_ok = quadric_lanes_record(qp, ray, &rt, h);
    h->slow = vm_or(h->slow, vm_andnot(h->found, normal_ok)); /* a normal it cannot certify */
    h->found = vm_andnot(h->found, h->slow);
}

#endif /* ISECT_QUADRIC_LANES_H */
