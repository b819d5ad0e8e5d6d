/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ellipsoid.c — the axis-aligned ellipsoid sum(((x - c)/R)^2) = 1
 * (ISECT_ELLIPSOID, data = c[3], R[3]), a solid; prim -1.
 *
 * The line function. Positions and semi-axes share one power-of-two scale
 * (the largest in [0.5, 1)), the direction its own (both exact), f = o - c
 * is exact as a double-double, and the equation is multiplied by
 * rho^2 = min R^2 so that its weights mu_k = (rho/R_k)^2 are at most 1:
 *     Q(t) = sum mu_k (f_k + t d_k)^2 - rho^2 = A t^2 + 2B t + C,
 *     A = sum mu_k d_k^2,  B = sum mu_k f_k d_k,  C = sum mu_k f_k^2 - rho^2,
 *     G = B^2 - A C = rho^2 A - sum_{i<j} mu_i mu_j (f_i d_j - f_j d_i)^2
 * (Lagrange's identity: Haines' form of the sphere's discriminant, free of
 * the cancellation between B^2 and AC that a ray from afar would suffer).
 * All five are formed as double-doubles with error bounds (core/ddx.h; mu_k
 * as a dd quotient squared) and core/quad_line.c certifies the crossings
 * from them; where it cannot (a touch or near-touch, a decision within the
 * bounds), the exact path forms the same function with exact weights,
 * w_k = prod_{j != k} R_j^2 and W = prod R_j^2 (the equation times W), as
 * expansions, and decides exactly. Exact while the semi-axes lie within a
 * factor 2^80 of each other (partial products of degree 12 stay normal).
 *
 * Tangency: |1 - h'^2| <= eps, h' the distance from the centre to the line
 * in the frame scaled by 1/R (where the ellipsoid is the unit sphere), i.e.
 * |G| <= eps rho^2 A (exact path: eps W A).
 *
 * Records: t from the certified or exact double-double root; the point
 * org + t dir from the double-double t (hit_set_dd: on the surface to an ulp
 * of its coordinates, far rays included); the normal, the gradient
 * mu_k v_k at v = f + t d (v to a few ulps of itself, from the dd t),
 * normalised to u.
 *
 * A zero semi-axis (or one that vanishes at the common scale, ~2^-1074 of
 * the largest) is degenerate: no hits, nothing inside.
 */
#include "prim/prim.h"
#include "prim/ellipsoid_lanes.h"
#include "core/ddx.h"
#include "core/expansion.h"
#include "core/quad_line.h"
#include "core/scaling.h"
#include "core/vec3.h"

/* The ellipsoid and the ray at the common scale. */
typedef struct ellipsoid_frame {
    double rho_s[3]; /* semi-axes 2^-e */
    double o_s[3], c_s[3], d_s[3];
    double rho_min;
    int    e, t_shift; /* positions 2^-e, t = t' 2^t_shift */
} ellipsoid_frame;

static int frame_make(const double *data, const double org[3], const double dir[3],
                      ellipsoid_frame *fr)
{
    const double *c = data, *radii = data + 3;
    if (radii[0] == 0.0 || radii[1] == 0.0 || radii[2] == 0.0)
        return 0;
    fr->e = pow2_exponent(fmax_nan(max_abs3(radii), fmax_nan(max_abs3(org), max_abs3(c))));
    int e_dir = dir != NULL ? pow2_exponent(max_abs3(dir)) : 0;
    scale3(fr->rho_s, radii, fr->e);
    scale3(fr->o_s, org, fr->e);
    scale3(fr->c_s, c, fr->e);
    if (dir != NULL)
        scale3(fr->d_s, dir, e_dir);
    fr->t_shift = fr->e - e_dir;
    fr->rho_min = fmin(fr->rho_s[0], fmin(fr->rho_s[1], fr->rho_s[2]));
    return fr->rho_min > 0.0;
}

/* mu_k = (rho_min / rho_k)^2 as a dd with its bound (ellipsoid_lanes.h:
 * ellipsoid_weight, within 12u^2 mu). */
static ddx weight(double rho_min, double rho_k)
{
    ddx mu;
    ellipsoid_weight(rho_min, rho_k, &mu.hi, &mu.lo);
    mu.err = rho_k == rho_min ? 0.0 : 12.0 * DDX_U * DDX_U * mu.hi + DDX_TINY;
    return mu;
}

