/* SPDX-License-Identifier: Apache-2.0 */
/*
 * plane_lanes.h — the infinite plane's fast kernel, LANE_W rays at once
 * (prim_lanes.h states the contract; plane.c holds the exact path).
 *
 * t = -(n.o + d)/(n.dir). Both dot products are double-double (exact
 * products, compensated sums), so the numerator keeps its digits when the
 * origin is near the plane (it cancels there) and the denominator when the
 * ray is nearly parallel; with E_num <= 16u^2 (sum|n_k o_k| + |d|) and
 * E_den <= 16u^2 sum|n_k dir_k| (plus ETA for underflow), the quotient
 * (dd_mul_inv_dd) errs by at most |t| (u + 40u^2 + E_den/|den|) +
 * E_num/|den|. The crossing is reported from here when that is at most
 * 3.5u|t| and its interval decision holds for every value within it; the
 * policy's parallel test (n.dir)^2 <= eps^2 |n|^2 |dir|^2 likewise only when
 * certain. The point is o + t d formed from t as a double-double, so it
 * lies on the plane to the rounding of its own coordinates even when the
 * origin is far away; the normal is n made unit once per call.
 *
 * Range: 2^-200 <= max|n_k| <= 2^200, |d| <= 2^400, |o| <= 2^200,
 * 2^-200 <= max|dir_k| <= 2^200.
 */
#ifndef ISECT_PLANE_LANES_H
#define ISECT_PLANE_LANES_H

#include "prim/prim_lanes.h"
#include "core/scaling.h"

#define PLANE_LANES_U   0x1p-53
#define PLANE_LANES_U2  0x1p-106
#define PLANE_LANES_ETA 0x1p-960

typedef struct plane_prep {
    double n[3], d;
    double normal[3];  /* n / |n|, unit to within u */
    double eps2_nn;    /* eps^2 |n|^2, rounded */
    int    in_range;
    int    degenerate; /* n == 0: never hit */
} plane_prep;

static inline void plane_prepare(const double *data, double eps, plane_prep *pp)
{
    double m = max_abs3(data);
    for (int k = 0; k < 3; k++)
        pp->n[k] = data[k];
    pp->d = data[3];
    pp->degenerate = m == 0.0;
    pp->in_range = m >= 0x1p-200 && m <= 0x1p200 && fabs(pp->d) <= 0x1p400;
    double nn = data[0] * data[0] + data[1] * data[1] + data[2] * data[2];
    pp->eps2_nn = eps * eps * nn;
    if (!unit3_accurate(pp->normal, data))
        pp->normal[0] = pp->normal[1] = pp->normal[2] = 0.0;
}

/* A plane's crossing per lane, for planes given per lane (n, d; the
 * infinite plane broadcasts one, a convex polyhedron's lanes each their
 * own face): t = -(n.o + d)/(n.dir) as a double-double with its bound
 * (see the top of the file), and den = n.dir with its bound. */
typedef struct lane_plane_cross {
    vdd t;
    vd  err;   /* |t - exact| <= err */
    vdd den;
    vd  e_den; /* |den - exact| <= e_den */
} lane_plane_cross;

