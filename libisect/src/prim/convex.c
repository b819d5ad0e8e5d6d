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
#include "core/ddx.h"
#include "core/expansion.h"
#include "core/ratio.h"
#include "core/scaling.h"
#include "core/vec3.h"

/* v' = v * 2^-e with e the exponent of max|v_i| (frexp), so max|v'_i| is in
 * [0.5, 1); returns e. A zero vector stays zero (e = 0). */
static int scale_to_unit_exponent(double out[3], const double v[3])
{
    int e;
    (void)frexp(fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))), &e);
    for (int k = 0; k < 3; k++)
        out[k] = ldexp(v[k], -e);
    return e;
}

/* Plane i scaled as described above: n' = n * 2^-e, d' = d * 2^-e. */
static void load_plane(const double *planes, int i, double n[3], double *d)
{
    const double *pl = planes + 4 * (int64_t)i;
    *d = ldexp(pl[3], -scale_to_unit_exponent(n, pl));
}

/* n_i/|n_i| from the scaled normal (no overflow at any scale); nonzero. */
static void unit_normal(const double *planes, int i, double normal[3])
{
    double n[3], d;
    load_plane(planes, i, n, &d);
    double len = sqrt(v3_dot(n, n));
    for (int k = 0; k < 3; k++)
        normal[k] = n[k] / len;
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

/* num_i and den_i certified. */
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
 * |dir|^2), certified or exact. */
static int plane_parallel(const convex_line *cl, int i, ddx den)
{
    double n[3], d;
    load_plane(cl->planes, i, n, &d);
    ddx nn = ddx_of(0.0), dd = ddx_of(0.0);
    for (int k = 0; k < 3; k++) {
        nn = ddx_add(nn, ddx_sqr(ddx_of(n[k])));
        dd = ddx_add(dd, ddx_sqr(ddx_of(cl->dir[k])));
    }
    int c = ddx_cmp_certain(ddx_sqr(den), ddx_mul(ddx_mul(nn, dd), ddx_sqr(ddx_of(cl->eps))));
    if (c != 2)
        return c <= 0;
    xp num_x, den_x, nn_x, dd_x;
    plane_exact(cl, i, &num_x, &den_x, &nn_x, &dd_x);
    return parallel_exact(&den_x, &nn_x, &dd_x, cl->eps);
}

/* The sign of a certified value, exactly: ddx, else num_i (den = 0) or
 * den_i (den = 1) of plane i as an expansion. */
static int plane_sign(const convex_line *cl, int i, ddx v, int which)
{
    int c = ddx_cmp_certain(v, ddx_of(0.0));
    if (c != 2)
        return c;
    xp num, den, nn, dd;
    plane_exact(cl, i, &num, &den, &nn, &dd);
    return xp_sign(which ? &den : &num);
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

/* The hit at crossing a when it lies in [tmin, tmax] (scaled units). */
static int cross_emit(const convex_line *cl, const convex_cross *a, int e_dir,
                      const isect_ray *ray, int32_t kind, isect_hit *out)
{
    double tmin = pow2_scale(ray->tmin, e_dir), tmax = pow2_scale(ray->tmax, e_dir);
    if (cross_cmp_tau(cl, a, tmin) < 0 || cross_cmp_tau(cl, a, tmax) > 0)
        return 0;
    double t_hi = a->t.hi, t_lo = a->t.lo;
    if (!(a->t.err <= 0x1p-53 * fabs(t_hi))) {
        xp num, den, nn, dd;
        plane_exact(cl, a->plane, &num, &den, &nn, &dd);
        ratio_value(&num, &den, &t_hi, &t_lo);
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

int convex_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                isect_hit out[ISECT_MAX_HITS])
{
    convex_line cl = { s->data, ray->org, { 0.0, 0.0, 0.0 }, prm->eps };
    int e_dir = scale_to_unit_exponent(cl.dir, ray->dir);
    convex_cross enter = { -1, { -INFINITY, 0.0, 0.0 } }, leave = { -1, { INFINITY, 0.0, 0.0 } };
    for (int i = 0; i < s->n; i++) {
        ddx num, den;
        plane_dd(&cl, i, &num, &den);
        if (!(isfinite(num.hi) && isfinite(den.hi)))
            return 0; /* geometry beyond the double range */
        if (plane_parallel(&cl, i, den)) {
            if (plane_sign(&cl, i, num, 0) < 0)
                return 0; /* origin outside a parallel face */
            continue;
        }
        convex_cross c = { i, ddx_div(num, den) };
        if (plane_sign(&cl, i, den, 1) < 0) {
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

int convex_contains(const isect_shape *s, const double p[3])
{
    convex_line cl = { s->data, p, { 0.0, 0.0, 0.0 }, 0.0 };
    for (int i = 0; i < s->n; i++) {
        ddx num, den;
        plane_dd(&cl, i, &num, &den);
        if (plane_sign(&cl, i, num, 0) < 0) /* n.p + d > 0 */
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
