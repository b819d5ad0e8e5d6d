/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh.c — isect_mesh_create / _destroy / _bytes: argument validation, the
 * copy of the caller's arrays, per-face data (exact degeneracy, polygon
 * planes), the BVH, and the edge pass that decides whether the mesh is
 * closed (contains() needs that answer on every call, so it is made once).
 */
#include "mesh/mesh.h"

#include "prim/planar.h"
#include "core/predicates.h"

#include <stdlib.h>
#include <string.h>

/* 1 when the three points span no area, decided exactly (such a face is
 * never hit: its exact projection has no area, triangle_test.h). */
static int triangle_degenerate(const double a[3], const double b[3], const double c[3])
{
    return collinear3(a, b, c);
}

/* ------------------------------------------------------------ validation */

/* ISECT_OK or the status the arguments deserve, checked in the order
 * isect.h lists them: counts and pointers, offsets, indices, then values. */
static int mesh_args_check(const double *verts, int64_t nv, const int32_t *idx,
                           const int64_t *offsets, int64_t nf)
{
    /* Face and vertex indices are int32 (isect_hit.prim, idx). */
    if (nv < 0 || nf < 0 || nv > INT32_MAX || nf > INT32_MAX)
        return ISECT_E_ARG;
    if ((verts == NULL && nv > 0) || (idx == NULL && nf > 0))
        return ISECT_E_ARG;
    int64_t corners = 3 * nf;
    if (offsets != NULL) {
        if (offsets[0] != 0)
            return ISECT_E_ARG;
        for (int64_t f = 0; f < nf; f++) {
            /* Written as a difference so no sum can overflow. */
            if (offsets[f + 1] < offsets[f] || offsets[f + 1] - offsets[f] < 3
                || offsets[f + 1] - offsets[f] > INT32_MAX)
                return ISECT_E_ARG;
        }
        corners = offsets[nf];
    }
    for (int64_t i = 0; i < corners; i++)
        if (idx[i] < 0 || idx[i] >= nv)
            return ISECT_E_ARG;
    return all_finite(verts, 3 * nv) ? ISECT_OK : ISECT_E_NONFINITE;
}

/* ------------------------------------------------------------ edge uses */

/* LSD radix sort of the uses by key, 11 bits a pass over the bits the keys
 * can have (max_key); stable, so the uses of one edge stay in face order. */
static int edge_uses_sort(mesh_edge_use *uses, int64_t n, uint64_t max_key)
{
    enum { DIGIT_BITS = 11, BUCKETS = 1 << DIGIT_BITS };
    int key_bits = 0;
    while (key_bits < 64 && (max_key >> key_bits) != 0)
        key_bits++;
    if (n < 2 || key_bits == 0)
        return ISECT_OK;
    mesh_edge_use *tmp = malloc((size_t)n * sizeof *tmp);
    if (tmp == NULL)
        return ISECT_E_NOMEM;
    mesh_edge_use *src = uses, *dst = tmp;
    for (int shift = 0; shift < key_bits; shift += DIGIT_BITS) {
        int64_t start[BUCKETS];
        memset(start, 0, sizeof start);
        for (int64_t i = 0; i < n; i++)
            start[(src[i].key >> shift) & (BUCKETS - 1)]++;
        int64_t sum = 0;
        for (int d = 0; d < BUCKETS; d++) {
            int64_t c = start[d];
            start[d] = sum;
            sum += c;
        }
        for (int64_t i = 0; i < n; i++)
            dst[start[(src[i].key >> shift) & (BUCKETS - 1)]++] = src[i];
        mesh_edge_use *swap = src;
        src = dst;
        dst = swap;
    }
    if (src != uses)
        memcpy(uses, src, (size_t)n * sizeof *uses);
    free(tmp);
    return ISECT_OK;
}

/* The undirected key of edge a - b. */
static inline uint64_t edge_key(uint64_t a, uint64_t b, uint64_t nv)
{
    return a < b ? a * nv + b : b * nv + a;
}

