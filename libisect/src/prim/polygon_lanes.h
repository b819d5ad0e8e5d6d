/* SPDX-License-Identifier: Apache-2.0 */
/*
 * polygon_lanes.h — a lone polygon's fast kernel, LANE_W rays at once
 * (prim_lanes.h states the contract; polygon.c holds the exact path): the
 * winding number of the frame origin from face_lanes.h's certified signs,
 * the crossing with the Newell plane from triangle_lanes.h's double-double
 * solve, the record. The plane (poly_plane: Newell normal and centroid as
 * double-doubles, planar.h) is prepared once per call or batch, by
 * polygon_prepare in polygon.c, so every instruction set sees the same
 * bits.
 */
#ifndef ISECT_POLYGON_LANES_H
#define ISECT_POLYGON_LANES_H

#include "prim/triangle_lanes.h"
#include "prim/planar.h"

typedef struct poly_prep {
    const double *v;   /* n x 3 vertices */
    int           n, rule;
    poly_plane    plane;
    int           in_range;   /* vertices and centroid within 2^200 */
    int           degenerate; /* no area: never hit (plane zeroed) */
} poly_prep;

void polygon_prepare(const double *v, int n, int rule, poly_prep *pp);

/*
 * A lane is found when every sign of the winding count was certified, the
 * count is inside by the fill rule, and the crossing is certified in
 * [tmin, tmax]; neither when the certified count is outside or the crossing
 * certainly out of range; slow otherwise (the exact path redoes the
 * uncertain signs exactly and the crossing from the same plane).
 */
static ALWAYS_INLINE void poly_lanes_first(const poly_prep *pp, const lane_ray *ray, lane_hit *h)
{
    face_axes fa;
    face_axes_make(ray, &fa);
    face_winding fw;
    face_winding_lanes(pp->v, NULL, pp->n, ray, &fa, &fw);
    vm inside = pp->rule == ISECT_NONZERO ? vm_not(vd_eq(fw.winding, vd_zero()))
                                          : vd_gt(fw.odd, vd_zero());
    tri_plane pl;
    vd m_hi[3], m_lo[3];
    for (int k = 0; k < 3; k++) {
        pl.n[k].hi = vd_set1(pp->plane.n_hi[k]);
        pl.n[k].lo = vd_set1(pp->plane.n_lo[k]);
        pl.err[k] = vd_set1(pp->plane.n_err[k]);
        m_hi[k] = vd_set1(pp->plane.m_hi[k]);
        m_lo[k] = vd_set1(pp->plane.m_lo[k]);
    }
    tri_crossing tc;
    tri_crossing_solve(&pl, m_hi, m_lo, vd_set1(pp->plane.m_err), ray, &tc);

    vm ok = pp->in_range ? lane_ray_in_range(ray, 0x1p200) : vm_false();
    vm decided = vm_and(fw.certain, vm_or(vm_not(inside), vm_or(tc.in, tc.out)));
    h->slow = pp->degenerate ? vm_false() : vm_not(vm_and(ok, decided));
    h->found = pp->degenerate ? vm_false() : vm_andnot(vm_and(inside, tc.in), h->slow);

    h->t = vd_add(lane_clamp_t(tc.t.hi, ray), vd_zero());
    lane_point_on_ray(ray, tc.t, h->point);
    for (int k = 0; k < 3; k++)
        h->normal[k] = vd_set1(pp->plane.unit[k]);
    h->uv[0] = h->uv[1] = vd_zero();
    h->prim = vd_set1(-1.0);
    h->kind = vd_sel(tc.enter, vd_set1((double)ISECT_ENTER), vd_set1((double)ISECT_EXIT));
}

#endif /* ISECT_POLYGON_LANES_H */
