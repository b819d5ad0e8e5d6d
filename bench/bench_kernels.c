/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bench_kernels.c — every analytic primitive's isect_intersect_batch against
 * the textbook loop a user would write instead.
 *
 * Part 1, compute (N = 4096 rays, every buffer in cache). For each primitive
 * the library's batch call (closest hit per ray, full 80-byte isect_hit
 * records) is timed against a plain double loop written below, in this file,
 * that computes the same things a user needs into the same records: the
 * closest t in [tmin, tmax], point = org + t*dir, the unit normal, ENTER or
 * EXIT, the face index where the shape has faces (MISS: t = inf, prim = -1).
 * The textbook loops use the classic formulas (each stated above its code)
 * with no tolerance and no special cases beyond what the formulas need; this
 * file is compiled with -O2 -march=native (and GCC's default FMA contraction)
 * like a user's own code, while the library is linked as the Makefile builds
 * it (build/libisect.a). Target: libisect's throughput at least half the
 * textbook loop's (ratio >= 0.5) for every primitive.
 *
 * Timing: B blocks; in each block every primitive in turn runs P pairs of
 * calls, library and textbook alternately first, after an untimed warm-up
 * pair. A pair's ratio is textbook time / library time (the throughput
 * ratio libisect/textbook of two calls made moments apart); the reported
 * ratio is its median over all pairs, and its range the min-max of the
 * per-block medians (a busy period of the shared machine then shows in one
 * block of every primitive, and the overall median lies inside the range).
 * Both loops' records are compared afterwards: hit/miss agreement and the
 * largest relative t difference on rays both hit (a large difference means
 * a wrong textbook loop; -v prints the disagreeing rays).
 *
 * Part 2, memory (N = 4M rays, no buffer fits in any cache): the batch call
 * for the sphere, box, triangle and plane against a streaming copy of the
 * same bytes (read every ray, write every hit record), interleaved, medians.
 * Target: batch/copy <= 2.0.
 *
 * Rays: a fixed-seed xorshift generator; origins on the sphere of radius 4
 * around the shape's centre, aimed at uniform points of a cube around it,
 * in random order. The cube's half-width is set per primitive by bisection
 * so that about half of the rays hit (by the textbook loop, so the rays do
 * not change when the library does). The plane and the hyperboloid, which
 * are unbounded, hit more than half even at the widest cube (64), so they
 * keep that one (about 51 %).
 *
 *     bench_kernels [-v] [--blocks B] [--stream-reps R] [results.json]
 *         (default bench/results/kernels.json; --stream-reps 0 skips part 2)
 *
 * Prints the tables and writes the same numbers as JSON. Exit status 1 only
 * if something failed (allocation, a library error, the results file), not
 * for a missed target.
 */
#define _POSIX_C_SOURCE 200809L

#include "isect.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define SMALL_N 4096
#define LARGE_N (4 * 1024 * 1024)
#define DEFAULT_BLOCKS 15
#define PAIRS_PER_BLOCK 40 /* even: each loop goes first equally often */
#define DEFAULT_STREAM_REPS 9
#define RATIO_TARGET 0.5
#define STREAM_TARGET 2.0
#define RNG_SEED 0x9E3779B97F4A7C15ull
#define ORIGIN_RADIUS 4.0
#define AIM_MIN 0.01
#define AIM_MAX 64.0
#define KERNELS 13
#define MAX_DATA 64
#define MAX_POLYGON 16
#define MAX_PLANES 16
#define DEFAULT_RESULTS "bench/results/kernels.json"
#define RESULTS_DIR "bench/results"

typedef struct kernel kernel;
/* A textbook loop: closest hit of rays[0..n) into out[0..n). */
typedef void (*textbook_fn)(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out);

struct kernel {
    const char *name;
    int32_t     type, count, flags; /* the isect_shape fields */
    double      data[MAX_DATA];     /* the library's numbers (object space if transformed) */
    int         transformed;
    double      m[16], inv[16];     /* object-to-world and its inverse, row-major */
    isect_xform xform;
    double      center[3];          /* where the rays aim (world space) */
    textbook_fn textbook;
    int         stream;             /* also in part 2 */
    /* Filled by the run. */
    double      aim;                /* half-width of the cube of aim points */
    isect_ray  *rays;
    isect_hit  *lib_hits, *tb_hits;
    double     *lib_times, *tb_times; /* [blocks * PAIRS_PER_BLOCK] seconds */
    double      lib_median, tb_median, ratio, ratio_lo, ratio_hi;
    double      hit_fraction, agreement, max_rel_dt, max_point_diff, max_normal_diff;
    int64_t     disagreements, kind_prim_diffs;
    double      stream_batch, stream_copy, stream_ratio, stream_lo, stream_hi;
    double      stream_hit_fraction;
};

/* ------------------------------------------------------------ vectors */

