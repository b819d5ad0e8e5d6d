/* SPDX-License-Identifier: Apache-2.0 */
/*
 * dyadic_sum.c — exact sums of products of doubles at any exponent (see
 * dyadic_sum.h for the method and why each step is exact).
 *
 * Exactness of the scaled additions: a factor scaled into [0.5, 1) is a
 * multiple of 2^-53, so the exact product of three is a multiple of
 * 2^-159, and so is every part TwoProduct splits it into. Added at a scale
 * of at least 2^-900 the parts are multiples of 2^-1059, as is every sum
 * and TwoSum residual formed from them: nothing is lost to underflow. The
 * running sum, when it is moved down to a lower base, is at most about
 * 2^62 times the number of terms, so scaling it up cannot overflow.
 */
#include "core/dyadic_sum.h"

#include "core/expansion.h"
#include "core/predicates.h"
#include "core/scaling.h"

#include <math.h>

#define DYADIC_WINDOW 900 /* terms at most 2^900 below the base are added scaled */
#define DYADIC_MARGIN 60  /* a sum 2^60 above what is left decides */

void dyadic_init(dyadic_sum *s)
{
    s->count = 0;
}

/* x = m 2^e with |m| in [0.5, 1), exactly (frexp's split). */
static double mantissa(double x, int *e)
{
    *e = pow2_exponent(x);
    return pow2_scale(x, -*e);
}

void dyadic_add3(dyadic_sum *s, double sign, double a, double b, double c)
{
    if (a == 0.0 || b == 0.0 || c == 0.0 || s->count >= DYADIC_SUM_TERMS)
        return;
    int ea, eb, ec;
    double ma = sign * mantissa(a, &ea), mb = mantissa(b, &eb), mc = mantissa(c, &ec);
    /* ma mb = h1 + l1, h1 mc = h2 + l2, l1 mc = h3 + l3, all exact */
    double h1 = ma * mb, l1 = product_error(ma, mb, h1);
    double h2 = h1 * mc, l2 = product_error(h1, mc, h2);
    double h3 = l1 * mc, l3 = product_error(l1, mc, h3);
    double *p = s->part[s->count];
    p[0] = l3;
    p[1] = h3;
    p[2] = l2;
    p[3] = h2;
    s->exp[s->count] = ea + eb + ec;
    s->count++;
}

/* The sum as acc 2^base: every term when that is needed, or the terms down
 * to where the rest cannot change the sign or the leading digits. */
static void dyadic_collapse(const dyadic_sum *s, xp *acc, int *base_out)
{
    int order[DYADIC_SUM_TERMS];
    for (int i = 0; i < s->count; i++) {
        int j = i;
        for (; j > 0 && s->exp[order[j - 1]] < s->exp[i]; j--)
            order[j] = order[j - 1];
        order[j] = i;
    }
    xp_set(acc, 0.0);
    int base = s->count > 0 ? s->exp[order[0]] : 0;
    for (int r = 0; r < s->count; r++) {
        int i = order[r], e = s->exp[i];
        if (base - e > DYADIC_WINDOW) {
            if (acc->n > 0) {
                /* |acc| > top/2 (nonoverlapping parts); each term left is
                 * below 2^e in magnitude. */
                double top = fabs(acc->p[acc->n - 1]);
                double left = ldexp((double)(s->count - r), DYADIC_MARGIN + e - base);
                if (0.5 * top > left)
                    break;
                for (int k = 0; k < acc->n; k++)
                    acc->p[k] = ldexp(acc->p[k], base - e);
            }
            base = e;
        }
        for (int k = 0; k < 4; k++)
            xp_add_d(acc, pow2_scale(s->part[i][k], e - base));
    }
    *base_out = base;
}

int dyadic_sign(const dyadic_sum *s)
{
    xp acc;
    int base;
    dyadic_collapse(s, &acc, &base);
    return xp_sign(&acc);
}

double dyadic_value(const dyadic_sum *s, int *e)
{
    xp acc;
    int base;
    dyadic_collapse(s, &acc, &base);
    double h = 0.0;
    for (int k = 0; k < acc.n; k++)
        h += acc.p[k];
    if (h == 0.0) {
        *e = 0;
        return 0.0;
    }
    int eh;
    double m = mantissa(h, &eh);
    *e = base + eh;
    return m;
}
