/* SPDX-License-Identifier: Apache-2.0 */
/*
 * expansion.h — exact arithmetic on floating-point expansions, for the
 * exact paths that the fast kernels defer to (rarely: decisions within a
 * rounding error, near-tangent and near-surface rays).
 *
 * An expansion is an unevaluated sum of doubles, nonoverlapping and in
 * increasing magnitude with no zero parts (Priest; Shewchuk, "Adaptive
 * Precision Floating-Point Arithmetic and Fast Robust Geometric
 * Predicates", DCG 1997): its value is exact, its sign is that of its
 * largest part. Sums and products of expansions are formed exactly with
 * TwoSum and TwoProduct, then compressed (so the parts stay few).
 *
 * Exactness. Every operation is exact while no partial product underflows
 * (falls below 2^-1022 with bits below 2^-1074) and nothing overflows. The
 * callers scale their input by powers of two first (exact) so that the
 * largest number is near 1; then a product of k inputs is exact while each
 * of its factors is above 2^(-1000/k) of that largest number. Beyond that
 * range the results are still deterministic, and wrong by at most a few
 * 2^-1074 in absolute terms. XP_CAP parts always suffice for the degree-4
 * polynomials of the callers (a compressed expansion has at most one part
 * per 53 bits of its exponent range); a result that would not fit keeps its
 * XP_CAP largest parts.
 */
#ifndef ISECT_EXPANSION_H
#define ISECT_EXPANSION_H

#define XP_CAP 128

typedef struct xp {
    int    n;
    double p[XP_CAP];
} xp;

/* x = a (exact). */
void xp_set(xp *x, double a);
/* x = hi + lo (exact; any two doubles). */
void xp_set2(xp *x, double hi, double lo);
/* x = x + a (exact). */
void xp_add_d(xp *x, double a);
/* out = a + b; out = a - b (exact; out may be a or b). */
void xp_add(xp *out, const xp *a, const xp *b);
void xp_sub(xp *out, const xp *a, const xp *b);
/* out = a * b (exact; out may be a). */
void xp_scale(xp *out, const xp *a, double b);
/* out = a * b (exact; out must differ from a and b). */
void xp_mul(xp *out, const xp *a, const xp *b);
/* x = a - b (exact). */
void xp_diff(xp *x, double a, double b);
/* acc = acc + a * b (exact). */
void xp_add_mul(xp *acc, const xp *a, const xp *b);
/* -1, 0 or +1: the sign of the exact value. */
int xp_sign(const xp *x);
/* hi + lo = the value to within 2u^2 |value| (hi the value rounded,
 * |lo| <= ulp(hi)/2). */
void xp_dd(const xp *x, double *hi, double *lo);

#endif /* ISECT_EXPANSION_H */
