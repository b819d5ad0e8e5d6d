/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ellipsoid_lanes.h — the axis-aligned ellipsoid's fast kernel, LANE_W rays
 * at once (prim_lanes.h states the contract; ellipsoid.c holds the exact
 * path it defers to). The sphere's method (sphere_lanes.h) with weights.
 *
 * The line function. With rho = min R_k, mu_k = (rho/R_k)^2 <= 1 and
 * f = o - c, the ellipsoid along the line is
 *     Q(t) = sum mu_k (f_k + t d_k)^2 - rho^2 = A t^2 + 2B t + C,
 *     A = sum mu_k d_k^2, B = sum mu_k f_k d_k,
 *     G = B^2 - A C = rho^2 A - sum_k nu_k m_k^2,
 * m = f x d, nu_k = mu_i mu_j ((k, i, j) cyclic; Lagrange's identity: the
 * sphere's geometric discriminant, which does not cancel for a small
 * ellipsoid far away). The weights are double-doubles, within 12u^2 mu of
 * (rho/R)^2 (ellipsoid_weight); rho^2 is exact as two doubles. These are
 * ellipsoid.c's function and tangency rule |G| <= eps rho^2 A.
 *
 * 1. Plain solve: A, B, C, G in doubles, G with a forward bound that decides
 *    miss / two crossings / maybe tangent (defer), and the starting values
 *    (prim_lanes.h: lane_quad_starts).
 * 2. Refinement, per needed crossing: v = f + t0 d to ~u^2 |f| (f exact by
 *    TwoSum, t0 d by TwoProduct), R = Q(t0) from exact squares times the
 *    weights' heads (TwoProduct again) with every low part kept to first
 *    order, P = sum mu_k v_k d_k, and one Newton step certified by
 *    Kantorovich's bound (lane_newton_certify): each root with its error
 *    and its kind, the entry where Q' < 0.
 * 3. Record: t, the point o + t d from t as a double-double (t0 - step
 *    exactly), the normal from the gradient mu_k v_k at the root, v =
 *    f + t0 d - step d, divided by its length and renormalised
 *    (lane_unit_newton). The root's own error moves v by at most rho |d|;
 *    the normal is certified only when that (and the rounding of step d) is
 *    below u/4 of |gradient| (a grazing ray's is not: it defers).
 *
 * Range: |o|, |c| <= 2^200, 2^-200 <= R_k <= 2^200 with max R / min R <=
 * 2^100, 2^-200 <= max|d_k| <= 2^200; every bound carries ETA = 2^-960 for
 * underflow. A zero semi-axis is degenerate (no hits).
 */
#ifndef ISECT_ELLIPSOID_LANES_H
#define ISECT_ELLIPSOID_LANES_H

#include "prim/prim_lanes.h"

#define ELLIPSOID_LANES_U   0x1p-53
#define ELLIPSOID_LANES_U2  0x1p-106
#define ELLIPSOID_LANES_ETA 0x1p-960

/*
 * (rho / r)^2 as hi + lo, rho <= r: the quotient x = rho/r as a double-double
 * (its residual rho - x r exact: Sterbenz and TwoProduct; one rounding in
 * the residual, one in lo: within 2u^2 x), then squared exactly but for
 * the cross term 2 x_hi x_lo (rounded) and x_lo^2 (dropped): within 12u^2
 * of (rho/r)^2 in all. r == rho gives 1 exactly. Shared with ellipsoid.c.
 */
static inline void ellipsoid_weight(double rho, double r, double *hi, double *lo)
{
    if (r == rho) {
        *hi = 1.0;
        *lo = 0.0;
        return;
    }
    double x = rho / r;
    double p = x * r;
    double x_lo = ((rho - p) - product_error(x, r, p)) / r;
    double s = x + x_lo; /* renormalised (Fast2Sum: |x_lo| <= u x) */
    x_lo = x_lo - (s - x);
    x = s;
    double sq = x * x;
    double sq_err = product_error(x, x, sq);
    double low = sq_err + (x * x_lo + x_lo * x);
    *hi = sq + low;
    double virt = *hi - sq;
    *lo = (sq - (*hi - virt)) + (low - virt);
}

/* The ellipsoid's constants, prepared once per call or batch. */
typedef struct ellipsoid_prep {
    double c[3];
    double mu_hi[3], mu_lo[3]; /* (rho/R_k)^2 */
    double nu[3];              /* mu_i mu_j, (k, i, j) cyclic, rounded */
    double nu_sum;
    double rr_hi, rr_lo;       /* rho^2 exactly */
    double screen_rr;          /* (1 + eps) rho^2 */
    double eps;
    int    in_range;
    int    degenerate;         /* a zero semi-axis: never hit */
} ellipsoid_prep;

static inline void ellipsoid_prepare(const double *data, double eps, ellipsoid_prep *ep)
{
    const double *radii = data + 3;
    double rho = radii[0], r_max = radii[0];
    for (int k = 1; k < 3; k++) {
        rho = radii[k] < rho ? radii[k] : rho;
        r_max = radii[k] > r_max ? radii[k] : r_max;
    }
    double c_max = 0.0;
    for (int k = 0; k < 3; k++) {
        ep->c[k] = data[k];
        c_max = fabs(data[k]) > c_max ? fabs(data[k]) : c_max;
    }
    ep->degenerate = !(rho > 0.0);
    ep->in_range = c_max <= 0x1p200 && rho >= 0x1p-200 && r_max <= 0x1p200
                && r_max <= 0x1p100 * rho;
    for (int k = 0; k < 3; k++) {
        if (ep->in_range)
            ellipsoid_weight(rho, radii[k], &ep->mu_hi[k], &ep->mu_lo[k]);
        else
            ep->mu_hi[k] = ep->mu_lo[k] = 0.0;
    }
    ep->nu_sum = 0.0;
    for (int k = 0; k < 3; k++) {
        ep->nu[k] = ep->mu_hi[(k + 1) % 3] * ep->mu_hi[(k + 2) % 3];
        ep->nu_sum += ep->nu[k];
    }
    ep->rr_hi = rho * rho;
    ep->rr_lo = product_error(rho, rho, ep->rr_hi);
    ep->screen_rr = (1.0 + eps) * ep->rr_hi;
    ep->eps = eps;
}

/* What the screen and the plain solve share, in doubles: md_k = mu_hi d_k,
 * A = sum md_k d_k, m = f x d, mm = sum nu_k m_k^2 and |m|_1. */
typedef struct ellipsoid_terms {
    vd md[3], a, mm, m_sum;
} ellipsoid_terms;

static ALWAYS_INLINE void ellipsoid_lanes_terms(const ellipsoid_prep *ep, const vd f[3],
                                                const vd d[3], ellipsoid_terms *et)
{
    vd m[3];
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        et->md[k] = vd_mul(vd_set1(ep->mu_hi[k]), d[k]);
        m[k] = vd_sub(vd_mul(f[i], d[j]), vd_mul(f[j], d[i]));
    }
    et->a = vd_add(vd_add(vd_mul(et->md[0], d[0]), vd_mul(et->md[1], d[1])), vd_mul(et->md[2], d[2]));
    et->mm = vd_add(vd_add(vd_mul(vd_set1(ep->nu[0]), vd_mul(m[0], m[0])),
                           vd_mul(vd_set1(ep->nu[1]), vd_mul(m[1], m[1]))),
                    vd_mul(vd_set1(ep->nu[2]), vd_mul(m[2], m[2])));
    et->m_sum = vd_add(vd_add(vd_abs(m[0]), vd_abs(m[1])), vd_abs(m[2]));
}

