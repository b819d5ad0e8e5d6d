/*
 * shape.c — one dispatcher over the isect_shape descriptor.
 *
 * Every scalar function, isect_intersect, isect_contains and the batch loops
 * come through here, so argument checking, the object-space transform, the
 * [tmin, tmax] filter, back-face culling, ordering and the snprintf-style copy
 * exist once. The per-type work is the family table below.
 */
#include "isect_internal.h"

#include <string.h>

enum solidity {
    SURFACE_THIN,            /* plane, triangle, polygon */
    SURFACE_SOLID,           /* has an inside: contains() works, hits are ENTER/EXIT */
    SURFACE_SOLID_IF_CAPPED  /* finite cylinder: a solid only with ISECT_CAPPED */
};

struct shape_family {
    int (*check)(const isect_shape *s);
    int (*hits)(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                isect_hit out[ISECT_MAX_HITS]);
    int (*contains)(const isect_shape *s, const double p[3]);
    enum solidity solidity;
    int uses_n;     /* isect_shape.n carries a count */
    int uses_flags; /* isect_shape.flags carries a rule or ISECT_CAPPED */
};

#define FAMILY(X, solidity, uses_n, uses_flags) \
    { X##_check, X##_hits, X##_contains, solidity, uses_n, uses_flags }
#define THIN_FAMILY(X, uses_n, uses_flags) \
    { X##_check, X##_hits, NULL, SURFACE_THIN, uses_n, uses_flags }

/* Indexed by shape type; entry 0 and ISECT_MESH (not yet built) are empty. */
static const shape_family families[ISECT_MESH + 1] = {
    [ISECT_PLANE]        = THIN_FAMILY(plane, 0, 0),
    [ISECT_SPHERE]       = FAMILY(sphere, SURFACE_SOLID, 0, 0),
    [ISECT_AABB]         = FAMILY(aabb, SURFACE_SOLID, 0, 0),
    [ISECT_TRIANGLE]     = THIN_FAMILY(triangle, 0, 0),
    [ISECT_POLYGON]      = THIN_FAMILY(polygon, 1, 1),
    [ISECT_CONVEX]       = FAMILY(convex, SURFACE_SOLID, 1, 0),
    [ISECT_CYLINDER]     = FAMILY(cylinder, SURFACE_SOLID_IF_CAPPED, 0, 1),
    [ISECT_CYLINDER_INF] = FAMILY(cylinder_inf, SURFACE_SOLID, 0, 0),
    [ISECT_ELLIPSOID]    = FAMILY(ellipsoid, SURFACE_SOLID, 0, 0),
    [ISECT_QUADRIC]      = FAMILY(quadric, SURFACE_SOLID, 0, 0),
};

int shape_is_solid(const shape_family *f, const isect_shape *s)
{
    return f->solidity == SURFACE_SOLID
        || (f->solidity == SURFACE_SOLID_IF_CAPPED && (s->flags & ISECT_CAPPED));
}

const shape_family *shape_prepare(const isect_shape *s, int *status)
{
    *status = ISECT_E_ARG;
    if (s == NULL || s->type <= 0 || s->type > ISECT_MESH || s->reserved != 0)
        return NULL;
    const shape_family *f = &families[s->type];
    if (f->check == NULL || s->data == NULL || s->mesh != NULL)
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

int shape_ray_hits(const shape_family *f, const isect_shape *s, const isect_ray *ray,
                   const isect_params *prm, isect_hit out[ISECT_MAX_HITS])
{
    isect_ray object_ray;
    const isect_ray *r = ray;
    if (s->xform != NULL) {
        /* A huge inverse can overflow an otherwise fine ray. */
        xform_ray_unchecked(s->xform, ray, &object_ray);
        int status = ray_check(&object_ray);
        if (status != ISECT_OK)
            return status;
        r = &object_ray;
    }
    int count = f->hits(s, r, prm, out);
    /* t is the same in both frames (dir is mapped, not renormalised), so the
     * range filter and the ordering can run before going back to world space. */
    count = hits_finish(out, count, r, prm, !shape_is_solid(f, s));
    if (s->xform != NULL)
        xform_hits_unchecked(s->xform, out, count);
    return count;
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

int scalar_intersect(const isect_shape *s, const isect_ray *ray, const isect_opts *opts,
                     isect_hit *hits, int cap)
{
    if (ray == NULL || cap < 0 || (hits == NULL && cap > 0))
        return ISECT_E_ARG;
    isect_params prm;
    int status = params_from_opts(opts, &prm);
    if (status != ISECT_OK)
        return status;
    const shape_family *f = shape_prepare(s, &status);
    if (f == NULL)
        return status;
    status = ray_check(ray);
    if (status != ISECT_OK)
        return status;
    isect_hit found[ISECT_MAX_HITS];
    int count = shape_ray_hits(f, s, ray, &prm, found);
    if (count > 0 && cap > 0)
        memcpy(hits, found, (size_t)(count < cap ? count : cap) * sizeof *hits);
    return count;
}

ISECT_API int isect_intersect(const isect_shape *shape, const isect_ray *ray,
                              const isect_opts *opts, isect_hit *hits, int cap)
{
    return scalar_intersect(shape, ray, opts, hits, cap);
}

ISECT_API int isect_contains(const isect_shape *shape, const double p[3])
{
    int status;
    const shape_family *f = shape_prepare(shape, &status);
    if (f == NULL)
        return status;
    if (p == NULL || !shape_is_solid(f, shape))
        return ISECT_E_ARG;
    if (!all_finite(p, 3))
        return ISECT_E_NONFINITE;
    return shape_point_inside(f, shape, p);
}
