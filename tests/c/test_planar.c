/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_planar.c — triangles, polygons and the planar helpers: hit records,
 * concave and self-intersecting polygons under both fill rules, Newell
 * normals, the epsilon policy for parallel rays, degenerate input, and the
 * documented status for bad input.
 *
 * Expected values are closed-form (integer or dyadic geometry), never taken
 * from the library.
 */
#include "check.h"

#include <isect.h>

#include <float.h>
#include <stdint.h>
#include <string.h>

static isect_ray ray_make(double ox, double oy, double oz, double dx, double dy, double dz)
{
    isect_ray r = { { ox, oy, oz }, { dx, dy, dz }, 0.0, INFINITY };
    return r;
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])
                + (a[2] - b[2]) * (a[2] - b[2]));
}

/* ------------------------------------------------------------ triangle */

static void test_triangle_hit_record(void)
{
    static const double a[3] = { 0, 0, 0 }, b[3] = { 2, 0, 0 }, c[3] = { 0, 2, 0 };
    isect_hit h[2];
    memset(h, 0xff, sizeof h);
    isect_ray r = ray_make(0.5, 0.25, 1, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, h, 2), 1);
    CHECK_NEAR(h[0].t, 1.0, 1e-15);
    CHECK_NEAR(h[0].point[0], 0.5, 1e-15);
    CHECK_NEAR(h[0].point[1], 0.25, 1e-15);
    CHECK_NEAR(h[0].point[2], 0.0, 1e-15);
    CHECK(h[0].normal[0] == 0 && h[0].normal[1] == 0 && h[0].normal[2] == 1);
    CHECK_NEAR(h[0].uv[0], 0.25, 1e-15);  /* weight of b */
    CHECK_NEAR(h[0].uv[1], 0.125, 1e-15); /* weight of c */
    CHECK_EQ_INT(h[0].prim, -1);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER); /* dir.n < 0: front side */

    /* From below: the back side; culled with ISECT_CULL_BACK. */
    r = ray_make(0.5, 0.25, -3, 0, 0, 4);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, h, 2), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_EXIT);
    CHECK_NEAR(h[0].t, 0.75, 1e-15); /* dir is not renormalised */
    isect_opts cull = ISECT_OPTS_INIT;
    cull.flags = ISECT_CULL_BACK;
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, &cull, h, 2), 0);

    /* Behind the origin, and outside [tmin, tmax]. */
    r = ray_make(0.5, 0.25, 1, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, NULL, 0), 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, h, 1), 1);
    CHECK_NEAR(h[0].t, -1.0, 1e-15);
    r = ray_make(0.5, 0.25, 1, 0, 0, -1);
    r.tmax = 0.5;
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, NULL, 0), 0);

    /* uv at the vertices is exact: (0,0) at a, (1,0) at b, (0,1) at c. */
    const double *verts[3] = { a, b, c };
    for (int i = 0; i < 3; i++) {
        isect_ray rv = ray_make(verts[i][0] + 0.25, verts[i][1] - 0.5, 2, -0.25, 0.5, -2);
        int n = isect_ray_triangle(&rv, a, b, c, NULL, h, 1);
        if (n == 1) { /* a vertex is claimed by the half-open rule or not */
            CHECK(h[0].uv[0] == (i == 1) && h[0].uv[1] == (i == 2));
            CHECK(h[0].t == 1.0);
        }
    }
    /* Just inside and just outside the edge a-b. */
    r = ray_make(1.0, 1e-9, 1, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, NULL, 0), 1);
    r = ray_make(1.0, -1e-9, 1, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, NULL, 0), 0);
}

/* A tilted triangle far from the origin: t, point and barycentrics. */
static void test_triangle_far_and_tilted(void)
{
    const double base[3] = { 1e6, -2e6, 5e5 };
    /* The plane x + 2y + 2z = const: edges (2, -1, 0) and (0, 1, -1). */
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
        a[k] = base[k];
        b[k] = base[k] + (k == 0 ? 2 : k == 1 ? -1 : 0) * 4.0;
        c[k] = base[k] + (k == 0 ? 0 : k == 1 ? 1 : -1) * 4.0;
    }
    /* The point a + (1/4)(b - a) + (1/2)(c - a), reached from 3 units along
     * the normal (1, 2, 2)/3 with dir = -(1, 2, 2). */
    double p[3];
    for (int k = 0; k < 3; k++)
        p[k] = a[k] + 0.25 * (b[k] - a[k]) + 0.5 * (c[k] - a[k]);
    isect_ray r = ray_make(p[0] + 3, p[1] + 6, p[2] + 6, -1, -2, -2);
    isect_hit h;
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, &h, 1), 1);
    CHECK_NEAR(h.t, 3.0, 1e-9);
    CHECK(dist3(h.point, p) < 1e-9);
    CHECK_NEAR(h.uv[0], 0.25, 1e-9);
    CHECK_NEAR(h.uv[1], 0.5, 1e-9);
    CHECK_NEAR(h.normal[0], 1.0 / 3.0, 1e-15);
    CHECK_NEAR(h.normal[1], 2.0 / 3.0, 1e-15);
    CHECK_NEAR(h.normal[2], 2.0 / 3.0, 1e-15);
    CHECK_EQ_INT(h.kind, ISECT_ENTER);
}

