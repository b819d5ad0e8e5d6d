/* SPDX-License-Identifier: Apache-2.0 */
/*
 * cylinder_lanes.h — the cylinders' fast kernels, LANE_W rays at once
 * (prim_lanes.h states the contract; cylinder.c holds the exact path they
 * defer to): the infinite cylinder, the open one (the side between the cap
 * planes) and the capped solid.
 *
 * The side (cylinder.c's function). With a the axis vector (p1 - p0
 * exactly as a double-double, or the given axis) and f = o - p0, the side
 * along the line is
 *     Q(t) = |w(t)|^2 - r^2 a.a,   w(t) = (f + t d) x a = m + t n,
 *     A = n.n (n = d x a),  B = m.n,  C = m.m - r^2 a.a,
 *     G = B^2 - A C = a.a (r^2 A - T^2),  T = f.n = [f, d, a]
 * (|m x n| = |a| |T|: the discriminant as the distance between the line and
 * the axis, free of the cancellation of B^2 - AC for a ray from afar).
 * Tangency |G| <= eps r^2 a.a A; parallel to the axis when A <= eps^2 d.d
 * a.a (both deferred here). The axis is taken times 2^-e (exact) so that
 * its largest component lies in [0.5, 1): Q scales by 2^-2e, t and every
 * decision stay.
 *
 * 1. Plain solve: n, m, A, B, C, T in doubles with forward bounds (per
 *    component |n - n*| <= en = 2^-50 max|d| max|a|, the low part of a
 *    included), G's bound deciding miss / two crossings / defer, the
 *    starting values (lane_quad_starts).
 * 2. Refinement: v = f + t0 d to ~u^2 (as the sphere's), w = v x a with
 *    exact products of the heads (TwoProduct) and the first-order low
 *    terms (v's and a's low parts) rounded, R = |w|^2 - r^2 a.a from exact
 *    squares, P = w.n (Q'/2), one Newton step certified by Kantorovich's
 *    bound (lane_newton_certify).
 * 3. Caps (finite cylinders): the planes (x - p0).a = 0 and (x - p1).a = 0
 *    crossed at t = -F0/D and -F1/D, F0 = f.a, F1 = F0 - (p1 - p0).a, D =
 *    d.a, each a double-double dot product (lane_dot3_dd) with a bound, the
 *    quotients certified (lane_quotient_neg). A cap plane parallel to the
 *    ray by the policy (|D| <= eps |d| |a|) or a D near 0 defers.
 *    Capped: entry = the later of the side's entry and the cap crossed
 *    first, exit = the earlier of the side's exit and the other cap, each
 *    choice made only where the certified intervals separate (a tie goes
 *    to the side by the rule: the exact path decides it); entry before
 *    exit, certainly and by more than 16u of their size, or a certain miss.
 *    Open: each side crossing reported where it lies certainly inside the
 *    slab between the caps, skipped where certainly outside.
 * 4. Records: t, the point o + t d from t as a double-double; the side's
 *    normal radial, a x w at the root (|a x w| = r a.a there), times
 *    1/(r a.a) and renormalised (lane_unit_newton), certified when the
 *    root's error moves w by less than u/4 of r |a|; a cap's the unit axis,
 *    outward.
 *
 * Range: |o|, |p0|, |p1| <= 2^200, 2^-200 <= r <= 2^200, 2^-200 <= max|a_k|
 * <= 2^202 (the given or p1 - p0) with its scaled low part exact,
 * 2^-200 <= max|d_k| <= 2^200; ETA = 2^-960 in every bound for underflow.
 * r = 0 or a zero axis is degenerate: never hit.
 */
#ifndef ISECT_CYLINDER_LANES_H
#define ISECT_CYLINDER_LANES_H

#include "prim/prim_lanes.h"
#include "core/scaling.h"

#define CYL_LANES_U   0x1p-53
#define CYL_LANES_U2  0x1p-106
#define CYL_LANES_ETA 0x1p-960

enum { CYL_INFINITE, CYL_OPEN, CYL_CAPPED };

/* The kind of an ISECT_CYLINDER or ISECT_CYLINDER_INF shape. */
static inline int cylinder_kind(int32_t type, int32_t flags)
{
    return type == ISECT_CYLINDER_INF ? CYL_INFINITE : (flags & ISECT_CAPPED) ? CYL_CAPPED : CYL_OPEN;
}

