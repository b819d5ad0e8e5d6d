/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_spawn.c — isect_spawn_ray on every shape type: secondary rays never
 * find the surface they leave at t ~ 0, and never skip a close second one.
 *
 * For each shape, primary rays that hit it are followed by secondary rays
 * spawned at the hit in four kinds of direction: the mirror reflection, a
 * refraction-like ray bent into the surface, and random directions on
 * either side of the surface. Checks:
 *  - isect_spawn_ray succeeds, returns the direction, tmin 0, tmax +inf, and
 *    an origin within a few hundred ulps of the hit point;
 *  - a solid's containment of the origin matches the side the ray leaves to
 *    (isect_contains: inside exactly when the direction points inwards);
 *  - intersecting the spawned ray with the same shape never reports a hit
 *    at t |dir| below 1e-9 of the shape's size — except where the exact
 *    geometry has one (a mesh's neighbouring face meeting it at a concave
 *    edge): for the convex shapes, the plane, the triangle and the polygon
 *    an outgoing ray must not hit at all, and an inward ray of a convex
 *    solid must leave it on the far side;
 *  - thin slabs (a box 1e-9 thick, two triangles 1e-9 apart, a flat closed
 *    mesh 1e-9 thick): a ray spawned through the first surface finds the
 *    second at the right distance.
 *
 *     test_spawn [secondary rays per shape]     (default 100000)
 */
#define _POSIX_C_SOURCE 200809L

#include "check.h"
#include "isect.h"

#include "test_random.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* A shape under test: descriptor, aim centre and size, and what kind of
 * surface it is. */
typedef struct spawn_shape {
    const char *name;
    isect_shape shape;
    double      data[64];
    isect_xform xform;
    isect_mesh *mesh;
    double      center[3], size;
    int         solid;   /* isect_contains applies */
    int         convex;  /* a ray leaving outwards never comes back */
} spawn_shape;

static void put(spawn_shape *ss, const char *name, int32_t type, const double *data, int count,
                int32_t n, int32_t flags, double cx, double cy, double cz, double size, int solid,
                int convex)
{
    memset(ss, 0, sizeof *ss);
    ss->name = name;
    memcpy(ss->data, data, (size_t)count * sizeof *data);
    ss->shape.type = type;
    ss->shape.n = n;
    ss->shape.flags = flags;
    ss->shape.data = ss->data;
    ss->center[0] = cx;
    ss->center[1] = cy;
    ss->center[2] = cz;
    ss->size = size;
    ss->solid = solid;
    ss->convex = convex;
}

/* An octahedron-like closed mesh around c of radius r (8 triangles). */
static isect_mesh *make_octahedron(double cx, double cy, double cz, double r)
{
    double v[18] = { cx + r, cy, cz, cx - r, cy, cz, cx, cy + r, cz,
                     cx, cy - r, cz, cx, cy, cz + r, cx, cy, cz - r };
    int32_t f[24] = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
    isect_mesh *m = NULL;
    CHECK(isect_mesh_create(v, 6, f, NULL, 8, &m) == ISECT_OK);
    return m;
}

/* A closed box mesh lo..hi of quads (polygon faces), outward. */
static isect_mesh *make_box_mesh(const double lo[3], const double hi[3])
{
    double v[24];
    for (int i = 0; i < 8; i++) {
        v[3 * i] = (i & 1) ? hi[0] : lo[0];
        v[3 * i + 1] = (i & 2) ? hi[1] : lo[1];
        v[3 * i + 2] = (i & 4) ? hi[2] : lo[2];
    }
    int32_t idx[24] = { 0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5 };
    int64_t off[7] = { 0, 4, 8, 12, 16, 20, 24 };
    isect_mesh *m = NULL;
    CHECK(isect_mesh_create(v, 8, idx, off, 6, &m) == ISECT_OK);
    return m;
}

/* A concave closed mesh: an L-shaped prism (its inner corner is a concave
 * edge), triangulated. */