static inline double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void sub3(double out[3], const double a[3], const double b[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static inline void cross3(double out[3], const double a[3], const double b[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline void unit3(double v[3])
{
    double s = 1.0 / sqrt(dot3(v, v));
    v[0] *= s;
    v[1] *= s;
    v[2] *= s;
}

/* Row-major 4x4 affine matrices: m p (point), m v (vector), m^T v. */
static inline void mat_point(const double m[16], const double p[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
}

static inline void mat_vector(const double m[16], const double v[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[4 * i] * v[0] + m[4 * i + 1] * v[1] + m[4 * i + 2] * v[2];
}

static inline void mat_transpose_vector(const double m[16], const double v[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[i] * v[0] + m[4 + i] * v[1] + m[8 + i] * v[2];
}

static void mat_mul(const double a[16], const double b[16], double out[16])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            out[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j]
                           + a[4 * i + 3] * b[12 + j];
}

/* ------------------------------------------------------------ records */

static inline void put_miss(isect_hit *h)
{
    h->t = INFINITY;
    h->point[0] = h->point[1] = h->point[2] = 0.0;
    h->normal[0] = h->normal[1] = h->normal[2] = 0.0;
    h->uv[0] = h->uv[1] = 0.0;
    h->prim = -1;
    h->kind = ISECT_MISS;
}

/* A hit at t with the given unit normal: point = org + t*dir. */
static inline void put_hit(isect_hit *h, const isect_ray *r, double t, const double normal[3],
                           int prim, int kind)
{
    h->t = t;
    h->point[0] = r->org[0] + t * r->dir[0];
    h->point[1] = r->org[1] + t * r->dir[1];
    h->point[2] = r->org[2] + t * r->dir[2];
    h->normal[0] = normal[0];
    h->normal[1] = normal[1];
    h->normal[2] = normal[2];
    h->uv[0] = h->uv[1] = 0.0;
    h->prim = prim;
    h->kind = kind;
}

static inline int in_range(double t, const isect_ray *r)
{
    return t >= r->tmin && t <= r->tmax;
}

/* ------------------------------------------------------ textbook loops */

/* Plane n.x + d = 0: t = -(n.o + d)/(n.d); ENTER when n.d < 0. */
static void tb_plane(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *pn = k->data, d = k->data[3];
    double unit[3] = { pn[0], pn[1], pn[2] };
    unit3(unit);
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double nd = dot3(pn, r->dir);
        double t = -(dot3(pn, r->org) + d) / nd;
        if (nd != 0.0 && in_range(t, r))
            put_hit(&out[i], r, t, unit, -1, nd < 0.0 ? ISECT_ENTER : ISECT_EXIT);
        else
            put_miss(&out[i]);
    }
}

/* Sphere |x - c| = r, f = o - c: t = (-(f.d) -+ sqrt((f.d)^2 - |d|^2 (|f|^2 - r^2))) / |d|^2.
 * The first root in [tmin, tmax] into *t; returns its kind (ENTER for the
 * smaller root, EXIT for the larger) or MISS. */
static inline int sphere_first(const double c[3], double radius, const double o[3],
                               const double d[3], double tmin, double tmax, double *t)
{
    double f[3];
    sub3(f, o, c);
    double a = dot3(d, d), b = dot3(f, d), cc = dot3(f, f) - radius * radius;
    double disc = b * b - a * cc;
    if (disc < 0.0)
        return ISECT_MISS;
    double sq = sqrt(disc);
    double t0 = (-b - sq) / a, t1 = (-b + sq) / a;
    if (t0 >= tmin && t0 <= tmax) {
        *t = t0;
        return ISECT_ENTER;
    }
    if (t1 >= tmin && t1 <= tmax) {
        *t = t1;
        return ISECT_EXIT;
    }
    return ISECT_MISS;
}

/* Sphere: the quadratic above; normal = (p - c)/r. */
static void tb_sphere(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *c = k->data, radius = k->data[3];
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double t, p[3], normal[3];
        int kind = sphere_first(c, radius, r->org, r->dir, r->tmin, r->tmax, &t);
        if (kind == ISECT_MISS) {
            put_miss(&out[i]);
            continue;
        }
        for (int j = 0; j < 3; j++) {
            p[j] = r->org[j] + t * r->dir[j];
            normal[j] = (p[j] - c[j]) / radius;
        }
        put_hit(&out[i], r, t, normal, -1, kind);
    }
}

/* Box lo <= x <= hi (Kay-Kajiya slabs): per axis t = (lo - o)/d and (hi - o)/d;
 * enter = the largest near t, exit = the smallest far t, a hit when enter <= exit;
 * the face is the slab that gave the t. The first of them in [tmin, tmax] into *t
 * and its face (0..5 = -x,+x,-y,+y,-z,+z); returns ENTER, EXIT or MISS. */
static inline int box_first(const double lo[3], const double hi[3], const double o[3],
                            const double d[3], double tmin, double tmax, double *t, int *face)
{
    double near[3], far[3];
    for (int j = 0; j < 3; j++) {
        double inv = 1.0 / d[j];
        double t_lo = (lo[j] - o[j]) * inv, t_hi = (hi[j] - o[j]) * inv;
        near[j] = t_lo < t_hi ? t_lo : t_hi;
        far[j] = t_lo < t_hi ? t_hi : t_lo;
    }
    double enter = near[0] > near[1] ? near[0] : near[1];
    enter = enter > near[2] ? enter : near[2];
    double exit = far[0] < far[1] ? far[0] : far[1];
    exit = exit < far[2] ? exit : far[2];
    if (enter > exit)
        return ISECT_MISS;
    int kind = enter >= tmin && enter <= tmax ? ISECT_ENTER
             : exit >= tmin && exit <= tmax  ? ISECT_EXIT
                                             : ISECT_MISS;
    const double *slab = kind == ISECT_ENTER ? near : far;
    *t = kind == ISECT_ENTER ? enter : exit;
    int axis = *t == slab[0] ? 0 : *t == slab[1] ? 1 : 2;
    /* The far face of the slab for d > 0 is hi, for d < 0 lo; the near face the other. */
    *face = 2 * axis + ((d[axis] > 0.0) == (kind == ISECT_EXIT));
    return kind;
}

/* Outward unit normal of box face f. */
static inline void box_normal(int face, double normal[3])
{
    double sign = face % 2 ? 1.0 : -1.0;
    normal[0] = face / 2 == 0 ? sign : 0.0;
    normal[1] = face / 2 == 1 ? sign : 0.0;
    normal[2] = face / 2 == 2 ? sign : 0.0;
}

/* Box: the slabs above. */
static void tb_box(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *lo = k->data, *hi = k->data + 3;
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double t, normal[3];
        int face;
        int kind = box_first(lo, hi, r->org, r->dir, r->tmin, r->tmax, &t, &face);
        if (kind == ISECT_MISS) {
            put_miss(&out[i]);
            continue;
        }
        box_normal(face, normal);
        put_hit(&out[i], r, t, normal, face, kind);
    }
}

/* Triangle (Moller-Trumbore): solve o + t d = a + u (b - a) + v (c - a) by Cramer's
 * rule, p = d x e2, q = (o - a) x e1: det = e1.p, u = (o - a).p/det, v = d.q/det,
 * t = e2.q/det; a hit when u >= 0, v >= 0, u + v <= 1. */
static void tb_triangle(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *a = k->data, *b = k->data + 3, *c = k->data + 6;
    double e1[3], e2[3], normal[3];
    sub3(e1, b, a);
    sub3(e2, c, a);
    cross3(normal, e1, e2);
    unit3(normal);
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double p[3], q[3], s[3];
        cross3(p, r->dir, e2);
        double det = dot3(e1, p);
        if (det == 0.0) {
            put_miss(&out[i]);
            continue;
        }
        double inv = 1.0 / det;
        sub3(s, r->org, a);
        double u = dot3(s, p) * inv;
        cross3(q, s, e1);
        double v = dot3(r->dir, q) * inv;
        double t = dot3(e2, q) * inv;
        if (u < 0.0 || v < 0.0 || u + v > 1.0 || !in_range(t, r)) {
            put_miss(&out[i]);
            continue;
        }
        put_hit(&out[i], r, t, normal, -1, det > 0.0 ? ISECT_ENTER : ISECT_EXIT);
        out[i].uv[0] = u;
        out[i].uv[1] = v;
    }
}

/* Crossing number (even-odd) of the 2D point (px, py) in the polygon xy[nv][2]:
 * count the edges that straddle the horizontal line y = py to the right of px. */
static inline int crossing_inside(const double *xy, int nv, double px, double py)
{
    int inside = 0;
    for (int i = 0, j = nv - 1; i < nv; j = i++) {
        double xi = xy[2 * i], yi = xy[2 * i + 1], xj = xy[2 * j], yj = xy[2 * j + 1];
        if ((yi > py) != (yj > py) && px < xj + (py - yj) * (xi - xj) / (yi - yj))
            inside = !inside;
    }
    return inside;
}

/* Polygon: Newell's normal n and d = -n.v0, the plane hit t = -(n.o + d)/(n.d),
 * then the crossing number of the hit point with everything projected onto
 * the two axes other than n's largest component. */
static void tb_polygon(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *v = k->data;
    int nv = k->count;
    double normal[3] = { 0.0, 0.0, 0.0 }, xy[2 * MAX_POLYGON];
    for (int i = 0, j = nv - 1; i < nv; j = i++) {
        const double *a = v + 3 * j, *b = v + 3 * i;
        normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
        normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
        normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    unit3(normal);
    double d = -dot3(normal, v);
    int drop = fabs(normal[0]) > fabs(normal[1])
                 ? (fabs(normal[0]) > fabs(normal[2]) ? 0 : 2)
                 : (fabs(normal[1]) > fabs(normal[2]) ? 1 : 2);
    int ax = (drop + 1) % 3, ay = (drop + 2) % 3;
    for (int i = 0; i < nv; i++) {
        xy[2 * i] = v[3 * i + ax];
        xy[2 * i + 1] = v[3 * i + ay];
    }
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double nd = dot3(normal, r->dir);
        double t = -(dot3(normal, r->org) + d) / nd;
        if (nd == 0.0 || !in_range(t, r)
            || !crossing_inside(xy, nv, r->org[ax] + t * r->dir[ax], r->org[ay] + t * r->dir[ay])) {
            put_miss(&out[i]);
            continue;
        }
        put_hit(&out[i], r, t, normal, -1, nd < 0.0 ? ISECT_ENTER : ISECT_EXIT);
    }
}

/* Convex polyhedron (enterMax/exitMin): plane j, n.x + d <= 0 inside, meets the ray at
 * t = -(n.o + d)/(n.d), an entry when n.d < 0, an exit when n.d > 0 (n.d = 0: outside
 * for ever when n.o + d > 0); a hit when the last entry <= the first exit. */
static void tb_convex(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *pl = k->data;
    int m = k->count;
    double unit[3 * MAX_PLANES];
    for (int j = 0; j < m; j++) {
        unit[3 * j] = pl[4 * j], unit[3 * j + 1] = pl[4 * j + 1], unit[3 * j + 2] = pl[4 * j + 2];
        unit3(unit + 3 * j);
    }
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double enter = -INFINITY, exit = INFINITY;
        int enter_plane = -1, exit_plane = -1, outside = 0;
        for (int j = 0; j < m && !outside; j++) {
            double nd = dot3(pl + 4 * j, r->dir), no = dot3(pl + 4 * j, r->org) + pl[4 * j + 3];
            double t = -no / nd;
            if (nd < 0.0 && t > enter)
                enter = t, enter_plane = j;
            else if (nd > 0.0 && t < exit)
                exit = t, exit_plane = j;
            else if (nd == 0.0 && no > 0.0)
                outside = 1;
        }
        /* (An unbounded polyhedron may have no entry or no exit plane.) */
        if (!outside && enter <= exit && enter_plane >= 0 && in_range(enter, r))
            put_hit(&out[i], r, enter, unit + 3 * enter_plane, enter_plane, ISECT_ENTER);
        else if (!outside && enter <= exit && enter < r->tmin && exit_plane >= 0
                 && in_range(exit, r))
            put_hit(&out[i], r, exit, unit + 3 * exit_plane, exit_plane, ISECT_EXIT);
        else
            put_miss(&out[i]);
    }
}

/* Cylinder side |w - (w.a) a| = r with w = o + t d - p, a the unit axis: with f = o - p,
 * f' = f - (f.a) a and d' = d - (d.a) a,
 * t = (-(f'.d') -+ sqrt((f'.d')^2 - |d'|^2 (|f'|^2 - r^2))) / |d'|^2.
 * Returns 0 when the line misses it (or runs parallel to the axis). */
static inline int cylinder_roots(const double p[3], const double a[3], double radius,
                                 const double o[3], const double d[3], double *t0, double *t1)
{
    double f[3], fp[3], dp[3];
    sub3(f, o, p);
    double fa = dot3(f, a), da = dot3(d, a);
    for (int j = 0; j < 3; j++) {
        fp[j] = f[j] - fa * a[j];
        dp[j] = d[j] - da * a[j];
    }
    double qa = dot3(dp, dp), qb = dot3(fp, dp), qc = dot3(fp, fp) - radius * radius;
    double disc = qb * qb - qa * qc;
    if (disc < 0.0 || qa == 0.0)
        return 0;
    double sq = sqrt(disc);
    *t0 = (-qb - sq) / qa;
    *t1 = (-qb + sq) / qa;
    return 1;
}

/* Outward radial unit normal of the cylinder side at the point o + t d. */
static inline void cylinder_normal(const double p[3], const double a[3], double radius,
                                   const isect_ray *r, double t, double normal[3])
{
    double w[3];
    for (int j = 0; j < 3; j++)
        w[j] = r->org[j] + t * r->dir[j] - p[j];
    double s = dot3(w, a);
    for (int j = 0; j < 3; j++)
        normal[j] = (w[j] - s * a[j]) / radius;
}

/* Axis p0 -> p1 as a unit vector and its length. */
static inline double cylinder_axis(const double p0[3], const double p1[3], double a[3])
{
    sub3(a, p1, p0);
    double len = sqrt(dot3(a, a));
    a[0] /= len, a[1] /= len, a[2] /= len;
    return len;
}

/* Capped cylinder: the side's interval [t0, t1] (quadratic above) meets the caps' slab,
 * where s = (o + t d - p0).a runs from 0 to L: s = 0 and s = L at t = -(f.a)/(d.a) and
 * (L - f.a)/(d.a); enter = max, exit = min of the two intervals, as for a convex solid. */
static void tb_cylinder(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *p0 = k->data, *p1 = k->data + 3, radius = k->data[6];
    double a[3], minus_a[3];
    double len = cylinder_axis(p0, p1, a);
    minus_a[0] = -a[0], minus_a[1] = -a[1], minus_a[2] = -a[2];
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double t0, t1, f[3];
        if (!cylinder_roots(p0, a, radius, r->org, r->dir, &t0, &t1)) {
            put_miss(&out[i]);
            continue;
        }
        sub3(f, r->org, p0);
        double inv = 1.0 / dot3(r->dir, a), fa = dot3(f, a);
        double s0 = -fa * inv, s1 = (len - fa) * inv; /* caps at p0 (prim 1) and p1 (prim 2) */
        int c0 = 1, c1 = 2;
        if (s0 > s1) {
            double ts = s0;
            s0 = s1, s1 = ts, c0 = 2, c1 = 1;
        }
        double enter = t0, exit = t1;
        int enter_prim = 0, exit_prim = 0;
        if (s0 > enter)
            enter = s0, enter_prim = c0;
        if (s1 < exit)
            exit = s1, exit_prim = c1;
        double t, normal[3];
        int prim, kind;
        if (enter <= exit && in_range(enter, r))
            t = enter, prim = enter_prim, kind = ISECT_ENTER;
        else if (enter <= exit && enter < r->tmin && in_range(exit, r))
            t = exit, prim = exit_prim, kind = ISECT_EXIT;
        else {
            put_miss(&out[i]);
            continue;
        }
        if (prim == 0)
            cylinder_normal(p0, a, radius, r, t, normal);
        put_hit(&out[i], r, t, prim == 0 ? normal : prim == 1 ? minus_a : a, prim, kind);
    }
}

