/* SPDX-License-Identifier: Apache-2.0 */
/*
 * prim_lanes.h — rays and hit records in lane form (one number per lane,
 * LANE_W rays at once), as the fast kernels (prim/ *_lanes.h) take and give
 * them. Include after core/lanes.h has been configured for an instruction
 * set (see lanes.h).
 *
 * The fast kernels' contract. A kernel decides, per lane, one of:
 *  - slow:  its plain arithmetic could not certify the answer (a decision
 *           within its error bound, a parameter that would not be within
 *           the accuracy contract, coordinates outside the range its bounds
 *           assume); the caller runs the family's exact path for that ray
 *           (prim X_hits), which starts with this same kernel (one lane) and
 *           so reaches the same verdict;
 *  - found: the first hit in [tmin, tmax] (by t, then prim, as the
 *           dispatcher orders them), fully written, decided exactly;
 *  - neither: certainly no hit in [tmin, tmax].
 * The same source is the scalar kernel (LANE_W = 1), so a batch's records
 * are bit for bit those of the scalar calls.
 */
#ifndef ISECT_PRIM_LANES_H
#define ISECT_PRIM_LANES_H

#include "core/eft.h"
#include "prim/prim.h"

/* LANE_W object-space rays. */
typedef struct lane_ray {
    vd org[3], dir[3];
    vd tmin, tmax;
} lane_ray;

/* LANE_W hit records (the fields of isect_hit; prim and kind as small
 * whole numbers in doubles), and the kernel's verdict per lane. */
typedef struct lane_hit {
    vd t, point[3], normal[3], uv[2];
    vd prim, kind;
    vm found, slow;
} lane_hit;

/* A lane_ray of one ray (the scalar kernels' input). */
static ALWAYS_INLINE void lane_ray_from(lane_ray *lr, const isect_ray *ray)
{
    for (int k = 0; k < 3; k++) {
        lr->org[k] = vd_set1(ray->org[k]);
        lr->dir[k] = vd_set1(ray->dir[k]);
    }
    lr->tmin = vd_set1(ray->tmin);
    lr->tmax = vd_set1(ray->tmax);
}

/* The rays at[0 .. LANE_W) (each record is 8 doubles: org, dir, tmin,
 * tmax), one per lane. */
static ALWAYS_INLINE void lane_ray_load(const isect_ray *const at[LANE_W], lane_ray *lr)
{
    const double *rows[LANE_W];
    for (int k = 0; k < LANE_W; k++)
        rows[k] = at[k]->org;
    vd col[8];
    vd_load_rows8(rows, col);
    for (int k = 0; k < 3; k++) {
        lr->org[k] = col[k];
        lr->dir[k] = col[3 + k];
    }
    lr->tmin = col[6];
    lr->tmax = col[7];
}

/* The lanes whose ray passes ray_check (core.h): org and dir finite, tmin
 * and tmax not NaN, dir not zero. */
static ALWAYS_INLINE vm lane_ray_valid(const lane_ray *lr)
{
    const vd *o = lr->org, *d = lr->dir;
    vd probe = vd_add(vd_add(vd_add(vd_sub(o[0], o[0]), vd_sub(o[1], o[1])), vd_sub(o[2], o[2])),
                      vd_add(vd_add(vd_sub(d[0], d[0]), vd_sub(d[1], d[1])), vd_sub(d[2], d[2])));
    vd d_max = vd_max(vd_abs(d[0]), vd_max(vd_abs(d[1]), vd_abs(d[2])));
    vm nonzero = vd_gt(d_max, vd_zero());
    vm finite = vd_eq(probe, vd_zero());
    vm ordered = vm_and(vd_eq(lr->tmin, lr->tmin), vd_eq(lr->tmax, lr->tmax));
    return vm_and(vm_and(finite, ordered), nonzero);
}

/* The object-space rays of world-space rays under x, bit for bit as
 * xform_ray_unchecked (core/xform.c) computes them: each coordinate
 * ((a0 r0 + a1 r1) + a2 r2), in that order, with r = org - T for the
 * origin (T the translation of x->m) and r = dir for the direction. */
static ALWAYS_INLINE void lane_ray_xform(const isect_xform *x, lane_ray *lr)
{
    const double *a = x->inv;
    vd org[3], dir[3], rel[3];
    for (int k = 0; k < 3; k++)
        rel[k] = vd_sub(lr->org[k], vd_set1(x->m[4 * k + 3]));
    for (int i = 0; i < 3; i++) {
        vd a0 = vd_set1(a[4 * i]), a1 = vd_set1(a[4 * i + 1]), a2 = vd_set1(a[4 * i + 2]);
        org[i] = vd_add(vd_add(vd_mul(a0, rel[0]), vd_mul(a1, rel[1])), vd_mul(a2, rel[2]));
        dir[i] = vd_add(vd_add(vd_mul(a0, lr->dir[0]), vd_mul(a1, lr->dir[1])),
                        vd_mul(a2, lr->dir[2]));
    }
    for (int k = 0; k < 3; k++) {
        lr->org[k] = org[k];
        lr->dir[k] = dir[k];
    }
}

