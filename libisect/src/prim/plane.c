/*
 * plane.c — the infinite plane n.x + d = 0 (ISECT_PLANE), data = n[3], d.
 * A thin surface: one hit or none, no containment.
 *
 * Numerics. n and dir are each scaled by a power of two (exact, barring
 * underflow of components 2^1022 times smaller than the largest one, which
 * cannot change a result) so that their largest component lies in [0.5, 1).
 * Then n.dir, |n|, |dir| cannot overflow whatever the caller's scale (normals
 * of 1e300 or directions of 1e-300 are fine), and every ratio and sign is the
 * one of the plane as given:
 *   parallel  |n'.dir'| <= eps |n'| |dir'|   (the policy test, scale-free)
 *   t         -(n'.org + d') / (n'.dir') * 2^-e_dir
 * A t beyond the double range (a nearly parallel ray with eps near 0, or
 * coordinates near DBL_MAX) is not a point of the ray and is not reported,
 * so no inf or NaN reaches the output. t = 0 is reported as +0.0.
 */
#include "prim/prim.h"
#include "core/expansion.h"
#include "core/quadratic.h"
#include "core/vec3.h"

/* v' = v * 2^-e with e the exponent of max|v_i| (frexp), so max|v'_i| is in
 * [0.5, 1); returns e. A zero vector stays zero (e = 0). */
static int scale_to_unit_exponent(double out[3], const double v[3])
{
    int e;
    (void)frexp(fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))), &e);
    for (int i = 0; i < 3; i++)
        out[i] = ldexp(v[i], -e);
    return e;
}

int plane_check(const isect_shape *s)
{
    return all_finite(s->data, 4) ? ISECT_OK : ISECT_E_NONFINITE;
}

int plane_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
               isect_hit out[ISECT_MAX_HITS])
{
    double n[3], dir[3], normal[3];
    int e_n = scale_to_unit_exponent(n, s->data);
    int e_dir = scale_to_unit_exponent(dir, ray->dir);
    double n_len = sqrt(v3_dot(n, n));
    if (n_len == 0.0)
        return 0; /* zero normal: degenerate */
    double d = ldexp(s->data[3], -e_n);

    double n_dot_dir = v3_dot(n, dir);
    if (fabs(n_dot_dir) <= prm->eps * n_len * sqrt(v3_dot(dir, dir)))
        return 0; /* parallel, including a ray lying in the plane */

    double t = ldexp(-(v3_dot(n, ray->org) + d) / n_dot_dir, -e_dir) + 0.0;
    if (!isfinite(t))
        return 0;
    for (int i = 0; i < 3; i++)
        normal[i] = n[i] / n_len;
    /* dir' has the signs of dir and cannot overflow the dot product. */
    hit_set(&out[0], ray, t, normal, -1, hit_kind_from_normal(dir, normal));
    return 1;
}

/* n.p + d exactly: n and d scaled by the power of two of n, then p and d by
 * that of the larger of p and the scaled d (the sign is kept). */
int plane_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    double n[3], q[3];
    int e_n = pow2_exponent(max_abs3(s->data));
    if (max_abs3(s->data) == 0.0)
        return 1; /* degenerate */
    scale3(n, s->data, e_n);
    double d = pow2_scale(s->data[3], -e_n);
    int e_p = pow2_exponent(fmax_nan(max_abs3(p), fabs(d)));
    scale3(q, p, e_p);
    xp sum, term;
    xp_set(&sum, pow2_scale(d, -e_p));
    for (int k = 0; k < 3; k++) {
        xp_set(&term, n[k]);
        xp_scale(&term, &term, q[k]);
        xp_add(&sum, &sum, &term);
    }
    return xp_sign(&sum);
}
