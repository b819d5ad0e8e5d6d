/* SPDX-License-Identifier: Apache-2.0 */
/*
 * frame_signs.c — exact signs of the sheared frame (see frame_signs.h).
 *
 * Each quantity is written out as a sum of products of the input doubles
 * (the differences v - o expanded, the terms in o o cancelling exactly
 * where they would appear) and handed to core/dyadic_sum.c, which sums
 * products of any exponents exactly: an origin a few 2^-1074 off an axis
 * plane, or a direction with subnormal components beside normal ones, is
 * decided as exactly as any other ray.
 */
#include "core/frame_signs.h"

#include "core/dyadic_sum.h"
#include <math.h>

/* s += sign (A x d)[i] with A = p - q: p_j d_k - q_j d_k - p_k d_j + q_k d_j. */
static void add_cross_d(dyadic_sum *s, double sign, const double p[3], const double q[3],
                        const double d[3], int i)
{
    int j = (i + 1) % 3, k = (i + 2) % 3;
    dyadic_add3(s, sign, p[j], d[k], 1.0);
    dyadic_add3(s, -sign, q[j], d[k], 1.0);
    dyadic_add3(s, -sign, p[k], d[j], 1.0);
    dyadic_add3(s, sign, q[k], d[j], 1.0);
}

/* s = d . ((p - o) x (q - o)) = sum_i d_i (p_j q_k - p_k q_j - p_j o_k + p_k o_j
 * - o_j q_k + o_k q_j): the o_j o_k terms cancel. */
static void set_triple(dyadic_sum *s, const double p[3], const double q[3], const double o[3],
                       const double d[3])
{
    dyadic_init(s);
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        dyadic_add3(s, 1.0, d[i], p[j], q[k]);
        dyadic_add3(s, -1.0, d[i], p[k], q[j]);
        dyadic_add3(s, -1.0, d[i], p[j], o[k]);
        dyadic_add3(s, 1.0, d[i], p[k], o[j]);
        dyadic_add3(s, -1.0, d[i], o[j], q[k]);
        dyadic_add3(s, 1.0, d[i], o[k], q[j]);
    }
}

int frame_above_exact(const ray_frame *f, const double v[3])
{
    dyadic_sum s;
    dyadic_init(&s);
    add_cross_d(&s, 1.0, v, f->org, f->dir, f->kx); /* |d[kz]| y */
    return dyadic_sign(&s) >= 0;
}

int frame_orient_exact(const ray_frame *f, const double p[3], const double q[3])
{
    dyadic_sum s;
    set_triple(&s, p, q, f->org, f->dir);
    int sign = dyadic_sign(&s);
    if (sign != 0)
        return sign;
    /* The perturbation (-e^2, -e) of the query point: orient(p, q) gains
     * e (x_p - x_q) + e^2 (y_q - y_p) (predicates.h). With D = p - q (the
     * origin cancels), |d[kz]| (x_p - x_q) = -(D x d)[ky] and |d[kz]|
     * (y_q - y_p) = -(D x d)[kx]. */
    dyadic_init(&s);
    add_cross_d(&s, -1.0, p, q, f->dir, f->ky);
    sign = dyadic_sign(&s);
    if (sign != 0)
        return sign;
    dyadic_init(&s);
    add_cross_d(&s, -1.0, p, q, f->dir, f->kx);
    return dyadic_sign(&s);
}

void frame_triangle_weights_exact(const ray_frame *f, const double a[3], const double b[3],
                                  const double c[3], double w[3])
{
    const double *v[3] = { a, b, c };
    double m[3];
    int e[3], top = 0, any = 0;
    for (int i = 0; i < 3; i++) {
        dyadic_sum s;
        set_triple(&s, v[(i + 1) % 3], v[(i + 2) % 3], f->org, f->dir);
        m[i] = dyadic_value(&s, &e[i]);
        if (m[i] != 0.0 && (!any || e[i] > top))
            top = e[i];
        any |= m[i] != 0.0;
    }
    /* one common power of two: the largest weight near 1, the others
     * scaled alike (those below 2^-1074 of it round to zero) */
    for (int i = 0; i < 3; i++)
        w[i] = m[i] == 0.0 ? 0.0 : ldexp(m[i], e[i] - top);
}