/* The records back to world space, bit for bit as xform_hits_unchecked
 * (core/xform.c): points by m (((m0 p0 + m1 p1) + m2 p2) + m3), normals by
 * the transpose of inv's linear part, then v3_normalize (divided by the
 * largest magnitude, then by the length; zero when that is not positive
 * and finite) and one Newton step, n (3 - n.n)/2. */
static ALWAYS_INLINE void lane_hit_to_world(const isect_xform *x, lane_hit *h)
{
    const double *m = x->m, *a = x->inv;
    vd p[3], r[3];
    for (int i = 0; i < 3; i++) {
        p[i] = vd_add(vd_add(vd_add(vd_mul(vd_set1(m[4 * i]), h->point[0]),
                                    vd_mul(vd_set1(m[4 * i + 1]), h->point[1])),
                             vd_mul(vd_set1(m[4 * i + 2]), h->point[2])),
                      vd_set1(m[4 * i + 3]));
        r[i] = vd_add(vd_add(vd_mul(vd_set1(a[i]), h->normal[0]), vd_mul(vd_set1(a[4 + i]), h->normal[1])),
                      vd_mul(vd_set1(a[8 + i]), h->normal[2]));
    }
    vd big = vd_max(vd_abs(r[0]), vd_max(vd_abs(r[1]), vd_abs(r[2])));
    vm usable = vm_and(vd_gt(big, vd_zero()), vd_le(big, vd_set1(1.7976931348623157e308)));
    vd x0 = vd_div(r[0], big), x1 = vd_div(r[1], big), x2 = vd_div(r[2], big);
    vd len = vd_sqrt(vd_add(vd_add(vd_mul(x0, x0), vd_mul(x1, x1)), vd_mul(x2, x2)));
    vd n0 = vd_sel(usable, vd_div(x0, len), vd_zero());
    vd n1 = vd_sel(usable, vd_div(x1, len), vd_zero());
    vd n2 = vd_sel(usable, vd_div(x2, len), vd_zero());
    /* affine_normal's Newton step, n (3 - n.n)/2 */
    vd nn = vd_add(vd_add(vd_mul(n0, n0), vd_mul(n1, n1)), vd_mul(n2, n2));
    vd f = vd_sub(vd_set1(1.5), vd_mul(vd_set1(0.5), nn));
    h->normal[0] = vd_mul(n0, f);
    h->normal[1] = vd_mul(n1, f);
    h->normal[2] = vd_mul(n2, f);
    for (int i = 0; i < 3; i++)
        h->point[i] = p[i];
}

/*
 * n, nearly unit (|n|^2 = 1 + e, |e| <= 2^-20), made unit to within u/2
 * plus the components' own roundings: one Newton step for 1/sqrt,
 * n (3 - |n|^2)/2 = n + n delta, delta = -e/2 (error O(e^2)), with |n|^2
 * summed exactly enough (exact squares, compensated sum) and 1 - |n|^2
 * taken exactly (Sterbenz), so that delta is right to ~u^2 and each
 * component rounds once, in n_k + n_k delta: ||n| - 1| <= ~u (a scale
 * factor 1 + delta rounded to a double would add another u). No square
 * root, no division.
 */
static ALWAYS_INLINE void lane_unit_newton(vd n[3])
{
    vdd p0 = two_prod(n[0], n[0]), p1 = two_prod(n[1], n[1]), p2 = two_prod(n[2], n[2]);
    vdd s = two_sum(p0.hi, p1.hi);
    vdd s2 = two_sum(s.hi, p2.hi);
    vd lo = vd_add(vd_add(s.lo, s2.lo), vd_add(vd_add(p0.lo, p1.lo), p2.lo));
    vd delta = vd_mul(vd_set1(0.5), vd_sub(vd_sub(vd_set1(1.0), s2.hi), lo));
    for (int k = 0; k < 3; k++)
        n[k] = vd_add(n[k], vd_mul(n[k], delta));
}

static ALWAYS_INLINE vd lane_max_abs3(vd a, vd b, vd c)
{
    return vd_max(vd_abs(a), vd_max(vd_abs(b), vd_abs(c)));
}

/* x0 y0 + x1 y1 + x2 y2 as dd: exact products (TwoProduct), compensated
 * sum; |error| <= 12u^2 sum |x_k y_k| while nothing underflows. */
