/* SPDX-License-Identifier: Apache-2.0 */
/*
 * eft.h — error-free transformations and double-double ("dd") arithmetic
 * in the lane vocabulary of lanes.h, for the fast kernels.
 *
 * A dd value is the unevaluated sum hi + lo of two doubles. The kernels use
 * dd for the handful of quantities whose rounding would cost the accuracy
 * contract (a ray parameter within 4 ulp of the exact one): differences of
 * input coordinates (exact as hi + lo by TwoSum), dot and cross products
 * (each product exact by TwoProduct, then compensated sums in the manner of
 * Ogita, Rump & Oishi, "Accurate sum and dot product", SISC 2005), and the
 * final quotients (one Newton correction). Each kernel states the error
 * bound of what it builds from these; the building blocks are:
 *
 *   two_sum(a, b)        hi + lo = a + b exactly (Knuth; no condition)
 *   fast_two_sum(a, b)   the same when |a| >= |b| or a == 0 (Dekker)
 *   two_prod(a, b)       hi + lo = a * b exactly unless the product is
 *                        within 2^-970 of underflow (then lo is rounded)
 *
 * Every operation is a plain lane operation of lanes.h, so these too give
 * the same bits in every instruction set.
 */
#ifndef ISECT_EFT_H
#define ISECT_EFT_H

#include "core/lanes.h"

typedef struct vdd {
    vd hi, lo;
} vdd;

static ALWAYS_INLINE vdd two_sum(vd a, vd b)
{
    vdd r;
    r.hi = vd_add(a, b);
    vd b_virtual = vd_sub(r.hi, a);
    vd a_virtual = vd_sub(r.hi, b_virtual);
    r.lo = vd_add(vd_sub(a, a_virtual), vd_sub(b, b_virtual));
    return r;
}

static ALWAYS_INLINE vdd fast_two_sum(vd a, vd b)
{
    vdd r;
    r.hi = vd_add(a, b);
    r.lo = vd_sub(b, vd_sub(r.hi, a));
    return r;
}

static ALWAYS_INLINE vdd two_prod(vd a, vd b)
{
    vdd r;
    r.hi = vd_mul(a, b);
    r.lo = vd_prod_err(a, b, r.hi);
    return r;
}

/* hi + lo renormalised, exactly, so that hi = fl(hi + lo) and |lo| <=
 * ulp(hi)/2 <= u|hi|. TwoSum, not Fast2Sum: after a cancellation in the
 * heads the low part may be the larger one. */
static ALWAYS_INLINE vdd dd_renorm(vdd a)
{
    return two_sum(a.hi, a.lo);
}

/* x / y for renormalised dd x, y (y.hi != 0), rounded to a double, given
 * inv_y = fl(1/y.hi) (one division shared by every quotient by y): the
 * head quotient tau = x.hi inv_y (within 2.1u of x.hi / y.hi), corrected
 * once by the residual x - tau y, whose part x.hi - tau y.hi is exact
 * (TwoProduct, and Sterbenz for the difference) and whose first-order
 * terms x.lo - tau y.lo are rounded: |result - x/y| <= (u + 24u^2) |x/y|
 * while nothing under- or overflows (residual error <= 9u^2 |x|, the
 * correction's own <= 12u^2 |x/y|, then the one final rounding). */
static ALWAYS_INLINE vd dd_mul_inv(vdd x, vdd y, vd inv_y)
{
    vd tau = vd_mul(x.hi, inv_y);
    vdd p = two_prod(tau, y.hi);
    vd r = vd_add(vd_sub(vd_sub(x.hi, p.hi), p.lo), vd_sub(x.lo, vd_mul(tau, y.lo)));
    return vd_add(tau, vd_mul(r, inv_y));
}

/* The same quotient kept as a renormalised dd, tau + correction (the
 * correction's own error, <= 21u^2 |x/y|, is the only one): for placing a
 * point at o + t d to a fraction of an ulp. */
static ALWAYS_INLINE vdd dd_mul_inv_dd(vdd x, vdd y, vd inv_y)
{
    vd tau = vd_mul(x.hi, inv_y);
    vdd p = two_prod(tau, y.hi);
    vd r = vd_add(vd_sub(vd_sub(x.hi, p.hi), p.lo), vd_sub(x.lo, vd_mul(tau, y.lo)));
    return two_sum(tau, vd_mul(r, inv_y));
}

/* x / y as dd_mul_inv, with its own division. */
static ALWAYS_INLINE vd dd_div(vdd x, vdd y)
{
    return dd_mul_inv(x, y, vd_div(vd_set1(1.0), y.hi));
}

#endif /* ISECT_EFT_H */
