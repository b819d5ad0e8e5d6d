/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_mesh.c — meshes (isect.h "meshes"): creation and every bad-input
 * class, queries against brute force over the faces, closest hit equal bit
 * for bit to the first of all hits, any hit, transformed meshes, exact
 * containment, and isect_mesh_check against closed-form values.
 *
 * Brute force runs every face through the public scalar functions
 * (isect_ray_triangle / isect_ray_polygon with ISECT_EVEN_ODD), which share
 * the mesh's per-face arithmetic, so the mesh must agree with it bit for bit.
 * It orders the hits as isect.h does: by t, hits whose t round alike by
 * their exact crossing parameters (computed here with exact_dyadic.h), then
 * by face index.
 */
#include "check.h"

#include <isect.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_fixtures.h"
#include "exact_dyadic.h"

/* ------------------------------------------------------------- helpers */

typedef struct lcg {
    uint64_t state;
} lcg;

static double lcg_uniform(lcg *g) /* in [-1, 1) */
{
    g->state = g->state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(g->state >> 11) * 0x1p-52 - 1.0;
}

static isect_shape mesh_shape(const isect_mesh *mesh, const isect_xform *x)
{
    isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, mesh, x };
    return s;
}

/* Appends src to dst (indices shifted). */
static void fx_append(fx_mesh *dst, const fx_mesh *src, double dx, double dy, double dz)
{
    int32_t base = (int32_t)dst->nv;
    for (int64_t i = 0; i < src->nv; i++)
        fx_vertex(dst, src->v[3 * i] + dx, src->v[3 * i + 1] + dy, src->v[3 * i + 2] + dz);
    for (int64_t f = 0; f < src->nf; f++) {
        int32_t corners[64];
        int n = (int)(src->off[f + 1] - src->off[f]);
        for (int i = 0; i < n; i++)
            corners[i] = base + src->idx[src->off[f] + i];
        fx_face(dst, n, corners);
    }
}

/* The exact crossing of face f's plane with the line of r. */
static void face_crossing(const fx_mesh *m, const isect_ray *r, int64_t f, exq *num, exq *den)
{
    int size = (int)(m->off[f + 1] - m->off[f]);
    const int32_t *c = m->idx + m->off[f];
    if (size == 3)
        ex_triangle_crossing(r->org, r->dir, m->v + 3 * c[0], m->v + 3 * c[1], m->v + 3 * c[2],
                             num, den);
    else
        ex_polygon_crossing(r->org, r->dir, m->v, c, size, num, den);
}

/* a before b: by t, then (t rounded alike) by the exact crossings of
 * their faces, then by face. */
static int hit_before_exact(const fx_mesh *m, const isect_ray *r, const isect_hit *a,
                            const isect_hit *b)
{
    if (a->t != b->t)
        return a->t < b->t;
    if (a->prim == b->prim)
        return 0;
    exq na, da, nb, db;
    face_crossing(m, r, a->prim, &na, &da);
    face_crossing(m, r, b->prim, &nb, &db);
    int c = ex_ratio_cmp(na, da, nb, db);
    return c != 0 ? c < 0 : a->prim < b->prim;
}

/* Every face through the public scalar functions: all hits, prim = face,
 * sorted by (t, prim). Returns the count. */
static int brute_hits(const fx_mesh *m, const isect_ray *r, uint32_t flags, isect_hit *out,
                      int cap)
{
    isect_opts o = ISECT_OPTS_INIT;
    o.flags = flags & ~ISECT_ANY_HIT;
    int n = 0;
    double buf[3 * 64];
    for (int64_t f = 0; f < m->nf; f++) {
        int size = (int)(m->off[f + 1] - m->off[f]);
        const int32_t *c = m->idx + m->off[f];
        isect_hit h;
        int got;
        if (size == 3) {
            got = isect_ray_triangle(r, m->v + 3 * c[0], m->v + 3 * c[1], m->v + 3 * c[2], &o,
                                     &h, 1);
        } else {
            for (int i = 0; i < size; i++)
                memcpy(buf + 3 * i, m->v + 3 * c[i], 3 * sizeof(double));
            got = isect_ray_polygon(r, buf, size, ISECT_EVEN_ODD, &o, &h, 1);
        }
        if (got < 0)
            return got;
        if (got > 0 && n < cap) {
            h.prim = (int32_t)f;
            int j = n++;
            for (; j > 0 && hit_before_exact(m, r, &h, &out[j - 1]); j--)
                out[j] = out[j - 1];
            out[j] = h;
        }
    }
    return n;
}

static int hits_equal(const isect_hit *a, const isect_hit *b, int n)
{
    return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

static int by_t_prim(const void *x, const void *y)
{
    const isect_hit *a = x, *b = y;
    if (a->t != b->t)
        return a->t < b->t ? -1 : 1;
    return (a->prim > b->prim) - (a->prim < b->prim);
}

/* The same records, in any order among those whose t are equal: for rays
 * beyond the range where the exact crossing parameters of two faces are
 * compared exactly (isect.h: exactness ranges), whose rounded ties are
 * ordered deterministically but not necessarily exactly. */
static int hits_equal_up_to_ties(const isect_hit *a, const isect_hit *b, int n)
{
    enum { MAX = 512 };
    static isect_hit sa[MAX], sb[MAX];
    if (n > MAX)
        return 0;
    memcpy(sa, a, (size_t)n * sizeof *a);
    memcpy(sb, b, (size_t)n * sizeof *b);
    qsort(sa, (size_t)n, sizeof *sa, by_t_prim);
    qsort(sb, (size_t)n, sizeof *sb, by_t_prim);
    return hits_equal(sa, sb, n);
}

/* The bounds of mesh m's vertices. */
static void mesh_bounds(const fx_mesh *m, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++)
        lo[k] = hi[k] = m->v[k];
    for (int64_t i = 1; i < m->nv; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->v[3 * i + k]);
            hi[k] = fmax(hi[k], m->v[3 * i + k]);
        }
}

/* A random ray for mesh m with bounds lo, hi: origin in a box 1.5x the
 * bounds, a random direction or (aim != 0) one aimed at a random vertex;
 * several range and culling variants. */
static isect_ray random_ray_in(const fx_mesh *m, const double lo[3], const double hi[3], lcg *g,
                               int aim, uint32_t *flags)
{
    isect_ray r;
    for (int k = 0; k < 3; k++) {
        double mid = 0.5 * (lo[k] + hi[k]), half = 0.85 * (hi[k] - lo[k]);
        r.org[k] = mid + half * lcg_uniform(g);
    }
    int kind = (int)((lcg_uniform(g) + 1.0) * 4.0);
    if (kind < 2 && aim) {
        int64_t i = (int64_t)((lcg_uniform(g) + 1.0) * 0.5 * (double)m->nv);
        for (int k = 0; k < 3; k++)
            r.dir[k] = m->v[3 * i + k] - r.org[k];
    } else {
        for (int k = 0; k < 3; k++)
            r.dir[k] = lcg_uniform(g);
    }
    r.tmin = 0.0;
    r.tmax = INFINITY;
    if (kind == 3 || kind == 5) {
        double a = 2.0 * lcg_uniform(g), b = 2.0 * lcg_uniform(g);
        r.tmin = fmin(a, b);
        r.tmax = fmax(a, b);
    }
    if (kind == 6)
        r.tmin = -INFINITY;
    *flags = kind == 4 || kind == 5 ? ISECT_CULL_BACK : 0u;
    return r;
}

