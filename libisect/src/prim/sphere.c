/* SPDX-License-Identifier: Apache-2.0 */
/*
 * sphere.c — the sphere |x - c| = r (ISECT_SPHERE, data = c[3], r), a
 * solid; prim -1.
 *
 * The fast kernel is sphere_lanes.h (Haines' geometric solve, one certified
 * Newton step per crossing; the batch runs it on several rays at once);
 * this file holds the scalar call, which runs the same kernel on one ray,
 * and the exact path for the rays the kernel cannot certify. Tangency:
 * |r^2 - h^2| <= eps r^2, h the distance from the centre to the line.
 *
 * Hit points are snapped onto the surface, c + r n, when that is the more
 * accurate of the two ways to place them: the snapped point carries an
 * error of order u(|c| + r), org + t*dir one of order u(|org| + |t dir|),
 * so the snapped one is used when |c| + r is the smaller (a small sphere
 * near the coordinate origin seen from afar), and org + t*dir otherwise (a
 * huge sphere hit near its surface's closest point to the origin, where
 * c + r n would lose the small coordinates).
 *
 * A zero radius is degenerate: no hits, no points inside.
 */
#include "prim/prim.h"
#include "prim/sphere_lanes.h"
#include "core/expansion.h"
#include "core/scaling.h"
#include "core/vec3.h"

/* ---------------------------------------------------------------- sphere */

int sphere_check(const isect_shape *s)
{
    if (!all_finite(s->data, 4))
        return ISECT_E_NONFINITE;
    return s->data[3] < 0.0 ? ISECT_E_ARG : ISECT_OK;
}

/*
 * The exponent the exact computations scale positions by: e puts the
 * largest of r and the positions just below 1, which keeps every square
 * below 2^4. A radius more than 2^450 below the positions would then have
 * r^2 (and eps r^2 D) underflow to 0 while |f|^2 does not, so a ray through
 * the centre of a sphere of radius 2^-600 seen from 1 away was decided as a
 * tangency (one TOUCH with a zero normal). Such a radius scales the whole
 * problem up by up to 2^500 instead, keeping r above 2^-450 where it can:
 * positions stay below 2^501 and squares of sums of them below 2^1010.
 */
static int sphere_scale_exponent(double r, int e)
{
    int er = pow2_exponent(r) - e; /* the exponent of the scaled radius */
    if (r > 0.0 && er < -450)
        e -= (-450 - er) < 500 ? (-450 - er) : 500;
    return e;
}

/*
 * The exact path, for the rays the fast kernel (sphere_lanes.h) cannot
 * certify. The same formulas, with D, B, C and G = B^2 - D C formed as
 * exact expansions (expansion.h) after scaling positions and the direction
 * by powers of two (exact: the largest position coordinate and the largest
 * direction component near 1), so that
 *  - the tangency rule |G| <= eps r^2 D and the sign of G are decided
 *    exactly;
 *  - each crossing's interval decision is exact: t_lo >= tau iff Q(tau) >= 0
 *    and tau <= t_mid, t_hi >= tau iff Q(tau) <= 0 or tau <= t_mid (and the
 *    mirror images for tmax), Q(tau) = D tau^2 + 2 B tau + C and
 *    tau <= t_mid = -B/D iff B + D tau <= 0, all signs of expansions;
 *  - the roots, normals and points come from the kernel's own formulas on
 *    the values of D, B, C, G, m rounded from the exact ones (error 2u^2),
 *    hence within ~1 ulp; C == 0 (the origin on the sphere) gives t = 0
 *    exactly.
 * Parameters are compared in the scaled units (t' = t 2^-t_shift; tmin and
 * tmax scaled alike, exactly unless they become subnormal).
 */