/* The cylinder's constants, prepared once per call or batch. */
typedef struct cylinder_prep {
    double p[3];                 /* p0, or the infinite cylinder's point */
    double a_hi[3], a_lo[3];     /* the axis times 2^-e */
    double aa_hi, aa_lo;         /* a.a (within 8u^2: compensated, a_lo^2 dropped) */
    double rr_hi;                /* r^2, rounded */
    double rr_aa_hi, rr_aa_lo;   /* r^2 a.a (within 12u^2) */
    double cap_hi, cap_lo;       /* (p1 - p0).a = 2^e a.a: F1 = F0 - this */
    double inv_r_aa;             /* 1/(r a.a), rounded */
    double unit_a[3];            /* a/|a|, the normal of the cap at p1 */
    double screen_rr;            /* (1 + eps) r^2 */
    double eps, eps2;
    int    kind;                 /* CYL_* */
    int    in_range;
    int    degenerate;           /* never hit */
} cylinder_prep;

static inline void cylinder_prepare(const double *data, int kind, double eps, cylinder_prep *cp)
{
    double r = data[6], a[3], a_lo[3], p_max = 0.0, a_max = 0.0;
    for (int k = 0; k < 3; k++) {
        cp->p[k] = data[k];
        if (kind == CYL_INFINITE) {
            a[k] = data[3 + k];
            a_lo[k] = 0.0;
        } else { /* p1 - p0, exactly */
            a[k] = data[3 + k] - data[k];
            double virt = a[k] - data[3 + k];
            a_lo[k] = (data[3 + k] - (a[k] - virt)) + (-data[k] - virt);
            p_max = fabs(data[3 + k]) > p_max ? fabs(data[3 + k]) : p_max;
        }
        p_max = fabs(data[k]) > p_max ? fabs(data[k]) : p_max;
        a_max = fabs(a[k]) > a_max ? fabs(a[k]) : a_max;
    }
    cp->kind = kind;
    cp->degenerate = !(r > 0.0) || !(a_max > 0.0);
    cp->in_range = !cp->degenerate && p_max <= 0x1p200 && r >= 0x1p-200 && r <= 0x1p200
                && a_max >= 0x1p-200 && a_max <= 0x1p202;
    int e = cp->in_range ? pow2_exponent(a_max) : 0;
    comp_sum aa = { 0.0, 0.0 };
    double cross = 0.0;
    for (int k = 0; k < 3; k++) {
        cp->a_hi[k] = pow2_scale(a[k], -e);
        cp->a_lo[k] = pow2_scale(a_lo[k], -e);
        cp->in_range &= pow2_scale(cp->a_lo[k], e) == a_lo[k]; /* no underflow */
        comp_add_product(&aa, cp->a_hi[k], cp->a_hi[k]);
        cross += cp->a_hi[k] * cp->a_lo[k];
    }
    comp_add(&aa, cross + cross);
    cp->aa_hi = aa.hi + aa.lo;
    cp->aa_lo = aa.lo - (cp->aa_hi - aa.hi);
    cp->cap_hi = pow2_scale(cp->aa_hi, e);
    cp->cap_lo = pow2_scale(cp->aa_lo, e);
    cp->rr_hi = r * r;
    double rr_lo = product_error(r, r, cp->rr_hi);
    double hi = cp->rr_hi * cp->aa_hi;
    double lo = product_error(cp->rr_hi, cp->aa_hi, hi) + (cp->rr_hi * cp->aa_lo + rr_lo * cp->aa_hi);
    cp->rr_aa_hi = hi + lo;
    cp->rr_aa_lo = lo - (cp->rr_aa_hi - hi);
    cp->inv_r_aa = 1.0 / (r * cp->aa_hi);
    if (!unit3_accurate(cp->unit_a, cp->a_hi))
        cp->unit_a[0] = cp->unit_a[1] = cp->unit_a[2] = 0.0;
    cp->screen_rr = (1.0 + eps) * cp->rr_hi;
    cp->eps = eps;
    cp->eps2 = eps * eps;
}

/* x cross y for lanes x and the axis heads y, plain. */
static ALWAYS_INLINE void cyl_cross_axis(const cylinder_prep *cp, const vd x[3], vd out[3])
{
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        out[k] = vd_sub(vd_mul(x[i], vd_set1(cp->a_hi[j])), vd_mul(x[j], vd_set1(cp->a_hi[i])));
    }
}

/* (xh + xl) x a, a = a_hi + a_lo, as yh + yl: the heads' products exact
 * (TwoProduct) and their difference exact (TwoSum), the first-order terms
 * (xl x a_hi, xh x a_lo, the products' errors) rounded, xl x a_lo dropped. */
