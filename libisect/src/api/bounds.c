/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bounds.c — isect_shape_bounds: a conservative world-space box of any
 * shape (the top level of a scene's BVH culls rays by it).
 *
 * Object space. Boxes follow the data layouts of isect.h: a sphere or an
 * ellipsoid is its centre plus and minus its radii; a finite cylinder lies
 * within the radius of its axis segment; triangles, polygons and meshes
 * within their vertices' extent; a box is itself. Sums are rounded outward
 * (one ulp down from a rounded lower end, up from an upper one), so the
 * box holds the exact shape (degenerate shapes, never hit, keep their
 * geometric box; a mesh without vertices has the empty box, lo = +inf and
 * hi = -inf). Planes, infinite cylinders and general
 * quadrics are unbounded; a convex polyhedron is reported unbounded too
 * (its extent would need its vertices, an LP per axis).
 *
 * Polygons. A polygon's hits lie on its plane (Newell's normal through the
 * vertex centroid) where a ray passes through its outline as seen along
 * the ray (the sheared-frame test). For exactly coplanar vertices that is
 * the polygon itself: its vertices' box, widened by 2^-40 of their
 * magnitude for the rounding of the reported crossings. Vertices off that
 * plane by any amount h make the outline a band of height ~h seen edge on,
 * which a ray nearly parallel to the plane passes through while meeting
 * the plane arbitrarily far away: such a polygon (and a mesh with such a
 * face) is unbounded. Coplanarity is decided exactly (polygon_plane_sign).
 *
 * World space. For x = L y + T and the object box c +- h (c its centre, h
 * its half extents, both rounded outward so the object box stays inside),
 * the image lies in L c + T +- |L| h. Each of those sums of three or four
 * products is within 4u of the sum of its terms' magnitudes, so the world
 * box is widened by 2^-48 of that sum (generous) plus the smallest normal
 * double, and its ends rounded outward once more. An axis that an
 * unbounded object axis maps into is unbounded.
 */
#include "api/dispatch.h"
#include "mesh/mesh.h"
#include "prim/planar.h"
#include "core/vec3.h"

#include <float.h>

static double down(double x)
{
    return nextafter(x, -INFINITY);
}
static double up(double x)
{
    return nextafter(x, INFINITY);
}

static void box_empty_extend(double lo[3], double hi[3], const double *p, int64_t count)
{
    for (int64_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) {
            double v = p[3 * i + k];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
}

/* c +- r per axis (r[k] >= 0), outward. */
static void box_around(double lo[3], double hi[3], const double c[3], const double r[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = down(c[k] - r[k]);
        hi[k] = up(c[k] + r[k]);
    }
}

/* Extends lo..hi by the polygon v[idx[i]] (idx NULL: v + 3i), n >= 3, and
 * returns 0; or returns 1 when its vertices are not exactly coplanar (then
 * its hits are unbounded: see the top of the file). */
static int polygon_box(const double *v, const int32_t *idx, int n, double lo[3], double hi[3])
{
    double plo[3] = { INFINITY, INFINITY, INFINITY }, phi[3] = { -INFINITY, -INFINITY, -INFINITY };
    double mag = 0.0;
    for (int i = 0; i < n; i++) {
        const double *p = idx != NULL ? v + 3 * (int64_t)idx[i] : v + 3 * (int64_t)i;
        if (polygon_plane_sign(v, idx, n, p, 1) != 0)
            return 1;
        box_empty_extend(plo, phi, p, 1);
        mag = fmax(mag, max_abs3(p));
    }
    /* hit points are the rays' crossings of that plane, rounded */
    double slack = 0x1p-40 * mag + DBL_MIN;
    for (int k = 0; k < 3; k++) {
        lo[k] = fmin(lo[k], down(plo[k] - slack));
        hi[k] = fmax(hi[k], up(phi[k] + slack));
    }
    return 0;
}

static void box_unbounded(double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = -INFINITY;
        hi[k] = INFINITY;
    }
}

/* lo..hi widened by 2^-40 of its largest magnitude: a reported hit point is
 * the rounded crossing, a few ulps off the exact surface. */
static void widen_for_rounding(double lo[3], double hi[3])
{
    double mag = fmax(max_abs3(lo), max_abs3(hi));
    double slack = 0x1p-40 * mag + DBL_MIN;
    for (int k = 0; k < 3; k++) {
        lo[k] = down(lo[k] - slack);
        hi[k] = up(hi[k] + slack);
    }
}

