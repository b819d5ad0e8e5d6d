/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh_check.c — isect_mesh_check: topology and measures of a mesh.
 *
 * Edges are the undirected vertex pairs of face boundaries (an edge a -> a
 * of a face that repeats a vertex is no edge). From the sorted edge uses:
 * an edge with one use is a boundary edge, with three or more non-manifold,
 * with two uses in the same direction misoriented. Faces sharing an edge
 * are in one component (union-find). Genus per closed oriented component
 * is (2 - chi_c)/2 with chi_c = V_c - E_c + F_c, V_c counting the vertices
 * of the component's faces (a vertex shared by two components counts in
 * each). Volume by the divergence theorem, area as the sum of the faces'
 * vector-area lengths; both over each face's fan from its first vertex,
 * relative to the centre of the vertices' bounding box (so the sums do not
 * cancel the mesh's position away) and summed with Neumaier's compensated
 * summation, in units scaled by powers of two (mesh_measures).
 */
#include "mesh/mesh.h"

#include "core/scaling.h"
#include "core/vec3.h"

#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------- union-find */

static int32_t uf_find(int32_t *parent, int32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]]; /* path halving */
        x = parent[x];
    }
    return x;
}

static void uf_union(int32_t *parent, int32_t a, int32_t b)
{
    a = uf_find(parent, a);
    b = uf_find(parent, b);
    if (a != b) {
        /* The larger index under the smaller: deterministic roots. */
        if (a < b)
            parent[b] = a;
        else
            parent[a] = b;
    }
}

/* ------------------------------------------------------------ measures */

/* Vertex i in the measures' units: (p 2^-e1 - ref) 2^-e2. Both scalings
 * are by powers of two (exact; only parts below 2^-1074 of the largest
 * coordinate are lost to underflow, far below the sums' rounding). */
static void measure_point(const isect_mesh *m, int32_t i, int e1, const double ref[3], int e2,
                          double out[3])
{
    const double *p = mesh_vertex(m, i);
    for (int k = 0; k < 3; k++)
        out[k] = pow2_scale(pow2_scale(p[k], -e1) - ref[k], -e2);
}

/* Volume and area. Products of coordinates overflow from ~1e103 (volume,
 * degree 3) and ~1e154 (area, degree 2), and inf - inf gave NaN, so the
 * sums run in scaled units: the coordinates scaled by 2^-e1 (the largest
 * below 1: nothing overflows), taken relative to the centre ref of their
 * box, and scaled by 2^-e2 (the largest relative coordinate in [0.5, 1):
 * tiny or far-away meshes keep their products normal). The results are
 * scaled back by 2^(3(e1+e2)) and 2^(2(e1+e2)) once, at the end: +-inf
 * exactly when the value exceeds the double range (isect.h), subnormal or
 * 0 when below it. */
static void mesh_measures(const isect_mesh *m, isect_mesh_report *r)
{
    double big = 0.0;
    for (int64_t i = 0; i < 3 * m->vertex_count; i++)
        big = fmax(big, fabs(m->verts[i]));
    int e1 = big > 0.0 ? pow2_exponent(big) : 0;
    double lo[3] = { 0.0, 0.0, 0.0 }, hi[3] = { 0.0, 0.0, 0.0 };
    for (int64_t i = 0; i < m->vertex_count; i++) {
        const double *p = m->verts + 3 * i;
        for (int k = 0; k < 3; k++) {
            double x = pow2_scale(p[k], -e1);
            lo[k] = i == 0 || x < lo[k] ? x : lo[k];
            hi[k] = i == 0 || x > hi[k] ? x : hi[k];
        }
    }
    double ref[3], spread = 0.0;
    for (int k = 0; k < 3; k++) {
        ref[k] = 0.5 * lo[k] + 0.5 * hi[k];
        spread = fmax(spread, fmax(hi[k] - ref[k], ref[k] - lo[k]));
    }
    int e2 = spread > 0.0 ? pow2_exponent(spread) : 0;
    comp_sum volume = { 0.0, 0.0 }, area = { 0.0, 0.0 };
    for (int64_t f = 0; f < m->face_count; f++) {
        const int32_t *corner = m->idx + mesh_face_start(m, f);
        int size = mesh_face_size(m, f);
        double a[3], vector_area[3] = { 0.0, 0.0, 0.0 };
        measure_point(m, corner[0], e1, ref, e2, a);
        for (int i = 1; i + 1 < size; i++) {
            double b[3], c[3], ab[3], ac[3], cross[3], bc[3];
            measure_point(m, corner[i], e1, ref, e2, b);
            measure_point(m, corner[i + 1], e1, ref, e2, c);
            /* Tetrahedron (ref, a, b, c): a . (b x c) / 6. */
            v3_cross(bc, b, c);
            comp_add(&volume, v3_dot(a, bc) / 6.0);
            v3_sub(ab, b, a);
            v3_sub(ac, c, a);
            v3_cross(cross, ab, ac);
            v3_add(vector_area, vector_area, cross);
        }
        comp_add(&area, 0.5 * v3_norm(vector_area));
    }
    int e = e1 + e2;
    r->volume = ldexp(comp_value(&volume), 3 * e);
    r->area = ldexp(comp_value(&area), 2 * e);
}

/* ------------------------------------------------------------- topology */

/* Vertices a component's faces use, counted once per (component, vertex):
 * almost every vertex has one component, remembered in first_comp; the
 * rare extra pairs are collected, sorted and counted once each. */
