/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_degenerate_mesh.c — exactly-once on closed meshes with the
 * degeneracies real data has: the parity of the hits of every ray in
 * [0, inf) must equal the exact containment of its origin, and the whole
 * line must cross an even number of times, on meshes with
 *
 *   - midpoint-split edges: a face's edge a-b replaced by a-m-b (the face
 *     fanned into triangles, or given the collinear run as a polygon) and
 *     the zero-area face (a, b, m) — or, with quarter points, the collinear
 *     polygon (a, b, m3, m2, m1) — closing the T-junction (issue 13's cube
 *     with face (3,0,4), v3 the midpoint of v0-v4);
 *   - edge collapses: a vertex split into two coincident vertices b, b'
 *     (distinct indices, same coordinates) along two of its edges, the gaps
 *     closed by the zero-area triangles (a, b', b) and (c, b, b');
 *   - repeated vertex indices: a face's corner doubled ((a, b, b, c): a
 *     triangle becomes a 4-index polygon), and zero-area flaps (a, a, b),
 *     (a, b, a), (a, b, c, b), (a, a, a) between vertices of the solid;
 *   - faces degenerate only after rounding: midpoints and the split
 *     vertex's twin computed or moved by an ulp on rotated, non-dyadic
 *     meshes (slivers of either orientation, a hair of area);
 *   - duplicated vertices: faces given their own copies of their vertices
 *     (geometrically closed, combinatorially open);
 *   - huge and tiny coordinates: the whole mesh scaled by 2^500 (~3e150),
 *     2^-500 (~3e-151), 1.2345e150 or 0.98765e-150 (non-dyadic: rounded),
 *     and translated; and one axis stretched by 2^+-300 or 2^+-540, so that
 *     faces across it are far smaller than their coordinates (a needle's
 *     caps: extent 1 at 2^540, whose products of coordinate differences
 *     underflowed in the crossing arithmetic before the face vectors were
 *     normalised: one hit from inside).
 *
 * Rays from random origins (in the expanded bounding box, near a vertex or
 * edge midpoint, or a few ulps from one) are aimed at vertices and edge
 * midpoints, with eps in {0, 1e-12, 1e-6, 0.25} (faces ignore eps). On
 * meshes with exactly planar faces (the integer-grid solids, scaled by
 * powers of two) origins are dyadic, so the ray passes exactly through the
 * target. Where the library reports the mesh closed, isect_contains must
 * agree with the reference too.
 *
 * The reference (oracle_inside) is independent of the code under test: it
 * shoots its own ray from the origin in a random direction r (never the
 * tested ray's), splits every face into the fan from its first vertex
 * (the library tests polygons whole, by even-odd winding in the sheared
 * frame, with t from the Newell plane), and decides with exact_dyadic.h's
 * big-integer arithmetic (the library uses floating-point expansions)
 * only three things per fan triangle: the signs of r . (A x B) over its
 * edges (A = a - p, ...) and of det(A, B, C). It uses no tie-breaking rule
 * at all: when a sign is zero where it matters (the line touches an edge or
 * vertex, or lies in the triangle's plane) the direction is discarded and
 * another drawn, so every counted crossing is a transversal crossing of a
 * triangle's interior, and by the Jordan-Brouwer theorem (mod 2: the
 * degree of a closed triangulated surface) the parity of crossings at t >
 * 0 is the containment of p — odd winding number; for a self-intersecting
 * surface (slivers after rounding) that is the parity the library claims.
 * A zero det with all three signs equal means p lies in a face: such
 * origins (on the surface, where the ray's hit count at t = 0 is a matter
 * of convention) are skipped and counted. Fan triangles and zero-area faces
 * need no special case: a triangle of zero area has r . n = 0, the sum of
 * its three edge signs, so they cannot agree. The signs are first
 * evaluated in double with a bound of 45 u times the sum of the absolute
 * products (the coordinates scaled by one power of two to below 1, exact),
 * and exactly wherever that bound does not decide them.
 *
 *     test_degenerate_mesh [rays [seed]]
 *                                   (default 100000, as the plain and the
 *                                    sanitized test loops run it; make test
 *                                    also runs 10^6; the long run is 10^8:
 *                                    see README, "The exactly-once rule")
 *
 * Prints the rays checked per kind of origin and the exceptions.
 */
#include "check.h"

#include <isect.h>

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "exact_dyadic.h"
#include "mesh_fixtures.h"
#include "test_random.h"

/* ------------------------------------------------------ the mesh model */

#define GEN_MAXV 16

typedef struct gface {
    int     n;
    int32_t v[GEN_MAXV];
} gface;

typedef struct gmesh {
    double  *v;
    int64_t  nv, vcap;
    gface   *f;
    int64_t  nf, fcap;
    int      exact;    /* coordinates on a dyadic grid: quarter points exact,
                          faces exactly planar */
    int      unwelded; /* some faces have their own vertex copies */
} gmesh;

static void *grow(void *p, int64_t *cap, int64_t need, size_t elem)
{
    return fx_grow(p, cap, need, elem);
}

static int32_t gm_vertex(gmesh *g, const double p[3])
{
    g->v = grow(g->v, &g->vcap, 3 * (g->nv + 1), sizeof *g->v);
    memcpy(g->v + 3 * g->nv, p, 3 * sizeof *p);
    return (int32_t)g->nv++;
}

static void gm_face(gmesh *g, int n, const int32_t *v)
{
    g->f = grow(g->f, &g->fcap, g->nf + 1, sizeof *g->f);
    g->f[g->nf].n = n;
    memcpy(g->f[g->nf].v, v, (size_t)n * sizeof *v);
    g->nf++;
}

static void gm_free(gmesh *g)
{
    free(g->v);
    free(g->f);
    memset(g, 0, sizeof *g);
}

static gmesh gm_of_fixture(fx_mesh fx, int exact)
{
    gmesh g;
    memset(&g, 0, sizeof g);
    for (int64_t i = 0; i < fx.nv; i++)
        gm_vertex(&g, fx.v + 3 * i);
    for (int64_t f = 0; f < fx.nf; f++)
        gm_face(&g, (int)(fx.off[f + 1] - fx.off[f]), fx.idx + fx.off[f]);
    g.exact = exact;
    fx_free(&fx);
    return g;
}

static int gm_all_triangles(const gmesh *g)
{
    for (int64_t f = 0; f < g->nf; f++)
        if (g->f[f].n != 3)
            return 0;
    return 1;
}

/* The faces holding the directed edge a -> b: how many, and the last one
 * (*face, with *pos the corner of a). */
static int directed_uses(const gmesh *g, int32_t a, int32_t b, int64_t *face, int *pos)
{
    int count = 0;
    for (int64_t f = 0; f < g->nf; f++) {
        const gface *F = &g->f[f];
        for (int i = 0; i < F->n; i++)
            if (F->v[i] == a && F->v[(i + 1) % F->n] == b) {
                count++;
                *face = f;
                *pos = i;
            }
    }
    return count;
}

/* 1 when some face has a - b as an edge (either direction). */
static int is_edge(const gmesh *g, int32_t a, int32_t b)
{
    int64_t f;
    int pos;
    return directed_uses(g, a, b, &f, &pos) + directed_uses(g, b, a, &f, &pos) > 0;
}

/* The occurrences of vertex b in face F (a repeated corner makes the fan
 * walk ambiguous). */
static int occurrences(const gface *F, int32_t b)
{
    int n = 0;
    for (int i = 0; i < F->n; i++)
        n += F->v[i] == b;
    return n;
}

/* ---------------------------------------------------- the degeneracies */

/* A random edge a -> b of a random face whose reverse b -> a is used by
 * exactly one face: 1 with the two faces, or 0. */
static int pick_edge(const gmesh *g, int64_t *f, int *i, int64_t *twin)
{
    for (int tries = 0; tries < 20; tries++) {
        *f = (int64_t)(rng_next() % (uint64_t)g->nf);
        const gface *F = &g->f[*f];
        *i = rng_int(0, F->n - 1);
        int32_t a = F->v[*i], b = F->v[(*i + 1) % F->n];
        int tpos;
        int64_t dummy;
        int dpos;
        if (a == b || directed_uses(g, a, b, &dummy, &dpos) != 1
            || directed_uses(g, b, a, twin, &tpos) != 1)
            continue;
        return 1;
    }
    return 0;
}

/* Split the edge a -> b of a face (and so the T-junction's zero-area
 * face): see the file comment. parts 2 (a midpoint) or 4 (quarter points,
 * exact meshes only). */
static void inject_split(gmesh *g)
{
    int64_t f, twin;
    int i;
    if (!pick_edge(g, &f, &i, &twin))
        return;
    gface F = g->f[f];
    int32_t a = F.v[i], b = F.v[(i + 1) % F.n];
    int parts = g->exact && rng_int(0, 1) ? 4 : 2;
    int32_t m[3];
    for (int k = 1; k < parts; k++) {
        double p[3];
        const double *pa = g->v + 3 * a, *pb = g->v + 3 * b;
        for (int c = 0; c < 3; c++)
            p[c] = parts == 2 ? 0.5 * (pa[c] + pb[c]) /* rounded unless exact */
                              : pa[c] + (pb[c] - pa[c]) * (0.25 * k);
        m[k - 1] = gm_vertex(g, p);
    }
    /* The face: the run inserted as a polygon (exact meshes: it stays
     * exactly planar), or a triangle fanned at its far corner. */
    if (F.n == 3 && (!g->exact || rng_int(0, 1))) {
        int32_t c = F.v[(i + 2) % 3];
        int32_t prev = a;
        for (int k = 0; k < parts - 1; k++) {
            int32_t t[3] = { prev, m[k], c };
            if (k == 0)
                memcpy(g->f[f].v, t, sizeof t);
            else
                gm_face(g, 3, t);
            prev = m[k];
        }
        int32_t t[3] = { prev, b, c };
        gm_face(g, 3, t);
    } else {
        if (!g->exact || F.n + parts - 1 > GEN_MAXV)
            return; /* (the vertices stay, unused) */
        gface G;
        G.n = 0;
        for (int k = 0; k < F.n; k++) {
            G.v[G.n++] = F.v[k];
            if (k == i)
                for (int j = 0; j < parts - 1; j++)
                    G.v[G.n++] = m[j];
        }
        g->f[f] = G;
    }
    /* The closing face a -> b -> m_last -> ... -> m_1: pairs a -> b with the
     * twin's b -> a and the run's edges with their reverses. */
    int32_t z[5];
    int n = 0;
    z[n++] = a;
    z[n++] = b;
    for (int k = parts - 2; k >= 0; k--)
        z[n++] = m[k];
    gm_face(g, n, z);
}

/* Split vertex b of a random face into b and a coincident b' over part of
 * its fan (an edge collapse, undone by index only): see the file comment. */
static void inject_vertex_split(gmesh *g)
{
    int64_t f0 = (int64_t)(rng_next() % (uint64_t)g->nf);
    const gface *F0 = &g->f[f0];
    int i = rng_int(0, F0->n - 1);
    int32_t b = F0->v[i], a = F0->v[(i + 1) % F0->n];
    enum { RING = 64 };
    int64_t ring[RING];
    int valence = 0;
    int64_t cur = f0;
    for (;;) {
        const gface *C = &g->f[cur];
        if (occurrences(C, b) != 1 || valence == RING)
            return;
        ring[valence++] = cur;
        int p = 0;
        while (C->v[p] != b)
            p++;
        int32_t x = C->v[(p + C->n - 1) % C->n]; /* x -> b in cur */
        int64_t next;
        int pos;
        if (x == b || directed_uses(g, b, x, &next, &pos) != 1)
            return;
        if (next == f0)
            break;
        cur = next;
    }
    if (valence < 2)
        return;
    int k = rng_int(1, valence - 1);
    const gface *L = &g->f[ring[k - 1]];
    int p = 0;
    while (L->v[p] != b)
        p++;
    int32_t c = L->v[(p + L->n - 1) % L->n];
    if (c == a || a == b)
        return;
    double q[3];
    memcpy(q, g->v + 3 * b, sizeof q);
    /* On a triangle mesh without exact planes: sometimes a twin one ulp
     * away (slivers degenerate only up to rounding). */
    if (!g->exact && gm_all_triangles(g) && rng_int(0, 1)) {
        int axis = rng_int(0, 2);
        q[axis] = ulps(q[axis], rng_int(0, 1) ? 1 : -1);
    }
    int32_t b2 = gm_vertex(g, q);
    for (int j = 0; j < k; j++) {
        gface *C = &g->f[ring[j]];
        for (int t = 0; t < C->n; t++)
            if (C->v[t] == b)
                C->v[t] = b2;
    }
    int32_t t1[3] = { a, b2, b }, t2[3] = { c, b, b2 };
    gm_face(g, 3, t1);
    gm_face(g, 3, t2);
}

/* A corner doubled: (a, b, c) -> (a, b, b, c). */
static void inject_repeat(gmesh *g)
{
    int64_t f = (int64_t)(rng_next() % (uint64_t)g->nf);
    gface *F = &g->f[f];
    if (F->n == GEN_MAXV)
        return;
    int i = rng_int(0, F->n - 1);
    memmove(F->v + i + 1, F->v + i, (size_t)(F->n - i) * sizeof *F->v);
    F->n++;
}

/* A zero-area flap between vertices that share no edge: its edges pair
 * with each other, so the mesh stays closed. */
static void inject_flap(gmesh *g)
{
    int32_t a = (int32_t)(rng_next() % (uint64_t)g->nv);
    int32_t b = (int32_t)(rng_next() % (uint64_t)g->nv);
    int32_t c = (int32_t)(rng_next() % (uint64_t)g->nv);
    int kind = rng_int(0, 4);
    if (kind == 4) {
        int32_t t[3] = { a, a, a };
        gm_face(g, 3, t);
        return;
    }
    if (a == b || is_edge(g, a, b))
        return;
    if (kind == 3) {
        if (c == a || c == b || is_edge(g, b, c))
            return;
        int32_t t[4] = { a, b, c, b };
        gm_face(g, 4, t);
        return;
    }
    int32_t t[3][3] = { { a, a, b }, { a, b, a }, { b, a, a } };
    gm_face(g, 3, t[kind]);
}

/* Some faces get their own copies of their vertices. */
static void unweld(gmesh *g)
{
    for (int64_t f = 0; f < g->nf; f++) {
        if (rng_int(0, 2) != 0)
            continue;
        gface *F = &g->f[f];
        for (int i = 0; i < F->n; i++) {
            double p[3];
            memcpy(p, g->v + 3 * F->v[i], sizeof p);
            F->v[i] = gm_vertex(g, p);
        }
        g->unwelded = 1;
    }
}

/* ---------------------------------------------------------- the meshes */

static void rotation(double r[9])
{
    double axis[3], ang = 3.0 * rng_unit();
    rng_dir(axis);
    fx_rotation(axis, ang, r);
}

static void gm_map(gmesh *g, const double r[9], double scale, const double shift[3])
{
    for (int64_t i = 0; i < g->nv; i++) {
        double *p = g->v + 3 * i, q[3];
        for (int k = 0; k < 3; k++)
            q[k] = r != NULL ? r[3 * k] * p[0] + r[3 * k + 1] * p[1] + r[3 * k + 2] * p[2] : p[k];
        for (int k = 0; k < 3; k++)
            p[k] = q[k] * scale + shift[k];
    }
}

enum { BASES = 9 };
static const char *const base_names[BASES] = {
    "cube (quads)", "cube (triangles)", "genus 2 (quads)", "genus 2 (triangles)",
    "L-prism (concave)", "icosphere", "torus (triangles)", "cube (rotated)",
    "genus 2 (rotated)" };

/* A mesh of the given base with random degeneracies and coordinates;
 * *scale_kind: which scaling (0: none, 1: 2^500, 2: 2^-500, 3: 1.2345e150,
 * 4: 0.98765e-150). */
static gmesh make_mesh(int base, int *scale_kind)
{
    gmesh g;
    double r[9];
    const double centre[3] = { 0.0, 0.0, 0.0 };
    switch (base) {
    case 0: g = gm_of_fixture(fx_cube(0), 1); break;
    case 1: g = gm_of_fixture(fx_cube(1), 1); break;
    case 2: g = gm_of_fixture(fx_genus2(0), 1); break;
    case 3: g = gm_of_fixture(fx_genus2(1), 1); break;
    case 4: g = gm_of_fixture(fx_l_prism(1.0), 1); break;
    case 5: g = gm_of_fixture(fx_icosphere(1, centre, 1.0), 0); break;
    case 6: g = gm_of_fixture(fx_torus(1.0, 0.4, 12, 8, 1), 0); break;
    case 7: g = gm_of_fixture(fx_cube(1), 0); break;
    default: g = gm_of_fixture(fx_genus2(1), 0); break;
    }
    if (base >= 7) {
        rotation(r);
        const double none[3] = { 0.0, 0.0, 0.0 };
        gm_map(&g, r, 1.0, none);
    }
    int rounds = rng_int(1, 6);
    for (int j = 0; j < rounds; j++) {
        switch (rng_int(0, 4)) {
        case 0:
        case 1: inject_split(&g); break;
        case 2: inject_vertex_split(&g); break;
        case 3: inject_repeat(&g); break;
        default: inject_flap(&g); break;
        }
    }
    if (rng_int(0, 7) == 0)
        unweld(&g);
    /* Coordinates: as built, 2^500 or 2^-500 (exact), or for meshes
     * without exact planes a non-dyadic huge or tiny factor (rounded: the
     * faces are triangles, or polygons with three distinct corners, planar
     * whatever the rounding); then a shift (dyadic on exact meshes). */
    static const double pow2[3] = { 1.0, 0x1p500, 0x1p-500 };
    static const double odd[2] = { 1.2345e150, 0.98765e-150 };
    *scale_kind = rng_int(0, g.exact ? 2 : 4);
    double scale = *scale_kind < 3 ? pow2[*scale_kind] : odd[*scale_kind - 3];
    double shift[3];
    for (int k = 0; k < 3; k++)
        shift[k] = g.exact ? rng_int(-8, 8) * 0.25 * scale : rng_unit() * scale;
    gm_map(&g, NULL, scale, shift);
    /* Sometimes one axis stretched by 2^+-300 or 2^+-540 (exact: planes stay
     * planes): faces across that axis are then far smaller than the
     * coordinates (a needle's caps: extent 1 at 2^540). */
    /* (Only unscaled meshes, to stay in range; only exact ones: a rounded
     * torus stretched by 2^540 has edge vectors whose own components span
     * 2^540, beyond the range where the crossing arithmetic is exact —
     * README, "The exactly-once rule".) */
    if (g.exact && *scale_kind == 0 && rng_int(0, 1) == 0) {
        static const int stretch[4] = { 300, 540, -300, -540 };
        int axis = rng_int(0, 2), k = stretch[rng_int(0, 3)];
        for (int64_t i = 0; i < g.nv; i++)
            g.v[3 * i + axis] = ldexp(g.v[3 * i + axis], k);
        *scale_kind += 10 * (1 + (k < 0) + 2 * (abs(k) > 300));
    }
    return g;
}

static isect_mesh *gm_build(const gmesh *g)
{
    fx_mesh fx;
    memset(&fx, 0, sizeof fx);
    for (int64_t i = 0; i < g->nv; i++)
        fx_vertex(&fx, g->v[3 * i], g->v[3 * i + 1], g->v[3 * i + 2]);
    for (int64_t f = 0; f < g->nf; f++)
        fx_face(&fx, g->f[f].n, g->f[f].v);
    isect_mesh *m = fx_build(&fx);
    fx_free(&fx);
    return m;
}

/* ---------------------------------------------------------- the oracle */

/* The fan triangles of the mesh, coordinates scaled by one power of two. */
typedef struct oracle {
    double  *tri;   /* [count][3][3] */
    int64_t  count;
    int      shift; /* the scaling exponent applied */
} oracle;

static void oracle_make(const gmesh *g, oracle *o)
{
    double big = 0.0;
    for (int64_t i = 0; i < 3 * g->nv; i++)
        big = fmax(big, fabs(g->v[i]));
    /* 2^shift * (every coordinate and origin) below 1/16: differences and
     * sums of three products stay below 1. Origins lie within 4x the
     * mesh's coordinates (checked in oracle_inside). */
    o->shift = -(ilogb(big) + 7);
    int64_t n = 0;
    for (int64_t f = 0; f < g->nf; f++)
        n += g->f[f].n - 2;
    o->tri = malloc((size_t)(9 * (n > 0 ? n : 1)) * sizeof *o->tri);
    o->count = 0;
    for (int64_t f = 0; f < g->nf; f++) {
        const gface *F = &g->f[f];
        for (int i = 1; i + 1 < F->n; i++) {
            const int32_t c[3] = { F->v[0], F->v[i], F->v[i + 1] };
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++) {
                    double x = g->v[3 * c[j] + k], s = ldexp(x, o->shift);
                    if (ldexp(s, -o->shift) != x) {
                        fprintf(stderr, "oracle: inexact scaling of %.17g\n", x);
                        exit(2);
                    }
                    o->tri[9 * o->count + 3 * j + k] = s;
                }
            o->count++;
        }
    }
}

