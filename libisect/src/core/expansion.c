/* SPDX-License-Identifier: Apache-2.0 */
/*
 * expansion.c — exact expansion arithmetic (see expansion.h).
 */
#include "core/expansion.h"

#include "core/predicates.h"

#include <math.h>
#include <string.h>

/* s + e = a + b exactly (Knuth's TwoSum). */
static void two_sum(double a, double b, double *s, double *e)
{
    double sum = a + b;
    double b_virtual = sum - a;
    double a_virtual = sum - b_virtual;
    *e = (a - a_virtual) + (b - b_virtual);
    *s = sum;
}

void xp_set(xp *x, double a)
{
    x->n = 0;
    if (a != 0.0)
        x->p[x->n++] = a;
}

/* Keeps the XP_CAP largest parts of an expansion that would not fit (see
 * expansion.h: not reached by the library's callers). */
static void xp_keep_largest(xp *x)
{
    if (x->n <= XP_CAP - 1)
        return;
    int drop = x->n - (XP_CAP - 1);
    memmove(x->p, x->p + drop, (size_t)(XP_CAP - 1) * sizeof x->p[0]);
    x->n = XP_CAP - 1;
}

/* Adds one double, carrying it up through the parts (Shewchuk's
 * GROW-EXPANSION) and dropping zero remainders: the parts stay
 * nonoverlapping and increasing; at most one part is added. */
void xp_add_d(xp *x, double a)
{
    if (a == 0.0)
        return;
    xp_keep_largest(x);
    double carry = a;
    int kept = 0;
    for (int i = 0; i < x->n; i++) {
        double sum, err;
        two_sum(carry, x->p[i], &sum, &err);
        if (err != 0.0)
            x->p[kept++] = err;
        carry = sum;
    }
    if (carry != 0.0)
        x->p[kept++] = carry;
    x->n = kept;
}

void xp_set2(xp *x, double hi, double lo)
{
    xp_set(x, lo);
    xp_add_d(x, hi);
}

/*
 * Renormalise in place to few parts: a pass from the top folds each part
 * into a running sum while the sum absorbs it exactly (a nonzero rounding
 * error starts a new part), then a pass from the bottom does the same the
 * other way (Shewchuk's COMPRESS). The value is unchanged; the parts stay
 * nonoverlapping and increasing, and the largest part approximates the
 * value to within an ulp.
 */
static void xp_compress(xp *x)
{
    if (x->n < 2)
        return;
    double g[XP_CAP];
    int bottom = x->n - 1;
    double q_run = x->p[bottom];
    for (int i = x->n - 2; i >= 0; i--) {
        double sum = q_run + x->p[i];          /* |q_run| >= |p[i]|: Fast2Sum */
        double err = x->p[i] - (sum - q_run);
        if (err != 0.0) {
            g[bottom--] = sum;
            q_run = err;
        } else {
            q_run = sum;
        }
    }
    int top = 0;
    for (int i = bottom + 1; i < x->n; i++) {
        double sum = g[i] + q_run;             /* |g[i]| >= |q_run| */
        double err = q_run - (sum - g[i]);
        if (err != 0.0)
            x->p[top++] = err;
        q_run = sum;
    }
    x->p[top++] = q_run;
    x->n = q_run == 0.0 ? top - 1 : top;
}

void xp_add(xp *out, const xp *a, const xp *b)
{
    xp sum = *a;
    for (int i = 0; i < b->n; i++)
        xp_add_d(&sum, b->p[i]);
    xp_compress(&sum);
    *out = sum;
}

void xp_sub(xp *out, const xp *a, const xp *b)
{
    xp sum = *a;
    for (int i = 0; i < b->n; i++)
        xp_add_d(&sum, -b->p[i]);
    xp_compress(&sum);
    *out = sum;
}

void xp_scale(xp *out, const xp *a, double b)
{
    xp prod;
    prod.n = 0;
    if (b != 0.0) {
        for (int i = 0; i < a->n; i++) {
            double p = a->p[i] * b;
            xp_add_d(&prod, product_error(a->p[i], b, p));
            xp_add_d(&prod, p);
        }
    }
    xp_compress(&prod);
    *out = prod;
}

void xp_mul(xp *out, const xp *a, const xp *b)
{
    xp_set(out, 0.0);
    for (int j = 0; j < b->n; j++) {
        xp term;
        xp_scale(&term, a, b->p[j]);
        xp_add(out, out, &term);
    }
}

void xp_diff(xp *x, double a, double b)
{
    double s, e;
    two_sum(a, -b, &s, &e);
    xp_set2(x, s, e);
}

void xp_add_mul(xp *acc, const xp *a, const xp *b)
{
    xp prod;
    xp_mul(&prod, a, b);
    xp_add(acc, acc, &prod);
}

int xp_sign(const xp *x)
{
    if (x->n == 0)
        return 0;
    return x->p[x->n - 1] > 0.0 ? 1 : -1;
}

/* Summing the parts from the smallest up rounds each partial sum, with
 * total error below u times the value (the parts are nonoverlapping); the
 * exact remainder value - hi, summed again, is within u^2 |value|. */
void xp_dd(const xp *x, double *hi, double *lo)
{
    double h = 0.0;
    for (int i = 0; i < x->n; i++)
        h += x->p[i];
    xp rest = *x;
    xp_add_d(&rest, -h);
    double l = 0.0;
    for (int i = 0; i < rest.n; i++)
        l += rest.p[i];
    /* hi + lo renormalised so that hi is the value rounded */
    double s, e;
    two_sum(h, l, &s, &e);
    *hi = s;
    *lo = e;
}
