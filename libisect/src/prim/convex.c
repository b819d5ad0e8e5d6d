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
 *    replaces it when strictly later (earlier). Ties are decided on the
 *    computed t_i (no exact arithmetic), so two planes through the same edge
 *    tie when their t_i round to the same double.
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
 * largest component into [0.5, 1), and dir likewise. The scaling is exact
 * (barring underflow of parts 2^1022 times smaller than the largest), so the
 * signs of n.p + d and the ratios t_i are those of the plane as given and as
 * evaluated in plain double precision, ((a x + b y) + c z) + d, while n.dir,
 * |n|, |dir| cannot overflow at any scale. All t_i are compared in units of
 * the scaled dir (a common power-of-two factor, which keeps their order) and
 * converted once at the end. A t beyond the double range is not reported.
 */
#include "prim/prim.h"
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

int convex_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                isect_hit out[ISECT_MAX_HITS])
{
    double dir[3];
    int e_dir = scale_to_unit_exponent(dir, ray->dir);
    double dir_len = sqrt(v3_dot(dir, dir));

    double t_enter = -INFINITY, t_exit = INFINITY; /* in units of the scaled dir */
    int plane_enter = -1, plane_exit = -1;
    for (int i = 0; i < s->n; i++) {
        double n[3], d;
        load_plane(s->data, i, n, &d);
        double side = v3_dot(n, ray->org) + d;
        double n_dot_dir = v3_dot(n, dir);
        if (fabs(n_dot_dir) <= prm->eps * sqrt(v3_dot(n, n)) * dir_len) {
            if (!(side <= 0.0))
                return 0; /* origin outside a parallel face (NaN: beyond range) */
            continue;
        }
        double t = -side / n_dot_dir;
        if (isnan(t))
            return 0; /* side overflowed both ways: geometry beyond the double range */
        if (n_dot_dir < 0.0) {
            if (t > t_enter) {
                t_enter = t;
                plane_enter = i;
            }
        } else if (t < t_exit) {
            t_exit = t;
            plane_exit = i;
        }
    }
    if (t_enter > t_exit)
        return 0;

    int touch = t_enter == t_exit;
    t_enter = ldexp(t_enter, -e_dir) + 0.0; /* + 0.0: report t = 0 as +0.0 */
    t_exit = ldexp(t_exit, -e_dir) + 0.0;
    int count = 0;
    double normal[3];
    if (touch) {
        if (!isfinite(t_enter))
            return 0;
        int low = plane_enter < plane_exit ? plane_enter : plane_exit;
        unit_normal(s->data, low, normal);
        hit_set(&out[0], ray, t_enter, normal, low, ISECT_TOUCH);
        return 1;
    }
    if (isfinite(t_enter)) {
        unit_normal(s->data, plane_enter, normal);
        hit_set(&out[count++], ray, t_enter, normal, plane_enter, ISECT_ENTER);
    }
    if (isfinite(t_exit)) {
        unit_normal(s->data, plane_exit, normal);
        hit_set(&out[count++], ray, t_exit, normal, plane_exit, ISECT_EXIT);
    }
    return count;
}

int convex_contains(const isect_shape *s, const double p[3])
{
    for (int i = 0; i < s->n; i++) {
        double n[3], d;
        load_plane(s->data, i, n, &d);
        if (!(v3_dot(n, p) + d <= 0.0))
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