/*
 * The lanes that may meet the ellipsoid: all but the certain misses, in
 * plain arithmetic (sphere_lanes_screen with weights). The plain m_k errs
 * by at most a = 2^-50 fm dm + 2^-1000 (f rounded, two products and a
 * difference); when a^2 sum nu <= 2^-64 mm (mm = sum nu_k m_k^2, at least
 * 2^-800) the weighted norm of the error is below 2^-32 |m|_nu, so the
 * exact sum nu* M^2 >= mm (1 - 2^-28) (nu within 4u); and rho^2 A* <=
 * rr A (1 + 8u). A miss without a touch, sum nu M^2 > (1 + eps) rho^2 A, is
 * then proved by mm (1 - 2^-28) > (1 + eps) rr A (1 + 2^-26).
 */
static ALWAYS_INLINE vm ellipsoid_lanes_screen(const ellipsoid_prep *ep, const lane_ray *ray)
{
    if (!ep->in_range)
        return vm_true();
    const vd *d = ray->dir;
    vd f[3];
    for (int k = 0; k < 3; k++)
        f[k] = vd_sub(ray->org[k], vd_set1(ep->c[k]));
    ellipsoid_terms et;
    ellipsoid_lanes_terms(ep, f, d, &et);
    vd mm = et.mm;
    vd a = vd_add(vd_mul(vd_set1(0x1p-50), vd_mul(lane_max_abs3(f[0], f[1], f[2]),
                                                  lane_max_abs3(d[0], d[1], d[2]))),
                  vd_set1(0x1p-1000));
    vm usable = vm_and(vd_ge(mm, vd_set1(0x1p-800)),
                       vd_le(vd_mul(vd_mul(a, a), vd_set1(ep->nu_sum)),
                             vd_mul(vd_set1(0x1p-64), mm)));
    usable = vm_and(usable, lane_ray_in_range(ray, 0x1p200));
    vd lhs = vd_mul(mm, vd_set1(1.0 - 0x1p-28));
    vd rhs = vd_mul(vd_mul(vd_set1(ep->screen_rr), et.a), vd_set1(1.0 + 0x1p-26));
    return vm_not(vm_and(usable, vd_gt(lhs, rhs)));
}

