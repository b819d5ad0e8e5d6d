/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_bounds.c — isect_shape_bounds: conservative world boxes.
 *
 * Every bounded shape type, plain and under random affine transforms
 * (rotations, shears, non-uniform scalings, mirrors, translations up to
 * 1e6): the hit points of 4,000 rays aimed at it, as the library reports
 * them, all lie in the box, and so do points sampled on the exact surface
 * where that is easy (a sphere's, a box's corners, the vertices); the box
 * is tight for the plain shapes (the exact extent widened by 2^-40 of its
 * magnitude, for the rounding of reported hit points).
 * Unbounded types give infinite axes, an empty mesh the empty box, and bad
 * input its status.
 */
#include "check.h"
#include "test_random.h"

#include "isect.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int inside_box(const double p[3], const double lo[3], const double hi[3])
{
    return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2]
        && p[2] <= hi[2];
}

/* Rays from random points 10 units around `aim` toward random points within
 * `spread` of it: every reported hit point must be in the box. */
static int64_t hits_outside(const isect_shape *s, const double aim[3], double spread,
                            const double lo[3], const double hi[3])
{
    int64_t outside = 0;
    for (int i = 0; i < 4000; i++) {
        isect_ray r;
        double target[3];
        for (int k = 0; k < 3; k++) {
            r.org[k] = aim[k] + 10.0 * spread * rng_unit();
            target[k] = aim[k] + spread * rng_unit();
            r.dir[k] = target[k] - r.org[k];
        }
        r.tmin = 0.0;
        r.tmax = INFINITY;
        isect_hit hits[8];
        int n = isect_intersect(s, &r, NULL, hits, 8);
        for (int j = 0; j < n && j < 8; j++)
            outside += !inside_box(hits[j].point, lo, hi);
    }
    return outside;
}

/* A random affine transform: rotation (Rodrigues) times a shear and a
 * non-uniform scaling (mirrored when `mirror`), translated by up to 1e6. */
static void random_xform(double m[16], int mirror)
{
    double axis[3] = { rng_unit(), rng_unit(), rng_unit() + 1.5 };
    double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (int k = 0; k < 3; k++)
        axis[k] /= len;
    double a = 3.0 * rng_unit(), c = cos(a), s = sin(a);
    double rot[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            rot[3 * i + j] = (i == j ? c : 0.0) + (1.0 - c) * axis[i] * axis[j];
    rot[1] -= s * axis[2], rot[2] += s * axis[1], rot[3] += s * axis[2];
    rot[5] -= s * axis[0], rot[6] -= s * axis[1], rot[7] += s * axis[0];
    double scale[3] = { (mirror ? -1.0 : 1.0) * (1.5 + rng_unit()), 0.7 + 0.5 * rng_unit(),
                        2.0 + rng_unit() };
    double shear = 0.5 * rng_unit();
    memset(m, 0, 16 * sizeof *m);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            /* rot * diag(scale) * (I + shear e_0 e_1^T) */
            double col = rot[3 * i + j] * scale[j];
            m[4 * i + j] += col;
            if (j == 0)
                m[4 * i + 1] += shear * col;
        }
        m[4 * i + 3] = 1e6 * rng_unit();
    }
    m[15] = 1.0;
}

static void check_shape(const char *name, isect_shape s, const double aim[3], double spread,
                        const double *points, int npoints)
{
    double lo[3], hi[3];
    CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
    for (int i = 0; i < npoints; i++)
        CHECK(inside_box(points + 3 * i, lo, hi));
    int64_t out = hits_outside(&s, aim, spread, lo, hi);
    if (out != 0)
        fprintf(stderr, "%s: %lld hit points outside the box\n", name, (long long)out);
    CHECK(out == 0);

    for (int t = 0; t < 20; t++) {
        isect_xform x;
        double m[16], world_aim[3], wlo[3], whi[3];
        random_xform(m, t % 2);
        CHECK(isect_xform_init(&x, m) == ISECT_OK);
        s.xform = &x;
        CHECK(isect_shape_bounds(&s, wlo, whi) == ISECT_OK);
        for (int i = 0; i < 3; i++)
            world_aim[i] = m[4 * i] * aim[0] + m[4 * i + 1] * aim[1] + m[4 * i + 2] * aim[2]
                         + m[4 * i + 3];
        out = hits_outside(&s, world_aim, 4.0 * spread, wlo, whi);
        if (out != 0)
            fprintf(stderr, "%s, transform %d: %lld hit points outside the box\n", name, t,
                    (long long)out);
        CHECK(out == 0);
        /* the image of every sampled surface point */
        for (int i = 0; i < npoints; i++) {
            double w[3];
            const double *p = points + 3 * i;
            for (int k = 0; k < 3; k++)
                w[k] = m[4 * k] * p[0] + m[4 * k + 1] * p[1] + m[4 * k + 2] * p[2] + m[4 * k + 3];
            /* w itself is rounded: the box's slack (2^-48 of the sums) covers it */
            CHECK(inside_box(w, wlo, whi));
        }
        s.xform = NULL;
    }
}

