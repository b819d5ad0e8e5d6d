/* SPDX-License-Identifier: Apache-2.0 */
/*
 * dyadic_sum.h — the exact sign (and a rounded value) of a sum of products
 * of up to three doubles, whatever their exponents: for exact predicates
 * whose inputs may span more than the double range allows a product of
 * them to be held (a ray direction with a subnormal component beside a
 * normal one, an origin a few 2^-1074 off a coordinate plane), where
 * scaling everything by one power of two (core/expansion.h's callers)
 * would round the small inputs or underflow their products.
 *
 * Each product is formed exactly as a four-part expansion of numbers in
 * (2^-162, 1) times 2^E, E an int: every factor is first scaled by its own
 * power of two into [0.5, 1) (exact for any finite double, subnormals
 * included), then multiplied by TwoProduct. The terms are summed from the
 * largest E down into one expansion (core/expansion.h) carried with a base
 * exponent: a term within 2^900 of the base is added scaled (exactly: its
 * parts stay above 2^-1062), and before one further down is added, either
 * the sum so far exceeds 2^60 times the total of everything left (then its
 * sign is the sum's, and its leading part the value to ~2^-52) or it is
 * small enough to move the base down to that term's exponent exactly. No
 * step underflows or overflows, so the result is exact for every finite
 * input.
 */
#ifndef ISECT_DYADIC_SUM_H
#define ISECT_DYADIC_SUM_H

#define DYADIC_SUM_TERMS 24

typedef struct dyadic_sum {
    int    count;
    int    exp[DYADIC_SUM_TERMS];      /* E of each product */
    double part[DYADIC_SUM_TERMS][4];  /* its exact parts, times 2^-E */
} dyadic_sum;

/* An empty sum. */
void dyadic_init(dyadic_sum *s);

/* Adds sign * a * b * c (sign +1 or -1; c = 1.0 for a product of two). At
 * most DYADIC_SUM_TERMS products with no zero factor are kept; products
 * with a zero factor are dropped (they add nothing). */
void dyadic_add3(dyadic_sum *s, double sign, double a, double b, double c);

/* The exact sign of the sum: -1, 0 or +1. */
int dyadic_sign(const dyadic_sum *s);

/* The sum as m * 2^(*e), m within a relative 2^-52 of the exact value
 * divided by 2^(*e), |m| in [0.5, 1) unless the sum is 0 (then m = 0 and *e = 0). */
double dyadic_value(const dyadic_sum *s, int *e);

#endif /* ISECT_DYADIC_SUM_H */
