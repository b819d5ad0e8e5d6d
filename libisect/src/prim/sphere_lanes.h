/* SPDX-License-Identifier: Apache-2.0 */
/*
 * sphere_lanes.h — the sphere's fast kernel: plain arithmetic, then one
 * Newton step whose a-posteriori bound certifies the result, LANE_W rays at
 * once (prim_lanes.h states the contract; sphere.c holds the exact path it
 * defers to).
 *
 * The line o + t d meets |x - c| = r where Q(t) = |f + t d|^2 - r^2 = 0,
 * f = o - c, i.e. D t^2 + 2 B t + C = 0 with D = d.d, B = f.d, C = f.f - r^2.
 *
 * 1. Plain solve. The discriminant in the geometric form of Haines,
 *    Guenther & Akenine-Moeller ("Precision Improvements for Ray/Sphere
 *    Intersection", Ray Tracing Gems 2019), G = B^2 - D C = D r^2 - |m|^2 with
 *    m = f x d, which does not cancel for a small sphere far away; its
 *    plain value with a forward bound decides miss / crossing / maybe
 *    tangent (the last defers: the tangency rule |G| <= eps r^2 D is the
 *    exact path's). The roots, never -B + sqrt(G) with B > 0: q = -(B +
 *    sign(B) sqrt(G)), q/D and C/q. These are starting values only.
 *
 * 2. Refinement. From a start t0 the residual R = Q(t0) is evaluated
 *    accurately — v = f + t0 d with f exact (TwoSum) and t0 d exact
 *    (TwoProduct), so the cancellation of a far ray leaves v (|v| ~ r)
 *    correct to ~u^2 |f|, then |v|^2 - r^2 from exact squares — and with P =
 *    d.v = Q'(t0)/2 one Newton step gives t = t0 - R/(2P). For the quadratic,
 *    Kantorovich's bound is sharp and cheap: at x = t0 - delta, |Q(x)| <= eta
 *    = D delta^2 + E_R + 2|delta| E_P + u|R| (the step's curvature term and
 *    the errors of R and P), |Q'(x)| >= m = 2(|P| - E_P - D|delta|); if
 *    4 D eta <= m^2 there is exactly one root within 2 eta/m of x, and
 *    Q' keeps its sign there: an entry (Q' < 0, P < 0) or an exit. So each
 *    refined root comes with its error, certified, and its kind; nothing
 *    depends on how good the start was.
 *
 * The first hit refines the entry root; only when it lies certainly before
 * tmin (an origin inside the sphere, a ray spawned from it) the exit too.
 * A crossing is reported from here when its bound is at most 3.5u|t| (so t
 * is within 4 ulp of the exact crossing: ulp(t) > u|t|) and its interval
 * decision tmin <= t <= tmax holds for every value within the bound. In
 * practice the plain path defers near tangency (within ~2^-50 r^2 D, or the
 * eps band), for grazing rays and origins whose distance to the surface is
 * below ~2^-45 of |f|, parameters within an ulp or so of tmin/tmax, and
 * coordinates outside the range below.
 *
 * The normal is v at the root, v - delta d (|v| = r up to a few u), scaled
 * by 1/r and renormalised by one Newton step: no square root, no division.
 * Two divisions and one square root per ray in all (1/(q D) for both
 * starts, 1/(2P) for the step; sqrt(G)), one more division for a second
 * refinement.
 *
 * Range: |o|, |c| <= 2^200, 2^-200 <= r <= 2^200, 2^-200 <= max|d_k| <=
 * 2^200, so that no product overflows and the relative bounds hold.
 * Underflow adds at most a few 2^-1074 to any quantity: every bound has
 * ETA = 2^-960 added, so a ray whose quantities are that small defers.
 */
#ifndef ISECT_SPHERE_LANES_H
#define ISECT_SPHERE_LANES_H

#include "prim/prim_lanes.h"

#define SPHERE_LANES_U   0x1p-53
#define SPHERE_LANES_U2  0x1p-106
#define SPHERE_LANES_ETA 0x1p-960

/* The sphere's constants, prepared once per call or batch. */
typedef struct sphere_prep {
    double c[3], r, inv_r;
    double rr_hi, rr_lo; /* r^2 exactly */
    double snap_scale;   /* max|c_k| + r: the error scale of a snapped point */
    double screen_rr;    /* (1 + eps) r^2, for the screen */
    double eps;
    int    in_range;     /* |c| <= 2^200 and 2^-200 <= r <= 2^200 */
    int    degenerate;   /* r == 0: never hit */
} sphere_prep;