/* Open cylinder (the side alone, a thin surface): the roots above whose
 * s = (o + t d - p0).a lies in [0, L]; the first in [tmin, tmax]. */
static void tb_cylinder_open(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *p0 = k->data, *p1 = k->data + 3, radius = k->data[6];
    double a[3];
    double len = cylinder_axis(p0, p1, a);
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double roots[2], f[3], normal[3];
        int found = -1;
        if (cylinder_roots(p0, a, radius, r->org, r->dir, &roots[0], &roots[1])) {
            sub3(f, r->org, p0);
            double fa = dot3(f, a), da = dot3(r->dir, a);
            for (int j = 1; j >= 0; j--) {
                double s = fa + roots[j] * da;
                if (s >= 0.0 && s <= len && in_range(roots[j], r))
                    found = j;
            }
        }
        if (found < 0) {
            put_miss(&out[i]);
            continue;
        }
        cylinder_normal(p0, a, radius, r, roots[found], normal);
        put_hit(&out[i], r, roots[found], normal, 0, found == 0 ? ISECT_ENTER : ISECT_EXIT);
    }
}

/* Infinite cylinder (a solid): the side's roots alone. */
static void tb_cylinder_inf(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *p = k->data, radius = k->data[6];
    double a[3] = { k->data[3], k->data[4], k->data[5] };
    unit3(a);
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double t0, t1, t, normal[3];
        int kind = ISECT_MISS;
        if (cylinder_roots(p, a, radius, r->org, r->dir, &t0, &t1)) {
            if (in_range(t0, r))
                t = t0, kind = ISECT_ENTER;
            else if (in_range(t1, r))
                t = t1, kind = ISECT_EXIT;
        }
        if (kind == ISECT_MISS) {
            put_miss(&out[i]);
            continue;
        }
        cylinder_normal(p, a, radius, r, t, normal);
        put_hit(&out[i], r, t, normal, 0, kind);
    }
}

