/* SPDX-License-Identifier: Apache-2.0 */
/*
 * convex.c — the convex polyhedron given as the intersection of n >= 1
 * closed half-spaces a x + b y + c z + d <= 0 (ISECT_CONVEX), data =
 * planes[n][4] with outward normals (a, b, c). Unbounded sets (a half-space,
 * a slab, a wedge) and the empty set are valid input.
 *
 * enterMax / exitMin: along the line, plane i is crossed at
 * t_i = -(n_i.org + d_i) / (n_i.dir); it is an entry when n_i.dir < 0 and an
 * exit when > 0. The line is inside for enterMax <= t <= exitMin.
 *  - Parallel plane (|n.dir| <= eps |n| |dir|, the library's epsilon policy):
 *    no crossing; the whole line is on the side of its origin. Outside
 *    (n.org + d > 0): the line misses the polyhedron altogether; on the plane
 *    or inside: no constraint. A zero normal always takes this branch, so
 *    (0, 0, 0, d) is the empty set for d > 0 and all of space for d <= 0.
 *  - Ties: the lowest plane index keeps enterMax (exitMin): a plane only
 *    replaces it when strictly later (earlier), compared exactly, so two
 *    planes through the same edge tie exactly when the line meets that edge.
 *  - enterMax == exitMin: the line only touches the closed set (an edge or a
 *    vertex), a tie between the entering and the leaving plane: one TOUCH
 *    hit with the lower of the two indices and that plane's normal (the
 *    lowest index of all planes the line crosses there).
 *  - enterMax > exitMin: miss. Otherwise ENTER at enterMax if some plane is
 *    entered and EXIT at exitMin if some plane is left; an unbounded
 *    polyhedron may give only one of them, or none (the line lies inside).
 * Hits are for the whole line; the dispatcher filters [tmin, tmax].
 *
 * Numerics. Each plane is scaled by the power of two that brings its normal's
 * largest component into [0.5, 1), and dir likewise (exact, barring
 * underflow of parts 2^1022 times smaller than the largest). Each crossing
 * t_i = num_i/den_i, num_i = -(n_i.org + d_i), den_i = n_i.dir, is formed as
 * a double-double with an error bound (core/ddx.h); every decision — the
 * parallel test, the side of the origin, which plane is the latest entry
 * or earliest exit, entry against exit, [tmin, tmax] — is taken on those
 * where the bounds separate the values, and exactly otherwise (num and den
 * as expansions, core/ratio.c). t is reported from the double-double
 * (exact where its bound is above an ulp), the point from it (hit_set_dd).
 * All t_i are compared in units of the scaled dir (a common power-of-two
 * factor, which keeps their order) and converted once at the end. A t
 * beyond the double range is not reported.
 */
#include "prim/prim.h"
#include "prim/convex_lanes.h"
#include "core/ddx.h"
#include "core/expansion.h"
#include "core/ratio.h"
#include "core/scaling.h"
#include "core/vec3.h"

/* v' = v * 2^-e with e the exponent of max|v_i| (frexp), so max|v'_i| is in
 * [0.5, 1); returns e. A zero vector stays zero (e = 0). */
static int scale_to_unit_exponent(double out[3], const double v[3])
{
    int e = pow2_exponent(max_abs3(v));
    scale3(out, v, e);
    return e;
}

/* Plane i scaled as described above: n' = n * 2^-e, d' = d * 2^-e. */
static void load_plane(const double *planes, int i, double n[3], double *d)
{
    const double *pl = planes + 4 * (int64_t)i;
    *d = pow2_scale(pl[3], -scale_to_unit_exponent(n, pl));
}

/* n_i/|n_i| from the scaled normal (no overflow at any scale), unit to u;
 * nonzero. */
static void unit_normal(const double *planes, int i, double normal[3])
{
    double n[3], d;
    load_plane(planes, i, n, &d);
    unit3_accurate(normal, n);
}

int convex_check(const isect_shape *s)
{
    if (s->n < 1)
        return ISECT_E_ARG;
    return all_finite(s->data, 4 * (int64_t)s->n) ? ISECT_OK : ISECT_E_NONFINITE;
}

/* The line against the planes, in the scaled units above. */
typedef struct convex_line {
    const double *planes;
    const double *org;
    double dir[3];
    double eps;
} convex_line;

