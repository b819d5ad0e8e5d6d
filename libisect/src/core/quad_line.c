/* SPDX-License-Identifier: Apache-2.0 */
/*
 * quad_line.c — a line's crossings with a quadric surface: certified from
 * double-doubles, or exact (see quad_line.h).
 */
#include "core/quad_line.h"
#include "core/ratio.h"

#include <math.h>

#define U DDX_U

/* ------------------------------------------------------------ certified */

/* Where the exact t (within err of t_hi) lies against tau: +1 above, -1
 * below, 0 equal (err == 0 only), 2 not certain. t_hi - tau is formed
 * exactly (TwoSum) so that an err of 0 decides by its sign alone. */
static int side_certain(double t_hi, double err, double tau)
{
    if (isinf(tau))
        return tau < 0.0 ? 1 : -1;
    ddx d = ddx_diff(t_hi, tau);
    if (err == 0.0)
        return (d.hi > 0.0) - (d.hi < 0.0);
    /* |d| >= |d.hi| (1 - u): the margin must clear err by that much */
    if (fabs(d.hi) * (1.0 - 2.0 * U) > err)
        return d.hi > 0.0 ? 1 : -1;
    return 2;
}

int quad_line_certify(const quad_line_dd *q, double tmin, double tmax, quad_line_roots *out)
{
    out->count = 0;
    out->touch = 0;
    /* A must be certainly away from the linear threshold (and from 0) */
    if (!(ddx_abs(q->a) * (1.0 - 2.0 * U) > 8.0 * q->a.err + q->l_thr))
        return 0;
    double g_low = (q->g.hi - fabs(q->g.lo)) * (1.0 - 2.0 * U) - q->g.err;
    double g_high = (q->g.hi + fabs(q->g.lo)) * (1.0 + 2.0 * U) + q->g.err;
    if (g_high < -q->t_thr)
        return 1; /* G < -T: the line misses */
    if (!(g_low > q->t_thr))
        return 0; /* a touch, or too close to tell */

    /* q = -(B + sigma sqrt(G)): the two terms share a sign (for the dd
     * values; either sign gives the roots, the bounds say how well), so
     * |q| >= sqrt(G) and nothing cancels; then the roots q/A and C/q */
    ddx root = ddx_sqrt(q->g, g_low);
    double sigma = q->b.hi < 0.0 ? -1.0 : 1.0;
    ddx qq = ddx_neg(ddx_add(q->b, sigma > 0.0 ? root : ddx_neg(root)));
    ddx t_q_a = ddx_div(qq, q->a), t_c_q = ddx_div(q->c, qq);
    /* q/A is r- for sigma = +1, r+ for sigma = -1; C/q the other */
    ddx r_minus = sigma > 0.0 ? t_q_a : t_c_q, r_plus = sigma > 0.0 ? t_c_q : t_q_a;
    int a_pos = q->a.hi > 0.0;
    ddx r[2] = { a_pos ? r_minus : r_plus, a_pos ? r_plus : r_minus };
    for (int i = 0; i < 2; i++) {
        /* the reported t_hi within 1.5 ulp: |t_lo| <= ulp/2, err <= ulp */
        if (!(r[i].err <= 0x1p-53 * fabs(r[i].hi)))
            return 0;
        double err = r[i].err + fabs(r[i].lo);
        int lo = side_certain(r[i].hi, err, tmin), hi = side_certain(r[i].hi, err, tmax);
        if (lo == 2 || hi == 2)
            return 0;
        out->t_hi[i] = r[i].hi;
        out->t_lo[i] = r[i].lo;
        out->err[i] = r[i].err;
        out->in[i] = lo >= 0 && hi <= 0;
        out->enter[i] = a_pos ? i == 0 : i == 1;
        out->which[i] = out->enter[i] ? QL_ROOT_MINUS : QL_ROOT_PLUS;
    }
    out->count = 2;
    return 1;
}

/* ---------------------------------------------------------------- exact */

