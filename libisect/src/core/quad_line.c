/*
 * quad_line.c — a line's crossings with a quadric surface: certified from
 * double-doubles, or exact (see quad_line.h).
 */
#include "core/quad_line.h"
#include "core/eft.h"
#include "core/ratio.h"

#include <math.h>

#define U 0x1p-53

/* ------------------------------------------------------------ certified */

/* Where the exact t (within err of t_hi) lies against tau: +1 above, -1
 * below, 0 equal (err == 0 only), 2 not certain. t_hi - tau is formed
 * exactly (TwoSum) so that an err of 0 decides by its sign alone. */
static int side_certain(double t_hi, double err, double tau)
{
    if (isinf(tau))
        return tau < 0.0 ? 1 : -1;
    vdd d = two_sum(t_hi, -tau);
    if (err == 0.0)
        return (d.hi > 0.0) - (d.hi < 0.0);
    /* |d| >= |d.hi| (1 - u): the margin must clear err by that much */
    if (fabs(d.hi) * (1.0 - 2.0 * U) > err)
        return d.hi > 0.0 ? 1 : -1;
    return 2;
}

/* x / y for dd x, y with absolute errors ex, ey (ey < |y|/8): the quotient
 * as a dd and a bound on its distance from the exact quotient. */
static double quotient_bound(vdd x, double ex, vdd y, double ey, vdd *out)
{
    double inv = 1.0 / y.hi;
    *out = dd_mul_inv_dd(x, y, inv);
    double t_abs = fabs(out->hi) + fabs(out->lo);
    double denom = (fabs(y.hi) - fabs(y.lo)) * (1.0 - 2.0 * U) - ey;
    /* |x/y - x'/y'| <= (ex + |x'/y'| ey) / |y| (first order exact: the
     * derivative bound on [y' - ey, y' + ey]), plus dd_mul_inv_dd's own
     * 21u^2 relative error */
    return ((ex + t_abs * ey) / denom + 32.0 * U * U * t_abs) * (1.0 + 8.0 * U);
}

int quad_line_certify(const quad_line_dd *q, double tmin, double tmax, quad_line_roots *out)
{
    out->count = 0;
    out->touch = 0;
    /* A must be certainly away from the linear threshold (and from 0) */
    double a_abs = fabs(q->a) - fabs(q->a_lo);
    if (!(a_abs * (1.0 - 2.0 * U) > 8.0 * q->a_err + q->l_thr))
        return 0;
    double g_lo_bound = (q->g - fabs(q->g_lo)) * (1.0 - 2.0 * U) - q->g_err;
    double g_hi_bound = (q->g + fabs(q->g_lo)) * (1.0 + 2.0 * U) + q->g_err;
    if (g_hi_bound < -q->t_thr)
        return 1; /* G < -T: the line misses */
    if (!(g_lo_bound > q->t_thr))
        return 0; /* a touch, or too close to tell */

    /* sqrt(G) as a dd: |sqrt(G) - sqrt(G')| <= |G - G'| / sqrt(G') */
    double s = sqrt(q->g);
    vdd s2 = two_prod(s, s);
    vdd root = { s, (((q->g - s2.hi) - s2.lo) + q->g_lo) / (s + s) };
    root = dd_renorm(root);
    double root_err = q->g_err / sqrt(g_lo_bound) + 4.0 * U * U * s;

    /* q = -(B + sigma sqrt(G)): the two terms share a sign, so
     * |q| >= sqrt(G) and the sum is as accurate as its parts */
    double sigma = q->b < 0.0 ? -1.0 : 1.0;
    vdd sum = two_sum(q->b, sigma * root.hi);
    vdd qq = dd_renorm((vdd){ -sum.hi, -(sum.lo + (q->b_lo + sigma * root.lo)) });
    double q_err = (q->b_err + root_err) * (1.0 + 4.0 * U) + 4.0 * U * U * fabs(qq.hi);
    if (!(q_err < fabs(qq.hi) / 8.0))
        return 0;

    vdd a = { q->a, q->a_lo }, c = { q->c, q->c_lo };
    vdd t_q_a, t_c_q;
    double e_q_a = quotient_bound(qq, q_err, a, q->a_err, &t_q_a);
    double e_c_q = quotient_bound(c, q->c_err, qq, q_err, &t_c_q);
    /* q/A is r- for sigma = +1, r+ for sigma = -1; C/q the other */
    vdd r_minus = sigma > 0.0 ? t_q_a : t_c_q, r_plus = sigma > 0.0 ? t_c_q : t_q_a;
    double e_minus = sigma > 0.0 ? e_q_a : e_c_q, e_plus = sigma > 0.0 ? e_c_q : e_q_a;
    int a_pos = q->a > 0.0;
    vdd r[2] = { a_pos ? r_minus : r_plus, a_pos ? r_plus : r_minus };
    double e[2] = { a_pos ? e_minus : e_plus, a_pos ? e_plus : e_minus };
    for (int i = 0; i < 2; i++) {
        /* the reported t_hi within 1.5 ulp: |t_lo| <= ulp/2, e <= ulp */
        double err = e[i] + fabs(r[i].lo);
        if (!(e[i] == 0.0 || e[i] <= 0x1p-53 * fabs(r[i].hi)))
            return 0;
        int lo = side_certain(r[i].hi, err, tmin), hi = side_certain(r[i].hi, err, tmax);
        if (lo == 2 || hi == 2)
            return 0;
        out->t_hi[i] = r[i].hi;
        out->t_lo[i] = r[i].lo;
        out->in[i] = lo >= 0 && hi <= 0;
        out->enter[i] = a_pos ? i == 0 : i == 1;
    }
    out->count = 2;
    return 1;
}