static inline void sphere_prepare(const double *data, double eps, sphere_prep *sp)
{
    for (int k = 0; k < 3; k++)
        sp->c[k] = data[k];
    sp->r = data[3];
    sp->inv_r = 1.0 / sp->r;
    sp->rr_hi = sp->r * sp->r;
    sp->rr_lo = product_error(sp->r, sp->r, sp->rr_hi);
    double c_max = fabs(data[0]);
    c_max = fabs(data[1]) > c_max ? fabs(data[1]) : c_max;
    c_max = fabs(data[2]) > c_max ? fabs(data[2]) : c_max;
    sp->snap_scale = c_max + sp->r;
    sp->screen_rr = (1.0 + eps) * sp->rr_hi;
    sp->eps = eps;
    sp->in_range = c_max <= 0x1p200 && sp->r >= 0x1p-200 && sp->r <= 0x1p200;
    sp->degenerate = sp->r == 0.0;
}

/*
 * The lanes that may meet the sphere: all but those that certainly miss it
 * (no crossing, no touch), decided in plain arithmetic (about half of all
 * rays in a batch miss; the batch sends only the others to the full
 * kernel). Inside the kernel's range (else: maybe).
 *
 * Numerics. M = f x d exact, X = r^2 D exact, a miss without a touch is
 * |M|^2 > (1 + eps) X. The plain m (f rounded, two products and a
 * difference per component) errs by at most 3.02u (|f_i d_j| + |f_j d_i|)
 * + 2^-1073 <= A = 2^-50 fm dm + 2^-1000 per component (fm, dm the largest
 * |f_k|, |d_k|). Requiring A <= 2^-32 max|m_k| gives |M| >= |m| (1 - 2^-30),
 * and max|m_k| >= 2^-400 keeps the plain mm = m.m normal, so |M|^2 >=
 * mm (1 - 2^-28). On the other side X <= rr dd (1 + 7u) for the rounded
 * r^2 and d.d. So mm (1 - 2^-28) > (1 + eps) rr dd (1 + 2^-26), each side
 * rounded, proves the miss.
 */
static ALWAYS_INLINE vm sphere_lanes_screen(const sphere_prep *sp, const lane_ray *ray)
{
    if (!sp->in_range)
        return vm_true();
    const vd *o = ray->org, *d = ray->dir;
    vd f0 = vd_sub(o[0], vd_set1(sp->c[0]));
    vd f1 = vd_sub(o[1], vd_set1(sp->c[1]));
    vd f2 = vd_sub(o[2], vd_set1(sp->c[2]));
    vd m0 = vd_sub(vd_mul(f1, d[2]), vd_mul(f2, d[1]));
    vd m1 = vd_sub(vd_mul(f2, d[0]), vd_mul(f0, d[2]));
    vd m2 = vd_sub(vd_mul(f0, d[1]), vd_mul(f1, d[0]));
    vd m_max = lane_max_abs3(m0, m1, m2);
    vd f_max = lane_max_abs3(f0, f1, f2);
    vd d_max = lane_max_abs3(d[0], d[1], d[2]);
    vd a = vd_add(vd_mul(vd_set1(0x1p-50), vd_mul(f_max, d_max)), vd_set1(0x1p-1000));
    vm usable = vm_and(vd_ge(m_max, vd_set1(0x1p-400)), vd_le(a, vd_mul(vd_set1(0x1p-32), m_max)));
    usable = vm_and(usable, lane_ray_in_range(ray, 0x1p200));
    vd mm = vd_add(vd_add(vd_mul(m0, m0), vd_mul(m1, m1)), vd_mul(m2, m2));
    vd dd = vd_add(vd_add(vd_mul(d[0], d[0]), vd_mul(d[1], d[1])), vd_mul(d[2], d[2]));
    vd lhs = vd_mul(mm, vd_set1(1.0 - 0x1p-28));
    vd rhs = vd_mul(vd_mul(vd_set1(sp->screen_rr), dd), vd_set1(1.0 + 0x1p-26));
    return vm_not(vm_and(usable, vd_gt(lhs, rhs)));
}

/* The plain quantities shared by the refinements (the pair's: cross, slow
 * = maybe tangent or out of range, the starts of the entry and the exit). */
typedef struct sphere_plain {
    lane_pair_plain pp;
    vdd f[3];   /* o - c exactly */
    vd  dd;     /* D = d.d, plain */
} sphere_plain;