/* sign(r . (A x B)) exactly, A = a - p, B = b - p. */
static int exact_edge_sign(const double r[3], const double a[3], const double b[3],
                           const double p[3])
{
    exq A[3], B[3], R[3], X[3];
    ex_diff3(a, p, A);
    ex_diff3(b, p, B);
    ex_of3(r, R);
    ex_cross(A, B, X);
    return ex_sign(ex_dot(R, X));
}

/* sign(det(A, B, C)) exactly. */
static int exact_det_sign(const double a[3], const double b[3], const double c[3],
                          const double p[3])
{
    exq A[3], B[3], C[3], X[3];
    ex_diff3(a, p, A);
    ex_diff3(b, p, B);
    ex_diff3(c, p, C);
    ex_cross(B, C, X);
    return ex_sign(ex_dot(A, X));
}

/* The filter: the double value with 45 u times the sum of the absolute
 * products as its error bound (the differences, the cross and the dot
 * products each round; about 10 roundings of relative u on terms bounded
 * by that sum), floored at 2^-960 (below it products may be subnormal).
 * 0 when uncertain, else the sign. */
static int filtered(double value, double magnitude)
{
    double bound = 45.0 * DBL_EPSILON * 0.5 * magnitude + 0x1p-960;
    return value > bound ? 1 : value < -bound ? -1 : 0;
}