int quad_line_cmp(const xp *a, const xp *b, const xp *c, int which, const xp *num,
                  const xp *den)
{
    int den_sign = xp_sign(den);
    xp s, tmp;
    /* A num + B den: s = A tau + B times den */
    xp_mul(&s, a, num);
    xp_add_mul(&s, b, den);
    if (which == QL_ROOT_TOUCH) /* -B/A - tau = -(A tau + B)/A */
        return -xp_sign(&s) * xp_sign(a) * den_sign;
    if (which == QL_ROOT_LINEAR) { /* -C/(2B) - tau = -(C + 2B tau)/(2B) */
        xp_mul(&tmp, c, den);
        xp_add_mul(&tmp, b, num);
        xp_add_mul(&tmp, b, num);
        return -xp_sign(&tmp) * xp_sign(b) * den_sign;
    }
    /* Q(tau) den^2 = A num^2 + 2B num den + C den^2
     *              = (A num + 2B den) num + (C den) den */
    xp s2, q, c_den;
    xp_mul(&s2, b, den);
    xp_add(&s2, &s2, &s);         /* A num + 2B den */
    xp_mul(&q, &s2, num);
    xp_mul(&c_den, c, den);
    xp_add_mul(&q, &c_den, den);
    int a_sign = xp_sign(a), ss = xp_sign(&s) * den_sign, sq = xp_sign(&q);
    /* the sign of s + sqrt(G) (r-) or s - sqrt(G) (r+): A (tau - r) */
    int term;
    if (which == QL_ROOT_MINUS)
        term = ss >= 0 ? 1 : -a_sign * sq;
    else
        term = ss <= 0 ? -1 : a_sign * sq;
    return -term * a_sign;
}

/* sign(r - tau) for a double tau (infinite allowed) */
static int cmp_tau(const xp *a, const xp *b, const xp *c, int which, double tau)
{
    if (isinf(tau))
        return tau < 0.0 ? 1 : -1;
    xp num, one;
    xp_set(&num, tau);
    xp_set(&one, 1.0);
    return quad_line_cmp(a, b, c, which, &num, &one);
}

/* The dd value of a ratio root and its decisions (ratio.c). */
static void set_from_ratio(const xp *num, const xp *den, double tmin, double tmax, int which,
                           quad_line_roots *out)
{
    int in = 0;
    double hi = 0.0, lo = 0.0;
    out->count = ratio_decide(num, den, tmin, tmax, &in, &hi, &lo);
    out->t_hi[0] = hi;
    out->t_lo[0] = lo;
    out->err[0] = 8.0 * U * U * fabs(hi) + DDX_TINY;
    out->in[0] = in;
    out->which[0] = which;
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
        set_from_ratio(&num, &den, tmin, tmax, QL_ROOT_LINEAR, out);
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
        set_from_ratio(&num, a, tmin, tmax, QL_ROOT_TOUCH, out); /* -B/A, A != 0 */
        out->touch = 1;
        return;
    }
    if (xp_sign(&g) < 0)
        return;

    /* Two roots: decisions from signs, values from the dd-rounded
     * coefficients (each within 2u^2 of the exact one, so each root within
     * ~30u^2 of itself: the terms of q share a sign). */
    ddx av, bv, cv, gv;
    xp_dd(a, &av.hi, &av.lo);
    xp_dd(b, &bv.hi, &bv.lo);
    xp_dd(c, &cv.hi, &cv.lo);
    xp_dd(&g, &gv.hi, &gv.lo);
    av.err = bv.err = cv.err = gv.err = 0.0; /* the bound is the one above */
    ddx root = ddx_sqrt(gv, gv.hi * 0.5);
    int sigma = xp_sign(b) < 0 ? -1 : 1;
    ddx qq = ddx_neg(ddx_add(bv, sigma > 0 ? root : ddx_neg(root)));
    ddx t_q_a = ddx_div(qq, av);
    ddx t_c_q = xp_sign(c) == 0 ? ddx_of(0.0) : ddx_div(cv, qq);
    ddx r_minus = sigma > 0 ? t_q_a : t_c_q, r_plus = sigma > 0 ? t_c_q : t_q_a;
    int a_pos = a_sign > 0;
    ddx r[2] = { a_pos ? r_minus : r_plus, a_pos ? r_plus : r_minus };
    for (int i = 0; i < 2; i++) {
        int which = (a_pos ? i == 0 : i == 1) ? QL_ROOT_MINUS : QL_ROOT_PLUS;
        out->t_hi[i] = r[i].hi;
        out->t_lo[i] = r[i].lo;
        out->err[i] = 64.0 * U * U * fabs(r[i].hi) + DDX_TINY;
        out->which[i] = which;
        /* tmin <= r <= tmax */
        out->in[i] = cmp_tau(a, b, c, which, tmin) >= 0 && cmp_tau(a, b, c, which, tmax) <= 0;
        out->enter[i] = which == QL_ROOT_MINUS;
    }
    out->count = 2;
}
