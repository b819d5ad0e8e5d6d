/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ratio.c — exact decisions on t = num/den (see ratio.h).
 */
#include "core/ratio.h"

#include <math.h>

int ratio_cmp_tau(const xp *num, const xp *den, double tau)
{
    if (isinf(tau))
        return tau < 0.0 ? 1 : -1;
    xp scaled, diff;
    xp_scale(&scaled, den, tau);
    xp_sub(&diff, num, &scaled);
    return xp_sign(&diff) * xp_sign(den);
}

int ratio_cmp(const xp *n1, const xp *d1, const xp *n2, const xp *d2)
{
    xp a, b;
    xp_mul(&a, n1, d2);
    xp_mul(&b, n2, d1);
    xp_sub(&a, &a, &b);
    return xp_sign(&a) * xp_sign(d1) * xp_sign(d2);
}

void ratio_value(const xp *num, const xp *den, double *t_hi, double *t_lo)
{
    /* the quotient of the rounded values, then the exact residual num - q
     * den divided once more */
    double nh, nl, dh, dl;
    xp_dd(num, &nh, &nl);
    xp_dd(den, &dh, &dl);
    double q = nh / dh;
    xp rest, qd;
    xp_scale(&qd, den, q);
    xp_sub(&rest, num, &qd);
    double rh, rl;
    xp_dd(&rest, &rh, &rl);
    double corr = rh / dh;
    double hi = q + corr;
    *t_hi = hi;
    *t_lo = corr - (hi - q); /* Fast2Sum: |q| >= |corr| */
}

int ratio_decide(const xp *num, const xp *den, double tmin, double tmax, int *in_range,
                 double *t_hi, double *t_lo)
{
    if (xp_sign(den) == 0)
        return 0;
    *in_range = ratio_cmp_tau(num, den, tmin) >= 0 && ratio_cmp_tau(num, den, tmax) <= 0;
    ratio_value(num, den, t_hi, t_lo);
    return 1;
}

int parallel_exact(const xp *den, const xp *nn, const xp *dd, double eps)
{
    if (xp_sign(den) == 0)
        return 1;
    if (eps == 0.0)
        return 0;
    double dh, dl, nh, nl, sh, sl;
    xp_dd(den, &dh, &dl);
    xp_dd(nn, &nh, &nl);
    xp_dd(dd, &sh, &sl);
    double a = fabs(dh), b = eps * sqrt(nh * sh);
    if (a > 2.0 * b)
        return 0;
    if (a < 0.5 * b)
        return 1;
    /* a and b within a factor 2: one scale for both, then exact squares */
    int e = 0;
    (void)frexp(a, &e);
    xp ds, d2, rhs;
    xp_scale(&ds, den, ldexp(1.0, -e));
    xp_mul(&d2, &ds, &ds);
    double es = ldexp(eps, -e);
    xp_mul(&rhs, nn, dd);
    xp_scale(&rhs, &rhs, es);
    xp_scale(&rhs, &rhs, es);
    xp_sub(&d2, &d2, &rhs);
    return xp_sign(&d2) <= 0;
}