static int edge_sign(const double r[3], const double a[3], const double b[3], const double p[3])
{
    double A[3], B[3];
    for (int k = 0; k < 3; k++) {
        A[k] = a[k] - p[k];
        B[k] = b[k] - p[k];
    }
    double v = 0.0, mag = 0.0;
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        v += r[i] * (A[j] * B[k] - A[k] * B[j]);
        mag += fabs(r[i]) * (fabs(A[j] * B[k]) + fabs(A[k] * B[j]));
    }
    int s = filtered(v, mag);
    return s != 0 ? s : exact_edge_sign(r, a, b, p);
}

static int det_sign(const double a[3], const double b[3], const double c[3], const double p[3])
{
    double A[3], B[3], C[3];
    for (int k = 0; k < 3; k++) {
        A[k] = a[k] - p[k];
        B[k] = b[k] - p[k];
        C[k] = c[k] - p[k];
    }
    double v = 0.0, mag = 0.0;
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        v += A[i] * (B[j] * C[k] - B[k] * C[j]);
        mag += fabs(A[i]) * (fabs(B[j] * C[k]) + fabs(B[k] * C[j]));
    }
    int s = filtered(v, mag);
    return s != 0 ? s : exact_det_sign(a, b, c, p);
}

enum { OR_OUTSIDE = 0, OR_INSIDE = 1, OR_ON_SURFACE = 2, OR_UNDECIDED = 3 };

