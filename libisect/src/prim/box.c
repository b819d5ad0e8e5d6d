/*
 * box.c — the closed axis-aligned box lo <= x <= hi (ISECT_AABB), data =
 * lo[3], hi[3]; faces 0..5 = -x, +x, -y, +y, -z, +z.
 *
 * Slab method. On an axis with dir != 0 the line is inside the slab for t
 * between (lo - org)/dir and (hi - org)/dir; the entry is the largest slab
 * entry and the exit the smallest slab exit. On an axis with dir == 0 the
 * slab does not depend on t: the whole line is inside iff lo <= org <= hi
 * (closed), else it misses. That case is decided by comparison before any
 * division, so no 0/0, 0*inf or inf-inf is ever formed and no NaN can reach
 * the output whatever the inputs (a dir component of -0.0 counts as zero).
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
 *  - Ties and TOUCH are decided on the computed t values, which are correctly
 *    rounded quotients whenever lo - org (resp. hi - org) is exact, as it is
 *    for the dyadic coordinates of test cases; two exactly equal slab
 *    parameters therefore always compare equal. Two distinct parameters that
 *    round to the same double count as a tie too (no exact arithmetic here:
 *    this kernel is on the batch hot path).
 *
 * Hits are for the whole line; the dispatcher keeps tmin <= t <= tmax, so an
 * origin inside the box yields only the EXIT, and an origin on a face yields
 * the hit at t = 0 (reported as +0.0, never -0.0).
 *
 * Flat boxes (lo == hi on an axis) are degenerate: no hits, no points inside.
 */
#include "prim/prim.h"

#include <float.h>

/*
 * Ray parameter at which coordinate o + t*d reaches `plane`, for d != 0:
 * (plane - o)/d, two roundings, the quotient correctly rounded from the
 * difference. The difference is finite for finite inputs unless both are
 * near +-DBL_MAX with opposite signs; then both are halved first (exact at
 * that magnitude) and the quotient doubled, which is bit for bit the plain
 * formula evaluated with an unbounded exponent, or +-inf when t itself is
 * beyond the double range. A finite numerator over a nonzero d is never NaN;
 * a tiny d may give +-inf, which the comparisons handle.
 */
static inline double slab_t(double plane, double o, double d)
{
    double diff = plane - o;
    if (!(fabs(diff) <= DBL_MAX))
        return ((0.5 * plane - 0.5 * o) / d) * 2.0;
    return diff / d;
}

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

int aabb_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
              isect_hit out[ISECT_MAX_HITS])
{
    const double *bound = s->data; /* lo[3], hi[3] */
    double t_enter = -INFINITY, t_exit = INFINITY;
    int face_enter = -1, face_exit = -1;
    (void)prm; /* no tolerance: faces are exact planes, corners are ties */

    /* The outcomes below are data-dependent (random rays mispredict half of
     * them), so the per-axis work is written as indexed loads, min/max
     * selects and masks rather than branches. The branches left are taken
     * the same way for almost every ray: a flat box, a zero dir component,
     * the overflow fallback in slab_t. */
    for (int a = 0; a < 3; a++) {
        double o = ray->org[a], d = ray->dir[a];
        double lo = bound[a], hi = bound[a + 3];
        if (!(lo < hi))
            return 0; /* flat: degenerate */
        if (d == 0.0) {
            if (o < lo || o > hi)
                return 0;
            continue; /* the slab is (-inf, inf): it never wins a comparison */
        }
        /* Going backwards (d < 0) the line meets hi first: near face 2a+1. */
        int backward = d < 0.0;
        double t_near = slab_t(bound[3 * backward + a], o, d);
        double t_far = slab_t(bound[3 * (1 - backward) + a], o, d);
        /* Strict comparisons: on a tie the earlier axis, i.e. the lower face
         * index, keeps its place (the tied values are equal, up to the sign
         * of a zero, which box_hit drops). */
        int later = t_near > t_enter, earlier = t_far < t_exit;
        face_enter ^= (face_enter ^ (2 * a + backward)) & -later;
        face_exit ^= (face_exit ^ (2 * a + 1 - backward)) & -earlier;
        t_enter = t_enter < t_near ? t_near : t_enter; /* maxsd */
        t_exit = t_exit > t_far ? t_far : t_exit;       /* minsd */
    }

    if (t_enter > t_exit)
        return 0;
    /* t = +-inf means the crossing lies beyond the double range (a subnormal
     * dir component): it is not a point of the ray and is not reported. */
    if (t_enter == t_exit) {
        if (!isfinite(t_enter))
            return 0;
        int low = face_enter < face_exit ? face_enter : face_exit;
        box_hit(&out[0], ray, bound, t_enter, low, face_enter + face_exit - low, ISECT_TOUCH);
        return 1;
    }
    int count = 0;
    if (isfinite(t_enter)) {
        box_hit(&out[count], ray, bound, t_enter, face_enter, face_enter, ISECT_ENTER);
        count++;
    }
    if (isfinite(t_exit)) {
        box_hit(&out[count], ray, bound, t_exit, face_exit, face_exit, ISECT_EXIT);
        count++;
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