/* ---------------------------------------------------------------- exact */

/* sign(tau - r) for the root r = (-B + pm sqrt(G))/A, pm = -1 (r-) or +1
 * (r+), G > 0, from the signs of s = A tau + B and Q(tau) (quad_line.h). */
static int root_side(const xp *a, const xp *b, const xp *c, int a_sign, double tau, int pm)
{
    if (isinf(tau))
        return tau < 0.0 ? -1 : 1;
    xp s, qt;
    xp_scale(&s, a, tau);
    xp_add(&s, &s, b);            /* s = A tau + B */
    xp_add(&qt, &s, b);
    xp_scale(&qt, &qt, tau);
    xp_add(&qt, &qt, c);          /* Q(tau) = (A tau + 2B) tau + C */
    int ss = xp_sign(&s), sq = xp_sign(&qt);
    int term; /* the sign of s - pm sqrt(G), i.e. of A (tau - r) */
    if (pm < 0)
        term = ss >= 0 ? 1 : -a_sign * sq;   /* s + sqrt(G) */
    else
        term = ss <= 0 ? -1 : a_sign * sq;   /* s - sqrt(G) */
    return term * a_sign;
}

static void set_from_ratio(const xp *num, const xp *den, double tmin, double tmax,
                           quad_line_roots *out)
{
    int in = 0;
    double hi = 0.0, lo = 0.0;
    out->count = ratio_decide(num, den, tmin, tmax, &in, &hi, &lo);
    out->t_hi[0] = hi;
    out->t_lo[0] = lo;
    out->in[0] = in;
}

void quad_line_exact(const xp *a, const xp *b, const xp *c, const xp *t_thr, const xp *l_thr,
                     double tmin, double tmax, quad_line_roots *out)
{
    out->count = 0;
    out->touch = 0;
    out->in[0] = out->in[1] = 0;
    out->enter[0] = out->enter[1] = 0;
    int a_sign = xp_sign(a);
    xp tmp, tmp2;

    /* The linear case |A| <= L: one root -C/(2B), entering where B < 0. */
    int linear = a_sign == 0;
    if (!linear && l_thr != NULL) {
        xp_scale(&tmp, a, (double)a_sign);
        xp_sub(&tmp, l_thr, &tmp);
        linear = xp_sign(&tmp) >= 0;
    }
    if (linear) {
        xp num, den;
        xp_scale(&num, c, -1.0);
        xp_scale(&den, b, 2.0);
        set_from_ratio(&num, &den, tmin, tmax, out);
        out->enter[0] = xp_sign(b) < 0;
        return;
    }

    xp g;
    xp_mul(&g, b, b);
    xp_mul(&tmp, a, c);
    xp_sub(&g, &g, &tmp);
    int touch;
    if (t_thr != NULL) {
        xp_add(&tmp, &g, t_thr);
        xp_sub(&tmp2, &g, t_thr);
        touch = xp_sign(&tmp) >= 0 && xp_sign(&tmp2) <= 0;
    } else {
        touch = xp_sign(&g) == 0;
    }
    if (touch) {
        xp num;
        xp_scale(&num, b, -1.0);
        set_from_ratio(&num, a, tmin, tmax, out); /* -B/A, A != 0 */
        out->touch = 1;
        return;
    }
    if (xp_sign(&g) < 0)
        return;

    /* Two roots: decisions from signs, values from the dd-rounded
     * coefficients (each within 2u^2 of the exact one). */
    int side_minus[2], side_plus[2];
    double bound[2] = { tmin, tmax };
    for (int k = 0; k < 2; k++) {
        side_minus[k] = root_side(a, b, c, a_sign, bound[k], -1);
        side_plus[k] = root_side(a, b, c, a_sign, bound[k], +1);
    }
    vdd av, bv, cv, gv;
    xp_dd(a, &av.hi, &av.lo);
    xp_dd(b, &bv.hi, &bv.lo);
    xp_dd(c, &cv.hi, &cv.lo);
    xp_dd(&g, &gv.hi, &gv.lo);
    double s = sqrt(gv.hi);
    vdd s2 = two_prod(s, s);
    vdd root = dd_renorm((vdd){ s, (((gv.hi - s2.hi) - s2.lo) + gv.lo) / (s + s) });
    double sigma = xp_sign(b) < 0 ? -1.0 : 1.0;
    vdd sum = two_sum(bv.hi, sigma * root.hi);
    vdd qq = dd_renorm((vdd){ -sum.hi, -(sum.lo + (bv.lo + sigma * root.lo)) });
    vdd t_q_a = dd_mul_inv_dd(qq, av, 1.0 / av.hi);
    vdd t_c_q = xp_sign(c) == 0 ? (vdd){ 0.0, 0.0 } : dd_mul_inv_dd(cv, qq, 1.0 / qq.hi);
    vdd r_minus = sigma > 0.0 ? t_q_a : t_c_q, r_plus = sigma > 0.0 ? t_c_q : t_q_a;
    int a_pos = a_sign > 0;
    vdd r[2] = { a_pos ? r_minus : r_plus, a_pos ? r_plus : r_minus };
    for (int i = 0; i < 2; i++) {
        int is_minus = a_pos ? i == 0 : i == 1;
        const int *side = is_minus ? side_minus : side_plus;
        out->t_hi[i] = r[i].hi;
        out->t_lo[i] = r[i].lo;
        out->in[i] = side[0] <= 0 && side[1] >= 0; /* tmin <= r <= tmax */
        out->enter[i] = is_minus;
    }
    out->count = 2;
}
