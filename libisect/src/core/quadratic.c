/*
 * quadratic.c — cancellation-free roots for the quadric family; see
 * quadratic.h for what each routine promises.
 */
#include "core/quadratic.h"

#include "core/predicates.h"
#include "core/vec3.h"

#include <math.h>

int pow2_exponent_slow(double m)
{
    int e = 0;
    (void)frexp(m, &e); /* frexp(0) sets e = 0 */
    return e;
}

double sumsq_minus_sq(const double v[3], double r)
{
    comp_sum s = { 0.0, 0.0 };
    for (int k = 0; k < 3; k++)
        comp_add_product(&s, v[k], v[k]);
    comp_add_product(&s, -r, r);
    return comp_value(&s);
}


void cross_accurate(double r[3], const double x[3], const double y[3])
{
    double c0 = det2_accurate(x[1], x[2], y[1], y[2]);
    double c1 = det2_accurate(x[2], x[0], y[2], y[0]);
    double c2 = det2_accurate(x[0], x[1], y[0], y[1]);
    v3_set(r, c0, c1, c2);
}

int unit3(double out[3], const double v[3])
{
    /* per component: fmax (in max_abs3) would ignore a NaN */
    if (!(isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2])) || max_abs3(v) == 0.0) {
        v3_set(out, 0.0, 0.0, 0.0);
        return 0;
    }
    double s[3];
    scale3(s, v, pow2_exponent(max_abs3(v))); /* largest component in [0.5, 1) */
    double len = sqrt(v3_dot(s, s));
    for (int k = 0; k < 3; k++)
        out[k] = s[k] / len + 0.0; /* + 0.0: never -0.0 */
    return 1;
}

int unit3_accurate(double out[3], const double v[3])
{
    if (!unit3(out, v))
        return 0;
    /* |n|^2 = 1 + e: exact squares, compensated sum, then n (3 - |n|^2)/2
     * as n + n delta (prim_lanes.h: lane_unit_newton, the same step) */
    comp_sum nn = { 0.0, 0.0 };
    for (int k = 0; k < 3; k++)
        comp_add_product(&nn, out[k], out[k]);
    double delta = 0.5 * ((1.0 - nn.hi) - nn.lo);
    for (int k = 0; k < 3; k++)
        out[k] = (out[k] + out[k] * delta) + 0.0;
    return 1;
}

void normal_or_facing(double normal[3], const double v[3], const double d[3], int32_t kind)
{
    if (unit3(normal, v))
        return;
    unit3(normal, d);
    if (kind != ISECT_EXIT)
        for (int k = 0; k < 3; k++)
            normal[k] = 0.0 - normal[k];
}

/* x cross y with each component kept exactly as hi + lo (two exact products
 * and a compensated difference), normalised. */
static void cross_twice(comp_sum r[3], const double x[3], const double y[3])
{
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        comp_sum c = { 0.0, 0.0 };
        comp_add_product(&c, x[i], y[j]);
        comp_add_product(&c, -x[j], y[i]);
        r[k] = comp_normalized(c);
    }
}

/*
 * (r^2 |d|^2 - |m|^2) / (r^2 |d|^2) for m = f x d given as hi + lo and
 * d.d given as hi + lo: 1 - (h/r)^2, h the distance from the centre to the
 * line. Every term is split into exact products, so the difference is
 * formed to about u^2 of r^2 |d|^2, not u of it: near tangency, where the
 * two agree to many digits, the result keeps its relative accuracy.
 */
static double tangency_gap(const comp_sum m[3], double r, comp_sum dd)
{
    double rr = r * r;
    double rr_err = product_error(r, r, rr); /* = fma(r, r, -rr) */
    comp_sum g = { 0.0, 0.0 };
    comp_add_product(&g, rr, dd.hi); /* r^2 d.d, to second order */
    g.lo += rr * dd.lo + rr_err * dd.hi;
    for (int k = 0; k < 3; k++) {    /* - |m|^2, to second order */
        comp_add_product(&g, -m[k].hi, m[k].hi);
        g.lo -= 2.0 * m[k].hi * m[k].lo;
    }
    return comp_value(&g) / (rr * dd.hi);
}