static ALWAYS_INLINE void lane_plane_crossing(vd n0, vd n1, vd n2, vd d, const lane_ray *ray,
                                              lane_plane_cross *out)
{
    const vd u2 = vd_set1(PLANE_LANES_U2), eta = vd_set1(PLANE_LANES_ETA);
    const vd *o = ray->org, *dir = ray->dir;

    vdd den = lane_dot3_dd(n0, n1, n2, dir[0], dir[1], dir[2]);
    den = dd_renorm(den);
    vd s_den = vd_add(vd_add(vd_abs(vd_mul(n0, dir[0])), vd_abs(vd_mul(n1, dir[1]))),
                      vd_abs(vd_mul(n2, dir[2])));
    vd e_den = vd_add(vd_mul(vd_set1(16.0), vd_mul(u2, s_den)), eta);

    vdd p = lane_dot3_dd(n0, n1, n2, o[0], o[1], o[2]);
    vdd num = two_sum(p.hi, d);
    num.lo = vd_add(num.lo, p.lo);
    num = dd_renorm(num);
    vd s_num = vd_add(vd_add(vd_add(vd_abs(vd_mul(n0, o[0])), vd_abs(vd_mul(n1, o[1]))),
                             vd_abs(vd_mul(n2, o[2]))),
                      vd_abs(d));
    vd e_num = vd_add(vd_mul(vd_set1(16.0), vd_mul(u2, s_num)), eta);

    vd inv = vd_div(vd_set1(1.0), den.hi);
    vdd minus_num = { vd_neg(num.hi), vd_neg(num.lo) };
    out->t = dd_mul_inv_dd(minus_num, den, inv);
    vd up = vd_set1(1.0 + 8.0 * PLANE_LANES_U);
    vd inv_abs = vd_mul(vd_abs(inv), up);
    out->err = vd_mul(vd_add(vd_mul(vd_abs(out->t.hi),
                                    vd_add(vd_set1(PLANE_LANES_U + 40.0 * PLANE_LANES_U2),
                                           vd_mul(e_den, inv_abs))),
                             vd_mul(e_num, inv_abs)),
                      up);
    out->den = den;
    out->e_den = e_den;
}

/* The crossing's verdicts: reported (in [tmin, tmax] for every value
 * within err, and err <= 3.5u|t|, so t_hi is within 4 ulp), or certainly
 * outside the interval. */
static ALWAYS_INLINE vm lane_plane_cross_in(const lane_plane_cross *c, const lane_ray *ray)
{
    return vm_and(lane_certainly_in(c->t.hi, c->err, ray),
                  vd_le(c->err, vd_mul(vd_set1(3.5 * PLANE_LANES_U), vd_abs(c->t.hi))));
}

/* The one crossing: verdicts and, where in range, the record. */
static ALWAYS_INLINE void plane_lanes_first(const plane_prep *pp, const lane_ray *ray, lane_hit *h)
{
    lane_plane_cross c;
    lane_plane_crossing(vd_set1(pp->n[0]), vd_set1(pp->n[1]), vd_set1(pp->n[2]), vd_set1(pp->d),
                        ray, &c);
    const vd *d = ray->dir;

    /* The parallel test on squares: den^2 against eps^2 |n|^2 |dir|^2, the
     * latter within 8u of its rounded value, den within e of den.hi. */
    vd dd = vd_add(vd_add(vd_mul(d[0], d[0]), vd_mul(d[1], d[1])), vd_mul(d[2], d[2]));
    vd thr2 = vd_mul(vd_set1(pp->eps2_nn), dd);
    vd e = vd_add(c.e_den, vd_mul(vd_set1(PLANE_LANES_U), vd_abs(c.den.hi)));
    vd lo = vd_sub(vd_abs(c.den.hi), e), hi = vd_add(vd_abs(c.den.hi), e);
    vm crossing = vm_and(vd_gt(lo, vd_zero()),
                         vd_gt(vd_mul(lo, lo), vd_mul(thr2, vd_set1(1.0 + 16.0 * PLANE_LANES_U))));
    vm parallel = vd_lt(vd_mul(hi, hi), vd_mul(thr2, vd_set1(1.0 - 16.0 * PLANE_LANES_U)));

    vm in = lane_plane_cross_in(&c, ray);
    vm out = lane_certainly_out(c.t.hi, c.err, ray);
    vm decided = vm_or(parallel, vm_and(crossing, vm_or(in, out)));
    vm ok = pp->in_range ? lane_ray_in_range(ray, 0x1p200) : vm_false();
    h->slow = pp->degenerate ? vm_false() : vm_not(vm_and(ok, decided));
    h->found = pp->degenerate ? vm_false() : vm_andnot(vm_and(crossing, in), h->slow);

    h->t = vd_add(lane_clamp_t(c.t.hi, ray), vd_zero());
    lane_point_on_ray(ray, c.t, h->point);
    for (int k = 0; k < 3; k++)
        h->normal[k] = vd_set1(pp->normal[k]);
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = vd_set1(-1.0);
    h->kind = vd_sel(vd_lt(c.den.hi, vd_zero()), vd_set1((double)ISECT_ENTER), vd_set1((double)ISECT_EXIT));
}

#endif /* ISECT_PLANE_LANES_H */