/* The same hit at any absolute scale: t, normal and uv are scale-free. */
static void test_extreme_scales(void)
{
    static const double scales[5] = { 1.0, 1e200, 1e-200, 0x1p1000, 0x1p-1000 };
    static const double tri[9] = { 0, 0, 0, 2, 0, 1, 0, 2, -1 };
    for (int i = 0; i < 5; i++) {
        double S = scales[i], v[9];
        for (int k = 0; k < 9; k++)
            v[k] = tri[k] * S;
        /* Through a + b/4 + c/4 = (0.5, 0.5, 0) at t = 1. */
        isect_ray r = ray_make(1.0 * S, 1.5 * S, 1.0 * S, -0.5 * S, -1.0 * S, -1.0 * S);
        isect_hit h;
        CHECK_EQ_INT(isect_ray_triangle(&r, v, v + 3, v + 6, NULL, &h, 1), 1);
        CHECK_NEAR(h.t, 1.0, 1e-15);
        CHECK_NEAR(h.uv[0], 0.25, 1e-15);
        CHECK_NEAR(h.uv[1], 0.25, 1e-15);
        /* (b - a) x (c - a) = (0*(-1) - 1*2, 1*0 - 2*(-1), 2*2 - 0) = (-2, 2, 4). */
        double len = sqrt(24.0);
        CHECK_NEAR(h.normal[0], -2 / len, 1e-15);
        CHECK_NEAR(h.normal[1], 2 / len, 1e-15);
        CHECK_NEAR(h.normal[2], 4 / len, 1e-15);
        CHECK_EQ_INT(isect_ray_polygon(&r, v, 3, ISECT_EVEN_ODD, NULL, &h, 1), 1);
        CHECK_NEAR(h.t, 1.0, 1e-15);
        CHECK_NEAR(h.normal[2], 4 / len, 1e-15);
    }
}

/* Revision 2: triangles and polygons have no epsilon — the exact test in
 * the sheared frame alone decides, at every eps; a ray lying in the face's
 * plane or parallel to it has no crossing point and never hits. */
static void test_parallel_rays(void)
{
    static const double a[3] = { 0, 0, 0 }, b[3] = { 4, 0, 0 }, c[3] = { 0, 4, 0 };
    static const double sq[12] = { 0, 0, 0, 4, 0, 0, 4, 4, 0, 0, 4, 0 };
    isect_opts eps0 = ISECT_OPTS_INIT, eps_big = ISECT_OPTS_INIT;
    eps0.eps = 0.0;
    eps_big.eps = 1e-3;
    /* In the plane, through the interior. */
    isect_ray r = ray_make(-1, 1, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, NULL, 0), 0);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, &eps0, NULL, 0), 0);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_EVEN_ODD, NULL, NULL, 0), 0);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_EVEN_ODD, &eps0, NULL, 0), 0);
    /* Above the plane, parallel. */
    r = ray_make(-1, 1, 1, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, &eps0, NULL, 0), 0);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_NONZERO, &eps0, NULL, 0), 0);
    /* Nearly parallel (|n.d|/|d| ~ 1e-13): a hit at every eps, at x = 2. */
    r = ray_make(1, 1, 1e-13, 1, 0, -1e-13);
    isect_hit h;
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, &h, 1), 1);
    CHECK_NEAR(h.t, 1.0, 1e-15);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, &eps_big, &h, 1), 1);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_EVEN_ODD, NULL, &h, 1), 1);
    CHECK_NEAR(h.t, 1.0, 1e-15);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_EVEN_ODD, &eps_big, &h, 1), 1);
    /* A steeper ray too, whatever eps. */
    r = ray_make(1, 1, 1e-4, 1, 0, -1e-4);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, NULL, NULL, 0), 1);
    CHECK_EQ_INT(isect_ray_triangle(&r, a, b, c, &eps_big, NULL, 0), 1);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_EVEN_ODD, NULL, NULL, 0), 1);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_EVEN_ODD, &eps_big, NULL, 0), 1);
}

