/* SPDX-License-Identifier: Apache-2.0 */
/*
 * convex_lanes.h — the convex polyhedron's fast kernel, LANE_W rays at once
 * (prim_lanes.h states the contract; convex.c holds the scalar call, which
 * runs this kernel with LANE_W = 1, and the exact path).
 *
 * enterMax / exitMin over the planes, each scaled by the power of two that
 * brings its normal's largest component into [0.5, 1) (exact). Per plane
 * and lane, in plain doubles: num = -(n.o + d) and den = n.dir, each within
 * 5u sum|terms| (a dot product of three terms plus one errs by at most
 * 4u sum|terms|; the fifth u covers the bound's own roundings); the
 * epsilon policy's parallel test den^2 <= eps^2 |n|^2 |dir|^2 decided where
 * the bound of den clears it by the roundings of the squares (12u), and a
 * parallel plane's side by the sign of num beyond its bound; otherwise
 * t = num/den within (e_num + |t| e_den)/(|den| - e_den) + u|t|. A plane
 * replaces the current entry (exit) only when strictly later (earlier), so
 * ties would go to the lowest index; every comparison that decides — plane
 * against the current one, entry against exit — must be certified (the
 * values further apart than their bounds), else the lane is deferred to the
 * exact path, as is any touch (entry == exit) and any parallel test or
 * sign within its bound.
 *
 * The record: the chosen plane's crossing recomputed as a double-double
 * with its bound (plane_lanes.h: lane_plane_crossing, the infinite plane's
 * arithmetic on the face each lane selected), its interval decision
 * certified, the point from the double-double t, the normal the scaled
 * face normal made unit (lane_unit_newton).
 */
#ifndef ISECT_CONVEX_LANES_H
#define ISECT_CONVEX_LANES_H

#include "prim/plane_lanes.h"
#include "prim/slab_lanes.h"
#include "core/scaling.h"

#define CONVEX_LANES_U    0x1p-53
#define CONVEX_LANES_TINY 0x1p-1000

typedef struct convex_prep {
    const double *planes; /* n x 4, as given */
    int           n;
    double        eps2;   /* eps^2, rounded (the bound covers it) */
} convex_prep;

static inline void convex_prepare(const double *planes, int n, double eps, convex_prep *cp)
{
    cp->planes = planes;
    cp->n = n;
    cp->eps2 = eps * eps;
}

/* Plane i scaled: n' = n 2^-e, d' = d 2^-e, e the exponent of max|n_k|. */
static ALWAYS_INLINE void convex_plane_scaled(const double *planes, int i, double out[4])
{
    const double *pl = planes + 4 * (int64_t)i;
    int e = pow2_exponent(max_abs3(pl));
    for (int k = 0; k < 4; k++)
        out[k] = pow2_scale(pl[k], -e);
}

/* The selection's outcome per lane. */
typedef struct convex_lanes {
    vd t_enter, t_exit;       /* plain values; -inf / +inf: none */
    vd face_enter, face_exit; /* plane indices (-1: none) */
    vd n_enter[4], n_exit[4]; /* those planes, scaled */
    vm miss;                  /* certainly no point of the line is inside */
    vm certain;               /* every decision above certified */
} convex_lanes;

static ALWAYS_INLINE void convex_lanes_solve(const convex_prep *cp, const lane_ray *r,
                                             convex_lanes *out)
{
    const vd u5 = vd_set1(5.0 * CONVEX_LANES_U), tiny = vd_set1(CONVEX_LANES_TINY);
    const vd *o = r->org, *dir = r->dir;
    vd dd = vd_add(vd_add(vd_mul(dir[0], dir[0]), vd_mul(dir[1], dir[1])), vd_mul(dir[2], dir[2]));
    lane_slab_end enter, leave;
    lane_slab_end_init(&enter, -INFINITY);
    lane_slab_end_init(&leave, INFINITY);
    for (int k = 0; k < 4; k++)
        out->n_enter[k] = out->n_exit[k] = vd_zero();
    vm certain = vm_true(), outside = vm_false();
    for (int i = 0; i < cp->n; i++) {
        double pl[4];
        convex_plane_scaled(cp->planes, i, pl);
        vd n0 = vd_set1(pl[0]), n1 = vd_set1(pl[1]), n2 = vd_set1(pl[2]), d = vd_set1(pl[3]);
        vd p0 = vd_mul(n0, o[0]), p1 = vd_mul(n1, o[1]), p2 = vd_mul(n2, o[2]);
        vd q0 = vd_mul(n0, dir[0]), q1 = vd_mul(n1, dir[1]), q2 = vd_mul(n2, dir[2]);
        vd num = vd_neg(vd_add(vd_add(vd_add(p0, p1), p2), d));
        vd num_err = vd_add(vd_mul(u5, vd_add(vd_add(vd_add(vd_abs(p0), vd_abs(p1)), vd_abs(p2)),
                                              vd_abs(d))),
                            tiny);
        vd den = vd_add(vd_add(q0, q1), q2);
        vd den_err = vd_add(vd_mul(u5, vd_add(vd_add(vd_abs(q0), vd_abs(q1)), vd_abs(q2))), tiny);

        /* the parallel test, certified or deferred */
        double nn = pl[0] * pl[0] + pl[1] * pl[1] + pl[2] * pl[2];
        vd thr = vd_mul(vd_set1(cp->eps2 * nn), dd);
        vd lo = vd_sub(vd_abs(den), den_err), hi = vd_add(vd_abs(den), den_err);
        vm crossing = vm_and(vd_gt(lo, vd_zero()),
                             vd_gt(vd_mul(vd_mul(lo, lo), vd_set1(1.0 - 4.0 * CONVEX_LANES_U)),
                                   vd_mul(thr, vd_set1(1.0 + 12.0 * CONVEX_LANES_U))));
        vm parallel = vd_lt(vd_mul(vd_mul(hi, hi), vd_set1(1.0 + 4.0 * CONVEX_LANES_U)),
                            vd_mul(thr, vd_set1(1.0 - 12.0 * CONVEX_LANES_U)));
        /* a parallel plane: the origin's side (num < 0: outside), only
         * where num clears its bound — an outside verdict ends the lane as
         * certain whatever else is undecided, so it must be certain itself */
        vm side_known = vd_gt(vd_abs(num), num_err);
        certain = vm_and(certain, vm_or(crossing, vm_and(parallel, side_known)));
        outside = vm_or(outside, vm_and(vm_and(parallel, side_known), vd_lt(num, vd_zero())));

        vd t = vd_div(num, den);
        vd t_abs = vd_abs(t);
        vd t_err = vd_add(vd_mul(vd_add(vd_div(vd_add(num_err, vd_mul(t_abs, den_err)), lo),
                                        vd_mul(vd_set1(CONVEX_LANES_U), t_abs)),
                                 vd_set1(1.0 + 8.0 * CONVEX_LANES_U)),
                          tiny);
        vm entering = vm_and(crossing, vd_lt(den, vd_zero()));
        vm leaving = vm_andnot(crossing, entering);
        vd face = vd_set1((double)i);
        vm later = lane_slab_take(&enter, entering, t, t_err, face, 1, &certain);
        vm earlier = lane_slab_take(&leave, leaving, t, t_err, face, 0, &certain);
        const vd nv[4] = { n0, n1, n2, d };
        for (int k = 0; k < 4; k++) {
            out->n_enter[k] = vd_sel(later, nv[k], out->n_enter[k]);
            out->n_exit[k] = vd_sel(earlier, nv[k], out->n_exit[k]);
        }
    }
    /* entry against exit (an absent one is infinite, apart from the other) */
    certain = vm_and(certain, lane_apart(enter.t, leave.t, vd_add(enter.err, leave.err)));
    out->t_enter = enter.t;
    out->t_exit = leave.t;
    out->face_enter = enter.face;
    out->face_exit = leave.face;
    out->miss = vm_or(outside, vd_gt(enter.t, leave.t));
    out->certain = vm_or(outside, certain);
}

