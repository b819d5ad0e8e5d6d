/*
 * test_mesh_exactly_once.c — the headline guarantee for meshes: a ray that
 * crosses a closed surface through a shared edge or vertex is counted
 * exactly once, so the number of hits in [0, inf) is even from outside and
 * odd from inside, for triangle and for polygon faces.
 *
 * Rays are aimed at every vertex and every edge midpoint of closed meshes —
 * an icosphere, a torus (genus 1) of triangles and of non-planar quads, a
 * cube of quads, an L-shaped prism whose caps are concave hexagons (also
 * rotated, so its faces are no longer exactly planar), and a genus-2 block
 * of quads and of triangles — from random points outside and inside. The
 * integer-coordinate meshes get dyadic origins, so the ray passes EXACTLY
 * through the vertex or midpoint; the others pass within an ulp. The whole
 * line (tmin = -inf) must give an even count too.
 *
 *     test_mesh_exactly_once [rays]    (default 1000000; also read from
 *                                       ISECT_EXACTLY_ONCE_RAYS)
 *
 * Prints the number of rays and of exceptions per mesh and in total.
 */
#include "check.h"

#include <isect.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ fixtures
 * Test meshes built in code (the same block is in test_mesh.c and
 * test_mesh_exactly_once.c, since each test is one source file). A mesh
 * under construction grows its arrays; faces are index lists, outward by
 * the right-hand rule. */
typedef struct fx_mesh {
    double  *v;
    int64_t  nv, v_cap;
    int32_t *idx;
    int64_t  nidx, idx_cap;
    int64_t *off; /* nf + 1 entries */
    int64_t  nf, f_cap;
} fx_mesh;

static void *fx_grow(void *p, int64_t *cap, int64_t need, size_t elem)
{
    if (need <= *cap)
        return p;
    int64_t c = *cap > 0 ? *cap : 16;
    while (c < need)
        c *= 2;
    void *q = realloc(p, (size_t)c * elem);
    if (q == NULL) {
        fprintf(stderr, "out of memory\n");
        exit(2);
    }
    *cap = c;
    return q;
}

static int32_t fx_vertex(fx_mesh *m, double x, double y, double z)
{
    m->v = fx_grow(m->v, &m->v_cap, 3 * (m->nv + 1), sizeof *m->v);
    m->v[3 * m->nv] = x;
    m->v[3 * m->nv + 1] = y;
    m->v[3 * m->nv + 2] = z;
    return (int32_t)m->nv++;
}

static void fx_face(fx_mesh *m, int n, const int32_t *corners)
{
    m->idx = fx_grow(m->idx, &m->idx_cap, m->nidx + n, sizeof *m->idx);
    m->off = fx_grow(m->off, &m->f_cap, m->nf + 2, sizeof *m->off);
    if (m->nf == 0)
        m->off[0] = 0;
    memcpy(m->idx + m->nidx, corners, (size_t)n * sizeof *corners);
    m->nidx += n;
    m->nf++;
    m->off[m->nf] = m->nidx;
}

static void fx_tri(fx_mesh *m, int32_t a, int32_t b, int32_t c)
{
    int32_t t[3] = { a, b, c };
    fx_face(m, 3, t);
}

static void fx_quad(fx_mesh *m, int32_t a, int32_t b, int32_t c, int32_t d, int split)
{
    int32_t q[4] = { a, b, c, d };
    if (!split) {
        fx_face(m, 4, q);
    } else {
        fx_tri(m, a, b, c);
        fx_tri(m, a, c, d);
    }
}

static void fx_free(fx_mesh *m)
{
    free(m->v);
    free(m->idx);
    free(m->off);
    memset(m, 0, sizeof *m);
}

/* 1 when every face is a triangle (then offsets can be NULL). */
static int fx_all_triangles(const fx_mesh *m)
{
    return m->nidx == 3 * m->nf;
}

/* The library mesh: triangles without offsets, anything else with. */
static isect_mesh *fx_build(const fx_mesh *m)
{
    isect_mesh *mesh = NULL;
    int status = isect_mesh_create(m->v, m->nv, m->idx, fx_all_triangles(m) ? NULL : m->off,
                                   m->nf, &mesh);
    if (status != ISECT_OK) {
        fprintf(stderr, "isect_mesh_create: %s\n", isect_strerror(status));
        exit(2);
    }
    return mesh;
}

