/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh.h — the mesh object and what its files share: mesh.c (creation,
 * validation, per-face data), mesh_query.c (ray queries over the BVH),
 * mesh_contains.c (containment), mesh_check.c (topology report),
 * winding.c (generalized winding numbers), and the queries the
 * dispatcher (api/shape.c) calls.
 *
 * Faces. A face of 3 vertices is a triangle, tested by triangle_hit;
 * a face of more is a planar polygon, tested by polygon_hit_plane_framed
 * under ISECT_EVEN_ODD with its plane precomputed once. These are the
 * library's one implementation of the exact, perturbed ray/face decision
 * (planar.h), so a mesh is watertight for exactly the reasons a set of
 * separate triangles and polygons is. Faces of zero area (decided exactly)
 * are kept in the mesh, counted by the report, and left out of the BVH:
 * they are never hit.
 */
#ifndef ISECT_MESH_H
#define ISECT_MESH_H

#include "core/bvh.h"
#include "prim/planar.h"

/* One face in BVH leaf order, with what the hot loop needs inline. 104
 * bytes. */
typedef struct mesh_prim {
    double  v[9];   /* triangle: its vertices a, b, c (copies, bit-identical to
                       the mesh's vertex array); polygon: 0 (its plane is in
                       the mesh's planes[face]) */
    double  n[3];   /* triangle: its triangle_plane normal, or 0 0 0 when that
                       has none (a face the exact test never hits); polygon: 0 */
    int32_t face;   /* face index (the hit's prim) */
    int32_t nverts; /* 3: triangle; > 3: polygon, vertices through the face's idx */
} mesh_prim;

struct isect_mesh {
    int64_t    vertex_count;
    int64_t    face_count;
    double    *verts;            /* [vertex_count][3], the caller's copy */
    int32_t   *idx;              /* face corners: 3 per triangle, or offsets[face_count] */
    int64_t   *offsets;          /* NULL for a triangle mesh, else [face_count + 1] */
    mesh_prim *prims;            /* the non-degenerate faces, in BVH leaf order */
    poly_plane *planes;          /* polygon meshes: each face's plane (polygon_plane,
                                    bit for bit the lone polygon's), by face index;
                                    NULL for a triangle mesh */
    int64_t    prim_count;
    int64_t    degenerate_faces; /* faces of zero area (not in the BVH) */
    bvh        tree;
    double     coord_bound;      /* max |coordinate| over all vertices: scales the
                                    traversal's error bounds */
    int32_t    closed;           /* every edge used by exactly two faces */
    int32_t    oriented;         /* closed, and those two uses run opposite ways */
};

/* Face f: its first corner in idx and its vertex count. */
static inline int64_t mesh_face_start(const isect_mesh *m, int64_t f)
{
    return m->offsets != NULL ? m->offsets[f] : 3 * f;
}
static inline int mesh_face_size(const isect_mesh *m, int64_t f)
{
    return m->offsets != NULL ? (int)(m->offsets[f + 1] - m->offsets[f]) : 3;
}
static inline const double *mesh_vertex(const isect_mesh *m, int32_t i)
{
    return m->verts + 3 * (int64_t)i;
}

/* The memory a traversal reads: the BVH nodes and the prims. */
static inline int64_t mesh_traversal_bytes(const isect_mesh *m)
{
    return m->tree.node_count * (int64_t)sizeof(bvh_node)
         + m->prim_count * (int64_t)sizeof(mesh_prim);
}

/* An undirected edge use, for the topology passes: key = lo * vertex_count
 * + hi for the two vertex indices lo < hi, the face, and whether the face
 * runs hi -> lo. */
typedef struct mesh_edge_use {
    uint64_t key;
    uint32_t face;
    uint32_t reversed;
} mesh_edge_use;

/* Every edge use of every face (self-loops a -> a skipped), sorted by key
 * (face order within one key): *uses (caller frees) and *count. ISECT_OK
 * or ISECT_E_NOMEM. */
int mesh_edge_uses(const isect_mesh *m, mesh_edge_use **uses, int64_t *count);

/* The dispatcher's entries (shape.c family table). The ray is valid and in
 * object space; [tmin, tmax], ISECT_CULL_BACK (faces are thin surfaces) and
 * ISECT_ANY_HIT are applied here; hits are sorted by (t, face index). */
int     mesh_check(const isect_shape *s);
int64_t mesh_hits_all(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                      isect_hit *hits, int64_t cap);
int     mesh_hit_first(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                       isect_hit *out);
int     mesh_contains(const isect_shape *s, const double p[3]);
/* The family's first_batch (isect_intersect_batch for a mesh): the closest
 * (any, under ISECT_ANY_HIT) hit of each world-space ray into closest[i],
 * ISECT_INVALID / ISECT_MISS records as the batch loop writes them;
 * returns the number of rays hit. Bit for bit the per-ray loop over
 * mesh_hit_first, several traversals interleaved to overlap their cache
 * misses. */
int64_t mesh_hit_first_batch(const isect_shape *s, const isect_ray *rays, int64_t n,
                             const isect_params *prm, isect_hit *closest);
/* The exact side of p against face prim's plane (prim/prim.h): a
 * triangle's by orient3, a polygon's by polygon_plane_sign. */
int     mesh_side_test(const isect_shape *s, const double p[3], int32_t prim);
/* The exact side of the direction d against face prim's plane (prim/prim.h:
 * X_tangent_side). */
int     mesh_tangent_side(const isect_shape *s, const double d[3], int32_t prim);
/* The signed count of the exact crossings of the perturbed +x ray from p
 * (mesh_contains.c: each crossing +1 where the ray leaves through a face's
 * front, -1 where it enters): for a closed, consistently oriented mesh the
 * winding number of p, exactly. Returns 1 without a count when p lies on
 * the surface (a face, edge or vertex), else 0. */
int     mesh_crossing_count(const isect_mesh *m, const double p[3], int64_t *count);

/* Generalized winding numbers (winding.c, which states the numerics and
 * the error bounds): by direct summation over the faces; over a tree of
 * far-field clusters built per query batch, within `accuracy` plus the
 * directly summed faces' bounds; and the value the library reports, exact
 * for a closed, oriented mesh off its surface, else direct. *bound (may
 * be NULL) receives the bound of |w - exact|. */
double  mesh_winding_direct(const isect_mesh *m, const double q[3], double *bound);
/* The same over the faces mapped to world space by x, at the world point q
 * (for a transform that is not a similarity). */
double  mesh_winding_direct_world(const isect_mesh *m, const isect_xform *x, const double q[3]);
typedef struct mesh_winding_tree mesh_winding_tree;
int     mesh_winding_tree_build(const isect_mesh *m, mesh_winding_tree **out);
void    mesh_winding_tree_free(mesh_winding_tree *t);
double  mesh_winding_far(const isect_mesh *m, const mesh_winding_tree *t, const double q[3],
                         double accuracy, double *bound);
double  mesh_generalized_winding(const isect_mesh *m, const double q[3], double *bound);

/* 1 when the mesh is closed (contains applies). */
int     mesh_is_closed(const isect_mesh *m);
/* 1 when it is closed and consistently oriented (its winding numbers are
 * the signed crossing counts). */
int     mesh_is_oriented(const isect_mesh *m);

#endif /* ISECT_MESH_H */