int mesh_edge_uses(const isect_mesh *m, mesh_edge_use **out, int64_t *count)
{
    *out = NULL;
    *count = 0;
    int64_t corners = m->offsets != NULL ? m->offsets[m->face_count] : 3 * m->face_count;
    mesh_edge_use *uses = malloc((size_t)(corners > 0 ? corners : 1) * sizeof *uses);
    if (uses == NULL)
        return ISECT_E_NOMEM;
    uint64_t nv = (uint64_t)m->vertex_count;
    int64_t n = 0;
    for (int64_t f = 0; f < m->face_count; f++) {
        const int32_t *corner = m->idx + mesh_face_start(m, f);
        int size = mesh_face_size(m, f);
        for (int i = 0; i < size; i++) {
            uint64_t a = (uint64_t)corner[i], b = (uint64_t)corner[i + 1 < size ? i + 1 : 0];
            if (a == b)
                continue;
            uses[n].key = edge_key(a, b, nv);
            uses[n].face = (uint32_t)f;
            uses[n].reversed = a > b;
            n++;
        }
    }
    int status = edge_uses_sort(uses, n, nv > 0 ? nv * nv - 1 : 0);
    if (status != ISECT_OK) {
        free(uses);
        return status;
    }
    *out = uses;
    *count = n;
    return ISECT_OK;
}

/* Closed: every edge has exactly two uses (no boundary, nothing
 * non-manifold); oriented as well when the two uses of every edge run in
 * opposite directions (the faces agree on an outside: the integer winding
 * number is then the signed crossing count). The uses are bucketed by
 * their lower vertex (a counting sort: two passes, where a full sort by key
 * takes four), and within a bucket (a handful of entries) the upper
 * vertices, each tagged with its direction in the low bit, are sorted by
 * insertion and must come in pairs. */
static int mesh_edges_closed(const isect_mesh *m, int *closed, int *oriented)
{
    int64_t corners = m->offsets != NULL ? m->offsets[m->face_count] : 3 * m->face_count;
    int64_t nv = m->vertex_count;
    int64_t *start = calloc((size_t)nv + 1, sizeof *start);
    int64_t *upper = malloc((size_t)(corners > 0 ? corners : 1) * sizeof *upper);
    if (start == NULL || upper == NULL) {
        free(start);
        free(upper);
        return ISECT_E_NOMEM;
    }
    for (int pass = 0; pass < 2; pass++) {
        for (int64_t f = 0; f < m->face_count; f++) {
            const int32_t *corner = m->idx + mesh_face_start(m, f);
            int size = mesh_face_size(m, f);
            for (int i = 0; i < size; i++) {
                int32_t a = corner[i], b = corner[i + 1 < size ? i + 1 : 0];
                if (a == b)
                    continue;
                int32_t lo = a < b ? a : b, hi = a < b ? b : a;
                if (pass == 0)
                    start[lo + 1]++;
                else
                    upper[start[lo]++] = 2 * (int64_t)hi + (a > b); /* low bit: hi -> lo */
            }
        }
        if (pass == 0)
            for (int64_t v = 0; v < nv; v++)
                start[v + 1] += start[v];
    }
    /* After the fill, start[v] is the end of bucket v (the old start[v+1]). */
    *closed = 1;
    *oriented = 1;
    int64_t begin = 0;
    for (int64_t v = 0; v < nv && *closed; v++) {
        int64_t end = start[v];
        for (int64_t i = begin + 1; i < end; i++) {
            int64_t x = upper[i];
            int64_t j = i;
            for (; j > begin && upper[j - 1] > x; j--)
                upper[j] = upper[j - 1];
            upper[j] = x;
        }
        for (int64_t i = begin; i < end; i += 2) {
            int64_t hi = upper[i] >> 1;
            if (i + 1 >= end || upper[i + 1] >> 1 != hi || (i + 2 < end && upper[i + 2] >> 1 == hi)) {
                *closed = 0;
                break;
            }
            *oriented &= upper[i] != upper[i + 1]; /* one use each way */
        }
        begin = end;
    }
    *oriented &= *closed;
    free(start);
    free(upper);
    return ISECT_OK;
}

/* ------------------------------------------------------------- creation */

/* The BVH items: the non-degenerate faces, their outward float boxes and
 * flags, and the per-face data their prims carry. */
typedef struct face_items {
    int32_t  *face;  /* item -> face */
    float   (*box)[6];
    uint8_t  *flags;
    int64_t   count;
} face_items;