/* The crossing of the plane nv (per lane) as a record of kind `kind`:
 * `in` and `out_of_range` its certified interval verdicts. */
static ALWAYS_INLINE void convex_lanes_record(const vd nv[4], vd face, vd kind, const lane_ray *r,
                                              lane_hit *h, vm *in, vm *out_of_range)
{
    lane_plane_cross c;
    lane_plane_crossing(nv[0], nv[1], nv[2], nv[3], r, &c);
    *in = lane_plane_cross_in(&c, r);
    *out_of_range = lane_certainly_out(c.t.hi, c.err, r);
    h->t = vd_add(lane_clamp_t(c.t.hi, r), vd_zero());
    lane_point_on_ray(r, c.t, h->point);
    vd len = vd_sqrt(vd_add(vd_add(vd_mul(nv[0], nv[0]), vd_mul(nv[1], nv[1])), vd_mul(nv[2], nv[2])));
    for (int k = 0; k < 3; k++)
        h->normal[k] = vd_div(nv[k], len);
    lane_unit_newton(h->normal);
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = face;
    h->kind = kind;
}

/* The first hit: the entry where it lies in [tmin, tmax], else the exit.
 * Both records are formed (no branches on the outcome) and selected. */
static ALWAYS_INLINE void convex_lanes_first(const convex_prep *cp, const lane_ray *r, lane_hit *h)
{
    convex_lanes cl;
    convex_lanes_solve(cp, r, &cl);
    lane_hit enter, leave;
    vm enter_in, enter_out, leave_in, leave_out;
    convex_lanes_record(cl.n_enter, cl.face_enter, vd_set1((double)ISECT_ENTER), r, &enter,
                        &enter_in, &enter_out);
    convex_lanes_record(cl.n_exit, cl.face_exit, vd_set1((double)ISECT_EXIT), r, &leave,
                        &leave_in, &leave_out);
    vm has_enter = vd_ge(cl.face_enter, vd_zero()), has_exit = vd_ge(cl.face_exit, vd_zero());
    /* each present crossing decided in or out; the entry first */
    vm decided = vm_and(vm_or(vm_not(has_enter), vm_or(enter_in, enter_out)),
                        vm_or(vm_not(has_exit), vm_or(leave_in, leave_out)));
    vm take_enter = vm_and(has_enter, enter_in);
    vm take_exit = vm_andnot(vm_and(has_exit, leave_in), take_enter);
    h->t = vd_sel(take_enter, enter.t, leave.t);
    for (int k = 0; k < 3; k++) {
        h->point[k] = vd_sel(take_enter, enter.point[k], leave.point[k]);
        h->normal[k] = vd_sel(take_enter, enter.normal[k], leave.normal[k]);
    }
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = vd_sel(take_enter, enter.prim, leave.prim);
    h->kind = vd_sel(take_enter, enter.kind, leave.kind);
    vm ok = lane_ray_in_range(r, 0x1p200);
    h->slow = vm_not(vm_and(ok, vm_or(vm_and(cl.certain, cl.miss),
                                      vm_and(cl.certain, decided))));
    h->found = vm_andnot(vm_andnot(vm_or(take_enter, take_exit), cl.miss), h->slow);
}

#endif /* ISECT_CONVEX_LANES_H */
