/* SPDX-License-Identifier: Apache-2.0 */
/*
 * quad_line.h — the crossings of a line with a quadric surface, certified
 * from double-double coefficients or decided exactly, for the quadric
 * family (ellipsoid, cylinder side, general quadric; the sphere's lane
 * kernel shares the ideas).
 *
 * A family writes its surface along the line as the quadratic
 *     Q(t) = A t^2 + 2B t + C     (inside where Q < 0),
 * in its own scaled units, with the reduced discriminant G = B^2 - A C and
 * two thresholds from the epsilon policy: the tangency threshold T >= 0 (a
 * single TOUCH when |G| <= T; T = 0: only an exact double root touches) and
 * the linear threshold L >= 0 (the quadratic term dropped when |A| <= L: a
 * ray along a cone's generator or a paraboloid's axis; L = 0: only A == 0).
 *
 * Two ways to the same answer:
 *  - quad_line_certify(): from A, B, C, G as double-doubles with absolute
 *    error bounds (the family forms them with error-free products and
 *    compensated sums, and G in whatever form avoids cancellation: Haines'
 *    r^2 |d|^2 - |f x d|^2 for spheres and ellipsoids, the distance of two
 *    lines for cylinders), it either certifies the answer — no crossing, or
 *    two distinct crossings, each within 1.5 ulp of the exact root, each
 *    interval decision and kind certain — or declines (returns 0).
 *  - quad_line_exact(): A, B, C, T, L as exact expansions: every decision
 *    exact, the roots to a few u^2.
 * Both report the same crossings (the decisions are exact in both), so a
 * certified answer and an exact one differ at most in the last bit of t.
 *
 * Root formulas (both): with sigma = sign(B) and q = -(B + sigma sqrt(G))
 * (no cancellation), the roots are q/A and C/q; the entry into Q < 0 is
 * r- = (-B - sqrt(G))/A, where Q' = -2 sqrt(G) < 0, the exit r+ (for A > 0
 * the entry comes first, for A < 0 last). A root C/q with C == 0 is 0
 * exactly (an origin on the surface).
 *
 * Exact decisions, from signs only: with s = A tau + B,
 *     tau - r- has the sign of A (s + sqrt(G)),  tau - r+ that of A (s - sqrt(G)),
 * where s + sqrt(G) is positive when s >= 0 and has the sign of G - s^2 =
 * -A Q(tau) otherwise, and s - sqrt(G) is negative when s <= 0 and has the
 * sign of s^2 - G = A Q(tau) otherwise (tau between tmin and tmax: a root
 * lies in [tmin, tmax] iff tmin - r <= 0 <= tmax - r).
 */
#ifndef ISECT_QUAD_LINE_H
#define ISECT_QUAD_LINE_H

#include "core/ddx.h"
#include "core/expansion.h"

/* Which root a reported crossing is (for exact comparisons). */
enum {
    QL_ROOT_MINUS  = -1, /* (-B - sqrt(G))/A: the entry */
    QL_ROOT_PLUS   = 1,  /* (-B + sqrt(G))/A: the exit */
    QL_ROOT_TOUCH  = 0,  /* -B/A, the tangency rule's single crossing */
    QL_ROOT_LINEAR = 2   /* -C/(2B), the linear case's */
};

/* The answer of either path, t in the family's scaled units. */
typedef struct quad_line_roots {
    int    count;            /* crossings: 0, 1 (a touch, or the linear case), 2 */
    int    touch;            /* count 1 by the tangency rule */
    double t_hi[2], t_lo[2]; /* increasing; each a renormalised double-double */
    double err[2];           /* |exact root - (t_hi + t_lo)| <= err */
    int    which[2];         /* QL_ROOT_* */
    int    in[2];            /* the exact root lies in [tmin, tmax] */
    int    enter[2];         /* Q' < 0 there (into the inside); a touch: 0 */
} quad_line_roots;

/* A, B, C, G as double-doubles with error bounds, and upper bounds for the
 * thresholds T and L. */
typedef struct quad_line_dd {
    ddx    a, b, c, g;
    double t_thr;            /* >= T */
    double l_thr;            /* >= L */
} quad_line_dd;

/* 1 and *out filled when certified (see above); 0 when not: a touch, a
 * linear or near-linear A, a discriminant or a decision within its error
 * bound, or a root not certain to 1.5 ulp. tmin = -inf, tmax = +inf ask
 * for the roots alone (every decision then certain). */
int quad_line_certify(const quad_line_dd *q, double tmin, double tmax, quad_line_roots *out);

/* The exact answer; t_thr and l_thr may be NULL (0). The values are within
 * 64u^2 of each root (err says so). */
void quad_line_exact(const xp *a, const xp *b, const xp *c, const xp *t_thr, const xp *l_thr,
                     double tmin, double tmax, quad_line_roots *out);

/* sign(r - num/den), exactly, for the root r of kind `which` of the exact
 * line function A, B, C (den != 0; a double tau is num = tau, den = 1). */
int quad_line_cmp(const xp *a, const xp *b, const xp *c, int which, const xp *num,
                  const xp *den);

#endif /* ISECT_QUAD_LINE_H */