/* The plain quantities shared by the refinements. */
typedef struct ellipsoid_plain {
    lane_pair_plain pp;  /* slow: maybe tangent, or out of range */
    vdd f[3];            /* o - c exactly */
    vd  a;               /* A */
} ellipsoid_plain;

/*
 * Bounds. The plain m_k err by at most am = 2^-50 fm dm (as the screen's);
 * A by 5.1u A (weights' heads within 1.1u, two products, two sums: all
 * terms positive), rr by u, so rr A by 7.2u; sum nu m^2 by 7.2u of itself
 * plus 2 am |m|_1 + 3 am^2 (nu <= 1); the difference by u. So |G - G*| <=
 * 2^-49 (rr A + mm) + 4 am (|m|_1 + am) + ETA, and the tangency threshold
 * eps rho^2 A* is below eps (1 + 2^-48) rr A (its own roundings included).
 */
static ALWAYS_INLINE void ellipsoid_lanes_plain(const ellipsoid_prep *ep, const lane_ray *ray,
                                                ellipsoid_plain *pl)
{
    const vd *d = ray->dir;
    vd fh[3], x[3];
    for (int k = 0; k < 3; k++) {
        pl->f[k] = two_sum(ray->org[k], vd_set1(-ep->c[k]));
        fh[k] = pl->f[k].hi;
        x[k] = vd_mul(vd_set1(ep->mu_hi[k]), fh[k]);
    }
    ellipsoid_terms et;
    ellipsoid_lanes_terms(ep, fh, d, &et);
    const vd *md = et.md;
    vd a = et.a, mm = et.mm, m_sum = et.m_sum;
    vd b = vd_add(vd_add(vd_mul(md[0], fh[0]), vd_mul(md[1], fh[1])), vd_mul(md[2], fh[2]));
    vd c = vd_sub(vd_add(vd_add(vd_mul(x[0], fh[0]), vd_mul(x[1], fh[1])), vd_mul(x[2], fh[2])),
                  vd_set1(ep->rr_hi));
    vd rr_a = vd_mul(vd_set1(ep->rr_hi), a);
    vd g = vd_sub(rr_a, mm);
    vd am = vd_mul(vd_set1(0x1p-50), vd_mul(lane_max_abs3(fh[0], fh[1], fh[2]),
                                            lane_max_abs3(d[0], d[1], d[2])));
    vd e_g = vd_add(vd_add(vd_mul(vd_set1(0x1p-49), vd_add(rr_a, mm)),
                           vd_mul(vd_set1(4.0), vd_mul(am, vd_add(m_sum, am)))),
                    vd_set1(ELLIPSOID_LANES_ETA));
    vd band = vd_add(vd_mul(vd_set1(ep->eps * (1.0 + 0x1p-48)), rr_a), e_g);
    pl->pp.cross = vd_gt(g, band);
    vm miss = vd_lt(g, vd_neg(band));
    vm ok = ep->in_range ? lane_ray_in_range(ray, 0x1p200) : vm_false();
    pl->pp.slow = vm_not(vm_and(ok, vm_or(pl->pp.cross, miss)));
    pl->pp.none = ep->degenerate ? vm_true() : vm_false();
    pl->pp.lo_enter = vm_true();
    pl->pp.g_low = vd_sub(g, e_g);
    pl->pp.a_up = vd_mul(a, vd_set1(1.0 + 8.0 * ELLIPSOID_LANES_U));
    pl->a = a;
    lane_quad_starts(a, b, c, g, &pl->pp.t_lo, &pl->pp.t_hi);
}

