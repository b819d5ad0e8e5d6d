/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ddx.h — double-double values that carry a bound on their own error, for
 * the certified paths of the quadric family (scalar code).
 *
 * A ddx is hi + lo (renormalised: hi = fl(hi + lo)) together with err, a
 * bound on |exact - (hi + lo)|. Inputs enter exactly (a double, or the
 * difference of two doubles by TwoSum); every operation adds the bound of
 * its own roundings to the propagated ones, so the certifying code compares
 * plain numbers against honest bounds (forward error analysis done by the
 * program, Shewchuk's filters in double-double form). The bounds:
 *   add:  ex + ey + u |x.lo + y.lo| + u |s.lo + (x.lo + y.lo)|,
 *   mul:  |x| ey + |y| ex + ex ey + the dropped x.lo y.lo and the rounded
 *         cross terms (u |x.hi y.lo| + u |x.lo y.hi| + u |their sum| + u |lo|),
 * each widened by 2^-40 (for the roundings of the bounds themselves) plus
 * DDX_TINY, which covers partial products that fall below the normal range
 * (the callers scale their numbers near 1, so only components 2^-400 below
 * the rest can get there). Exact results (err 0) stay exact only when no
 * operation rounded; anything else certifies with a tiny err > 0.
 */
#ifndef ISECT_DDX_H
#define ISECT_DDX_H

#include "core/predicates.h"

#include <math.h>

#define DDX_U    0x1p-53
#define DDX_TINY 0x1p-1000
#define DDX_WIDEN (1.0 + 0x1p-40)

typedef struct ddx {
    double hi, lo, err;
} ddx;

static inline ddx ddx_two_sum(double a, double b, double err)
{
    ddx r;
    r.hi = a + b;
    double b_virtual = r.hi - a;
    double a_virtual = r.hi - b_virtual;
    r.lo = (a - a_virtual) + (b - b_virtual);
    r.err = err;
    return r;
}

/* a (exact) */
static inline ddx ddx_of(double a)
{
    ddx r = { a, 0.0, 0.0 };
    return r;
}

/* a - b, exact */
static inline ddx ddx_diff(double a, double b)
{
    return ddx_two_sum(a, -b, 0.0);
}

static inline double ddx_abs(ddx x)
{
    return fabs(x.hi) + fabs(x.lo);
}

static inline ddx ddx_neg(ddx x)
{
    ddx r = { -x.hi, -x.lo, x.err };
    return r;
}

static inline ddx ddx_add(ddx x, ddx y)
{
    ddx s = ddx_two_sum(x.hi, y.hi, 0.0);
    double low = x.lo + y.lo;
    double lo = s.lo + low;
    ddx r = ddx_two_sum(s.hi, lo, 0.0);
    double rounding = DDX_U * (fabs(low) + fabs(lo));
    r.err = (x.err + y.err + rounding) * DDX_WIDEN + (rounding != 0.0 ? DDX_TINY : 0.0);
    return r;
}

static inline ddx ddx_sub(ddx x, ddx y)
{
    return ddx_add(x, ddx_neg(y));
}

static inline ddx ddx_mul(ddx x, ddx y)
{
    double p = x.hi * y.hi;
    double p_err = product_error(x.hi, y.hi, p);
    double c1 = x.hi * y.lo, c2 = x.lo * y.hi;
    double cross = c1 + c2;
    double lo = p_err + cross;
    ddx r = ddx_two_sum(p, lo, 0.0);
    /* cross == 0: both cross terms vanish and lo = p_err exactly */
    double rounding = cross == 0.0 && c1 == 0.0 ? 0.0
                    : DDX_U * (fabs(c1) + fabs(c2) + fabs(cross) + fabs(lo))
                      + fabs(x.lo * y.lo) * (1.0 + DDX_U);
    double propagated = ddx_abs(x) * y.err + ddx_abs(y) * x.err + x.err * y.err;
    int inexact = rounding != 0.0 || (p != 0.0 && fabs(p) < 0x1p-969);
    r.err = (propagated + rounding) * DDX_WIDEN + (inexact ? DDX_TINY : 0.0);
    return r;
}

static inline ddx ddx_mul_d(ddx x, double d)
{
    return ddx_mul(x, ddx_of(d));
}

static inline ddx ddx_sqr(ddx x)
{
    return ddx_mul(x, x);
}

/* sqrt(x) for x > 0 as a dd with its bound, one Newton step from s =
 * fl(sqrt(x.hi)): s + (x - s^2)/(2s), s^2 exact by TwoProduct (x.hi - s^2
 * then exact by Sterbenz); the step leaves at most (s - sqrt x)^2/(2s) <=
 * u^2 s/2 and its residual's roundings u |r| each (|r| <= u s): 4u^2 s in
 * all. Propagated: |sqrt(X) - sqrt(x')| <= |X - x'| / sqrt(x') for the
 * exact X >= 0 near x' = hi + lo, with x_low_bound <= x' (a lower bound the
 * caller knows; 0 or less: an infinite bound). */
static inline ddx ddx_sqrt(ddx x, double x_low_bound)
{
    if (!(x.hi > 0.0)) {
        ddx zero = { 0.0, 0.0, sqrt(fmax(x.hi, 0.0) + x.err) };
        return zero;
    }
    double s = sqrt(x.hi);
    double sq = s * s;
    double sq_err = product_error(s, s, sq);
    ddx r = { s, (((x.hi - sq) - sq_err) + x.lo) / (s + s), 0.0 };
    r = ddx_add(r, ddx_of(0.0));
    double propagated = x.err == 0.0 ? 0.0
                      : x_low_bound > 0.0 ? x.err / sqrt(x_low_bound) : INFINITY;
    r.err = (propagated + 4.0 * DDX_U * DDX_U * s) * DDX_WIDEN + DDX_TINY;
    return r;
}

/* x / y, kept as a renormalised dd: the head quotient corrected once by the
 * residual x - tau y (its head part exact by TwoProduct). The bound: the
 * propagated (ex + |x/y| ey) / (|y| - ey) (exact to first order on the
 * interval of y), the correction's own 21u^2 |x/y| taken as 32u^2, then
 * widened. A y within 8 ey of zero gives err = +inf (not a number to
 * certify with). */
static inline ddx ddx_div(ddx x, ddx y)
{
    double y_abs = fabs(y.hi) - fabs(y.lo);
    ddx r = { x.hi / y.hi, 0.0, INFINITY };
    if (!(y_abs > 8.0 * y.err) || !isfinite(r.hi))
        return r;
    double tau = r.hi;
    double p = tau * y.hi;
    double p_err = product_error(tau, y.hi, p);
    double rest = ((x.hi - p) - p_err) + (x.lo - tau * y.lo);
    r = ddx_two_sum(tau, rest / y.hi, 0.0);
    double t_abs = ddx_abs(r);
    double denom = y_abs * (1.0 - 2.0 * DDX_U) - y.err;
    r.err = ((x.err + t_abs * y.err) / denom + 32.0 * DDX_U * DDX_U * t_abs) * DDX_WIDEN + DDX_TINY;
    return r;
}

/* sign(x - y) where the bounds decide it (an exact zero only when both are
 * exact), else 2. */
static inline int ddx_cmp_certain(ddx x, ddx y)
{
    ddx diff = ddx_sub(x, y);
    double bound = x.err + y.err + diff.err;
    if (bound == 0.0)
        return (diff.hi > 0.0) - (diff.hi < 0.0);
    if (fabs(diff.hi) * (1.0 - 2.0 * DDX_U) > bound)
        return diff.hi > 0.0 ? 1 : -1;
    return 2;
}

#endif /* ISECT_DDX_H */
