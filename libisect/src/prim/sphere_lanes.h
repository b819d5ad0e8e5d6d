/*
 * sphere_lanes.h — the sphere's fast kernel: a plain double-double
 * evaluation with a forward error bound, LANE_W rays at once (see
 * prim_lanes.h for the contract, sphere.c for the exact path it defers to).
 *
 * The line o + t d meets |x - c| = r where
 *     D t^2 + 2 B t + C = 0,   D = d.d,  B = f.d,  C = f.f - r^2,  f = o - c,
 * with the discriminant in the geometric form of Haines, Guenther &
 * Akenine-Moeller ("Precision Improvements for Ray/Sphere Intersection",
 * Ray Tracing Gems 2019), by Lagrange's identity
 *     G = B^2 - D C = D r^2 - |m|^2,   m = f x d,   G = D (r^2 - h^2),
 * h the distance from the centre to the line. G does not cancel for a
 * small sphere far away (B^2 and D C agree to as many digits as the
 * distance is large), only near tangency. The roots, never -B + sqrt(G)
 * with B > 0:
 *     q = -(B + sign(B) sqrt(G)),   t1 = q / D,   t2 = C / q   (Vieta),
 * and the crossing normals (f + t d)/r = (l -+ w d)/r from the foot of the
 * perpendicular l = (d x m)/D and the half chord w = sqrt(G)/D, both small
 * and accurate where f + t d would cancel.
 *
 * Numerics (u = 2^-53). f is exact as hi + lo (TwoSum); D, B, C, m, |m|^2
 * and G are dd values built from exact products (TwoProduct) and
 * compensated sums, each with a bound E_X on its error:
 *     E_D <= 16u^2 D,  E_B <= 40u^2 SB,  E_C <= 80u^2 (|f|^2 + r^2),
 *     E_m_k <= 16u^2 Sm_k,  E_G <= 40u^2 (r^2 D) + 48u^2 |m|^2 + 40u^2 sum |m_k| Sm_k,
 * SB = sum |f_k d_k| and Sm_k = |f_i d_j| + |f_j d_i| the magnitudes that
 * can cancel (the constants carry a factor ~2 of slack over the
 * term-by-term count in the comments below). Underflow can add at most a
 * few 2^-1074 to any of them: every bound has ETA = 2^-960 added, so a
 * kernel whose quantities are that small always defers.
 *   sqrt(G) = s + (G - s^2)/(2s), s = fl(sqrt(G.hi)): error <= E_G/(2s) +
 *             4u^2 s;
 *   q       dd, error <= E_B + E_S + 8u^2 |q| (B and sign(B) sqrt(G) do not
 *             cancel);
 *   t1, t2  dd_mul_inv: |t - exact| <= |t| (u + 24u^2) + propagated
 *             (E_q |t| + E_D |t| or E_C)/(|q| or D).
 * Four divisions in all (1/D, 1/sqrt(G), 1/q, 1/|normal|), every other
 * quotient a product by one of them.
 * A crossing is reported from here only when that bound is at most 3.5u|t|
 * (so t is within 4 ulp of the exact crossing: ulp(t) > u|t|) and its
 * interval decision tmin <= t <= tmax holds for every value within the
 * bound; the tangency rule |G| <= eps r^2 D (sphere.c) likewise only when
 * |G| is certainly on one side of eps r^2 D. In practice the plain path
 * defers for tangency within ~2^-45 of the threshold, origins within ~2^-45
 * relative of the surface or of a parameter within ~2^-50 of tmin/tmax, and
 * coordinates outside the range below.
 *
 * Range: |o|, |c| <= 2^200, 2^-200 <= r <= 2^200, 2^-200 <= max|d_k| <=
 * 2^200, so that no product overflows and the relative bounds hold.
 */
#ifndef ISECT_SPHERE_LANES_H
#define ISECT_SPHERE_LANES_H

#include "prim/prim_lanes.h"

#define SPHERE_LANES_U   0x1p-53
#define SPHERE_LANES_U2  0x1p-106
#define SPHERE_LANES_ETA 0x1p-960

