/* SPDX-License-Identifier: Apache-2.0 */
/*
 * shape.c — one dispatcher over the isect_shape descriptor.
 *
 * Every scalar function, isect_intersect, isect_contains and the batch loops
 * come through here, so argument checking, the object-space transform, the
 * [tmin, tmax] filter, back-face culling, ordering and the snprintf-style copy
 * exist once. The per-type work is the family table below.
 */
#include "api/dispatch.h"
#include "mesh/mesh.h"

#include <limits.h>
#include <string.h>

enum solidity {
    SURFACE_THIN,            /* plane, triangle, polygon */
    SURFACE_SOLID,           /* has an inside: contains() works, hits are ENTER/EXIT */
    SURFACE_SOLID_IF_CAPPED, /* finite cylinder: a solid only with ISECT_CAPPED */
    SURFACE_SOLID_IF_CLOSED  /* mesh: a solid only when closed (no boundary or
                                non-manifold edge) */
};

typedef int64_t (*hits_all_fn)(const shape_family *f, const isect_shape *s,
                               const isect_ray *ray, const isect_params *prm,
                               isect_hit *hits, int64_t cap);
typedef int (*hit_first_fn)(const shape_family *f, const isect_shape *s,
                            const isect_ray *ray, const isect_params *prm, isect_hit *out);

struct shape_family {
    int (*check)(const isect_shape *s);
    /* Analytic shapes: every hit of the line, at most ISECT_MAX_HITS. */
    int (*hits)(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                isect_hit out[ISECT_MAX_HITS]);
    int (*contains)(const isect_shape *s, const double p[3]);
    /* All hits in range, sorted, the first cap written; and the first alone. */
    hits_all_fn hits_all;
    hit_first_fn hit_first;
    /* Optional: isect_intersect_batch's closest (any) hits of many rays at
     * once, bit for bit the records and count of the per-ray loop over
     * hit_first (batch.c); NULL: that loop. */
    first_batch_fn first_batch;
    enum solidity solidity;
    int uses_n;     /* isect_shape.n carries a count */
    int uses_flags; /* isect_shape.flags carries a rule or ISECT_CAPPED */
    /* The exact side of an object-space point (prim/prim.h). */
    int (*side)(const isect_shape *s, const double p[3], int32_t prim);
    /* The exact side of an object-space direction against a flat prim's
     * plane (prim/prim.h); NULL: the family's surfaces are curved. */
    int (*tangent_side)(const isect_shape *s, const double d[3], int32_t prim);
};

/* The two query paths of the analytic shapes, over their bounded kernel. */
static int64_t analytic_hits_all(const shape_family *f, const isect_shape *s,
                                 const isect_ray *ray, const isect_params *prm,
                                 isect_hit *hits, int64_t cap)
{
    isect_hit found[ISECT_MAX_HITS];
    int count = f->hits(s, ray, prm, found);
    count = hits_finish(found, count, ray, prm, !shape_is_solid(f, s));
    if (count > 0 && cap > 0)
        memcpy(hits, found, (size_t)(count < cap ? count : cap) * sizeof *hits);
    return count;
}

/* hits.c's order: by t, ties in kernel order (the exact order). */
static inline int hit_before_first(const isect_hit *a, const isect_hit *b)
{
    return a->t < b->t;
}

/*
 * The first record of analytic_hits_all without sorting or copying the
 * rest. hits_finish keeps the same hits (same range test, same culling) in
 * kernel order and insertion-sorts them, which is stable under the strict
 * weak order hit_before (kept t are never NaN); so its first record is the
 * earliest kernel record among those no other kept record precedes. The
 * scan below picks exactly that one (it replaces only on strictly before)
 * and copies that very record: bit for bit the same.
 */
static int analytic_hit_first(const shape_family *f, const isect_shape *s,
                              const isect_ray *ray, const isect_params *prm, isect_hit *out)
{
    isect_hit found[ISECT_MAX_HITS];
    int count = f->hits(s, ray, prm, found);
    int cull_exit = count > 0 && (prm->flags & ISECT_CULL_BACK) && !shape_is_solid(f, s);
    int best = -1;
    for (int i = 0; i < count; i++) {
        /* The comparison is false for NaN, so a NaN t can never escape. */
        if (!(found[i].t >= ray->tmin && found[i].t <= ray->tmax))
            continue;
        if (cull_exit && found[i].kind == ISECT_EXIT)
            continue;
        if (best < 0 || hit_before_first(&found[i], &found[best]))
            best = i;
    }
    if (best < 0)
        return 0;
    *out = found[best];
    return 1;
}