/* Zero area is never hit, from any direction, as a triangle or polygon. */
static void test_degenerate_never_hit(void)
{
    /* a, 2a, 4a are exactly collinear (power-of-two multiples), but the
     * rounded cross product (2a - a) x (4a - a) need not be zero. */
    static const double a[3] = { 0.1, 0.3, 0.7 };
    double b[3], c[3], far[3], mid[3];
    for (int k = 0; k < 3; k++) {
        b[k] = 2 * a[k];
        c[k] = 4 * a[k];
        far[k] = 8 * a[k];
        mid[k] = (a[k] + b[k] + c[k]) / 3.0; /* near the line, not on it */
    }
    static const double dirs[7][3] = { { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 1 },
                                       { 3, -1, 2 }, { -0.3, 0.1, -0.2 }, { 0.7, -0.3, 0.1 } };
    double poly[12];
    memcpy(poly, a, sizeof a);
    memcpy(poly + 3, b, sizeof b);
    memcpy(poly + 6, c, sizeof c);
    memcpy(poly + 9, far, sizeof far);
    int hits = 0;
    isect_opts eps0 = ISECT_OPTS_INIT;
    eps0.eps = 0.0;
    for (int i = 0; i < 7; i++)
        for (int s = -1; s <= 1; s += 2) {
            isect_ray r = ray_make(mid[0] - s * dirs[i][0], mid[1] - s * dirs[i][1],
                                   mid[2] - s * dirs[i][2], s * dirs[i][0], s * dirs[i][1],
                                   s * dirs[i][2]);
            r.tmin = -INFINITY;
            hits += isect_ray_triangle(&r, a, b, c, &eps0, NULL, 0);
            hits += isect_ray_triangle(&r, a, b, c, NULL, NULL, 0);
            hits += isect_ray_polygon(&r, poly, 4, ISECT_EVEN_ODD, &eps0, NULL, 0);
            hits += isect_ray_polygon(&r, poly, 3, ISECT_NONZERO, &eps0, NULL, 0);
            /* Coincident vertices. */
            hits += isect_ray_triangle(&r, a, a, c, &eps0, NULL, 0);
            hits += isect_ray_triangle(&r, a, a, a, &eps0, NULL, 0);
        }
    CHECK_EQ_INT(hits, 0);
    double n[3] = { 9, 9, 9 };
    CHECK_EQ_INT(isect_polygon_normal(poly, 4, n), ISECT_E_DEGENERATE);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 0);
    double plane[4] = { 9, 9, 9, 9 };
    CHECK_EQ_INT(isect_plane_from_points(poly, 3, plane), ISECT_E_DEGENERATE);
    CHECK(plane[0] == 0 && plane[1] == 0 && plane[2] == 0 && plane[3] == 0);
}

/* ------------------------------------------------------------- polygons */

/* A "U": the notch x in (1, 2), y in (1, 3) is outside. Extra collinear
 * vertex (1.5, 0) on the bottom edge; reflex vertices (2, 1) and (1, 1).
 * Boundary points follow the half-open rule: the point is moved by
 * (-e^2, -e), mostly down, slightly left. */
static const double u_shape[9][3] = { { 0, 0, 0 }, { 1.5, 0, 0 }, { 3, 0, 0 }, { 3, 3, 0 },
                                      { 2, 3, 0 }, { 2, 1, 0 },   { 1, 1, 0 }, { 1, 3, 0 },
                                      { 0, 3, 0 } };