/* The containment of p: OR_INSIDE / OR_OUTSIDE, OR_ON_SURFACE, or
 * OR_UNDECIDED when every direction tried touched an edge (only for
 * origins on the surface's edges, in practice). */
static int oracle_inside(const oracle *o, const double p_in[3])
{
    double p[3];
    for (int k = 0; k < 3; k++) {
        p[k] = ldexp(p_in[k], o->shift);
        if (!(fabs(p[k]) < 0.25) || ldexp(p[k], -o->shift) != p_in[k]) {
            fprintf(stderr, "oracle: origin out of range\n");
            exit(2);
        }
    }
    for (int attempt = 0; attempt < 6; attempt++) {
        double r[3];
        rng_dir(r);
        int crossings = 0, generic = 1;
        for (int64_t t = 0; t < o->count && generic; t++) {
            const double *a = o->tri + 9 * t, *b = a + 3, *c = a + 6;
            /* Quick rejection: the box of the triangle against the ray's
             * quadrant (the ray leaves p in the signs of r). */
            int away = 0;
            for (int k = 0; k < 3 && !away; k++)
                away = (r[k] > 0.0 && a[k] < p[k] && b[k] < p[k] && c[k] < p[k])
                    || (r[k] < 0.0 && a[k] > p[k] && b[k] > p[k] && c[k] > p[k]);
            if (away)
                continue;
            int s1 = edge_sign(r, a, b, p);
            int s2 = edge_sign(r, b, c, p);
            if (s1 != 0 && s2 != 0 && s1 != s2)
                continue;
            int s3 = edge_sign(r, c, a, p);
            int pos = (s1 > 0) + (s2 > 0) + (s3 > 0), neg = (s1 < 0) + (s2 < 0) + (s3 < 0);
            if (pos > 0 && neg > 0)
                continue; /* the line misses the closed triangle */
            if (pos + neg < 3) {
                generic = 0; /* it touches an edge or vertex, or lies in the plane */
                break;
            }
            int d = det_sign(a, b, c, p);
            if (d == 0)
                return OR_ON_SURFACE; /* crossed at t = 0: p is in the face */
            /* t = det / (r . n), and r . n has the sign of the edges. */
            crossings += d == (pos == 3 ? 1 : -1);
        }
        if (generic)
            return crossings & 1;
    }
    return OR_UNDECIDED;
}