static void line_dd(const ellipsoid_frame *fr, double eps, quad_line_dd *q)
{
    ddx mu[3], f[3];
    for (int k = 0; k < 3; k++) {
        mu[k] = weight(fr->rho_min, fr->rho_s[k]);
        f[k] = ddx_diff(fr->o_s[k], fr->c_s[k]);
    }
    ddx rr = ddx_sqr(ddx_of(fr->rho_min));
    ddx a = ddx_of(0.0), b = ddx_of(0.0), c = ddx_neg(rr), perp = ddx_of(0.0);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        a = ddx_add(a, ddx_mul(mu[k], ddx_sqr(ddx_of(fr->d_s[k]))));
        b = ddx_add(b, ddx_mul(mu[k], ddx_mul_d(f[k], fr->d_s[k])));
        c = ddx_add(c, ddx_mul(mu[k], ddx_sqr(f[k])));
        ddx m = ddx_sub(ddx_mul_d(f[i], fr->d_s[j]), ddx_mul_d(f[j], fr->d_s[i]));
        perp = ddx_add(perp, ddx_mul(ddx_mul(mu[i], mu[j]), ddx_sqr(m)));
    }
    ddx g = ddx_sub(ddx_mul(rr, a), perp);
    *q = (quad_line_dd){ a, b, c, g, 0.0, 0.0 };
    q->t_thr = eps * (rr.hi + rr.err) * (ddx_abs(a) + a.err) * (1.0 + 8.0 * DDX_U);
}

/* The exact path: the equation times W = prod rho_k^2, as expansions. */
static void line_exact(const ellipsoid_frame *fr, double eps, double tmin, double tmax,
                       quad_line_roots *out)
{
    xp rr[3], w, f, a, b, c, thr, tmp, tmp2;
    for (int k = 0; k < 3; k++) {
        xp_set(&rr[k], fr->rho_s[k]);
        xp_scale(&rr[k], &rr[k], fr->rho_s[k]);
    }
    xp_set(&a, 0.0);
    xp_set(&b, 0.0);
    xp_mul(&tmp, &rr[0], &rr[1]);
    xp_mul(&c, &tmp, &rr[2]);
    xp_scale(&c, &c, -1.0); /* -W */
    for (int k = 0; k < 3; k++) {
        xp_mul(&w, &rr[(k + 1) % 3], &rr[(k + 2) % 3]);
        xp_diff(&f, fr->o_s[k], fr->c_s[k]);
        xp_scale(&tmp, &w, fr->d_s[k]);   /* w d */
        xp_scale(&tmp2, &tmp, fr->d_s[k]);
        xp_add(&a, &a, &tmp2);            /* + w d^2 */
        xp_mul(&tmp2, &tmp, &f);
        xp_add(&b, &b, &tmp2);            /* + w f d */
        xp_mul(&tmp, &w, &f);
        xp_add_mul(&c, &tmp, &f);         /* + w f^2 */
    }
    /* T = eps W A */
    xp_mul(&tmp, &rr[0], &rr[1]);
    xp_mul(&tmp2, &tmp, &rr[2]);
    xp_mul(&thr, &tmp2, &a);
    xp_scale(&thr, &thr, eps);
    quad_line_exact(&a, &b, &c, &thr, NULL, tmin, tmax, out);
}

int ellipsoid_check(const isect_shape *s)
{
    if (!all_finite(s->data, 6))
        return ISECT_E_NONFINITE;
    const double *radii = s->data + 3;
    return radii[0] < 0.0 || radii[1] < 0.0 || radii[2] < 0.0 ? ISECT_E_ARG : ISECT_OK;
}

/* The exact path: certified from double-doubles, else exact. */
static int ellipsoid_exact(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                           isect_hit out[ISECT_MAX_HITS])
{
    ellipsoid_frame fr;
    if (!frame_make(s->data, ray->org, ray->dir, &fr))
        return 0;
    double tmin = pow2_scale(ray->tmin, -fr.t_shift), tmax = pow2_scale(ray->tmax, -fr.t_shift);
    quad_line_dd q;
    line_dd(&fr, prm->eps, &q);
    quad_line_roots roots;
    if (!quad_line_certify(&q, tmin, tmax, &roots))
        line_exact(&fr, prm->eps, tmin, tmax, &roots);

    int count = 0;
    for (int i = 0; i < roots.count; i++) {
        if (!roots.in[i])
            continue;
        double t_hi = pow2_scale(roots.t_hi[i], fr.t_shift) + 0.0;
        double t_lo = pow2_scale(roots.t_lo[i], fr.t_shift);
        if (!isfinite(t_hi))
            continue; /* beyond the double range: not reported */
        /* the gradient mu_k v_k at v = f + t d (scaled units, dd t) */
        double g[3], normal[3];
        for (int k = 0; k < 3; k++) {
            ddx f = ddx_diff(fr.o_s[k], fr.c_s[k]);
            double p = roots.t_hi[i] * fr.d_s[k];
            double p_err = product_error(roots.t_hi[i], fr.d_s[k], p);
            ddx v = ddx_add(f, (ddx){ p, p_err + roots.t_lo[i] * fr.d_s[k], 0.0 });
            ddx mu = weight(fr.rho_min, fr.rho_s[k]);
            g[k] = (v.hi + v.lo) * (mu.hi + mu.lo);
        }
        int32_t kind = roots.touch ? ISECT_TOUCH : roots.enter[i] ? ISECT_ENTER : ISECT_EXIT;
        if (!unit3_accurate(normal, g))
            normal_or_facing(normal, g, ray->dir, kind); /* a touch through the centre */
        hit_set_dd(&out[count++], ray, t_hi, t_lo, normal, -1, kind);
    }
    return count;
}

