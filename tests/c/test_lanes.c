/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_lanes.c — batch records are bit for bit the scalar call's, at every
 * instruction set the library dispatches to.
 *
 * For each analytic shape with a fast kernel (spheres, planes, triangles,
 * polygons; plain, far and small, huge, tiny, degenerate, transformed),
 * rays of several classes (random at mixed scales, far and small, grazing
 * / near tangent or within ulps of an edge or vertex, origins within ulps
 * of the surface, interval ends near the crossings, bad rays) go through
 * isect_intersect_batch under every ISECT_SIMD level and are compared,
 * record by record with memcmp, with the first hit of isect_intersect on
 * the same ray (or the MISS / INVALID record isect.h defines); thin
 * surfaces once more under ISECT_CULL_BACK. The test also prints one digest of all the records, which the
 * test script compares between this build and the portable one
 * (-DISECT_NO_SIMD): same bits on every build.
 *
 *     test_lanes [rays per shape]     (default 1000000)
 */
#define _POSIX_C_SOURCE 200809L

#include "check.h"
#include "isect.h"
#include "test_random.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ shapes */

/* A shape to test: its descriptor (data in `numbers`), a centre and size
 * for aiming, and a point-on-surface generator. */
typedef struct test_shape {
    const char *name;
    isect_shape shape;
    double      numbers[48];
    isect_xform xform;
    double      center[3], size;
    double      planes[32]; /* a convex polyhedron's */
    isect_opts  opts;  /* the options of every query */
} test_shape;

static void shape_plane(test_shape *ts, const char *name, double nx, double ny, double nz,
                        double d)
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    ts->numbers[0] = nx;
    ts->numbers[1] = ny;
    ts->numbers[2] = nz;
    ts->numbers[3] = d;
    ts->shape.type = ISECT_PLANE;
    ts->shape.data = ts->numbers;
    double nn = nx * nx + ny * ny + nz * nz;
    for (int k = 0; k < 3; k++) /* the plane's point nearest the origin */
        ts->center[k] = -d * ts->numbers[k] / nn;
    ts->size = 1.0 + fabs(d) / sqrt(nn);
}

static void shape_sphere(test_shape *ts, const char *name, double cx, double cy, double cz,
                         double r)
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    ts->numbers[0] = cx;
    ts->numbers[1] = cy;
    ts->numbers[2] = cz;
    ts->numbers[3] = r;
    ts->shape.type = ISECT_SPHERE;
    ts->shape.data = ts->numbers;
    ts->center[0] = cx;
    ts->center[1] = cy;
    ts->center[2] = cz;
    ts->size = r;
}

static void shape_box(test_shape *ts, const char *name, const double lo[3], const double hi[3])
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    ts->shape.type = ISECT_AABB;
    ts->shape.data = ts->numbers;
    for (int k = 0; k < 3; k++) {
        ts->numbers[k] = lo[k];
        ts->numbers[k + 3] = hi[k];
        ts->center[k] = 0.5 * lo[k] + 0.5 * hi[k];
        ts->size = fmax(ts->size, 0.5 * (hi[k] - lo[k]));
    }
}

/* The octahedron |x - c|_1 <= r as 8 planes (normals (+-1, +-1, +-1)
 * times `scale`, so that they are not unit). */
static void shape_octahedron(test_shape *ts, const char *name, const double c[3], double r,
                             double scale)
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    ts->shape.type = ISECT_CONVEX;
    ts->shape.n = 8;
    ts->shape.data = ts->planes;
    for (int i = 0; i < 8; i++) {
        double *pl = ts->planes + 4 * i;
        double dot = 0.0;
        for (int k = 0; k < 3; k++) {
            pl[k] = (i >> k & 1 ? -1.0 : 1.0) * scale;
            dot += pl[k] * c[k];
        }
        pl[3] = -dot - r * scale;
    }
    for (int k = 0; k < 3; k++)
        ts->center[k] = c[k];
    ts->size = r;
}