static void test_concave_polygon(void)
{
    static const struct { double x, y; int hit; } cases[] = {
        { 1.5, 2, 0 },    /* in the notch */
        { 0.5, 2, 1 },    /* left arm */
        { 2.5, 2.75, 1 }, /* right arm */
        { 1.5, 0.5, 1 },  /* base */
        { 1.5, 1, 1 },    /* notch floor: perturbed down into the base */
        { 2, 1, 1 },      /* reflex vertex, same */
        { 1, 1, 1 },      /* reflex vertex */
        { 1, 2, 1 },      /* notch wall x = 1: perturbed left, into the arm */
        { 2, 2, 0 },      /* notch wall x = 2: perturbed left, into the notch */
        { 1.5, 0, 0 },    /* collinear vertex on the bottom edge */
        { 1.5, 1e-12, 1 },
        { 4, 1, 0 },      /* beside it */
        { 1.5, 3, 0 }     /* above the notch */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int want = cases[i].hit;
        for (int rule = 0; rule < 2; rule++) {
            /* Along +z the sheared frame is (x - org.x, y - org.y), so the
             * perturbation moves the point by (-e^2, -e), as in 2D. */
            isect_ray r = ray_make(cases[i].x, cases[i].y, -5, 0, 0, 1);
            isect_hit h;
            int got = isect_ray_polygon(&r, &u_shape[0][0], 9, rule, NULL, &h, 1);
            CHECK_EQ_INT(got, want);
            if (got == 1) {
                CHECK_NEAR(h.t, 5.0, 1e-15);
                CHECK(h.normal[2] == 1.0);
                CHECK_EQ_INT(h.kind, ISECT_EXIT); /* from below: the back */
                CHECK(h.uv[0] == 0 && h.uv[1] == 0 && h.prim == -1);
            }
            double q[2] = { cases[i].x, cases[i].y }, poly2[18];
            for (int k = 0; k < 9; k++) {
                poly2[2 * k] = u_shape[k][0];
                poly2[2 * k + 1] = u_shape[k][1];
            }
            CHECK_EQ_INT(isect_point_in_polygon2(poly2, 9, q, rule), want);
        }
    }
    double n[3];
    CHECK_EQ_INT(isect_polygon_normal(&u_shape[0][0], 9, n), ISECT_OK);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 1);
}

/* A pentagram with integer corners, drawn counter-clockwise twice around
 * the centre: winding 2 in the pentagon core, 1 in the points, 0 outside. */
static const double star2[10] = { 0, 10, -6, -8, 10, 3, -10, 3, 6, -8 };

static void test_pentagram(void)
{
    static const struct { double x, y; int32_t winding; } cases[] = {
        { 0, 0, 2 }, { 0.5, -1, 2 }, { 0, 7, 1 }, { -7.5, 2.5, 1 }, { 0, -7, 0 },
        { 8, 2.75, 1 }, { 20, 0, 0 }, { -4.5, -6, 1 }
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double q[2] = { cases[i].x, cases[i].y };
        int32_t w = 99;
        CHECK_EQ_INT(isect_winding_number2(star2, 5, q, &w), ISECT_OK);
        CHECK_EQ_INT(w, cases[i].winding);
        CHECK_EQ_INT(isect_point_in_polygon2(star2, 5, q, ISECT_EVEN_ODD),
                     cases[i].winding % 2 != 0);
        CHECK_EQ_INT(isect_point_in_polygon2(star2, 5, q, ISECT_NONZERO),
                     cases[i].winding != 0);
        /* The same star on the tilted plane z = x/2 + y/4 + 3, hit from
         * above: centre outside under even-odd, inside under nonzero. */
        double v[15];
        for (int k = 0; k < 5; k++) {
            v[3 * k] = star2[2 * k];
            v[3 * k + 1] = star2[2 * k + 1];
            v[3 * k + 2] = star2[2 * k] / 2 + star2[2 * k + 1] / 4 + 3;
        }
        isect_ray r = ray_make(q[0], q[1], 100, 0, 0, -2);
        isect_hit h;
        CHECK_EQ_INT(isect_ray_polygon(&r, v, 5, ISECT_EVEN_ODD, NULL, NULL, 0),
                     cases[i].winding % 2 != 0);
        int got = isect_ray_polygon(&r, v, 5, ISECT_NONZERO, NULL, &h, 1);
        CHECK_EQ_INT(got, cases[i].winding != 0);
        if (got == 1) {
            double z = q[0] / 2 + q[1] / 4 + 3;
            CHECK_NEAR(h.point[2], z, 1e-12);
            CHECK_NEAR(h.t, (100 - z) / 2, 1e-12);
            /* Normal of the plane z = x/2 + y/4 + 3 (upward: the star is
             * counter-clockwise seen from above): (-1/2, -1/4, 1)/|.|. */
            double len = sqrt(0.25 + 0.0625 + 1.0);
            CHECK_NEAR(h.normal[0], -0.5 / len, 1e-15);
            CHECK_NEAR(h.normal[1], -0.25 / len, 1e-15);
            CHECK_NEAR(h.normal[2], 1.0 / len, 1e-15);
        }
    }
    /* Reversed, the windings change sign. */
    double rev[10];
    for (int k = 0; k < 5; k++) {
        rev[2 * k] = star2[2 * (4 - k)];
        rev[2 * k + 1] = star2[2 * (4 - k) + 1];
    }
    int32_t w = 0;
    static const double centre[2] = { 0, 0 };
    CHECK_EQ_INT(isect_winding_number2(rev, 5, centre, &w), ISECT_OK);
    CHECK_EQ_INT(w, -2);
    CHECK_EQ_INT(isect_point_in_polygon2(rev, 5, centre, ISECT_NONZERO), 1);
}