static ALWAYS_INLINE void sphere_lanes_plain(const sphere_prep *sp, const lane_ray *ray,
                                             sphere_plain *pl)
{
    const vd *d = ray->dir;
    for (int k = 0; k < 3; k++)
        pl->f[k] = two_sum(ray->org[k], vd_set1(-sp->c[k]));
    const vd f0 = pl->f[0].hi, f1 = pl->f[1].hi, f2 = pl->f[2].hi;
    vd dd = vd_add(vd_add(vd_mul(d[0], d[0]), vd_mul(d[1], d[1])), vd_mul(d[2], d[2]));
    pl->dd = dd;
    pl->pp.a_up = vd_mul(dd, vd_set1(1.0 + 4.0 * SPHERE_LANES_U));
    vd b = vd_add(vd_add(vd_mul(f0, d[0]), vd_mul(f1, d[1])), vd_mul(f2, d[2]));
    vd m0 = vd_sub(vd_mul(f1, d[2]), vd_mul(f2, d[1]));
    vd m1 = vd_sub(vd_mul(f2, d[0]), vd_mul(f0, d[2]));
    vd m2 = vd_sub(vd_mul(f0, d[1]), vd_mul(f1, d[0]));
    vd mm = vd_add(vd_add(vd_mul(m0, m0), vd_mul(m1, m1)), vd_mul(m2, m2));
    vd rr_dd = vd_mul(vd_set1(sp->rr_hi), dd);
    vd g = vd_sub(rr_dd, mm);

    /* |G - g| <= 2^-50 (r^2 D + |m|^2) + 4 A sum|m_k| + 4 A^2 + ETA, A =
     * 2^-50 fm dm bounding each plain m_k's error (f rounded to fh included:
     * 3.02u (|f_i d_j| + |f_j d_i|) + 2u fm dm <= 6.04u fm dm). */
    vd a = vd_mul(vd_set1(0x1p-50), vd_mul(lane_max_abs3(f0, f1, f2), lane_max_abs3(d[0], d[1], d[2])));
    vd m_sum = vd_add(vd_add(vd_abs(m0), vd_abs(m1)), vd_abs(m2));
    vd e_g = vd_add(vd_add(vd_mul(vd_set1(0x1p-50), vd_add(rr_dd, mm)),
                           vd_mul(vd_set1(4.0), vd_mul(a, vd_add(m_sum, a)))),
                    vd_set1(SPHERE_LANES_ETA));
    /* Tangency band: |G| <= eps r^2 D (+ its rounding) cannot be excluded. */
    vd band = vd_add(vd_mul(vd_set1(sp->eps * (1.0 + 0x1p-50)), rr_dd), e_g);
    pl->pp.cross = vd_gt(g, band);
    vm miss = vd_lt(g, vd_neg(band));
    vm ok = sp->in_range ? lane_ray_in_range(ray, 0x1p200) : vm_false();
    pl->pp.slow = vm_not(vm_and(ok, vm_or(pl->pp.cross, miss)));
    pl->pp.none = sp->degenerate ? vm_true() : vm_false(); /* r = 0: never hit */
    pl->pp.lo_enter = vm_true();
    pl->pp.g_low = vd_sub(g, e_g);

    vd c = vd_sub(vd_add(vd_add(vd_mul(f0, f0), vd_mul(f1, f1)), vd_mul(f2, f2)),
                  vd_set1(sp->rr_hi));
    lane_quad_starts(dd, b, c, g, &pl->pp.t_lo, &pl->pp.t_hi);
}

/*
 * One certified Newton step from t0 (see the top of the file). Bounds:
 *   v    = vh + vl: vh exact sum of fh and fl(t0 d), vl = its error + fl +
 *          the product's error, rounded: |v - v_exact| <= 8u^2 F per
 *          component, F = max|fh| + |t0| max|d|;
 *   R    = sum (vh + vl)^2 - r^2: exact squares of vh, low parts rounded:
 *          E_R <= 32u^2 (|vh|^2 + r^2) + 8u (2 V L + L^2) + 28u^2 V F + u|R| + ETA,
 *          V = sum|vh_k|, L = sum|vl_k|;
 *   P    = d.vh: E_P <= 4u sum|d_k vh_k| + max|d| L (1 + 2u);
 *   step = R (1/(2P)) (two roundings);
 *   with k = (E_P + D|step|) 2/|2P| <= 1/4: m >= 1.5|P|, so the
 *   Kantorovich condition holds when 4 D eta <= 2.25 P^2, and the root is
 *   within 2 eta/m <= (8/3) eta / (2|P|) of t0 - step; the final rounding
 *   of t adds u|t|.
 */