static void shape_triangle(test_shape *ts, const char *name, const double v[9])
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    memcpy(ts->numbers, v, 9 * sizeof(double));
    ts->shape.type = ISECT_TRIANGLE;
    ts->shape.data = ts->numbers;
    double size = 0.0;
    for (int k = 0; k < 3; k++) {
        ts->center[k] = (v[k] + v[3 + k] + v[6 + k]) / 3.0;
        size = fmax(size, fabs(v[k] - ts->center[k]));
        size = fmax(size, fabs(v[3 + k] - ts->center[k]));
        size = fmax(size, fabs(v[6 + k] - ts->center[k]));
    }
    ts->size = size > 0.0 ? size : 1.0;
}

/* A polygon of n vertices around c in the plane spanned by u, w: a
 * rounded regular n-gon, or a star (every other vertex at 0.4 of the
 * radius) when concave. */
static void shape_polygon(test_shape *ts, const char *name, int n, int concave, int rule,
                          const double c[3], const double u[3], const double w[3], double r)
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    for (int j = 0; j < n; j++) {
        double ang = 6.283185307179586 * j / n;
        double rad = r * (concave && j % 2 ? 0.4 : 1.0);
        for (int k = 0; k < 3; k++)
            ts->numbers[3 * j + k] = c[k] + rad * cos(ang) * u[k] + rad * sin(ang) * w[k];
    }
    ts->shape.type = ISECT_POLYGON;
    ts->shape.n = n;
    ts->shape.flags = rule;
    ts->shape.data = ts->numbers;
    memcpy(ts->center, c, sizeof ts->center);
    ts->size = r > 0.0 ? r : 1.0;
}

static void shape_ellipsoid(test_shape *ts, const char *name, const double c[3],
                            const double radii[3])
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    for (int k = 0; k < 3; k++) {
        ts->numbers[k] = ts->center[k] = c[k];
        ts->numbers[3 + k] = radii[k];
        ts->size = radii[k] > ts->size ? radii[k] : ts->size;
    }
    ts->shape.type = ISECT_ELLIPSOID;
    ts->shape.data = ts->numbers;
}

static void shape_cylinder(test_shape *ts, const char *name, int32_t type, const double p[3],
                           const double q[3], double r, int32_t flags)
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    ts->shape.type = type;
    ts->shape.flags = flags;
    ts->shape.data = ts->numbers;
    for (int k = 0; k < 3; k++) {
        ts->numbers[k] = p[k];
        ts->numbers[3 + k] = q[k];
    }
    ts->numbers[6] = r;
    double len = 0.0;
    for (int k = 0; k < 3; k++) {
        double a = type == ISECT_CYLINDER ? q[k] - p[k] : q[k];
        ts->center[k] = type == ISECT_CYLINDER ? 0.5 * (p[k] + q[k]) : p[k];
        len += a * a;
    }
    ts->size = r + (type == ISECT_CYLINDER ? 0.5 * sqrt(len) : 2.0 * r);
}

static void shape_quadric(test_shape *ts, const char *name, const double q[10], const double c[3],
                          double size)
{
    memset(ts, 0, sizeof *ts);
    ts->name = name;
    ts->shape.type = ISECT_QUADRIC;
    ts->shape.data = ts->numbers;
    memcpy(ts->numbers, q, 10 * sizeof *q);
    memcpy(ts->center, c, sizeof ts->center);
    ts->size = size;
}

/* Puts ts under the object-to-world matrix m; the centre and size for
 * aiming become those of its world image (surface_point maps its
 * object-space points by m). */
static void shape_transform(test_shape *ts, const double m[16])
{
    CHECK(isect_xform_init(&ts->xform, m) == ISECT_OK);
    ts->shape.xform = &ts->xform;
    double c[3] = { ts->center[0], ts->center[1], ts->center[2] };
    for (int i = 0; i < 3; i++)
        ts->center[i] = m[4 * i] * c[0] + m[4 * i + 1] * c[1] + m[4 * i + 2] * c[2] + m[4 * i + 3];
    ts->size *= 2.0;
}

/* A point near the surface of ts (object space == world space for the
 * untransformed shapes). */
