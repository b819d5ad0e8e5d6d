/*
 * quadratic.c — cancellation-free roots for the quadric family; see
 * quadratic.h for what each routine promises.
 */
#include "quadratic.h"

#include "predicates.h"
#include "vec3.h"

#include <math.h>

int pow2_exponent(double m)
{
    int e = 0;
    (void)frexp(m, &e); /* frexp(0) sets e = 0 */
    return e;
}

double max_abs3(const double v[3])
{
    return fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
}

void scale3(double out[3], const double v[3], int e)
{
    for (int k = 0; k < 3; k++)
        out[k] = ldexp(v[k], -e);
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
    double rr_err = fma(r, r, -rr);
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
    int e = pow2_exponent(fmax(max_abs3(f_in), r_in));
    if (pow2_exponent(r_in) - e < -500)
        e = pow2_exponent(r_in) + 500;
    int e_dir = pow2_exponent(max_abs3(d_in));
    double f[3], d[3];
    scale3(f, f_in, e);
    scale3(d, d_in, e_dir);
    double r = ldexp(r_in, -e);
    if (!(r > 0.0) || !(max_abs3(f) < 0x1p500))
        return; /* a sphere below 2^-1000 of its distance: nothing to hit */
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
        out->t[0] = ldexp(t_mid, t_shift) + 0.0; /* + 0.0: t = 0 as +0.0 */
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
    out->t[0] = ldexp(t_lo, t_shift) + 0.0;
    v3_madd(v, l, -w, d);
    normal_or_facing(out->normal[0], v, d, ISECT_ENTER);
    out->t[1] = ldexp(t_hi, t_shift) + 0.0;
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
    int e = pow2_exponent(fmax(fabs(a.hi), fmax(fabs(b.hi), fabs(c.hi))));
    double ah = ldexp(a.hi, -e), al = ldexp(a.lo, -e);
    double bh = ldexp(b.hi, -e), bl = ldexp(b.lo, -e);
    double ch = ldexp(c.hi, -e), cl = ldexp(c.lo, -e);
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