/* Ellipsoid sum(((x - c)/R)^2) = 1: the unit sphere in coordinates scaled by 1/R (t is
 * unchanged), solved by the sphere's quadratic; normal = unit((p - c)/R^2). */
static void tb_ellipsoid(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *c = k->data, *radii = k->data + 3;
    const double zero[3] = { 0.0, 0.0, 0.0 };
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double o[3], d[3], t, normal[3];
        for (int j = 0; j < 3; j++) {
            o[j] = (r->org[j] - c[j]) / radii[j];
            d[j] = r->dir[j] / radii[j];
        }
        int kind = sphere_first(zero, 1.0, o, d, r->tmin, r->tmax, &t);
        if (kind == ISECT_MISS) {
            put_miss(&out[i]);
            continue;
        }
        for (int j = 0; j < 3; j++)
            normal[j] = (o[j] + t * d[j]) / radii[j];
        unit3(normal);
        put_hit(&out[i], r, t, normal, -1, kind);
    }
}

/* Quadric Q(x) = Ax^2 + By^2 + Cz^2 + Dxy + Exz + Fyz + Gx + Hy + Iz + J: gradient. */
static inline void quadric_grad(const double *q, const double x[3], double g[3])
{
    g[0] = 2.0 * q[0] * x[0] + q[3] * x[1] + q[4] * x[2] + q[6];
    g[1] = 2.0 * q[1] * x[1] + q[3] * x[0] + q[5] * x[2] + q[7];
    g[2] = 2.0 * q[2] * x[2] + q[4] * x[0] + q[5] * x[1] + q[8];
}

/* Quadric: Q(o + t d) = a t^2 + b t + c with a = Q's quadratic part at d, b = grad Q(o).d,
 * c = Q(o); t = (-b -+ sqrt(b^2 - 4ac)) / 2a (a = 0: t = -c/b); normal = unit(grad Q(p)),
 * ENTER when it points against d. */
static void tb_quadric(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *q = k->data;
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        const double *o = r->org, *d = r->dir;
        double g[3], roots[2], normal[3], p[3];
        int count = 0;
        quadric_grad(q, o, g);
        double a = q[0] * d[0] * d[0] + q[1] * d[1] * d[1] + q[2] * d[2] * d[2]
                 + q[3] * d[0] * d[1] + q[4] * d[0] * d[2] + q[5] * d[1] * d[2];
        double b = dot3(g, d);
        double c = q[0] * o[0] * o[0] + q[1] * o[1] * o[1] + q[2] * o[2] * o[2]
                 + q[3] * o[0] * o[1] + q[4] * o[0] * o[2] + q[5] * o[1] * o[2]
                 + q[6] * o[0] + q[7] * o[1] + q[8] * o[2] + q[9];
        if (a == 0.0) {
            if (b != 0.0)
                roots[count++] = -c / b;
        } else {
            double disc = b * b - 4.0 * a * c;
            if (disc >= 0.0) {
                double sq = sqrt(disc);
                double r0 = (-b - sq) / (2.0 * a), r1 = (-b + sq) / (2.0 * a);
                roots[0] = r0 < r1 ? r0 : r1;
                roots[1] = r0 < r1 ? r1 : r0;
                count = 2;
            }
        }
        int found = -1;
        for (int j = count - 1; j >= 0; j--)
            if (in_range(roots[j], r))
                found = j;
        if (found < 0) {
            put_miss(&out[i]);
            continue;
        }
        double t = roots[found];
        for (int j = 0; j < 3; j++)
            p[j] = o[j] + t * d[j];
        quadric_grad(q, p, normal);
        unit3(normal);
        put_hit(&out[i], r, t, normal, -1, dot3(normal, d) < 0.0 ? ISECT_ENTER : ISECT_EXIT);
    }
}

/* Transformed shapes: the ray to object space by the inverse (o' = M^-1 o, d' = M^-1 d,
 * t unchanged), the object's loop there, the normal back by the inverse transpose
 * n = unit(M^-T n'), the point o + t d in world space. */
static void tb_xform_sphere(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *c = k->data, radius = k->data[3];
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double o[3], d[3], t, local[3], normal[3];
        mat_point(k->inv, r->org, o);
        mat_vector(k->inv, r->dir, d);
        int kind = sphere_first(c, radius, o, d, r->tmin, r->tmax, &t);
        if (kind == ISECT_MISS) {
            put_miss(&out[i]);
            continue;
        }
        for (int j = 0; j < 3; j++)
            local[j] = (o[j] + t * d[j] - c[j]) / radius;
        mat_transpose_vector(k->inv, local, normal);
        unit3(normal);
        put_hit(&out[i], r, t, normal, -1, kind);
    }
}

static void tb_xform_box(const kernel *k, const isect_ray *rays, int64_t n, isect_hit *out)
{
    const double *lo = k->data, *hi = k->data + 3;
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        double o[3], d[3], t, local[3], normal[3];
        int face;
        mat_point(k->inv, r->org, o);
        mat_vector(k->inv, r->dir, d);
        int kind = box_first(lo, hi, o, d, r->tmin, r->tmax, &t, &face);
        if (kind == ISECT_MISS) {
            put_miss(&out[i]);
            continue;
        }
        box_normal(face, local);
        mat_transpose_vector(k->inv, local, normal);
        unit3(normal);
        put_hit(&out[i], r, t, normal, face, kind);
    }
}

/* ------------------------------------------------------------ shapes */

/* Rotation by angle about a unit axis (Rodrigues) as a 4x4 matrix, and its inverse. */
static void rotation(const double axis[3], double angle, double rot[16], double inv[16])
{
    double c = cos(angle), s = sin(angle), x = axis[0], y = axis[1], z = axis[2];
    double r[9] = { c + x * x * (1 - c),     x * y * (1 - c) - z * s, x * z * (1 - c) + y * s,
                    y * x * (1 - c) + z * s, c + y * y * (1 - c),     y * z * (1 - c) - x * s,
                    z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c) };
    memset(rot, 0, 16 * sizeof *rot);
    memset(inv, 0, 16 * sizeof *inv);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            rot[4 * i + j] = r[3 * i + j];
            inv[4 * i + j] = r[3 * j + i];
        }
    rot[15] = inv[15] = 1.0;
}