static ALWAYS_INLINE vdd lane_dot3_dd(vd x0, vd x1, vd x2, vd y0, vd y1, vd y2)
{
    vdd p0 = two_prod(x0, y0), p1 = two_prod(x1, y1), p2 = two_prod(x2, y2);
    vdd s = two_sum(p0.hi, p1.hi);
    vdd s2 = two_sum(s.hi, p2.hi);
    s2.lo = vd_add(vd_add(s.lo, s2.lo), vd_add(vd_add(p0.lo, p1.lo), p2.lo));
    return s2;
}

/* The fast kernels' range for a ray: |org| <= org_bound, 2^-200 <=
 * max|dir_k| <= 2^200 (a NaN fails it too). */
static ALWAYS_INLINE vm lane_ray_in_range(const lane_ray *ray, double org_bound)
{
    vd o_max = lane_max_abs3(ray->org[0], ray->org[1], ray->org[2]);
    vd d_max = lane_max_abs3(ray->dir[0], ray->dir[1], ray->dir[2]);
    return vm_and(vd_le(o_max, vd_set1(org_bound)),
                  vm_and(vd_ge(d_max, vd_set1(0x1p-200)), vd_le(d_max, vd_set1(0x1p200))));
}

/*
 * One certified Newton step on a quadratic line function (a sphere's,
 * ellipsoid's, cylinder's or general quadric's Q(o + t dir) = A t^2 + 2B t
 * + C), at a start t0: from r = Q(t0) (within e_r), p = Q'(t0)/2 (within
 * e_p) and a = A (with a_up >= |A| and a_up - |a| >= |A - a|), the step
 * sigma = r/(2p) (1 + c), c = a r/(4p^2): Newton's step with the
 * quadratic's own curvature term (the exact small root of r + 2p h + a h^2
 * = 0 is -r/(2p) (1 + c + 2c^2 + ...)), so the residual left at x = t0 -
 * sigma is of third order, r c^2 (2 + c) = a sigma^2 c (2 + c)/(1 + c)^2,
 * below 1.14 a sigma^2 |c| (2 + |c|) for |c| <= 1/16, and a start off by
 * u|t| lands within a tiny fraction of an ulp. Kantorovich's bound for the
 * quadratic is sharp and cheap: with eta >= |Q(x)| (that term, the errors
 * of r and p, (A - a) sigma^2, and the step's roundings, 16u |sigma| |p|)
 * and m = 2(|p| - e_p - |a| |sigma|) <= |Q'(x)|, if
 * 4 |a| eta <= m^2 there is exactly one root within rho = 2 eta/m of x,
 * and Q' keeps its sign there: the root is an entry into Q < 0 when p < 0.
 * Taken only when the shortfall (e_p + |a| |sigma|)/|p| <= 1/4 (so m >=
 * 1.5|p|) and |c| <= 1/16. One division (1/(2p)).
 */
typedef struct lane_newton {
    vd t;      /* t0 - sigma, rounded */
    vd step;   /* sigma */
    vd rho;    /* |root - (t0 - sigma)| <= rho, before t's rounding */
    vd err;    /* |root - t| <= err */
    vm ok;     /* the bound holds: one root, within err */
    vm enter;  /* Q' < 0 at the root */
} lane_newton;

static ALWAYS_INLINE void lane_newton_certify(vd t0, vd r, vd e_r, vd p, vd e_p, vd a, vd a_up,
                                              lane_newton *out)
{
    const double u = 0x1p-53;
    vd inv_2p = vd_div(vd_set1(0.5), p);
    vd newton = vd_mul(r, inv_2p);
    vd curv = vd_mul(vd_mul(a, newton), inv_2p);
    vd step = vd_add(newton, vd_mul(newton, curv));
    out->step = step;
    out->t = vd_sub(t0, step);
    vd up = vd_set1(1.0 + 8.0 * u);
    vd step_abs = vd_mul(vd_abs(step), up);
    vd c_abs = vd_abs(curv);
    vd inv_2p_abs = vd_mul(vd_abs(inv_2p), up);
    vd shortfall = vd_mul(vd_mul(vd_add(e_p, vd_mul(a_up, step_abs)), vd_set1(2.0)), inv_2p_abs);
    vd e_a = vd_mul(vd_sub(a_up, vd_abs(a)), up);
    vd curvature = vd_mul(vd_mul(step_abs, step_abs),
                          vd_add(vd_mul(vd_mul(vd_set1(1.14), a_up),
                                        vd_mul(c_abs, vd_add(vd_set1(2.0), c_abs))),
                                 e_a));
    vd eta = vd_add(vd_add(curvature, e_r),
                    vd_mul(vd_add(vd_add(e_p, e_p), vd_mul(vd_set1(16.0 * u), vd_abs(p))), step_abs));
    vm kantorovich = vd_le(vd_mul(vd_mul(vd_set1(4.0), a_up), eta),
                           vd_mul(vd_set1(2.25 * (1.0 - 8.0 * u)), vd_mul(p, p)));
    out->rho = vd_mul(vd_mul(vd_set1(8.0 / 3.0), eta), inv_2p_abs);
    out->ok = vm_and(vm_and(vd_le(shortfall, vd_set1(0.25)), vd_le(c_abs, vd_set1(0.0625))),
                     kantorovich);
    out->err = vd_mul(vd_add(out->rho, vd_mul(vd_set1(u), vd_abs(out->t))), up);
    out->enter = vd_lt(p, vd_zero());
}