/* A triangle and the same triangle as a polygon agree on every ray: hit or
 * not, t, normal and kind. Rays near and through edges and vertices. */
static void test_triangle_polygon_agree(void)
{
    uint64_t state = 31337;
    int disagreements = 0, hits = 0;
    for (int trial = 0; trial < 3000; trial++) {
        double v[9], org[3], target[3];
        for (int k = 0; k < 9; k++) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            v[k] = (double)(int)((state >> 33) % 17) - 8; /* small integers */
        }
        /* Target: a vertex, an edge point at 1/2 or 1/4, or a generic mix. */
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        int kind = (int)((state >> 40) % 4), i = (int)((state >> 44) % 3), j = (i + 1) % 3;
        double f = kind == 1 ? 0.5 : kind == 2 ? 0.25 : (double)((state >> 20) % 1000) / 999.0;
        for (int k = 0; k < 3; k++) {
            target[k] = kind == 0 ? v[3 * i + k] : v[3 * i + k] + f * (v[3 * j + k] - v[3 * i + k]);
            org[k] = (double)(int)((state >> (8 * k + 3)) % 23) - 11;
        }
        isect_ray r = ray_make(org[0], org[1], org[2], target[0] - org[0],
                               target[1] - org[1], target[2] - org[2]);
        r.tmin = -INFINITY;
        if (r.dir[0] == 0 && r.dir[1] == 0 && r.dir[2] == 0)
            continue;
        isect_hit ht, hp, hn;
        int nt = isect_ray_triangle(&r, v, v + 3, v + 6, NULL, &ht, 1);
        int np = isect_ray_polygon(&r, v, 3, ISECT_EVEN_ODD, NULL, &hp, 1);
        int nn = isect_ray_polygon(&r, v, 3, ISECT_NONZERO, NULL, &hn, 1);
        if (nt != np || nt != nn) {
            disagreements++;
            continue;
        }
        if (nt == 1) {
            hits++;
            double scale = fmax(1.0, fabs(ht.t));
            if (fabs(ht.t - hp.t) > 1e-12 * scale || ht.kind != hp.kind
                || dist3(ht.normal, hp.normal) > 1e-14 || hp.t != hn.t)
                disagreements++;
        }
    }
    CHECK_EQ_INT(disagreements, 0);
    CHECK(hits > 500);
}

/* --------------------------------------------------------- Newell normal */

