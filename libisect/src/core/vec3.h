/* SPDX-License-Identifier: Apache-2.0 */
/*
 * vec3.h — the small amount of 3-vector arithmetic every primitive needs.
 * Plain double[3] arrays (no struct) so data can be passed straight from the
 * caller's buffers.
 */
#ifndef ISECT_VEC3_H
#define ISECT_VEC3_H

#include <math.h>

static inline void v3_set(double r[3], double x, double y, double z)
{
    r[0] = x; r[1] = y; r[2] = z;
}
static inline void v3_copy(double r[3], const double a[3])
{
    r[0] = a[0]; r[1] = a[1]; r[2] = a[2];
}
static inline void v3_sub(double r[3], const double a[3], const double b[3])
{
    r[0] = a[0] - b[0]; r[1] = a[1] - b[1]; r[2] = a[2] - b[2];
}
static inline void v3_add(double r[3], const double a[3], const double b[3])
{
    r[0] = a[0] + b[0]; r[1] = a[1] + b[1]; r[2] = a[2] + b[2];
}
static inline void v3_scale(double r[3], const double a[3], double s)
{
    r[0] = a[0] * s; r[1] = a[1] * s; r[2] = a[2] * s;
}
/* r = a + s*b */
static inline void v3_madd(double r[3], const double a[3], double s, const double b[3])
{
    r[0] = a[0] + s * b[0]; r[1] = a[1] + s * b[1]; r[2] = a[2] + s * b[2];
}
static inline double v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline void v3_cross(double r[3], const double a[3], const double b[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    r[0] = x; r[1] = y; r[2] = z;
}
/* max(|a0|, |a1|, |a2|) ignoring NaN components, exactly as the nested
 * fmax(fabs(.), ...) it replaces (all NaN: NaN), but as maxsd selects: without
 * -ffast-math fmax is a libm call, and a compare-and-branch would
 * mispredict on random rays. b > m ? b : m keeps m when b is NaN; the
 * second select (never taken for finite input) drops a NaN m for b. */
static inline double v3_fmax_nan(double m, double b)
{
    double r = b > m ? b : m;
    return r != r ? b : r;
}
static inline double v3_max_abs(const double a[3])
{
    return v3_fmax_nan(fabs(a[0]), v3_fmax_nan(fabs(a[1]), fabs(a[2])));
}
/* max(|a0|, |a1|, |a2|) by two plain selects, for hot paths: a NaN a0 is
 * returned (so an all-NaN a gives NaN), a NaN a1 or a2 is passed over;
 * v3_max_abs, which ignores every NaN component, costs a select more per
 * step. */
static inline double v3_max_abs_finite(const double a[3])
{
    double m = fabs(a[0]);
    m = fabs(a[1]) > m ? fabs(a[1]) : m;
    return fabs(a[2]) > m ? fabs(a[2]) : m;
}
/* |a| without overflow or underflow for any finite a (hypot-style scaling). */
static inline double v3_norm(const double a[3])
{
    double m = v3_max_abs(a);
    if (m == 0.0 || !isfinite(m))
        return m;
    double x = a[0] / m, y = a[1] / m, z = a[2] / m;
    return m * sqrt(x * x + y * y + z * z);
}
/* r = a/|a|; returns |a| (0 leaves r = 0). Divides by the largest
 * component first, so a vector of subnormal length (whose reciprocal length
 * would overflow) still comes out unit. */
static inline double v3_normalize(double r[3], const double a[3])
{
    double m = v3_max_abs(a);
    if (!(m > 0.0) || !isfinite(m)) {
        v3_set(r, 0.0, 0.0, 0.0);
        return m;
    }
    double x = a[0] / m, y = a[1] / m, z = a[2] / m;
    double s = sqrt(x * x + y * y + z * z);
    v3_set(r, x / s, y / s, z / s);
    return m * s;
}

#endif /* ISECT_VEC3_H */