/* The object-space box of a validated shape, and 1 when it is unbounded. */
static int object_box(const isect_shape *s, double lo[3], double hi[3])
{
    const double *d = s->data;
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    switch (s->type) {
    case ISECT_SPHERE: {
        const double r[3] = { d[3], d[3], d[3] };
        box_around(lo, hi, d, r);
        return 0;
    }
    case ISECT_ELLIPSOID: {
        const double r[3] = { fabs(d[3]), fabs(d[4]), fabs(d[5]) };
        box_around(lo, hi, d, r);
        return 0;
    }
    case ISECT_AABB:
        for (int k = 0; k < 3; k++) {
            lo[k] = d[k];
            hi[k] = d[3 + k];
        }
        return 0;
    case ISECT_TRIANGLE:
        box_empty_extend(lo, hi, d, 3);
        return 0;
    case ISECT_POLYGON:
        if (polygon_box(d, NULL, s->n, lo, hi)) {
            box_unbounded(lo, hi);
            return 1;
        }
        return 0;
    case ISECT_CYLINDER: {
        double seg_lo[3] = { INFINITY, INFINITY, INFINITY };
        double seg_hi[3] = { -INFINITY, -INFINITY, -INFINITY };
        box_empty_extend(seg_lo, seg_hi, d, 2);
        for (int k = 0; k < 3; k++) {
            lo[k] = down(seg_lo[k] - d[6]);
            hi[k] = up(seg_hi[k] + d[6]);
        }
        return 0;
    }
    case ISECT_MESH: {
        const isect_mesh *m = s->mesh;
        box_empty_extend(lo, hi, m->verts, m->vertex_count);
        if (m->offsets != NULL) /* polygon faces */
            for (int64_t f = 0; f < m->face_count; f++)
                if (mesh_face_size(m, f) > 3 && polygon_box(m->verts, m->idx + mesh_face_start(m, f),
                                                            mesh_face_size(m, f), lo, hi)) {
                    box_unbounded(lo, hi);
                    return 1;
                }
        return 0;
    }
    default: /* plane, infinite cylinder, quadric, convex */
        box_unbounded(lo, hi);
        return 1;
    }
}

/* The world box of the object box lo..hi under x (see the top). */
static void world_box(const isect_xform *x, double lo[3], double hi[3])
{
    double c[3], h[3];
    int unbounded[3];
    for (int k = 0; k < 3; k++) {
        unbounded[k] = !(isfinite(lo[k]) && isfinite(hi[k]));
        /* a centre within the box and a half extent reaching both ends:
         * |c - lo| and |hi - c| are at most h, rounded up */
        c[k] = unbounded[k] ? 0.0 : 0.5 * lo[k] + 0.5 * hi[k];
        h[k] = unbounded[k] ? 0.0 : up(fmax(up(c[k] - lo[k]), up(hi[k] - c[k])));
    }
    for (int i = 0; i < 3; i++) {
        const double *row = x->m + 4 * i;
        int open = 0;
        double w = row[3], e = 0.0, mag = fabs(row[3]);
        for (int j = 0; j < 3; j++) {
            if (row[j] == 0.0)
                continue;
            open |= unbounded[j];
            w += row[j] * c[j];
            e += fabs(row[j]) * h[j];
            mag += fabs(row[j] * c[j]);
        }
        if (open) {
            lo[i] = -INFINITY;
            hi[i] = INFINITY;
            continue;
        }
        double slack = 0x1p-48 * (mag + e) + DBL_MIN;
        lo[i] = down(w - e - slack);
        hi[i] = up(w + e + slack);
    }
}

ISECT_API int isect_shape_bounds(const isect_shape *shape, double lo[3], double hi[3])
{
    int status;
    const shape_family *f = shape_prepare(shape, &status);
    if (f == NULL)
        return status;
    if (lo == NULL || hi == NULL)
        return ISECT_E_ARG;
    double l[3], h[3];
    int unbounded = object_box(shape, l, h);
    int empty = l[0] > h[0] || l[1] > h[1] || l[2] > h[2]; /* a mesh without vertices */
    if (!unbounded && !empty && shape->type != ISECT_AABB)
        widen_for_rounding(l, h);
    if (shape->xform != NULL && !empty)
        world_box(shape->xform, l, h);
    for (int k = 0; k < 3; k++) {
        lo[k] = l[k];
        hi[k] = h[k];
    }
    return ISECT_OK;
}