static void test_newell_normal(void)
{
    double n[3];
    /* Concave L, counter-clockwise in z = 0. */
    static const double ell[18] = { 0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0 };
    CHECK_EQ_INT(isect_polygon_normal(ell, 6, n), ISECT_OK);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 1);
    /* Clockwise: the other side. */
    double ell_cw[18];
    for (int k = 0; k < 6; k++)
        memcpy(ell_cw + 3 * k, ell + 3 * (5 - k), 3 * sizeof(double));
    CHECK_EQ_INT(isect_polygon_normal(ell_cw, 6, n), ISECT_OK);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == -1);
    /* The first three vertices collinear (a cross product of them fails). */
    static const double lead_collinear[15] = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 2, 0, 1, 0, 0, 1 };
    CHECK_EQ_INT(isect_polygon_normal(lead_collinear, 5, n), ISECT_OK);
    CHECK(n[0] == 0 && n[1] == -1 && n[2] == 0); /* xz plane, x then z: -y */
    /* Nearly collinear: a sliver 1e-9 high. */
    static const double sliver[9] = { 0, 0, 5, 1, 0, 5, 0.5, 1e-9, 5 };
    CHECK_EQ_INT(isect_polygon_normal(sliver, 3, n), ISECT_OK);
    CHECK_NEAR(n[2], 1.0, 1e-15);
    CHECK(fabs(n[0]) < 1e-15 && fabs(n[1]) < 1e-15);

    /* Integer points on x + 2y + 2z = 0 (normal (1, 2, 2)/3), shifted far
     * from the origin; and the same scaled to 1e300 and to 1e-300. */
    static const double tilted[12] = { 0, 0, 0, 2, -1, 0, 2, 1, -2, 0, 1, -1 };
    static const double shifts[4] = { 0, 1e8, 0x1p40, -3e12 };
    for (int s = 0; s < 4; s++) {
        double v[12];
        for (int k = 0; k < 12; k++)
            v[k] = tilted[k] + shifts[s] * (k % 3 == 1 ? -1 : 1);
        CHECK_EQ_INT(isect_polygon_normal(v, 4, n), ISECT_OK);
        CHECK_NEAR(n[0], 1.0 / 3.0, 1e-15);
        CHECK_NEAR(n[1], 2.0 / 3.0, 1e-15);
        CHECK_NEAR(n[2], 2.0 / 3.0, 1e-15);
        /* d = -n.centroid, the centroid (1, 1/4, -3/4) + shift (1, -1, 1). */
        double plane[4];
        CHECK_EQ_INT(isect_plane_from_points(v, 4, plane), ISECT_OK);
        CHECK_NEAR(plane[3], -(1.0 + 0.5 - 1.5 + shifts[s]) / 3.0, 1e-15);
        for (int i = 0; i < 4; i++) {
            double f = plane[0] * v[3 * i] + plane[1] * v[3 * i + 1] + plane[2] * v[3 * i + 2]
                     + plane[3];
            CHECK(fabs(f) <= 4 * DBL_EPSILON * fmax(1.0, fabs(shifts[s])));
        }
    }
    static const double scales[3] = { 1e300, 1e-300, 0x1p-1070 };
    for (int s = 0; s < 3; s++) {
        double v[12];
        for (int k = 0; k < 12; k++)
            v[k] = tilted[k] * scales[s];
        CHECK_EQ_INT(isect_polygon_normal(v, 4, n), ISECT_OK);
        CHECK_NEAR(n[0], 1.0 / 3.0, 1e-15);
        CHECK_NEAR(n[2], 2.0 / 3.0, 1e-15);
    }
    /* Far apart coordinates near the overflow threshold. */
    static const double huge[9] = { -1e308, -1e308, 0, 1e308, -1e308, 0, 0, 1e308, 0 };
    CHECK_EQ_INT(isect_polygon_normal(huge, 3, n), ISECT_OK);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 1);

    /* Zero area: a bowtie whose halves cancel, a repeated point, a line. */
    static const double bowtie[12] = { 0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0 };
    static const double same[9] = { 1, 2, 3, 1, 2, 3, 1, 2, 3 };
    static const double line[12] = { 0, 0, 0, 1, 1, 1, 3, 3, 3, 2, 2, 2 };
    CHECK_EQ_INT(isect_polygon_normal(bowtie, 4, n), ISECT_E_DEGENERATE);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 0);
    CHECK_EQ_INT(isect_polygon_normal(same, 3, n), ISECT_E_DEGENERATE);
    CHECK_EQ_INT(isect_polygon_normal(line, 4, n), ISECT_E_DEGENERATE);
    isect_ray r = ray_make(0.75, 0.5, 1, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_polygon(&r, bowtie, 4, ISECT_NONZERO, NULL, NULL, 0), 0);
}

/* A slightly non-planar quad (a saddle, z = +-1/4 at alternate corners):
 * Newell's normal is exactly (0, 0, 1) and the plane goes through the
 * vertex centroid, z = 0, not through any vertex. */
static void test_nonplanar_uses_centroid_plane(void)
{
    static const double saddle[12] = { 0, 0, 0.25, 1, 0, -0.25, 1, 1, 0.25, 0, 1, -0.25 };
    double n[3], plane[4];
    CHECK_EQ_INT(isect_polygon_normal(saddle, 4, n), ISECT_OK);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 1);
    CHECK_EQ_INT(isect_plane_from_points(saddle, 4, plane), ISECT_OK);
    CHECK(plane[3] == 0);
    isect_ray r = ray_make(0.25, 0.5, 3, 0, 0, -1);
    isect_hit h;
    CHECK_EQ_INT(isect_ray_polygon(&r, saddle, 4, ISECT_EVEN_ODD, NULL, &h, 1), 1);
    CHECK(h.t == 3 && h.point[2] == 0);
}

/* ------------------------------------------------------------ bad input */