/* ------------------------------------------------------------- the test */

typedef struct tally {
    int64_t rays, inside, outside, skipped, bad, bad_line, errors, contains, bad_contains;
    int64_t meshes, closed_meshes;
} tally;

enum { ORIGIN_BOX, ORIGIN_NEAR, ORIGIN_ULPS, ORIGIN_KINDS };
static const char *const origin_names[ORIGIN_KINDS] = { "box", "near (1e-3)", "ulps" };

/* The targets: every vertex and every edge midpoint (each face edge). */
static double *targets_of(const gmesh *g, int64_t *count)
{
    int64_t n = g->nv;
    for (int64_t f = 0; f < g->nf; f++)
        n += g->f[f].n;
    double *t = malloc((size_t)(3 * n) * sizeof *t);
    memcpy(t, g->v, (size_t)(3 * g->nv) * sizeof *t);
    n = g->nv;
    for (int64_t f = 0; f < g->nf; f++) {
        const gface *F = &g->f[f];
        for (int i = 0; i < F->n; i++) {
            const double *a = g->v + 3 * F->v[i], *b = g->v + 3 * F->v[(i + 1) % F->n];
            for (int k = 0; k < 3; k++)
                t[3 * n + k] = 0.5 * a[k] + 0.5 * b[k];
            n++;
        }
    }
    *count = n;
    return t;
}