static isect_ray random_ray(const fx_mesh *m, lcg *g, int aim, uint32_t *flags)
{
    double lo[3], hi[3];
    mesh_bounds(m, lo, hi);
    return random_ray_in(m, lo, hi, g, aim, flags);
}

/* ------------------------------------------------------------- creation */

static void test_create_destroy(void)
{
    isect_mesh_destroy(NULL); /* a no-op */
    fx_mesh cube = fx_cube(0);
    isect_mesh *mesh = NULL;
    CHECK_EQ_INT(isect_mesh_create(cube.v, cube.nv, cube.idx, cube.off, cube.nf, &mesh), ISECT_OK);
    CHECK(mesh != NULL);
    CHECK(isect_mesh_bytes(mesh) > 0);
    CHECK_EQ_INT(isect_mesh_bytes(NULL), ISECT_E_ARG);
    /* The input is copied: clobbering it changes nothing. */
    fx_mesh copy = fx_cube(0);
    for (int64_t i = 0; i < cube.nv * 3; i++)
        cube.v[i] = NAN;
    for (int64_t i = 0; i < cube.nidx; i++)
        cube.idx[i] = -7;
    isect_shape s = mesh_shape(mesh, NULL);
    isect_ray r = { { 0.5, 0.5, -1.0 }, { 0.0, 0.0, 1.0 }, 0.0, INFINITY };
    isect_hit h[4];
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 4), 2);
    CHECK(h[0].t == 1.0 && h[1].t == 2.0 && h[0].kind == ISECT_ENTER && h[1].kind == ISECT_EXIT);
    CHECK(h[0].normal[2] == -1.0 && h[1].normal[2] == 1.0);
    isect_mesh_destroy(mesh);
    fx_free(&cube);

    /* Empty meshes are valid and never hit. */
    CHECK_EQ_INT(isect_mesh_create(NULL, 0, NULL, NULL, 0, &mesh), ISECT_OK);
    s = mesh_shape(mesh, NULL);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 4), 0);
    isect_mesh_destroy(mesh);
    CHECK_EQ_INT(isect_mesh_create(copy.v, copy.nv, copy.idx, NULL, 0, &mesh), ISECT_OK);
    isect_mesh_destroy(mesh);
    fx_free(&copy);
}

static void test_bad_input(void)
{
    fx_mesh cube = fx_cube(0);
    fx_mesh tris = fx_cube(1);
    isect_mesh *mesh = (isect_mesh *)&cube; /* must be reset to NULL on error */
    int64_t nv = cube.nv, nf = cube.nf;

    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, nf, NULL), ISECT_E_ARG);
    CHECK_EQ_INT(isect_mesh_create(NULL, nv, cube.idx, cube.off, nf, &mesh), ISECT_E_ARG);
    CHECK(mesh == NULL);
    mesh = (isect_mesh *)&cube;
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, NULL, cube.off, nf, &mesh), ISECT_E_ARG);
    CHECK(mesh == NULL);
    CHECK_EQ_INT(isect_mesh_create(cube.v, -1, cube.idx, cube.off, nf, &mesh), ISECT_E_ARG);
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, -1, &mesh), ISECT_E_ARG);
    CHECK_EQ_INT(isect_mesh_create(cube.v, (int64_t)1 << 40, cube.idx, cube.off, nf, &mesh),
                 ISECT_E_ARG);

    /* An index out of range, in a polygon and in a triangle mesh. */
    int32_t saved = cube.idx[5];
    cube.idx[5] = (int32_t)nv;
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, nf, &mesh), ISECT_E_ARG);
    cube.idx[5] = -1;
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, nf, &mesh), ISECT_E_ARG);
    cube.idx[5] = saved;
    saved = tris.idx[tris.nidx - 1];
    tris.idx[tris.nidx - 1] = (int32_t)tris.nv;
    CHECK_EQ_INT(isect_mesh_create(tris.v, tris.nv, tris.idx, NULL, tris.nf, &mesh), ISECT_E_ARG);
    tris.idx[tris.nidx - 1] = saved;
    CHECK_EQ_INT(isect_mesh_create(tris.v, tris.nv - 1, tris.idx, NULL, tris.nf, &mesh),
                 ISECT_E_ARG);

    /* Offsets: not starting at 0, a face of fewer than 3 vertices, decreasing. */
    int64_t off[8];
    memcpy(off, cube.off, sizeof off[0] * 7);
    off[0] = 1;
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, off, nf, &mesh), ISECT_E_ARG);
    memcpy(off, cube.off, sizeof off[0] * 7);
    off[1] = 2; /* face 0 has 2 vertices */
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, off, nf, &mesh), ISECT_E_ARG);
    memcpy(off, cube.off, sizeof off[0] * 7);
    off[2] = 3; /* decreasing */
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, off, nf, &mesh), ISECT_E_ARG);
    memcpy(off, cube.off, sizeof off[0] * 7);
    off[6] = off[5]; /* last face empty */
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, off, nf, &mesh), ISECT_E_ARG);
    CHECK(mesh == NULL);

    /* Non-finite vertices. */
    double keep = cube.v[4];
    cube.v[4] = NAN;
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, nf, &mesh), ISECT_E_NONFINITE);
    cube.v[4] = INFINITY;
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, nf, &mesh), ISECT_E_NONFINITE);
    cube.v[4] = -INFINITY;
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, nf, &mesh), ISECT_E_NONFINITE);
    cube.v[4] = keep;
    CHECK(mesh == NULL);

    /* Descriptors: a mesh type needs mesh set, data NULL, n and flags 0. */
    CHECK_EQ_INT(isect_mesh_create(cube.v, nv, cube.idx, cube.off, nf, &mesh), ISECT_OK);
    isect_ray r = { { 0.5, 0.5, -1.0 }, { 0.0, 0.0, 1.0 }, 0.0, INFINITY };
    isect_hit h;
    isect_shape s = mesh_shape(NULL, NULL);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, &h, 1), ISECT_E_ARG);
    s = mesh_shape(mesh, NULL);
    s.data = cube.v;
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, &h, 1), ISECT_E_ARG);
    s = mesh_shape(mesh, NULL);
    s.n = 3;
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, &h, 1), ISECT_E_ARG);
    /* flags: the containment rule, EVEN_ODD, NONZERO or WINDING (rays
     * ignore it); anything else is refused */
    s = mesh_shape(mesh, NULL);
    s.flags = 3;
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, &h, 1), ISECT_E_ARG);
    s.flags = -1;
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, &h, 1), ISECT_E_ARG);
    s.flags = ISECT_WINDING;
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, &h, 1), 2); /* in and out of the cube */
    isect_mesh_report rep;
    CHECK_EQ_INT(isect_mesh_check(NULL, &rep), ISECT_E_ARG);
    CHECK_EQ_INT(isect_mesh_check(mesh, NULL), ISECT_E_ARG);
    isect_mesh_destroy(mesh);
    fx_free(&cube);
    fx_free(&tris);
}

