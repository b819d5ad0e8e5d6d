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
#include "core/expansion.h"
#include "core/ratio.h"

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

/* The faces' crossings as exact ratios (plane - org)/dir. */
static void face_ratio(const double *bound, const isect_ray *ray, int face, xp *num, xp *den)
{
    int a = face >> 1;
    xp_diff(num, bound[3 * (face & 1) + a], ray->org[a]);
    xp_set(den, ray->dir[a]);
}

/* sign(t_f - t_g) for the crossings of faces f and g (g < 0: t = -inf for
 * an entry, +inf for an exit, given by `none`). */
static int face_cmp(const double *bound, const isect_ray *ray, int f, int g, int none)
{
    if (g < 0)
        return -none;
    xp nf, df, ng, dg;
    face_ratio(bound, ray, f, &nf, &df);
    face_ratio(bound, ray, g, &ng, &dg);
    return ratio_cmp(&nf, &df, &ng, &dg);
}

/* One hit on `face` if its exact t lies in [tmin, tmax]; t to a double-double
 * rounded once, clamped into the interval. */
static int face_emit(const double *bound, const isect_ray *ray, int face, int also_on, int32_t kind,
                     isect_hit *out)
{
    xp num, den;
    face_ratio(bound, ray, face, &num, &den);
    if (ratio_cmp_tau(&num, &den, ray->tmin) < 0 || ratio_cmp_tau(&num, &den, ray->tmax) > 0)
        return 0;
    double t_hi, t_lo;
    ratio_value(&num, &den, &t_hi, &t_lo);
    if (!isfinite(t_hi))
        return 0;
    box_hit(out, ray, bound, fmin(fmax(t_hi, ray->tmin), ray->tmax), face, also_on, kind);
    return 1;
}

/* The exact path: the same selection with every comparison exact. */
static int aabb_exact(const double *bound, const isect_ray *ray, isect_hit out[ISECT_MAX_HITS])
{
    int face_enter = -1, face_exit = -1;
    for (int a = 0; a < 3; a++) {
        double d = ray->dir[a];
        if (d == 0.0)
            continue; /* decided by the fast loop: the origin is inside the slab */
        int backward = d < 0.0;
        int near = 2 * a + backward, far = 2 * a + 1 - backward;
        if (face_cmp(bound, ray, near, face_enter, -1) > 0)
            face_enter = near;
        if (face_cmp(bound, ray, far, face_exit, 1) < 0)
            face_exit = far;
    }
    int order = face_cmp(bound, ray, face_enter, face_exit, 1);
    if (order > 0)
        return 0;
    if (order == 0) {
        int low = face_enter < face_exit ? face_enter : face_exit;
        return face_emit(bound, ray, low, face_enter + face_exit - low, ISECT_TOUCH, &out[0]);
    }
    int count = face_emit(bound, ray, face_enter, face_enter, ISECT_ENTER, &out[0]);
    return count + face_emit(bound, ray, face_exit, face_exit, ISECT_EXIT, &out[count]);
}

/* 2.5u: the bound on |t - exact| per unit |t| (see the top of the file). */
#define SLAB_ERR 0x1.4p-52
#define SLAB_TINY 0x1p-1070

/* t and tau are separated by more than err (false for NaN, and for an
 * infinite t, whose err is infinite). */
static inline int apart(double t, double tau, double err)
{
    return fabs(t - tau) > err;
}

int aabb_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
              isect_hit out[ISECT_MAX_HITS])
{
    const double *bound = s->data; /* lo[3], hi[3] */
    double t_enter = -INFINITY, t_exit = INFINITY, e_enter = 0.0, e_exit = 0.0;
    int face_enter = -1, face_exit = -1;
    int certain = 1;
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
        double e_near = SLAB_ERR * fabs(t_near) + SLAB_TINY;
        double e_far = SLAB_ERR * fabs(t_far) + SLAB_TINY;
        certain &= apart(t_near, t_enter, e_near + e_enter) & apart(t_far, t_exit, e_far + e_exit);
        /* Strict comparisons: on a tie the earlier axis, i.e. the lower face
         * index, keeps its place (exact ties go to the exact path). */
        int later = t_near > t_enter, earlier = t_far < t_exit;
        face_enter ^= (face_enter ^ (2 * a + backward)) & -later;
        face_exit ^= (face_exit ^ (2 * a + 1 - backward)) & -earlier;
        t_enter = later ? t_near : t_enter;
        e_enter = later ? e_near : e_enter;
        t_exit = earlier ? t_far : t_exit;
        e_exit = earlier ? e_far : e_exit;
    }
    /* Entry against exit, and each against tmin and tmax (an infinite tmin
     * or tmax is apart from any finite t). */
    certain &= apart(t_enter, t_exit, e_enter + e_exit);
    certain &= apart(t_enter, ray->tmin, e_enter) & apart(t_enter, ray->tmax, e_enter);
    certain &= apart(t_exit, ray->tmin, e_exit) & apart(t_exit, ray->tmax, e_exit);
    if (!certain)
        return aabb_exact(bound, ray, out);

    if (t_enter > t_exit)
        return 0;
    int count = 0;
    if (t_enter >= ray->tmin && t_enter <= ray->tmax) {
        box_hit(&out[count], ray, bound, t_enter, face_enter, face_enter, ISECT_ENTER);
        count++;
    }
    if (t_exit >= ray->tmin && t_exit <= ray->tmax) {
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