static ALWAYS_INLINE void cyl_cross_axis_dd(const cylinder_prep *cp, const vd xh[3], const vd xl[3],
                                            vd yh[3], vd yl[3])
{
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        vd ai = vd_set1(cp->a_hi[i]), aj = vd_set1(cp->a_hi[j]);
        vdd p1 = two_prod(xh[i], aj), p2 = two_prod(xh[j], ai);
        vdd s = two_sum(p1.hi, vd_neg(p2.hi));
        yh[k] = s.hi;
        vd low_x = vd_sub(vd_mul(xl[i], aj), vd_mul(xl[j], ai));
        vd low_a = vd_sub(vd_mul(xh[i], vd_set1(cp->a_lo[j])), vd_mul(xh[j], vd_set1(cp->a_lo[i])));
        yl[k] = vd_add(vd_add(s.lo, vd_sub(p1.lo, p2.lo)), vd_add(low_x, low_a));
    }
}

/*
 * Bounds shared by the screen and the plain solve, for n = d x a_hi and
 * T = f.n with f rounded (|f - f*| <= u|f|): per component |n - n*| <= en
 * (two products and a difference, 6u max|d| max|a|, and d x a_lo); A = n.n
 * within e_A = 2 |n|_1 en + 3 en^2 + 4u A; T within e_T = max|f| (5u
 * |n|_1 + 4 en).
 */
typedef struct cyl_bounds {
    vd en, n_sum, e_a, e_t;
} cyl_bounds;

static ALWAYS_INLINE void cyl_bounds_make(const vd n[3], vd a, vd f_max, vd d_max, cyl_bounds *b)
{
    const vd u = vd_set1(CYL_LANES_U);
    b->en = vd_mul(vd_set1(0x1p-50), d_max); /* max|a_hi| < 1 */
    b->n_sum = vd_add(vd_add(vd_abs(n[0]), vd_abs(n[1])), vd_abs(n[2]));
    b->e_a = vd_add(vd_add(vd_mul(vd_mul(vd_set1(2.0), b->n_sum), b->en),
                           vd_mul(vd_mul(vd_set1(3.0), b->en), b->en)),
                    vd_add(vd_mul(vd_mul(vd_set1(4.0), u), a), vd_set1(CYL_LANES_ETA)));
    b->e_t = vd_add(vd_mul(f_max, vd_add(vd_mul(vd_mul(vd_set1(5.0), u), b->n_sum),
                                         vd_mul(vd_set1(4.0), b->en))),
                    vd_set1(CYL_LANES_ETA));
}

/*
 * The lanes that may meet the side (the cylinder itself for every kind):
 * all but the lines certainly farther than r sqrt(1 + eps) from the axis
 * (then G < -eps r^2 a.a A: no crossing, no touch), i.e. where (|T| -
 * e_T)^2 > (1 + eps) r^2 (A + e_A) (1 + 2^-48).
 */
static ALWAYS_INLINE vm cylinder_lanes_screen(const cylinder_prep *cp, const lane_ray *ray)
{
    if (!cp->in_range)
        return vm_true();
    const vd *d = ray->dir;
    vd f[3], n[3];
    for (int k = 0; k < 3; k++)
        f[k] = vd_sub(ray->org[k], vd_set1(cp->p[k]));
    cyl_cross_axis(cp, d, n);
    vd t = vd_add(vd_add(vd_mul(f[0], n[0]), vd_mul(f[1], n[1])), vd_mul(f[2], n[2]));
    vd a = vd_add(vd_add(vd_mul(n[0], n[0]), vd_mul(n[1], n[1])), vd_mul(n[2], n[2]));
    cyl_bounds b;
    cyl_bounds_make(n, a, lane_max_abs3(f[0], f[1], f[2]), lane_max_abs3(d[0], d[1], d[2]), &b);
    vd t_low = vd_sub(vd_abs(t), b.e_t);
    vd rhs = vd_mul(vd_mul(vd_set1(cp->screen_rr), vd_add(a, b.e_a)), vd_set1(1.0 + 0x1p-48));
    vm miss = vm_and(vd_gt(t_low, vd_zero()), vd_gt(vd_mul(t_low, t_low), rhs));
    return vm_not(vm_and(miss, lane_ray_in_range(ray, 0x1p200)));
}

/* The side's plain quantities (the pair's: slow = maybe tangent, maybe
 * parallel to the axis, or out of range). */
typedef struct cyl_plain {
    lane_pair_plain pp;
    vdd f[3];       /* o - p0 exactly */
    vd  n[3];       /* d x a_hi */
    vd  en, n_sum;  /* n's bound per component, |n|_1 */
    vd  a;          /* A */
} cyl_plain;

