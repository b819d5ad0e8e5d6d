/* SPDX-License-Identifier: Apache-2.0 */
/*
 * plane.c — the infinite plane n.x + d = 0 (ISECT_PLANE), data = n[3], d.
 * A thin surface: one hit or none, no containment.
 *
 * The fast kernel (plane_lanes.h) decides almost every ray; this file adds
 * the exact path for the rest. Parallel (the epsilon policy) when
 * (n.dir)^2 <= eps^2 |n|^2 |dir|^2, decided exactly; a parallel plane,
 * including one the ray lies in, is not hit. Otherwise t = -(n.o + d)/(n.dir),
 * kept exactly when it lies in [tmin, tmax] (core/ratio.c), reported to
 * about an ulp; a t beyond the double range is not a point of the ray and
 * is not reported; t = 0 is +0.0. The kind comes from the sign of n.dir
 * (ENTER when the ray meets the front side).
 *
 * Numerics of the exact path. n and d are scaled by the power of two of n,
 * then o and d by that of the larger of |o| and the scaled d, and dir by
 * its own (all exact): num and den are then sums of products of doubles of
 * moderate size, exact as expansions, and t = -num/den 2^(e_o - e_dir).
 */
#include "prim/prim.h"
#include "prim/plane_lanes.h"
#include "core/dyadic_sum.h"
#include "core/expansion.h"
#include "core/scaling.h"
#include "core/ratio.h"
#include "core/vec3.h"

static int plane_exact(const double *data, const isect_ray *ray, double eps,
                       isect_hit out[ISECT_MAX_HITS])
{
    double n[3], o[3], dir[3];
    int e_n = pow2_exponent(max_abs3(data));
    scale3(n, data, e_n);
    double d = pow2_scale(data[3], -e_n);
    int e_o = pow2_exponent(fmax_nan(max_abs3(ray->org), fabs(d)));
    scale3(o, ray->org, e_o);
    d = pow2_scale(d, -e_o);
    int e_dir = pow2_exponent(max_abs3(ray->dir));
    scale3(dir, ray->dir, e_dir);
    int t_shift = e_o - e_dir;

    xp num, den, tmp, nn, dd;
    xp_set(&num, -d);
    xp_set(&den, 0.0);
    xp_set(&nn, 0.0);
    xp_set(&dd, 0.0);
    for (int k = 0; k < 3; k++) {
        xp_set(&tmp, n[k]);
        xp_scale(&tmp, &tmp, -o[k]);
        xp_add(&num, &num, &tmp);
        xp_set(&tmp, n[k]);
        xp_scale(&tmp, &tmp, dir[k]);
        xp_add(&den, &den, &tmp);
        xp_set(&tmp, n[k]);
        xp_scale(&tmp, &tmp, n[k]);
        xp_add(&nn, &nn, &tmp);
        xp_set(&tmp, dir[k]);
        xp_scale(&tmp, &tmp, dir[k]);
        xp_add(&dd, &dd, &tmp);
    }
    if (parallel_exact(&den, &nn, &dd, eps))
        return 0;

    int in_range;
    double t_hi, t_lo;
    if (!ratio_decide(&num, &den, pow2_scale(ray->tmin, -t_shift), pow2_scale(ray->tmax, -t_shift),
                      &in_range, &t_hi, &t_lo) || !in_range)
        return 0;
    double t = pow2_scale(t_hi, t_shift);
    if (!isfinite(t))
        return 0;
    /* The record: t clamped into the interval, the point from t as a
     * double-double (in scaled units, then scaled back). */
    lane_ray lr;
    isect_ray scaled = { { o[0], o[1], o[2] }, { dir[0], dir[1], dir[2] },
                         pow2_scale(ray->tmin, -t_shift), pow2_scale(ray->tmax, -t_shift) };
    lane_ray_from(&lr, &scaled);
    vdd tv = { t_hi, t_lo };
    double p[3];
    lane_point_on_ray(&lr, tv, p);
    isect_hit *h = &out[0];
    h->t = fmin(fmax(t, ray->tmin), ray->tmax) + 0.0;
    for (int k = 0; k < 3; k++)
        h->point[k] = pow2_scale(p[k], e_o);
    if (!unit3_accurate(h->normal, data))
        return 0;
    h->uv[0] = h->uv[1] = 0.0;
    h->prim = -1;
    h->kind = xp_sign(&den) < 0 ? ISECT_ENTER : ISECT_EXIT;
    return 1;
}

int plane_check(const isect_shape *s)
{
    return all_finite(s->data, 4) ? ISECT_OK : ISECT_E_NONFINITE;
}

int plane_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
               isect_hit out[ISECT_MAX_HITS])
{
    plane_prep pp;
    plane_prepare(s->data, prm->eps, &pp);
    if (pp.degenerate)
        return 0; /* zero normal */
    lane_ray lr;
    lane_ray_from(&lr, ray);
    lane_hit h;
    plane_lanes_first(&pp, &lr, &h);
    if (h.slow)
        return plane_exact(s->data, ray, prm->eps, out);
    if (!h.found)
        return 0;
    lane_hit_store(&h, 0, &out[0]);
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

/* n.d exactly, whatever the exponents of n and d (dyadic_sum: a subnormal
 * component of d beside a normal one). */
int plane_tangent_side(const isect_shape *s, const double d[3], int32_t prim)
{
    (void)prim;
    dyadic_sum dot;
    dyadic_init(&dot);
    for (int k = 0; k < 3; k++)
        dyadic_add3(&dot, 1.0, s->data[k], d[k], 1.0);
    return dyadic_sign(&dot);
}