static ALWAYS_INLINE void sphere_lanes_refine(const void *prep, const lane_ray *ray,
                                              const void *plain, vd t0, lane_root *rt)
{
    const sphere_prep *sp = prep;
    const sphere_plain *pl = plain;
    const vd *d = ray->dir;
    const vd u = vd_set1(SPHERE_LANES_U), u2 = vd_set1(SPHERE_LANES_U2);
    vd vh[3], vl[3];
    lane_offset_at(pl->f, t0, d, vh, vl);
    lane_sq3 sq;
    lane_sq3_minus(vh, vl, sp->rr_hi, sp->rr_lo, &sq);
    vd r = sq.r, l_sum = sq.l_sum;
    vd d_max = lane_max_abs3(d[0], d[1], d[2]);
    vd f_max = lane_max_abs3(pl->f[0].hi, pl->f[1].hi, pl->f[2].hi);
    vd big_f = vd_add(f_max, vd_mul(vd_abs(t0), d_max));
    vd e_r = vd_add(sq.e, vd_add(vd_mul(vd_mul(vd_set1(28.0), u2), vd_mul(sq.v_sum, big_f)),
                                 vd_set1(SPHERE_LANES_ETA)));

    vd p0 = vd_mul(d[0], vh[0]), p1 = vd_mul(d[1], vh[1]), p2 = vd_mul(d[2], vh[2]);
    vd pp = vd_add(vd_add(p0, p1), p2);
    vd e_p = vd_add(vd_mul(vd_mul(vd_set1(4.0), u), vd_add(vd_add(vd_abs(p0), vd_abs(p1)), vd_abs(p2))),
                    vd_mul(vd_set1(1.0 + 2.0 * SPHERE_LANES_U), vd_mul(d_max, l_sum)));
    lane_newton nt;
    lane_root_newton(t0, r, e_r, pp, e_p, pl->dd, pl->pp.a_up, &nt, rt);
    /* v = f + (t0 - step) d is then within rho |d| of the vector to the
     * exact hit: the normal is certified when that is below u r (a grazing
     * ray's is not: it defers). */
    vm normal_ok = vd_le(vd_mul(vd_mul(nt.rho, d_max), vd_set1(2.0)),
                         vd_set1(SPHERE_LANES_U * sp->r));
    rt->ok = vm_and(nt.ok, normal_ok);
    for (int k = 0; k < 3; k++)
        rt->v[k] = vd_sub(vd_add(vh[k], vl[k]), vd_mul(nt.step, d[k]));
}

/* The record of a crossing at t (entry or exit) with v = f + t d: the unit
 * outward normal v/|v|, the point — snapped onto the surface, c + r n,
 * where that is the more accurate placement (|c| + r below |o| + |t d|),
 * else o + t d — prim -1 and the kind. |v| = r up to a few u: v/r, made
 * unit by lane_unit_newton (no square root, no division). */
static ALWAYS_INLINE void sphere_lanes_record(const sphere_prep *sp, const lane_ray *ray, vd t,
                                              const vd v[3], vm exit, lane_hit *h)
{
    const vd *d = ray->dir;
    vd n[3];
    lane_unit_scaled(v, vd_set1(sp->inv_r), n);
    h->t = t;
    vd o_max = lane_max_abs3(ray->org[0], ray->org[1], ray->org[2]);
    vd d_max = lane_max_abs3(d[0], d[1], d[2]);
    vm snap = vd_lt(vd_set1(sp->snap_scale), vd_add(o_max, vd_mul(vd_abs(t), d_max)));
    for (int k = 0; k < 3; k++) {
        vd nk = n[k];
        h->normal[k] = nk;
        vd snapped = vd_add(vd_set1(sp->c[k]), vd_mul(vd_set1(sp->r), nk));
        vd along = vd_add(ray->org[k], vd_mul(t, d[k]));
        h->point[k] = vd_sel(snap, snapped, along);
    }
    h->uv[0] = vd_zero();
    h->uv[1] = vd_zero();
    h->prim = vd_set1(-1.0);
    h->kind = vd_sel(exit, vd_set1((double)ISECT_EXIT), vd_set1((double)ISECT_ENTER));
}

/* The crossings' verdicts (prim_lanes.h: lane_pair_solve). */
typedef struct sphere_lanes {
    lane_pair pr;
    lane_root root[2];
} sphere_lanes;

static ALWAYS_INLINE void sphere_lanes_solve(const sphere_prep *sp, const lane_ray *ray, int first,
                                             sphere_lanes *sl)
{
    sphere_plain pl;
    sphere_lanes_plain(sp, ray, &pl);
    lane_pair_solve(sphere_lanes_refine, sp, &pl, NULL, NULL, &pl.pp, ray, first, sl->root, &sl->pr);
}

/* The first hit in [tmin, tmax] (lane form of the dispatcher's first-hit
 * query for a sphere), for lanes the screen passed. */
static ALWAYS_INLINE void sphere_lanes_first(const sphere_prep *sp, const lane_ray *ray, lane_hit *h)
{
    sphere_lanes sl;
    sphere_lanes_solve(sp, ray, 1, &sl);
    lane_root rt;
    vm exit = lane_pair_first(&sl.pr, sl.root, &rt, h);
    sphere_lanes_record(sp, ray, rt.t, rt.v, exit, h);
}

#endif /* ISECT_SPHERE_LANES_H */