/*
 * G = a.a (r^2 A - T^2) in doubles: with rr within u, |r^2 A - T^2 - exact|
 * <= rr (e_A + 2u A) + e_T (2|T| + e_T) + 3u (rr A + T^2) (the roundings),
 * and a.a within u^2 of a.a_hi, the product's rounding: e_G = a.a (rr (e_A
 * + 2u A) + e_T (2|T| + e_T) + 6u (rr A + T^2)) (1 + 2^-40) + ETA. The
 * tangency threshold eps r^2 a.a A* is below eps rr_aa (A + e_A) (1 +
 * 2^-48); not parallel to the axis when A - e_A > eps^2 |d|^2 a.a (1 +
 * 2^-48).
 */
static ALWAYS_INLINE void cyl_lanes_plain(const cylinder_prep *cp, const lane_ray *ray,
                                          cyl_plain *pl)
{
    const vd *d = ray->dir;
    const vd u = vd_set1(CYL_LANES_U);
    vd fh[3], m[3];
    for (int k = 0; k < 3; k++) {
        pl->f[k] = two_sum(ray->org[k], vd_set1(-cp->p[k]));
        fh[k] = pl->f[k].hi;
    }
    cyl_cross_axis(cp, d, pl->n);
    cyl_cross_axis(cp, fh, m);
    const vd *n = pl->n;
    vd a = vd_add(vd_add(vd_mul(n[0], n[0]), vd_mul(n[1], n[1])), vd_mul(n[2], n[2]));
    vd b = vd_add(vd_add(vd_mul(m[0], n[0]), vd_mul(m[1], n[1])), vd_mul(m[2], n[2]));
    vd c = vd_sub(vd_add(vd_add(vd_mul(m[0], m[0]), vd_mul(m[1], m[1])), vd_mul(m[2], m[2])),
                  vd_set1(cp->rr_aa_hi));
    vd t = vd_add(vd_add(vd_mul(fh[0], n[0]), vd_mul(fh[1], n[1])), vd_mul(fh[2], n[2]));
    vd d_max = lane_max_abs3(d[0], d[1], d[2]);
    cyl_bounds bd;
    cyl_bounds_make(n, a, lane_max_abs3(fh[0], fh[1], fh[2]), d_max, &bd);
    vd rr = vd_set1(cp->rr_hi);
    vd rr_a = vd_mul(rr, a), tt = vd_mul(t, t);
    vd g = vd_mul(vd_set1(cp->aa_hi), vd_sub(rr_a, tt));
    vd e_in = vd_add(vd_add(vd_mul(rr, vd_add(bd.e_a, vd_mul(vd_add(u, u), a))),
                            vd_mul(bd.e_t, vd_add(vd_add(vd_abs(t), vd_abs(t)), bd.e_t))),
                     vd_mul(vd_mul(vd_set1(6.0), u), vd_add(rr_a, tt)));
    vd e_g = vd_add(vd_mul(vd_mul(vd_set1(cp->aa_hi), e_in), vd_set1(1.0 + 0x1p-40)),
                    vd_set1(CYL_LANES_ETA));
    vd band = vd_add(vd_mul(vd_mul(vd_set1(cp->eps * (1.0 + 0x1p-48)), vd_set1(cp->rr_aa_hi)),
                            vd_add(a, bd.e_a)),
                     e_g);
    vd dd = vd_add(vd_add(vd_mul(d[0], d[0]), vd_mul(d[1], d[1])), vd_mul(d[2], d[2]));
    vm not_parallel = vd_gt(vd_sub(a, bd.e_a),
                            vd_mul(vd_mul(vd_set1(cp->eps2 * cp->aa_hi * (1.0 + 0x1p-48)), dd),
                                   vd_set1(1.0 + 0x1p-48)));
    vm ok = cp->in_range ? vm_and(lane_ray_in_range(ray, 0x1p200), not_parallel) : vm_false();
    pl->pp.cross = vm_and(ok, vd_gt(g, band));
    pl->pp.slow = vm_not(vm_or(pl->pp.cross, vm_and(ok, vd_lt(g, vd_neg(band)))));
    pl->pp.none = cp->degenerate ? vm_true() : vm_false();
    pl->pp.lo_enter = vm_true();
    pl->pp.g_low = vd_sub(g, e_g);
    pl->pp.a_up = vd_mul(vd_add(a, bd.e_a), vd_set1(1.0 + 4.0 * CYL_LANES_U));
    pl->en = bd.en;
    pl->n_sum = bd.n_sum;
    pl->a = a;
    lane_quad_starts(a, b, c, g, &pl->pp.t_lo, &pl->pp.t_hi);
}

