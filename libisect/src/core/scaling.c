/* SPDX-License-Identifier: Apache-2.0 */
/*
 * scaling.c — see scaling.h.
 */
#include "core/scaling.h"

#include "core/predicates.h"
#include "core/vec3.h"

#include <math.h>

int pow2_exponent_slow(double m)
{
    int e = 0;
    (void)frexp(m, &e); /* frexp(0) sets e = 0 */
    return e;
}


void cross_accurate(double r[3], const double x[3], const double y[3])
{
    double c0 = det2_accurate(x[1], x[2], y[1], y[2]);
    double c1 = det2_accurate(x[2], x[0], y[2], y[0]);
    double c2 = det2_accurate(x[0], x[1], y[0], y[1]);
    v3_set(r, c0, c1, c2);
}

int unit3(double out[3], const double v[3])
{
    /* per component: fmax (in max_abs3) would ignore a NaN */
    if (!(isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2])) || max_abs3(v) == 0.0) {
        v3_set(out, 0.0, 0.0, 0.0);
        return 0;
    }
    double s[3];
    scale3(s, v, pow2_exponent(max_abs3(v))); /* largest component in [0.5, 1) */
    double len = sqrt(v3_dot(s, s));
    for (int k = 0; k < 3; k++)
        out[k] = s[k] / len + 0.0; /* + 0.0: never -0.0 */
    return 1;
}

int unit3_accurate(double out[3], const double v[3])
{
    if (!unit3(out, v))
        return 0;
    /* |n|^2 = 1 + e: exact squares, compensated sum, then n (3 - |n|^2)/2
     * as n + n delta (prim_lanes.h: lane_unit_newton, the same step) */
    comp_sum nn = { 0.0, 0.0 };
    for (int k = 0; k < 3; k++)
        comp_add_product(&nn, out[k], out[k]);
    double delta = 0.5 * ((1.0 - nn.hi) - nn.lo);
    for (int k = 0; k < 3; k++)
        out[k] = (out[k] + out[k] * delta) + 0.0;
    return 1;
}

void normal_or_facing(double normal[3], const double v[3], const double d[3], int32_t kind)
{
    if (unit3(normal, v))
        return;
    unit3(normal, d);
    if (kind != ISECT_EXIT)
        for (int k = 0; k < 3; k++)
            normal[k] = 0.0 - normal[k];
}