/* ------------------------------------------------------------- queries */

/* rays random rays against m: the mesh's hit list equals brute force bit
 * for bit; the batch closest hit is its first record; any-hit returns one
 * of its records. Returns the number of hits seen (so callers can check
 * the test exercised something). */
static int64_t check_against_brute(const fx_mesh *m, int rays, uint64_t seed)
{
    enum { CAP = 512 };
    static isect_hit want[CAP], got[CAP];
    isect_mesh *mesh = fx_build(m);
    isect_shape s = mesh_shape(mesh, NULL);
    lcg g = { seed };
    int64_t seen = 0;
    int bad_all = 0, bad_first = 0, bad_any = 0, bad_count = 0, bad_cap = 0;
    for (int i = 0; i < rays; i++) {
        uint32_t flags;
        isect_ray r = random_ray(m, &g, 1, &flags);
        isect_opts o = ISECT_OPTS_INIT;
        o.flags = flags;
        int n_want = brute_hits(m, &r, flags, want, CAP);
        int n_got = isect_intersect(&s, &r, &o, got, CAP);
        seen += n_want;
        if (n_got != n_want || !hits_equal(want, got, n_want))
            bad_all++;
        /* Counting only, and a short buffer: the best cap, in order. */
        if (isect_intersect(&s, &r, &o, NULL, 0) != n_want)
            bad_count++;
        if (n_want > 1) {
            int c = n_want / 2;
            if (isect_intersect(&s, &r, &o, got, c) != n_want || !hits_equal(want, got, c))
                bad_cap++;
        }
        isect_hit closest;
        int64_t hit = isect_intersect_batch(&s, &r, 1, &o, &closest);
        if (hit != (n_want > 0) || (n_want > 0 && !hits_equal(&closest, want, 1))
            || (n_want == 0 && closest.kind != ISECT_MISS))
            bad_first++;
        o.flags |= ISECT_ANY_HIT;
        hit = isect_intersect_batch(&s, &r, 1, &o, &closest);
        int member = 0;
        for (int j = 0; j < n_want; j++)
            member |= hits_equal(&closest, &want[j], 1);
        if (hit != (n_want > 0) || (n_want > 0 && !member))
            bad_any++;
        int any_count = isect_intersect(&s, &r, &o, got, 1);
        if (any_count != (n_want > 0) || (any_count > 0 && !hits_equal(got, &closest, 1)))
            bad_any++;
    }
    CHECK_EQ_INT(bad_all, 0);
    CHECK_EQ_INT(bad_count, 0);
    CHECK_EQ_INT(bad_cap, 0);
    CHECK_EQ_INT(bad_first, 0);
    CHECK_EQ_INT(bad_any, 0);
    isect_mesh_destroy(mesh);
    return seen;
}

/* Rays nearly parallel to coordinate planes: one or two direction
 * components zero, subnormal or small relative to the others (below and
 * just above the 2^-20 under which the node test treats an axis as flat:
 * its slab then passes all or nothing by the side of the padded origin).
 * Each ray passes through a vertex at t = 1, its origin moved along the
 * flat axis by the ray's own drift, so the origin lies just outside the
 * boxes whose extreme that vertex is: a pad too small to cover the drift
 * loses their hits. The mesh must give brute force's hits bit for bit. */
static int64_t check_flat_rays(const fx_mesh *m, int rays, uint64_t seed)
{
    enum { CAP = 256 };
    static isect_hit want[CAP], got[CAP];
    static const double relative[6] = { 0.0, 1e-7, 0x1p-21, 0x1.ep-21, 0x1.2p-20, 0x1p-1070 };
    isect_mesh *mesh = fx_build(m);
    isect_shape s = mesh_shape(mesh, NULL);
    lcg g = { seed };
    int64_t seen = 0;
    int bad = 0;
    for (int i = 0; i < rays; i++) {
        uint32_t flags;
        isect_ray r = random_ray(m, &g, 0, &flags);
        int64_t v = (int64_t)((lcg_uniform(&g) + 1.0) * 0.5 * (double)m->nv);
        const double *target = m->v + 3 * v;
        int k = i % 3, both = (i / 3) % 2;
        double f = relative[(i / 6) % 6] * (lcg_uniform(&g) < 0.0 ? -1.0 : 1.0);
        for (int a = 0; a < 3; a++)
            r.dir[a] = target[a] - r.org[a];
        double scale = fabs(r.dir[(k + 1) % 3]) + fabs(r.dir[(k + 2) % 3]);
        r.dir[k] = f * scale;
        if (both)
            r.dir[(k + 2) % 3] = f * scale;
        if (r.dir[0] == 0.0 && r.dir[1] == 0.0 && r.dir[2] == 0.0)
            r.dir[(k + 1) % 3] = 1.0;
        for (int a = 0; a < 3; a++)
            r.org[a] = target[a] - r.dir[a];
        r.tmin = 0.0;
        r.tmax = INFINITY;
        isect_opts o = ISECT_OPTS_INIT;
        o.flags = flags;
        int n_want = brute_hits(m, &r, flags, want, CAP);
        int n_got = isect_intersect(&s, &r, &o, got, CAP);
        seen += n_want;
        isect_hit closest;
        int64_t hit = isect_intersect_batch(&s, &r, 1, &o, &closest);
        /* Subnormal direction components beside normal ones (and the
         * 2^600 and 2^-600 meshes) are beyond the exact tie order's range:
         * the records must be brute force's, in any order among equal t,
         * and the batch's the first of the mesh's own list. */
        if (n_got != n_want || !hits_equal_up_to_ties(want, got, n_want)
            || hit != (n_want > 0) || (n_want > 0 && !hits_equal(&closest, got, 1))
            || (n_want > 0 && closest.t != want[0].t))
            bad++;
    }
    CHECK_EQ_INT(bad, 0);
    isect_mesh_destroy(mesh);
    return seen;
}