/* k->m = T(shift) R(axis, angle) S(scale) and k->inv = S^-1 R^T T^-1, both from
 * their factors (the textbook loop's inverse does not come from the library). */
static int set_transform(kernel *k, const double shift[3], const double axis[3], double angle,
                         const double scale[3])
{
    double t[16] = { 0 }, ti[16] = { 0 }, rot[16], roti[16], s[16] = { 0 }, si[16] = { 0 };
    double tmp[16];
    double ax[3] = { axis[0], axis[1], axis[2] };
    unit3(ax);
    for (int i = 0; i < 3; i++) {
        t[5 * i] = ti[5 * i] = 1.0;
        t[4 * i + 3] = shift[i];
        ti[4 * i + 3] = -shift[i];
        s[5 * i] = scale[i];
        si[5 * i] = 1.0 / scale[i];
    }
    t[15] = ti[15] = s[15] = si[15] = 1.0;
    rotation(ax, angle, rot, roti);
    mat_mul(rot, s, tmp);
    mat_mul(t, tmp, k->m);
    mat_mul(roti, ti, tmp);
    mat_mul(si, tmp, k->inv);
    k->transformed = 1;
    memcpy(k->center, shift, sizeof k->center);
    return isect_xform_init(&k->xform, k->m) == ISECT_OK;
}

/* Appends a primitive with its numbers; returns it for the caller to finish. */
static kernel *add(kernel *ks, int *n, const char *name, int32_t type, textbook_fn textbook,
                   const double *data, int count)
{
    kernel *k = &ks[(*n)++];
    k->name = name;
    k->type = type;
    k->textbook = textbook;
    memcpy(k->data, data, (size_t)count * sizeof *data);
    return k;
}

#define COUNT_OF(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* The thirteen primitives (KERNELS). Returns their number, 0 if a transform failed. */
static int kernels_init(kernel *ks)
{
    static const double plane[] = { 1.0, 2.0, 2.0, -0.5 }; /* n, d */
    static const double sphere[] = { 0.1, -0.2, 0.3, 1.0 };
    static const double box[] = { -1.0, -0.5, -0.75, 1.0, 0.5, 0.75 };
    static const double triangle[] = { -1.0, -1.0, 0.2, 1.2, -0.8, -0.1, 0.1, 1.1, 0.3 };
    static const double cylinder[] = { -0.3, -0.6, -0.9, 0.3, 0.6, 0.9, 0.6 };  /* p0, p1, r */
    static const double cylinder_inf[] = { 0.1, 0.0, 0.0, 0.2, 0.3, 1.0, 0.7 }; /* p, axis, r */
    static const double ellipsoid[] = { 0.0, 0.1, -0.1, 1.2, 0.7, 0.9 };
    /* x^2 + 2y^2 - z^2 + 0.5xy - 0.5 = 0: a hyperboloid of one sheet. */
    static const double hyperboloid[] = { 1.0, 2.0, -1.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, -0.5 };
    static const double unit_sphere[] = { 0.0, 0.0, 0.0, 1.0 };
    static const double cube[] = { -1.0, -1.0, -1.0, 1.0, 1.0, 1.0 };
    static const double shift_s[3] = { 0.2, -0.1, 0.3 }, axis_s[3] = { 1.0, 2.0, 3.0 };
    static const double scale_s[3] = { 1.3, 0.6, 0.9 };
    static const double shift_b[3] = { -0.1, 0.2, 0.1 }, axis_b[3] = { -2.0, 1.0, 1.0 };
    static const double scale_b[3] = { 0.8, 0.5, 1.1 };
    /* A concave heptagon (a crown with two notches) in the plane through
     * `at` spanned by the orthonormal u, v. */
    static const double crown[7][2] = { { -1.0, -1.0 }, { 1.0, -1.0 }, { 1.0, 1.0 },
                                         { 0.4, 0.1 },   { 0.0, 1.0 },  { -0.4, 0.1 },
                                         { -1.0, 1.0 } };
    static const double u[3] = { 2.0 / 3, 2.0 / 3, 1.0 / 3 }, v[3] = { -2.0 / 3, 1.0 / 3, 2.0 / 3 };
    static const double at[3] = { 0.1, -0.2, 0.05 };
    double polygon[7 * 3], planes[14 * 4];
    kernel *k;
    int n = 0;

    for (int j = 0; j < 7; j++)
        for (int c = 0; c < 3; c++)
            polygon[3 * j + c] = at[c] + crown[j][0] * u[c] + crown[j][1] * v[c];
    /* Truncated octahedron: the cube |x|,|y|,|z| <= 1 (planes 0..5 = -x,+x,-y,+y,-z,+z)
     * cut by |x| + |y| + |z| <= 1.5 (planes 6..13). */
    for (int j = 0; j < 6; j++) {
        double *p = planes + 4 * j;
        p[0] = p[1] = p[2] = 0.0;
        p[j / 2] = j % 2 ? 1.0 : -1.0;
        p[3] = -1.0;
    }
    for (int j = 0; j < 8; j++) {
        double *p = planes + 4 * (6 + j);
        p[0] = j & 1 ? 1.0 : -1.0, p[1] = j & 2 ? 1.0 : -1.0, p[2] = j & 4 ? 1.0 : -1.0;
        p[3] = -1.5;
    }

    memset(ks, 0, KERNELS * sizeof *ks);
    add(ks, &n, "plane", ISECT_PLANE, tb_plane, plane, COUNT_OF(plane))->stream = 1;
    k = add(ks, &n, "sphere", ISECT_SPHERE, tb_sphere, sphere, COUNT_OF(sphere));
    k->stream = 1;
    memcpy(k->center, sphere, sizeof k->center);
    add(ks, &n, "box", ISECT_AABB, tb_box, box, COUNT_OF(box))->stream = 1;
    add(ks, &n, "triangle", ISECT_TRIANGLE, tb_triangle, triangle, COUNT_OF(triangle))->stream = 1;
    k = add(ks, &n, "polygon", ISECT_POLYGON, tb_polygon, polygon, COUNT_OF(polygon));
    k->count = 7;
    k->flags = ISECT_EVEN_ODD;
    memcpy(k->center, at, sizeof k->center);
    k = add(ks, &n, "convex (14 planes)", ISECT_CONVEX, tb_convex, planes, COUNT_OF(planes));
    k->count = 14;
    k = add(ks, &n, "cylinder capped", ISECT_CYLINDER, tb_cylinder, cylinder, COUNT_OF(cylinder));
    k->flags = ISECT_CAPPED;
    add(ks, &n, "cylinder open", ISECT_CYLINDER, tb_cylinder_open, cylinder, COUNT_OF(cylinder));
    add(ks, &n, "cylinder infinite", ISECT_CYLINDER_INF, tb_cylinder_inf, cylinder_inf,
        COUNT_OF(cylinder_inf));
    k = add(ks, &n, "ellipsoid", ISECT_ELLIPSOID, tb_ellipsoid, ellipsoid, COUNT_OF(ellipsoid));
    memcpy(k->center, ellipsoid, sizeof k->center);
    add(ks, &n, "quadric (hyperboloid)", ISECT_QUADRIC, tb_quadric, hyperboloid,
        COUNT_OF(hyperboloid));
    k = add(ks, &n, "xform sphere", ISECT_SPHERE, tb_xform_sphere, unit_sphere,
            COUNT_OF(unit_sphere));
    if (!set_transform(k, shift_s, axis_s, 0.7, scale_s))
        return 0;
    k = add(ks, &n, "xform box", ISECT_AABB, tb_xform_box, cube, COUNT_OF(cube));
    if (!set_transform(k, shift_b, axis_b, 1.1, scale_b))
        return 0;
    return n;
}