static void face_items_free(face_items *it)
{
    free(it->face);
    free(it->box);
    free(it->flags);
}

static int face_items_make(isect_mesh *m, face_items *it)
{
    int64_t nf = m->face_count;
    size_t n = (size_t)(nf > 0 ? nf : 1);
    it->face = malloc(n * sizeof *it->face);
    it->box = malloc(n * sizeof *it->box);
    it->flags = malloc(n * sizeof *it->flags);
    it->count = 0;
    if (it->face == NULL || it->box == NULL || it->flags == NULL)
        return ISECT_E_NOMEM;
    for (int64_t f = 0; f < nf; f++) {
        const int32_t *corner = m->idx + mesh_face_start(m, f);
        int size = mesh_face_size(m, f);
        int64_t k = it->count;
        if (size == 3) {
            if (triangle_degenerate(mesh_vertex(m, corner[0]), mesh_vertex(m, corner[1]),
                                         mesh_vertex(m, corner[2]))) {
                m->degenerate_faces++;
                continue;
            }
            it->flags[k] = 0;
        } else {
            if (!polygon_plane(m->verts, corner, size, &m->planes[f])) {
                m->degenerate_faces++;
                continue;
            }
            it->flags[k] = BVH_FLAG_LOOSE_T;
        }
        double lo[3], hi[3];
        memcpy(lo, mesh_vertex(m, corner[0]), sizeof lo);
        memcpy(hi, lo, sizeof hi);
        for (int i = 1; i < size; i++) {
            const double *p = mesh_vertex(m, corner[i]);
            for (int a = 0; a < 3; a++) {
                lo[a] = p[a] < lo[a] ? p[a] : lo[a];
                hi[a] = p[a] > hi[a] ? p[a] : hi[a];
            }
        }
        bvh_box_from_double(lo, hi, it->box[k]);
        it->face[k] = (int32_t)f;
        it->count++;
    }
    return ISECT_OK;
}

static int mesh_build(isect_mesh *m)
{
    for (int64_t i = 0; i < 3 * m->vertex_count; i++) {
        double a = fabs(m->verts[i]);
        m->coord_bound = a > m->coord_bound ? a : m->coord_bound;
    }

    face_items it;
    int status = face_items_make(m, &it);
    int32_t *order = NULL;
    if (status == ISECT_OK) {
        order = malloc((size_t)(it.count > 0 ? it.count : 1) * sizeof *order);
        status = order == NULL ? ISECT_E_NOMEM
                               : bvh_build((const float (*)[6])it.box, it.flags, it.count,
                                           BVH_MAX_LEAF, order, &m->tree);
    }
    if (status == ISECT_OK) {
        m->prims = malloc((size_t)(it.count > 0 ? it.count : 1) * sizeof *m->prims);
        if (m->prims == NULL)
            status = ISECT_E_NOMEM;
    }
    if (status == ISECT_OK) {
        m->prim_count = it.count;
        for (int64_t i = 0; i < it.count; i++) {
            int32_t item = order[i], f = it.face[item];
            mesh_prim *p = &m->prims[i];
            const int32_t *corner = m->idx + mesh_face_start(m, f);
            p->face = f;
            p->nverts = mesh_face_size(m, f);
            if (p->nverts == 3) {
                for (int c = 0; c < 3; c++)
                    memcpy(p->v + 3 * c, mesh_vertex(m, corner[c]), 3 * sizeof(double));
                /* The plane the exact test would compute on every hit. */
                int nonzero;
                if (!triangle_plane(p->v, p->v + 3, p->v + 6, p->n, &nonzero))
                    memset(p->n, 0, sizeof p->n);
            } else {
                memset(p->v, 0, sizeof p->v);
                memset(p->n, 0, sizeof p->n);
            }
        }
    }
    free(order);
    face_items_free(&it);
    if (status != ISECT_OK)
        return status;

    int closed = 0, oriented = 0;
    status = mesh_edges_closed(m, &closed, &oriented);
    m->closed = closed;
    m->oriented = oriented;
    return status;
}