static void test_bad_input(void)
{
    static const double sq[12] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
    static const double sq2[8] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    isect_ray r = ray_make(0.5, 0.5, 1, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, ISECT_EVEN_ODD, NULL, NULL, 0), 1);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 2, ISECT_EVEN_ODD, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 0, ISECT_EVEN_ODD, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, -3, ISECT_EVEN_ODD, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, 2, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_polygon(&r, sq, 4, -1, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_polygon(&r, NULL, 4, ISECT_EVEN_ODD, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_polygon(NULL, sq, 4, ISECT_EVEN_ODD, NULL, NULL, 0), ISECT_E_ARG);
    double bad[12];
    memcpy(bad, sq, sizeof bad);
    bad[7] = NAN;
    CHECK_EQ_INT(isect_ray_polygon(&r, bad, 4, ISECT_EVEN_ODD, NULL, NULL, 0),
                 ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_polygon(&r, bad, 2, ISECT_EVEN_ODD, NULL, NULL, 0), ISECT_E_ARG);
    bad[7] = -INFINITY;
    CHECK_EQ_INT(isect_ray_polygon(&r, bad, 4, ISECT_NONZERO, NULL, NULL, 0),
                 ISECT_E_NONFINITE);
    /* Only the first n vertices are read: a NaN after them is fine. */
    CHECK_EQ_INT(isect_ray_polygon(&r, bad, 2 + 0, ISECT_NONZERO, NULL, NULL, 0), ISECT_E_ARG);

    /* Triangle. */
    CHECK_EQ_INT(isect_ray_triangle(&r, NULL, sq + 3, sq + 6, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_triangle(&r, sq, sq + 3, NULL, NULL, NULL, 0), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_triangle(&r, bad, bad + 3, bad + 6, NULL, NULL, 0),
                 ISECT_E_NONFINITE);
    isect_hit h;
    CHECK_EQ_INT(isect_ray_triangle(&r, sq, sq + 3, sq + 6, NULL, NULL, 1), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_triangle(&r, sq, sq + 3, sq + 6, NULL, &h, -1), ISECT_E_ARG);
    isect_ray rn = r;
    rn.dir[2] = 0;
    CHECK_EQ_INT(isect_ray_triangle(&rn, sq, sq + 3, sq + 6, NULL, NULL, 0),
                 ISECT_E_DEGENERATE);

    /* Through the descriptor: n and flags carry the count and rule. */
    isect_shape s = { ISECT_POLYGON, 4, ISECT_NONZERO, 0, sq, NULL, NULL };
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, NULL, 0), 1);
    s.flags = 7;
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, NULL, 0), ISECT_E_ARG);
    s.flags = ISECT_EVEN_ODD;
    s.n = 1;
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, NULL, 0), ISECT_E_ARG);
    isect_shape t = { ISECT_TRIANGLE, 0, 0, 0, sq, NULL, NULL };
    CHECK_EQ_INT(isect_intersect(&t, &r, NULL, NULL, 0), 0); /* (0.5, 0.5): on the diagonal */
    isect_ray r2 = ray_make(0.75, 0.25, 1, 0, 0, -1);
    CHECK_EQ_INT(isect_intersect(&t, &r2, NULL, NULL, 0), 1);
    t.n = 3;
    CHECK_EQ_INT(isect_intersect(&t, &r, NULL, NULL, 0), ISECT_E_ARG);
    t.n = 0;
    CHECK_EQ_INT(isect_contains(&t, sq), ISECT_E_ARG); /* thin */

    /* Helpers. */
    double n[3] = { 7, 7, 7 }, plane[4];
    CHECK_EQ_INT(isect_polygon_normal(NULL, 4, n), ISECT_E_ARG);
    CHECK_EQ_INT(isect_polygon_normal(sq, 4, NULL), ISECT_E_ARG);
    CHECK_EQ_INT(isect_polygon_normal(sq, 2, n), ISECT_E_ARG);
    bad[7] = NAN;
    CHECK_EQ_INT(isect_polygon_normal(bad, 4, n), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_plane_from_points(NULL, 4, plane), ISECT_E_ARG);
    CHECK_EQ_INT(isect_plane_from_points(sq, 4, NULL), ISECT_E_ARG);
    CHECK_EQ_INT(isect_plane_from_points(sq, -1, plane), ISECT_E_ARG);
    CHECK_EQ_INT(isect_plane_from_points(bad, 4, plane), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_plane_from_points(sq, 4, plane), ISECT_OK);
    CHECK(plane[0] == 0 && plane[1] == 0 && plane[2] == 1 && plane[3] == 0);

    /* 2D. */
    double q[2] = { 0.5, 0.5 }, qnan[2] = { NAN, 0.5 }, poly_nan[8];
    memcpy(poly_nan, sq2, sizeof poly_nan);
    poly_nan[3] = INFINITY;
    int32_t w = 5;
    CHECK_EQ_INT(isect_point_in_polygon2(sq2, 4, q, ISECT_EVEN_ODD), 1);
    CHECK_EQ_INT(isect_point_in_polygon2(NULL, 4, q, ISECT_EVEN_ODD), ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2(sq2, 4, NULL, ISECT_EVEN_ODD), ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2(sq2, 2, q, ISECT_EVEN_ODD), ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2(sq2, 4, q, 3), ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2(poly_nan, 4, q, ISECT_NONZERO), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_point_in_polygon2(sq2, 4, qnan, ISECT_NONZERO), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_winding_number2(sq2, 4, q, &w), ISECT_OK);
    CHECK_EQ_INT(w, 1);
    CHECK_EQ_INT(isect_winding_number2(sq2, 4, q, NULL), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number2(NULL, 4, q, &w), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number2(sq2, 4, NULL, &w), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number2(sq2, -5, q, &w), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number2(poly_nan, 4, q, &w), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_winding_number2(sq2, 4, qnan, &w), ISECT_E_NONFINITE);

    /* Batches: a bad point is marked and the batch goes on. */
    double pts[10] = { 0.5, 0.5, NAN, 0, 2, 2, 0.25, INFINITY, 0.75, 0.25 };
    uint8_t inside[5] = { 9, 9, 9, 9, 9 };
    int32_t wind[5] = { 9, 9, 9, 9, 9 };
    CHECK_EQ_INT(isect_point_in_polygon2_batch(sq2, 4, pts, 5, ISECT_EVEN_ODD, inside), 2);
    CHECK(inside[0] == 1 && inside[1] == ISECT_INVALID && inside[2] == 0
          && inside[3] == ISECT_INVALID && inside[4] == 1);
    CHECK_EQ_INT(isect_winding_number2_batch(sq2, 4, pts, 5, wind), 2);
    CHECK(wind[0] == 1 && wind[1] == INT32_MIN && wind[2] == 0 && wind[3] == INT32_MIN
          && wind[4] == 1);
    CHECK_EQ_INT(isect_point_in_polygon2_batch(sq2, 4, pts, -1, ISECT_EVEN_ODD, inside),
                 ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2_batch(sq2, 4, pts, 5, 9, inside), ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2_batch(sq2, 4, NULL, 5, ISECT_EVEN_ODD, inside),
                 ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2_batch(sq2, 4, pts, 5, ISECT_EVEN_ODD, NULL),
                 ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2_batch(NULL, 4, pts, 5, ISECT_EVEN_ODD, inside),
                 ISECT_E_ARG);
    CHECK_EQ_INT(isect_point_in_polygon2_batch(poly_nan, 4, pts, 5, ISECT_EVEN_ODD, inside),
                 ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_point_in_polygon2_batch(sq2, 4, NULL, 0, ISECT_EVEN_ODD, NULL), 0);
    CHECK_EQ_INT(isect_winding_number2_batch(sq2, 4, pts, -2, wind), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number2_batch(sq2, 2, pts, 5, wind), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number2_batch(sq2, 4, pts, 5, NULL), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number2_batch(poly_nan, 4, pts, 5, wind), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_winding_number2_batch(sq2, 4, NULL, 0, NULL), 0);
}

