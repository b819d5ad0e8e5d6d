/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_threads.c — many threads on shared shapes and meshes give exactly the
 * single-threaded results (the contract: no global mutable state, every
 * function reentrant, a mesh immutable after creation and safe to query from
 * many threads at once).
 *
 * One set of shapes — every shape type, polygons under both fill rules, the
 * open and the capped cylinder, four meshes (triangles without offsets, quads,
 * concave polygon faces, a torus), and each of them again under a shared
 * transform — one set of rays (random, aimed at vertices, edges and corners,
 * with tmin/tmax windows and a few bad rays) and one set of points are built
 * once. The main thread computes every result single-threaded first; then
 * THREADS threads (default 8), released together by a barrier, run every
 * query kind on every shape in a different order and with different chunk
 * sizes, and compare each result with the reference bit for bit:
 *
 *   closest        isect_intersect_batch (chunks of a thread-dependent size)
 *   any-hit        the same with ISECT_ANY_HIT
 *   cull-back      the same with ISECT_CULL_BACK
 *   all-hits       isect_intersect_all_batch (offsets and every hit)
 *   count          isect_intersect_all_batch with cap 0 and hits NULL, and
 *                  isect_intersect with cap 0 per ray
 *   scalar         isect_intersect per ray (every hit)
 *   contains       isect_contains_batch (chunks) and isect_contains (solids)
 *   spawn          isect_spawn_ray from every closest hit
 *   shared output  isect_intersect_batch into disjoint interleaved chunks of
 *                  one shared buffer, as a split batch writes it
 *   2D helpers     isect_point_in_polygon2_batch (both rules) and
 *                  isect_winding_number2_batch
 *   mesh_check     isect_mesh_check on the shared meshes (it allocates)
 *   mesh_create    a private copy of each mesh built from the shared input
 *                  arrays, queried (closest) and destroyed
 *
 * The C API has no threads parameter of its own (threading is the caller's,
 * e.g. the Python binding's threads=), so splitting a batch over threads is
 * what this test does. Built plain, under ASan+UBSan, and under
 * ThreadSanitizer (mk/tsan.mk: build/tsan/tests/test_threads), where the run
 * must report no race.
 *
 * Usage: test_threads [--race] [rays [threads]]   (defaults 1500 and 8;
 * --race adds a deliberate data race, to show the sanitizer reports one)
 */
#define _POSIX_C_SOURCE 200809L

#include <isect.h>

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "mesh_fixtures.h"
#include "test_random.h"

enum {
    MAX_SHAPES = 48,
    MAX_THREADS = 64,
    SCALAR_CAP = 64, /* more hits than any shape here gives one ray */
    N_MESHES = 4
};

enum kind {
    K_CLOSEST,
    K_ANY,
    K_CULL,
    K_ALL,
    K_COUNT,
    K_SCALAR,
    K_CONTAINS,
    K_SPAWN,
    K_SHARED,
    N_KINDS
};
static const char *const kind_names[N_KINDS] = { "closest", "any-hit",  "cull-back",
                                                 "all-hits", "count",   "scalar",
                                                 "contains", "spawn",   "shared output" };

/* Per-shape results: the reference of the main thread. */
typedef struct reference {
    isect_hit *closest, *any, *cull;
    int64_t n_closest, n_any, n_cull;
    int64_t *offsets; /* nrays + 1 */
    isect_hit *all;
    int64_t total;
    uint8_t *inside;  /* contains batch, solids only */
    int64_t n_inside;
    isect_ray *spawned;
    int *spawn_status;
    isect_hit *shared; /* written by the threads' interleaved chunks */
} reference;

typedef struct shape_entry {
    isect_shape s;
    char name[48];
    int solid; /* contains applies */
} shape_entry;

static shape_entry shapes[MAX_SHAPES];
static reference refs[MAX_SHAPES];
static int n_shapes;

static isect_ray *rays;
static int64_t n_rays;
static double *points;
static int64_t n_points;
static double *spawn_dirs; /* n_rays x 3 */

static fx_mesh fx[N_MESHES];
static isect_mesh *meshes[N_MESHES];
static int mesh_shape[N_MESHES]; /* index of the untransformed mesh shape */
static isect_mesh_report mesh_reports[N_MESHES];

/* The 2D helpers: a concave self-overlapping polygon and points on its
 * vertices, edges and around it. */
enum { POLY2_N = 7 };
static const double poly2[POLY2_N][2] = { { 0, 0 },  { 4, 0 }, { 4, 3 }, { 1, 3 },
                                          { 3, 1 },  { 2, 4 }, { 0, 2 } };
static double *pts2;
static int64_t n_pts2;
static uint8_t *ref_pip[2];
static int64_t ref_pip_count[2];
static int32_t *ref_wind;
static int64_t ref_wind_count;

static isect_xform xform;

static const isect_opts opts_any = { (uint32_t)sizeof(isect_opts), ISECT_ANY_HIT,
                                     ISECT_EPS_DEFAULT };
static const isect_opts opts_cull = { (uint32_t)sizeof(isect_opts), ISECT_CULL_BACK,
                                      ISECT_EPS_DEFAULT };

static pthread_barrier_t start_line;
static int n_threads;

/* --race: the threads also bump this counter without synchronisation — a
 * deliberate data race, so a ThreadSanitizer run can show that the
 * sanitizer is live (scripts/run_tsan.sh expects a report from it). */
static int race_mode;
static long race_counter;

typedef struct thread_state {
    int id;
    int fails[MAX_SHAPES][N_KINDS];
    int fails_2d, fails_check, fails_create;
    int ran[MAX_SHAPES][N_KINDS];
} thread_state;

static void *xmalloc(size_t n)
{
    void *p = malloc(n > 0 ? n : 1);
    if (p == NULL) {
        fprintf(stderr, "out of memory\n");
        exit(2);
    }
    return p;
}

/* ------------------------------------------------------------- fixtures */

static double shape_numbers[MAX_SHAPES][64];

static void add_shape(const char *name, int32_t type, int32_t n, int32_t flags, const double *data,
                      int count, const isect_mesh *mesh, int solid)
{
    for (int pass = 0; pass < 2; pass++) {
        shape_entry *e = &shapes[n_shapes];
        memset(e, 0, sizeof *e);
        if (data != NULL) {
            memcpy(shape_numbers[n_shapes], data, (size_t)count * sizeof *data);
            e->s.data = shape_numbers[n_shapes];
        }
        e->s.type = type;
        e->s.n = n;
        e->s.flags = flags;
        e->s.mesh = mesh;
        e->s.xform = pass ? &xform : NULL;
        e->solid = solid;
        snprintf(e->name, sizeof e->name, "%s%s", name, pass ? " (transformed)" : "");
        n_shapes++;
    }
}

static void build_shapes(void)
{
    /* A rotation about (1, 2, 2)/3 by acos(0.6), scaled by (1.5, 0.75, 1) and
     * moved by (0.25, -0.5, 0.125): no face stays axis-aligned. */
    const double m[16] = { 1.2, -0.45, 0.4, 0.25, 0.9, 0.6, -0.3, -0.5,
                           -0.3, 0.3, 0.9, 0.125, 0, 0, 0, 1 };
    if (isect_xform_init(&xform, m) != ISECT_OK) {
        fprintf(stderr, "isect_xform_init failed\n");
        exit(2);
    }
    const double plane[4] = { 0.25, -0.5, 1.0, 0.125 };
    const double sphere[4] = { 0.125, -0.25, 0.0625, 1.0 };
    const double box[6] = { -1, -0.5, -0.75, 1, 0.5, 0.75 };
    const double tri[9] = { -1, -1, 0, 1, -1, 0.5, 0, 1, -0.25 };
    /* A concave, self-intersecting pentagram in z = 0.25: the rules differ
     * in its centre. */
    double star[15];
    for (int i = 0; i < 5; i++) {
        double a = 6.283185307179586 * (2 * i) / 5.0;
        star[3 * i] = cos(a);
        star[3 * i + 1] = sin(a);
        star[3 * i + 2] = 0.25;
    }
    /* The octahedron |x| + |y| + |z| <= 1. */
    double octa[32];
    for (int i = 0; i < 8; i++) {
        octa[4 * i] = (i & 1) ? -1 : 1;
        octa[4 * i + 1] = (i & 2) ? -1 : 1;
        octa[4 * i + 2] = (i & 4) ? -1 : 1;
        octa[4 * i + 3] = -1;
    }
    const double cyl[7] = { 0, 0, -1, 0.25, 0.5, 1, 0.75 };
    const double cyl_inf[7] = { 0.5, 0, 0, 0, 1, 0.5, 0.5 };
    const double ell[6] = { 0, 0.25, 0, 1.25, 0.5, 0.75 };
    /* A hyperboloid of one sheet x^2 + y^2 - z^2 - 0.25 = 0. */
    const double quad[10] = { 1, 1, -1, 0, 0, 0, 0, 0, 0, -0.25 };

    add_shape("plane", ISECT_PLANE, 0, 0, plane, 4, NULL, 0);
    add_shape("sphere", ISECT_SPHERE, 0, 0, sphere, 4, NULL, 1);
    add_shape("aabb", ISECT_AABB, 0, 0, box, 6, NULL, 1);
    add_shape("triangle", ISECT_TRIANGLE, 0, 0, tri, 9, NULL, 0);
    add_shape("polygon even-odd", ISECT_POLYGON, 5, ISECT_EVEN_ODD, star, 15, NULL, 0);
    add_shape("polygon nonzero", ISECT_POLYGON, 5, ISECT_NONZERO, star, 15, NULL, 0);
    add_shape("convex", ISECT_CONVEX, 8, 0, octa, 32, NULL, 1);
    add_shape("cylinder capped", ISECT_CYLINDER, 0, ISECT_CAPPED, cyl, 7, NULL, 1);
    add_shape("cylinder open", ISECT_CYLINDER, 0, 0, cyl, 7, NULL, 0);
    add_shape("cylinder_inf", ISECT_CYLINDER_INF, 0, 0, cyl_inf, 7, NULL, 1);
    add_shape("ellipsoid", ISECT_ELLIPSOID, 0, 0, ell, 6, NULL, 1);
    add_shape("quadric", ISECT_QUADRIC, 0, 0, quad, 10, NULL, 1);

    const double centre[3] = { 0, 0, 0 };
    fx[0] = fx_icosphere(2, centre, 1.0); /* 320 triangles, offsets NULL */
    fx[1] = fx_cube(0);                   /* 6 quads through offsets */
    fx[2] = fx_l_prism(1.0);              /* concave hexagon caps */
    fx[3] = fx_torus(1.0, 0.375, 16, 8, 1);
    static const char *const mesh_names[N_MESHES] = { "mesh icosphere", "mesh cube quads",
                                                      "mesh L-prism", "mesh torus" };
    for (int i = 0; i < N_MESHES; i++) {
        meshes[i] = fx_build(&fx[i]);
        mesh_shape[i] = n_shapes;
        add_shape(mesh_names[i], ISECT_MESH, 0, 0, NULL, 0, meshes[i], 1);
    }
}

/* A point the rays aim at: random near the shapes, or a lattice point (box
 * and cube corners, edge midpoints, the origin) where exact ties decide. */
static void aim_point(double p[3])
{
    int r = rng_int(0, 9);
    if (r < 6) {
        for (int k = 0; k < 3; k++)
            p[k] = 1.5 * rng_unit();
    } else if (r < 8) {
        for (int k = 0; k < 3; k++)
            p[k] = 0.5 * rng_int(-2, 2);
    } else {
        /* a vertex of one of the meshes */
        const fx_mesh *m = &fx[rng_int(0, N_MESHES - 1)];
        int64_t v = (int64_t)(rng_next() % (uint64_t)m->nv);
        memcpy(p, m->v + 3 * v, 3 * sizeof *p);
    }
}

static void build_rays(void)
{
    rays = xmalloc((size_t)n_rays * sizeof *rays);
    spawn_dirs = xmalloc((size_t)n_rays * 3 * sizeof *spawn_dirs);
    for (int64_t i = 0; i < n_rays; i++) {
        isect_ray *r = &rays[i];
        double target[3], d[3];
        rng_dir(d);
        aim_point(target);
        double dist = 2.0 + 3.0 * fabs(rng_unit());
        for (int k = 0; k < 3; k++) {
            r->org[k] = target[k] - dist * d[k];
            r->dir[k] = d[k] * rng_scale(-2, 2);
        }
        r->tmin = 0.0;
        r->tmax = INFINITY;
        switch (i % 17) {
        case 3: /* a window */
            r->tmin = fabs(rng_unit()) * dist / fabs(rng_scale(-2, 2));
            r->tmax = r->tmin + 2.0 * fabs(rng_unit());
            break;
        case 5: /* axis-aligned, through lattice points */
            memset(r->dir, 0, sizeof r->dir);
            r->dir[i % 3] = (i & 8) ? 1.0 : -1.0;
            for (int k = 0; k < 3; k++)
                r->org[k] = (k == (int)(i % 3)) ? -4.0 * r->dir[k] : 0.5 * rng_int(-2, 2);
            break;
        case 7: /* origin inside the shapes */
            for (int k = 0; k < 3; k++)
                r->org[k] = 0.25 * rng_unit();
            break;
        default:
            break;
        }
        if (i % 97 == 11)
            r->org[1] = NAN; /* bad: INVALID in batches, an error from scalars */
        if (i % 97 == 13)
            memset(r->dir, 0, sizeof r->dir);
        double s[3];
        rng_dir(s);
        memcpy(spawn_dirs + 3 * i, s, sizeof s);
    }
    n_points = n_rays;
    points = xmalloc((size_t)n_points * 3 * sizeof *points);
    for (int64_t i = 0; i < n_points; i++) {
        if (i % 5 == 0)
            for (int k = 0; k < 3; k++)
                points[3 * i + k] = 0.25 * rng_int(-6, 6);
        else
            for (int k = 0; k < 3; k++)
                points[3 * i + k] = 1.75 * rng_unit();
        if (i % 101 == 7)
            points[3 * i + 2] = INFINITY;
    }
    n_pts2 = n_rays;
    pts2 = xmalloc((size_t)n_pts2 * 2 * sizeof *pts2);
    for (int64_t i = 0; i < n_pts2; i++) {
        if (i % 3 == 0) {
            pts2[2 * i] = 0.5 * rng_int(-1, 9);
            pts2[2 * i + 1] = 0.5 * rng_int(-1, 9);
        } else {
            pts2[2 * i] = 2.0 + 2.5 * rng_unit();
            pts2[2 * i + 1] = 2.0 + 2.5 * rng_unit();
        }
        if (i % 89 == 5)
            pts2[2 * i] = NAN;
    }
}

/* ------------------------------------------------------------ reference */

/* The spawned ray from a closest hit: along dirs[i], or its mirror image
 * when that points back into the surface is left to the library: any
 * direction is valid. */
static int spawn_one(const isect_shape *s, const isect_hit *hit, const double *dir,
                     isect_ray *out)
{
    memset(out, 0, sizeof *out);
    return isect_spawn_ray(s, hit, dir, out);
}

static void build_reference(void)
{
    for (int si = 0; si < n_shapes; si++) {
        const isect_shape *s = &shapes[si].s;
        reference *r = &refs[si];
        size_t hb = (size_t)n_rays * sizeof(isect_hit);
        r->closest = xmalloc(hb);
        r->any = xmalloc(hb);
        r->cull = xmalloc(hb);
        r->shared = xmalloc(hb);
        memset(r->shared, 0xA5, hb);
        r->n_closest = isect_intersect_batch(s, rays, n_rays, NULL, r->closest);
        r->n_any = isect_intersect_batch(s, rays, n_rays, &opts_any, r->any);
        r->n_cull = isect_intersect_batch(s, rays, n_rays, &opts_cull, r->cull);
        CHECK(r->n_closest >= 0 && r->n_any >= 0 && r->n_cull >= 0);
        r->offsets = xmalloc((size_t)(n_rays + 1) * sizeof *r->offsets);
        r->total = isect_intersect_all_batch(s, rays, n_rays, NULL, r->offsets, NULL, 0);
        CHECK(r->total >= 0);
        r->all = xmalloc((size_t)(r->total > 0 ? r->total : 1) * sizeof *r->all);
        CHECK_EQ_INT(isect_intersect_all_batch(s, rays, n_rays, NULL, r->offsets, r->all,
                                               r->total),
                     r->total);
        if (shapes[si].solid) {
            r->inside = xmalloc((size_t)n_points);
            r->n_inside = isect_contains_batch(s, points, n_points, r->inside);
            CHECK(r->n_inside >= 0);
        }
        r->spawned = xmalloc((size_t)n_rays * sizeof *r->spawned);
        r->spawn_status = xmalloc((size_t)n_rays * sizeof *r->spawn_status);
        for (int64_t i = 0; i < n_rays; i++) {
            int kind = r->closest[i].kind;
            if (kind == ISECT_ENTER || kind == ISECT_EXIT || kind == ISECT_TOUCH)
                r->spawn_status[i] = spawn_one(s, &r->closest[i], spawn_dirs + 3 * i,
                                               &r->spawned[i]);
            else
                r->spawn_status[i] = 1; /* not spawned */
        }
    }
    for (int rule = 0; rule < 2; rule++) {
        ref_pip[rule] = xmalloc((size_t)n_pts2);
        ref_pip_count[rule] = isect_point_in_polygon2_batch(&poly2[0][0], POLY2_N, pts2, n_pts2,
                                                            rule, ref_pip[rule]);
        CHECK(ref_pip_count[rule] >= 0);
    }
    ref_wind = xmalloc((size_t)n_pts2 * sizeof *ref_wind);
    ref_wind_count = isect_winding_number2_batch(&poly2[0][0], POLY2_N, pts2, n_pts2, ref_wind);
    CHECK(ref_wind_count >= 0);
    for (int i = 0; i < N_MESHES; i++) {
        memset(&mesh_reports[i], 0, sizeof mesh_reports[i]);
        CHECK_EQ_INT(isect_mesh_check(meshes[i], &mesh_reports[i]), ISECT_OK);
    }
}

/* -------------------------------------------------------------- threads */

/* The chunk size thread t uses for batch calls: 1, 7, 61, ... or the whole
 * batch, so the split differs between threads. */
static int64_t chunk_for(int t)
{
    static const int64_t sizes[] = { 0, 1, 7, 61, 256, 999, 3, 4096 };
    int64_t c = sizes[t % (int)(sizeof sizes / sizeof sizes[0])];
    return c == 0 || c > n_rays ? n_rays : c;
}

static int closest_in_chunks(const isect_shape *s, const isect_opts *o, int64_t chunk,
                             isect_hit *out, const isect_hit *want, int64_t want_n)
{
    int64_t found = 0;
    for (int64_t lo = 0; lo < n_rays; lo += chunk) {
        int64_t m = n_rays - lo < chunk ? n_rays - lo : chunk;
        int64_t f = isect_intersect_batch(s, rays + lo, m, o, out + lo);
        if (f < 0)
            return 1;
        found += f;
    }
    return found != want_n || memcmp(out, want, (size_t)n_rays * sizeof *out) != 0;
}

static void run_shape(thread_state *ts, int si, isect_hit *buf, int64_t *offs, isect_hit *all,
                      uint8_t *inside)
{
    const isect_shape *s = &shapes[si].s;
    const reference *r = &refs[si];
    int64_t chunk = chunk_for(ts->id + si);
    int *f = ts->fails[si];

    ts->ran[si][K_CLOSEST] = 1;
    f[K_CLOSEST] += closest_in_chunks(s, NULL, chunk, buf, r->closest, r->n_closest);
    ts->ran[si][K_ANY] = 1;
    f[K_ANY] += closest_in_chunks(s, &opts_any, chunk, buf, r->any, r->n_any);
    ts->ran[si][K_CULL] = 1;
    f[K_CULL] += closest_in_chunks(s, &opts_cull, chunk, buf, r->cull, r->n_cull);

    ts->ran[si][K_ALL] = 1;
    int64_t total = isect_intersect_all_batch(s, rays, n_rays, NULL, offs, all, r->total);
    f[K_ALL] += total != r->total
                || memcmp(offs, r->offsets, (size_t)(n_rays + 1) * sizeof *offs) != 0
                || memcmp(all, r->all, (size_t)total * sizeof *all) != 0;

    ts->ran[si][K_COUNT] = 1;
    memset(offs, 0, (size_t)(n_rays + 1) * sizeof *offs);
    total = isect_intersect_all_batch(s, rays, n_rays, NULL, offs, NULL, 0);
    f[K_COUNT] += total != r->total
                  || memcmp(offs, r->offsets, (size_t)(n_rays + 1) * sizeof *offs) != 0;

    ts->ran[si][K_SCALAR] = 1;
    isect_hit one[SCALAR_CAP];
    for (int64_t i = 0; i < n_rays; i++) {
        int64_t want = r->offsets[i + 1] - r->offsets[i];
        int bad = r->closest[i].kind == ISECT_INVALID;
        int count = isect_intersect(s, &rays[i], NULL, NULL, 0);
        f[K_COUNT] += bad ? count >= 0 : count != want;
        int got = isect_intersect(s, &rays[i], NULL, one, SCALAR_CAP);
        if (bad)
            f[K_SCALAR] += got >= 0;
        else
            f[K_SCALAR] += got != want || got > SCALAR_CAP
                           || memcmp(one, r->all + r->offsets[i], (size_t)got * sizeof *one) != 0;
    }

    if (shapes[si].solid) {
        ts->ran[si][K_CONTAINS] = 1;
        int64_t in = 0;
        for (int64_t lo = 0; lo < n_points; lo += chunk) {
            int64_t m = n_points - lo < chunk ? n_points - lo : chunk;
            int64_t c = isect_contains_batch(s, points + 3 * lo, m, inside + lo);
            in = c < 0 || in < 0 ? -1 : in + c;
        }
        f[K_CONTAINS] += in != r->n_inside || memcmp(inside, r->inside, (size_t)n_points) != 0;
        for (int64_t i = ts->id; i < n_points; i += n_threads) {
            int c = isect_contains(s, points + 3 * i);
            f[K_CONTAINS] += r->inside[i] == ISECT_INVALID ? c != ISECT_E_NONFINITE
                                                           : c != r->inside[i];
        }
    }

    ts->ran[si][K_SPAWN] = 1;
    for (int64_t i = 0; i < n_rays; i++) {
        if (r->spawn_status[i] == 1)
            continue;
        isect_ray out;
        int status = spawn_one(s, &r->closest[i], spawn_dirs + 3 * i, &out);
        f[K_SPAWN] += status != r->spawn_status[i]
                      || memcmp(&out, &r->spawned[i], sizeof out) != 0;
    }

    /* Disjoint interleaved chunks of one shared buffer: thread t writes
     * chunks t, t + T, t + 2T, ... (compared by the main thread). */
    ts->ran[si][K_SHARED] = 1;
    const int64_t piece = 61;
    for (int64_t c = ts->id; c * piece < n_rays; c += n_threads) {
        int64_t lo = c * piece, m = n_rays - lo < piece ? n_rays - lo : piece;
        f[K_SHARED] += isect_intersect_batch(s, rays + lo, m, NULL, refs[si].shared + lo) < 0;
    }
}

static void run_2d(thread_state *ts, uint8_t *inside, int32_t *wind)
{
    for (int rule = 0; rule < 2; rule++) {
        int64_t c = isect_point_in_polygon2_batch(&poly2[0][0], POLY2_N, pts2, n_pts2, rule,
                                                  inside);
        ts->fails_2d += c != ref_pip_count[rule]
                        || memcmp(inside, ref_pip[rule], (size_t)n_pts2) != 0;
    }
    int64_t c = isect_winding_number2_batch(&poly2[0][0], POLY2_N, pts2, n_pts2, wind);
    ts->fails_2d += c != ref_wind_count
                    || memcmp(wind, ref_wind, (size_t)n_pts2 * sizeof *wind) != 0;
    for (int64_t i = ts->id; i < n_pts2; i += n_threads) {
        int32_t w = 0;
        int status = isect_winding_number2(&poly2[0][0], POLY2_N, pts2 + 2 * i, &w);
        ts->fails_2d += ref_wind[i] == INT32_MIN ? status != ISECT_E_NONFINITE
                                                 : status != ISECT_OK || w != ref_wind[i];
    }
}

static void run_meshes(thread_state *ts, isect_hit *buf)
{
    for (int j = 0; j < N_MESHES; j++) {
        int i = (j + ts->id) % N_MESHES;
        isect_mesh_report rep;
        memset(&rep, 0, sizeof rep);
        ts->fails_check += isect_mesh_check(meshes[i], &rep) != ISECT_OK
                           || memcmp(&rep, &mesh_reports[i], sizeof rep) != 0;
        /* A private mesh from the shared input arrays gives the shared
         * mesh's results. */
        isect_mesh *own = NULL;
        const fx_mesh *m = &fx[i];
        int status = isect_mesh_create(m->v, m->nv, m->idx, fx_all_triangles(m) ? NULL : m->off,
                                       m->nf, &own);
        if (status != ISECT_OK) {
            ts->fails_create++;
            continue;
        }
        isect_shape s = shapes[mesh_shape[i]].s;
        s.mesh = own;
        const reference *r = &refs[mesh_shape[i]];
        ts->fails_create += closest_in_chunks(&s, NULL, chunk_for(ts->id + 3), buf, r->closest,
                                              r->n_closest);
        isect_mesh_destroy(own);
    }
}

static void *worker(void *arg)
{
    thread_state *ts = arg;
    isect_hit *buf = xmalloc((size_t)n_rays * sizeof *buf);
    int64_t *offs = xmalloc((size_t)(n_rays + 1) * sizeof *offs);
    int64_t most = 1;
    for (int si = 0; si < n_shapes; si++)
        most = refs[si].total > most ? refs[si].total : most;
    isect_hit *all = xmalloc((size_t)most * sizeof *all);
    uint8_t *inside = xmalloc((size_t)(n_points > n_pts2 ? n_points : n_pts2));
    int32_t *wind = xmalloc((size_t)n_pts2 * sizeof *wind);

    pthread_barrier_wait(&start_line);
    if (race_mode)
        for (int i = 0; i < 1000; i++)
            race_counter++;
    /* Each thread starts at another shape, so different shapes and kinds
     * overlap in time. */
    for (int j = 0; j < n_shapes; j++) {
        int si = (j + ts->id * 5) % n_shapes;
        run_shape(ts, si, buf, offs, all, inside);
        if (j % 8 == ts->id % 8)
            run_2d(ts, inside, wind);
    }
    run_meshes(ts, buf);

    free(buf);
    free(offs);
    free(all);
    free(inside);
    free(wind);
    return NULL;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--race") == 0) {
        race_mode = 1;
        argv++;
        argc--;
    }
    n_rays = argc > 1 ? atol(argv[1]) : 1500;
    n_threads = argc > 2 ? atoi(argv[2]) : 8;
    if (n_rays < 1 || n_threads < 1 || n_threads > MAX_THREADS) {
        fprintf(stderr, "usage: %s [rays >= 1 [threads 1..%d]]\n", argv[0], MAX_THREADS);
        return 2;
    }
    rng_seed(0x7468726561647321ull);
    build_shapes();
    build_rays();
    build_reference();

    thread_state *states = calloc((size_t)n_threads, sizeof *states);
    pthread_t *tids = xmalloc((size_t)n_threads * sizeof *tids);
    if (states == NULL || pthread_barrier_init(&start_line, NULL, (unsigned)n_threads) != 0) {
        fprintf(stderr, "cannot set up the threads\n");
        return 2;
    }
    int started = 0;
    for (int t = 0; t < n_threads; t++) {
        states[t].id = t;
        if (pthread_create(&tids[t], NULL, worker, &states[t]) != 0)
            break;
        started++;
    }
    CHECK_EQ_INT(started, n_threads);
    if (started != n_threads) {
        fprintf(stderr, "pthread_create failed after %d threads\n", started);
        return 2; /* the others wait at the barrier forever: give up */
    }
    for (int t = 0; t < n_threads; t++)
        pthread_join(tids[t], NULL);
    pthread_barrier_destroy(&start_line);

    long queries = 0;
    for (int si = 0; si < n_shapes; si++) {
        for (int k = 0; k < N_KINDS; k++) {
            int fails = 0, ran = 0;
            for (int t = 0; t < n_threads; t++) {
                fails += states[t].fails[si][k];
                ran += states[t].ran[si][k];
            }
            if (k == K_CONTAINS && !shapes[si].solid)
                continue;
            if (fails)
                fprintf(stderr, "%s, %s: %d mismatches over %d threads\n", shapes[si].name,
                        kind_names[k], fails, n_threads);
            CHECK_EQ_INT(fails, 0);
            CHECK_EQ_INT(ran, n_threads);
            queries += ran;
        }
        CHECK(memcmp(refs[si].shared, refs[si].closest, (size_t)n_rays * sizeof(isect_hit))
              == 0);
    }
    int f2d = 0, fcheck = 0, fcreate = 0;
    for (int t = 0; t < n_threads; t++) {
        f2d += states[t].fails_2d;
        fcheck += states[t].fails_check;
        fcreate += states[t].fails_create;
    }
    CHECK_EQ_INT(f2d, 0);
    CHECK_EQ_INT(fcheck, 0);
    CHECK_EQ_INT(fcreate, 0);
    if (race_mode)
        printf("--race: the unsynchronised counter reached %ld\n", race_counter);
    printf("%d threads, %d shapes, %ld rays and %ld points each: %ld batch runs compared\n",
           n_threads, n_shapes, (long)n_rays, (long)n_points, queries);

    for (int si = 0; si < n_shapes; si++) {
        reference *r = &refs[si];
        free(r->closest);
        free(r->any);
        free(r->cull);
        free(r->shared);
        free(r->offsets);
        free(r->all);
        free(r->inside);
        free(r->spawned);
        free(r->spawn_status);
    }
    for (int i = 0; i < N_MESHES; i++) {
        isect_mesh_destroy(meshes[i]);
        fx_free(&fx[i]);
    }
    free(ref_pip[0]);
    free(ref_pip[1]);
    free(ref_wind);
    free(rays);
    free(spawn_dirs);
    free(points);
    free(pts2);
    free(states);
    free(tids);
    return check_summary();
}
