/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh_fixtures.h — closed and open test meshes built in code, shared by the
 * mesh tests and the mesh benchmark: icosphere, torus, voxel solids (cube,
 * genus-2 block), the concave L-prism. A mesh under construction grows its
 * arrays; faces are index lists, outward by the right-hand rule. Static
 * functions in a header, so each test stays one program; a test that uses
 * only some of them must not trip -Wunused-function.
 */
#ifndef ISECT_TEST_MESH_FIXTURES_H
#define ISECT_TEST_MESH_FIXTURES_H

#include <isect.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
#define FX_MAYBE_UNUSED __attribute__((unused))
#else
#define FX_MAYBE_UNUSED
#endif

typedef struct fx_mesh {
    double  *v;
    int64_t  nv, v_cap;
    int32_t *idx;
    int64_t  nidx, idx_cap;
    int64_t *off; /* nf + 1 entries */
    int64_t  nf, f_cap;
} fx_mesh;

static FX_MAYBE_UNUSED void *fx_grow(void *p, int64_t *cap, int64_t need, size_t elem)
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

static FX_MAYBE_UNUSED int32_t fx_vertex(fx_mesh *m, double x, double y, double z)
{
    m->v = fx_grow(m->v, &m->v_cap, 3 * (m->nv + 1), sizeof *m->v);
    m->v[3 * m->nv] = x;
    m->v[3 * m->nv + 1] = y;
    m->v[3 * m->nv + 2] = z;
    return (int32_t)m->nv++;
}

static FX_MAYBE_UNUSED void fx_face(fx_mesh *m, int n, const int32_t *corners)
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

static FX_MAYBE_UNUSED void fx_tri(fx_mesh *m, int32_t a, int32_t b, int32_t c)
{
    int32_t t[3] = { a, b, c };
    fx_face(m, 3, t);
}

static FX_MAYBE_UNUSED void fx_quad(fx_mesh *m, int32_t a, int32_t b, int32_t c, int32_t d, int split)
{
    int32_t q[4] = { a, b, c, d };
    if (!split) {
        fx_face(m, 4, q);
    } else {
        fx_tri(m, a, b, c);
        fx_tri(m, a, c, d);
    }
}

static FX_MAYBE_UNUSED void fx_free(fx_mesh *m)
{
    free(m->v);
    free(m->idx);
    free(m->off);
    memset(m, 0, sizeof *m);
}

/* 1 when every face is a triangle (then offsets can be NULL). */
static FX_MAYBE_UNUSED int fx_all_triangles(const fx_mesh *m)
{
    return m->nidx == 3 * m->nf;
}

/* The library mesh: triangles without offsets, anything else with. */
static FX_MAYBE_UNUSED isect_mesh *fx_build(const fx_mesh *m)
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
static FX_MAYBE_UNUSED int32_t fx_midpoint(fx_mesh *m, int64_t *keys, int32_t *vals, int64_t cap, int32_t a,
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

static FX_MAYBE_UNUSED fx_mesh fx_icosphere(int levels, const double c[3], double r)
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
static FX_MAYBE_UNUSED fx_mesh fx_torus(double R, double r, int nu, int nv, int split)
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
static FX_MAYBE_UNUSED fx_mesh fx_voxels(int nx, int ny, int nz, const char *occupied, int split)
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

/* r (row-major 3x3): the rotation by `angle` radians about the unit
 * vector `axis` (Rodrigues' formula). */
static FX_MAYBE_UNUSED void fx_rotation(const double axis[3], double angle, double r[9])
{
    double c = cos(angle), s = sin(angle);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double cross = 0.0;
            if (i != j) {
                int k = 3 - i - j;
                cross = ((i + 1) % 3 == j ? -1.0 : 1.0) * axis[k];
            }
            r[3 * i + j] = (i == j ? c : 0.0) + (1.0 - c) * axis[i] * axis[j] + s * cross;
        }
}

/* The unit cube [0,1]^3 as six quads (split: twelve triangles). */
static FX_MAYBE_UNUSED fx_mesh fx_cube(int split)
{
    const char one = 1;
    return fx_voxels(1, 1, 1, &one, split);
}

/* A solid of genus 2: a 5 x 3 x 1 block with two 1 x 1 holes through it. */
static FX_MAYBE_UNUSED fx_mesh fx_genus2(int split)
{
    char occ[15];
    memset(occ, 1, sizeof occ);
    occ[1 * 5 + 1] = 0;
    occ[1 * 5 + 3] = 0;
    return fx_voxels(5, 3, 1, occ, split);
}

/* The L-shaped prism: the concave hexagon (0,0) (2,0) (2,1) (1,1) (1,2)
 * (0,2) extruded from z = 0 to z = h; its caps are concave polygon faces. */
static FX_MAYBE_UNUSED fx_mesh fx_l_prism(double h)
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

#endif