static void surface_point(const test_shape *ts, double p[3])
{
    double d[3];
    rng_dir(d);
    switch (ts->shape.type) {
    case ISECT_PLANE: { /* the centre moved within the plane */
        double nv[3] = { ts->numbers[0], ts->numbers[1], ts->numbers[2] };
        double s = (d[0] * nv[0] + d[1] * nv[1] + d[2] * nv[2]) / (nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
        for (int k = 0; k < 3; k++)
            p[k] = ts->center[k] + ts->size * (d[k] - s * nv[k]);
        break;
    }
    case ISECT_SPHERE:
        for (int k = 0; k < 3; k++)
            p[k] = ts->numbers[k] + ts->numbers[3] * d[k];
        break;
    case ISECT_AABB: { /* on a face, an edge (1 in 4) or a corner (1 in 8) */
        const double *lo = ts->numbers, *hi = ts->numbers + 3;
        uint64_t pick = rng_next();
        int snapped = pick % 8 == 0 ? 3 : pick % 4 == 0 ? 2 : 1;
        for (int k = 0; k < 3; k++)
            p[k] = lo[k] + (hi[k] - lo[k]) * (0.5 + 0.5 * d[k]);
        for (int j = 0; j < snapped; j++) {
            int a = (int)((pick >> (8 + 2 * j)) % 3);
            p[a] = (pick >> (16 + j)) & 1u ? hi[a] : lo[a];
        }
        break;
    }
    case ISECT_CONVEX: { /* on the octahedron: a face, an edge (1 in 4), a vertex (1 in 8) */
        uint64_t pick = rng_next();
        double a[3] = { fabs(d[0]), fabs(d[1]), fabs(d[2]) };
        if (pick % 8 == 0)
            a[0] = a[1] = 0.0, a[2] = 1.0;
        else if (pick % 4 == 0)
            a[pick >> 8 & 1] = 0.0;
        double l1 = a[0] + a[1] + a[2];
        for (int k = 0; k < 3; k++)
            p[k] = ts->center[k] + ts->size * (d[k] < 0.0 ? -a[k] : a[k]) / l1;
        break;
    }
    case ISECT_TRIANGLE:
    case ISECT_POLYGON: { /* a vertex, a point of an edge, or one inside */
        const double *v = ts->numbers;
        int n = ts->shape.type == ISECT_TRIANGLE ? 3 : ts->shape.n;
        int i = (int)(rng_next() % (uint64_t)n), j = (i + 1) % n;
        double s = 0.5 * (rng_unit() + 1.0), in = rng_next() % 3 == 0 ? 0.5 : 0.0;
        for (int k = 0; k < 3; k++) {
            double e = v[3 * i + k] + s * (v[3 * j + k] - v[3 * i + k]);
            p[k] = e + in * (ts->center[k] - e);
        }
        break;
    }
    case ISECT_ELLIPSOID:
        for (int k = 0; k < 3; k++)
            p[k] = ts->numbers[k] + ts->numbers[3 + k] * d[k];
        break;
    case ISECT_CYLINDER:
    case ISECT_CYLINDER_INF: { /* on the side, or (capped) on a cap, or on a rim */
        const double *p0 = ts->numbers, r = ts->numbers[6];
        double a[3], e[3], len = 0.0, s = 0.5 * (rng_unit() + 1.0), rho = r;
        for (int k = 0; k < 3; k++)
            a[k] = ts->shape.type == ISECT_CYLINDER ? ts->numbers[3 + k] - p0[k] : ts->numbers[3 + k];
        for (int k = 0; k < 3; k++) { /* e = unit(d x a), perpendicular to the axis */
            e[k] = d[(k + 1) % 3] * a[(k + 2) % 3] - d[(k + 2) % 3] * a[(k + 1) % 3];
            len += e[k] * e[k];
        }
        len = sqrt(len);
        switch (rng_next() % 4) {
        case 0: s = rng_next() % 2; rho = r * 0.5 * (rng_unit() + 1.0); break; /* a cap */
        case 1: s = rng_next() % 2; break;                                    /* a rim */
        default: break;
        }
        if (ts->shape.type == ISECT_CYLINDER_INF)
            s = 2.0 * rng_unit();
        for (int k = 0; k < 3; k++)
            p[k] = p0[k] + s * a[k] + rho * e[k] / len;
        break;
    }
    case ISECT_QUADRIC: { /* a crossing of a line through the aiming box */
        isect_shape object = ts->shape;
        object.xform = NULL;
        isect_ray line = { { 0 }, { d[0], d[1], d[2] }, -INFINITY, INFINITY };
        for (int k = 0; k < 3; k++)
            line.org[k] = ts->center[k] + 0.5 * ts->size * rng_unit();
        isect_hit h[4];
        int n = isect_intersect(&object, &line, NULL, h, 4);
        for (int k = 0; k < 3; k++)
            p[k] = n > 0 ? h[rng_next() % (uint64_t)(n < 4 ? n : 4)].point[k] : line.org[k];
        break;
    }
    default:
        for (int k = 0; k < 3; k++)
            p[k] = ts->center[k] + ts->size * d[k];
        break;
    }
    if (ts->shape.xform != NULL) { /* to world space */
        const double *m = ts->xform.m;
        double w[3];
        for (int i = 0; i < 3; i++)
            w[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
        memcpy(p, w, sizeof w);
    }
}

/* ------------------------------------------------------------ rays */

enum ray_class { RANDOM, FAR, GRAZING, NEAR_SURFACE, INTERVAL, BAD, CLASSES };

static void make_ray(const test_shape *ts, enum ray_class cls, isect_ray *r)
{
    double aim[3], d[3];
    r->tmin = 0.0;
    r->tmax = INFINITY;
    switch (cls) {
    case RANDOM: /* origins at 1.5..2^20 sizes, aim within 1.3 sizes */
    default: {
        double dist = ts->size * 1.5 * rng_scale(0, 20);
        rng_dir(d);
        for (int k = 0; k < 3; k++) {
            r->org[k] = ts->center[k] + dist * d[k];
            aim[k] = ts->center[k] + 1.3 * ts->size * rng_unit();
            r->dir[k] = (aim[k] - r->org[k]) * rng_scale(-30, 30);
        }
        if (rng_next() % 8 == 0) /* some origins inside */
            for (int k = 0; k < 3; k++)
                r->org[k] = ts->center[k] + 0.5 * ts->size * rng_unit();
        if (rng_next() % 8 == 0) /* some directions in a coordinate plane */
            r->dir[rng_next() % 3] = rng_next() % 2 ? 0.0 : -0.0;
        break;
    }
    case FAR: { /* tiny objects seen from 2^30..2^50 sizes away */
        double dist = ts->size * rng_scale(30, 50);
        rng_dir(d);
        for (int k = 0; k < 3; k++) {
            r->org[k] = ts->center[k] + dist * d[k];
            aim[k] = ts->center[k] + 1.1 * ts->size * rng_unit();
            r->dir[k] = aim[k] - r->org[k];
        }
        break;
    }
    case GRAZING: { /* aimed at surface points, then nudged sideways by ~ulps */
        double p[3];
        surface_point(ts, p);
        double dist = ts->size * rng_scale(0, 12);
        rng_dir(d);
        for (int k = 0; k < 3; k++)
            r->org[k] = p[k] + dist * d[k];
        for (int k = 0; k < 3; k++)
            r->dir[k] = ulps(p[k], (int)(rng_next() % 9) - 4) - r->org[k];
        break;
    }
    case NEAR_SURFACE: { /* origins within a few ulps of the surface */
        double p[3];
        surface_point(ts, p);
        for (int k = 0; k < 3; k++)
            r->org[k] = ulps(p[k], (int)(rng_next() % 7) - 3);
        rng_dir(r->dir);
        break;
    }
    case INTERVAL: { /* a crossing near tmin or tmax */
        make_ray(ts, RANDOM, r);
        isect_hit h[4];
        int n = isect_intersect(&ts->shape, r, &ts->opts, h, 4);
        if (n > 0) {
            double t = h[rng_next() % (uint64_t)(n < 4 ? n : 4)].t;
            int k = (int)(rng_next() % 9) - 4;
            if (rng_next() % 2)
                r->tmin = ulps(t, k);
            else
                r->tmax = ulps(t, k);
        }
        break;
    }
    case BAD: {
        make_ray(ts, RANDOM, r);
        switch (rng_next() % 4) {
        case 0: r->org[rng_next() % 3] = NAN; break;
        case 1: r->dir[rng_next() % 3] = INFINITY; break;
        case 2: r->dir[0] = r->dir[1] = r->dir[2] = 0.0; break;
        default: r->tmin = NAN; break;
        }
        break;
    }
    }
}

/* ------------------------------------------------------------ checks */

/* The record isect_intersect_batch must write for ray r: the first hit of
 * the scalar call, or MISS / INVALID as isect.h defines them. */
static void scalar_record(const isect_shape *s, const isect_ray *r, const isect_opts *opts,
                          isect_hit *out)
{
    isect_hit h[8];
    int n = isect_intersect(s, r, opts, h, 8);
    if (n > 0) {
        *out = h[0];
        return;
    }
    memset(out, 0, sizeof *out);
    out->t = n < 0 ? NAN : INFINITY;
    out->prim = -1;
    out->kind = n < 0 ? ISECT_INVALID : ISECT_MISS;
}

static uint64_t digest = 0xcbf29ce484222325ull; /* FNV-1a over every record */

static void digest_add(const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) {
        digest ^= b[i];
        digest *= 0x100000001b3ull;
    }
}

static const char *const levels[] = { "scalar", "sse2", "avx2", "avx512" };

static void test_shape_rays(const test_shape *ts, int64_t n)
{
    isect_ray *rays = malloc((size_t)n * sizeof *rays);
    isect_hit *want = malloc((size_t)n * sizeof *want);
    isect_hit *got = malloc((size_t)n * sizeof *got);
    if (rays == NULL || want == NULL || got == NULL) {
        CHECK(!"allocation");
        free(rays); free(want); free(got);
        return;
    }
    for (int64_t i = 0; i < n; i++) {
        make_ray(ts, (enum ray_class)(i % CLASSES), &rays[i]);
        scalar_record(&ts->shape, &rays[i], &ts->opts, &want[i]);
    }
    int64_t want_hits = 0;
    for (int64_t i = 0; i < n; i++)
        want_hits += want[i].kind != ISECT_MISS && want[i].kind != ISECT_INVALID;
    for (int lv = 0; lv < 4; lv++) {
        setenv("ISECT_SIMD", levels[lv], 1);
        memset(got, 0xA5, (size_t)n * sizeof *got);
        int64_t hits = isect_intersect_batch(&ts->shape, rays, n, &ts->opts, got);
        CHECK_EQ_INT(hits, want_hits);
        int64_t bad = 0;
        for (int64_t i = 0; i < n; i++) {
            if (memcmp(&got[i], &want[i], sizeof got[i]) != 0) {
                if (bad++ < 3)
                    fprintf(stderr, "%s%s [%s] ray %lld (class %d): batch t=%.17g kind=%d, "
                            "scalar t=%.17g kind=%d\n", ts->name, ts->opts.flags & ISECT_CULL_BACK ? " (culled)" : "",
                            levels[lv], (long long)i, (int)(i % CLASSES), got[i].t, got[i].kind,
                            want[i].t, want[i].kind);
            }
        }
        if (bad != 0)
            fprintf(stderr, "%s [%s]: %lld of %lld records differ\n", ts->name, levels[lv],
                    (long long)bad, (long long)n);
        CHECK(bad == 0);
    }
    unsetenv("ISECT_SIMD");
    uint64_t before = digest;
    for (int64_t i = 0; i < n; i++) {
        /* INVALID records carry NaN: hash its class, not its payload bits */
        if (want[i].kind == ISECT_INVALID)
            digest_add(&want[i].kind, sizeof want[i].kind);
        else
            digest_add(&want[i], sizeof want[i]);
    }
    /* per shape, so that a digest differing between builds names its shape */
    printf("%-20s %016llx\n", ts->name, (unsigned long long)(digest ^ before));
    free(rays);
    free(want);
    free(got);
}

int main(int argc, char **argv)
{
    /* rays per shape: a short run by default (the sanitizer build runs
     * it too); scripts/run_tests.sh runs 10^6 per shape in the release and
     * the portable builds and compares their digests */
    int64_t n = argc > 1 ? atoll(argv[1]) : 20000;
    rng_seed(0x2545F4914F6CDD1Dull);
    if (n < CLASSES)
        n = CLASSES;
    enum { SHAPES = 55 };
    static test_shape shapes[SHAPES];
    shape_sphere(&shapes[0], "unit sphere", 0.0, 0.0, 0.0, 1.0);
    shape_sphere(&shapes[1], "small far sphere", 1e7, -3e6, 2.5e6, 1e-3);
    shape_sphere(&shapes[2], "huge sphere", -1e9, 2e9, 0.5, 3e8);
    shape_sphere(&shapes[3], "tiny sphere", 1e-150, 2e-150, -1e-150, 1e-151);
    shape_sphere(&shapes[4], "transformed sphere", 1.0, 2.0, 3.0, 0.75);
    static const double m[16] = { 0.8, -0.6, 0.1, 5.0, 0.6, 0.8, 0.2, -1.0,
                                  0.0, 0.3, 2.0, 0.25, 0.0, 0.0, 0.0, 1.0 };
    CHECK(isect_xform_init(&shapes[4].xform, m) == ISECT_OK);
    shapes[4].shape.xform = &shapes[4].xform;
    /* aim at the sphere's world-space image: surface_point maps its
     * object-space points by m; the centre and size are only for aiming */
    const double *c = shapes[4].numbers;
    for (int i = 0; i < 3; i++)
        shapes[4].center[i] = m[4 * i] * c[0] + m[4 * i + 1] * c[1] + m[4 * i + 2] * c[2] + m[4 * i + 3];
    shapes[4].size = 2.0 * c[3];
    shape_plane(&shapes[5], "plane", 0.3, -0.4, 0.866, -2.5);
    shape_plane(&shapes[6], "far plane", 1e-3, 2.0, -0.5, 3e7);
    shape_plane(&shapes[7], "axis plane", 0.0, 0.0, 1.0, 0.0);
    static const double box_lo[3] = { -1.0, -0.5, -0.75 }, box_hi[3] = { 1.0, 0.5, 0.75 };
    static const double far_lo[3] = { 1e7, -3e6, 2.5e6 }, far_hi[3] = { 1e7 + 1e-3, -3e6 + 2e-3, 2.5e6 + 0.5e-3 };
    shape_box(&shapes[8], "box", box_lo, box_hi);
    shape_box(&shapes[9], "small far box", far_lo, far_hi);
    shape_box(&shapes[10], "transformed box", box_lo, box_hi);
    CHECK(isect_xform_init(&shapes[10].xform, m) == ISECT_OK);
    shapes[10].shape.xform = &shapes[10].xform;
    for (int i = 0; i < 3; i++)
        shapes[10].center[i] = m[4 * i + 3];
    shapes[10].size = 2.0;
    static const double origin[3] = { 0.0, 0.0, 0.0 }, far_c[3] = { 3e6, -1e7, 2e5 };
    shape_octahedron(&shapes[11], "octahedron", origin, 1.0, 1.0);
    shape_octahedron(&shapes[12], "small far octahedron", far_c, 1e-3, 3.0);
    shape_octahedron(&shapes[13], "transformed octahedron", origin, 0.5, 0.25);
    CHECK(isect_xform_init(&shapes[13].xform, m) == ISECT_OK);
    shapes[13].shape.xform = &shapes[13].xform;
    for (int i = 0; i < 3; i++)
        shapes[13].center[i] = m[4 * i + 3];
    shapes[13].size = 1.5;

    static const double tri[9] = { -1.0, -1.0, 0.2, 1.2, -0.8, -0.1, 0.1, 1.1, 0.3 };
    static const double far_tri[9] = { 1e7, 1e7, 5.0, 1e7 + 1e-3, 1e7, 5.0, 1e7, 1e7 + 1e-3, 5.5 };
    static const double sliver[9] = { 0.1, 0.2, 0.3, 1.1, 1.2, 1.3, 2.1, 2.2, 2.3000000000000003 };
    static const double collinear[9] = { 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 2.0, 2.0, 0.0 };
    static const double huge_tri[9] = { 0x1p210, 0.0, 0.0, 0.0, 0x1p210, 0.0, 0.0, 0.0, 0x1p210 };
    static const double tiny_tri[9] = { 1e-160, 0.0, 0.0, 0.0, 1e-160, 0.0, 0.0, 0.0, 1e-160 };
    shape_triangle(&shapes[14], "triangle", tri);
    shape_triangle(&shapes[15], "small far triangle", far_tri);
    shape_triangle(&shapes[16], "sliver triangle", sliver);
    shape_triangle(&shapes[17], "collinear triangle", collinear);
    shape_triangle(&shapes[18], "huge triangle (beyond the fast range)", huge_tri);
    shape_triangle(&shapes[19], "tiny triangle", tiny_tri);
    shape_triangle(&shapes[20], "transformed triangle", tri);
    CHECK(isect_xform_init(&shapes[20].xform, m) == ISECT_OK);
    shapes[20].shape.xform = &shapes[20].xform;
    for (int i = 0; i < 3; i++)
        shapes[20].center[i] = m[4 * i + 3];
    shapes[20].size = 3.0;
    static const double pc[3] = { 0.1, -0.2, 0.05 }, pu[3] = { 2.0 / 3, 2.0 / 3, 1.0 / 3 },
                        pw[3] = { -2.0 / 3, 1.0 / 3, 2.0 / 3 };
    static const double fc[3] = { 3e6, -1e7, 2e5 };
    shape_polygon(&shapes[21], "convex polygon", 7, 0, ISECT_EVEN_ODD, pc, pu, pw, 1.0);
    shape_polygon(&shapes[22], "concave polygon (nonzero)", 12, 1, ISECT_NONZERO, pc, pu, pw, 1.0);
    shape_polygon(&shapes[23], "small far polygon", 9, 1, ISECT_EVEN_ODD, fc, pu, pw, 1e-3);
    shape_polygon(&shapes[24], "degenerate polygon", 5, 0, ISECT_EVEN_ODD, pc, pu, pu, 1.0);
    static const double e_c[5][3] = { { 0.0, 0.1, -0.1 }, { 1e7, -3e6, 2.5e6 }, { -1e9, 2e9, 0.5 },
                                      { 1e-150, 2e-150, -1e-150 }, { 1.0, 2.0, 3.0 } };
    static const double e_r[5][3] = { { 1.2, 0.7, 0.9 }, { 1e-3, 3e-3, 2e-4 }, { 3e8, 1e8, 5e8 },
                                      { 1e-151, 3e-151, 2e-151 }, { 0.75, 0.3, 1.5 } };
    shape_ellipsoid(&shapes[25], "ellipsoid", e_c[0], e_r[0]);
    shape_ellipsoid(&shapes[26], "small far ellipsoid", e_c[1], e_r[1]);
    shape_ellipsoid(&shapes[27], "huge ellipsoid", e_c[2], e_r[2]);
    shape_ellipsoid(&shapes[28], "tiny ellipsoid", e_c[3], e_r[3]);
    shape_ellipsoid(&shapes[29], "transformed ellipsoid", e_c[4], e_r[4]);
    shape_transform(&shapes[29], m);
    static const double e_flat[3] = { 1.0, 1e-20, 2.0 }, e_long[3] = { 1e6, 1.0, 1.0 };
    shape_ellipsoid(&shapes[30], "flat ellipsoid", e_c[0], e_flat);
    shape_ellipsoid(&shapes[31], "long ellipsoid", e_c[4], e_long);
    static const double c_p[6][3] = { { -0.3, -0.6, -0.9 }, { -0.31, -0.57, -0.93 },
                                      { 1e6, 2e6, -3e6 }, { -1e9, 2e9, 0.5 },
                                      { 1e-150, 2e-150, -1e-150 }, { 0.1, 0.2, 0.3 } };
    static const double c_q[6][3] = { { 0.3, 0.6, 0.9 }, { 0.61, 0.97, 0.83 },
                                      { 1e6 + 3e-3, 2e6 + 1e-3, -3e6 - 2e-3 }, { -1e9 + 3e8, 2e9, 5e8 },
                                      { 3e-150, 2e-150, -1e-150 }, { 100.1, 0.2, 0.3 } };
    static const double c_r[6] = { 0.6, 0.37, 1e-3, 2e8, 1e-151, 0.25 };
    static const char *const c_names[2][6] = {
        { "capped cylinder", "capped cylinder 2", "small far capped cylinder", "huge capped cylinder",
          "tiny capped cylinder", "long capped cylinder" },
        { "open cylinder", "open cylinder 2", "small far open cylinder", "huge open cylinder",
          "tiny open cylinder", "long open cylinder" } };
    for (int i = 0; i < 6; i++) {
        shape_cylinder(&shapes[32 + i], c_names[0][i], ISECT_CYLINDER, c_p[i], c_q[i], c_r[i], ISECT_CAPPED);
        shape_cylinder(&shapes[38 + i], c_names[1][i], ISECT_CYLINDER, c_p[i], c_q[i], c_r[i], 0);
    }
    static const double i_p[2][3] = { { 0.1, 0.0, 0.0 }, { 1e6, 2e6, -3e6 } };
    static const double i_a[2][3] = { { 0.2, 0.3, 1.0 }, { 1e-3, 7.0, -2.0 } };
    shape_cylinder(&shapes[44], "infinite cylinder", ISECT_CYLINDER_INF, i_p[0], i_a[0], 0.7, 0);
    shape_cylinder(&shapes[45], "thin far infinite cylinder", ISECT_CYLINDER_INF, i_p[1], i_a[1], 1e-2, 0);
    shape_cylinder(&shapes[46], "transformed capped cylinder", ISECT_CYLINDER, c_p[1], c_q[1], 0.37,
                   ISECT_CAPPED);
    shape_transform(&shapes[46], m);
    shape_cylinder(&shapes[47], "transformed infinite cylinder", ISECT_CYLINDER_INF, i_p[0], i_a[0],
                   0.7, 0);
    shape_transform(&shapes[47], m);
    static const double hyperboloid[10] = { 1.0, 2.0, -1.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, -0.5 };
    static const double cone[10] = { 1.0, 1.0, -1.0, 0.0, 0.0, 0.0, -0.2, -0.4, 0.6, -0.04 };
    static const double paraboloid[10] = { 1.0, 0.5, 0.0, 0.1, 0.0, 0.0, 0.0, 0.0, -1.0, -0.3 };
    static const double general[10] = { 1.1, 0.9, 1.3, 0.2, -0.3, 0.1, 0.05, -0.07, 0.11, -1.0 };
    static const double far_ball[10] = { 1.0, 2.0, 3.0, 0.0, 0.0, 0.0, -2e3, 0.0, 0.0, 1e6 - 1.0 };
    static const double tiny[10] = { 1e30, 2e30, -1e30, 0.5e30, 0.0, 0.0, 0.0, 0.0, 0.0, -0.5 };
    static const double ball_c[3] = { 1e3, 0.0, 0.0 };
    static const double cone_c[3] = { 0.1, 0.2, -0.3 }, tiny_c[3] = { 0.0, 0.0, 0.0 };
    shape_quadric(&shapes[48], "hyperboloid", hyperboloid, origin, 2.0);
    shape_quadric(&shapes[49], "cone", cone, cone_c, 2.0);
    shape_quadric(&shapes[50], "paraboloid", paraboloid, origin, 2.0);
    shape_quadric(&shapes[51], "general quadric", general, origin, 2.0);
    shape_quadric(&shapes[52], "far ellipsoid quadric", far_ball, ball_c, 1.0);
    shape_quadric(&shapes[53], "tiny hyperboloid", tiny, tiny_c, 2e-15);
    shape_quadric(&shapes[54], "transformed hyperboloid", hyperboloid, origin, 2.0);
    shape_transform(&shapes[54], m);
    /* options: the default, and on some shapes eps = 0, a large eps, and
     * back-face culling (thin surfaces drop EXIT hits) */
    for (int i = 0; i < SHAPES; i++) {
        isect_opts o = ISECT_OPTS_INIT;
        shapes[i].opts = o;
    }
    shapes[1].opts.eps = 0.0;
    shapes[6].opts.flags = ISECT_CULL_BACK;
    shapes[26].opts.eps = 1e-6;
    shapes[33].opts.eps = 0.0;
    shapes[38].opts.flags = ISECT_CULL_BACK;
    shapes[39].opts.eps = 1e-6;
    shapes[43].opts.flags = ISECT_CULL_BACK;
    shapes[45].opts.eps = 0.0;
    shapes[49].opts.eps = 0.0;
    shapes[51].opts.eps = 1e-6;
    for (int i = 0; i < SHAPES; i++) {
        test_shape_rays(&shapes[i], n);
        int thin = shapes[i].shape.type == ISECT_PLANE || shapes[i].shape.type == ISECT_TRIANGLE
                || shapes[i].shape.type == ISECT_POLYGON;
        if (thin && shapes[i].opts.flags == 0) { /* the faces under CULL_BACK too */
            test_shape cull = shapes[i];
            cull.opts.flags = ISECT_CULL_BACK;
            test_shape_rays(&cull, n / 4);
        }
    }
    printf("digest %016llx\n", (unsigned long long)digest);
    return check_summary();
}