/* The number of set bits of a lane mask (LANE_W <= 8). */
static ALWAYS_INLINE int lane_count(unsigned bits)
{
    int n = 0;
    for (; bits != 0; bits &= bits - 1u)
        n++;
    return n;
}

/* Lane i of h as an isect_hit. */
static ALWAYS_INLINE void lane_hit_store(const lane_hit *h, int i, isect_hit *out)
{
    out->t = vd_lane(h->t, i);
    for (int k = 0; k < 3; k++) {
        out->point[k] = vd_lane(h->point[k], i);
        out->normal[k] = vd_lane(h->normal[k], i);
    }
    out->uv[0] = vd_lane(h->uv[0], i);
    out->uv[1] = vd_lane(h->uv[1], i);
    out->prim = (int32_t)vd_lane(h->prim, i);
    out->kind = (int32_t)vd_lane(h->kind, i);
}

/* Whether a parameter t known to within err of the exact one lies in
 * [tmin, tmax]: certainly in, certainly out, or neither (undecided). */
static ALWAYS_INLINE vm lane_certainly_in(vd t, vd err, const lane_ray *r)
{
    return vm_and(vd_ge(vd_sub(t, err), r->tmin), vd_le(vd_add(t, err), r->tmax));
}
static ALWAYS_INLINE vm lane_certainly_out(vd t, vd err, const lane_ray *r)
{
    return vm_or(vd_lt(vd_add(t, err), r->tmin), vd_gt(vd_sub(t, err), r->tmax));
}

/* o + t d for t = t.hi + t.lo as xh + xl per coordinate: TwoProduct of
 * t.hi d, TwoSum with o (xh its head), the low parts summed and rounded
 * once (xl): within u|xl| + |t.lo d| u, ~3u^2 (|o| + |t d|). */
static ALWAYS_INLINE void lane_point_on_ray_dd(const lane_ray *r, vdd t, vd xh[3], vd xl[3])
{
    for (int k = 0; k < 3; k++) {
        vdd p = two_prod(t.hi, r->dir[k]);
        vdd s = two_sum(r->org[k], p.hi);
        xh[k] = s.hi;
        xl[k] = vd_add(vd_add(s.lo, p.lo), vd_mul(t.lo, r->dir[k]));
    }
}

/* The same rounded to doubles: the one final rounding is the only error,
 * so a point on the ray at a parameter known to ~u^2 lies within its own
 * ulp, even where |o| is far larger than the point. */
static ALWAYS_INLINE void lane_point_on_ray(const lane_ray *r, vdd t, vd out[3])
{
    vd xh[3], xl[3];
    lane_point_on_ray_dd(r, t, xh, xl);
    for (int k = 0; k < 3; k++)
        out[k] = vd_add(xh[k], xl[k]);
}

/* f + t0 d for f exact as f.hi + f.lo (a difference of coordinates by
 * TwoSum) and a double t0: vh the exact sum of f.hi and fl(t0 d), vl its
 * error + f.lo + the product's error, rounded: within 8u^2 F per
 * component, F = max|f.hi| + |t0| max|d|. The vector from a shape's point
 * to the ray's point at t0, to ~u^2 of the larger of the two however
 * much they cancel. */
static ALWAYS_INLINE void lane_offset_at(const vdd f[3], vd t0, const vd d[3], vd vh[3], vd vl[3])
{
    for (int k = 0; k < 3; k++) {
        vdd p = two_prod(t0, d[k]);
        vdd sum = two_sum(f[k].hi, p.hi);
        vh[k] = sum.hi;
        vl[k] = vd_add(sum.lo, vd_add(f[k].lo, p.lo));
    }
}

