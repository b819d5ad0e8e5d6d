/* SPDX-License-Identifier: Apache-2.0 */
/*
 * exact_dyadic.h — exact arithmetic for the tests' own reference answers,
 * independent of the library: every finite double is an integer times a
 * power of two, so sums, differences and products of doubles are exactly
 * (sign, big integer, exponent). The big integer is a plain little-endian
 * array of 32-bit limbs, added, subtracted and multiplied by schoolbook
 * rules; a result that would not fit aborts the test (EX_LIMBS limbs hold
 * 4096 bits: a degree-6 product of doubles needs 318, and aligning two
 * values adds the difference of their exponents).
 *
 * Slow and simple on purpose: it decides the expected answers the library
 * is checked against (signs of orientations in the exact sheared frame,
 * the exact order of two crossing parameters).
 */
#ifndef ISECT_TEST_EXACT_DYADIC_H
#define ISECT_TEST_EXACT_DYADIC_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EX_LIMBS 128

#if defined(__GNUC__) || defined(__clang__)
#define EX_UNUSED __attribute__((unused))
#else
#define EX_UNUSED
#endif

typedef struct exq {
    int      neg;   /* 1 when negative (never for zero) */
    int      exp;   /* value = (-1)^neg * mag * 2^exp */
    int      n;     /* limbs in use; 0 for zero */
    uint32_t mag[EX_LIMBS];
} exq;

static EX_UNUSED void ex_overflow(void)
{
    fprintf(stderr, "exact_dyadic: out of room\n");
    abort();
}

static EX_UNUSED void ex_trim(exq *x)
{
    while (x->n > 0 && x->mag[x->n - 1] == 0)
        x->n--;
    if (x->n == 0)
        x->neg = 0;
}

static EX_UNUSED exq ex_of(double v)
{
    exq x;
    memset(&x, 0, sizeof x);
    if (v == 0.0)
        return x;
    int e;
    double m = frexp(fabs(v), &e); /* v = m 2^e, m in [0.5, 1) */
    uint64_t M = (uint64_t)ldexp(m, 53);
    x.neg = v < 0.0;
    x.exp = e - 53;
    x.mag[0] = (uint32_t)M;
    x.mag[1] = (uint32_t)(M >> 32);
    x.n = 2;
    ex_trim(&x);
    return x;
}

/* mag << s bits (s >= 0), in place. */
static EX_UNUSED void ex_shl(exq *x, int s)
{
    if (x->n == 0 || s == 0)
        return;
    int limbs = s / 32, bits = s % 32;
    if (x->n + limbs + 1 > EX_LIMBS)
        ex_overflow();
    for (int i = x->n - 1; i >= 0; i--) {
        uint64_t v = (uint64_t)x->mag[i] << bits;
        x->mag[i + limbs + 1] |= (uint32_t)(v >> 32);
        x->mag[i + limbs] = (uint32_t)v;
        if (i + limbs != i)
            x->mag[i] = 0;
    }
    for (int i = 0; i < limbs; i++)
        x->mag[i] = 0;
    x->n += limbs + 1;
    x->exp -= s;
    ex_trim(x);
}

/* Compare magnitudes of two values with the same exponent. */
static EX_UNUSED int ex_cmp_mag(const exq *a, const exq *b)
{
    if (a->n != b->n)
        return a->n < b->n ? -1 : 1;
    for (int i = a->n - 1; i >= 0; i--)
        if (a->mag[i] != b->mag[i])
            return a->mag[i] < b->mag[i] ? -1 : 1;
    return 0;
}

static EX_UNUSED exq ex_add(exq a, exq b)
{
    if (a.n == 0)
        return b;
    if (b.n == 0)
        return a;
    /* align to the smaller exponent */
    if (a.exp > b.exp)
        ex_shl(&a, a.exp - b.exp);
    else if (b.exp > a.exp)
        ex_shl(&b, b.exp - a.exp);
    exq r;
    memset(&r, 0, sizeof r);
    r.exp = a.exp;
    int n = a.n > b.n ? a.n : b.n;
    if (a.neg == b.neg) {
        if (n + 1 > EX_LIMBS)
            ex_overflow();
        uint64_t carry = 0;
        for (int i = 0; i < n; i++) {
            uint64_t s = carry + (i < a.n ? a.mag[i] : 0) + (i < b.n ? b.mag[i] : 0);
            r.mag[i] = (uint32_t)s;
            carry = s >> 32;
        }
        r.mag[n] = (uint32_t)carry;
        r.n = n + 1;
        r.neg = a.neg;
    } else {
        const exq *big = &a, *small = &b;
        if (ex_cmp_mag(&a, &b) < 0) {
            big = &b;
            small = &a;
        }
        int64_t borrow = 0;
        for (int i = 0; i < big->n; i++) {
            int64_t s = (int64_t)big->mag[i] - (i < small->n ? small->mag[i] : 0) - borrow;
            borrow = s < 0;
            r.mag[i] = (uint32_t)(s + (borrow ? ((int64_t)1 << 32) : 0));
        }
        r.n = big->n;
        r.neg = big->neg;
    }
    ex_trim(&r);
    return r;
}