/*
 * One certified Newton step from t0. Bounds (F = max|fh| + |t0| max|d|,
 * V = sum|vh_k|, L = sum|vl_k|, S = sum mu_hi vh^2 as summed):
 *   v    = vh + vl: within 8u^2 F per component (sphere_lanes.h);
 *   R    = sum mu (vh + vl)^2 - rho^2, with mu_hi vh^2 exact (two
 *          TwoProducts), the heads summed exactly (TwoSum), every low part
 *          (mu_hi vh_lo^2, mu_lo vh^2, 2 mu_hi vh vl) rounded, mu vl^2
 *          dropped: E_R <= 48u^2 (S + rr) + 24u^2 V F + 24u V L + L^2 +
 *          u|R| + ETA (the weights' 12u^2, the lows' roundings in a tree of
 *          depth <= 6, v's error);
 *   P    = sum fl(mu_hi vh_k) d_k: E_P <= 6u sum|x_k d_k| + max|d| (L +
 *          24u^2 F) (1 + 2^-40) + ETA;
 *   A    within 5.1u: a_up = A (1 + 8u).
 * The root's v is the gradient mu_k v_k there, vv its squared length.
 */
static ALWAYS_INLINE void ellipsoid_lanes_refine(const void *prep, const lane_ray *ray,
                                                 const void *plain, vd t0, lane_root *rt)
{
    const ellipsoid_prep *ep = prep;
    const ellipsoid_plain *pl = plain;
    const vd *d = ray->dir;
    const vd u = vd_set1(ELLIPSOID_LANES_U), u2 = vd_set1(ELLIPSOID_LANES_U2);
    vd vh[3], vl[3], x[3], w[3], h_hi[3];
    lane_offset_at(pl->f, t0, d, vh, vl);
    for (int k = 0; k < 3; k++) {
        vd mu = vd_set1(ep->mu_hi[k]);
        vdd sq = two_prod(vh[k], vh[k]);
        vdd h = two_prod(mu, sq.hi);
        h_hi[k] = h.hi;
        w[k] = vd_add(vd_add(h.lo, vd_mul(mu, sq.lo)), vd_mul(vd_set1(ep->mu_lo[k]), sq.hi));
        x[k] = vd_mul(mu, vh[k]);
    }
    vdd s1 = two_sum(h_hi[0], h_hi[1]);
    vdd s2 = two_sum(s1.hi, h_hi[2]);
    vdd s3 = two_sum(s2.hi, vd_set1(-ep->rr_hi));
    vd cross = vd_add(vd_add(vd_mul(x[0], vl[0]), vd_mul(x[1], vl[1])), vd_mul(x[2], vl[2]));
    vd lows = vd_add(vd_add(vd_add(s1.lo, s2.lo), vd_sub(s3.lo, vd_set1(ep->rr_lo))),
                     vd_add(vd_add(w[0], w[1]), vd_add(w[2], vd_add(cross, cross))));
    vd r = vd_add(s3.hi, lows);

    vd v_sum = vd_add(vd_add(vd_abs(vh[0]), vd_abs(vh[1])), vd_abs(vh[2]));
    vd l_sum = vd_add(vd_add(vd_abs(vl[0]), vd_abs(vl[1])), vd_abs(vl[2]));
    vd d_max = lane_max_abs3(d[0], d[1], d[2]);
    vd big_f = vd_add(lane_max_abs3(pl->f[0].hi, pl->f[1].hi, pl->f[2].hi),
                      vd_mul(vd_abs(t0), d_max));
    vd e_r = vd_add(vd_add(vd_mul(vd_mul(vd_set1(48.0), u2), vd_add(s2.hi, vd_set1(ep->rr_hi))),
                           vd_mul(vd_mul(vd_set1(24.0), u2), vd_mul(v_sum, big_f))),
                    vd_add(vd_add(vd_mul(vd_mul(vd_set1(24.0), u), vd_mul(v_sum, l_sum)),
                                  vd_mul(l_sum, l_sum)),
                           vd_add(vd_mul(u, vd_abs(r)), vd_set1(ELLIPSOID_LANES_ETA))));

    vd p0 = vd_mul(x[0], d[0]), p1 = vd_mul(x[1], d[1]), p2 = vd_mul(x[2], d[2]);
    vd pp = vd_add(vd_add(p0, p1), p2);
    vd e_p = vd_add(vd_add(vd_mul(vd_mul(vd_set1(6.0), u),
                                  vd_add(vd_add(vd_abs(p0), vd_abs(p1)), vd_abs(p2))),
                           vd_mul(vd_mul(d_max, vd_add(l_sum, vd_mul(vd_mul(vd_set1(24.0), u2), big_f))),
                                  vd_set1(1.0 + 0x1p-40))),
                    vd_set1(ELLIPSOID_LANES_ETA));
    lane_newton nt;
    lane_root_newton(t0, r, e_r, pp, e_p, pl->a, pl->pp.a_up, &nt, rt);
    vd gg = vd_zero();
    for (int k = 0; k < 3; k++) {
        vd v = vd_add(vh[k], vd_sub(vl[k], vd_mul(nt.step, d[k])));
        rt->v[k] = vd_mul(vd_set1(ep->mu_hi[k]), v);
        gg = vd_add(gg, vd_mul(rt->v[k], rt->v[k]));
    }
    rt->vv = gg;
    vd e_n = vd_add(vd_mul(vd_add(vd_mul(vd_set1(4.0), nt.rho), vd_mul(vd_mul(vd_set1(4.0), u), vd_abs(nt.step))),
                           d_max),
                    vd_mul(vd_mul(vd_set1(32.0), u2), big_f));
    vm normal_ok = vd_le(vd_mul(e_n, e_n), vd_mul(vd_set1(ELLIPSOID_LANES_U2), gg));
    rt->ok = vm_and(nt.ok, normal_ok);
}