/* A many-sided polygon (a 1000-gon with integer vertices around a circle
 * of radius 2^20) and a star with repeated vertices. */
static void test_large_polygon(void)
{
    enum { N = 1000 };
    static double v[3 * N], v2[2 * N];
    for (int i = 0; i < N; i++) {
        double a = 2.0 * 3.14159265358979323846 * i / N;
        v[3 * i] = v2[2 * i] = floor(0x1p20 * cos(a));
        v[3 * i + 1] = v2[2 * i + 1] = floor(0x1p20 * sin(a));
        v[3 * i + 2] = 7;
    }
    isect_ray r = ray_make(1000, -2000, 10, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_polygon(&r, v, N, ISECT_EVEN_ODD, NULL, NULL, 0), 1);
    r = ray_make(0x1p20 + 1, 0, 10, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_polygon(&r, v, N, ISECT_EVEN_ODD, NULL, NULL, 0), 0);
    double q[2] = { 0.5 * 0x1p20, 0.5 * 0x1p20 };
    int32_t w = 0;
    CHECK_EQ_INT(isect_winding_number2(v2, N, q, &w), ISECT_OK);
    CHECK_EQ_INT(w, 1);
    /* Repeated consecutive vertices (zero-length edges) change nothing. */
    static const double dup[14] = { 0, 0, 0, 0, 1, 0, 1, 0, 1, 1, 1, 1, 0, 1 };
    double in[2] = { 0.5, 0.5 }, out[2] = { 1.5, 0.5 };
    CHECK_EQ_INT(isect_point_in_polygon2(dup, 7, in, ISECT_EVEN_ODD), 1);
    CHECK_EQ_INT(isect_point_in_polygon2(dup, 7, out, ISECT_EVEN_ODD), 0);
}

int main(void)
{
    test_triangle_hit_record();
    test_triangle_far_and_tilted();
    test_extreme_scales();
    test_parallel_rays();
    test_degenerate_never_hit();
    test_concave_polygon();
    test_pentagram();
    test_triangle_polygon_agree();
    test_newell_normal();
    test_nonplanar_uses_centroid_plane();
    test_bad_input();
    test_large_polygon();
    return check_summary();
}
