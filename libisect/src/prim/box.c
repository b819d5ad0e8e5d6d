/* SPDX-License-Identifier: Apache-2.0 */
/*
 * box.c — the closed axis-aligned box lo <= x <= hi (ISECT_AABB), data =
 * lo[3], hi[3]; faces 0..5 = -x, +x, -y, +y, -z, +z.
 *
 * Slab method (the fast kernel is box_lanes.h, which the batch runs on
 * several rays at once and this file's scalar call on one): on an axis with
 * dir != 0 the line is inside the slab for t between (lo - org)/dir and
 * (hi - org)/dir; the entry is the largest slab entry and the exit the
 * smallest slab exit. On an axis with dir == 0 the slab does not depend on
 * t: the whole line is inside iff lo <= org <= hi (closed), else it misses,
 * decided by comparison before any division (a dir component of -0.0 counts
 * as zero).
 *
 * Which face is reported, and why:
 *  - Ties between faces (the line crosses an edge or a corner, so several slab
 *    entries, or exits, are the same double) go to the LOWEST face index. The
 *    axes are scanned x, y, z and a slab only replaces the current entry
 *    (exit) when strictly later (earlier); each axis contributes one entry
 *    and one exit face, so the first axis to reach the extreme value, i.e. the
 *    lowest index, keeps it.
 *  - entry == exit: the line meets the closed box in a single point, on an
 *    edge or a corner it grazes. That point is a tie between the entry face
 *    and the exit face, so the same rule applies: one TOUCH hit with the
 *    lower of the two indices and that face's outward normal (which is the
 *    lowest index of all faces the line crosses there). Its point lies on
 *    both faces and is snapped onto both planes.
 *  - Ties, TOUCH and [tmin, tmax] are decided exactly. The fast loop keeps
 *    a bound on each t (the quotient's rounding and that of lo - org: at
 *    most 2u|t|, taken as 2.5u|t| + 2^-1070 for the roundings of the bound
 *    itself); where two compared values (or a value and tmin / tmax) are
 *    within their bounds — an exact tie, a line through an edge, an origin
 *    on a face — or a t is infinite, the whole box is redone by the exact
 *    path, which compares the crossings (plane - org)/dir as ratios of
 *    expansions (core/ratio.c).
 *
 * The kernel reports the hits in [tmin, tmax] (the dispatcher's range filter
 * then keeps them all: t is clamped into the interval where its rounding
 * left it), so an origin inside the box yields only the EXIT, and an origin
 * on a face the hit at t = 0 (reported as +0.0, never -0.0).
 *
 * Flat boxes (lo == hi on an axis) are degenerate: no hits, no points inside.
 */
#include "prim/prim.h"
#include "prim/box_lanes.h"
#include "core/expansion.h"
#include "core/ratio.h"
#include "core/scaling.h"

#include <float.h>

/*
 * Fill one hit on `face`. The point is org + t*dir, then pulled onto the
 * surface it is known to lie on: the coordinate across `face` (and across
 * `also_on`, the other face of a TOUCH, which the point lies on as well) is
 * set to that face's plane exactly, and the others are clamped into
 * [lo, hi]. That removes the rounding of org + t*dir, and keeps the point
 * finite even where t*dir overflows. bound = lo[3], hi[3], so face f's plane
 * is bound[3*(f & 1) + f/2]: indexed, not branched on.
 */
static inline void box_hit(isect_hit *h, const isect_ray *ray, const double *bound, double t,
                           int face, int also_on, int32_t kind)
{
    t += 0.0; /* -0.0 -> +0.0 (round-to-nearest); (0 - o)/-d gives -0.0 */
    h->t = t;
    for (int a = 0; a < 3; a++) {
        double p = ray->org[a] + t * ray->dir[a];
        p = bound[a] > p ? bound[a] : p;         /* maxsd */
        p = bound[a + 3] < p ? bound[a + 3] : p; /* minsd */
        h->point[a] = p;
        h->normal[a] = 0.0;
    }
    h->point[also_on >> 1] = bound[3 * (also_on & 1) + (also_on >> 1)];
    h->point[face >> 1] = bound[3 * (face & 1) + (face >> 1)]; /* wins if same axis */
    h->normal[face >> 1] = (double)(2 * (face & 1) - 1);
    h->uv[0] = 0.0;
    h->uv[1] = 0.0;
    h->prim = face;
    h->kind = kind;
}

int aabb_check(const isect_shape *s)
{
    const double *lo = s->data, *hi = s->data + 3;
    if (!all_finite(s->data, 6))
        return ISECT_E_NONFINITE;
    for (int a = 0; a < 3; a++)
        if (lo[a] > hi[a])
            return ISECT_E_ARG;
    return ISECT_OK;
}

/* The faces' crossings as exact ratios (plane - org)/dir, in positions
 * scaled by `scale` (1, or 1/4 where a difference could overflow: exact at
 * that magnitude), so the ratios are t * scale. */
static double exact_scale(const double *bound, const isect_ray *ray)
{
    double m = max_abs3(ray->org);
    for (int k = 0; k < 6; k++)
        m = fmax_nan(m, fabs(bound[k]));
    return m >= 0x1p1020 ? 0.25 : 1.0;
}