/* The record of a refined crossing: the point from the double-double t,
 * the unit normal from the gradient (divided by its length, renormalised),
 * prim -1 and the kind. */
static ALWAYS_INLINE void ellipsoid_lanes_record(const lane_ray *ray, const lane_root *rt,
                                                 vm exit, lane_hit *h)
{
    lane_unit_scaled(rt->v, vd_div(vd_set1(1.0), vd_sqrt(rt->vv)), h->normal);
    h->t = rt->t;
    lane_point_on_ray(ray, rt->t_dd, h->point);
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = vd_set1(-1.0);
    h->kind = vd_sel(exit, vd_set1((double)ISECT_EXIT), vd_set1((double)ISECT_ENTER));
}

/* The crossings' verdicts (prim_lanes.h: lane_pair_solve). */
typedef struct ellipsoid_lanes {
    lane_pair pr;
    lane_root root[2];
} ellipsoid_lanes;

static ALWAYS_INLINE void ellipsoid_lanes_solve(const ellipsoid_prep *ep, const lane_ray *ray,
                                                int first, ellipsoid_lanes *el)
{
    ellipsoid_plain pl;
    ellipsoid_lanes_plain(ep, ray, &pl);
    lane_pair_solve(ellipsoid_lanes_refine, ep, &pl, NULL, NULL, &pl.pp, ray, first, el->root,
                    &el->pr);
}

/* The first hit in [tmin, tmax], for lanes the screen passed. */
static ALWAYS_INLINE void ellipsoid_lanes_first(const ellipsoid_prep *ep, const lane_ray *ray,
                                                lane_hit *h)
{
    ellipsoid_lanes el;
    ellipsoid_lanes_solve(ep, ray, 1, &el);
    lane_root rt;
    vm exit = lane_pair_first(&el.pr, el.root, &rt, h);
    ellipsoid_lanes_record(ray, &rt, exit, h);
}

#endif /* ISECT_ELLIPSOID_LANES_H */
