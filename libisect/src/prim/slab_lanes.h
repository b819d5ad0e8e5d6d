/* SPDX-License-Identifier: Apache-2.0 */
/*
 * slab_lanes.h — enterMax / exitMin with certified comparisons, in the lane
 * vocabulary: the bookkeeping the box's slabs and the convex polyhedron's
 * planes share (box_lanes.h, convex_lanes.h).
 *
 * Each candidate crossing carries its value t and a bound err on |t -
 * exact|. A candidate replaces the current end only when strictly later
 * (entries) or earlier (exits), so on a tie the earlier candidate — the
 * lower face or plane index — keeps it; the comparison counts as certified
 * only when the two values are further apart than their bounds together
 * (then the exact order is the computed one); otherwise the caller defers
 * the lane to its exact path.
 */
#ifndef ISECT_SLAB_LANES_H
#define ISECT_SLAB_LANES_H

#include "prim/prim_lanes.h"

/* The current entry or exit: t (-inf / +inf: none yet), its bound, its
 * face or plane index (-1: none). */
typedef struct lane_slab_end {
    vd t, err, face;
} lane_slab_end;

static ALWAYS_INLINE void lane_slab_end_init(lane_slab_end *end, double t_none)
{
    end->t = vd_set1(t_none);
    end->err = vd_zero();
    end->face = vd_set1(-1.0);
}

/* |t - tau| > err: false for NaN, and for an infinite t (whose bound is
 * infinite); true against an infinite tau for a finite t and err. */
static ALWAYS_INLINE vm lane_apart(vd t, vd tau, vd err)
{
    return vd_gt(vd_abs(vd_sub(t, tau)), err);
}

/* The candidate (t, err, face) in the lanes of `cand`: takes the end's
 * place where strictly later (later != 0) or earlier; returns the lanes it
 * replaced, and clears *certain in candidate lanes whose comparison is not
 * certified. */
static ALWAYS_INLINE vm lane_slab_take(lane_slab_end *end, vm cand, vd t, vd err, vd face,
                                       int later, vm *certain)
{
    vm apart = lane_apart(t, end->t, vd_add(err, end->err));
    *certain = vm_and(*certain, vm_or(vm_not(cand), apart));
    vm beyond = later ? vd_gt(t, end->t) : vd_lt(t, end->t);
    vm take = vm_and(cand, beyond);
    end->t = vd_sel(take, t, end->t);
    end->err = vd_sel(take, err, end->err);
    end->face = vd_sel(take, face, end->face);
    return take;
}

/* The entry against the exit, and each against tmin and tmax, certified
 * (an absent end is infinite and apart from any finite value). */
static ALWAYS_INLINE vm lane_slab_ends_apart(const lane_slab_end *enter, const lane_slab_end *leave,
                                             const lane_ray *r)
{
    vm ok = lane_apart(enter->t, leave->t, vd_add(enter->err, leave->err));
    ok = vm_and(ok, vm_and(lane_apart(enter->t, r->tmin, enter->err),
                           lane_apart(enter->t, r->tmax, enter->err)));
    return vm_and(ok, vm_and(lane_apart(leave->t, r->tmin, leave->err),
                             lane_apart(leave->t, r->tmax, leave->err)));
}

#endif /* ISECT_SLAB_LANES_H */