static int sphere_exact(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                        isect_hit out[ISECT_MAX_HITS])
{
    const double *data = s->data;
    double eps = prm->eps;
    const double *c = data;
    double r = data[3];
    int e = sphere_scale_exponent(
        r, pow2_exponent(fmax_nan(r, fmax_nan(max_abs3(ray->org), max_abs3(c)))));
    int e_dir = pow2_exponent(max_abs3(ray->dir));
    int t_shift = e - e_dir;
    double scaled[4], o_s[3], d_s[3];
    scale3(scaled, c, e);
    scaled[3] = pow2_scale(r, -e);
    scale3(o_s, ray->org, e);
    scale3(d_s, ray->dir, e_dir);
    if (!(scaled[3] > 0.0))
        return 0; /* below 2^-1074 of the distances: nothing to hit */

    /* f = o - c exactly, and D, B, C, G = B^2 - D C, eps r^2 D. */
    xp f[3], dd, b, cc, g, thr, tmp, tmp2;
    double fh[3], fl[3];
    xp_set(&dd, 0.0);
    xp_set(&b, 0.0);
    xp_set(&cc, 0.0);
    for (int k = 0; k < 3; k++) {
        vdd fk = two_sum(o_s[k], -scaled[k]);
        fh[k] = fk.hi;
        fl[k] = fk.lo;
        xp_set2(&f[k], fh[k], fl[k]);
        xp_set(&tmp, d_s[k]);
        xp_scale(&tmp, &tmp, d_s[k]);
        xp_add(&dd, &dd, &tmp);
        xp_scale(&tmp, &f[k], d_s[k]);
        xp_add(&b, &b, &tmp);
        xp_mul(&tmp, &f[k], &f[k]);
        xp_add(&cc, &cc, &tmp);
    }
    xp_set(&tmp, scaled[3]);
    xp_scale(&tmp, &tmp, scaled[3]);
    xp_sub(&cc, &cc, &tmp);
    xp_mul(&thr, &tmp, &dd);
    xp_scale(&thr, &thr, eps);
    xp_mul(&g, &b, &b);
    xp_mul(&tmp2, &dd, &cc);
    xp_sub(&g, &g, &tmp2);

    xp_add(&tmp, &g, &thr);
    xp_sub(&tmp2, &g, &thr);
    int touch = xp_sign(&tmp) >= 0 && xp_sign(&tmp2) <= 0;
    if (!touch && xp_sign(&g) <= 0)
        return 0;

    /* Interval decisions. */
    double bound[2] = { ray->tmin, ray->tmax };
    int lo_ok[2], hi_ok[2], mid_ok[2]; /* [0]: >= tmin, [1]: <= tmax */
    for (int side = 0; side < 2; side++) {
        double tau = bound[side];
        if (isinf(tau)) {
            int all = side == 0 ? tau < 0.0 : tau > 0.0;
            lo_ok[side] = hi_ok[side] = mid_ok[side] = all;
            continue;
        }
        /* Every root and the midpoint lie within 2^508 in the scaled units
         * (positions below 2^501, the direction's largest component in
         * [1/2, 1)), so a bound beyond 2^510 decides as 2^510 does, and
         * D tau^2 cannot overflow. */
        double tau_s = fmax(-0x1p510, fmin(0x1p510, pow2_scale(tau, -t_shift)));
        xp q_tau, m_tau; /* Q(tau), B + D tau */
        xp_scale(&m_tau, &dd, tau_s);
        xp_add(&m_tau, &m_tau, &b);
        xp_add(&q_tau, &m_tau, &b);
        xp_scale(&q_tau, &q_tau, tau_s);
        xp_add(&q_tau, &q_tau, &cc);
        int sq = xp_sign(&q_tau), sm = xp_sign(&m_tau);
        if (side == 0) {
            lo_ok[0] = sq >= 0 && sm <= 0;
            hi_ok[0] = sq <= 0 || sm <= 0;
            mid_ok[0] = sm <= 0;
        } else {
            lo_ok[1] = sq <= 0 || sm >= 0;
            hi_ok[1] = sq >= 0 && sm >= 0;
            mid_ok[1] = sm >= 0;
        }
    }

    /* The kernel's formulas on the values rounded from the exact ones: the
     * roots, l = (d x m)/D (m = f x d, exactly to dd) and w = sqrt(G)/D, so
     * that the crossings' vectors from the centre are l -+ w d (the foot of
     * the perpendicular and the half chord: small where f + t d would
     * cancel). */
    vdd dv, bv, cv, gv;
    xp_dd(&dd, &dv.hi, &dv.lo);
    xp_dd(&b, &bv.hi, &bv.lo);
    xp_dd(&cc, &cv.hi, &cv.lo);
    xp_dd(&g, &gv.hi, &gv.lo);
    double l[3];
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        xp m_i, m_j;
        xp_scale(&m_i, &f[j], d_s[k]);   /* m_i = f_j d_k - f_k d_j */
        xp_scale(&tmp, &f[k], d_s[j]);
        xp_sub(&m_i, &m_i, &tmp);
        xp_scale(&m_j, &f[k], d_s[i]);   /* m_j = f_k d_i - f_i d_k */
        xp_scale(&tmp, &f[i], d_s[k]);
        xp_sub(&m_j, &m_j, &tmp);
        xp_scale(&tmp, &m_j, d_s[i]);    /* d_i m_j - d_j m_i */
        xp_scale(&tmp2, &m_i, d_s[j]);
        xp_sub(&tmp, &tmp, &tmp2);
        vdd num;
        xp_dd(&tmp, &num.hi, &num.lo);
        l[k] = dd_div(num, dv);
    }
    double t[2], w = 0.0;
    int in[2];
    if (touch) {
        vdd minus_b = { -bv.hi, -bv.lo };
        t[0] = t[1] = dd_div(minus_b, dv);
        in[0] = mid_ok[0] && mid_ok[1];
        in[1] = 0;
    } else {
        double s = sqrt(gv.hi);
        vdd s2 = two_prod(s, s);
        vdd sqrt_g = { s, (((gv.hi - s2.hi) - s2.lo) + gv.lo) / (s + s) };
        double sigma = xp_sign(&b) < 0 ? -1.0 : 1.0;
        vdd q = two_sum(bv.hi, sigma * sqrt_g.hi);
        q.hi = -q.hi;
        q.lo = -(q.lo + (bv.lo + sigma * sqrt_g.lo));
        q = dd_renorm(q);
        double t1 = dd_div(q, dv), t2 = dd_div(cv, q);
        t[0] = sigma > 0.0 ? t1 : t2;
        t[1] = sigma > 0.0 ? t2 : t1;
        t[0] = fmin(t[0], t[1]);
        w = dd_div(sqrt_g, dv);
        in[0] = lo_ok[0] && lo_ok[1];
        in[1] = hi_ok[0] && hi_ok[1];
    }

    /* The records, in the scaled units, then scaled back. */
    lane_ray lr;
    isect_ray scaled_ray = { { o_s[0], o_s[1], o_s[2] }, { d_s[0], d_s[1], d_s[2] },
                             pow2_scale(ray->tmin, -t_shift), pow2_scale(ray->tmax, -t_shift) };
    lane_ray_from(&lr, &scaled_ray);
    sphere_prep sp;
    sphere_prepare(scaled, eps, &sp);
    int count = 0;
    for (int i = 0; i < 2; i++) {
        if (!in[i])
            continue;
        double side = touch ? 0.0 : (i == 0 ? -w : w);
        double v[3] = { l[0] + side * d_s[0], l[1] + side * d_s[1], l[2] + side * d_s[2] };
        lane_hit h;
        sphere_lanes_record(&sp, &lr, lane_clamp_t(t[i], &lr) + 0.0, v, i == 1, &h);
        isect_hit *hit = &out[count];
        lane_hit_store(&h, 0, hit);
        if (touch) {
            /* The foot of the perpendicular, c + l (snapped as the
             * crossings are: l is accurate where o + t d would lose the
             * small coordinates) or o + t d, and the normal l/|l| (|l| = r
             * only to ~eps/2, so divided by its length, then renormalised). */
            unit3(hit->normal, l);
            if (l[0] == 0.0 && l[1] == 0.0 && l[2] == 0.0) {
                /* A line through the centre declared tangent (eps >= 1
                 * lets |G| = r^2 D pass; found by tests/fuzz/fuzz_shape)
                 * has no foot direction: the normal is -unit(dir), the
                 * ellipsoid's choice there and the quadric's at a zero
                 * gradient, instead of 0. */
                double back[3] = { -d_s[0], -d_s[1], -d_s[2] };
                unit3(hit->normal, back);
            }
            lane_unit_newton(hit->normal);
            int snap = sp.snap_scale < max_abs3(o_s) + fabs(hit->t) * max_abs3(d_s);
            for (int k = 0; k < 3; k++)
                hit->point[k] = snap ? scaled[k] + l[k] : o_s[k] + hit->t * d_s[k];
            hit->kind = ISECT_TOUCH;
        }
        hit->t = pow2_scale(hit->t, t_shift) + 0.0;
        for (int k = 0; k < 3; k++)
            hit->point[k] = pow2_scale(hit->point[k], e);
        if (isfinite(hit->t)) /* beyond the double range: not reported */
            count++;
    }
    return count;
}