static isect_mesh *make_l_prism(void)
{
    /* L in the xy plane: (0,0) (2,0) (2,1) (1,1) (1,2) (0,2), z in [0, 1] */
    static const double xy[6][2] = { { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
    double v[36];
    for (int i = 0; i < 6; i++) {
        v[3 * i] = xy[i][0];
        v[3 * i + 1] = xy[i][1];
        v[3 * i + 2] = 0.0;
        v[3 * (i + 6)] = xy[i][0];
        v[3 * (i + 6) + 1] = xy[i][1];
        v[3 * (i + 6) + 2] = 1.0;
    }
    int32_t f[3 * 20];
    int nf = 0;
    /* bottom (down) and top (up) as fans over a convex split: (0,1,2,3) and (0,3,4,5) */
    static const int tris[4][3] = { { 0, 1, 2 }, { 0, 2, 3 }, { 0, 3, 4 }, { 0, 4, 5 } };
    for (int t = 0; t < 4; t++) {
        f[3 * nf] = tris[t][0];
        f[3 * nf + 1] = tris[t][2];
        f[3 * nf + 2] = tris[t][1];
        nf++;
        f[3 * nf] = 6 + tris[t][0];
        f[3 * nf + 1] = 6 + tris[t][1];
        f[3 * nf + 2] = 6 + tris[t][2];
        nf++;
    }
    for (int i = 0; i < 6; i++) { /* sides, outward for a counter-clockwise L */
        int j = (i + 1) % 6;
        f[3 * nf] = i;
        f[3 * nf + 1] = j;
        f[3 * nf + 2] = 6 + j;
        nf++;
        f[3 * nf] = i;
        f[3 * nf + 1] = 6 + j;
        f[3 * nf + 2] = 6 + i;
        nf++;
    }
    isect_mesh *m = NULL;
    CHECK(isect_mesh_create(v, 12, f, NULL, nf, &m) == ISECT_OK);
    return m;
}

static void set_mesh(spawn_shape *ss, const char *name, isect_mesh *m, double cx, double cy,
                     double cz, double size, int convex)
{
    memset(ss, 0, sizeof *ss);
    ss->name = name;
    ss->mesh = m;
    ss->shape.type = ISECT_MESH;
    ss->shape.mesh = m;
    ss->center[0] = cx;
    ss->center[1] = cy;
    ss->center[2] = cz;
    ss->size = size;
    ss->solid = 1;
    ss->convex = convex;
}

static int64_t rehits, failures, origin_side_errors;

/* One primary ray at the shape and its secondary rays. */
static void spawn_round(const spawn_shape *ss)
{
    isect_ray ray;
    double d[3];
    rng_dir(d);
    double dist = ss->size * (3.0 + 100.0 * (rng_unit() + 1.0));
    for (int k = 0; k < 3; k++) {
        ray.org[k] = ss->center[k] + dist * d[k];
        ray.dir[k] = ss->center[k] + 0.7 * ss->size * rng_unit() - ray.org[k];
    }
    ray.tmin = 0.0;
    ray.tmax = INFINITY;
    isect_hit hits[16];
    int n = isect_intersect(&ss->shape, &ray, NULL, hits, 16);
    if (n <= 0)
        return;
    const isect_hit *h = &hits[rng_next() % (uint64_t)(n < 16 ? n : 16)];
    double dl = sqrt(dot(ray.dir, ray.dir));
    for (int kind = 0; kind < 4; kind++) {
        double sd[3];
        double dn = dot(ray.dir, h->normal);
        switch (kind) {
        case 0: /* mirror reflection */
            for (int k = 0; k < 3; k++)
                sd[k] = ray.dir[k] - 2.0 * dn * h->normal[k];
            break;
        case 1: /* refraction-like: bent towards the inward normal */
            for (int k = 0; k < 3; k++)
                sd[k] = 0.5 * ray.dir[k] / dl - (dn < 0 ? 1.0 : -1.0) * h->normal[k];
            break;
        default: { /* random, on the normal's side (2) or the other (3) */
            rng_dir(sd);
            double s = dot(sd, h->normal);
            if ((kind == 2) != (s > 0.0))
                for (int k = 0; k < 3; k++)
                    sd[k] -= 2.0 * s * h->normal[k];
            break;
        }
        }
        isect_ray out;
        int st = isect_spawn_ray(&ss->shape, h, sd, &out);
        if (st != ISECT_OK) {
            if (failures++ < 5)
                fprintf(stderr, "%s: isect_spawn_ray failed: %s\n", ss->name, isect_strerror(st));
            continue;
        }
        int outward = dot(sd, h->normal) >= 0.0;
        int ok = out.tmin == 0.0 && out.tmax == INFINITY && out.dir[0] == sd[0]
              && out.dir[1] == sd[1] && out.dir[2] == sd[2];
        double off = 0.0;
        for (int k = 0; k < 3; k++)
            off = fmax(off, fabs(out.org[k] - h->point[k]));
        double scale = fmax(fabs(h->point[0]), fmax(fabs(h->point[1]), fabs(h->point[2])));
        ok &= off <= 1024.0 * 0x1p-52 * fmax(scale, ss->size);
        if (!ok && failures++ < 5)
            fprintf(stderr, "%s: spawned ray malformed or moved by %g\n", ss->name, off);
        if (ss->solid) {
            int in = isect_contains(&ss->shape, out.org);
            if (in != !outward && origin_side_errors++ < 5)
                fprintf(stderr, "%s: spawned origin contains() = %d, outward = %d\n", ss->name, in,
                        outward);
        }
        isect_hit again[16];
        int m = isect_intersect(&ss->shape, &out, NULL, again, 16);
        double sl = sqrt(dot(sd, sd));
        int bad = 0;
        for (int i = 0; i < m && i < 16; i++)
            if (again[i].t * sl < 1e-9 * ss->size)
                bad = 1;
        if (ss->convex) {
            if (outward && m != 0)
                bad = 1; /* a convex surface left outwards is never met again */
            if (!outward && ss->solid && m != 1)
                bad = 1; /* into a convex solid: exactly the far side */
        }
        if (bad && rehits++ < 5)
            fprintf(stderr, "%s: spawned ray (kind %d, outward %d) re-hits: %d hits, first t = %g\n",
                    ss->name, kind, outward, m, m > 0 ? again[0].t : 0.0);
    }
}

/* Through a thin slab: spawned inwards at the first face, the second face
 * is found at thickness / |dir.normal| (to 1e-6 relative). */
static void test_slab(const isect_shape *s, double thickness, const char *name)
{
    int64_t missed = 0;
    for (int i = 0; i < 1000; i++) {
        /* through the top face (z = thickness): x, y stay within 0.6 */
        isect_ray ray = { { 0.3 * rng_unit(), 0.3 * rng_unit(), 5.0 },
                          { 0.05 * rng_unit(), 0.05 * rng_unit(), -1.0 }, 0.0, INFINITY };
        isect_hit h[8];
        int n = isect_intersect(s, &ray, NULL, h, 8);
        if (n < 1 || h[0].normal[2] != 1.0) {
            missed++;
            continue;
        }
        /* refraction straight down through the slab */
        double sd[3] = { 0.1 * rng_unit(), 0.1 * rng_unit(), -1.0 };
        isect_ray out;
        if (isect_spawn_ray(s, &h[0], sd, &out) != ISECT_OK) {
            missed++;
            continue;
        }
        isect_hit g[8];
        int m = isect_intersect(s, &out, NULL, g, 8);
        double want = thickness / fabs(sd[2]);
        if (m < 1 || fabs(g[0].t - want) > 1e-6 * want)
            missed++;
    }
    if (missed != 0)
        fprintf(stderr, "%s: %lld of 1000 rays through the slab missed its second face\n", name,
                (long long)missed);
    CHECK(missed == 0);
}

/* A direction whose dot product with the normal underflows (fuzz_spawn's
 * find): the unit-size normal of a subnormal triangle has a y component of
 * -2^-19 and the new direction is (0, 127 2^-1074, 0), so dir.normal is
 * negative but rounds to -0. The ray must leave behind the face (where it
 * points), so it never meets the face again; a plain dot product took -0
 * for "tangent" and put the origin in front, and the ray met the face at
 * t ~ 1684. */
static void test_underflowing_side(void)
{
    static const double tri[9] = { 0x0p+0, 0x0p+0, 0x0.000000000003fp-1022,
                                   0x0.02ep-1022, 0x0p+0, 0x0.000000026p-1022,
                                   0x0.0000000003ffp-1022, 0x0.00000ffffc01p-1022,
                                   0x0.0000000003ff4p-1022 };
    isect_shape s = { ISECT_TRIANGLE, 0, 0, 0, tri, NULL, NULL };
    isect_ray r = { { 0x0.0000000003ff8p-1022, 0x0.000000000bffp-1022, 0x0.000000000bffp-1022 },
                    { -0x1p-8, -0x1p-8, -0x1.94p+6 }, 0.0, INFINITY };
    isect_hit h, again[2];
    CHECK(isect_intersect(&s, &r, NULL, &h, 1) == 1);
    const double dir[3] = { 0.0, 127 * 0x1p-1074, 0.0 };
    isect_ray out;
    CHECK(isect_spawn_ray(&s, &h, dir, &out) == ISECT_OK);
    CHECK(isect_intersect(&s, &out, NULL, again, 2) == 0);
}

/* A direction within the normal's rounding of the plane (fuzz_spawn's
 * find): the triangle below lies in a plane whose exact normal is ~2^-56
 * off (0, -1, 1)/sqrt(2), but its unit normal rounds to exactly (0, -h, h),
 * perpendicular to the new direction (-1/4, -2^-8, -2^-8) in doubles. Taken
 * for "tangent", the origin went in front and the ray, sinking through the
 * plane at a slope of ~2^-64, met the face again at t ~ 1300. The exact
 * plane decides: the ray leaves behind it, and never meets the face. The
 * same through a transform (a scaling by 2: the object-space direction is
 * exact). */
static void test_nearly_tangent_flat(void)
{
    static const double tri[9] = { 0x1.6403a7100302bp-95, 0x1p-52, -0x1p-64,
                                   -0x1.57a020205p+83, -14.75, -14.75,
                                   -14.75, -14.75, -14.75 };
    static const double scale2[16] = { 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 };
    isect_xform x;
    CHECK(isect_xform_init(&x, scale2) == ISECT_OK);
    for (int transformed = 0; transformed < 2; transformed++) {
        isect_shape s = { ISECT_TRIANGLE, 0, 0, 0, tri, NULL, transformed ? &x : NULL };
        double k = transformed ? 2.0 : 1.0;
        isect_ray r = { { -0.25 * k, -1.0 * k, 1.0 * k }, { 0, 1, -1 }, 0.0, INFINITY };
        isect_hit h, again[2];
        CHECK(isect_intersect(&s, &r, NULL, &h, 1) == 1);
        const double dir[3] = { -0.25, -0x1p-8, -0x1p-8 };
        CHECK(h.normal[0] == 0.0 && h.normal[1] == -h.normal[2]); /* dir.normal == 0 */
        isect_ray out;
        CHECK(isect_spawn_ray(&s, &h, dir, &out) == ISECT_OK);
        CHECK(isect_intersect(&s, &out, NULL, again, 2) == 0);
    }
}

/* Spawning inward at an edge or corner of a solid: the primary ray meets
 * the unit cube [0,1]^3 exactly on its edge x = 1, z = 1 (or its corner
 * (1,1,1)), and the new direction points into the solid. Offsets along the
 * hit face's inward normal alone stay on the other face through that edge
 * at every step (isect_spawn_ray returned ISECT_E_DEGENERATE); the
 * spawned ray must start strictly inside and meet the cube exactly once,
 * leaving it through the far side at t ~ 1 (never at t ~ 0). For the box,
 * the same cube as a convex polyhedron and as a closed mesh of quads (where
 * the origin must also be off the other face: a ray from a point on it met
 * that face at t = 0). */
static void test_edges_and_corners(void)
{
    static const double box[6] = { 0, 0, 0, 1, 1, 1 };
    static const double cube_planes[24] = { 1, 0, 0, -1, -1, 0, 0, 0, 0, 1, 0, -1,
                                            0, -1, 0, 0, 0, 0, 1, -1, 0, 0, -1, 0 };
    const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
    isect_mesh *m = make_box_mesh(lo, hi);
    isect_shape shapes[3] = { { ISECT_AABB, 0, 0, 0, box, NULL, NULL },
                              { ISECT_CONVEX, 6, 0, 0, cube_planes, NULL, NULL },
                              { ISECT_MESH, 0, 0, 0, NULL, m, NULL } };
    /* primary rays onto the edge (1, 0.5, 1) and the corner (1, 1, 1), each
     * with two inward directions whose exit lies 1 away along x or z */
    static const double aims[2][3] = { { 1, 0.5, 1 }, { 1, 1, 1 } };
    static const double from[3][3] = { { 0, 0, -1 }, { -1, 0, 0 }, { -1, -1, -1 } };
    static const double inward[2][3] = { { -1, 0, -1 }, { -1, -0.25, -0.5 } };
    for (int si = 0; si < 3; si++) {
        for (int a = 0; a < 2; a++) {
            for (int fi = 0; fi < 3; fi++) {
                isect_ray r;
                for (int k = 0; k < 3; k++) {
                    r.org[k] = aims[a][k] - 2.0 * from[fi][k];
                    r.dir[k] = from[fi][k];
                }
                r.tmin = 0.0;
                r.tmax = INFINITY;
                isect_hit h, again[4];
                if (isect_intersect(&shapes[si], &r, NULL, &h, 1) < 1 || h.t != 2.0) {
                    CHECK(0 && "the primary ray meets the edge or corner at t = 2");
                    continue;
                }
                for (int d = 0; d < 2; d++) {
                    isect_ray out;
                    int st = isect_spawn_ray(&shapes[si], &h, inward[d], &out);
                    if (a == 1 && d == 0) {
                        /* (-1, 0, -1) from the corner runs in the face
                         * y = 1: no offset along the hit's normal and dir
                         * leaves that face, as isect.h documents */
                        CHECK(st == ISECT_E_DEGENERATE);
                        continue;
                    }
                    CHECK(st == ISECT_OK);
                    if (st != ISECT_OK) {
                        fprintf(stderr, "shape %d aim %d from %d dir %d: status %d\n", si, a, fi,
                                d, st);
                        continue;
                    }
                    CHECK(isect_contains(&shapes[si], out.org) == 1);
                    int n = isect_intersect(&shapes[si], &out, NULL, again, 4);
                    CHECK(n == 1 && again[0].kind == ISECT_EXIT && again[0].t > 0.5);
                }
            }
        }
    }
    isect_mesh_destroy(m);
}

int main(int argc, char **argv)
{
    test_edges_and_corners();
    test_underflowing_side();
    test_nearly_tangent_flat();
    int64_t per_shape = argc > 1 ? atoll(argv[1]) : 100000;
    enum { COUNT = 17 };
    static spawn_shape shapes[COUNT];
    int c = 0;
    { const double d[4] = { 0.3, -0.4, 0.866, -2.5 };
      put(&shapes[c++], "plane", ISECT_PLANE, d, 4, 0, 0, 0.75, -1.0, 2.165, 1.0, 0, 1); }
    { const double d[4] = { 1.0, -2.0, 0.5, 0.75 };
      put(&shapes[c++], "sphere", ISECT_SPHERE, d, 4, 0, 0, 1.0, -2.0, 0.5, 0.75, 1, 1); }
    { const double d[4] = { 1e6, -3e6, 2e5, 1e-2 };
      put(&shapes[c++], "small far sphere", ISECT_SPHERE, d, 4, 0, 0, 1e6, -3e6, 2e5, 1e-2, 1, 1); }
    { const double d[6] = { -1.0, -0.5, 0.25, 1.5, 0.5, 2.0 };
      put(&shapes[c++], "box", ISECT_AABB, d, 6, 0, 0, 0.25, 0.0, 1.125, 1.5, 1, 1); }
    { const double d[9] = { 0.0, 0.0, 1.0, 2.0, 0.5, 1.5, -0.5, 1.75, 0.25 };
      put(&shapes[c++], "triangle", ISECT_TRIANGLE, d, 9, 0, 0, 0.5, 0.75, 0.9, 1.2, 0, 1); }
    { const double d[15] = { 0, 0, 0, 2, 0, 0.5, 2, 2, 1, 1, 0.75, 0.5, 0, 2, 0.5 };
      put(&shapes[c++], "concave polygon", ISECT_POLYGON, d, 15, 5, ISECT_EVEN_ODD, 1.0, 1.0, 0.5,
          1.2, 0, 1); }
    { const double d[24] = { 1, 0, 0, -1, -1, 0, 0, -1, 0, 1, 0, -1, 0, -1, 0, -1,
                             0, 0, 1, -1, 0, 0, -1, -1 };
      put(&shapes[c++], "convex (cube)", ISECT_CONVEX, d, 24, 6, 0, 0, 0, 0, 1.0, 1, 1); }
    { const double d[7] = { 0.0, 0.0, -1.0, 0.5, 0.25, 1.0, 0.6 };
      put(&shapes[c++], "capped cylinder", ISECT_CYLINDER, d, 7, 0, ISECT_CAPPED, 0.25, 0.125, 0,
          1.2, 1, 1); }
    { const double d[7] = { 0.0, 0.0, -1.0, 0.5, 0.25, 1.0, 0.6 };
      put(&shapes[c++], "open cylinder", ISECT_CYLINDER, d, 7, 0, 0, 0.25, 0.125, 0, 1.2, 0, 0); }
    { const double d[7] = { 0.5, -0.5, 0.0, 0.3, 0.4, 1.0, 0.8 };
      put(&shapes[c++], "infinite cylinder", ISECT_CYLINDER_INF, d, 7, 0, 0, 0.5, -0.5, 0.0, 1.0,
          1, 1); }
    { const double d[6] = { -1.0, 2.0, 0.5, 0.5, 1.5, 0.25 };
      put(&shapes[c++], "ellipsoid", ISECT_ELLIPSOID, d, 6, 0, 0, -1.0, 2.0, 0.5, 1.5, 1, 1); }
    { const double d[10] = { 1, 1, -1, 0, 0, 0, 0, 0, 0, -1 }; /* hyperboloid of one sheet */
      put(&shapes[c++], "hyperboloid", ISECT_QUADRIC, d, 10, 0, 0, 0, 0, 0, 2.0, 1, 0); }
    { const double d[7] = { 1.0, 2.0, 3.0, 0.75 };
      put(&shapes[c++], "transformed sphere", ISECT_SPHERE, d, 4, 0, 0, 0, 0, 0, 2.0, 1, 1);
      static const double m[16] = { 0.8, -0.6, 0.1, 5.0, 0.6, 0.8, 0.2, -1.0,
                                    0.0, 0.3, 2.0, 0.25, 0.0, 0.0, 0.0, 1.0 };
      CHECK(isect_xform_init(&shapes[c - 1].xform, m) == ISECT_OK);
      shapes[c - 1].shape.xform = &shapes[c - 1].xform;
      /* aim at the sphere's image */
      shapes[c - 1].center[0] = 0.8 * 1 - 0.6 * 2 + 0.1 * 3 + 5.0;
      shapes[c - 1].center[1] = 0.6 * 1 + 0.8 * 2 + 0.2 * 3 - 1.0;
      shapes[c - 1].center[2] = 0.3 * 2 + 2.0 * 3 + 0.25; }
    set_mesh(&shapes[c++], "octahedron mesh", make_octahedron(0.5, -0.25, 1.0, 1.5), 0.5, -0.25,
             1.0, 1.5, 1);
    { const double lo[3] = { -1, -2, -0.5 }, hi[3] = { 1.5, 0.5, 1.0 };
      set_mesh(&shapes[c++], "box mesh (quads)", make_box_mesh(lo, hi), 0.25, -0.75, 0.25, 2.0, 1); }
    set_mesh(&shapes[c++], "L prism mesh (concave)", make_l_prism(), 1.0, 1.0, 0.5, 1.5, 0);
    { const double d[9] = { 0.0, 0.0, 1.0, 2.0, 0.5, 1.5, -0.5, 1.75, 0.25 };
      put(&shapes[c++], "transformed triangle", ISECT_TRIANGLE, d, 9, 0, 0, 0, 0, 0, 3.0, 0, 1);
      static const double m[16] = { 2.0, 0.0, 0.5, 1.0, 0.0, 0.5, 0.0, -2.0,
                                    0.25, 0.0, 1.0, 3.0, 0.0, 0.0, 0.0, 1.0 };
      CHECK(isect_xform_init(&shapes[c - 1].xform, m) == ISECT_OK);
      shapes[c - 1].shape.xform = &shapes[c - 1].xform;
      shapes[c - 1].center[0] = 2.0 * 0.5 + 0.5 * 0.9 + 1.0;
      shapes[c - 1].center[1] = 0.5 * 0.75 - 2.0;
      shapes[c - 1].center[2] = 0.25 * 0.5 + 0.9 + 3.0; }
    CHECK(c == COUNT);

    for (int i = 0; i < COUNT; i++) {
        rehits = failures = origin_side_errors = 0;
        for (int64_t r = 0; r < per_shape / 4; r++)
            spawn_round(&shapes[i]);
        if (rehits || failures || origin_side_errors)
            fprintf(stderr, "%s: %lld re-hits, %lld failures, %lld origins on the wrong side\n",
                    shapes[i].name, (long long)rehits, (long long)failures,
                    (long long)origin_side_errors);
        CHECK(rehits == 0);
        CHECK(failures == 0);
        CHECK(origin_side_errors == 0);
    }

    /* Thin slabs, 1e-9 thick. */
    { const double d[6] = { -1, -1, 0.0, 1, 1, 1e-9 };
      isect_shape s = { ISECT_AABB, 0, 0, 0, d, NULL, NULL };
      test_slab(&s, 1e-9, "box slab"); }
    { const double lo[3] = { -1, -1, 0.0 }, hi[3] = { 1, 1, 1e-9 };
      isect_mesh *m = make_box_mesh(lo, hi);
      isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, m, NULL };
      test_slab(&s, 1e-9, "box mesh slab");
      isect_mesh_destroy(m); }

    for (int i = 0; i < COUNT; i++)
        isect_mesh_destroy(shapes[i].mesh);
    return check_summary();
}