ISECT_API int isect_mesh_create(const double *verts, int64_t nv, const int32_t *idx,
                                const int64_t *offsets, int64_t nf, isect_mesh **out)
{
    if (out == NULL)
        return ISECT_E_ARG;
    *out = NULL;
    int status = mesh_args_check(verts, nv, idx, offsets, nf);
    if (status != ISECT_OK)
        return status;

    isect_mesh *m = calloc(1, sizeof *m);
    if (m == NULL)
        return ISECT_E_NOMEM;
    m->vertex_count = nv;
    m->face_count = nf;
    int64_t corners = offsets != NULL ? offsets[nf] : 3 * nf;
    m->verts = malloc((size_t)(nv > 0 ? 3 * nv : 1) * sizeof *m->verts);
    m->idx = malloc((size_t)(corners > 0 ? corners : 1) * sizeof *m->idx);
    if (offsets != NULL) {
        m->offsets = malloc((size_t)(nf + 1) * sizeof *m->offsets);
        m->planes = calloc((size_t)(nf > 0 ? nf : 1), sizeof *m->planes);
    }
    if (m->verts == NULL || m->idx == NULL
        || (offsets != NULL && (m->offsets == NULL || m->planes == NULL))) {
        isect_mesh_destroy(m);
        return ISECT_E_NOMEM;
    }
    if (nv > 0)
        memcpy(m->verts, verts, (size_t)(3 * nv) * sizeof *m->verts);
    if (corners > 0)
        memcpy(m->idx, idx, (size_t)corners * sizeof *m->idx);
    if (offsets != NULL)
        memcpy(m->offsets, offsets, (size_t)(nf + 1) * sizeof *m->offsets);

    status = mesh_build(m);
    if (status != ISECT_OK) {
        isect_mesh_destroy(m);
        return status;
    }
    *out = m;
    return ISECT_OK;
}

ISECT_API void isect_mesh_destroy(isect_mesh *mesh)
{
    if (mesh == NULL)
        return;
    free(mesh->verts);
    free(mesh->idx);
    free(mesh->offsets);
    free(mesh->prims);
    free(mesh->planes);
    bvh_free(&mesh->tree);
    free(mesh);
}

ISECT_API int64_t isect_mesh_bytes(const isect_mesh *mesh)
{
    if (mesh == NULL)
        return ISECT_E_ARG;
    int64_t corners = mesh->offsets != NULL ? mesh->offsets[mesh->face_count]
                                            : 3 * mesh->face_count;
    int64_t bytes = (int64_t)sizeof *mesh;
    bytes += 3 * mesh->vertex_count * (int64_t)sizeof(double);
    bytes += corners * (int64_t)sizeof(int32_t);
    if (mesh->offsets != NULL)
        bytes += (mesh->face_count + 1) * (int64_t)sizeof(int64_t);
    bytes += mesh_traversal_bytes(mesh);
    if (mesh->planes != NULL)
        bytes += mesh->face_count * (int64_t)sizeof *mesh->planes;
    return bytes;
}

int mesh_is_closed(const isect_mesh *m)
{
    return m->closed;
}

int mesh_is_oriented(const isect_mesh *m)
{
    return m->oriented;
}

int mesh_check(const isect_shape *s)
{
    /* The mesh was validated when it was created and cannot change; the
     * descriptor's flags are its containment rule. */
    int rule = s->flags;
    return rule == ISECT_EVEN_ODD || rule == ISECT_NONZERO || rule == ISECT_WINDING
         ? ISECT_OK : ISECT_E_ARG;
}

int mesh_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    const isect_mesh *m = s->mesh;
    const int32_t *corners = m->idx + mesh_face_start(m, prim);
    int n = mesh_face_size(m, prim);
    if (n == 3) {
        const double *a = mesh_vertex(m, corners[0]), *b = mesh_vertex(m, corners[1]);
        const double *c = mesh_vertex(m, corners[2]);
        return collinear3(a, b, c) ? 1 : -orient3_sign(a, b, c, p);
    }
    return polygon_plane_sign(m->verts, corners, n, p, 1);
}

int mesh_tangent_side(const isect_shape *s, const double d[3], int32_t prim)
{
    const isect_mesh *m = s->mesh;
    const int32_t *corners = m->idx + mesh_face_start(m, prim);
    return polygon_plane_sign(m->verts, corners, mesh_face_size(m, prim), d, 0);
}