static EX_UNUSED exq ex_neg(exq a)
{
    if (a.n > 0)
        a.neg = !a.neg;
    return a;
}

static EX_UNUSED exq ex_sub(exq a, exq b)
{
    return ex_add(a, ex_neg(b));
}

static EX_UNUSED exq ex_mul(const exq a, const exq b)
{
    exq r;
    memset(&r, 0, sizeof r);
    if (a.n == 0 || b.n == 0)
        return r;
    if (a.n + b.n > EX_LIMBS)
        ex_overflow();
    for (int i = 0; i < a.n; i++) {
        uint64_t carry = 0;
        for (int j = 0; j < b.n; j++) {
            uint64_t s = (uint64_t)a.mag[i] * b.mag[j] + r.mag[i + j] + carry;
            r.mag[i + j] = (uint32_t)s;
            carry = s >> 32;
        }
        r.mag[i + b.n] = (uint32_t)carry;
    }
    r.n = a.n + b.n;
    r.exp = a.exp + b.exp;
    r.neg = a.neg != b.neg;
    ex_trim(&r);
    return r;
}

static EX_UNUSED int ex_sign(const exq a)
{
    return a.n == 0 ? 0 : a.neg ? -1 : 1;
}

/* ---------------------------------------------------- geometry helpers */

/* v = p - q, exactly. */
static EX_UNUSED void ex_diff3(const double p[3], const double q[3], exq v[3])
{
    for (int k = 0; k < 3; k++)
        v[k] = ex_sub(ex_of(p[k]), ex_of(q[k]));
}

static EX_UNUSED void ex_cross(const exq a[3], const exq b[3], exq out[3])
{
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        out[i] = ex_sub(ex_mul(a[j], b[k]), ex_mul(a[k], b[j]));
    }
}

static EX_UNUSED exq ex_dot(const exq a[3], const exq b[3])
{
    return ex_add(ex_add(ex_mul(a[0], b[0]), ex_mul(a[1], b[1])), ex_mul(a[2], b[2]));
}

static EX_UNUSED void ex_of3(const double v[3], exq out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = ex_of(v[k]);
}

/* sign(n1/d1 - n2/d2) for nonzero d1, d2. */
static EX_UNUSED int ex_ratio_cmp(exq n1, exq d1, exq n2, exq d2)
{
    return ex_sign(ex_sub(ex_mul(n1, d2), ex_mul(n2, d1))) * ex_sign(d1) * ex_sign(d2);
}

/* The crossing of the line o + t d with the plane of triangle a, b, c:
 * t = num/den, num = N.(a - o), den = N.d, N = (b - a) x (c - a). */
static EX_UNUSED void ex_triangle_crossing(const double o[3], const double d[3], const double a[3],
                                 const double b[3], const double c[3], exq *num, exq *den)
{
    exq e1[3], e2[3], n[3], ao[3], dd[3];
    ex_diff3(b, a, e1);
    ex_diff3(c, a, e2);
    ex_cross(e1, e2, n);
    ex_diff3(a, o, ao);
    ex_of3(d, dd);
    *num = ex_dot(n, ao);
    *den = ex_dot(n, dd);
}

/* The crossing of the line o + t d with a polygon's plane (the Newell
 * normal N = sum_i v_i x v_{i+1} through the vertex centroid S/n, as
 * isect.h defines it): t = N.(S - n o) / (n N.d). v: n x 3, or with idx. */
static EX_UNUSED void ex_polygon_crossing(const double o[3], const double d[3], const double *v,
                                const int32_t *idx, int n, exq *num, exq *den)
{
    exq N[3], S[3], c[3], a[3], b[3], dd[3], on[3];
    for (int k = 0; k < 3; k++)
        N[k] = S[k] = ex_of(0.0);
    for (int i = 0; i < n; i++) {
        const double *p = v + 3 * (idx ? idx[i] : i), *q = v + 3 * (idx ? idx[(i + 1) % n] : (i + 1) % n);
        ex_of3(p, a);
        ex_of3(q, b);
        ex_cross(a, b, c);
        for (int k = 0; k < 3; k++) {
            N[k] = ex_add(N[k], c[k]);
            S[k] = ex_add(S[k], a[k]);
        }
    }
    ex_of3(d, dd);
    exq nn = ex_of((double)n);
    for (int k = 0; k < 3; k++)
        on[k] = ex_sub(S[k], ex_mul(nn, ex_of(o[k])));
    *num = ex_dot(N, on);
    *den = ex_mul(nn, ex_dot(N, dd));
}

#endif /* ISECT_TEST_EXACT_DYADIC_H */