/*
 * One certified Newton step from t0. Bounds (F = max|fh| + |t0| max|d|,
 * max|a_hi| < 1; W = sum|wh|, Lw = sum|wl|):
 *   v  = vh + vl within 8u^2 F per component (sphere_lanes.h);
 *   w  = wh + wl: the heads' products exact, their difference exact as
 *        TwoSum, the low terms (vl x a_hi, vh x a_lo, the products' errors)
 *        rounded, vl x a_lo and v's error dropped: within ew = 128u^2 F
 *        (54u^2 F counted) per component;
 *   R  = |wh + wl|^2 - r^2 a.a, as the sphere's residual: E_R <= 32u^2
 *        (|wh|^2 + rr_aa) + 16u^2 rr_aa (its own error) + 8u (2 W Lw +
 *        Lw^2) + 2.01 W ew + 3 ew^2 + u|R| + ETA;
 *   P  = wh.n: E_P <= W en + (Lw + 3 ew) |n|_1 + 4u sum|wh_k n_k| + ETA.
 * The root's v is w there ((f + t d) x a, |w| = r |a| to a few u).
 */
static ALWAYS_INLINE void cyl_lanes_refine(const void *prep, const lane_ray *ray, const void *plain,
                                           vd t0, lane_root *rt)
{
    const cylinder_prep *cp = prep;
    const cyl_plain *pl = plain;
    const vd *d = ray->dir, *n = pl->n;
    const vd u = vd_set1(CYL_LANES_U), u2 = vd_set1(CYL_LANES_U2);
    vd vh[3], vl[3], wh[3], wl[3];
    lane_offset_at(pl->f, t0, d, vh, vl);
    cyl_cross_axis_dd(cp, vh, vl, wh, wl);
    lane_sq3 sq;
    lane_sq3_minus(wh, wl, cp->rr_aa_hi, cp->rr_aa_lo, &sq);
    vd r = sq.r, w_sum = sq.v_sum, l_sum = sq.l_sum;
    vd d_max = lane_max_abs3(d[0], d[1], d[2]);
    vd big_f = vd_add(lane_max_abs3(pl->f[0].hi, pl->f[1].hi, pl->f[2].hi), vd_mul(vd_abs(t0), d_max));
    vd ew = vd_add(vd_mul(vd_mul(vd_set1(128.0), u2), big_f), vd_set1(CYL_LANES_ETA));
    vd rr_aa = vd_set1(cp->rr_aa_hi);
    vd e_r = vd_add(vd_add(sq.e, vd_mul(vd_mul(vd_set1(16.0), u2), rr_aa)),
                    vd_add(vd_mul(ew, vd_add(vd_mul(vd_set1(2.01), w_sum), vd_mul(vd_set1(3.0), ew))),
                           vd_set1(CYL_LANES_ETA)));

    vd q0 = vd_mul(wh[0], n[0]), q1 = vd_mul(wh[1], n[1]), q2 = vd_mul(wh[2], n[2]);
    vd pp = vd_add(vd_add(q0, q1), q2);
    vd e_p = vd_add(vd_add(vd_mul(w_sum, pl->en),
                           vd_mul(vd_add(l_sum, vd_mul(vd_set1(3.0), ew)), pl->n_sum)),
                    vd_add(vd_mul(vd_mul(vd_set1(4.0), u),
                                  vd_add(vd_add(vd_abs(q0), vd_abs(q1)), vd_abs(q2))),
                           vd_set1(CYL_LANES_ETA)));
    lane_newton nt;
    lane_root_newton(t0, r, e_r, pp, e_p, pl->a, pl->pp.a_up, &nt, rt);
    for (int k = 0; k < 3; k++)
        rt->v[k] = vd_add(wh[k], vd_sub(wl[k], vd_mul(nt.step, n[k])));
    /* w at the root is off by at most rho |n| + |step| (u |n| + en) + ew
     * (the root's error, the step's rounding, w's own): below u/4 of r |a| */
    vd e_n = vd_mul(vd_set1(4.0), vd_add(vd_add(vd_mul(nt.rho, pl->n_sum), ew),
                                         vd_mul(vd_abs(nt.step), vd_add(vd_mul(u, pl->n_sum), pl->en))));
    vm normal_ok = vd_le(vd_mul(e_n, e_n), vd_mul(u2, rr_aa));
    rt->ok = vm_and(nt.ok, normal_ok);
}

/* The side's outward unit normal from w at the root: a x w = -(w x a),
 * |a x w| = |a| |w| = r a.a, each component from exact products rounded
 * once (within u of itself, to first order: no cancellation costs the
 * direction anything), scaled by 1/(r a.a) and renormalised. */
static ALWAYS_INLINE void cyl_side_normal(const cylinder_prep *cp, const vd w[3], vd out[3])
{
    const vd zero[3] = { vd_zero(), vd_zero(), vd_zero() };
    vd yh[3], yl[3], radial[3];
    cyl_cross_axis_dd(cp, w, zero, yh, yl);
    for (int k = 0; k < 3; k++)
        radial[k] = vd_neg(vd_add(yh[k], yl[k]));
    lane_unit_scaled(radial, vd_set1(cp->inv_r_aa), out);
}