/* x rounded to a multiple of 2^e (exact meshes: dyadic origins). */
static double to_grid(double x, int e)
{
    return ldexp(nearbyint(ldexp(x, -e)), e);
}

static void run_mesh(int base, int64_t rays, tally *t, tally *per_origin)
{
    int scale_kind;
    gmesh g = make_mesh(base, &scale_kind);
    isect_mesh *mesh = gm_build(&g);
    isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, mesh, NULL };
    isect_mesh_report rep;
    CHECK_EQ_INT(isect_mesh_check(mesh, &rep), ISECT_OK);
    oracle o;
    oracle_make(&g, &o);
    int64_t ntargets;
    double *targets = targets_of(&g, &ntargets);
    double lo[3], hi[3], ext = 0.0;
    for (int k = 0; k < 3; k++) {
        lo[k] = hi[k] = g.v[k];
        for (int64_t i = 1; i < g.nv; i++) {
            lo[k] = fmin(lo[k], g.v[3 * i + k]);
            hi[k] = fmax(hi[k], g.v[3 * i + k]);
        }
        ext = fmax(ext, hi[k] - lo[k]);
    }
    /* The grid of dyadic origins: 2^-12 of the mesh's unit. */
    int grid = ilogb(ext) - 14;
    t->meshes++;
    t->closed_meshes += rep.closed == 1;
    static const double eps_values[4] = { 0.0, 1e-12, 1e-6, 0.25 };
    int64_t done = 0, skipped_here = 0;
    while (done < rays) {
        int kind = rng_int(0, ORIGIN_KINDS - 1);
        double org[3];
        const double *near = targets + 3 * (int64_t)(rng_next() % (uint64_t)ntargets);
        for (int k = 0; k < 3; k++) {
            if (kind == ORIGIN_BOX)
                org[k] = lo[k] + (hi[k] - lo[k]) * (0.5 + 0.75 * rng_unit());
            else if (kind == ORIGIN_NEAR)
                org[k] = near[k] + 1e-3 * ext * rng_unit();
            else if (fabs(near[k]) >= ldexp(ext, -30))
                org[k] = ulps(near[k], rng_int(-3, 3));
            else /* (ulps of 0 would be subnormal: a few ulps of ext) */
                org[k] = near[k] + rng_int(-3, 3) * ldexp(ext, -60);
            if (g.exact && kind != ORIGIN_ULPS)
                org[k] = to_grid(org[k], grid);
        }
        int inside = oracle_inside(&o, org);
        if (inside >= OR_ON_SURFACE) {
            t->skipped++;
            per_origin[kind].skipped++;
            if (++skipped_here > rays + 100)
                break; /* (CHECKed below: skips stay rare) */
            continue;
        }
        if (rep.closed == 1) {
            t->contains++;
            int c = isect_contains(&s, org);
            if (c != inside) {
                t->bad_contains++;
                if (t->bad_contains <= 3)
                    fprintf(stderr, "    %s: contains (%a, %a, %a) = %d, expected %d\n",
                            base_names[base], org[0], org[1], org[2], c, inside);
            }
        }
        /* Sixteen rays from this origin at random targets. */
        for (int j = 0; j < 16 && done < rays; j++) {
            const double *target = targets + 3 * (int64_t)(rng_next() % (uint64_t)ntargets);
            isect_ray r;
            for (int k = 0; k < 3; k++) {
                r.org[k] = org[k];
                r.dir[k] = target[k] - org[k];
            }
            if (r.dir[0] == 0.0 && r.dir[1] == 0.0 && r.dir[2] == 0.0)
                continue;
            done++;
            r.tmin = 0.0;
            r.tmax = INFINITY;
            isect_opts opts = ISECT_OPTS_INIT;
            opts.eps = eps_values[rng_int(0, 3)];
            int n = isect_intersect(&s, &r, &opts, NULL, 0);
            t->rays++;
            per_origin[kind].rays++;
            if (inside)
                t->inside++;
            else
                t->outside++;
            if (n < 0) {
                t->errors++;
                continue;
            }
            if (n % 2 != inside) {
                t->bad++;
                per_origin[kind].bad++;
                if (t->bad <= 5)
                    fprintf(stderr,
                            "    %s (scale %d, %s origin, eps %g): org (%a, %a, %a) dir (%a, "
                            "%a, %a): %d hits, origin %s\n",
                            base_names[base], scale_kind, origin_names[kind], opts.eps,
                            r.org[0], r.org[1], r.org[2], r.dir[0], r.dir[1], r.dir[2], n,
                            inside ? "inside" : "outside");
            }
            if (j % 8 == 0) {
                r.tmin = -INFINITY;
                n = isect_intersect(&s, &r, &opts, NULL, 0);
                if (n < 0 || n % 2 != 0)
                    t->bad_line++;
            }
        }
    }
    free(targets);
    free(o.tri);
    isect_mesh_destroy(mesh);
    gm_free(&g);
}

