/* SPDX-License-Identifier: Apache-2.0 */
/*
 * box_lanes.h — the axis-aligned box's fast kernel, LANE_W rays at once
 * (prim_lanes.h states the contract; box.c holds the scalar call, which
 * runs this kernel with LANE_W = 1, and the exact path).
 *
 * The slab method with a forward error bound. On an axis with dir != 0 the
 * slab's crossings are t = (plane - org)/dir: the difference rounds once
 * (or is exact), the quotient once, so |t - exact| <= 2u|t| (plus the
 * underflow of a subnormal quotient); the bound is taken as 2.5u|t| +
 * 2^-1070 to cover the roundings of the bound itself. The entry is the
 * latest slab entry, the exit the earliest slab exit (a slab replaces the
 * current one only when strictly later / earlier, so on a tie the lower
 * face index would keep it). Every comparison that decides the answer —
 * slab against slab, entry against exit, each against tmin and tmax — is
 * certified when the values are further apart than their bounds; a lane
 * where one is not (an exact tie through an edge or corner, a touch, an
 * origin on a face, an infinite t from a tiny dir component, a difference
 * that overflows) is deferred to the exact path. An axis with dir == 0
 * (-0.0 included) is decided exactly by comparisons: the origin inside the
 * closed slab leaves the axis out, outside it the lane misses.
 *
 * The record: t, and the point org + t dir with the coordinate across the
 * face set to the face's plane exactly and the others clamped into
 * [lo, hi] (the point is on the box whatever the rounding), the face's
 * axis normal. A touch is never certified here, so the kinds are ENTER
 * (the entry in [tmin, tmax]) and EXIT (otherwise the exit, an origin
 * inside).
 */
#ifndef ISECT_BOX_LANES_H
#define ISECT_BOX_LANES_H

#include "prim/slab_lanes.h"

#define BOX_LANES_ERR  0x1.4p-52 /* 2.5u */
#define BOX_LANES_TINY 0x1p-1070

typedef struct box_prep {
    double bound[6]; /* lo[3], hi[3] */
    int    flat;     /* lo == hi on some axis: degenerate, never hit */
} box_prep;

static inline void box_prepare(const double *data, box_prep *bp)
{
    bp->flat = 0;
    for (int k = 0; k < 6; k++)
        bp->bound[k] = data[k];
    for (int a = 0; a < 3; a++)
        bp->flat |= !(data[a] < data[a + 3]);
}

/* The slabs' verdict for LANE_W lines. */
typedef struct box_lanes {
    vd t_enter, t_exit;
    vd face_enter, face_exit; /* face indices 0..5 (as doubles) */
    vm miss;                  /* certainly no point of the line is in the box */
    vm certain;               /* every comparison above is certified */
} box_lanes;

static ALWAYS_INLINE void box_lanes_solve(const box_prep *bp, const lane_ray *r, box_lanes *out)
{
    const vd err_k = vd_set1(BOX_LANES_ERR), tiny = vd_set1(BOX_LANES_TINY);
    lane_slab_end enter, leave;
    lane_slab_end_init(&enter, -INFINITY);
    lane_slab_end_init(&leave, INFINITY);
    vm certain = vm_true(), outside = vm_false();
    for (int a = 0; a < 3; a++) {
        vd o = r->org[a], d = r->dir[a];
        vd lo = vd_set1(bp->bound[a]), hi = vd_set1(bp->bound[a + 3]);
        vm zero = vd_eq(d, vd_zero());
        outside = vm_or(outside, vm_and(zero, vm_or(vd_lt(o, lo), vd_gt(o, hi))));
        /* going backwards (d < 0) the line meets hi first: near face 2a+1 */
        vm backward = vd_lt(d, vd_zero());
        vd d_safe = vd_sel(zero, vd_set1(1.0), d);
        vd t_near = vd_div(vd_sub(vd_sel(backward, hi, lo), o), d_safe);
        vd t_far = vd_div(vd_sub(vd_sel(backward, lo, hi), o), d_safe);
        vd e_near = vd_add(vd_mul(err_k, vd_abs(t_near)), tiny);
        vd e_far = vd_add(vd_mul(err_k, vd_abs(t_far)), tiny);
        vd near_face = vd_sel(backward, vd_set1(2.0 * a + 1.0), vd_set1(2.0 * a));
        vd far_face = vd_sel(backward, vd_set1(2.0 * a), vd_set1(2.0 * a + 1.0));
        (void)lane_slab_take(&enter, vm_not(zero), t_near, e_near, near_face, 1, &certain);
        (void)lane_slab_take(&leave, vm_not(zero), t_far, e_far, far_face, 0, &certain);
    }
    certain = vm_and(certain, lane_slab_ends_apart(&enter, &leave, r));
    out->t_enter = enter.t;
    out->t_exit = leave.t;
    out->face_enter = enter.face;
    out->face_exit = leave.face;
    out->miss = vm_or(outside, vd_gt(enter.t, leave.t));
    out->certain = vm_or(outside, certain);
}

/* The record of a hit on `face` at t (face as a double per lane). */
static ALWAYS_INLINE void box_lanes_record(const box_prep *bp, const lane_ray *r, vd t, vd face,
                                           vd kind, lane_hit *h)
{
    t = vd_add(t, vd_zero()); /* -0.0 -> +0.0: (0 - o)/-d gives -0.0 */
    h->t = t;
    for (int a = 0; a < 3; a++) {
        vd lo = vd_set1(bp->bound[a]), hi = vd_set1(bp->bound[a + 3]);
        vd p = vd_add(r->org[a], vd_mul(t, r->dir[a]));
        p = vd_min(hi, vd_max(lo, p));
        vm on_lo = vd_eq(face, vd_set1(2.0 * a)), on_hi = vd_eq(face, vd_set1(2.0 * a + 1.0));
        h->point[a] = vd_sel(on_lo, lo, vd_sel(on_hi, hi, p));
        h->normal[a] = vd_sel(on_lo, vd_set1(-1.0), vd_sel(on_hi, vd_set1(1.0), vd_zero()));
    }
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = face;
    h->kind = kind;
}

/* The first hit: the entry where it lies in [tmin, tmax], else the exit. */
static ALWAYS_INLINE void box_lanes_first(const box_prep *bp, const lane_ray *r, lane_hit *h)
{
    box_lanes bl;
    box_lanes_solve(bp, r, &bl);
    vm enter_in = vm_and(vd_ge(bl.t_enter, r->tmin), vd_le(bl.t_enter, r->tmax));
    vm exit_in = vm_and(vd_ge(bl.t_exit, r->tmin), vd_le(bl.t_exit, r->tmax));
    vd t = vd_sel(enter_in, bl.t_enter, bl.t_exit);
    vd face = vd_sel(enter_in, bl.face_enter, bl.face_exit);
    vd kind = vd_sel(enter_in, vd_set1((double)ISECT_ENTER), vd_set1((double)ISECT_EXIT));
    box_lanes_record(bp, r, t, face, kind, h);
    h->slow = bp->flat ? vm_false() : vm_not(bl.certain);
    h->found = bp->flat ? vm_false()
                        : vm_andnot(vm_andnot(vm_or(enter_in, exit_in), bl.miss), h->slow);
}

#endif /* ISECT_BOX_LANES_H */