/* The two cap crossings: t0 at the cap at p0 (prim 1), t1 at p1 (prim 2). */
typedef struct cyl_caps {
    lane_quotient c[2];
    vm up;        /* D > 0: the cap at p0 is crossed first */
    vm ok;        /* both certified (D far from 0) */
    vm crossing;  /* and the caps not parallel to the ray by the policy */
} cyl_caps;

/*
 * F0 = f.a and D = d.a as double-doubles: the heads' dot products by
 * lane_dot3_dd (12u^2 of sum|x_k y_k|) plus the first-order terms with
 * a's and f's low parts (rounded; f_lo a_lo dropped): within 16u^2
 * sum|x_k a_k| + ETA each. F1 = F0 - (p1 - p0).a, with the prepared value
 * within 8u^2 of itself and the low parts' rounding: e_F1 = e_F0 + 16u^2
 * (|F0| + |cap|). Parallel by the policy when D^2 <= eps^2 |d|^2 a.a:
 * certainly not when (|D| - e_D)^2 > eps^2 |d|^2 a.a (1 + 2^-46).
 */
static ALWAYS_INLINE void cyl_lanes_caps(const cylinder_prep *cp, const lane_ray *ray,
                                         const cyl_plain *pl, cyl_caps *cc)
{
    const vd *d = ray->dir;
    const vd u2 = vd_set1(CYL_LANES_U2), eta = vd_set1(CYL_LANES_ETA);
    vd a0 = vd_set1(cp->a_hi[0]), a1 = vd_set1(cp->a_hi[1]), a2 = vd_set1(cp->a_hi[2]);
    vd l0 = vd_set1(cp->a_lo[0]), l1 = vd_set1(cp->a_lo[1]), l2 = vd_set1(cp->a_lo[2]);
    const vd f0 = pl->f[0].hi, f1 = pl->f[1].hi, f2 = pl->f[2].hi;

    vdd den = lane_dot3_dd(a0, a1, a2, d[0], d[1], d[2]);
    den.lo = vd_add(den.lo, vd_add(vd_add(vd_mul(l0, d[0]), vd_mul(l1, d[1])), vd_mul(l2, d[2])));
    den = dd_renorm(den);
    vd s_den = vd_add(vd_add(vd_abs(vd_mul(a0, d[0])), vd_abs(vd_mul(a1, d[1]))), vd_abs(vd_mul(a2, d[2])));
    vd e_den = vd_add(vd_mul(vd_mul(vd_set1(16.0), u2), s_den), eta);

    vdd f_a = lane_dot3_dd(a0, a1, a2, f0, f1, f2);
    vd f_lo = vd_add(vd_add(vd_mul(a0, pl->f[0].lo), vd_mul(a1, pl->f[1].lo)), vd_mul(a2, pl->f[2].lo));
    vd a_lo = vd_add(vd_add(vd_mul(l0, f0), vd_mul(l1, f1)), vd_mul(l2, f2));
    f_a.lo = vd_add(f_a.lo, vd_add(f_lo, a_lo));
    f_a = dd_renorm(f_a);
    vd s_num = vd_add(vd_add(vd_abs(vd_mul(a0, f0)), vd_abs(vd_mul(a1, f1))), vd_abs(vd_mul(a2, f2)));
    vd e_f0 = vd_add(vd_mul(vd_mul(vd_set1(16.0), u2), s_num), eta);

    vdd f_b = two_sum(f_a.hi, vd_set1(-cp->cap_hi));
    f_b.lo = vd_add(f_b.lo, vd_sub(f_a.lo, vd_set1(cp->cap_lo)));
    f_b = dd_renorm(f_b);
    vd e_f1 = vd_add(e_f0, vd_mul(vd_mul(vd_set1(16.0), u2), vd_add(vd_abs(f_a.hi), vd_set1(cp->cap_hi))));

    vd inv = vd_div(vd_set1(1.0), den.hi);
    lane_quotient_neg(f_a, e_f0, den, e_den, inv, &cc->c[0]);
    lane_quotient_neg(f_b, e_f1, den, e_den, inv, &cc->c[1]);
    cc->up = vd_gt(den.hi, vd_zero());
    vd dd = vd_add(vd_add(vd_mul(d[0], d[0]), vd_mul(d[1], d[1])), vd_mul(d[2], d[2]));
    vd lo = vd_sub(vd_abs(den.hi), vd_add(e_den, vd_mul(vd_set1(CYL_LANES_U), vd_abs(den.hi))));
    cc->ok = vm_and(vm_and(cc->c[0].ok, cc->c[1].ok), vd_gt(lo, vd_zero()));
    cc->crossing = vm_and(cc->ok, vd_gt(vd_mul(lo, lo),
                                        vd_mul(vd_mul(vd_set1(cp->eps2 * cp->aa_hi * (1.0 + 0x1p-46)), dd),
                                               vd_set1(1.0 + 0x1p-46))));
}

