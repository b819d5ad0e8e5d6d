/* SPDX-License-Identifier: Apache-2.0 */
/*
 * scaling.h — the numeric groundwork every primitive shares: power-of-two
 * scaling (exact, so numbers can be brought near 1 before anything is
 * squared), compensated sums, accurate cross products and unit vectors.
 *
 * Scaling. The primitives bring their numbers to a common power-of-two
 * scale before squaring anything (pow2_exponent, scale3). Multiplying by a
 * power of two is exact (barring underflow of parts 2^1022 times smaller
 * than the largest), so the results are those of the unscaled arithmetic,
 * while no square, product or difference can overflow or lose its bits to
 * underflow at any input magnitude.
 */
#ifndef ISECT_SCALING_H
#define ISECT_SCALING_H

#include "core/predicates.h"

#include "isect.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/*
 * A compensated sum (Ogita, Rump & Oishi 2005, Sum2/Dot2): hi + lo carries
 * the running sum as if in twice the working precision; every addition is
 * split exactly by TwoSum and every product by an FMA residual. The value
 * comp_value() is then as accurate as the sum evaluated in twice the
 * precision and rounded once (error <= u|sum| + O(u^2) sum|terms|).
 */
typedef struct comp_sum {
    double hi, lo;
} comp_sum;

/* hi + lo accumulates x exactly (Knuth's TwoSum: no branch on magnitudes). */
static inline void comp_add(comp_sum *s, double x)
{
    double sum = s->hi + x;
    double x_virtual = sum - s->hi;
    double hi_virtual = sum - x_virtual;
    s->lo += (s->hi - hi_virtual) + (x - x_virtual);
    s->hi = sum;
}


/* x*y = p + its exact residual, both accumulated. */
static inline void comp_add_product(comp_sum *s, double x, double y)
{
    double p = x * y;
    s->lo += product_error(x, y, p);
    comp_add(s, p);
}

static inline double comp_value(const comp_sum *s)
{
    return s->hi + s->lo;
}

/* r = x cross y, each component a*d - b*c by det2_accurate (Kahan's FMA
 * algorithm, relative error <= 2u per component whatever the cancellation). */
void cross_accurate(double r[3], const double x[3], const double y[3]);

/*
 * Power-of-two helpers, inline and free of libm calls in the common case
 * (they run on every ray of the quadric family).
 *
 * pow2_exponent(): for a normal m the exponent comes straight from the
 * biased exponent field (m = 1.f * 2^(E-1023) = 0.1f * 2^(E-1022), so frexp
 * would return E - 1022); zero, subnormals, inf and NaN take frexp itself,
 * so every input gives frexp's answer bit for bit.
 *
 * pow2_scale(x, k) = x * 2^k. While -1022 <= k <= 1023, 2^k is a normal
 * double built from its bits, and x * 2^k is one IEEE multiplication: the
 * exact product rounded once (exact unless it leaves the normal range, and
 * then rounded/overflowed exactly as the exact value dictates). ldexp (and
 * glibc's scalbn) return that same correctly rounded value, so the result
 * is bit for bit ldexp(x, k), including subnormal and infinite results.
 * Outside that k range 2^k is not a normal double: ldexp itself is used.
 *
 * fmax_nan(a, b) is C99 fmax for the values used here (NaN ignored, the
 * larger otherwise; the callers never compare +0 with -0 as their inputs
 * are fabs() or known positive), written as a compare and select because
 * without -ffast-math the compiler emits a libm call for fmax.
 */
int pow2_exponent_slow(double m);

static inline int pow2_exponent(double m)
{
    uint64_t bits;
    memcpy(&bits, &m, sizeof bits);
    int biased = (int)((bits >> 52) & 0x7ff);
    if (biased != 0 && biased != 0x7ff)
        return biased - 1022;
    return pow2_exponent_slow(m); /* 0, subnormal, inf, NaN */
}

static inline double pow2_scale(double x, int k)
{
    if (k >= -1022 && k <= 1023) {
        uint64_t bits = (uint64_t)(k + 1023) << 52;
        double p;
        memcpy(&p, &bits, sizeof p);
        return x * p;
    }
    return ldexp(x, k);
}

static inline double fmax_nan(double a, double b)
{
    /* b > a ? b : a is one maxsd (no data-dependent branch: random rays
     * would mispredict it); it keeps a NaN a, which the second select,
     * never taken for the finite inputs of the hot paths, replaces by b. */
    double m = b > a ? b : a;
    return m != m ? b : m;
}

/* max(|v0|, |v1|, |v2|), NaN components ignored as by fmax */
static inline double max_abs3(const double v[3])
{
    return fmax_nan(fabs(v[0]), fmax_nan(fabs(v[1]), fabs(v[2])));
}

/* out = v * 2^-e, exact (bit for bit ldexp(v, -e)) */
static inline void scale3(double out[3], const double v[3], int e)
{
    for (int k = 0; k < 3; k++)
        out[k] = pow2_scale(v[k], -e);
}

/* out = v/|v| for any finite v, computed after scaling v by a power of two
 * (so neither |v| nor the division can overflow or underflow, unlike
 * v * (1/|v|) for a subnormal |v|); components never -0.0. Returns 1, or 0
 * with out = 0 for a zero or non-finite v. */
int unit3(double out[3], const double v[3]);

/* unit3, then one Newton step towards unit length with |n|^2 summed to
 * ~u^2: |out| within about u of 1 (unit3 alone: ~2u). For normals computed
 * once per shape. Same return. */
int unit3_accurate(double out[3], const double v[3]);

/*
 * A unit normal: unit(v) when v is finite and nonzero; otherwise (the
 * gradient vanishes at a cone's apex, a tangent line passes through the
 * centre under eps >= 1) the direction facing the ray as `kind` says:
 * -unit(d) for ENTER and TOUCH, +unit(d) for EXIT, so that dir.normal has the
 * sign the kind promises. Components are never -0.0.
 */
void normal_or_facing(double normal[3], const double v[3], const double d[3], int32_t kind);

#endif /* ISECT_SCALING_H */