/* Icosphere: the icosahedron subdivided `levels` times, vertices pushed to
 * the sphere of radius r about c; 20 * 4^levels triangles. */
static int32_t fx_midpoint(fx_mesh *m, int64_t *keys, int32_t *vals, int64_t cap, int32_t a,
                           int32_t b)
{
    if (a > b) {
        int32_t t = a;
        a = b;
        b = t;
    }
    int64_t key = (int64_t)a * 0x80000000LL + b;
    uint64_t h = ((uint64_t)key * 0x9E3779B97F4A7C15ULL) >> 17;
    for (;; h++) {
        h &= (uint64_t)(cap - 1);
        if (keys[h] == key)
            return vals[h];
        if (keys[h] < 0) {
            double p[3], len = 0.0;
            for (int k = 0; k < 3; k++) {
                p[k] = m->v[3 * a + k] + m->v[3 * b + k];
                len += p[k] * p[k];
            }
            len = sqrt(len);
            keys[h] = key;
            vals[h] = fx_vertex(m, p[0] / len, p[1] / len, p[2] / len);
            return vals[h];
        }
    }
}

static fx_mesh fx_icosphere(int levels, const double c[3], double r)
{
    const double g = (1.0 + sqrt(5.0)) / 2.0;
    static const int32_t base[20][3] = {
        { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
        { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },
        { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 },
        { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
    const double corner[12][3] = {
        { -1, g, 0 }, { 1, g, 0 }, { -1, -g, 0 }, { 1, -g, 0 }, { 0, -1, g }, { 0, 1, g },
        { 0, -1, -g }, { 0, 1, -g }, { g, 0, -1 }, { g, 0, 1 }, { -g, 0, -1 }, { -g, 0, 1 } };
    fx_mesh m;
    memset(&m, 0, sizeof m);
    double len = sqrt(1.0 + g * g);
    for (int i = 0; i < 12; i++)
        fx_vertex(&m, corner[i][0] / len, corner[i][1] / len, corner[i][2] / len);
    int32_t *tris = malloc(sizeof base);
    memcpy(tris, base, sizeof base);
    int64_t nt = 20;
    for (int l = 0; l < levels; l++) {
        int64_t cap = 1;
        while (cap < 4 * (m.nv + 3 * nt))
            cap *= 2;
        int64_t *keys = malloc((size_t)cap * sizeof *keys);
        int32_t *vals = malloc((size_t)cap * sizeof *vals);
        int32_t *next = malloc((size_t)(12 * nt) * sizeof *next);
        for (int64_t i = 0; i < cap; i++)
            keys[i] = -1;
        for (int64_t i = 0; i < nt; i++) {
            int32_t a = tris[3 * i], b = tris[3 * i + 1], cc = tris[3 * i + 2];
            int32_t ab = fx_midpoint(&m, keys, vals, cap, a, b);
            int32_t bc = fx_midpoint(&m, keys, vals, cap, b, cc);
            int32_t ca = fx_midpoint(&m, keys, vals, cap, cc, a);
            int32_t q[12] = { a, ab, ca, b, bc, ab, cc, ca, bc, ab, bc, ca };
            memcpy(next + 12 * i, q, sizeof q);
        }
        free(tris);
        free(keys);
        free(vals);
        tris = next;
        nt *= 4;
    }
    for (int64_t i = 0; i < m.nv; i++)
        for (int k = 0; k < 3; k++)
            m.v[3 * i + k] = c[k] + r * m.v[3 * i + k];
    for (int64_t i = 0; i < nt; i++)
        fx_tri(&m, tris[3 * i], tris[3 * i + 1], tris[3 * i + 2]);
    free(tris);
    return m;
}

/* Torus about the z axis: major radius R, minor r, nu x nv grid of quads
 * (split into triangles when split != 0). The quads are mathematically
 * planar trapezoids but not exactly planar in doubles. */
static fx_mesh fx_torus(double R, double r, int nu, int nv, int split)
{
    fx_mesh m;
    memset(&m, 0, sizeof m);
    const double two_pi = 6.283185307179586;
    for (int i = 0; i < nu; i++) {
        double u = two_pi * i / nu;
        for (int j = 0; j < nv; j++) {
            double w = two_pi * j / nv;
            double rho = R + r * cos(w);
            fx_vertex(&m, rho * cos(u), rho * sin(u), r * sin(w));
        }
    }
    for (int i = 0; i < nu; i++) {
        for (int j = 0; j < nv; j++) {
            int32_t a = i * nv + j, b = ((i + 1) % nu) * nv + j;
            int32_t c = ((i + 1) % nu) * nv + (j + 1) % nv, d = i * nv + (j + 1) % nv;
            fx_quad(&m, a, b, c, d, split);
        }
    }
    return m;
}

/* The boundary of a union of unit voxels: occupied(x, y, z) for
 * 0 <= x < nx etc.; one outward quad per voxel face next to an empty cell,
 * vertices on the integer grid shared between faces. */
static fx_mesh fx_voxels(int nx, int ny, int nz, const char *occupied, int split)
{
    fx_mesh m;
    memset(&m, 0, sizeof m);
    int gx = nx + 1, gy = ny + 1, gz = nz + 1;
    int32_t *grid = malloc((size_t)gx * gy * gz * sizeof *grid);
    for (int i = 0; i < gx * gy * gz; i++)
        grid[i] = -1;
#define FX_OCC(x, y, z)                                                              \
    ((x) >= 0 && (y) >= 0 && (z) >= 0 && (x) < nx && (y) < ny && (z) < nz           \
     && occupied[((z) * ny + (y)) * nx + (x)])
    for (int z = 0; z < nz; z++)
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x++) {
                if (!FX_OCC(x, y, z))
                    continue;
                for (int a = 0; a < 3; a++) {
                    for (int s = 0; s < 2; s++) {
                        int n[3] = { x, y, z };
                        n[a] += s ? 1 : -1;
                        if (FX_OCC(n[0], n[1], n[2]))
                            continue;
                        int b = (a + 1) % 3, c = (a + 2) % 3;
                        int base[3] = { x, y, z };
                        base[a] += s;
                        int32_t q[4];
                        for (int corner = 0; corner < 4; corner++) {
                            int p[3] = { base[0], base[1], base[2] };
                            p[b] += corner == 1 || corner == 2;
                            p[c] += corner >= 2;
                            int32_t *slot = &grid[(p[2] * gy + p[1]) * gx + p[0]];
                            if (*slot < 0)
                                *slot = fx_vertex(&m, p[0], p[1], p[2]);
                            q[corner] = *slot;
                        }
                        /* e_b x e_c = e_a: counter-clockwise seen from +a. */
                        if (s)
                            fx_quad(&m, q[0], q[1], q[2], q[3], split);
                        else
                            fx_quad(&m, q[3], q[2], q[1], q[0], split);
                    }
                }
            }
#undef FX_OCC
    free(grid);
    return m;
}

/* The unit cube [0,1]^3 as six quads (split: twelve triangles). */
static fx_mesh fx_cube(int split)
{
    const char one = 1;
    return fx_voxels(1, 1, 1, &one, split);
}

/* A solid of genus 2: a 5 x 3 x 1 block with two 1 x 1 holes through it. */
static fx_mesh fx_genus2(int split)
{
    char occ[15];
    memset(occ, 1, sizeof occ);
    occ[1 * 5 + 1] = 0;
    occ[1 * 5 + 3] = 0;
    return fx_voxels(5, 3, 1, occ, split);
}

/* The L-shaped prism: the concave hexagon (0,0) (2,0) (2,1) (1,1) (1,2)
 * (0,2) extruded from z = 0 to z = h; its caps are concave polygon faces. */
static fx_mesh fx_l_prism(double h)
{
    static const double hex[6][2] = { { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
    fx_mesh m;
    memset(&m, 0, sizeof m);
    int32_t bottom[6], top[6];
    for (int i = 0; i < 6; i++) {
        bottom[i] = fx_vertex(&m, hex[i][0], hex[i][1], 0.0);
        top[i] = fx_vertex(&m, hex[i][0], hex[i][1], h);
    }
    int32_t down[6];
    for (int i = 0; i < 6; i++)
        down[i] = bottom[5 - i];
    fx_face(&m, 6, down); /* normal -z */
    fx_face(&m, 6, top);  /* normal +z */
    for (int i = 0; i < 6; i++) {
        int j = (i + 1) % 6;
        fx_quad(&m, bottom[i], bottom[j], top[j], top[i], 0);
    }
    return m;
}

/* ------------------------------------------------------------- the test */

typedef struct lcg {
    uint64_t state;
} lcg;

static double lcg_uniform(lcg *g) /* in [0, 1) */
{
    g->state = g->state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(g->state >> 11) * 0x1p-53;
}

/* The targets: every vertex and every edge midpoint (each undirected edge
 * once; the same face-boundary pairs as the report's edges). */
static double *targets_of(const fx_mesh *m, int64_t *count)
{
    int64_t cap = m->nv + m->nidx, n = 0;
    double *t = malloc((size_t)(3 * cap) * sizeof *t);
    for (int64_t i = 0; i < m->nv; i++, n++)
        memcpy(t + 3 * n, m->v + 3 * i, 3 * sizeof(double));
    for (int64_t f = 0; f < m->nf; f++) {
        int size = (int)(m->off[f + 1] - m->off[f]);
        const int32_t *c = m->idx + m->off[f];
        for (int i = 0; i < size; i++) {
            int32_t a = c[i], b = c[(i + 1) % size];
            if (a > b) /* each interior edge once: the use with a < b */
                continue;
            for (int k = 0; k < 3; k++)
                t[3 * n + k] = 0.5 * (m->v[3 * a + k] + m->v[3 * b + k]);
            n++;
        }
    }
    *count = n;
    return t;
}

/* How a mesh's random interior points are drawn. */
enum interior { IN_BALL, IN_TORUS, IN_BOX, IN_L, IN_GENUS2 };

typedef struct case_def {
    const char   *name;
    fx_mesh       mesh;
    enum interior interior;
    double        param[4];   /* ball: centre, radius; torus: R, r; box/L: size, height */
    int           dyadic;     /* integer vertices: dyadic origins, exact aim */
    double        rot[9];     /* rotation applied to mesh and interior points (or identity) */
} case_def;

static void rotate(const double r[9], const double p[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = r[3 * i] * p[0] + r[3 * i + 1] * p[1] + r[3 * i + 2] * p[2];
}

static void interior_point(const case_def *c, lcg *g, double p[3])
{
    double q[3];
    switch (c->interior) {
    case IN_BALL: {
        for (;;) {
            double d2 = 0.0;
            for (int k = 0; k < 3; k++) {
                q[k] = 2.0 * lcg_uniform(g) - 1.0;
                d2 += q[k] * q[k];
            }
            if (d2 <= 1.0)
                break;
        }
        for (int k = 0; k < 3; k++)
            q[k] = c->param[k] + c->param[3] * q[k];
        break;
    }
    case IN_TORUS: {
        /* Within 0.8 of the tube radius of the core circle: inside the
         * tessellated tube too. */
        double u = 6.283185307179586 * lcg_uniform(g), w = 6.283185307179586 * lcg_uniform(g);
        double rho = 0.8 * c->param[1] * sqrt(lcg_uniform(g));
        double ring = c->param[0] + rho * cos(w);
        q[0] = ring * cos(u);
        q[1] = ring * sin(u);
        q[2] = rho * sin(w);
        break;
    }
    case IN_BOX:
        for (int k = 0; k < 3; k++)
            q[k] = c->param[k] * (0.001 + 0.998 * lcg_uniform(g));
        break;
    case IN_L:
        for (;;) {
            q[0] = 0.001 + 1.998 * lcg_uniform(g);
            q[1] = 0.001 + 1.998 * lcg_uniform(g);
            if (q[0] < 0.999 || q[1] < 0.999)
                break;
        }
        q[2] = c->param[0] * (0.001 + 0.998 * lcg_uniform(g));
        break;
    default: { /* genus 2: a random solid cell of the 5 x 3 block */
        int x, y;
        do {
            x = (int)(5.0 * lcg_uniform(g));
            y = (int)(3.0 * lcg_uniform(g));
        } while (y == 1 && (x == 1 || x == 3));
        q[0] = x + 0.001 + 0.998 * lcg_uniform(g);
        q[1] = y + 0.001 + 0.998 * lcg_uniform(g);
        q[2] = 0.001 + 0.998 * lcg_uniform(g);
        break;
    }
    }
    rotate(c->rot, q, p);
}

/* An origin for an exact aim: a multiple of 2^-12, so target - origin is
 * exact for targets on the half-integer grid and org + 1*dir == target. */
static void dyadic(double p[3])
{
    for (int k = 0; k < 3; k++)
        p[k] = ldexp(nearbyint(ldexp(p[k], 12)), -12);
}

typedef struct tally {
    int64_t rays, bad_outside, bad_inside, bad_line, errors;
} tally;

static void run_case(const case_def *c, int64_t rays, uint64_t seed, tally *t)
{
    isect_mesh *mesh = fx_build(&c->mesh);
    isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, mesh, NULL };
    isect_mesh_report rep;
    CHECK_EQ_INT(isect_mesh_check(mesh, &rep), ISECT_OK);
    CHECK(rep.closed == 1 && rep.oriented == 1);
    int64_t ntargets;
    double *targets = targets_of(&c->mesh, &ntargets);
    /* Outside: points on a sphere three times the mesh's radius. */
    double centre[3] = { 0.0, 0.0, 0.0 }, radius = 0.0;
    for (int64_t i = 0; i < c->mesh.nv; i++)
        for (int k = 0; k < 3; k++)
            centre[k] += c->mesh.v[3 * i + k] / (double)c->mesh.nv;
    for (int64_t i = 0; i < c->mesh.nv; i++) {
        double d2 = 0.0;
        for (int k = 0; k < 3; k++)
            d2 += (c->mesh.v[3 * i + k] - centre[k]) * (c->mesh.v[3 * i + k] - centre[k]);
        radius = fmax(radius, sqrt(d2));
    }
    lcg g = { seed };
    tally local = { 0, 0, 0, 0, 0 };
    for (int64_t i = 0; i < rays; i++) {
        const double *target = targets + 3 * (i % ntargets);
        int inside = (i / ntargets) % 2 == 1;
        double org[3];
        if (inside) {
            interior_point(c, &g, org);
        } else {
            double d[3], len;
            do {
                len = 0.0;
                for (int k = 0; k < 3; k++) {
                    d[k] = 2.0 * lcg_uniform(&g) - 1.0;
                    len += d[k] * d[k];
                }
            } while (len > 1.0 || len < 1e-4);
            len = sqrt(len);
            for (int k = 0; k < 3; k++)
                org[k] = centre[k] + 3.0 * radius * d[k] / len;
        }
        if (c->dyadic)
            dyadic(org);
        isect_ray r;
        for (int k = 0; k < 3; k++) {
            r.org[k] = org[k];
            r.dir[k] = target[k] - org[k];
        }
        r.tmin = 0.0;
        r.tmax = INFINITY;
        int n = isect_intersect(&s, &r, NULL, NULL, 0);
        local.rays++;
        if (n < 0) {
            local.errors++;
            continue;
        }
        if (n % 2 != inside) {
            if (inside)
                local.bad_inside++;
            else
                local.bad_outside++;
            if (local.bad_inside + local.bad_outside <= 3)
                fprintf(stderr, "    %s: %s ray org (%.17g, %.17g, %.17g) dir (%.17g, %.17g, %.17g): %d hits\n",
                        c->name, inside ? "inside" : "outside", r.org[0], r.org[1], r.org[2],
                        r.dir[0], r.dir[1], r.dir[2], n);
        }
        /* The whole line crosses a closed surface an even number of times;
         * checked on every 16th ray (it costs a second query). */
        if (i % 16 == 0) {
            r.tmin = -INFINITY;
            n = isect_intersect(&s, &r, NULL, NULL, 0);
            if (n < 0 || n % 2 != 0)
                local.bad_line++;
        }
    }
    printf("  %-22s %8lld rays (%lld targets): %lld outside, %lld inside, %lld line exceptions\n",
           c->name, (long long)local.rays, (long long)ntargets, (long long)local.bad_outside,
           (long long)local.bad_inside, (long long)local.bad_line);
    CHECK_EQ_INT(local.errors, 0);
    CHECK_EQ_INT(local.bad_outside, 0);
    CHECK_EQ_INT(local.bad_inside, 0);
    CHECK_EQ_INT(local.bad_line, 0);
    t->rays += local.rays;
    t->bad_outside += local.bad_outside;
    t->bad_inside += local.bad_inside;
    t->bad_line += local.bad_line;
    t->errors += local.errors;
    free(targets);
    isect_mesh_destroy(mesh);
}

static void rotate_mesh(fx_mesh *m, const double r[9])
{
    for (int64_t i = 0; i < m->nv; i++) {
        double p[3];
        rotate(r, m->v + 3 * i, p);
        memcpy(m->v + 3 * i, p, sizeof p);
    }
}

int main(int argc, char **argv)
{
    int64_t total = 1000000;
    const char *env = getenv("ISECT_EXACTLY_ONCE_RAYS");
    if (argc > 1)
        total = atoll(argv[1]);
    else if (env != NULL && *env != '\0')
        total = atoll(env);
    if (total < 1) {
        fprintf(stderr, "usage: test_mesh_exactly_once [rays]\n");
        return 2;
    }
    const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    /* A rotation with no exactly representable structure (about (1,2,3)). */
    double rot[9];
    {
        double axis[3] = { 1.0, 2.0, 3.0 }, len = sqrt(14.0), a = 0.61;
        for (int k = 0; k < 3; k++)
            axis[k] /= len;
        double c = cos(a), s = sin(a);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double cross = 0.0;
                if (i != j) {
                    int k = 3 - i - j;
                    cross = ((i + 1) % 3 == j ? -1.0 : 1.0) * axis[k];
                }
                rot[3 * i + j] = (i == j ? c : 0.0) + (1.0 - c) * axis[i] * axis[j] + s * cross;
            }
    }
    const double ball_c[3] = { 0.25, -0.125, 0.5 };
    enum { CASES = 9 };
    case_def cases[CASES];
    memset(cases, 0, sizeof cases);
    cases[0].name = "icosphere (triangles)";
    cases[0].mesh = fx_icosphere(3, ball_c, 1.5);
    cases[0].interior = IN_BALL;
    cases[0].param[0] = ball_c[0];
    cases[0].param[1] = ball_c[1];
    cases[0].param[2] = ball_c[2];
    cases[0].param[3] = 1.2;
    cases[1].name = "torus (triangles)";
    cases[1].mesh = fx_torus(1.0, 0.4, 48, 24, 1);
    cases[1].interior = IN_TORUS;
    cases[1].param[0] = 1.0;
    cases[1].param[1] = 0.4;
    cases[2].name = "torus (quads)";
    cases[2].mesh = fx_torus(1.0, 0.4, 32, 16, 0);
    cases[2].interior = IN_TORUS;
    cases[2].param[0] = 1.0;
    cases[2].param[1] = 0.4;
    cases[3].name = "cube (quads)";
    cases[3].mesh = fx_cube(0);
    cases[3].interior = IN_BOX;
    cases[3].param[0] = cases[3].param[1] = cases[3].param[2] = 1.0;
    cases[3].dyadic = 1;
    cases[4].name = "cube (triangles)";
    cases[4].mesh = fx_cube(1);
    cases[4].interior = IN_BOX;
    cases[4].param[0] = cases[4].param[1] = cases[4].param[2] = 1.0;
    cases[4].dyadic = 1;
    cases[5].name = "L-prism (concave)";
    cases[5].mesh = fx_l_prism(1.0);
    cases[5].interior = IN_L;
    cases[5].param[0] = 1.0;
    cases[5].dyadic = 1;
    cases[6].name = "L-prism (rotated)";
    cases[6].mesh = fx_l_prism(1.0);
    cases[6].interior = IN_L;
    cases[6].param[0] = 1.0;
    cases[7].name = "genus 2 (quads)";
    cases[7].mesh = fx_genus2(0);
    cases[7].interior = IN_GENUS2;
    cases[7].dyadic = 1;
    cases[8].name = "genus 2 (triangles)";
    cases[8].mesh = fx_genus2(1);
    cases[8].interior = IN_GENUS2;
    cases[8].dyadic = 1;
    for (int i = 0; i < CASES; i++)
        memcpy(cases[i].rot, i == 6 ? rot : identity, sizeof identity);
    rotate_mesh(&cases[6].mesh, rot);

    /* The rays shared out evenly, at least a few per target. */
    tally t = { 0, 0, 0, 0, 0 };
    printf("exactly-once: %lld rays at vertices and edge midpoints\n", (long long)total);
    for (int i = 0; i < CASES; i++) {
        int64_t share = total / CASES + (i < total % CASES);
        run_case(&cases[i], share, 0x5DEECE66DULL + 977ULL * (uint64_t)i, &t);
        fx_free(&cases[i].mesh);
    }
    printf("exactly-once total: %lld rays, %lld exceptions (%lld outside, %lld inside, "
           "%lld whole-line, %lld errors)\n",
           (long long)t.rays,
           (long long)(t.bad_outside + t.bad_inside + t.bad_line + t.errors),
           (long long)t.bad_outside, (long long)t.bad_inside, (long long)t.bad_line,
           (long long)t.errors);
    return check_summary();
}