/* A cap crossing as a root (prim 1 at p0, 2 at p1). */
static ALWAYS_INLINE void cyl_cap_root(const lane_quotient *q, vm ok, lane_root *rt)
{
    rt->t = q->t.hi;
    rt->err = q->err;
    rt->t_dd = q->t;
    rt->rho = q->err;
    rt->ok = ok;
    rt->enter = vm_false();
    rt->v[0] = rt->v[1] = rt->v[2] = rt->vv = vd_zero();
}

/* The open cylinder's clip (lane_pair_solve): a side crossing inside the
 * slab between the cap planes (closed), certainly, or outside. */
static ALWAYS_INLINE void cyl_slab_clip(const void *data, const lane_root *rt, vm *in, vm *out)
{
    const cyl_caps *cc = data;
    const lane_quotient *first = &cc->c[0], *last = &cc->c[1];
    vd lo_t = vd_sel(cc->up, first->t.hi, last->t.hi), lo_e = vd_sel(cc->up, first->err, last->err);
    vd hi_t = vd_sel(cc->up, last->t.hi, first->t.hi), hi_e = vd_sel(cc->up, last->err, first->err);
    vd t_lo = vd_sub(rt->t, rt->err), t_hi = vd_add(rt->t, rt->err);
    *in = vm_and(cc->ok, vm_and(vd_ge(t_lo, vd_add(lo_t, lo_e)), vd_le(t_hi, vd_sub(hi_t, hi_e))));
    *out = vm_and(cc->ok, vm_or(vd_lt(t_hi, vd_sub(lo_t, lo_e)), vd_gt(t_lo, vd_add(hi_t, hi_e))));
}

/* The two reported crossings of a cylinder (entry first) and their prims. */
typedef struct cyl_lanes {
    lane_pair pr;
    lane_root root[2];
    vd prim[2];
} cyl_lanes;

/*
 * The capped solid: both side roots refined, the caps; entry = the later
 * of (side entry, first cap), exit = the earlier of (side exit, last cap),
 * each chosen where the certified intervals separate; then a crossing pair
 * (entry before exit by more than 32u |entry|: lane_roots_apart's margin)
 * or certainly none (exit before entry), else the exact path.
 */
static ALWAYS_INLINE void cyl_lanes_capped(const cylinder_prep *cp, const lane_ray *ray,
                                           const cyl_plain *pl, int first, cyl_lanes *cl)
{
    cyl_caps caps;
    cyl_lanes_caps(cp, ray, pl, &caps);
    lane_root side[2], cap[2];
    cyl_lanes_refine(cp, ray, pl, pl->pp.t_lo, &side[0]);
    cyl_lanes_refine(cp, ray, pl, pl->pp.t_hi, &side[1]);
    vm sides_ok = vm_and(vm_and(side[0].ok, side[0].enter), vm_andnot(side[1].ok, side[1].enter));
    cyl_cap_root(&caps.c[0], caps.crossing, &cap[0]);
    cyl_cap_root(&caps.c[1], caps.crossing, &cap[1]);
    lane_root cap_in, cap_out;
    lane_root_sel(caps.up, &cap[0], &cap[1], &cap_in);
    lane_root_sel(caps.up, &cap[1], &cap[0], &cap_out);
    vd prim_in = vd_sel(caps.up, vd_set1(1.0), vd_set1(2.0));
    vd prim_out = vd_sel(caps.up, vd_set1(2.0), vd_set1(1.0));

    lane_root *entry = &cl->root[0], *exit = &cl->root[1];
    vm side_later = vd_gt(vd_sub(side[0].t, side[0].err), vd_add(cap_in.t, cap_in.err));
    vm cap_later = vd_gt(vd_sub(cap_in.t, cap_in.err), vd_add(side[0].t, side[0].err));
    vm side_earlier = vd_lt(vd_add(side[1].t, side[1].err), vd_sub(cap_out.t, cap_out.err));
    vm cap_earlier = vd_lt(vd_add(cap_out.t, cap_out.err), vd_sub(side[1].t, side[1].err));
    lane_root_sel(cap_later, &cap_in, &side[0], entry);
    lane_root_sel(cap_earlier, &cap_out, &side[1], exit);
    cl->prim[0] = vd_sel(cap_later, prim_in, vd_zero());
    cl->prim[1] = vd_sel(cap_earlier, prim_out, vd_zero());
    vm known = vm_and(vm_and(pl->pp.cross, vm_and(sides_ok, caps.crossing)),
                      vm_and(vm_or(side_later, cap_later), vm_or(side_earlier, cap_earlier)));
    vd lo = vd_add(entry->t, entry->err), hi = vd_sub(exit->t, exit->err);
    vd margin = vd_mul(vd_set1(32.0 * CYL_LANES_U * (1.0 + 0x1p-40)), vd_add(vd_abs(entry->t), entry->err));
    vm hit = vm_and(known, vd_gt(vd_sub(hi, lo), margin));
    vm none_hit = vm_and(known, vd_lt(vd_add(exit->t, exit->err), vd_sub(entry->t, entry->err)));
    vm slow = vm_or(pl->pp.slow, vm_andnot(pl->pp.cross, vm_or(hit, none_hit)));

    vm e_in = lane_root_in(vm_true(), entry->t, entry->err, ray);
    vm e_out = lane_root_out(vm_true(), entry->t, entry->err, ray);
    vm e_beyond = vm_and(e_out, vd_gt(entry->t, ray->tmax));
    vm need_hi = lane_pair_need_hi(hit, e_out, e_beyond, first);
    vm x_in = lane_root_in(vm_true(), exit->t, exit->err, ray);
    vm x_out = lane_root_out(vm_true(), exit->t, exit->err, ray);
    lane_pair_decide(slow, pl->pp.none, hit, vm_true(), e_in, e_out, need_hi, x_in, x_out, &cl->pr);
    entry->t = vd_add(lane_clamp_t(entry->t, ray), vd_zero());
    exit->t = vd_add(lane_clamp_t(exit->t, ray), vd_zero());
}