/* Crossing i of the solved kernel (lane_pair_hits). */
static int sphere_record(const void *prep, const lane_ray *ray, const void *solved, int i,
                         lane_hit *h)
{
    const lane_root *rt = &((const sphere_lanes *)solved)->root[i];
    sphere_lanes_record(prep, ray, rt->t, rt->v, i == 1, h);
    return 1;
}

int sphere_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                isect_hit out[ISECT_MAX_HITS])
{
    if (s->data[3] == 0.0)
        return 0;
    sphere_prep sp;
    sphere_prepare(s->data, prm->eps, &sp);
    lane_ray lr;
    lane_ray_from(&lr, ray);
    if (!sphere_lanes_screen(&sp, &lr))
        return 0;
    sphere_lanes sl;
    sphere_lanes_solve(&sp, &lr, 0, &sl);
    static const int32_t kind[2] = { ISECT_ENTER, ISECT_EXIT };
    return lane_pair_hits(&sl.pr, kind, sphere_record, &sp, &lr, &sl, sphere_exact, s, ray, prm, out);
}

/* The exact side of p: the sign of |p - c|^2 - r^2 (f = p - c exact as two
 * parts, every product exact). */
int sphere_side(const double *data, const double p[3])
{
    int e = sphere_scale_exponent(
        data[3], pow2_exponent(fmax_nan(data[3], fmax_nan(max_abs3(p), max_abs3(data)))));
    xp sum, tmp, f;
    xp_set(&sum, 0.0);
    for (int k = 0; k < 3; k++) {
        vdd fk = two_sum(pow2_scale(p[k], -e), -pow2_scale(data[k], -e));
        xp_set2(&f, fk.hi, fk.lo);
        xp_mul(&tmp, &f, &f);
        xp_add(&sum, &sum, &tmp);
    }
    double r_s = pow2_scale(data[3], -e);
    xp_set(&tmp, r_s);
    xp_scale(&tmp, &tmp, -r_s);
    xp_add(&sum, &sum, &tmp);
    return xp_sign(&sum);
}

int sphere_contains(const isect_shape *s, const double p[3])
{
    if (s->data[3] == 0.0)
        return 0;
    return sphere_side(s->data, p) <= 0;
}


int sphere_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    return s->data[3] == 0.0 ? 1 : sphere_side(s->data, p);
}