/* The sphere's constants, prepared once per call or batch. */
typedef struct sphere_prep {
    double c[3], r;
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

static ALWAYS_INLINE vd max_abs3v(vd a, vd b, vd c)
{
    return vd_max(vd_abs(a), vd_max(vd_abs(b), vd_abs(c)));
}

/* The kernel's range for the ray (see the top of the file). */
static ALWAYS_INLINE vm sphere_ray_in_range(const lane_ray *ray)
{
    vd o_max = max_abs3v(ray->org[0], ray->org[1], ray->org[2]);
    vd d_max = max_abs3v(ray->dir[0], ray->dir[1], ray->dir[2]);
    return vm_and(vd_le(o_max, vd_set1(0x1p200)),
                  vm_and(vd_ge(d_max, vd_set1(0x1p-200)), vd_le(d_max, vd_set1(0x1p200))));
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
    vd m_max = max_abs3v(m0, m1, m2);
    vd f_max = max_abs3v(f0, f1, f2);
    vd d_max = max_abs3v(d[0], d[1], d[2]);
    vd a = vd_add(vd_mul(vd_set1(0x1p-50), vd_mul(f_max, d_max)), vd_set1(0x1p-1000));
    vm usable = vm_and(vd_ge(m_max, vd_set1(0x1p-400)), vd_le(a, vd_mul(vd_set1(0x1p-32), m_max)));
    usable = vm_and(usable, sphere_ray_in_range(ray));
    vd mm = vd_add(vd_add(vd_mul(m0, m0), vd_mul(m1, m1)), vd_mul(m2, m2));
    vd dd = vd_add(vd_add(vd_mul(d[0], d[0]), vd_mul(d[1], d[1])), vd_mul(d[2], d[2]));
    vd lhs = vd_mul(mm, vd_set1(1.0 - 0x1p-28));
    vd rhs = vd_mul(vd_mul(vd_set1(sp->screen_rr), dd), vd_set1(1.0 + 0x1p-26));
    return vm_not(vm_and(usable, vd_gt(lhs, rhs)));
}

/* What the plain evaluation found for LANE_W rays. */
typedef struct sphere_lanes {
    vm  slow;      /* undecided: the exact path decides */
    vm  touch;     /* one tangent contact at t[0] */
    vm  in[2];     /* crossing i lies in [tmin, tmax] (decided) */
    vd  t[2];      /* entry t[0] <= exit t[1] (or the touch at t[0]), clamped */
    vd  l[3], w;   /* the foot of the perpendicular and the half chord */
} sphere_lanes;

/* x0 y0 + x1 y1 + x2 y2 as dd: exact products, compensated sum; |error|
 * <= 12u^2 sum |x_k y_k| (before the caller's own low-order terms). */
static ALWAYS_INLINE vdd dot3_dd(vd x0, vd x1, vd x2, vd y0, vd y1, vd y2)
{
    vdd p0 = two_prod(x0, y0), p1 = two_prod(x1, y1), p2 = two_prod(x2, y2);
    vdd s = two_sum(p0.hi, p1.hi);
    vdd s2 = two_sum(s.hi, p2.hi);
    s2.lo = vd_add(vd_add(s.lo, s2.lo), vd_add(vd_add(p0.lo, p1.lo), p2.lo));
    return s2;
}

/* One component a_i b_j - a_j b_i of a x b for a = ah + al exact (al the
 * low parts, multiplied plainly) and b double, renormalised (|lo| <= u|hi|),
 * with |error| <= 16u^2 (|ah_i b_j| + |ah_j b_i|), that magnitude in *mag. */
static ALWAYS_INLINE vdd cross_comp_dd(vd ah_i, vd al_i, vd ah_j, vd al_j, vd b_i, vd b_j, vd *mag)
{
    vdd x = two_prod(ah_i, b_j), y = two_prod(ah_j, b_i);
    vdd s = two_sum(x.hi, vd_neg(y.hi));
    vd lo = vd_add(vd_add(s.lo, vd_sub(x.lo, y.lo)), vd_sub(vd_mul(al_i, b_j), vd_mul(al_j, b_i)));
    *mag = vd_add(vd_abs(x.hi), vd_abs(y.hi));
    return two_sum(s.hi, lo);
}

/* One component (d x m)_k = d_i m_j - d_j m_i of the perpendicular's
 * direction, compensated: accurate to about u of its value. */
static ALWAYS_INLINE vd cross_comp_acc(vd d_i, vd d_j, vdd m_i, vdd m_j)
{
    vdd x = two_prod(d_i, m_j.hi), y = two_prod(d_j, m_i.hi);
    return vd_add(vd_sub(x.hi, y.hi),
                  vd_add(vd_sub(x.lo, y.lo), vd_sub(vd_mul(d_i, m_j.lo), vd_mul(d_j, m_i.lo))));
}

static ALWAYS_INLINE void sphere_lanes_solve(const sphere_prep *sp, const lane_ray *ray,
                                             sphere_lanes *out)
{
    const vd u2 = vd_set1(SPHERE_LANES_U2), eta = vd_set1(SPHERE_LANES_ETA);
    vm ok = sp->in_range ? sphere_ray_in_range(ray) : vm_false();

    /* f = o - c exactly (fh + fl). */
    vdd f0 = two_sum(ray->org[0], vd_set1(-sp->c[0]));
    vdd f1 = two_sum(ray->org[1], vd_set1(-sp->c[1]));
    vdd f2 = two_sum(ray->org[2], vd_set1(-sp->c[2]));
    const vd d0 = ray->dir[0], d1 = ray->dir[1], d2 = ray->dir[2];

    /* D = d.d: three exact squares summed; 5 low terms of total <= 3.01u D,
     * summed with error <= 4.01u of that. */
    vdd dd = dd_renorm(dot3_dd(d0, d1, d2, d0, d1, d2));
    vd e_d = vd_add(vd_mul(vd_set1(16.0), vd_mul(u2, dd.hi)), eta);

    /* B = f.d = fh.d + fl.d; the fl.d terms (<= u SB) rounded plainly. */
    vdd b = dot3_dd(f0.hi, f1.hi, f2.hi, d0, d1, d2);
    b.lo = vd_add(b.lo, vd_add(vd_add(vd_mul(f0.lo, d0), vd_mul(f1.lo, d1)), vd_mul(f2.lo, d2)));
    b = dd_renorm(b);
    vd sb = vd_add(vd_add(vd_abs(vd_mul(f0.hi, d0)), vd_abs(vd_mul(f1.hi, d1))),
                   vd_abs(vd_mul(f2.hi, d2)));
    vd e_b = vd_add(vd_mul(vd_set1(40.0), vd_mul(u2, sb)), eta);

    /* C = |f|^2 - r^2 = fh.fh + 2 fh.fl - r^2 (+ fl.fl <= u^2 |f|^2, in the
     * bound). */
    vdd ff = dot3_dd(f0.hi, f1.hi, f2.hi, f0.hi, f1.hi, f2.hi);
    vdd c = two_sum(ff.hi, vd_set1(-sp->rr_hi));
    vd cross_terms = vd_add(vd_add(vd_mul(f0.hi, f0.lo), vd_mul(f1.hi, f1.lo)), vd_mul(f2.hi, f2.lo));
    c.lo = vd_add(vd_add(c.lo, vd_sub(ff.lo, vd_set1(sp->rr_lo))), vd_add(cross_terms, cross_terms));
    c = dd_renorm(c);
    vd sc = vd_add(ff.hi, vd_set1(sp->rr_hi));
    vd e_c = vd_add(vd_mul(vd_set1(80.0), vd_mul(u2, sc)), eta);

    /* m = f x d, each component dd (cross_comp_dd). */
    vd sm0, sm1, sm2;
    vdd m0 = cross_comp_dd(f1.hi, f1.lo, f2.hi, f2.lo, d1, d2, &sm0);
    vdd m1 = cross_comp_dd(f2.hi, f2.lo, f0.hi, f0.lo, d2, d0, &sm1);
    vdd m2 = cross_comp_dd(f0.hi, f0.lo, f1.hi, f1.lo, d0, d1, &sm2);

    /* |m|^2 = mh.mh + 2 mh.ml, and G = r^2 D - |m|^2 (r^2 D = rr * dd to
     * second order). */
    vdd mm = dot3_dd(m0.hi, m1.hi, m2.hi, m0.hi, m1.hi, m2.hi);
    vd mcross = vd_add(vd_add(vd_mul(m0.hi, m0.lo), vd_mul(m1.hi, m1.lo)), vd_mul(m2.hi, m2.lo));
    mm.lo = vd_add(mm.lo, vd_add(mcross, mcross));
    vdd z = two_prod(vd_set1(sp->rr_hi), dd.hi);
    z.lo = vd_add(z.lo, vd_add(vd_mul(vd_set1(sp->rr_hi), dd.lo), vd_mul(vd_set1(sp->rr_lo), dd.hi)));
    vdd g = two_sum(z.hi, vd_neg(mm.hi));
    g.lo = vd_add(g.lo, vd_sub(z.lo, mm.lo));
    g = dd_renorm(g);
    vd msm = vd_add(vd_add(vd_mul(vd_abs(m0.hi), sm0), vd_mul(vd_abs(m1.hi), sm1)),
                    vd_mul(vd_abs(m2.hi), sm2));
    vd e_g = vd_add(vd_mul(u2, vd_add(vd_add(vd_mul(vd_set1(40.0), z.hi), vd_mul(vd_set1(48.0), mm.hi)),
                                      vd_mul(vd_set1(40.0), msm))),
                    eta);
    e_g = vd_add(e_g, vd_mul(vd_set1(SPHERE_LANES_U), vd_abs(g.hi))); /* comparisons use g.hi alone */

    /* Tangency: TOUCH iff |G| <= eps r^2 D; T = fl(eps fl(rr dd)) is within
     * 4u relative of eps r^2 D (and ETA absolute). */
    vd thr = vd_mul(vd_set1(sp->eps), z.hi);
    vd thr_lo = vd_sub(vd_mul(thr, vd_set1(1.0 - 4.0 * SPHERE_LANES_U)), eta);
    vd thr_hi = vd_add(vd_mul(thr, vd_set1(1.0 + 4.0 * SPHERE_LANES_U)), eta);
    vd g_abs = vd_abs(g.hi);
    vm touch = vd_le(vd_add(g_abs, e_g), thr_lo);
    vm apart = vd_gt(vd_sub(g_abs, e_g), thr_hi);
    vm undecided = vm_not(vm_or(touch, apart));
    vm cross = vm_and(apart, vd_gt(g.hi, vd_zero()));

    /* Two crossings (lanes without a crossing compute garbage that is
     * masked below; sqrt of a negative gives NaN, harmlessly). Three
     * reciprocals serve every quotient: 1/D, 1/s, 1/q (dd_mul_inv); a
     * bound multiplied by a reciprocal is rounded up by (1 + 8u). */
    const vd up = vd_set1(1.0 + 8.0 * SPHERE_LANES_U);
    vd inv_d = vd_div(vd_set1(1.0), dd.hi);
    vd s = vd_sqrt(g.hi);
    vd inv_s = vd_div(vd_set1(1.0), s);
    vdd s2 = two_prod(s, s);
    vd s_corr = vd_mul(vd_add(vd_sub(vd_sub(g.hi, s2.hi), s2.lo), g.lo), vd_mul(vd_set1(0.5), inv_s));
    vd e_s = vd_add(vd_mul(vd_mul(e_g, inv_s), up), vd_mul(vd_set1(4.0), vd_mul(u2, s)));
    vd sigma = vd_sel(vd_lt(b.hi, vd_zero()), vd_set1(-1.0), vd_set1(1.0));
    vdd q = two_sum(b.hi, vd_mul(sigma, s));
    q.hi = vd_neg(q.hi);
    q.lo = vd_neg(vd_add(q.lo, vd_add(b.lo, vd_mul(sigma, s_corr))));
    q = dd_renorm(q);
    vd q_abs = vd_abs(q.hi);
    vd inv_q = vd_div(vd_set1(1.0), q.hi);
    vd inv_q_abs = vd_mul(vd_abs(inv_q), up);
    vd inv_d_up = vd_mul(inv_d, up);
    vd rel_q = vd_mul(vd_add(vd_add(e_b, e_s), vd_mul(vd_set1(8.0), vd_mul(u2, q_abs))), inv_q_abs);
    vd rel_d = vd_mul(e_d, inv_d_up);
    vd t1 = dd_mul_inv(q, dd, inv_d);
    vd t2 = dd_mul_inv(c, q, inv_q);
    vd round = vd_set1(SPHERE_LANES_U + 24.0 * SPHERE_LANES_U2);
    vd e_t1 = vd_mul(vd_mul(vd_abs(t1), vd_add(round, vd_add(rel_q, rel_d))), up);
    vd e_t2 = vd_mul(vd_add(vd_mul(vd_abs(t2), vd_add(round, rel_q)), vd_mul(e_c, inv_q_abs)), up);

    /* t1 = (-B - sigma sqrt G)/D is the entry when sigma = +1. */
    vm t1_first = vd_gt(sigma, vd_zero());
    vd t_lo = vd_sel(t1_first, t1, t2), t_hi = vd_sel(t1_first, t2, t1);
    vd e_lo = vd_sel(t1_first, e_t1, e_t2), e_hi = vd_sel(t1_first, e_t2, e_t1);

    /* One tangent contact at t_mid = -B/D. */
    vdd minus_b = { vd_neg(b.hi), vd_neg(b.lo) };
    vd t_mid = dd_mul_inv(minus_b, dd, inv_d);
    vd e_mid = vd_mul(vd_add(vd_mul(vd_abs(t_mid), vd_add(round, rel_d)), vd_mul(e_b, inv_d_up)), up);
    t_lo = vd_sel(touch, t_mid, t_lo);
    e_lo = vd_sel(touch, e_mid, e_lo);

    /* Per crossing: certainly in range and within 3.5u|t|, or certainly out
     * of range (then its accuracy does not matter); else undecided. */
    vd budget = vd_set1(3.5 * SPHERE_LANES_U);
    vm in_lo = vm_and(lane_certainly_in(t_lo, e_lo, ray), vd_le(e_lo, vd_mul(budget, vd_abs(t_lo))));
    vm in_hi = vm_and(lane_certainly_in(t_hi, e_hi, ray), vd_le(e_hi, vd_mul(budget, vd_abs(t_hi))));
    vm out_lo = lane_certainly_out(t_lo, e_lo, ray);
    vm out_hi = lane_certainly_out(t_hi, e_hi, ray);
    vm lo_ok = vm_or(in_lo, out_lo);
    vm hi_ok = vm_or(in_hi, vm_or(out_hi, touch)); /* a touch has one parameter */
    vm has = vm_or(cross, touch);
    vm decided = vm_and(vm_not(undecided), vm_or(vm_not(has), vm_and(lo_ok, hi_ok)));

    if (sp->degenerate) { /* never hit: decided, no crossing */
        out->slow = out->touch = out->in[0] = out->in[1] = vm_false();
    } else {
        out->slow = vm_not(vm_and(ok, decided));
        out->touch = touch;
        out->in[0] = vm_and(has, in_lo);
        out->in[1] = vm_and(cross, in_hi);
    }

    /* Rounding can put an entry an ulp above its exit when w is below the
     * rounding of t: report both at the smaller value. */
    t_lo = vd_sel(cross, vd_min(t_lo, t_hi), t_lo);
    out->t[0] = vd_add(lane_clamp_t(t_lo, ray), vd_zero());
    out->t[1] = vd_add(lane_clamp_t(t_hi, ray), vd_zero());

    /* l = (d x m)/D, each component compensated, and w = sqrt(G)/D. */
    out->l[0] = vd_mul(cross_comp_acc(d1, d2, m1, m2), inv_d);
    out->l[1] = vd_mul(cross_comp_acc(d2, d0, m2, m0), inv_d);
    out->l[2] = vd_mul(cross_comp_acc(d0, d1, m0, m1), inv_d);
    vdd sqrt_g = { s, s_corr };
    out->w = dd_mul_inv(sqrt_g, dd, inv_d);
}

/* The record of crossing `which` (0: entry or touch, 1: exit) of lanes
 * where sl says it is in range: t, the unit outward normal (l -+ w d)/|..|
 * (l/|l| for a touch), the point — snapped onto the surface, c + r n,
 * where that is the more accurate placement (|c| + r below |o| + |t d|),
 * else o + t d; a touch keeps the foot of the perpendicular, o + t d —
 * prim -1 and the kind. */
static ALWAYS_INLINE void sphere_lanes_record(const sphere_prep *sp, const lane_ray *ray,
                                              const sphere_lanes *sl, vm which_exit, lane_hit *h)
{
    const vd *d = ray->dir;
    /* w is garbage (NaN) in a touching lane: selected away, not multiplied */
    vd ws = vd_sel(which_exit, sl->w, vd_neg(sl->w));
    ws = vd_sel(sl->touch, vd_zero(), ws);
    vd v0 = vd_add(sl->l[0], vd_mul(ws, d[0]));
    vd v1 = vd_add(sl->l[1], vd_mul(ws, d[1]));
    vd v2 = vd_add(sl->l[2], vd_mul(ws, d[2]));
    vd inv_len = vd_div(vd_set1(1.0),
                        vd_sqrt(vd_add(vd_add(vd_mul(v0, v0), vd_mul(v1, v1)), vd_mul(v2, v2))));
    vd t = vd_sel(which_exit, sl->t[1], sl->t[0]);
    h->t = t;
    vd o_max = max_abs3v(ray->org[0], ray->org[1], ray->org[2]);
    vd d_max = max_abs3v(d[0], d[1], d[2]);
    vd ray_scale = vd_add(o_max, vd_mul(vd_abs(t), d_max));
    vm snap = vm_andnot(vd_lt(vd_set1(sp->snap_scale), ray_scale), sl->touch);
    const vd v[3] = { v0, v1, v2 };
    for (int k = 0; k < 3; k++) {
        vd n = vd_add(vd_mul(v[k], inv_len), vd_zero()); /* + 0: never -0 */
        h->normal[k] = n;
        vd snapped = vd_add(vd_set1(sp->c[k]), vd_mul(vd_set1(sp->r), n));
        vd along = vd_add(ray->org[k], vd_mul(t, d[k]));
        h->point[k] = vd_sel(snap, snapped, along);
    }
    h->uv[0] = vd_zero();
    h->uv[1] = vd_zero();
    h->prim = vd_set1(-1.0);
    h->kind = vd_sel(sl->touch, vd_set1((double)ISECT_TOUCH),
                     vd_sel(which_exit, vd_set1((double)ISECT_EXIT), vd_set1((double)ISECT_ENTER)));
}

/* The first hit in [tmin, tmax] (lane form of the dispatcher's first-hit
 * query for a sphere), for lanes the screen passed. */
static ALWAYS_INLINE void sphere_lanes_first(const sphere_prep *sp, const lane_ray *ray, lane_hit *h)
{
    sphere_lanes sl;
    sphere_lanes_solve(sp, ray, &sl);
    vm exit_first = vm_andnot(sl.in[1], sl.in[0]);
    sphere_lanes_record(sp, ray, &sl, exit_first, h);
    h->found = vm_andnot(vm_or(sl.in[0], sl.in[1]), sl.slow);
    h->slow = sl.slow;
}

#endif /* ISECT_SPHERE_LANES_H */