/* num_i and den_i in plain doubles with bounds on their errors (a dot
 * product of three terms plus one: at most 4u sum |terms|, taken as 5u for
 * the bound's own roundings), and the parallel test on them. */
typedef struct plane_fast {
    double num, num_err, den, den_err;
} plane_fast;

static void plane_fast_make(const convex_line *cl, int i, plane_fast *pf)
{
    double n[3], d;
    load_plane(cl->planes, i, n, &d);
    double p0 = n[0] * cl->org[0], p1 = n[1] * cl->org[1], p2 = n[2] * cl->org[2];
    double q0 = n[0] * cl->dir[0], q1 = n[1] * cl->dir[1], q2 = n[2] * cl->dir[2];
    pf->num = -(((p0 + p1) + p2) + d);
    pf->num_err = 5.0 * DDX_U * (((fabs(p0) + fabs(p1)) + fabs(p2)) + fabs(d)) + DDX_TINY;
    pf->den = (q0 + q1) + q2;
    pf->den_err = 5.0 * DDX_U * ((fabs(q0) + fabs(q1)) + fabs(q2)) + DDX_TINY;
}

/* num_i and den_i certified as double-doubles. */
static void plane_dd(const convex_line *cl, int i, ddx *num, ddx *den)
{
    double n[3], d;
    load_plane(cl->planes, i, n, &d);
    ddx side = ddx_of(d), dot = ddx_of(0.0);
    for (int k = 0; k < 3; k++) {
        side = ddx_add(side, ddx_mul_d(ddx_of(n[k]), cl->org[k]));
        dot = ddx_add(dot, ddx_mul_d(ddx_of(n[k]), cl->dir[k]));
    }
    *num = ddx_neg(side);
    *den = dot;
}

/* num_i, den_i exactly, and |n_i|^2, |dir|^2 for the parallel test. */
static void plane_exact(const convex_line *cl, int i, xp *num, xp *den, xp *nn, xp *dd)
{
    double n[3], d;
    load_plane(cl->planes, i, n, &d);
    xp tmp;
    xp_set(num, -d);
    xp_set(den, 0.0);
    xp_set(nn, 0.0);
    xp_set(dd, 0.0);
    for (int k = 0; k < 3; k++) {
        xp_set(&tmp, -n[k]);
        xp_scale(&tmp, &tmp, cl->org[k]);
        xp_add(num, num, &tmp);
        xp_set(&tmp, n[k]);
        xp_scale(&tmp, &tmp, cl->dir[k]);
        xp_add(den, den, &tmp);
        xp_set(&tmp, n[k]);
        xp_scale(&tmp, &tmp, n[k]);
        xp_add(nn, nn, &tmp);
        xp_set(&tmp, cl->dir[k]);
        xp_scale(&tmp, &tmp, cl->dir[k]);
        xp_add(dd, dd, &tmp);
    }
}

/* The parallel test |den| <= eps |n| |dir| (den^2 against eps^2 |n|^2
 * |dir|^2): certified from the plain values (|n|^2 |dir|^2 rounded within
 * 6u), else exact. */
static int plane_parallel(const convex_line *cl, int i, const plane_fast *pf)
{
    double n[3], d;
    load_plane(cl->planes, i, n, &d);
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    double dd = cl->dir[0] * cl->dir[0] + cl->dir[1] * cl->dir[1] + cl->dir[2] * cl->dir[2];
    double thr = cl->eps * cl->eps * nn * dd;
    double lo = fabs(pf->den) - pf->den_err, hi = fabs(pf->den) + pf->den_err;
    if (lo > 0.0 && lo * lo * (1.0 - 4.0 * DDX_U) > thr * (1.0 + 12.0 * DDX_U))
        return 0;
    if (hi * hi * (1.0 + 4.0 * DDX_U) < thr * (1.0 - 12.0 * DDX_U))
        return 1;
    xp num_x, den_x, nn_x, dd_x;
    plane_exact(cl, i, &num_x, &den_x, &nn_x, &dd_x);
    return parallel_exact(&den_x, &nn_x, &dd_x, cl->eps);
}

/* One crossing: plane index and certified t. */
typedef struct convex_cross {
    int plane;   /* -1: none (t = -inf or +inf) */
    ddx t;
} convex_cross;