static void test_queries(void)
{
    const double origin[3] = { 0.0, 0.0, 0.0 }, off_center[3] = { 0.3, -0.2, 0.1 };
    fx_mesh m = fx_icosphere(3, origin, 1.0);
    CHECK(check_against_brute(&m, 3000, 1) > 1000);
    fx_free(&m);
    m = fx_icosphere(5, off_center, 2.0); /* 20480 faces: a deep tree */
    CHECK(check_against_brute(&m, 300, 2) > 100);
    fx_free(&m);
    m = fx_torus(1.0, 0.35, 24, 12, 1);
    CHECK(check_against_brute(&m, 2000, 3) > 500);
    fx_free(&m);
    m = fx_torus(1.0, 0.35, 16, 8, 0); /* non-planar quads: polygon faces */
    CHECK(check_against_brute(&m, 2000, 4) > 500);
    fx_free(&m);
    m = fx_l_prism(1.0);
    CHECK(check_against_brute(&m, 3000, 5) > 500);
    fx_free(&m);
    m = fx_genus2(0);
    CHECK(check_against_brute(&m, 3000, 6) > 500);
    fx_free(&m);
    /* Triangles and polygons in one mesh. */
    m = fx_genus2(1);
    fx_mesh part = fx_l_prism(0.5);
    fx_append(&m, &part, 1.0, 0.5, 1.5);
    fx_free(&part);
    part = fx_icosphere(2, origin, 0.7);
    fx_append(&m, &part, 2.5, 1.5, 0.5); /* overlaps the block */
    fx_free(&part);
    CHECK(check_against_brute(&m, 3000, 7) > 1000);
    fx_free(&m);
    /* Far from 1 in scale (the traversal's error bounds scale with the
     * coordinates) and far from the origin (they grow with |org|). */
    const double scales[3] = { 0x1p600, 0x1p-600, 1e-3 };
    const double shifts[3] = { 0.0, 0.0, 1e6 };
    for (int i = 0; i < 3; i++) {
        m = fx_icosphere(2, origin, 1.0);
        part = fx_l_prism(0.5);
        fx_append(&m, &part, 0.25, 0.25, 0.25);
        fx_free(&part);
        for (int64_t v = 0; v < 3 * m.nv; v++)
            m.v[v] = m.v[v] * scales[i] + shifts[i];
        CHECK(check_against_brute(&m, 1000, 8 + (uint64_t)i) > 300);
        CHECK(check_flat_rays(&m, 600, 20 + (uint64_t)i) > 100);
        fx_free(&m);
    }
    m = fx_genus2(0);
    CHECK(check_flat_rays(&m, 3000, 30) > 500);
    fx_free(&m);
}

/* Rays through the vertices and edges of a cube of quads, on its faces'
 * lines: the exact hit lists. */
static void test_cube_exact(void)
{
    fx_mesh m = fx_cube(0);
    isect_mesh *mesh = fx_build(&m);
    isect_shape s = mesh_shape(mesh, NULL);
    isect_hit h[8];
    /* Through the corner (1,1,1) along the diagonal: enters at (0,0,0). */
    isect_ray r = { { -1.0, -1.0, -1.0 }, { 1.0, 1.0, 1.0 }, 0.0, INFINITY };
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 8), 2);
    CHECK(h[0].t == 1.0 && h[1].t == 2.0);
    CHECK(h[0].kind == ISECT_ENTER && h[1].kind == ISECT_EXIT);
    /* Through the middle of the edge x = 0, z = 0. */
    isect_ray e = { { -1.0, 0.5, -1.0 }, { 1.0, 0.0, 1.0 }, 0.0, INFINITY };
    CHECK_EQ_INT(isect_intersect(&s, &e, NULL, h, 8), 2);
    CHECK(h[0].t == 1.0 && h[1].t == 2.0);
    /* Culling keeps the entry only; a window keeps the exit only. */
    isect_opts o = ISECT_OPTS_INIT;
    o.flags = ISECT_CULL_BACK;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 8), 1);
    CHECK(h[0].kind == ISECT_ENTER);
    isect_ray w = r;
    w.tmin = 1.5;
    CHECK_EQ_INT(isect_intersect(&s, &w, NULL, h, 8), 1);
    CHECK(h[0].t == 2.0 && h[0].kind == ISECT_EXIT);
    w.tmin = 2.5;
    CHECK_EQ_INT(isect_intersect(&s, &w, NULL, h, 8), 0);
    w.tmin = 3.0;
    w.tmax = 2.0; /* tmin > tmax */
    CHECK_EQ_INT(isect_intersect(&s, &w, NULL, h, 8), 0);
    /* Batch with a bad ray in the middle. */
    isect_ray rays[3] = { r, r, e };
    rays[1].dir[0] = NAN;
    isect_hit closest[3];
    CHECK_EQ_INT(isect_intersect_batch(&s, rays, 3, NULL, closest), 2);
    CHECK(closest[0].t == 1.0 && closest[1].kind == ISECT_INVALID && closest[2].t == 1.0);
    int64_t offsets[4];
    isect_hit all[8];
    CHECK_EQ_INT(isect_intersect_all_batch(&s, rays, 3, NULL, offsets, all, 8), 5);
    CHECK(offsets[1] == 2 && offsets[2] == 3 && offsets[3] == 5);
    isect_mesh_destroy(mesh);
    fx_free(&m);
}

/* out = the 3x4 part of the row-major 4x4 mat applied to (p, w): w = 1 for
 * a point, 0 for a direction. */
static void affine_apply(const double mat[16], const double p[3], double w, double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = mat[4 * i] * p[0] + mat[4 * i + 1] * p[1] + mat[4 * i + 2] * p[2]
             + mat[4 * i + 3] * w;
    memcpy(out, r, sizeof r);
}

/* The world-space mesh and the same mesh through a transform agree. */
static void test_transformed(void)
{
    const double origin[3] = { 0.0, 0.0, 0.0 };
    fx_mesh m = fx_icosphere(3, origin, 1.0);
    fx_mesh l = fx_l_prism(0.7);
    fx_append(&m, &l, 1.5, 0.0, 0.0);
    fx_free(&l);
    /* Rotation about (1,2,2)/3 by 0.7 rad, scale (2, 0.5, 1.25), shift. */
    double axis[3] = { 1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0 }, a = 0.7;
    double c = cos(a), sn = sin(a), rot[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double cross = 0.0;
            if (i != j) {
                int k = 3 - i - j;
                double sign = ((i + 1) % 3 == j) ? -1.0 : 1.0;
                cross = sign * axis[k];
            }
            rot[i][j] = (i == j ? c : 0.0) + (1.0 - c) * axis[i] * axis[j] + sn * cross;
        }
    const double scale[3] = { 2.0, 0.5, 1.25 }, shift[3] = { 3.0, -1.0, 0.5 };
    double mat[16] = { 0 };
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            mat[4 * i + j] = rot[i][j] * scale[j];
        mat[4 * i + 3] = shift[i];
    }
    mat[15] = 1.0;
    isect_xform x;
    CHECK_EQ_INT(isect_xform_init(&x, mat), ISECT_OK);
    fx_mesh world;
    memset(&world, 0, sizeof world);
    fx_append(&world, &m, 0.0, 0.0, 0.0);
    for (int64_t i = 0; i < world.nv; i++)
        affine_apply(mat, m.v + 3 * i, 1.0, world.v + 3 * i);
    isect_mesh *obj = fx_build(&m), *wm = fx_build(&world);
    isect_shape so = mesh_shape(obj, &x), sw = mesh_shape(wm, NULL);
    lcg g = { 99 };
    int bad = 0, hits = 0;
    for (int i = 0; i < 2000; i++) {
        uint32_t flags;
        /* Generic rays: at a shared vertex or edge the two meshes (rounded
         * differently) may legitimately pick different faces. */
        isect_ray r = random_ray(&world, &g, 0, &flags);
        isect_opts o = ISECT_OPTS_INIT;
        o.flags = flags;
        isect_hit ho[64], hw[64];
        int no = isect_intersect(&so, &r, &o, ho, 64), nw = isect_intersect(&sw, &r, &o, hw, 64);
        if (no != nw) {
            bad++;
            continue;
        }
        hits += no;
        for (int j = 0; j < no; j++) {
            double err = fabs(ho[j].t - hw[j].t) / fmax(1.0, fabs(hw[j].t));
            double nerr = 0.0, perr = 0.0;
            for (int k = 0; k < 3; k++) {
                nerr = fmax(nerr, fabs(ho[j].normal[k] - hw[j].normal[k]));
                perr = fmax(perr, fabs(ho[j].point[k] - hw[j].point[k]));
            }
            if (err > 1e-9 || nerr > 1e-9 || perr > 1e-8 || ho[j].prim != hw[j].prim
                || ho[j].kind != hw[j].kind)
                bad++;
        }
        isect_hit first;
        if (isect_intersect_batch(&so, &r, 1, &o, &first) != (no > 0)
            || (no > 0 && !hits_equal(&first, ho, 1)))
            bad++;
    }
    CHECK_EQ_INT(bad, 0);
    CHECK(hits > 100);
    /* Containment through the transform. */
    double inside_obj[3] = { 0.1, 0.2, -0.1 }, p[3];
    for (int r = 0; r < 3; r++)
        p[r] = mat[4 * r] * inside_obj[0] + mat[4 * r + 1] * inside_obj[1]
             + mat[4 * r + 2] * inside_obj[2] + mat[4 * r + 3];
    CHECK_EQ_INT(isect_contains(&so, p), 1);
    CHECK_EQ_INT(isect_contains(&so, inside_obj), 0);
    isect_mesh_destroy(obj);
    isect_mesh_destroy(wm);
    fx_free(&m);
    fx_free(&world);
}