static void face_ratio(const double *bound, const isect_ray *ray, double scale, int face, xp *num,
                       xp *den)
{
    int a = face >> 1;
    xp_diff(num, scale * bound[3 * (face & 1) + a], scale * ray->org[a]);
    xp_set(den, ray->dir[a]);
}

/* sign(t_f - t_g) for the crossings of faces f and g (g < 0: t = -inf for
 * an entry, +inf for an exit, given by `none`). */
static int face_cmp(const double *bound, const isect_ray *ray, double scale, int f, int g,
                    int none)
{
    if (g < 0)
        return -none;
    xp nf, df, ng, dg;
    face_ratio(bound, ray, scale, f, &nf, &df);
    face_ratio(bound, ray, scale, g, &ng, &dg);
    return ratio_cmp(&nf, &df, &ng, &dg);
}

/* One hit on `face` if its exact t lies in [tmin, tmax]; t to a double-double
 * rounded once, clamped into the interval. */
static int face_emit(const double *bound, const isect_ray *ray, double scale, int face,
                     int also_on, int32_t kind, isect_hit *out)
{
    xp num, den;
    face_ratio(bound, ray, scale, face, &num, &den);
    if (ratio_cmp_tau(&num, &den, scale * ray->tmin) < 0
        || ratio_cmp_tau(&num, &den, scale * ray->tmax) > 0)
        return 0;
    double t_hi, t_lo;
    ratio_value(&num, &den, &t_hi, &t_lo);
    t_hi /= scale;
    if (!isfinite(t_hi))
        return 0;
    box_hit(out, ray, bound, fmin(fmax(t_hi, ray->tmin), ray->tmax), face, also_on, kind);
    return 1;
}

/* The exact path: the same selection with every comparison exact (the
 * kernel has already decided the axes with dir == 0: the origin lies in
 * their slabs). */
static int aabb_exact(const double *bound, const isect_ray *ray, isect_hit out[ISECT_MAX_HITS])
{
    double scale = exact_scale(bound, ray);
    int face_enter = -1, face_exit = -1;
    for (int a = 0; a < 3; a++) {
        double d = ray->dir[a];
        if (d == 0.0)
            continue; /* decided by the fast loop: the origin is inside the slab */
        int backward = d < 0.0;
        int near = 2 * a + backward, far = 2 * a + 1 - backward;
        if (face_cmp(bound, ray, scale, near, face_enter, -1) > 0)
            face_enter = near;
        if (face_cmp(bound, ray, scale, far, face_exit, 1) < 0)
            face_exit = far;
    }
    int order = face_cmp(bound, ray, scale, face_enter, face_exit, 1);
    if (order > 0)
        return 0;
    if (order == 0) {
        int low = face_enter < face_exit ? face_enter : face_exit;
        return face_emit(bound, ray, scale, low, face_enter + face_exit - low, ISECT_TOUCH, &out[0]);
    }
    int count = face_emit(bound, ray, scale, face_enter, face_enter, ISECT_ENTER, &out[0]);
    return count + face_emit(bound, ray, scale, face_exit, face_exit, ISECT_EXIT, &out[count]);
}

int aabb_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
              isect_hit out[ISECT_MAX_HITS])
{
    (void)prm; /* no tolerance: faces are exact planes, corners are ties */
    box_prep bp;
    box_prepare(s->data, &bp);
    if (bp.flat)
        return 0;
    /* the batch's kernel on this one ray (box_lanes.h), so the first record
     * is the batch's bit for bit */
    lane_ray lr;
    lane_ray_from(&lr, ray);
    box_lanes bl;
    box_lanes_solve(&bp, &lr, &bl);
    if (!bl.certain)
        return aabb_exact(s->data, ray, out);
    if (bl.miss)
        return 0;
    int count = 0;
    if (bl.t_enter >= ray->tmin && bl.t_enter <= ray->tmax) {
        int face = (int)bl.face_enter;
        box_hit(&out[count++], ray, s->data, bl.t_enter, face, face, ISECT_ENTER);
    }
    if (bl.t_exit >= ray->tmin && bl.t_exit <= ray->tmax) {
        int face = (int)bl.face_exit;
        box_hit(&out[count++], ray, s->data, bl.t_exit, face, face, ISECT_EXIT);
    }
    return count;
}

int aabb_contains(const isect_shape *s, const double p[3])
{
    const double *lo = s->data, *hi = s->data + 3;
    int inside = 1;
    for (int a = 0; a < 3; a++)
        inside &= (lo[a] < hi[a]) & (lo[a] <= p[a]) & (p[a] <= hi[a]);
    return inside;
}

int aabb_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    const double *lo = s->data, *hi = s->data + 3;
    int inside = 1;
    for (int a = 0; a < 3; a++) {
        if (!(lo[a] < hi[a]) || p[a] < lo[a] || p[a] > hi[a])
            return 1; /* flat (degenerate), or outside */
        inside &= lo[a] < p[a] && p[a] < hi[a];
    }
    return inside ? -1 : 0;
}