/*
 * 1 when the line certainly misses by the margin that makes the full
 * computation below return no crossing, decided in plain arithmetic (about
 * half of all rays in a batch miss; they skip the compensated sums).
 * f, d, r are the scaled values of line_sphere_roots: |f| <= 2^500,
 * max|d_k| in [0.5, 1), r >= 2^-501 (so r^2 is normal).
 *
 * Numerics (u = 2^-53). M = f x d exact, X = r^2 |d|^2 exact, rho = |M|^2/X
 * = (h/r)^2. The plain cross product m (two products and a difference per
 * component) errs by at most 2.01u (|f_i d_j| + |f_j d_i|) + 2^-1073 <= A =
 * 2^-50 fm dm + 2^-1070 per component (fm, dm the largest |f_k|, |d_k|; the
 * absolute term covers subnormal products). Requiring A <= 2^-32 max|m_k|
 * gives |M| >= |m| (1 - 2^-30), and max|m_k| >= 2^-400 keeps the plain
 * mm = m.m normal, so |M|^2 >= mm (1 - 2^-28) up to a few u. On the other
 * side rr dd (rounded r^2 and d.d) gives X <= rr dd (1 + 6u). Then
 *     mm (1 - 2^-28) > (1 + eps) rr dd (1 + 2^-26)   (each side rounded)
 * implies rho >= (1 + eps)(1 + 2^-28). The full computation forms
 * delta = 1 - rho (tangency_gap) with a relative error of a few u plus
 * O(u^2)(1 + rho), so its delta is below -(eps + 2^-28 (1 + eps))(1 - 5u)
 * < -eps: neither TOUCH (|delta| <= eps) nor a crossing (delta > 0), i.e.
 * exactly the count 0 returned here. Overflow of the right side (huge eps)
 * or any NaN makes the test false and the full computation decides.
 */
static int clear_miss(const double f[3], const double d[3], double r, double eps)
{
    double m0 = f[1] * d[2] - f[2] * d[1];
    double m1 = f[2] * d[0] - f[0] * d[2];
    double m2 = f[0] * d[1] - f[1] * d[0];
    double m_max = max_abs3((const double[3]){ m0, m1, m2 });
    /* A <= 2^-32 m_max, split in two so that no subnormal constant is
     * ever an operand (a subnormal operand costs a microcode assist):
     * 2^-1070 <= 2^-33 m_max follows from m_max >= 2^-400. */
    double a = 0x1p-50 * (max_abs3(f) * max_abs3(d));
    if (!(m_max >= 0x1p-400 && a <= 0x1p-33 * m_max))
        return 0;
    double mm = m0 * m0 + m1 * m1 + m2 * m2;
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    return mm * (1.0 - 0x1p-28) > (1.0 + eps) * (r * r) * dd * (1.0 + 0x1p-26);
}

/*
 * The geometric form of Haines et al. (2019), in the line parameter t, f and
 * r scaled by one power of two (the largest of |f|, r into [0.5, 1), but r
 * not below 2^-500 so r^2 stays normal) and d by another (all exact):
 *   t_mid = -(f.d)/(d.d)    the foot of the perpendicular from the centre,
 *                           both dot products compensated;
 *   m     = f x d           |m| = h |d|, h the distance from the centre to
 *                           the line, each component exact as hi + lo;
 *   r^2 - h^2               = (r^2 |d|^2 - |m|^2)/|d|^2 by tangency_gap(),
 *                           accurate to ~u^2: the discriminant is never
 *                           b^2 - 4ac, and beyond Haines' (r - h)(r + h) it
 *                           stays accurate near tangency, where h itself
 *                           would be off by a few u;
 *   l     = d x m / (d.d)   the perpendicular vector f + t_mid d, each cross
 *                           component by Kahan's FMA algorithm: accurate to
 *                           a few u of |l| (f - (f.d/d.d) d would be good
 *                           only to u|f|, most of |l| for a small sphere
 *                           far away).
 * Tangent when |r^2 - h^2| <= eps r^2. The half chord is w = r sqrt(1 -
 * (h/r)^2)/|d|. Roots, never -b + sqrt(disc) with b > 0:
 *  - the one of larger magnitude, t_mid + sign(t_mid) w: like signs, no
 *    cancellation;
 *  - the other, t_mid - sign(t_mid) w while w <= |t_mid|/2 (the difference
 *    keeps at least half of t_mid, so at most one bit is lost: the far small
 *    sphere), else by Vieta, ((|f|^2 - r^2)/(d.d)) / (the first root), with
 *    |f|^2 - r^2 compensated: accurate when the origin is on or near the
 *    surface, where the difference would cancel.
 * The normals are l -+ w d normalised: centre-to-point vectors built from
 * the small, accurate quantities, not from the rounded t.
 */