/* The expected batch record of ray r: the scalar call's closest (or any)
 * hit, or a miss / invalid record as isect.h describes them. */
static int64_t expected_record(const isect_shape *s, const isect_ray *r, const isect_opts *o,
                               isect_hit *want)
{
    int n = isect_intersect(s, r, o, want, 1);
    if (n > 0)
        return 1;
    memset(want, 0, sizeof *want);
    want->t = n < 0 ? NAN : INFINITY;
    want->prim = -1;
    want->kind = n < 0 ? ISECT_INVALID : ISECT_MISS;
    return 0;
}

/* isect_intersect_batch on a mesh keeps several traversals in flight and
 * finishes rays out of order: over long batches mixing hits, misses, empty
 * ranges and bad rays, every record must be bit for bit the scalar call's
 * (closest hit, or the any-hit the same traversal finds), for triangle and
 * polygon faces, with and without a transform. */
static void test_batch_lanes(void)
{
    enum { N = 4099 }; /* not a multiple of the lane count */
    const double origin[3] = { 0.0, 0.0, 0.0 };
    /* 81,920 triangles: above the size below which the batch traces every
     * ray at once (LANES_MIN_BYTES in mesh_query.c), so the lanes run. */
    fx_mesh m = fx_icosphere(6, origin, 1.0);
    fx_mesh l = fx_l_prism(0.7);
    fx_append(&m, &l, 1.2, 0.0, 0.0);
    fx_free(&l);
    isect_mesh *mesh = fx_build(&m);
    double lo[3], hi[3];
    mesh_bounds(&m, lo, hi);
    const double mat[16] = { 0.0, -2.0, 0.0, 1.0, 1.5, 0.0, 0.0, -0.5,
                             0.0, 0.3, 0.8, 2.0, 0.0, 0.0, 0.0, 1.0 };
    isect_xform x;
    CHECK_EQ_INT(isect_xform_init(&x, mat), ISECT_OK);
    static isect_ray rays[N];
    static isect_hit got[N], want[N];
    const uint32_t flag_sets[4] = { 0u, ISECT_ANY_HIT, ISECT_CULL_BACK,
                                    ISECT_ANY_HIT | ISECT_CULL_BACK };
    for (int transformed = 0; transformed < 2; transformed++) {
        isect_shape s = mesh_shape(mesh, transformed ? &x : NULL);
        for (int fs = 0; fs < 4; fs++) {
            lcg g = { 1000u + 10u * (uint64_t)transformed + (uint64_t)fs };
            isect_opts o = ISECT_OPTS_INIT;
            o.flags = flag_sets[fs];
            isect_ray obj_prev;
            for (int i = 0; i < N; i++) {
                uint32_t ignored;
                rays[i] = random_ray_in(&m, lo, hi, &g, 1, &ignored);
                /* Runs of coherent rays (the batch traces a ray that closely
                 * follows the one before at once, the others in lanes):
                 * every other run of 300 turns the previous object-space
                 * ray by about 1e-4, keeping this ray's range. */
                if ((i / 300) % 2 == 1 && i % 300 != 0) {
                    isect_ray turned = obj_prev;
                    for (int k = 0; k < 3; k++)
                        turned.dir[k] += 1e-4 * lcg_uniform(&g);
                    turned.tmin = rays[i].tmin;
                    turned.tmax = rays[i].tmax;
                    rays[i] = turned;
                }
                obj_prev = rays[i];
                if (transformed) { /* the object-space ray taken to world space */
                    affine_apply(mat, rays[i].org, 1.0, rays[i].org);
                    affine_apply(mat, rays[i].dir, 0.0, rays[i].dir);
                }
                switch (i % 97) {
                case 5: rays[i].org[1] = NAN; break;         /* bad: ISECT_INVALID */
                case 17: memset(rays[i].dir, 0, sizeof rays[i].dir); break;
                case 29: rays[i].tmin = 2.0; rays[i].tmax = 1.0; break; /* empty range */
                case 41: rays[i].tmax = INFINITY; rays[i].tmin = -INFINITY; break;
                default: break;
                }
            }
            int64_t want_hits = 0;
            for (int i = 0; i < N; i++)
                want_hits += expected_record(&s, &rays[i], &o, &want[i]);
            memset(got, 0xA5, sizeof got);
            int64_t hits = isect_intersect_batch(&s, rays, N, &o, got);
            int bad = 0, invalid = 0;
            for (int i = 0; i < N; i++) {
                bad += !hits_equal(&got[i], &want[i], 1);
                invalid += got[i].kind == ISECT_INVALID;
            }
            CHECK_EQ_INT(hits, want_hits);
            CHECK_EQ_INT(bad, 0);
            CHECK(invalid >= 2 * (N / 97));
            CHECK(want_hits > N / 5 && want_hits < N - N / 10);
            /* Short batches (fewer rays than lanes) and the tail of a long
             * one go through the same code: any split gives the same. */
            for (int64_t at = 0; at < N; at += 3) {
                int64_t len = N - at < 3 ? N - at : 3;
                if (isect_intersect_batch(&s, rays + at, len, &o, got + at) < 0)
                    bad++;
            }
            for (int i = 0; i < N; i++)
                bad += !hits_equal(&got[i], &want[i], 1);
            CHECK_EQ_INT(bad, 0);
        }
    }
    isect_mesh_destroy(mesh);
    fx_free(&m);
}

/* --------------------------------------------------------- containment */