/*
 * |vh + vl|^2 - (c_hi + c_lo) for a vector known as heads and small low
 * parts: exact squares of the heads (TwoProduct), summed exactly with
 * -c_hi (TwoSum), the low parts (the squares' errors, 2 vh.vl, |vl|^2, the
 * sums' errors, -c_lo) rounded in a tree of depth <= 5. Bound of its own
 * arithmetic: e = 32u^2 (S + c_hi) + 8u (2 V L + L^2) + u|R|, S the heads'
 * rounded sum of squares, V = sum|vh_k|, L = sum|vl_k|; the caller adds
 * the errors of vh + vl and of c, and ETA.
 */
typedef struct lane_sq3 {
    vd r, e;
    vd v_sum, l_sum;
} lane_sq3;

static ALWAYS_INLINE void lane_sq3_minus(const vd vh[3], const vd vl[3], double c_hi, double c_lo,
                                         lane_sq3 *out)
{
    const double u = 0x1p-53;
    vdd g0 = two_prod(vh[0], vh[0]), g1 = two_prod(vh[1], vh[1]), g2 = two_prod(vh[2], vh[2]);
    vdd a = two_sum(g0.hi, g1.hi);
    vdd b = two_sum(a.hi, g2.hi);
    vdd c = two_sum(b.hi, vd_set1(-c_hi));
    vd cross = vd_add(vd_add(vd_mul(vh[0], vl[0]), vd_mul(vh[1], vl[1])), vd_mul(vh[2], vl[2]));
    vd sq_lo = vd_add(vd_add(vd_mul(vl[0], vl[0]), vd_mul(vl[1], vl[1])), vd_mul(vl[2], vl[2]));
    vd lows = vd_add(vd_add(vd_add(a.lo, b.lo), vd_add(c.lo, vd_set1(-c_lo))),
                     vd_add(vd_add(vd_add(g0.lo, g1.lo), g2.lo), vd_add(vd_add(cross, cross), sq_lo)));
    out->r = vd_add(c.hi, lows);
    out->v_sum = vd_add(vd_add(vd_abs(vh[0]), vd_abs(vh[1])), vd_abs(vh[2]));
    out->l_sum = vd_add(vd_add(vd_abs(vl[0]), vd_abs(vl[1])), vd_abs(vl[2]));
    vd v_sum = out->v_sum, l_sum = out->l_sum;
    out->e = vd_add(vd_add(vd_mul(vd_set1(32.0 * u * u), vd_add(b.hi, vd_set1(c_hi))),
                           vd_mul(vd_set1(8.0 * u), vd_add(vd_mul(vd_add(v_sum, v_sum), l_sum),
                                                           vd_mul(l_sum, l_sum)))),
                    vd_mul(vd_set1(u), vd_abs(out->r)));
}

/* v scaled by inv to nearly unit length (|v inv| = 1 + O(u)), then made
 * unit by lane_unit_newton; never -0. */
static ALWAYS_INLINE void lane_unit_scaled(const vd v[3], vd inv, vd out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = vd_mul(v[k], inv);
    lane_unit_newton(out);
    for (int k = 0; k < 3; k++)
        out[k] = vd_add(out[k], vd_zero());
}

/* t clamped into [tmin, tmax]: the parameter reported for a crossing
 * decided to lie in the interval, which its rounded value may have left by
 * an ulp or two. */
static ALWAYS_INLINE vd lane_clamp_t(vd t, const lane_ray *r)
{
    return vd_min(vd_max(t, r->tmin), r->tmax);
}

/*
 * -num/den for double-doubles num (within e_num) and den (within e_den),
 * renormalised, den.hi != 0, given inv = fl(1/den.hi): t as a double-double
 * (dd_mul_inv_dd: tau plus one correction, within 21u^2 |t| of the
 * quotient of the two double-doubles) and err >= |t.hi - exact|, the
 * first-order bound |t| (u + 40u^2 + e_den/|den|) + e_num/|den| (plane
 * lanes' quotient), widened by 2^-9: it holds while e_den <= 2^-20 |den|,
 * which `ok` says.
 */
typedef struct lane_quotient {
    vdd t;
    vd  err;
    vm  ok;
} lane_quotient;

static ALWAYS_INLINE void lane_quotient_neg(vdd num, vd e_num, vdd den, vd e_den, vd inv,
                                            lane_quotient *q)
{
    const double u = 0x1p-53;
    vdd minus_num = { vd_neg(num.hi), vd_neg(num.lo) };
    q->t = dd_mul_inv_dd(minus_num, den, inv);
    vd inv_abs = vd_mul(vd_abs(inv), vd_set1(1.0 + 0x1p-9));
    q->err = vd_mul(vd_add(vd_mul(vd_abs(q->t.hi), vd_add(vd_set1(u + 40.0 * u * u),
                                                            vd_mul(e_den, inv_abs))),
                           vd_mul(e_num, inv_abs)),
                    vd_set1(1.0 + 0x1p-9));
    q->ok = vd_le(e_den, vd_mul(vd_set1(0x1p-20), vd_abs(den.hi)));
}