void line_sphere_roots(const double f_in[3], const double d_in[3], double r_in, double eps,
                       line_sphere *out)
{
    out->count = 0;
    int e = pow2_exponent(fmax_nan(max_abs3(f_in), r_in));
    if (pow2_exponent(r_in) - e < -500)
        e = pow2_exponent(r_in) + 500;
    int e_dir = pow2_exponent(max_abs3(d_in));
    double f[3], d[3];
    scale3(f, f_in, e);
    scale3(d, d_in, e_dir);
    double r = pow2_scale(r_in, -e);
    if (!(r > 0.0) || !(max_abs3(f) < 0x1p500))
        return; /* a sphere below 2^-1000 of its distance: nothing to hit */
    if (clear_miss(f, d, r, eps))
        return;
    int t_shift = e - e_dir; /* f + t' d in scaled units: t = t' 2^t_shift */

    comp_sum dd_sum = { 0.0, 0.0 }, fd_sum = { 0.0, 0.0 };
    for (int k = 0; k < 3; k++) {
        comp_add_product(&dd_sum, d[k], d[k]);
        comp_add_product(&fd_sum, f[k], d[k]);
    }
    comp_sum dd = comp_normalized(dd_sum); /* in [0.25, 3] */
    double t_mid = -comp_value(&fd_sum) / dd.hi;
    comp_sum m_twice[3];
    cross_twice(m_twice, f, d);
    double m[3] = { m_twice[0].hi, m_twice[1].hi, m_twice[2].hi };
    double l[3];
    cross_accurate(l, d, m);
    v3_scale(l, l, 1.0 / dd.hi);
    double delta = tangency_gap(m_twice, r, dd); /* (r^2 - h^2) / r^2 */

    if (fabs(delta) <= eps) {
        out->count = 1;
        out->t[0] = pow2_scale(t_mid, t_shift) + 0.0; /* + 0.0: t = 0 as +0.0 */
        normal_or_facing(out->normal[0], l, d, ISECT_TOUCH);
        return;
    }
    if (!(delta > 0.0))
        return;

    double w = r * sqrt(delta) / sqrt(dd.hi);
    double w_signed = copysign(w, t_mid);
    double t_far = t_mid + w_signed;
    double t_near = w <= 0.5 * fabs(t_mid)
                  ? t_mid - w_signed
                  : (sumsq_minus_sq(f, r) / dd.hi) / t_far; /* |t_far| >= w > 0 */
    double t_lo = signbit(t_mid) ? t_far : t_near;
    double t_hi = signbit(t_mid) ? t_near : t_far;
    if (t_lo > t_hi) /* only when w is at the rounding level of t_mid */
        t_lo = t_hi = t_mid;

    double v[3];
    out->count = 2;
    out->t[0] = pow2_scale(t_lo, t_shift) + 0.0;
    v3_madd(v, l, -w, d);
    normal_or_facing(out->normal[0], v, d, ISECT_ENTER);
    out->t[1] = pow2_scale(t_hi, t_shift) + 0.0;
    v3_madd(v, l, w, d);
    normal_or_facing(out->normal[1], v, d, ISECT_EXIT);
}

/*
 * Scaled so the largest coefficient is in [0.5, 1) (the roots do not change,
 * b^2 and 4ac cannot overflow). The discriminant to second order:
 *     b^2 - 4ac = (bh^2 - 4 ah ch) + 2 bh bl - 4 (ah cl + al ch) + O(u^2 b^2),
 * the first part by det2_accurate (Kahan's FMA algorithm, relative error
 * <= 2u whatever the cancellation), the first-order correction from the low
 * parts plainly (its own rounding is second order). Near tangency, where
 * b^2 and 4ac agree to many digits, this is what keeps the discriminant,
 * hence the TOUCH decision and the roots, accurate: rounding c to one double
 * alone would cost an error of u c in it. Roots by
 * q = -(b + sign(b) sqrt(disc)) / 2, t = q/a and c/q: no cancellation.
 */
void quadratic_roots(comp_sum a, comp_sum b, comp_sum c, double eps, quad_roots *out)
{
    a = comp_normalized(a);
    b = comp_normalized(b);
    c = comp_normalized(c);
    int e = pow2_exponent(fmax_nan(fabs(a.hi), fmax_nan(fabs(b.hi), fabs(c.hi))));
    double ah = pow2_scale(a.hi, -e), al = pow2_scale(a.lo, -e);
    double bh = pow2_scale(b.hi, -e), bl = pow2_scale(b.lo, -e);
    double ch = pow2_scale(c.hi, -e), cl = pow2_scale(c.lo, -e);
    double disc = det2_accurate(bh, 4.0 * ah, ch, bh)
                + (2.0 * bh * bl - 4.0 * (ah * cl + al * ch));
    if (fabs(disc) <= eps * (bh * bh + 4.0 * fabs(ah * ch))) {
        out->count = 1;
        out->t[0] = -bh / (2.0 * ah) + 0.0;
        return;
    }
    if (!(disc > 0.0)) {
        out->count = 0;
        return;
    }
    double q = -0.5 * (bh + copysign(sqrt(disc), bh));
    double t1 = q / ah + 0.0;
    double t2 = q != 0.0 ? ch / q + 0.0 : t1; /* q == 0 needs b == disc == 0 */
    out->count = 2;
    out->t[0] = fmin(t1, t2);
    out->t[1] = fmax(t1, t2);
}