static void test_contains_icosphere(void)
{
    const double c[3] = { 0.1, -0.2, 0.3 };
    const double radius = 1.5;
    fx_mesh m = fx_icosphere(4, c, radius);
    isect_mesh *mesh = fx_build(&m);
    isect_shape s = mesh_shape(mesh, NULL);
    /* The polyhedron lies between its inscribed sphere (> 0.998 r at this
     * level) and the sphere; test points clear of that shell. */
    lcg g = { 5 };
    enum { N = 20000 };
    static double pts[3 * N];
    static uint8_t in[N];
    int n = 0, wrong = 0, inside = 0;
    while (n < N) {
        double p[3], d2 = 0.0;
        for (int k = 0; k < 3; k++) {
            p[k] = c[k] + 2.0 * radius * lcg_uniform(&g);
            d2 += (p[k] - c[k]) * (p[k] - c[k]);
        }
        double d = sqrt(d2);
        if (d > 0.99 * radius && d < 1.01 * radius)
            continue;
        int want = d < radius;
        int got = isect_contains(&s, p);
        wrong += got != want;
        inside += want;
        memcpy(pts + 3 * n, p, sizeof p);
        n++;
    }
    CHECK_EQ_INT(wrong, 0);
    CHECK(inside > 1000);
    CHECK_EQ_INT(isect_contains_batch(&s, pts, N, in), inside);
    int differ = 0;
    for (int i = 0; i < N; i++)
        differ += in[i] != isect_contains(&s, pts + 3 * i);
    CHECK_EQ_INT(differ, 0);
    /* Every vertex and edge midpoint is on the surface: inside. */
    int on = 0;
    for (int64_t i = 0; i < m.nv; i++)
        on += isect_contains(&s, m.v + 3 * i) == 1;
    CHECK_EQ_INT(on, m.nv);
    double bad[3] = { 0.0, NAN, 0.0 };
    CHECK_EQ_INT(isect_contains(&s, bad), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_contains(&s, NULL), ISECT_E_ARG);
    isect_mesh_destroy(mesh);
    fx_free(&m);
}

/* Points of the closed set: on faces, edges and vertices of the cube,
 * the L-prism (concave caps) and the genus-2 block are inside; just off
 * the surface they are what they should be. */
static void test_contains_boundary(void)
{
    for (int split = 0; split < 2; split++) {
        fx_mesh m = fx_cube(split);
        isect_mesh *mesh = fx_build(&m);
        isect_shape s = mesh_shape(mesh, NULL);
        int wrong = 0;
        const double v[3] = { 0.0, 0.5, 1.0 };
        const double d = 0x1p-40;
        for (int i = 0; i < 27; i++) {
            double p[3] = { v[i % 3], v[(i / 3) % 3], v[i / 9] };
            wrong += isect_contains(&s, p) != 1;
            for (int k = 0; k < 3; k++) {
                if (p[k] == 0.5)
                    continue;
                double q[3] = { p[0], p[1], p[2] };
                q[k] += p[k] == 0.0 ? -d : d;
                wrong += isect_contains(&s, q) != 0;
                /* Moved inward: inside, or still on another face. */
                q[k] = p[k] + (p[k] == 0.0 ? d : -d);
                wrong += isect_contains(&s, q) != 1;
            }
        }
        CHECK_EQ_INT(wrong, 0);
        isect_mesh_destroy(mesh);
        fx_free(&m);
    }

    fx_mesh l = fx_l_prism(1.0);
    isect_mesh *mesh = fx_build(&l);
    isect_shape s = mesh_shape(mesh, NULL);
    const double in_l[][3] = { { 0.5, 0.5, 0.5 }, { 1.5, 0.5, 0.5 }, { 0.5, 1.5, 0.5 },
                               { 0.5, 1.5, 0.0 }, { 1.0, 1.0, 1.0 }, { 1.5, 1.0, 0.5 },
                               { 2.0, 0.0, 0.0 }, { 1.0, 1.5, 1.0 }, { 0.5, 0.5, 1.0 } };
    const double out_l[][3] = { { 1.5, 1.5, 0.5 }, { 1.5, 1.5, 0.0 }, { 1.5, 1.5, 1.0 },
                                { 2.5, 0.5, 0.5 }, { 0.5, 0.5, 1.5 }, { 1.0, 2.5, 0.0 },
                                { 1.25, 1.25, 1.0 }, { 2.0, 2.0, 0.0 } };
    int wrong = 0;
    for (size_t i = 0; i < sizeof in_l / sizeof in_l[0]; i++)
        wrong += isect_contains(&s, in_l[i]) != 1;
    for (size_t i = 0; i < sizeof out_l / sizeof out_l[0]; i++)
        wrong += isect_contains(&s, out_l[i]) != 0;
    CHECK_EQ_INT(wrong, 0);
    isect_mesh_destroy(mesh);
    fx_free(&l);

    for (int split = 0; split < 2; split++) {
        fx_mesh g2 = fx_genus2(split);
        mesh = fx_build(&g2);
        s = mesh_shape(mesh, NULL);
        wrong = 0;
        /* Cell centres: holes at (1,1) and (3,1). */
        for (int y = 0; y < 3; y++)
            for (int x = 0; x < 5; x++) {
                double p[3] = { x + 0.5, y + 0.5, 0.5 };
                int want = !(y == 1 && (x == 1 || x == 3));
                wrong += isect_contains(&s, p) != want;
                p[2] = 0.0; /* on the bottom face, or in a hole's opening */
                wrong += isect_contains(&s, p) != want;
            }
        double rim[3] = { 1.0, 1.5, 0.5 }; /* on a hole's wall */
        wrong += isect_contains(&s, rim) != 1;
        CHECK_EQ_INT(wrong, 0);
        isect_mesh_destroy(mesh);
        fx_free(&g2);
    }

    /* A torus against its analytic form, clear of the tessellation error. */
    fx_mesh t = fx_torus(1.0, 0.4, 64, 32, 1);
    mesh = fx_build(&t);
    s = mesh_shape(mesh, NULL);
    lcg g = { 11 };
    wrong = 0;
    int tested = 0;
    for (int i = 0; i < 20000; i++) {
        double p[3] = { 1.5 * lcg_uniform(&g), 1.5 * lcg_uniform(&g), 0.5 * lcg_uniform(&g) };
        double rho = sqrt(p[0] * p[0] + p[1] * p[1]) - 1.0;
        double dist = sqrt(rho * rho + p[2] * p[2]);
        if (fabs(dist - 0.4) < 0.02)
            continue;
        tested++;
        wrong += isect_contains(&s, p) != (dist < 0.4);
    }
    CHECK_EQ_INT(wrong, 0);
    CHECK(tested > 10000);
    isect_mesh_destroy(mesh);
    fx_free(&t);

    /* An open mesh has no inside. */
    fx_mesh open = fx_cube(0);
    open.nf--;
    open.nidx = open.off[open.nf];
    mesh = fx_build(&open);
    s = mesh_shape(mesh, NULL);
    double p[3] = { 0.5, 0.5, 0.5 };
    uint8_t flag;
    CHECK_EQ_INT(isect_contains(&s, p), ISECT_E_ARG);
    CHECK_EQ_INT(isect_contains_batch(&s, p, 1, &flag), ISECT_E_ARG);
    isect_mesh_destroy(mesh);
    fx_free(&open);
}