static int count_component_vertices(const isect_mesh *m, const int32_t *comp_of_face,
                                    int64_t *vertices_of_comp, int64_t *referenced)
{
    int32_t *first_comp = malloc((size_t)(m->vertex_count > 0 ? m->vertex_count : 1)
                                 * sizeof *first_comp);
    if (first_comp == NULL)
        return ISECT_E_NOMEM;
    for (int64_t v = 0; v < m->vertex_count; v++)
        first_comp[v] = -1;
    mesh_edge_use *extra = NULL; /* key = comp * vertex_count + vertex */
    int64_t extra_count = 0, extra_cap = 0;
    *referenced = 0;
    for (int64_t f = 0; f < m->face_count; f++) {
        const int32_t *corner = m->idx + mesh_face_start(m, f);
        int size = mesh_face_size(m, f);
        int32_t c = comp_of_face[f];
        for (int i = 0; i < size; i++) {
            int32_t v = corner[i];
            if (first_comp[v] < 0) {
                first_comp[v] = c;
                vertices_of_comp[c]++;
                (*referenced)++;
            } else if (first_comp[v] != c) {
                if (extra_count == extra_cap) {
                    int64_t cap = extra_cap > 0 ? 2 * extra_cap : 64;
                    mesh_edge_use *grown = realloc(extra, (size_t)cap * sizeof *grown);
                    if (grown == NULL) {
                        free(extra);
                        free(first_comp);
                        return ISECT_E_NOMEM;
                    }
                    extra = grown;
                    extra_cap = cap;
                }
                extra[extra_count].key = (uint64_t)c * (uint64_t)m->vertex_count + (uint64_t)v;
                extra[extra_count].face = (uint32_t)c;
                extra[extra_count].reversed = 0;
                extra_count++;
            }
        }
    }
    /* Sort the extras (few) by key and count each distinct pair once. */
    for (int64_t i = 1; i < extra_count; i++) {
        mesh_edge_use x = extra[i];
        int64_t j = i;
        for (; j > 0 && extra[j - 1].key > x.key; j--)
            extra[j] = extra[j - 1];
        extra[j] = x;
    }
    for (int64_t i = 0; i < extra_count; i++)
        if (i == 0 || extra[i].key != extra[i - 1].key)
            vertices_of_comp[extra[i].face]++;
    free(extra);
    free(first_comp);
    return ISECT_OK;
}

static int mesh_topology(const isect_mesh *m, isect_mesh_report *r)
{
    int64_t nf = m->face_count;
    mesh_edge_use *uses;
    int64_t use_count;
    int status = mesh_edge_uses(m, &uses, &use_count);
    if (status != ISECT_OK)
        return status;
    size_t faces_alloc = (size_t)(nf > 0 ? nf : 1);
    int32_t *parent = malloc(faces_alloc * sizeof *parent);
    int32_t *comp_of_face = malloc(faces_alloc * sizeof *comp_of_face);
    int64_t *stats = calloc(3 * faces_alloc, sizeof *stats); /* V_c, E_c, F_c */
    if (parent == NULL || comp_of_face == NULL || stats == NULL) {
        free(uses);
        free(parent);
        free(comp_of_face);
        free(stats);
        return ISECT_E_NOMEM;
    }
    for (int64_t f = 0; f < nf; f++)
        parent[f] = (int32_t)f;

    for (int64_t i = 0; i < use_count;) {
        int64_t j = i + 1;
        while (j < use_count && uses[j].key == uses[i].key) {
            uf_union(parent, (int32_t)uses[i].face, (int32_t)uses[j].face);
            j++;
        }
        int64_t n = j - i;
        r->edges++;
        if (n == 1)
            r->boundary_edges++;
        else if (n >= 3)
            r->nonmanifold_edges++;
        else if (uses[i].reversed == uses[i + 1].reversed)
            r->misoriented_edges++;
        i = j;
    }

    int64_t *vertices_of_comp = stats, *edges_of_comp = stats + faces_alloc,
            *faces_of_comp = stats + 2 * faces_alloc;
    for (int64_t f = 0; f < nf; f++) {
        int32_t root = uf_find(parent, (int32_t)f);
        if (root == f)
            comp_of_face[f] = (int32_t)r->components++;
        else
            comp_of_face[f] = comp_of_face[root]; /* root < f: already numbered */
        faces_of_comp[comp_of_face[f]]++;
    }
    for (int64_t i = 0; i < use_count; i++)
        if (i == 0 || uses[i].key != uses[i - 1].key)
            edges_of_comp[comp_of_face[uses[i].face]]++;
    free(uses);
    free(parent);

    status = count_component_vertices(m, comp_of_face, vertices_of_comp, &r->vertices);
    free(comp_of_face);
    if (status != ISECT_OK) {
        free(stats);
        return status;
    }
    r->faces = nf;
    r->degenerate_faces = m->degenerate_faces;
    r->euler_characteristic = r->vertices - r->edges + r->faces;
    r->closed = r->boundary_edges == 0 && r->nonmanifold_edges == 0;
    r->oriented = r->misoriented_edges == 0;
    r->genus = -1;
    if (r->closed && r->oriented) {
        r->genus = 0;
        for (int64_t c = 0; c < r->components; c++) {
            int64_t chi = vertices_of_comp[c] - edges_of_comp[c] + faces_of_comp[c];
            r->genus += (2 - chi) / 2;
        }
    }
    free(stats);
    return ISECT_OK;
}

ISECT_API int isect_mesh_check(const isect_mesh *mesh, isect_mesh_report *report)
{
    if (mesh == NULL || report == NULL)
        return ISECT_E_ARG;
    isect_mesh_report r;
    memset(&r, 0, sizeof r);
    int status = mesh_topology(mesh, &r);
    if (status != ISECT_OK)
        return status;
    mesh_measures(mesh, &r);
    *report = r;
    return ISECT_OK;
}