/* sign(t_a - t_b) for two crossings, exactly. */
static int cross_cmp(const convex_line *cl, const convex_cross *a, const convex_cross *b)
{
    int c = ddx_cmp_certain(a->t, b->t);
    if (c != 2)
        return c;
    xp na, da, nb, db, nn, dd;
    plane_exact(cl, a->plane, &na, &da, &nn, &dd);
    plane_exact(cl, b->plane, &nb, &db, &nn, &dd);
    return ratio_cmp(&na, &da, &nb, &db);
}

/* sign(t - tau), exactly. */
static int cross_cmp_tau(const convex_line *cl, const convex_cross *a, double tau)
{
    if (isinf(tau))
        return tau < 0.0 ? 1 : -1;
    int c = ddx_cmp_certain(a->t, ddx_of(tau));
    if (c != 2)
        return c;
    xp num, den, nn, dd;
    plane_exact(cl, a->plane, &num, &den, &nn, &dd);
    return ratio_cmp_tau(&num, &den, tau);
}

/* The hit at crossing a when it lies in [tmin, tmax] (scaled units): its t
 * recomputed as a certified double-double first (the selection ran on
 * plain values), exactly where that is not within an ulp. */
static int cross_emit(const convex_line *cl, const convex_cross *a, int e_dir,
                      const isect_ray *ray, int32_t kind, isect_hit *out)
{
    ddx num, den;
    plane_dd(cl, a->plane, &num, &den);
    convex_cross c = { a->plane, ddx_div(num, den) };
    double tmin = pow2_scale(ray->tmin, e_dir), tmax = pow2_scale(ray->tmax, e_dir);
    if (cross_cmp_tau(cl, &c, tmin) < 0 || cross_cmp_tau(cl, &c, tmax) > 0)
        return 0;
    double t_hi = c.t.hi, t_lo = c.t.lo;
    if (!(c.t.err <= 0x1p-53 * fabs(t_hi))) {
        xp num_x, den_x, nn, dd;
        plane_exact(cl, a->plane, &num_x, &den_x, &nn, &dd);
        ratio_value(&num_x, &den_x, &t_hi, &t_lo);
    }
    t_hi = pow2_scale(t_hi, -e_dir) + 0.0; /* + 0.0: report t = 0 as +0.0 */
    t_lo = pow2_scale(t_lo, -e_dir);
    if (!isfinite(t_hi))
        return 0;
    double normal[3];
    unit_normal(cl->planes, a->plane, normal);
    hit_set_dd(out, ray, t_hi, t_lo, normal, a->plane, kind);
    return 1;
}

/* The sign of a plain value with its bound, exactly: num_i (which = 0) or
 * den_i (which = 1) as an expansion where the bound straddles 0. */
static int plane_sign(const convex_line *cl, int i, double v, double err, int which)
{
    if (fabs(v) > err)
        return v > 0.0 ? 1 : -1;
    xp num, den, nn, dd;
    plane_exact(cl, i, &num, &den, &nn, &dd);
    return xp_sign(which ? &den : &num);
}

/* The exact path (certified where it can, exact where not), for the rays
 * the kernel defers. */
static int convex_hits_exact(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                             isect_hit out[ISECT_MAX_HITS])
{
    convex_line cl = { s->data, ray->org, { 0.0, 0.0, 0.0 }, prm->eps };
    int e_dir = scale_to_unit_exponent(cl.dir, ray->dir);
    convex_cross enter = { -1, { -INFINITY, 0.0, 0.0 } }, leave = { -1, { INFINITY, 0.0, 0.0 } };
    for (int i = 0; i < s->n; i++) {
        plane_fast pf;
        plane_fast_make(&cl, i, &pf);
        if (!(isfinite(pf.num) && isfinite(pf.den)))
            return 0; /* geometry beyond the double range */
        if (plane_parallel(&cl, i, &pf)) {
            if (plane_sign(&cl, i, pf.num, pf.num_err, 0) < 0)
                return 0; /* origin outside a parallel face */
            continue;
        }
        /* t = num/den plain: |t - exact| <= (e_num + |t| e_den)/(|den| -
         * e_den) + the division's u|t| (infinite where den is within its
         * bound of 0: the comparisons then go exact) */
        double t = pf.num / pf.den;
        double margin = fabs(pf.den) - pf.den_err;
        double t_err = margin > 0.0
                     ? ((pf.num_err + fabs(t) * pf.den_err) / margin + DDX_U * fabs(t))
                           * (1.0 + 8.0 * DDX_U) + DDX_TINY
                     : INFINITY;
        convex_cross c = { i, { t, 0.0, t_err } };
        if (plane_sign(&cl, i, pf.den, pf.den_err, 1) < 0) {
            if (enter.plane < 0 || cross_cmp(&cl, &c, &enter) > 0)
                enter = c;
        } else if (leave.plane < 0 || cross_cmp(&cl, &c, &leave) < 0) {
            leave = c;
        }
    }
    int order = enter.plane < 0 || leave.plane < 0 ? -1 : cross_cmp(&cl, &enter, &leave);
    if (order > 0)
        return 0;
    if (order == 0) {
        convex_cross low = enter.plane < leave.plane ? enter : leave;
        return cross_emit(&cl, &low, e_dir, ray, ISECT_TOUCH, &out[0]);
    }
    int count = 0;
    if (enter.plane >= 0)
        count += cross_emit(&cl, &enter, e_dir, ray, ISECT_ENTER, &out[count]);
    if (leave.plane >= 0)
        count += cross_emit(&cl, &leave, e_dir, ray, ISECT_EXIT, &out[count]);
    return count;
}