#define FAMILY(X, solidity, uses_n, uses_flags, tangent)                        \
    { X##_check, X##_hits, X##_contains, analytic_hits_all, analytic_hit_first, \
      NULL, solidity, uses_n, uses_flags, X##_side_test, tangent }
#define THIN_FAMILY(X, uses_n, uses_flags)                                      \
    { X##_check, X##_hits, NULL, analytic_hits_all, analytic_hit_first,         \
      NULL, SURFACE_THIN, uses_n, uses_flags, X##_side_test, X##_tangent_side }

/* The mesh's queries (mesh/mesh.h) under the family table's signatures. */
static int64_t mesh_family_hits_all(const shape_family *f, const isect_shape *s,
                                    const isect_ray *ray, const isect_params *prm,
                                    isect_hit *hits, int64_t cap)
{
    (void)f;
    return mesh_hits_all(s, ray, prm, hits, cap);
}
static int mesh_family_hit_first(const shape_family *f, const isect_shape *s,
                                 const isect_ray *ray, const isect_params *prm, isect_hit *out)
{
    (void)f;
    return mesh_hit_first(s, ray, prm, out);
}
static int64_t mesh_family_first_batch(const shape_family *f, const isect_shape *s,
                                       const isect_ray *rays, int64_t n,
                                       const isect_params *prm, isect_hit *closest)
{
    (void)f;
    return mesh_hit_first_batch(s, rays, n, prm, closest);
}

/* Indexed by shape type; entry 0 is empty so a zeroed descriptor is rejected. */
static const shape_family families[ISECT_MESH + 1] = {
    [ISECT_PLANE]        = THIN_FAMILY(plane, 0, 0),
    [ISECT_SPHERE]       = FAMILY(sphere, SURFACE_SOLID, 0, 0, NULL),
    /* a box's normals are exactly axis vectors: the hit's normal decides */
    [ISECT_AABB]         = FAMILY(aabb, SURFACE_SOLID, 0, 0, NULL),
    [ISECT_TRIANGLE]     = THIN_FAMILY(triangle, 0, 0),
    [ISECT_POLYGON]      = THIN_FAMILY(polygon, 1, 1),
    [ISECT_CONVEX]       = FAMILY(convex, SURFACE_SOLID, 1, 0, convex_tangent_side),
    [ISECT_CYLINDER]     = FAMILY(cylinder, SURFACE_SOLID_IF_CAPPED, 0, 1, NULL),
    [ISECT_CYLINDER_INF] = FAMILY(cylinder_inf, SURFACE_SOLID, 0, 0, NULL),
    [ISECT_ELLIPSOID]    = FAMILY(ellipsoid, SURFACE_SOLID, 0, 0, NULL),
    [ISECT_QUADRIC]      = FAMILY(quadric, SURFACE_SOLID, 0, 0, NULL),
    [ISECT_MESH]         = { mesh_check, NULL, mesh_contains, mesh_family_hits_all,
                             mesh_family_hit_first, mesh_family_first_batch,
                             SURFACE_SOLID_IF_CLOSED, 0, 1, mesh_side_test,
                             mesh_tangent_side },
};

int shape_is_solid(const shape_family *f, const isect_shape *s)
{
    return f->solidity == SURFACE_SOLID
        || (f->solidity == SURFACE_SOLID_IF_CAPPED && (s->flags & ISECT_CAPPED))
        || (f->solidity == SURFACE_SOLID_IF_CLOSED && mesh_is_closed(s->mesh));
}

int shape_can_contain(const shape_family *f, const isect_shape *s)
{
    if (s->type != ISECT_MESH)
        return shape_is_solid(f, s);
    /* a mesh, by its rule (isect.h: isect_contains) */
    return s->flags == ISECT_WINDING
        || (s->flags == ISECT_NONZERO ? mesh_is_oriented(s->mesh) : mesh_is_closed(s->mesh));
}

const shape_family *shape_prepare(const isect_shape *s, int *status)
{
    *status = ISECT_E_ARG;
    if (s == NULL || s->type <= 0 || s->type > ISECT_MESH || s->reserved != 0)
        return NULL;
    const shape_family *f = &families[s->type];
    if (f->check == NULL)
        return NULL;
    int is_mesh = s->type == ISECT_MESH;
    if ((s->data == NULL) != is_mesh || (s->mesh != NULL) != is_mesh)
        return NULL;
    if ((!f->uses_n && s->n != 0) || (!f->uses_flags && s->flags != 0))
        return NULL;
    if (s->xform != NULL && (!all_finite(s->xform->m, 16) || !all_finite(s->xform->inv, 16))) {
        *status = ISECT_E_NONFINITE;
        return NULL;
    }
    *status = f->check(s);
    return *status == ISECT_OK ? f : NULL;
}

const shape_family *query_prepare(const isect_shape *s, const isect_opts *opts,
                                  isect_params *prm, int *status)
{
    *status = params_from_opts(opts, prm);
    return *status == ISECT_OK ? shape_prepare(s, status) : NULL;
}

first_batch_fn shape_first_batch(const shape_family *f)
{
    return f->first_batch;
}

/* t is the same in both frames (dir is mapped, not renormalised), so range
 * filtering and ordering happen in object space; only the written records
 * go back to world space. */
int64_t shape_ray_hits(const shape_family *f, const isect_shape *s, const isect_ray *ray,
                       const isect_params *prm, isect_hit *hits, int64_t cap)
{
    isect_ray tmp;
    const isect_ray *r;
    int status = shape_object_ray(s, ray, &tmp, &r);
    if (status != ISECT_OK)
        return status;
    int64_t count = f->hits_all(f, s, r, prm, hits, cap);
    if (count > 0)
        shape_hits_to_world(s, hits, count < cap ? count : cap);
    return count;
}

int shape_ray_first(const shape_family *f, const isect_shape *s, const isect_ray *ray,
                    const isect_params *prm, isect_hit *out)
{
    isect_ray tmp;
    const isect_ray *r;
    int status = shape_object_ray(s, ray, &tmp, &r);
    if (status != ISECT_OK)
        return status;
    int found = f->hit_first(f, s, r, prm, out);
    if (found > 0)
        shape_hits_to_world(s, out, 1);
    return found;
}

int shape_point_inside(const shape_family *f, const isect_shape *s, const double p[3])
{
    if (s->xform == NULL)
        return f->contains(s, p);
    double q[3];
    xform_point_to_object(s->xform, p, q);
    if (!all_finite(q, 3))
        return ISECT_E_NONFINITE;
    return f->contains(s, q);
}

/* fn (a side hook) at the object-space image of the world point (is_point)
 * or direction v, or ISECT_E_NONFINITE if the transform takes it out of
 * the finite doubles. */
static int object_side(const isect_shape *s, const double v[3], int is_point, int32_t prim,
                       int (*fn)(const isect_shape *, const double *, int32_t))
{
    if (s->xform == NULL)
        return fn(s, v, prim);
    double q[3];
    if (is_point)
        xform_point_to_object(s->xform, v, q);
    else
        xform_vector_to_object(s->xform, v, q);
    if (!all_finite(q, 3))
        return ISECT_E_NONFINITE;
    return fn(s, q, prim);
}

int shape_point_side(const shape_family *f, const isect_shape *s, const double p[3],
                     int32_t prim)
{
    return object_side(s, p, 1, prim, f->side);
}

int shape_direction_side(const shape_family *f, const isect_shape *s, const double d[3],
                         int32_t prim)
{
    return f->tangent_side == NULL ? SIDE_CURVED : object_side(s, d, 0, prim, f->tangent_side);
}

int shape_prim_valid(const isect_shape *s, int32_t prim)
{
    if (s->type == ISECT_MESH)
        return prim >= 0 && prim < s->mesh->face_count;
    return 1;
}

ISECT_API int isect_intersect(const isect_shape *shape, const isect_ray *ray,
                              const isect_opts *opts, isect_hit *hits, int cap)
{
    if (ray == NULL || cap < 0 || (hits == NULL && cap > 0))
        return ISECT_E_ARG;
    isect_params prm;
    int status;
    const shape_family *f = query_prepare(shape, opts, &prm, &status);
    if (f == NULL)
        return status;
    status = ray_check(ray);
    if (status != ISECT_OK)
        return status;
    int64_t count = shape_ray_hits(f, shape, ray, &prm, hits, cap);
    return count > INT_MAX ? INT_MAX : (int)count;
}

ISECT_API int isect_contains(const isect_shape *shape, const double p[3])
{
    int status;
    const shape_family *f = shape_prepare(shape, &status);
    if (f == NULL)
        return status;
    if (p == NULL || !shape_can_contain(f, shape))
        return ISECT_E_ARG;
    if (!all_finite(p, 3))
        return ISECT_E_NONFINITE;
    return shape_point_inside(f, shape, p);
}