/* lo and hi outside the exact ends e_lo, e_hi, by at most 2^-38 of the
 * largest magnitude (the documented widening is 2^-40 of it). */
static int tight(const double lo[3], const double hi[3], const double e_lo[3],
                 const double e_hi[3])
{
    double mag = 0.0;
    for (int k = 0; k < 3; k++)
        mag = fmax(mag, fmax(fabs(e_lo[k]), fabs(e_hi[k])));
    for (int k = 0; k < 3; k++)
        if (!(lo[k] <= e_lo[k] && e_lo[k] - lo[k] <= 0x1p-38 * mag && hi[k] >= e_hi[k]
              && hi[k] - e_hi[k] <= 0x1p-38 * mag))
            return 0;
    return 1;
}

int main(void)
{
    double lo[3], hi[3];

    /* sphere: the centre +- r, tight; points on the surface */
    {
        const double d[4] = { 1.0, -2.0, 0.5, 0.75 };
        isect_shape s = { ISECT_SPHERE, 0, 0, 0, d, NULL, NULL };
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
        const double e_lo[3] = { 0.25, -2.75, -0.25 }, e_hi[3] = { 1.75, -1.25, 1.25 };
        CHECK(tight(lo, hi, e_lo, e_hi));
        double pts[6 * 3];
        for (int i = 0; i < 6; i++)
            for (int k = 0; k < 3; k++)
                pts[3 * i + k] = d[k] + (k == i / 2 ? (i % 2 ? -d[3] : d[3]) : 0.0);
        check_shape("sphere", s, d, 0.75, pts, 6);
    }
    /* box: itself, exactly */
    {
        const double d[6] = { -1.0, -0.5, 0.25, 1.5, 0.5, 2.0 };
        isect_shape s = { ISECT_AABB, 0, 0, 0, d, NULL, NULL };
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
        CHECK(memcmp(lo, d, sizeof lo) == 0 && memcmp(hi, d + 3, sizeof hi) == 0);
        double corners[8 * 3];
        for (int i = 0; i < 8; i++)
            for (int k = 0; k < 3; k++)
                corners[3 * i + k] = (i >> k) & 1 ? d[3 + k] : d[k];
        const double aim[3] = { 0.25, 0.0, 1.125 };
        check_shape("box", s, aim, 1.5, corners, 8);
    }
    /* triangle and polygon: their vertices' extent, exactly */
    {
        const double d[9] = { 0.0, 0.0, 1.0, 2.0, 0.5, 1.5, -0.5, 1.75, 0.25 };
        isect_shape s = { ISECT_TRIANGLE, 0, 0, 0, d, NULL, NULL };
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
        const double e_lo[3] = { -0.5, 0.0, 0.25 }, e_hi[3] = { 2.0, 1.75, 1.5 };
        CHECK(tight(lo, hi, e_lo, e_hi));
        const double aim[3] = { 0.5, 0.75, 0.9 };
        check_shape("triangle", s, aim, 1.0, d, 3);
    }
    {
        /* concave, in the plane z = (x + y)/4 exactly */
        const double d[15] = { 0, 0, 0, 2, 0, 0.5, 2, 2, 1, 1, 0.75, 0.4375, 0, 2, 0.5 };
        isect_shape s = { ISECT_POLYGON, 5, ISECT_EVEN_ODD, 0, d, NULL, NULL };
        const double aim[3] = { 1.0, 1.0, 0.5 };
        check_shape("concave polygon", s, aim, 1.2, d, 5);
        /* one vertex off that plane by 1/16: its hits (on the mean plane,
         * wherever a ray passes through its outline) are unbounded */
        const double off[15] = { 0, 0, 0, 2, 0, 0.5, 2, 2, 1, 1, 0.75, 0.5, 0, 2, 0.5 };
        s.data = off;
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
        CHECK(lo[0] == -INFINITY && hi[2] == INFINITY);
    }
    /* ellipsoid and cylinders */
    {
        const double d[6] = { -1.0, 2.0, 0.5, 0.5, 1.5, 0.25 };
        isect_shape s = { ISECT_ELLIPSOID, 0, 0, 0, d, NULL, NULL };
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
        const double e_lo[3] = { -1.5, 0.5, 0.25 }, e_hi[3] = { -0.5, 3.5, 0.75 };
        CHECK(tight(lo, hi, e_lo, e_hi));
        check_shape("ellipsoid", s, d, 1.5, NULL, 0);
    }
    for (int capped = 0; capped < 2; capped++) {
        const double d[7] = { 0.0, 0.0, -1.0, 0.5, 0.25, 1.0, 0.6 };
        isect_shape s = { ISECT_CYLINDER, 0, capped ? ISECT_CAPPED : 0, 0, d, NULL, NULL };
        const double aim[3] = { 0.25, 0.125, 0.0 };
        check_shape(capped ? "capped cylinder" : "open cylinder", s, aim, 1.2, d, 2);
    }
    /* a mesh: its vertices' extent (an octahedron) */
    {
        const double v[18] = { 1.5, 0, 0, -1, 0, 0, 0, 1, 0, 0, -2, 0, 0, 0, 0.5, 0, 0, -1 };
        const int32_t f[24] = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
        isect_mesh *m = NULL;
        CHECK(isect_mesh_create(v, 6, f, NULL, 8, &m) == ISECT_OK);
        isect_shape s = { ISECT_MESH, 0, ISECT_EVEN_ODD, 0, NULL, m, NULL };
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
        const double e_lo[3] = { -1, -2, -1 }, e_hi[3] = { 1.5, 1, 0.5 };
        CHECK(tight(lo, hi, e_lo, e_hi));
        const double aim[3] = { 0.0, 0.0, 0.0 };
        check_shape("octahedron mesh", s, aim, 1.5, v, 6);
        isect_mesh_destroy(m);
    }
    /* unbounded types: infinite on every axis, under any transform too */
    {
        static const double plane[4] = { 0, 0, 1, -2 }, cyl_inf[7] = { 0, 0, 0, 0, 0, 1, 1 };
        static const double quadric[10] = { 1, 1, -1, 0, 0, 0, 0, 0, 0, -1 };
        static const double convex[24] = { 1, 0, 0, -1, -1, 0, 0, -1, 0, 1, 0, -1,
                                           0, -1, 0, -1, 0, 0, 1, -1, 0, 0, -1, -1 };
        isect_shape shapes[4] = { { ISECT_PLANE, 0, 0, 0, plane, NULL, NULL },
                                  { ISECT_CYLINDER_INF, 0, 0, 0, cyl_inf, NULL, NULL },
                                  { ISECT_QUADRIC, 0, 0, 0, quadric, NULL, NULL },
                                  { ISECT_CONVEX, 6, 0, 0, convex, NULL, NULL } };
        static const double scale2[16] = { 2, 0, 0, 1, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 };
        isect_xform x;
        CHECK(isect_xform_init(&x, scale2) == ISECT_OK);
        for (int i = 0; i < 4; i++)
            for (int t = 0; t < 2; t++) {
                shapes[i].xform = t ? &x : NULL;
                CHECK(isect_shape_bounds(&shapes[i], lo, hi) == ISECT_OK);
                for (int k = 0; k < 3; k++)
                    CHECK(lo[k] == -INFINITY && hi[k] == INFINITY);
            }
    }
    /* a mesh without faces or vertices: the empty box */
    {
        isect_mesh *m = NULL;
        if (isect_mesh_create(NULL, 0, NULL, NULL, 0, &m) == ISECT_OK) {
            isect_shape s = { ISECT_MESH, 0, ISECT_EVEN_ODD, 0, NULL, m, NULL };
            CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_OK);
            CHECK(lo[0] == INFINITY && hi[0] == -INFINITY);
            isect_mesh_destroy(m);
        }
    }
    /* bad input: the shape's status; NULL outputs */
    {
        const double bad[4] = { 0, 0, 0, -1.0 }, good[4] = { 0, 0, 0, 1.0 };
        isect_shape s = { ISECT_SPHERE, 0, 0, 0, bad, NULL, NULL };
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_E_ARG);
        s.data = good;
        CHECK(isect_shape_bounds(&s, NULL, hi) == ISECT_E_ARG);
        CHECK(isect_shape_bounds(&s, lo, NULL) == ISECT_E_ARG);
        CHECK(isect_shape_bounds(NULL, lo, hi) == ISECT_E_ARG);
        const double nan_data[4] = { 0, NAN, 0, 1.0 };
        s.data = nan_data;
        CHECK(isect_shape_bounds(&s, lo, hi) == ISECT_E_NONFINITE);
    }
    return check_summary();
}