/*
 * Starting values for the two roots of A t^2 + 2B t + C from plain
 * coefficients and the plain reduced discriminant G (any sign of A): never
 * -B + sqrt(G) with B > 0 (Haines et al.), q = -(B + sign(B) sqrt(G)) and
 * the roots q/A and C/q, both from one division, q/A = q^2/(qA), C/q =
 * CA/(qA). The entry root r- = (-B - sqrt(G))/A (where Q' = -2 sqrt(G) < 0)
 * is q/A when B >= 0, C/q when B < 0; the exit r+ the other. Only starting
 * values: a NaN or infinity (q A = 0) fails the refinement's certificate.
 */
static ALWAYS_INLINE void lane_quad_starts(vd a, vd b, vd c, vd g, vd *t_enter, vd *t_exit)
{
    vd s = vd_sqrt(vd_max(g, vd_zero()));
    vd q = vd_neg(vd_add(b, vd_copysign(s, b)));
    vd inv = vd_div(vd_set1(1.0), vd_mul(q, a));
    vd t_qa = vd_mul(vd_mul(q, q), inv), t_cq = vd_mul(vd_mul(c, a), inv);
    vm b_neg = vd_lt(b, vd_zero());
    *t_enter = vd_sel(b_neg, t_cq, t_qa);
    *t_exit = vd_sel(b_neg, t_qa, t_cq);
}

/* A refined root's verdict against [tmin, tmax] (ok: its bound holds):
 * certainly in and within 3.5u|t| (so t is within 4 ulp of the exact root:
 * ulp(t) > u|t|), certainly outside, or neither. */
static ALWAYS_INLINE vm lane_root_in(vm ok, vd t, vd err, const lane_ray *r)
{
    return vm_and(vm_and(ok, lane_certainly_in(t, err, r)),
                  vd_le(err, vd_mul(vd_set1(3.5 * 0x1p-53), vd_abs(t))));
}
static ALWAYS_INLINE vm lane_root_out(vm ok, vd t, vd err, const lane_ray *r)
{
    return vm_and(ok, lane_certainly_out(t, err, r));
}

/* A crossing refined from a start by a shape's refinement step. */
typedef struct lane_root {
    vd  t, err;  /* the refined parameter, |t - exact| <= err (when ok) */
    vdd t_dd;    /* the parameter as a double-double (t0 - step exactly) */
    vd  rho;     /* |exact - t_dd| <= rho (when ok) */
    vm  ok;      /* one root within err, and what the record needs certified */
    vm  enter;   /* Q' < 0 there: into the inside */
    vd  v[3];    /* the shape's vector at the root, for the normal */
    vd  vv;      /* and a scalar (e.g. its squared length) */
} lane_root;

/* One certified Newton step (lane_newton_certify, arguments as there) as
 * a root: t and its bound, t as a double-double (t0 - step exactly, within
 * rho), its kind; ok is the certificate alone (a shape adds what its
 * record needs). */
static ALWAYS_INLINE void lane_root_newton(vd t0, vd r, vd e_r, vd p, vd e_p, vd a, vd a_up,
                                           lane_newton *nt, lane_root *rt)
{
    lane_newton_certify(t0, r, e_r, p, e_p, a, a_up, nt);
    rt->t = nt->t;
    rt->err = nt->err;
    rt->enter = nt->enter;
    rt->t_dd = two_sum(t0, vd_neg(nt->step));
    rt->rho = nt->rho;
    rt->ok = nt->ok;
    rt->vv = vd_zero();
}

/* The lanes of e where m, of f elsewhere. */
static ALWAYS_INLINE void lane_root_sel(vm m, const lane_root *e, const lane_root *f, lane_root *out)
{
    out->t = vd_sel(m, e->t, f->t);
    out->err = vd_sel(m, e->err, f->err);
    out->t_dd.hi = vd_sel(m, e->t_dd.hi, f->t_dd.hi);
    out->t_dd.lo = vd_sel(m, e->t_dd.lo, f->t_dd.lo);
    out->rho = vd_sel(m, e->rho, f->rho);
    out->ok = vm_or(vm_and(m, e->ok), vm_andnot(f->ok, m));
    out->enter = vm_or(vm_and(m, e->enter), vm_andnot(f->enter, m));
    for (int k = 0; k < 3; k++)
        out->v[k] = vd_sel(m, e->v[k], f->v[k]);
    out->vv = vd_sel(m, e->vv, f->vv);
}