/* Containment equals the parity of the hits of any ray from the point (the
 * exactly-once guarantee makes the count's parity direction-free), for
 * triangles, non-planar quads and a rotated concave prism (its faces are
 * no longer exactly planar); also for points at the vertices (on the
 * surface: inside). */
static void test_contains_vs_rays(void)
{
    const double c[3] = { 0.1, 0.2, 0.3 };
    fx_mesh meshes[4];
    meshes[0] = fx_icosphere(3, c, 1.0);
    meshes[1] = fx_torus(1.0, 0.4, 20, 10, 0);
    meshes[2] = fx_l_prism(0.75);
    meshes[3] = fx_genus2(1);
    /* Rotate the prism about (2, -1, 2)/3 by 1 radian. */
    {
        double axis[3] = { 2.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0 }, co = cos(1.0), si = sin(1.0);
        for (int64_t i = 0; i < meshes[2].nv; i++) {
            double *v = meshes[2].v + 3 * i, r[3];
            double dot = axis[0] * v[0] + axis[1] * v[1] + axis[2] * v[2];
            double cr[3] = { axis[1] * v[2] - axis[2] * v[1], axis[2] * v[0] - axis[0] * v[2],
                             axis[0] * v[1] - axis[1] * v[0] };
            for (int k = 0; k < 3; k++)
                r[k] = v[k] * co + cr[k] * si + axis[k] * dot * (1.0 - co);
            memcpy(v, r, sizeof r);
        }
    }
    lcg g = { 23 };
    for (int mi = 0; mi < 4; mi++) {
        const fx_mesh *m = &meshes[mi];
        isect_mesh *mesh = fx_build(m);
        isect_shape s = mesh_shape(mesh, NULL);
        double lo[3], hi[3];
        for (int k = 0; k < 3; k++)
            lo[k] = hi[k] = m->v[k];
        for (int64_t i = 1; i < m->nv; i++)
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], m->v[3 * i + k]);
                hi[k] = fmax(hi[k], m->v[3 * i + k]);
            }
        int wrong = 0, inside = 0, on_vertex = 0;
        for (int i = 0; i < 4000; i++) {
            isect_ray r;
            for (int k = 0; k < 3; k++) {
                r.org[k] = lo[k] + (hi[k] - lo[k]) * 0.5 * (lcg_uniform(&g) + 1.0);
                r.dir[k] = lcg_uniform(&g);
            }
            r.tmin = 0.0;
            r.tmax = INFINITY;
            int in = isect_contains(&s, r.org);
            int hits = isect_intersect(&s, &r, NULL, NULL, 0);
            wrong += in != (hits & 1);
            inside += in == 1;
        }
        for (int64_t i = 0; i < m->nv; i++)
            on_vertex += isect_contains(&s, m->v + 3 * i) == 1;
        CHECK_EQ_INT(wrong, 0);
        CHECK(inside > 100);
        CHECK_EQ_INT(on_vertex, m->nv);
        isect_mesh_destroy(mesh);
    }
    for (int mi = 0; mi < 4; mi++)
        fx_free(&meshes[mi]);
}

/* --------------------------------------------------------------- report */

static isect_mesh_report report_of(const fx_mesh *m)
{
    isect_mesh *mesh = fx_build(m);
    isect_mesh_report r;
    memset(&r, 0xff, sizeof r);
    CHECK_EQ_INT(isect_mesh_check(mesh, &r), ISECT_OK);
    isect_mesh_destroy(mesh);
    return r;
}

static void test_report(void)
{
    for (int split = 0; split < 2; split++) {
        fx_mesh m = fx_cube(split);
        isect_mesh_report r = report_of(&m);
        CHECK_EQ_INT(r.vertices, 8);
        CHECK_EQ_INT(r.edges, split ? 18 : 12);
        CHECK_EQ_INT(r.faces, split ? 12 : 6);
        CHECK_EQ_INT(r.euler_characteristic, 2);
        CHECK_EQ_INT(r.genus, 0);
        CHECK_EQ_INT(r.components, 1);
        CHECK_EQ_INT(r.boundary_edges, 0);
        CHECK_EQ_INT(r.nonmanifold_edges, 0);
        CHECK_EQ_INT(r.misoriented_edges, 0);
        CHECK_EQ_INT(r.degenerate_faces, 0);
        CHECK(r.closed == 1 && r.oriented == 1);
        CHECK_NEAR(r.volume, 1.0, 1e-15);
        CHECK_NEAR(r.area, 6.0, 1e-15);
        CHECK(r.reserved[0] == 0 && r.reserved[1] == 0 && r.reserved[2] == 0);
        fx_free(&m);
    }
    /* Torus: chi = 0, genus 1; volume and area near 2 pi^2 R r^2, 4 pi^2 R r. */
    fx_mesh t = fx_torus(2.0, 0.5, 96, 48, 1);
    isect_mesh_report r = report_of(&t);
    CHECK_EQ_INT(r.euler_characteristic, 0);
    CHECK_EQ_INT(r.genus, 1);
    CHECK_EQ_INT(r.vertices, 96 * 48);
    CHECK_EQ_INT(r.edges, 3 * 96 * 48);
    CHECK(r.closed == 1 && r.oriented == 1);
    const double pi = 3.141592653589793;
    CHECK(fabs(r.volume - 2.0 * pi * pi * 2.0 * 0.25) < 0.01 * r.volume);
    CHECK(fabs(r.area - 4.0 * pi * pi * 2.0 * 0.5) < 0.01 * r.area);
    fx_free(&t);
    t = fx_torus(2.0, 0.5, 12, 6, 0);
    r = report_of(&t);
    CHECK_EQ_INT(r.euler_characteristic, 0);
    CHECK_EQ_INT(r.genus, 1);
    fx_free(&t);
    /* Genus 2 (quads and triangles): chi = -2; volume 13, area 2*13 + 16 + 8. */
    for (int split = 0; split < 2; split++) {
        fx_mesh g2 = fx_genus2(split);
        r = report_of(&g2);
        CHECK_EQ_INT(r.euler_characteristic, -2);
        CHECK_EQ_INT(r.genus, 2);
        CHECK_EQ_INT(r.components, 1);
        CHECK_NEAR(r.volume, 13.0, 1e-14);
        CHECK_NEAR(r.area, 50.0, 1e-14);
        fx_free(&g2);
    }
    /* L-prism: concave caps; volume 3 h, area 2*3 + 8 h. */
    fx_mesh l = fx_l_prism(0.5);
    r = report_of(&l);
    CHECK_EQ_INT(r.euler_characteristic, 2);
    CHECK_EQ_INT(r.genus, 0);
    CHECK_NEAR(r.volume, 1.5, 1e-15);
    CHECK_NEAR(r.area, 10.0, 1e-15);
    fx_free(&l);
    /* A cube with a face removed: 4 boundary edges, not closed. */
    fx_mesh open = fx_cube(0);
    open.nf--;
    open.nidx = open.off[open.nf];
    r = report_of(&open);
    CHECK_EQ_INT(r.boundary_edges, 4);
    CHECK_EQ_INT(r.faces, 5);
    CHECK_EQ_INT(r.euler_characteristic, 1);
    CHECK(r.closed == 0 && r.oriented == 1);
    CHECK_EQ_INT(r.genus, -1);
    fx_free(&open);
    /* A flipped face: its four edges are misoriented. */
    fx_mesh flip = fx_cube(0);
    int32_t *q = flip.idx + flip.off[2];
    int32_t tmp = q[1];
    q[1] = q[3];
    q[3] = tmp;
    r = report_of(&flip);
    CHECK_EQ_INT(r.misoriented_edges, 4);
    CHECK(r.closed == 1 && r.oriented == 0);
    CHECK_EQ_INT(r.genus, -1);
    CHECK(fabs(r.volume - 1.0) > 0.1);
    fx_free(&flip);
    /* Two cubes: two components, chi 4, genus 0; a shared face: non-manifold. */
    fx_mesh two = fx_cube(0), other = fx_cube(0);
    fx_append(&two, &other, 3.0, 0.0, 0.0);
    r = report_of(&two);
    CHECK_EQ_INT(r.components, 2);
    CHECK_EQ_INT(r.euler_characteristic, 4);
    CHECK_EQ_INT(r.genus, 0);
    CHECK_NEAR(r.volume, 2.0, 1e-15);
    fx_free(&two);
    fx_mesh fin = fx_cube(0);
    int32_t extra[4] = { fin.idx[0], fin.idx[1], fin.idx[2], fin.idx[3] };
    fx_face(&fin, 4, extra); /* the first face again, reversed below */
    int32_t *e = fin.idx + fin.off[6];
    tmp = e[1];
    e[1] = e[3];
    e[3] = tmp;
    r = report_of(&fin);
    CHECK_EQ_INT(r.nonmanifold_edges, 4);
    CHECK(r.closed == 0);
    fx_free(&fin);
    fx_free(&other);
    /* An icosphere: chi 2, area and volume close to the sphere's. */
    const double c[3] = { 5.0, 5.0, 5.0 };
    fx_mesh ico = fx_icosphere(4, c, 1.0);
    r = report_of(&ico);
    CHECK_EQ_INT(r.euler_characteristic, 2);
    CHECK_EQ_INT(r.faces, 5120);
    CHECK_EQ_INT(r.edges, 7680);
    CHECK(fabs(r.volume - 4.0 / 3.0 * pi) < 0.01 && fabs(r.area - 4.0 * pi) < 0.02);
    fx_free(&ico);
}