int convex_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                isect_hit out[ISECT_MAX_HITS])
{
    /* the batch's kernel on this one ray (convex_lanes.h), so that the
     * first record is the batch's bit for bit */
    convex_prep cp;
    convex_prepare(s->data, s->n, prm->eps, &cp);
    lane_ray lr;
    lane_ray_from(&lr, ray);
    convex_lanes sel;
    convex_lanes_solve(&cp, &lr, &sel);
    if (!sel.certain || !lane_ray_in_range(&lr, 0x1p200))
        return convex_hits_exact(s, ray, prm, out);
    if (sel.miss)
        return 0;
    lane_hit rec[2];
    vm in[2], outside[2];
    int present[2] = { sel.face_enter >= 0.0, sel.face_exit >= 0.0 };
    convex_lanes_record(sel.n_enter, sel.face_enter, (double)ISECT_ENTER, &lr, &rec[0], &in[0],
                        &outside[0]);
    convex_lanes_record(sel.n_exit, sel.face_exit, (double)ISECT_EXIT, &lr, &rec[1], &in[1],
                        &outside[1]);
    for (int k = 0; k < 2; k++)
        if (present[k] && !in[k] && !outside[k])
            return convex_hits_exact(s, ray, prm, out);
    int count = 0;
    for (int k = 0; k < 2; k++)
        if (present[k] && in[k])
            lane_hit_store(&rec[k], 0, &out[count++]);
    return count;
}

int convex_contains(const isect_shape *s, const double p[3])
{
    convex_line cl = { s->data, p, { 0.0, 0.0, 0.0 }, 0.0 };
    for (int i = 0; i < s->n; i++) {
        plane_fast pf;
        plane_fast_make(&cl, i, &pf);
        if (plane_sign(&cl, i, pf.num, pf.num_err, 0) < 0) /* n.p + d > 0 */
            return 0;
    }
    return 1;
}

/* Outside if any plane's a.p + d is positive, strictly inside if all are
 * negative (each sign exact: plane_side_test on that plane). */
int convex_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    int all_negative = 1;
    for (int i = 0; i < s->n; i++) {
        const double *pl = s->data + 4 * (int64_t)i;
        int side;
        if (pl[0] == 0.0 && pl[1] == 0.0 && pl[2] == 0.0) {
            side = pl[3] > 0.0 ? 1 : pl[3] < 0.0 ? -1 : 0;
        } else {
            isect_shape plane = { ISECT_PLANE, 0, 0, 0, pl, NULL, NULL };
            side = plane_side_test(&plane, p, -1);
        }
        if (side > 0)
            return 1;
        all_negative &= side < 0;
    }
    return all_negative ? -1 : 0;
}

/* A convex polyhedron is flat on each face: the plane prim's a.d. */
int convex_tangent_side(const isect_shape *s, const double d[3], int32_t prim)
{
    if (prim < 0 || prim >= s->n)
        return SIDE_CURVED; /* not a face of this shape: the hit's normal decides */
    isect_shape plane = { ISECT_PLANE, 0, 0, 0, s->data + 4 * (int64_t)prim, NULL, NULL };
    return plane_tangent_side(&plane, d, -1);
}
