/*
 * quadratic.h — the root finding shared by the quadric family (sphere,
 * ellipsoid, cylinder side, general quadric), written once and free of
 * cancellation.
 *
 *  - line_sphere_roots(): a line against a sphere in the geometric form of
 *    Haines, Günther & Akenine-Möller, "Precision Improvements for Ray/Sphere
 *    Intersection" (Ray Tracing Gems, 2019). The sphere, the ellipsoid (a
 *    unit sphere in the frame scaled by 1/radii) and the cylinder side (a
 *    circle in the plane across the axis) all reduce to it.
 *  - quadratic_roots(): a t^2 + b t + c = 0 for the general quadric, with the
 *    discriminant evaluated by Kahan's FMA algorithm from coefficients known
 *    to twice the working precision (compensated sums).
 *
 * Scaling. Every routine here, and every caller, brings its numbers to a
 * common power-of-two scale before squaring anything (pow2_exponent,
 * scale3). Multiplying by a power of two is exact (barring underflow of parts
 * 2^1022 times smaller than the largest), so the results are those of the
 * unscaled arithmetic, while no square, product or difference can overflow
 * or lose its bits to underflow at any input magnitude.
 */
#ifndef ISECT_QUADRATIC_H
#define ISECT_QUADRATIC_H

#include "core/predicates.h"

#include "isect.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* The crossings of a line with a sphere. */
typedef struct line_sphere {
    int    count;        /* 0: miss; 1: tangent (one TOUCH at t[0]);
                            2: enters at t[0], leaves at t[1] (t[0] <= t[1]) */
    double t[2];         /* line parameters */
    double normal[2][3]; /* unit outward normal at each crossing: the
                            direction from the centre to the point */
} line_sphere;

/*
 * Crossings of the line f + t*d with the sphere |x| = r: f is the line's
 * point relative to the centre, d != 0, r > 0, all finite, any scale.
 * Tangent when |r^2 - h^2| <= eps*r^2, h the distance from the centre to
 * the line (r^2 - h^2 formed from f x d to about twice the working
 * precision); then one hit at the foot of the perpendicular.
 */
void line_sphere_roots(const double f[3], const double d[3], double r, double eps,
                       line_sphere *out);

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

/* x*y*z: the residual of x*y times z is a second-order term, added plainly. */
static inline void comp_add_product3(comp_sum *s, double x, double y, double z)
{
    double p = x * y;
    s->lo += product_error(x, y, p) * z;
    comp_add_product(s, p, z);
}

static inline double comp_value(const comp_sum *s)
{
    return s->hi + s->lo;
}

/* The same sum as hi = comp_value(s) plus the exact remainder lo (TwoSum,
 * which, unlike Fast2Sum, needs no |hi| >= |lo|: after cancellation the
 * running hi may be the smaller part). */
static inline comp_sum comp_normalized(comp_sum s)
{
    comp_sum n = { 0.0, 0.0 };
    comp_add(&n, s.hi);
    comp_add(&n, s.lo);
    return n;
}

/* The real roots of a quadratic. */
typedef struct quad_roots {
    int    count; /* 0; 1: double root (tangent); 2: t[0] <= t[1] */
    double t[2];
} quad_roots;

/*
 * Roots of a t^2 + b t + c = 0, each coefficient given as an unevaluated
 * sum hi + lo (a compensated sum, so that the coefficients may be known to
 * about twice the working precision); a != 0, all finite, any scale.
 * Double root (count 1, t = -b/2a) when |b^2 - 4ac| <= eps*(b^2 + 4|ac|).
 * A root beyond the double range comes out as +-inf.
 */
void quadratic_roots(comp_sum a, comp_sum b, comp_sum c, double eps, quad_roots *out);

/* v.v - r*r with error-free products and a compensated sum (Ogita, Rump &
 * Oishi 2005, Dot2): as accurate as if evaluated in twice the precision and
 * then rounded. Its sign is the closed-ball test |v| <= r. The caller keeps
 * |v| and r below 2^500 (scaled), so nothing overflows. */
double sumsq_minus_sq(const double v[3], double r);

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

#endif /* ISECT_QUADRATIC_H */
