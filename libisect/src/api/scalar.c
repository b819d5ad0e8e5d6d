/* SPDX-License-Identifier: Apache-2.0 */
/*
 * scalar.c — the public per-primitive entry points isect_ray_plane ...
 * isect_ray_quadric: each packs its arguments into an isect_shape
 * descriptor and runs it through isect_intersect (shape.c), so validation,
 * filtering, sorting and the snprintf-style copy are written once.
 */
#include "api/dispatch.h"

#include <string.h>

ISECT_API int isect_ray_aabb(const isect_ray *ray, const double lo[3], const double hi[3],
                             const isect_opts *opts, isect_hit *hits, int cap)
{
    if (lo == NULL || hi == NULL)
        return ISECT_E_ARG;
    double data[6] = { lo[0], lo[1], lo[2], hi[0], hi[1], hi[2] };
    isect_shape s = { ISECT_AABB, 0, 0, 0, data, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_convex(const isect_ray *ray, const double *planes, int m,
                               const isect_opts *opts, isect_hit *hits, int cap)
{
    isect_shape s = { ISECT_CONVEX, m, 0, 0, planes, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_cylinder(const isect_ray *ray, const double p0[3], const double p1[3],
                                 double r, int capped, const isect_opts *opts,
                                 isect_hit *hits, int cap)
{
    if (p0 == NULL || p1 == NULL)
        return ISECT_E_ARG;
    double data[7] = { p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], r };
    /* capped goes through as the flags word, so cylinder_check rejects
     * anything but 0 and ISECT_CAPPED (1). */
    isect_shape s = { ISECT_CYLINDER, 0, (int32_t)capped, 0, data, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_cylinder_inf(const isect_ray *ray, const double p[3],
                                     const double axis[3], double r, const isect_opts *opts,
                                     isect_hit *hits, int cap)
{
    if (p == NULL || axis == NULL)
        return ISECT_E_ARG;
    double data[7] = { p[0], p[1], p[2], axis[0], axis[1], axis[2], r };
    isect_shape s = { ISECT_CYLINDER_INF, 0, 0, 0, data, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_plane(const isect_ray *ray, const double n[3], double d,
                              const isect_opts *opts, isect_hit *hits, int cap)
{
    if (n == NULL)
        return ISECT_E_ARG;
    double data[4] = { n[0], n[1], n[2], d };
    isect_shape s = { ISECT_PLANE, 0, 0, 0, data, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_polygon(const isect_ray *ray, const double *v, int n, int rule,
                                const isect_opts *opts, isect_hit *hits, int cap)
{
    isect_shape s = { ISECT_POLYGON, n, rule, 0, v, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_quadric(const isect_ray *ray, const double q[10],
                                const isect_opts *opts, isect_hit *hits, int cap)
{
    if (q == NULL)
        return ISECT_E_ARG;
    isect_shape s = { ISECT_QUADRIC, 0, 0, 0, q, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_sphere(const isect_ray *ray, const double c[3], double r,
                               const isect_opts *opts, isect_hit *hits, int cap)
{
    if (c == NULL)
        return ISECT_E_ARG;
    double data[4] = { c[0], c[1], c[2], r };
    isect_shape s = { ISECT_SPHERE, 0, 0, 0, data, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_ellipsoid(const isect_ray *ray, const double c[3], const double radii[3],
                                  const isect_opts *opts, isect_hit *hits, int cap)
{
    if (c == NULL || radii == NULL)
        return ISECT_E_ARG;
    double data[6] = { c[0], c[1], c[2], radii[0], radii[1], radii[2] };
    isect_shape s = { ISECT_ELLIPSOID, 0, 0, 0, data, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}

ISECT_API int isect_ray_triangle(const isect_ray *ray, const double a[3], const double b[3],
                                 const double c[3], const isect_opts *opts,
                                 isect_hit *hits, int cap)
{
    /* A NULL vertex leaves data NULL, which the dispatcher reports as
     * ISECT_E_ARG in its usual order of checks. */
    double abc[9];
    const double *data = NULL;
    if (a != NULL && b != NULL && c != NULL) {
        memcpy(abc, a, 3 * sizeof *abc);
        memcpy(abc + 3, b, 3 * sizeof *abc);
        memcpy(abc + 6, c, 3 * sizeof *abc);
        data = abc;
    }
    isect_shape s = { ISECT_TRIANGLE, 0, 0, 0, data, NULL, NULL };
    return isect_intersect(&s, ray, opts, hits, cap);
}