/* Issue 13, item 2: a triangle at z = DBL_MAX and a ray from z = -DBL_MAX
 * (the old triangle test negated ilogb(NaN) = INT_MIN there: UBSan stops
 * the sanitized build of this test on a284350). Every call must return a
 * status >= 0; the triangle as large as its height (a = (-M/4, -M/4, M),
 * b = (M, 0, M), c = (0, M, M)) is crossed at t = 2 by dir (0, 0, M) —
 * alone, as a polygon and as a mesh face. (The unit triangle at
 * that height is not asserted on: its record is out of the range where the
 * crossing arithmetic is exact, see README "The exactly-once rule".) */
static void test_far_triangle(void)
{
    const double M = DBL_MAX;
    const double unit[9] = { 0, 0, M, 1, 0, M, 0, 1, M };
    const double wide[9] = { -M / 4, -M / 4, M, M, 0, M, 0, M, M };
    const double dirs[5][3] = { { 0, 0, 1 }, { 0.25, 0.25, 1 }, { 1e-300, 0, 1 }, { 0, 0, M },
                                { 1, 1, 1e-300 } };
    const int32_t idx[3] = { 0, 1, 2 };
    for (int w = 0; w < 2; w++) {
        const double *v = w ? wide : unit;
        isect_mesh *mesh = NULL;
        CHECK_EQ_INT(isect_mesh_create(v, 3, idx, NULL, 1, &mesh), ISECT_OK);
        isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, mesh, NULL };
        for (int i = 0; i < 5; i++) {
            isect_ray r = { { 0.25, 0.25, -M }, { dirs[i][0], dirs[i][1], dirs[i][2] }, 0.0,
                            INFINITY };
            isect_hit h[2];
            int n1 = isect_ray_triangle(&r, v, v + 3, v + 6, NULL, h, 2);
            int n2 = isect_ray_polygon(&r, v, 3, ISECT_EVEN_ODD, NULL, h, 2);
            int n3 = isect_intersect(&s, &r, NULL, h, 2);
            CHECK(n1 >= 0 && n1 <= 1 && n2 == n1 && n3 == n1);
            if (w == 1 && i == 3) {
                CHECK_EQ_INT(n3, 1);
                CHECK(n3 == 1 && h[0].t == 2.0);
            }
        }
        isect_mesh_destroy(mesh);
    }
}