static isect_shape shape_of(const kernel *k)
{
    isect_shape s;
    memset(&s, 0, sizeof s);
    s.type = k->type;
    s.n = k->count;
    s.flags = k->flags;
    s.data = k->data;
    s.xform = k->transformed ? &k->xform : NULL;
    return s;
}

/* ------------------------------------------------------------ rays */

/* xorshift64: the same numbers on every platform. */
static uint64_t rng_next(uint64_t *state)
{
    uint64_t x = *state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    *state = x;
    return x;
}

/* Uniform in [-1, 1). */
static double rng_signed_unit(uint64_t *state)
{
    return (double)(rng_next(state) >> 11) * 0x1p-52 - 1.0;
}

/* Origins uniform on the sphere of radius ORIGIN_RADIUS around center, aimed
 * at uniform points of the cube center +- aim. */
static void rays_generate(isect_ray *rays, int64_t n, const double center[3], double aim)
{
    uint64_t state = RNG_SEED;
    for (int64_t i = 0; i < n; i++) {
        isect_ray *r = &rays[i];
        double o[3], len2;
        do {
            o[0] = rng_signed_unit(&state);
            o[1] = rng_signed_unit(&state);
            o[2] = rng_signed_unit(&state);
            len2 = dot3(o, o);
        } while (len2 > 1.0 || len2 < 1e-6);
        double scale = ORIGIN_RADIUS / sqrt(len2);
        for (int j = 0; j < 3; j++) {
            r->org[j] = center[j] + scale * o[j];
            r->dir[j] = center[j] + aim * rng_signed_unit(&state) - r->org[j];
        }
        r->tmin = 0.0;
        r->tmax = INFINITY;
    }
}

static int64_t count_hits(const isect_hit *h, int64_t n)
{
    int64_t hits = 0;
    for (int64_t i = 0; i < n; i++)
        hits += h[i].kind != ISECT_MISS;
    return hits;
}

/* The aim half-width at which the textbook loop hits about half of the n
 * rays (the hit fraction falls as the cube grows), then those rays. */
static void rays_calibrate(kernel *k, isect_ray *rays, isect_hit *scratch, int64_t n)
{
    double lo = AIM_MIN, hi = AIM_MAX;
    rays_generate(rays, n, k->center, hi);
    k->textbook(k, rays, n, scratch);
    if (count_hits(scratch, n) * 2 < n) {
        for (int step = 0; step < 40; step++) {
            double mid = sqrt(lo * hi);
            rays_generate(rays, n, k->center, mid);
            k->textbook(k, rays, n, scratch);
            if (count_hits(scratch, n) * 2 > n)
                lo = mid;
            else
                hi = mid;
        }
    }
    k->aim = hi;
    rays_generate(rays, n, k->center, k->aim);
}