/* Degenerate faces are kept, counted, and never hit. */
static void test_degenerate(void)
{
    fx_mesh m = fx_cube(0);
    int32_t a = fx_vertex(&m, 0.25, 0.25, 0.25), b = fx_vertex(&m, 0.5, 0.5, 0.5),
            c = fx_vertex(&m, 0.75, 0.75, 0.75);
    fx_tri(&m, a, b, c);              /* collinear: zero area */
    fx_tri(&m, a, a, c);              /* a repeated vertex */
    int32_t line[4] = { a, b, c, b }; /* a polygon folded onto a line */
    fx_face(&m, 4, line);
    isect_mesh_report r = report_of(&m);
    CHECK_EQ_INT(r.degenerate_faces, 3);
    CHECK_NEAR(r.area, 6.0, 1e-15);
    isect_mesh *mesh = fx_build(&m);
    isect_shape s = mesh_shape(mesh, NULL);
    int hit_degenerate = 0;
    lcg g = { 17 };
    for (int i = 0; i < 2000; i++) {
        const double *target = m.v + 3 * (8 + i % 3);
        isect_ray ray;
        for (int k = 0; k < 3; k++) {
            ray.org[k] = target[k] + 3.0 * lcg_uniform(&g);
            ray.dir[k] = target[k] - ray.org[k];
        }
        ray.tmin = -INFINITY;
        ray.tmax = INFINITY;
        isect_hit h[16];
        int n = isect_intersect(&s, &ray, NULL, h, 16);
        for (int j = 0; j < n; j++)
            hit_degenerate += h[j].prim >= 6;
    }
    CHECK_EQ_INT(hit_degenerate, 0);
    isect_mesh_destroy(mesh);
    fx_free(&m);
}

/* isect_mesh_check's volume and area at extreme scales (issue 13: NaN
 * volume from ~1e103, NaN area from ~1e154, where products of coordinates
 * overflowed and inf - inf followed): the corner tetrahedron of side s has
 * volume s^3/6 and area s^2 (3 + sqrt 3)/2; each is finite and within
 * 1e-14 when the true value is in the double range, +-inf beyond it
 * (isect.h), and never NaN. Also far from the origin and inside out. */
static void test_report_extreme_scale(void)
{
    static const double sides[] = { 1e103, 1e-103, 1e153, 1e154, 1e-154, 1e300, 0x1p-600, 1.0 };
    static const int32_t tet[12] = { 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3 };
    for (size_t i = 0; i < sizeof sides / sizeof sides[0]; i++) {
        for (int variant = 0; variant < 3; variant++) {
            double s = sides[i], shift = variant == 1 ? 3.0 * s : 0.0;
            double v[12] = { 0, 0, 0, s, 0, 0, 0, s, 0, 0, 0, s };
            for (int k = 0; k < 12; k++)
                v[k] += shift;
            int32_t idx[12];
            memcpy(idx, tet, sizeof idx);
            if (variant == 2) /* inside out: negative volume */
                for (int f = 0; f < 4; f++) {
                    int32_t t = idx[3 * f + 1];
                    idx[3 * f + 1] = idx[3 * f + 2];
                    idx[3 * f + 2] = t;
                }
            isect_mesh *mesh = NULL;
            CHECK_EQ_INT(isect_mesh_create(v, 4, idx, NULL, 4, &mesh), ISECT_OK);
            isect_mesh_report r;
            CHECK_EQ_INT(isect_mesh_check(mesh, &r), ISECT_OK);
            /* The true values' binary exponents decide the expectation:
             * beyond 2^1024 inf, below 2^-1020 (subnormal) only small, else
             * the value itself (each formula's roundings: a few ulp). */
            double sign = variant == 2 ? -1.0 : 1.0, k = 0.5 * (3.0 + sqrt(3.0));
            double l3 = 3.0 * log2(s) - log2(6.0), l2 = 2.0 * log2(s) + log2(k);
            CHECK(!isnan(r.volume) && !isnan(r.area));
            if (l3 >= 1024.0)
                CHECK(r.volume == sign * INFINITY);
            else if (l3 < -1020.0)
                CHECK(fabs(r.volume) <= 0x1p-1000);
            else
                CHECK_NEAR(r.volume / (s / 6.0 * s * s), sign, 1e-14);
            if (l2 >= 1024.0)
                CHECK(r.area == INFINITY);
            else if (l2 < -1020.0)
                CHECK(r.area <= 0x1p-1000);
            else
                CHECK_NEAR(r.area / (s * (s * k)), 1.0, 1e-14);
            isect_mesh_destroy(mesh);
        }
    }
}

int main(void)
{
    test_create_destroy();
    test_bad_input();
    test_queries();
    test_cube_exact();
    test_transformed();
    test_batch_lanes();
    test_contains_icosphere();
    test_contains_boundary();
    test_contains_vs_rays();
    test_report();
    test_degenerate();
    test_report_extreme_scale();
    return check_summary();
}