int main(int argc, char **argv)
{
    int64_t total = 100000;
    if (argc > 1)
        total = atoll(argv[1]);
    if (total < 1) {
        fprintf(stderr, "usage: test_degenerate_mesh [rays [seed]]\n");
        return 2;
    }
    test_far_triangle();
    /* A second argument seeds other meshes and rays (the long run may be
     * split over seeds). */
    rng_seed(argc > 2 ? (uint64_t)strtoull(argv[2], NULL, 0) : 0xDE6E4E7A7EULL);
    tally t, per_origin[ORIGIN_KINDS];
    memset(&t, 0, sizeof t);
    memset(per_origin, 0, sizeof per_origin);
    /* 2,000 rays per mesh: fresh degeneracies every few thousand rays. */
    const int64_t per_mesh = 2000;
    for (int64_t done = 0, i = 0; done < total; i++) {
        int64_t share = total - done < per_mesh ? total - done : per_mesh;
        run_mesh((int)(i % BASES), share, &t, per_origin);
        done += share;
    }
    printf("degenerate meshes: %lld meshes (%lld closed by the report), %lld rays "
           "(%lld from inside, %lld from outside), %lld origins on the surface skipped\n",
           (long long)t.meshes, (long long)t.closed_meshes, (long long)t.rays,
           (long long)t.inside, (long long)t.outside, (long long)t.skipped);
    for (int k = 0; k < ORIGIN_KINDS; k++)
        printf("  origins %-12s %10lld rays, %lld exceptions, %lld skipped\n", origin_names[k],
               (long long)per_origin[k].rays, (long long)per_origin[k].bad,
               (long long)per_origin[k].skipped);
    printf("degenerate meshes: %lld parity exceptions, %lld whole-line exceptions, %lld "
           "errors; contains %lld checked, %lld exceptions\n",
           (long long)t.bad, (long long)t.bad_line, (long long)t.errors, (long long)t.contains,
           (long long)t.bad_contains);
    CHECK_EQ_INT(t.bad, 0);
    CHECK_EQ_INT(t.bad_line, 0);
    CHECK_EQ_INT(t.errors, 0);
    CHECK_EQ_INT(t.bad_contains, 0);
    CHECK(t.inside > t.rays / 10 && t.outside > t.rays / 10);
    CHECK(t.skipped < t.rays / 4);
    return check_summary();
}