/* A shape's refinement (one certified Newton step from t0, over its
 * prepared constants and the ray's plain quantities), and an optional
 * further condition on a crossing (a cylinder's slab): in / out certain. */
typedef void (*lane_refine_fn)(const void *prep, const lane_ray *ray, const void *plain, vd t0,
                               lane_root *rt);
typedef void (*lane_clip_fn)(const void *data, const lane_root *rt, vm *in, vm *out);

/*
 * The verdicts on a line's two crossings (lower t first), shared by the
 * quadric family's kernels. A crossing is reported (in) where its root is
 * certified, of the kind expected of it, certainly in [tmin, tmax] and
 * within 3.5u|t|, and inside whatever the clip requires; certainly not
 * (out) where certified and certainly outside either. The upper crossing
 * is refined only where needed: for the first hit when the lower one is
 * out but not certainly after tmax, for all hits unless it is. decided[i]
 * says in[i] is certain; a crossing decided here is decided the same way,
 * with the same record, in every query, so a scalar all-hits path asks its
 * exact path only for the undecided ones (hits_merge).
 */
typedef struct lane_pair {
    vm plain_slow;  /* nothing decided (maybe tangent, out of range, ...) */
    vm slow;        /* the first hit is not decided */
    vm in[2];       /* lower, upper: reported */
    vm decided[2];  /* in[i] is certain (crossing i absent, out or in) */
} lane_pair;

/* What the plain solve knows. */
typedef struct lane_pair_plain {
    vm cross;       /* two crossings, certainly (else none, unless slow) */
    vm slow;        /* undecided: maybe tangent, out of range, ... */
    vm none;        /* the shape is degenerate: never hit */
    vm lo_enter;    /* the lower root is the entry (A > 0) */
    vd g_low;       /* <= the reduced discriminant G = B^2 - AC */
    vd a_up;        /* >= |A| */
    vd t_lo, t_hi;  /* starting values, lower root first */
} lane_pair_plain;

/*
 * Whether the two roots x < y of A t^2 + 2B t + C are more than 16u
 * max(|x|, |y|) apart, from a lower bound g_low > 0 of the reduced
 * discriminant (y - x = 2 sqrt(G)/|A|), a_up >= |A| and one root known to
 * lie within err of t: if neither root is twice the other, y - x > 32u
 * |t|-ish suffices, and otherwise y - x >= max/2 anyway. Then any values
 * within 4 ulp (8u) of the roots, from a kernel or from an exact path, and
 * clamped into [tmin, tmax] (monotone), keep the roots' order, so the
 * scalar call sorts the crossings as the batch assumes.
 */
static ALWAYS_INLINE vm lane_roots_apart(vd g_low, vd a_up, vd t, vd err)
{
    vd x = vd_mul(vd_mul(vd_set1(16.0 * 0x1p-53 * (1.0 + 0x1p-40)), vd_add(vd_abs(t), err)), a_up);
    return vd_gt(g_low, vd_mul(x, x));
}

static ALWAYS_INLINE vm lane_pair_need_hi(vm cross, vm lo_out, vm lo_beyond, int first)
{
    return vm_and(cross, first ? vm_andnot(lo_out, lo_beyond) : vm_not(lo_beyond));
}

/* cross: two crossings, certainly; apart: they are far enough apart to
 * keep their order (a pair that is not defers); lo_ and hi_ in / out as
 * above (hi_ only where need_hi). */
static ALWAYS_INLINE void lane_pair_decide(vm plain_slow, vm none, vm cross, vm apart, vm lo_in,
                                           vm lo_out, vm need_hi, vm hi_in, vm hi_out, lane_pair *pr)
{
    plain_slow = vm_or(plain_slow, vm_andnot(cross, apart));
    vm lo_decided = vm_or(vm_not(cross), vm_or(lo_in, lo_out));
    vm hi_decided = vm_or(vm_not(need_hi), vm_or(hi_in, hi_out));
    pr->plain_slow = vm_andnot(plain_slow, none);
    pr->decided[0] = vm_or(none, vm_andnot(lo_decided, plain_slow));
    pr->decided[1] = vm_or(none, vm_andnot(vm_and(hi_decided, lo_decided), plain_slow));
    pr->in[0] = vm_andnot(vm_and(cross, lo_in), none);
    pr->in[1] = vm_andnot(vm_and(need_hi, hi_in), none);
    pr->slow = vm_or(pr->plain_slow, vm_not(vm_and(pr->decided[0], pr->decided[1])));
}