/* ------------------------------------------------------------ timing */

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of values[0..n), which it sorts. */
static double median(double *values, int n)
{
    qsort(values, (size_t)n, sizeof *values, compare_doubles);
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

static double median_copy(const double *values, int n, double *scratch)
{
    memcpy(scratch, values, (size_t)n * sizeof *values);
    return median(scratch, n);
}

/* One block of one primitive: a warm-up pair, then PAIRS_PER_BLOCK timed
 * pairs, alternately library first and textbook first. */
static int time_block(kernel *k, int block)
{
    isect_shape shape = shape_of(k);
    double *lt = k->lib_times + block * PAIRS_PER_BLOCK;
    double *tt = k->tb_times + block * PAIRS_PER_BLOCK;
    if (isect_intersect_batch(&shape, k->rays, SMALL_N, NULL, k->lib_hits) < 0)
        return 0;
    k->textbook(k, k->rays, SMALL_N, k->tb_hits);
    for (int p = 0; p < PAIRS_PER_BLOCK; p++) {
        double t0, t1, t2;
        int64_t status;
        if (p % 2 == 0) {
            t0 = now_seconds();
            status = isect_intersect_batch(&shape, k->rays, SMALL_N, NULL, k->lib_hits);
            t1 = now_seconds();
            k->textbook(k, k->rays, SMALL_N, k->tb_hits);
            t2 = now_seconds();
            lt[p] = t1 - t0, tt[p] = t2 - t1;
        } else {
            t0 = now_seconds();
            k->textbook(k, k->rays, SMALL_N, k->tb_hits);
            t1 = now_seconds();
            status = isect_intersect_batch(&shape, k->rays, SMALL_N, NULL, k->lib_hits);
            t2 = now_seconds();
            tt[p] = t1 - t0, lt[p] = t2 - t1;
        }
        if (status < 0)
            return 0;
    }
    return 1;
}

/* Medians of each loop's times, and of the pairs' ratios textbook / library
 * time: over all pairs, and per block for the range (the overall median lies
 * between the blocks' medians). */
static void summarize_times(kernel *k, int blocks)
{
    int total = blocks * PAIRS_PER_BLOCK;
    double *ratios = malloc((size_t)total * sizeof *ratios);
    double *scratch = malloc((size_t)total * sizeof *scratch);
    if (ratios == NULL || scratch == NULL) {
        free(ratios);
        free(scratch);
        return;
    }
    for (int p = 0; p < total; p++)
        ratios[p] = k->tb_times[p] / k->lib_times[p];
    k->lib_median = median_copy(k->lib_times, total, scratch);
    k->tb_median = median_copy(k->tb_times, total, scratch);
    k->ratio = median_copy(ratios, total, scratch);
    k->ratio_lo = INFINITY, k->ratio_hi = 0.0;
    for (int b = 0; b < blocks; b++) {
        double ratio = median_copy(ratios + b * PAIRS_PER_BLOCK, PAIRS_PER_BLOCK, scratch);
        k->ratio_lo = fmin(k->ratio_lo, ratio);
        k->ratio_hi = fmax(k->ratio_hi, ratio);
    }
    free(ratios);
    free(scratch);
}

/* Hit/miss agreement and the largest relative t difference on rays both hit;
 * on those rays also the largest difference of any point or normal
 * coordinate (relative to the point's size) and the rays whose kind or prim
 * differ. With verbose, the first few rays that disagree beyond rounding. */
static void compare_records(kernel *k, int verbose)
{
    int64_t agree = 0, shown = 0;
    k->max_rel_dt = k->max_point_diff = k->max_normal_diff = 0.0;
    k->disagreements = k->kind_prim_diffs = 0;
    for (int64_t i = 0; i < SMALL_N; i++) {
        const isect_hit *a = &k->lib_hits[i], *b = &k->tb_hits[i];
        int hit_a = a->kind != ISECT_MISS, hit_b = b->kind != ISECT_MISS;
        double rel = 0.0, dp = 0.0, dn = 0.0;
        agree += hit_a == hit_b;
        if (hit_a && hit_b) {
            double size = fmax(fabs(a->point[0]), fmax(fabs(a->point[1]), fabs(a->point[2])));
            rel = fabs(a->t - b->t) / fmax(fabs(a->t), 1e-300);
            for (int j = 0; j < 3; j++) {
                dp = fmax(dp, fabs(a->point[j] - b->point[j]) / fmax(size, 1e-300));
                dn = fmax(dn, fabs(a->normal[j] - b->normal[j]));
            }
            k->max_rel_dt = fmax(k->max_rel_dt, rel);
            k->max_point_diff = fmax(k->max_point_diff, dp);
            k->max_normal_diff = fmax(k->max_normal_diff, dn);
            k->kind_prim_diffs += a->kind != b->kind || a->prim != b->prim;
        }
        if (hit_a != hit_b || rel > 1e-9 || dp > 1e-9 || dn > 1e-9
            || (hit_a && (a->kind != b->kind || a->prim != b->prim))) {
            k->disagreements++;
            if (verbose && shown++ < 5) {
                const isect_ray *r = &k->rays[i];
                printf("  %s ray %lld org (%.17g, %.17g, %.17g) dir (%.17g, %.17g, %.17g):\n"
                       "    libisect t %.17g kind %d prim %d; textbook t %.17g kind %d prim %d\n",
                       k->name, (long long)i, r->org[0], r->org[1], r->org[2], r->dir[0],
                       r->dir[1], r->dir[2], a->t, a->kind, a->prim, b->t, b->kind, b->prim);
            }
        }
    }
    k->agreement = (double)agree / SMALL_N;
    k->hit_fraction = (double)count_hits(k->lib_hits, SMALL_N) / SMALL_N;
}

/* ------------------------------------------------------------ streaming */

/* The batch call's memory traffic and nothing else: every byte of every ray
 * read, every byte of every hit record written. */
static void stream_copy(const isect_ray *rays, int64_t n, isect_hit *out)
{
    for (int64_t i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        isect_hit *h = &out[i];
        h->t = r->tmin;
        h->point[0] = r->org[0], h->point[1] = r->org[1], h->point[2] = r->org[2];
        h->normal[0] = r->dir[0], h->normal[1] = r->dir[1], h->normal[2] = r->dir[2];
        h->uv[0] = r->tmax;
        h->uv[1] = 0.0;
        h->prim = -1;
        h->kind = ISECT_MISS;
    }
}

static int time_stream(kernel *k, isect_ray *rays, isect_hit *hits, int reps)
{
    isect_shape shape = shape_of(k);
    double *bt = malloc((size_t)reps * sizeof *bt), *ct = malloc((size_t)reps * sizeof *ct);
    double *pr = malloc((size_t)reps * sizeof *pr);
    int64_t status = 0;
    int ok = bt != NULL && ct != NULL && pr != NULL;
    rays_generate(rays, LARGE_N, k->center, k->aim);
    stream_copy(rays, LARGE_N, hits); /* faults the pages in */
    if (ok && isect_intersect_batch(&shape, rays, LARGE_N, NULL, hits) < 0)
        ok = 0;
    k->stream_lo = INFINITY, k->stream_hi = 0.0;
    for (int rep = 0; ok && rep < reps; rep++) {
        double t0, t1, t2;
        t0 = now_seconds();
        if (rep % 2 == 0)
            stream_copy(rays, LARGE_N, hits);
        else
            status = isect_intersect_batch(&shape, rays, LARGE_N, NULL, hits);
        t1 = now_seconds();
        if (rep % 2 == 0)
            status = isect_intersect_batch(&shape, rays, LARGE_N, NULL, hits);
        else
            stream_copy(rays, LARGE_N, hits);
        t2 = now_seconds();
        ct[rep] = rep % 2 == 0 ? t1 - t0 : t2 - t1;
        bt[rep] = rep % 2 == 0 ? t2 - t1 : t1 - t0;
        pr[rep] = bt[rep] / ct[rep];
        k->stream_lo = fmin(k->stream_lo, pr[rep]);
        k->stream_hi = fmax(k->stream_hi, pr[rep]);
        ok = status >= 0;
    }
    if (ok) {
        k->stream_hit_fraction = (double)status / LARGE_N;
        k->stream_ratio = median(pr, reps);
        k->stream_batch = median(bt, reps);
        k->stream_copy = median(ct, reps);
    }
    free(bt);
    free(ct);
    free(pr);
    return ok;
}

/* ------------------------------------------------------------ output */

static const char *verdict(int pass)
{
    return pass ? "PASS" : "FAIL";
}

static void print_kernels(const kernel *ks, int count, int blocks)
{
    printf("\nlibisect %s: isect_intersect_batch vs a textbook loop (-O2 -march=native), "
           "N = %d rays in cache,\n%d blocks x %d interleaved pairs, medians; ratio = "
           "libisect/textbook throughput (median of the pairs'\ntextbook time / library "
           "time), range = min-max of the blocks' medians; agree = same hit/miss; max rel dt "
           "on rays both hit\n\n",
           isect_version_string(), SMALL_N, blocks, PAIRS_PER_BLOCK);
    printf("%-22s %5s %12s %12s %6s %11s %8s %10s  %s\n", "primitive", "hit%", "libisect/s",
           "textbook/s", "ratio", "range", "agree%", "max rel dt", "target >= 0.5");
    for (int i = 0; i < count; i++) {
        const kernel *k = &ks[i];
        double ratio = k->ratio;
        printf("%-22s %5.1f %12.4g %12.4g %6.3f %5.3f-%5.3f %8.2f %10.2g  %s\n", k->name,
               100.0 * k->hit_fraction, SMALL_N / k->lib_median, SMALL_N / k->tb_median, ratio,
               k->ratio_lo, k->ratio_hi, 100.0 * k->agreement, k->max_rel_dt,
               verdict(ratio >= RATIO_TARGET));
    }
}

static void print_stream(const kernel *ks, int count, int reps)
{
    printf("\nisect_intersect_batch vs a streaming copy of the same bytes (read N x %zu-byte "
           "rays, write N x %zu-byte hits),\nN = %d, %d interleaved pairs, medians; range of "
           "the pairs' ratios\n\n",
           sizeof(isect_ray), sizeof(isect_hit), LARGE_N, reps);
    printf("%-10s %5s %12s %12s %9s %10s %11s  %s\n", "primitive", "hit%", "batch rays/s",
           "copy rays/s", "copy GB/s", "batch/copy", "range", "target <= 2.0");
    for (int i = 0; i < count; i++) {
        const kernel *k = &ks[i];
        double ratio = k->stream_ratio;
        if (!k->stream)
            continue;
        printf("%-10s %5.1f %12.4g %12.4g %9.2f %10.2f %5.2f-%5.2f  %s\n", k->name,
               100.0 * k->stream_hit_fraction, LARGE_N / k->stream_batch,
               LARGE_N / k->stream_copy,
               LARGE_N * (double)(sizeof(isect_ray) + sizeof(isect_hit)) / k->stream_copy * 1e-9,
               ratio, k->stream_lo, k->stream_hi, verdict(ratio <= STREAM_TARGET));
    }
}

/* Opened before the measurements so a bad path fails at once. */
static FILE *results_open(const char *path)
{
    if (strcmp(path, DEFAULT_RESULTS) == 0 && mkdir(RESULTS_DIR, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "bench_kernels: cannot create %s: %s\n", RESULTS_DIR, strerror(errno));
        return NULL;
    }
    FILE *f = fopen(path, "w");
    if (f == NULL)
        fprintf(stderr, "bench_kernels: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

static int results_write(FILE *f, const char *path, const kernel *ks, int count, int blocks,
                         int stream_reps)
{
    int first = 1;
    fprintf(f, "{\n  \"benchmark\": \"bench_kernels\",\n  \"library_version\": \"%s\",\n",
            isect_version_string());
    fprintf(f, "  \"textbook_flags\": \"-O2 -march=native -ffp-contract=fast\",\n");
    fprintf(f, "  \"n\": %d,\n  \"blocks\": %d,\n  \"pairs_per_block\": %d,\n", SMALL_N, blocks,
            PAIRS_PER_BLOCK);
    fprintf(f, "  \"statistic\": \"median\",\n  \"ratio_target_min\": %.2f,\n", RATIO_TARGET);
    fprintf(f, "  \"kernels\": [\n");
    for (int i = 0; i < count; i++) {
        const kernel *k = &ks[i];
        fprintf(f,
                "    {\"primitive\": \"%s\", \"aim_half_width\": %.6g, \"hit_fraction\": %.4f, "
                "\"libisect_rays_per_second\": %.6g, \"textbook_rays_per_second\": %.6g, "
                "\"ratio\": %.4f, \"ratio_min\": %.4f, \"ratio_max\": %.4f, "
                "\"hit_agreement\": %.6f, \"max_rel_dt\": %.3g, \"max_point_diff\": %.3g, "
                "\"max_normal_diff\": %.3g, \"kind_or_prim_differs\": %lld, "
                "\"rays_disagreeing\": %lld, \"pass\": %s}%s\n",
                k->name, k->aim, k->hit_fraction, SMALL_N / k->lib_median,
                SMALL_N / k->tb_median, k->ratio, k->ratio_lo, k->ratio_hi, k->agreement,
                k->max_rel_dt, k->max_point_diff, k->max_normal_diff,
                (long long)k->kind_prim_diffs, (long long)k->disagreements,
                k->ratio >= RATIO_TARGET ? "true" : "false",
                i + 1 < count ? "," : "");
    }
    fprintf(f, "  ],\n  \"stream\": {\"n\": %d, \"pairs\": %d, \"ratio_target_max\": %.2f, "
               "\"results\": [\n", LARGE_N, stream_reps, STREAM_TARGET);
    for (int i = 0; i < count && stream_reps > 0; i++) {
        const kernel *k = &ks[i];
        double ratio = k->stream_ratio;
        if (!k->stream)
            continue;
        fprintf(f,
                "%s    {\"primitive\": \"%s\", \"hit_fraction\": %.4f, \"batch_seconds\": %.6g, "
                "\"copy_seconds\": %.6g, \"ratio\": %.4f, \"ratio_min\": %.4f, "
                "\"ratio_max\": %.4f, \"pass\": %s}",
                first ? "" : ",\n", k->name, k->stream_hit_fraction, k->stream_batch,
                k->stream_copy, ratio, k->stream_lo, k->stream_hi,
                ratio <= STREAM_TARGET ? "true" : "false");
        first = 0;
    }
    fprintf(f, "\n  ]}\n}\n");
    if (fclose(f) != 0) {
        fprintf(stderr, "bench_kernels: cannot write %s\n", path);
        return 0;
    }
    printf("\nresults: %s\n", path);
    return 1;
}

/* ------------------------------------------------------------ main */

static int allocate(kernel *k, int blocks)
{
    k->rays = malloc(SMALL_N * sizeof *k->rays);
    k->lib_hits = malloc(SMALL_N * sizeof *k->lib_hits);
    k->tb_hits = malloc(SMALL_N * sizeof *k->tb_hits);
    k->lib_times = malloc((size_t)blocks * PAIRS_PER_BLOCK * sizeof *k->lib_times);
    k->tb_times = malloc((size_t)blocks * PAIRS_PER_BLOCK * sizeof *k->tb_times);
    return k->rays && k->lib_hits && k->tb_hits && k->lib_times && k->tb_times;
}

static void release(kernel *k)
{
    free(k->rays);
    free(k->lib_hits);
    free(k->tb_hits);
    free(k->lib_times);
    free(k->tb_times);
}

int main(int argc, char **argv)
{
    kernel ks[KERNELS];
    const char *path = DEFAULT_RESULTS;
    int blocks = DEFAULT_BLOCKS, stream_reps = DEFAULT_STREAM_REPS, verbose = 0, ok = 1;

    for (int a = 1; a < argc; a++) {
        if (strcmp(argv[a], "-v") == 0)
            verbose = 1;
        else if (strcmp(argv[a], "--blocks") == 0 && a + 1 < argc)
            blocks = atoi(argv[++a]);
        else if (strcmp(argv[a], "--stream-reps") == 0 && a + 1 < argc)
            stream_reps = atoi(argv[++a]);
        else if (argv[a][0] != '-')
            path = argv[a];
        else {
            fprintf(stderr, "usage: bench_kernels [-v] [--blocks B] [--stream-reps R] "
                            "[results.json]\n");
            return 1;
        }
    }
    if (blocks < 1 || stream_reps < 0) {
        fprintf(stderr, "bench_kernels: --blocks must be >= 1, --stream-reps >= 0\n");
        return 1;
    }
    int count = kernels_init(ks);
    if (count == 0) {
        fprintf(stderr, "bench_kernels: isect_xform_init failed\n");
        return 1;
    }
    FILE *results = results_open(path);
    if (results == NULL)
        return 1;

    for (int i = 0; i < count && ok; i++) {
        ok = allocate(&ks[i], blocks);
        if (ok)
            rays_calibrate(&ks[i], ks[i].rays, ks[i].tb_hits, SMALL_N);
    }
    /* Blocks outermost: every primitive gets a share of each period of the run. */
    for (int b = 0; b < blocks && ok; b++)
        for (int i = 0; i < count && ok; i++)
            if (!time_block(&ks[i], b)) {
                fprintf(stderr, "bench_kernels: isect_intersect_batch(%s) failed\n", ks[i].name);
                ok = 0;
            }
    if (ok) {
        for (int i = 0; i < count; i++) {
            summarize_times(&ks[i], blocks);
            compare_records(&ks[i], verbose);
        }
        print_kernels(ks, count, blocks);
        fflush(stdout);
    }

    if (ok && stream_reps > 0) {
        isect_ray *rays = malloc((size_t)LARGE_N * sizeof *rays);
        isect_hit *hits = malloc((size_t)LARGE_N * sizeof *hits);
        ok = rays != NULL && hits != NULL;
        for (int i = 0; i < count && ok; i++)
            if (ks[i].stream && !time_stream(&ks[i], rays, hits, stream_reps)) {
                fprintf(stderr, "bench_kernels: the %d-ray batch (%s) failed\n", LARGE_N,
                        ks[i].name);
                ok = 0;
            }
        if (ok)
            print_stream(ks, count, stream_reps);
        free(rays);
        free(hits);
    }
    /* Written even after a failure (without the numbers), so the file never
     * holds stale results of an earlier run. */
    if (!results_write(results, path, ks, ok ? count : 0, blocks, ok ? stream_reps : 0))
        ok = 0;
    for (int i = 0; i < count; i++)
        release(&ks[i]);
    return ok ? 0 : 1;
}