/* Crossing i of the solved kernel (lane_pair_hits). */
static int ellipsoid_record(const void *prep, const lane_ray *ray, const void *solved, int i,
                            lane_hit *h)
{
    (void)prep;
    ellipsoid_lanes_record(ray, &((const ellipsoid_lanes *)solved)->root[i], i == 1, h);
    return 1;
}

/* The fast kernel (ellipsoid_lanes.h) on one ray, as the batch runs it,
 * then the exact path for what it leaves undecided. */
int ellipsoid_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                   isect_hit out[ISECT_MAX_HITS])
{
    ellipsoid_prep ep;
    ellipsoid_prepare(s->data, prm->eps, &ep);
    if (ep.degenerate)
        return 0;
    lane_ray lr;
    lane_ray_from(&lr, ray);
    if (!ellipsoid_lanes_screen(&ep, &lr))
        return 0;
    ellipsoid_lanes el;
    ellipsoid_lanes_solve(&ep, &lr, 0, &el);
    static const int32_t kind[2] = { ISECT_ENTER, ISECT_EXIT };
    return lane_pair_hits(&el.pr, kind, ellipsoid_record, &ep, &lr, &el, ellipsoid_exact, s, ray,
                          prm, out);
}

/* Sum_k (p_k - c_k)^2 prod_{j != k} R_j^2 - prod R_j^2: the ellipsoid's
 * equation times prod R^2 (> 0), exactly, at the common scale (degree 6:
 * the sign is kept). */
static int side_exact(const ellipsoid_frame *fr)
{
    xp rr[3], f2[3], sum, tmp, prod;
    for (int k = 0; k < 3; k++) {
        xp_set(&rr[k], fr->rho_s[k]);
        xp_scale(&rr[k], &rr[k], fr->rho_s[k]);
        xp f;
        xp_diff(&f, fr->o_s[k], fr->c_s[k]);
        xp_mul(&f2[k], &f, &f);
    }
    xp_set(&sum, 0.0);
    for (int k = 0; k < 3; k++) {
        xp_mul(&tmp, &rr[(k + 1) % 3], &rr[(k + 2) % 3]);
        xp_add_mul(&sum, &f2[k], &tmp);
    }
    xp_mul(&tmp, &rr[0], &rr[1]);
    xp_mul(&prod, &tmp, &rr[2]);
    xp_sub(&sum, &sum, &prod);
    return xp_sign(&sum);
}

/* The side of the point the frame was made for: sum y_k^2 - 1, y_k = f_k /
 * R_k, in doubles where its error bound (9u (sum y_k^2 + 1): five roundings
 * per square, three in the sum) decides, exactly otherwise. */
static int side_filtered(const ellipsoid_frame *fr)
{
    double sum = 0.0;
    for (int k = 0; k < 3; k++) {
        double y = (fr->o_s[k] - fr->c_s[k]) / fr->rho_s[k];
        sum += y * y;
    }
    double value = sum - 1.0, bound = 9.0 * DDX_U * (sum + 1.0);
    if (value > bound)
        return 1;
    if (value < -bound)
        return -1;
    return side_exact(fr);
}

int ellipsoid_contains(const isect_shape *s, const double p[3])
{
    ellipsoid_frame fr;
    if (!frame_make(s->data, p, NULL, &fr))
        return 0;
    return side_filtered(&fr) <= 0;
}

int ellipsoid_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    ellipsoid_frame fr;
    if (!frame_make(s->data, p, NULL, &fr))
        return 1;
    return side_exact(&fr);
}