/* One crossing's verdicts: its root of the kind `enter` says, in and out. */
static ALWAYS_INLINE vm lane_pair_verdict(const lane_root *rt, vm enter, lane_clip_fn clip,
                                          const void *clip_data, const lane_ray *ray, vm *in,
                                          vm *out)
{
    vm kind = vm_or(vm_and(rt->enter, enter), vm_andnot(vm_not(rt->enter), enter));
    vm ok = vm_and(rt->ok, kind);
    *in = lane_root_in(ok, rt->t, rt->err, ray);
    *out = lane_root_out(ok, rt->t, rt->err, ray);
    vm beyond = vm_and(*out, vd_gt(rt->t, ray->tmax));
    if (clip != NULL) {
        vm c_in, c_out;
        clip(clip_data, rt, &c_in, &c_out);
        *in = vm_and(*in, c_in);
        *out = vm_or(*out, vm_and(ok, c_out));
    }
    return beyond;
}

/* The two crossings: the lower refined always, the upper where needed;
 * reported parameters clamped into [tmin, tmax] (+0, never -0). */
static ALWAYS_INLINE void lane_pair_solve(lane_refine_fn refine, const void *prep,
                                          const void *plain, lane_clip_fn clip,
                                          const void *clip_data, const lane_pair_plain *pl,
                                          const lane_ray *ray, int first, lane_root root[2],
                                          lane_pair *pr)
{
    lane_root *lo = &root[0], *hi = &root[1];
    vm lo_in, lo_out, hi_in = vm_false(), hi_out = vm_false();
    refine(prep, ray, plain, pl->t_lo, lo);
    vm lo_beyond = lane_pair_verdict(lo, pl->lo_enter, clip, clip_data, ray, &lo_in, &lo_out);
    vm need_hi = lane_pair_need_hi(pl->cross, lo_out, lo_beyond, first);
    if (vm_any(vm_andnot(need_hi, pl->slow))) {
        refine(prep, ray, plain, pl->t_hi, hi);
        (void)lane_pair_verdict(hi, vm_not(pl->lo_enter), clip, clip_data, ray, &hi_in, &hi_out);
    } else {
        *hi = *lo;
    }
    vm apart = lane_roots_apart(pl->g_low, pl->a_up, lo->t, lo->err);
    lane_pair_decide(pl->slow, pl->none, pl->cross, apart, lo_in, lo_out, need_hi, hi_in, hi_out, pr);
    lo->t = vd_add(lane_clamp_t(lo->t, ray), vd_zero());
    hi->t = vd_add(lane_clamp_t(hi->t, ray), vd_zero());
}

/* The first hit's verdicts in h (found, slow) and the crossing to report:
 * the upper one where only it is in (returned as a mask). */
static ALWAYS_INLINE vm lane_pair_first(const lane_pair *pr, const lane_root root[2], lane_root *rt,
                                        lane_hit *h)
{
    vm upper = vm_andnot(pr->in[1], pr->in[0]);
    lane_root_sel(upper, &root[1], &root[0], rt);
    h->found = vm_andnot(vm_or(pr->in[0], pr->in[1]), pr->slow);
    h->slow = pr->slow;
    return upper;
}

#if LANE_W == 1
/*
 * The scalar all-hits call over a two-crossing kernel run on one ray
 * (first = 0), so that each crossing the kernel decides gets the record the
 * batch gives it: the exact path alone where the kernel decided nothing,
 * else each crossing from the kernel where decided and certified by its
 * record, from the exact path where not (hits_merge). record() writes
 * crossing i of the solved kernel (`solved`) and says whether that record
 * is certified; kind[] are the crossings' kinds.
 */
typedef int (*lane_record_fn)(const void *prep, const lane_ray *ray, const void *solved, int i,
                              lane_hit *h);
typedef int (*lane_exact_fn)(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                             isect_hit out[ISECT_MAX_HITS]);

static inline int lane_pair_hits(const lane_pair *pr, const int32_t kind[2], lane_record_fn record,
                                 const void *prep, const lane_ray *lr, const void *solved,
                                 lane_exact_fn exact, const isect_shape *s, const isect_ray *ray,
                                 const isect_params *prm, isect_hit out[ISECT_MAX_HITS])
{
    if (pr->plain_slow)
        return exact(s, ray, prm, out);
    isect_hit rec[2], found[ISECT_MAX_HITS];
    int decided[2], in[2], found_count = 0;
    for (int i = 0; i < 2; i++) {
        decided[i] = pr->decided[i];
        in[i] = pr->in[i];
        if (decided[i] && in[i]) {
            lane_hit h;
            decided[i] = record(prep, lr, solved, i, &h);
            lane_hit_store(&h, 0, &rec[i]);
        }
    }
    if (!decided[0] || !decided[1])
        found_count = exact(s, ray, prm, found);
    return hits_merge(rec, decided, in, kind, found, found_count, out);
}
#endif

#endif /* ISECT_PRIM_LANES_H */