/* The crossings of any kind of cylinder (cp->kind, one per batch). */
static ALWAYS_INLINE void cylinder_lanes_solve(const cylinder_prep *cp, const lane_ray *ray,
                                               int first, cyl_lanes *cl)
{
    cyl_plain pl;
    cyl_lanes_plain(cp, ray, &pl);
    cl->prim[0] = cl->prim[1] = vd_zero();
    if (cp->kind == CYL_CAPPED) {
        cyl_lanes_capped(cp, ray, &pl, first, cl);
    } else if (cp->kind == CYL_OPEN) {
        cyl_caps caps;
        cyl_lanes_caps(cp, ray, &pl, &caps);
        lane_pair_solve(cyl_lanes_refine, cp, &pl, cyl_slab_clip, &caps, &pl.pp, ray, first,
                        cl->root, &cl->pr);
    } else {
        lane_pair_solve(cyl_lanes_refine, cp, &pl, NULL, NULL, &pl.pp, ray, first, cl->root,
                        &cl->pr);
    }
}

/* The record of a crossing: the side's radial normal (prim 0) or a cap's
 * (prim 1: -unit(a), prim 2: +unit(a)); the point from t as a
 * double-double. */
static ALWAYS_INLINE void cylinder_lanes_record(const cylinder_prep *cp, const lane_ray *ray,
                                                const lane_root *rt, vd prim, vm exit, lane_hit *h)
{
    vd radial[3];
    cyl_side_normal(cp, rt->v, radial);
    vm cap = vd_gt(prim, vd_set1(0.5)), cap1 = vd_gt(prim, vd_set1(1.5));
    for (int k = 0; k < 3; k++) {
        vd a = vd_set1(cp->unit_a[k]);
        vd cap_n = vd_sel(cap1, a, vd_sub(vd_zero(), a));
        h->normal[k] = vd_add(vd_sel(cap, cap_n, radial[k]), vd_zero()); /* never -0 */
    }
    h->t = rt->t;
    lane_point_on_ray(ray, rt->t_dd, h->point);
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = prim;
    h->kind = vd_sel(exit, vd_set1((double)ISECT_EXIT), vd_set1((double)ISECT_ENTER));
}

/* The first hit in [tmin, tmax], for lanes the screen passed. */
static ALWAYS_INLINE void cylinder_lanes_first(const cylinder_prep *cp, const lane_ray *ray,
                                               lane_hit *h)
{
    cyl_lanes cl;
    cylinder_lanes_solve(cp, ray, 1, &cl);
    lane_root rt;
    vm exit = lane_pair_first(&cl.pr, cl.root, &rt, h);
    cylinder_lanes_record(cp, ray, &rt, vd_sel(exit, cl.prim[1], cl.prim[0]), exit, h);
}

#endif /* ISECT_CYLINDER_LANES_H */
