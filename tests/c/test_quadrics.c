/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_quadrics.c — sphere, ellipsoid, finite and infinite cylinder and the
 * general quadric: hits, misses, origins behind / inside / on the surface,
 * tangency on both sides of the eps threshold, non-unit directions, a far
 * small sphere to the last ulp, rims and axis-parallel rays, linear quadric
 * cases, containment and bad input.
 *
 * Every expected value is worked out by hand in the comment next to it
 * (closed forms, or configurations whose answers are exact dyadic numbers);
 * none is taken from the library.
 */
#include "check.h"

#include <isect.h>

#include <float.h>
#include <string.h>

#define TOL 1e-12

static const double origin[3] = { 0, 0, 0 };

static isect_ray ray_make(double ox, double oy, double oz, double dx, double dy, double dz)
{
    isect_ray r = { { ox, oy, oz }, { dx, dy, dz }, 0.0, INFINITY };
    return r;
}

/* The same ray over the whole line. */
static isect_ray line_make(double ox, double oy, double oz, double dx, double dy, double dz)
{
    isect_ray r = ray_make(ox, oy, oz, dx, dy, dz);
    r.tmin = -INFINITY;
    return r;
}

static isect_opts opts_eps(double eps)
{
    isect_opts o = ISECT_OPTS_INIT;
    o.eps = eps;
    return o;
}

/* Checks every field of one hit; reports the caller's line. */
static void hit_check(int line, const isect_hit *h, double t, const double p[3],
                      const double n[3], int prim, int kind, double tol)
{
    char what[96];
    int ok = fabs(h->t - t) <= tol * fmax(1.0, fabs(t));
    snprintf(what, sizeof what, "hit t = %.17g, expected %.17g", h->t, t);
    check_record(ok, __FILE__, line, what);
    for (int k = 0; k < 3; k++) {
        ok = fabs(h->point[k] - p[k]) <= tol * fmax(1.0, fabs(p[k]));
        snprintf(what, sizeof what, "hit point[%d] = %.17g, expected %.17g", k, h->point[k], p[k]);
        check_record(ok, __FILE__, line, what);
        ok = fabs(h->normal[k] - n[k]) <= tol;
        snprintf(what, sizeof what, "hit normal[%d] = %.17g, expected %.17g", k, h->normal[k],
                 n[k]);
        check_record(ok, __FILE__, line, what);
    }
    snprintf(what, sizeof what, "hit prim = %d, expected %d", (int)h->prim, prim);
    check_record(h->prim == prim, __FILE__, line, what);
    snprintf(what, sizeof what, "hit kind = %d, expected %d", (int)h->kind, kind);
    check_record(h->kind == kind, __FILE__, line, what);
    check_record(h->uv[0] == 0.0 && h->uv[1] == 0.0, __FILE__, line, "hit uv == 0");
}

#define V3(x, y, z) ((const double[3]){ (x), (y), (z) })
#define HIT(h, t, p, n, prim, kind) hit_check(__LINE__, (h), (t), (p), (n), (prim), (kind), TOL)
#define HIT_TOL(h, t, p, n, prim, kind, tol) \
    hit_check(__LINE__, (h), (t), (p), (n), (prim), (kind), (tol))

/* Distance in ulps between two doubles of the same sign. */
static double ulps(double a, double b)
{
    int e;
    (void)frexp(fmax(fabs(a), fabs(b)), &e);
    return fabs(a - b) / ldexp(1.0, e - 53);
}

/* ---------------------------------------------------------------- sphere */

static void test_sphere_basic(void)
{
    isect_hit h[4];
    isect_ray r = ray_make(-5, 0, 0, 1, 0, 0);
    /* |(-5 + t, 0, 0)| = 1 at t = 4, 6 */
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 2);
    HIT(&h[0], 4.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(1, 0, 0), V3(1, 0, 0), -1, ISECT_EXIT);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, NULL, 0), 2); /* count only */

    /* miss: the line passes at distance 2 */
    r = ray_make(-5, 2, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 0);

    /* behind the origin: roots -6, -4 */
    r = ray_make(5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 2);
    HIT(&h[0], -6.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], -4.0, V3(1, 0, 0), V3(1, 0, 0), -1, ISECT_EXIT);

    /* origin inside: only the exit at t = 1 */
    r = ray_make(0, 0, 0, 0, 1, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 1);
    HIT(&h[0], 1.0, V3(0, 1, 0), V3(0, 1, 0), -1, ISECT_EXIT);

    /* centre off the origin: c = (1, 2, 3), r = 2, ray along -z from z = 10:
     * z - 3 = +-2 at t = 5, 9 */
    r = ray_make(1, 2, 10, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_sphere(&r, V3(1, 2, 3), 2.0, NULL, h, 4), 2);
    HIT(&h[0], 5.0, V3(1, 2, 5), V3(0, 0, 1), -1, ISECT_ENTER);
    HIT(&h[1], 9.0, V3(1, 2, 1), V3(0, 0, -1), -1, ISECT_EXIT);

    /* oblique: c = 0, r = 5, line (t, 3, 0)... through x = +-4 (3-4-5) */
    r = line_make(0, 3, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 5.0, NULL, h, 4), 2);
    HIT(&h[0], -4.0, V3(-4, 3, 0), V3(-0.8, 0.6, 0), -1, ISECT_ENTER);
    HIT(&h[1], 4.0, V3(4, 3, 0), V3(0.8, 0.6, 0), -1, ISECT_EXIT);
}

static void test_sphere_on_surface(void)
{
    isect_hit h[4];
    /* origin (3, 4, 0) on |x| = 5 (exact), going -x: x = 3 - t, x^2 = 9 at
     * t = 0 (entering: the normal (0.6, 0.8, 0) faces against -x) and 6 */
    isect_ray r = ray_make(3, 4, 0, -1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 5.0, NULL, h, 4), 2);
    HIT(&h[0], 0.0, V3(3, 4, 0), V3(0.6, 0.8, 0), -1, ISECT_ENTER);
    CHECK(h[0].t == 0.0 && !signbit(h[0].t)); /* exactly +0 */
    HIT(&h[1], 6.0, V3(-3, 4, 0), V3(-0.6, 0.8, 0), -1, ISECT_EXIT);

    /* going +x: roots -6 and 0; only the exit at t = 0 is in [0, inf) */
    r = ray_make(3, 4, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 5.0, NULL, h, 4), 1);
    HIT(&h[0], 0.0, V3(3, 4, 0), V3(0.6, 0.8, 0), -1, ISECT_EXIT);
    CHECK(h[0].t == 0.0 && !signbit(h[0].t));

    /* along the normal from (0, 0, 5): roots 0 and 10 (dir (0,0,-1)) */
    r = ray_make(0, 0, 5, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 5.0, NULL, h, 4), 2);
    HIT(&h[0], 0.0, V3(0, 0, 5), V3(0, 0, 1), -1, ISECT_ENTER);
    HIT(&h[1], 10.0, V3(0, 0, -5), V3(0, 0, -1), -1, ISECT_EXIT);
}

/*
 * Tangency: line (-5 + t, y, 0) against the unit sphere; h = |y|, and
 * |r^2 - h^2| = |1 - y^2|. With y = 1 -+ 2^-k exactly representable,
 * 1 - y^2 = +-2^(1-k) - 2^-2k: about 2^-41 = 4.5e-13 for k = 42 (below the
 * default eps 1e-12: TOUCH) and 2^-39 = 1.8e-12 for k = 40 (above: two
 * hits at t = 5 -+ sqrt(1 - y^2), or none when y > 1).
 */
static void test_sphere_tangency(void)
{
    isect_hit h[4];
    isect_opts eps0 = opts_eps(0.0);
    isect_ray r = ray_make(-5, 1, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, 1, 0), V3(0, 1, 0), -1, ISECT_TOUCH);
    /* exact tangency still touches with eps = 0 */
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &eps0, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, 1, 0), V3(0, 1, 0), -1, ISECT_TOUCH);

    double y_in_touch = 1.0 - ldexp(1, -42), y_in_two = 1.0 - ldexp(1, -40);
    double y_out_touch = 1.0 + ldexp(1, -42), y_out_miss = 1.0 + ldexp(1, -40);

    r = ray_make(-5, y_in_touch, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, y_in_touch, 0), V3(0, 1, 0), -1, ISECT_TOUCH);
    /* eps = 0: two hits, half chord sqrt(1 - y^2) = sqrt(2^-41 - 2^-84) */
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &eps0, h, 4), 2);
    double w = sqrt(ldexp(1, -41) - ldexp(1, -84));
    CHECK_NEAR(h[0].t, 5.0 - w, 1e-15);
    CHECK_NEAR(h[1].t, 5.0 + w, 1e-15);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    CHECK_EQ_INT(h[1].kind, ISECT_EXIT);

    r = ray_make(-5, y_in_two, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 2);
    w = sqrt(ldexp(1, -39) - ldexp(1, -80));
    HIT(&h[0], 5.0 - w, V3(-w, y_in_two, 0), V3(-w, y_in_two, 0), -1, ISECT_ENTER);
    HIT(&h[1], 5.0 + w, V3(w, y_in_two, 0), V3(w, y_in_two, 0), -1, ISECT_EXIT);
    CHECK(h[0].t < h[1].t);

    r = ray_make(-5, y_out_touch, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, 1, 0), V3(0, 1, 0), -1, ISECT_TOUCH);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &eps0, h, 4), 0);

    r = ray_make(-5, y_out_miss, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 0);

    /* r = 0.1 (r^2 not a double), y = r - 2^-40 (exact): 1 - (y/r)^2 ~ 1.8e-10,
     * two hits at 5 -+ sqrt((r - y)(r + y)), r - y exact, r + y and the
     * product one rounding each. Forming r^2 - y^2 from a rounded r^2 would
     * cost ~3e-13 in t. */
    double r_tenth = 0.1, y_tenth = 0.1 - ldexp(1, -40);
    r = ray_make(-5, y_tenth, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, r_tenth, NULL, h, 4), 2);
    w = sqrt((r_tenth - y_tenth) * (r_tenth + y_tenth));
    CHECK_NEAR(h[0].t, 5.0 - w, 1e-16);
    CHECK_NEAR(h[1].t, 5.0 + w, 1e-16);

    /* a looser eps: 1e-6. y = 1 - 2^-30: |1 - y^2| ~ 2^-29 = 1.9e-9 -> TOUCH;
     * y = 1 - 2^-18: ~ 2^-17 = 7.6e-6 -> two hits */
    isect_opts loose = opts_eps(1e-6);
    r = ray_make(-5, 1.0 - ldexp(1, -30), 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &loose, h, 4), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_TOUCH);
    r = ray_make(-5, 1.0 - ldexp(1, -18), 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &loose, h, 4), 2);

    /* scale invariance: the same configuration scaled by 2^300 and 2^-300
     * decides the same way and scales t (dir kept): t = 5 * 2^+-300 */
    for (int s = -300; s <= 300; s += 600) {
        double k = ldexp(1, s);
        r = ray_make(-5 * k, y_in_touch * k, 0, 1, 0, 0);
        CHECK_EQ_INT(isect_ray_sphere(&r, origin, k, NULL, h, 4), 1);
        CHECK_NEAR(h[0].t / k, 5.0, 1e-15);
        r = ray_make(-5 * k, y_in_two * k, 0, 1, 0, 0);
        CHECK_EQ_INT(isect_ray_sphere(&r, origin, k, NULL, h, 4), 2);
    }
}

static void test_sphere_direction_scale(void)
{
    isect_hit h[4];
    /* dir (4, 0, 0): the unit case's t = 4, 6 divided by 4 */
    isect_ray r = ray_make(-5, 0, 0, 4, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 2);
    HIT(&h[0], 1.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], 1.5, V3(1, 0, 0), V3(1, 0, 0), -1, ISECT_EXIT);
    /* dir (0.5, 0, 0): times 2 */
    r = ray_make(-5, 0, 0, 0.5, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 2);
    HIT(&h[0], 8.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], 12.0, V3(1, 0, 0), V3(1, 0, 0), -1, ISECT_EXIT);
    /* a tiny and a huge direction: t = 4 / 2^-600 and 4 / 2^600 */
    r = ray_make(-5, 0, 0, ldexp(1, -600), 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 2);
    CHECK(h[0].t == ldexp(4, 600) && h[1].t == ldexp(6, 600));
    r = ray_make(-5, 0, 0, ldexp(1, 600), 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, NULL, h, 4), 2);
    CHECK(h[0].t == ldexp(4, -600) && h[1].t == ldexp(6, -600));
    /* diagonal dir (1, 1, 0) from (-5, -5, 0) to the sphere of radius
     * sqrt(2)*... : |(-5 + t)(1, 1, 0)| = sqrt(2)|t - 5| = 2 -> t = 5 -+ sqrt(2) */
    r = ray_make(-5, -5, 0, 1, 1, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 2.0, NULL, h, 4), 2);
    double s2 = sqrt(2.0);
    HIT(&h[0], 5.0 - s2, V3(-s2, -s2, 0), V3(-s2 / 2, -s2 / 2, 0), -1, ISECT_ENTER);
    HIT(&h[1], 5.0 + s2, V3(s2, s2, 0), V3(s2 / 2, s2 / 2, 0), -1, ISECT_EXIT);
}

/*
 * Haines et al.'s test: a sphere of radius r = 1e-3 (the double nearest) at
 * distance 1e7. Along an axis the exact roots are 1e7 -+ r, so the expected
 * values are the correctly rounded IEEE differences 1e7 - 1e-3 and
 * 1e7 + 1e-3 (one rounding of exact operands). The naive b^2 - 4ac form
 * loses about half the digits here.
 */
static void test_sphere_far_small(void)
{
    isect_hit h[4];
    const double r_small = 1e-3, far = 1e7;
    double near_t = far - r_small, far_t = far + r_small;

    isect_ray r = ray_make(0, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, V3(far, 0, 0), r_small, NULL, h, 4), 2);
    CHECK(ulps(h[0].t, near_t) <= 1.0);
    CHECK(ulps(h[1].t, far_t) <= 1.0);
    CHECK(ulps(h[0].point[0], near_t) <= 1.0);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    CHECK(h[0].normal[0] == -1.0);

    /* from the far side, backwards: 2e7 - (1e7 + r) = 1e7 - r exactly */
    r = ray_make(2 * far, 0, 0, -1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, V3(far, 0, 0), r_small, NULL, h, 4), 2);
    CHECK(ulps(h[0].t, near_t) <= 1.0);
    CHECK(ulps(h[1].t, far_t) <= 1.0);

    /* along -z with dir (0, 0, -2): t halves exactly */
    r = ray_make(0, 0, 0, 0, 0, -2);
    CHECK_EQ_INT(isect_ray_sphere(&r, V3(0, 0, -far), r_small, NULL, h, 4), 2);
    CHECK(ulps(h[0].t, near_t / 2) <= 1.0);
    CHECK(ulps(h[1].t, far_t / 2) <= 1.0);

    /* the sphere at the coordinate origin, seen from 1e7 away: the point is
     * placed from the centre, so it is -r to full relative precision (org +
     * t*dir would only be good to ulp(1e7) ~ 2e-9, i.e. 1e-6 relative) */
    r = ray_make(-far, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, r_small, NULL, h, 4), 2);
    CHECK(ulps(h[0].t, near_t) <= 1.0);
    CHECK(ulps(h[0].point[0], -r_small) <= 1.0);
    CHECK(ulps(h[1].point[0], r_small) <= 1.0);
    CHECK(h[0].point[1] == 0.0 && h[0].point[2] == 0.0);

    /* a huge sphere hit near the coordinate origin keeps the small
     * coordinates (org + t*dir there, good to ~u absolutely; c + R n would
     * only be good to u*1e7 ~ 1e-9): c = (0, 0, -1e7), R = 1e7 touches z = 0
     * at the origin; the line x = 1, dir -z meets it at
     * z = -1e7 + sqrt(1e14 - 1) = -1/(1e7 + sqrt(1e14 - 1)) ~ -5e-8 */
    r = ray_make(1, 0, 1, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_sphere(&r, V3(0, 0, -far), far, NULL, h, 4), 2);
    double z_hit = -1.0 / (far + sqrt(far * far - 1.0));
    CHECK(fabs(h[0].point[2] - z_hit) <= 1e-15);
    CHECK_NEAR(h[0].t, 1.0 - z_hit, 1e-15);
}

/* A sphere whose radius is more than 2^450 below the distances (found by
 * tests/fuzz/fuzz_shape): r^2 underflowed in the exact path, so a ray
 * through the centre was one TOUCH with a zero normal. Centre at the origin,
 * radius 2^-600, the line from -8.75 (1, 1, 1) along -8.75 (1, 1, 1): it
 * passes through the centre at t = -1 and crosses the sphere at
 * t = -1 -+ 2^-600 / (8.75 sqrt 3), both rounding to -1; the crossings are
 * at -+ 2^-600 (1, 1, 1)/sqrt 3, normals -+ (1, 1, 1)/sqrt 3 (the direction
 * is -(1, 1, 1), so the entry is on the +(1, 1, 1) side). */
static void test_sphere_tiny_radius(void)
{
    const double r_tiny = 0x1p-600, s3 = 1.0 / sqrt(3.0);
    const double bounds[4][2] = { { -INFINITY, INFINITY }, { -1e300, 1e300 },
                                  { -DBL_MAX, DBL_MAX }, { -2.0, -0.999999 } };
    isect_hit h[4];
    for (int i = 0; i < 4; i++) {
        isect_ray r = line_make(-8.75, -8.75, -8.75, -8.75, -8.75, -8.75);
        r.tmin = bounds[i][0];
        r.tmax = bounds[i][1];
        CHECK_EQ_INT(isect_ray_sphere(&r, origin, r_tiny, NULL, h, 4), 2);
        hit_check(__LINE__, &h[0], -1.0, V3(r_tiny * s3, r_tiny * s3, r_tiny * s3),
                  V3(s3, s3, s3), -1, ISECT_ENTER, TOL);
        hit_check(__LINE__, &h[1], -1.0, V3(-r_tiny * s3, -r_tiny * s3, -r_tiny * s3),
                  V3(-s3, -s3, -s3), -1, ISECT_EXIT, TOL);
    }
    /* Intervals that end between or before the crossings (t = -1 is
     * neither of them). */
    isect_ray r = line_make(-8.75, -8.75, -8.75, -8.75, -8.75, -8.75);
    r.tmax = -1.0;
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, r_tiny, NULL, h, 4), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    r.tmin = -1.0;
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, r_tiny, NULL, h, 4), 0);
    r.tmin = -0.5;
    r.tmax = INFINITY;
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, r_tiny, NULL, h, 4), 0);
    /* The smallest normal radius scale the fuzzer used, 2^-1007. */
    r = line_make(-8.75, -8.75, -8.75, -8.75, -8.75, -8.75);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 0x1.004p-1007, NULL, h, 4), 2);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    CHECK_NEAR(h[0].normal[0], s3, TOL);
    /* Containment at that scale: r/2 inside, 2r outside. */
    isect_shape s = { ISECT_SPHERE, 0, 0, 0, (const double[]){ 0, 0, 0, 0x1p-600 }, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&s, V3(0x1p-601, 0, 0)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(0x1p-599, 0, 0)), 0);
}

/* eps >= 1 declares a line through the centre tangent (|G| = r^2 D <=
 * eps r^2 D; found by tests/fuzz/fuzz_shape): one TOUCH at the foot of the
 * perpendicular, the centre, t = 5 for the unit sphere seen from (0, 0, -5)
 * along +z; its normal was 0 (the foot has no direction) and is -unit(dir),
 * the ellipsoid's choice there, at any scale of the direction. */
static void test_sphere_touch_through_centre(void)
{
    isect_hit h[4];
    isect_opts o = opts_eps(2.0);
    isect_ray r = ray_make(0, 0, -5, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &o, h, 4), 1);
    hit_check(__LINE__, &h[0], 5.0, origin, V3(0, 0, -1), -1, ISECT_TOUCH, TOL);
    r = ray_make(0, 0, -5, 0, 0, 0x1p-600);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &o, h, 4), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_TOUCH);
    CHECK(h[0].normal[0] == 0.0 && h[0].normal[1] == 0.0 && h[0].normal[2] == -1.0);
}

static void test_sphere_degenerate_and_bad(void)
{
    isect_hit h[4];
    isect_ray r = ray_make(-5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 0.0, NULL, h, 4), 0);  /* r = 0 */
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, -0.0, NULL, h, 4), 0); /* -0 is zero */
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, -1.0, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, NAN, NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, INFINITY, NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_sphere(&r, V3(0, NAN, 0), 1.0, NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_sphere(&r, V3(-INFINITY, 0, 0), 1.0, NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_sphere(&r, NULL, 1.0, NULL, h, 4), ISECT_E_ARG);

    /* coordinates near the double range: org - c would overflow unscaled.
     * c = (-1e308, 0, 0), r = 1e308, line from (1.5e308, 0, 0) along -x at
     * unit speed: x = 1.5e308 - t hits x = 0 at t = 1.5e308 (and the far side
     * x = -2e308 is beyond the double range: not reported) */
    r = ray_make(1.5e308, 0, 0, -1, 0, 0);
    int n = isect_ray_sphere(&r, V3(-1e308, 0, 0), 1e308, NULL, h, 4);
    CHECK_EQ_INT(n, 1);
    if (n == 1) {
        CHECK_NEAR(h[0].t / 1e308, 1.5, 1e-15);
        CHECK(isfinite(h[0].point[0]) && isfinite(h[0].normal[0]));
    }
}

static void test_sphere_contains(void)
{
    const double data[4] = { 0, 0, 0, 5 };
    isect_shape s = { ISECT_SPHERE, 0, 0, 0, data, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&s, V3(3, 4, 0)), 1); /* on the surface: closed */
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 0)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(5, 0, 0)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(nextafter(5.0, 6.0), 0, 0)), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(3, 4, 1e-7)), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(3, nextafter(4.0, 0.0), 0)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(1e300, 0, 0)), 0);
    const double zero[4] = { 1, 1, 1, 0 };
    s.data = zero;
    CHECK_EQ_INT(isect_contains(&s, V3(1, 1, 1)), 0); /* degenerate: contains nothing */
}

/* ------------------------------------------------------------- ellipsoid */

static void test_ellipsoid(void)
{
    isect_hit h[4];
    const double c[3] = { 1, 2, 3 }, radii[3] = { 2, 3, 4 };
    /* along x through the centre: x - 1 = +-2 at t = 8, 12 */
    isect_ray r = ray_make(-9, 2, 3, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, c, radii, NULL, h, 4), 2);
    HIT(&h[0], 8.0, V3(-1, 2, 3), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], 12.0, V3(3, 2, 3), V3(1, 0, 0), -1, ISECT_EXIT);
    /* along z, dir (0, 0, 2): z - 3 = +-4 from z = -7 at t = 3, 7 */
    r = ray_make(1, 2, -7, 0, 0, 2);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, c, radii, NULL, h, 4), 2);
    HIT(&h[0], 3.0, V3(1, 2, -1), V3(0, 0, -1), -1, ISECT_ENTER);
    HIT(&h[1], 7.0, V3(1, 2, 7), V3(0, 0, 1), -1, ISECT_EXIT);

    /* from the centre along the radii: y(t) = t (1, 1, 1), |y| = 1 at
     * t = +-1/sqrt(3); point c +- radii/sqrt(3); normal ~ y/radii ~
     * (1/2, 1/3, 1/4) ~ (6, 4, 3)/sqrt(61) */
    r = line_make(1, 2, 3, 2, 3, 4);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, c, radii, NULL, h, 4), 2);
    double s3 = 1.0 / sqrt(3.0), s61 = 1.0 / sqrt(61.0);
    HIT_TOL(&h[0], -s3, V3(1 - 2 * s3, 2 - 3 * s3, 3 - 4 * s3), V3(-6 * s61, -4 * s61, -3 * s61),
            -1, ISECT_ENTER, 1e-15);
    HIT_TOL(&h[1], s3, V3(1 + 2 * s3, 2 + 3 * s3, 3 + 4 * s3), V3(6 * s61, 4 * s61, 3 * s61), -1,
            ISECT_EXIT, 1e-15);

    /* origin inside: one exit */
    r = ray_make(1, 2, 3, 0, 1, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, c, radii, NULL, h, 4), 1);
    HIT(&h[0], 3.0, V3(1, 5, 3), V3(0, 1, 0), -1, ISECT_EXIT);
    /* miss */
    r = ray_make(-9, 5.5, 3, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, c, radii, NULL, h, 4), 0);

    /* equal radii: the sphere */
    r = ray_make(-5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, V3(1, 1, 1), NULL, h, 4), 2);
    HIT(&h[0], 4.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(1, 0, 0), V3(1, 0, 0), -1, ISECT_EXIT);
}

/* Tangency in the scaled frame: |1 - h'^2| <= eps. Line (-10 + t, y, 0)
 * against radii (2, 3, 4) at the origin: h' = y/3. */
static void test_ellipsoid_tangency(void)
{
    isect_hit h[4];
    const double radii[3] = { 2, 3, 4 };
    isect_ray r = ray_make(-10, 3, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, radii, NULL, h, 4), 1);
    HIT(&h[0], 10.0, V3(0, 3, 0), V3(0, 1, 0), -1, ISECT_TOUCH);

    /* y = 3 (1 - 2^-40) (exact), y/3 = 1 - 2^-40 (exact): |1 - h'^2| ~
     * 2^-39 > 1e-12, two hits at x = -+2 sqrt(1 - h'^2) */
    double y = 3.0 - 3.0 * ldexp(1, -40);
    r = ray_make(-10, y, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, radii, NULL, h, 4), 2);
    double x = 2.0 * sqrt(ldexp(1, -39) - ldexp(1, -80));
    CHECK_NEAR(h[0].t, 10.0 - x, 1e-15);
    CHECK_NEAR(h[1].t, 10.0 + x, 1e-15);
    /* y/3 = 1 - 2^-42: ~2^-41 < 1e-12: TOUCH at x = 0 */
    y = 3.0 - 3.0 * ldexp(1, -42);
    r = ray_make(-10, y, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, radii, NULL, h, 4), 1);
    HIT(&h[0], 10.0, V3(0, 3, 0), V3(0, 1, 0), -1, ISECT_TOUCH);
    isect_opts eps0 = opts_eps(0.0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, radii, &eps0, h, 4), 2);
    /* outside by 2^-40: miss */
    r = ray_make(-10, 3.0 + 3.0 * ldexp(1, -40), 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, radii, NULL, h, 4), 0);
}

static void test_ellipsoid_degenerate_and_bad(void)
{
    isect_hit h[4];
    isect_ray r = ray_make(-10, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, V3(2, 0, 4), NULL, h, 4), 0);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, V3(2, -1, 4), NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, V3(2, NAN, 4), NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, V3(INFINITY, 0, 0), V3(1, 1, 1), NULL, h, 4),
                 ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, NULL, V3(1, 1, 1), NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_ellipsoid(&r, origin, NULL, NULL, h, 4), ISECT_E_ARG);

    const double flat[6] = { 0, 0, 0, 2, 0, 4 };
    isect_shape s = { ISECT_ELLIPSOID, 0, 0, 0, flat, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 0)), 0);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 4), 0);
}

static void test_ellipsoid_contains(void)
{
    const double data[6] = { 0, 0, 0, 2, 3, 4 };
    isect_shape s = { ISECT_ELLIPSOID, 0, 0, 0, data, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&s, V3(2, 0, 0)), 1); /* boundary: closed */
    CHECK_EQ_INT(isect_contains(&s, V3(0, -3, 0)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 4)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, nextafter(4.0, 5.0))), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(1, 1, 1)), 1); /* 1/4 + 1/9 + 1/16 < 1 */
    CHECK_EQ_INT(isect_contains(&s, V3(2, 3, 0)), 0); /* 1 + 1 */
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 0)), 1);
}

/* -------------------------------------------------------------- cylinder */

/* The capped cylinder p0 = (0,0,0), p1 = (0,0,2), r = 1 used below. */
static const double cyl_p0[3] = { 0, 0, 0 }, cyl_p1[3] = { 0, 0, 2 };

static int cyl(const isect_ray *r, int capped, const isect_opts *o, isect_hit *h)
{
    return isect_ray_cylinder(r, cyl_p0, cyl_p1, 1.0, capped, o, h, 4);
}

static void test_cylinder_side_and_caps(void)
{
    isect_hit h[4];
    /* across the side at mid-height: x = -5 + t = -+1 at t = 4, 6 */
    isect_ray r = ray_make(-5, 0, 1, 1, 0, 0);
    for (int capped = 0; capped <= 1; capped++) {
        CHECK_EQ_INT(cyl(&r, capped, NULL, h), 2);
        HIT(&h[0], 4.0, V3(-1, 0, 1), V3(-1, 0, 0), 0, ISECT_ENTER);
        HIT(&h[1], 6.0, V3(1, 0, 1), V3(1, 0, 0), 0, ISECT_EXIT);
    }
    /* miss beside it, and above it */
    r = ray_make(-5, 1.5, 1, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 0);
    r = ray_make(-5, 0, 2.5, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 0);
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 0);

    /* in through the cap at p0, out through the side: (0.5 t, 0, -1 + t):
     * z = 0 at t = 1 (x = 0.5, inside the disk), x = 1 at t = 2 (z = 1) */
    r = ray_make(0, 0, -1, 0.5, 0, 1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], 1.0, V3(0.5, 0, 0), V3(0, 0, -1), 1, ISECT_ENTER);
    HIT(&h[1], 2.0, V3(1, 0, 1), V3(1, 0, 0), 0, ISECT_EXIT);
    /* open: only the side, from inside (back side): EXIT */
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 1);
    HIT(&h[0], 2.0, V3(1, 0, 1), V3(1, 0, 0), 0, ISECT_EXIT);
    /* open with back-face culling: nothing */
    isect_opts cull = ISECT_OPTS_INIT;
    cull.flags = ISECT_CULL_BACK;
    CHECK_EQ_INT(cyl(&r, 0, &cull, h), 0);

    /* origin inside the capped solid: only the exit */
    r = ray_make(0, 0, 1, 0, 0, 1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 1);
    HIT(&h[0], 1.0, V3(0, 0, 2), V3(0, 0, 1), 2, ISECT_EXIT);
    /* behind */
    r = ray_make(0, 0, 5, 0, 0, 1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], -5.0, V3(0, 0, 0), V3(0, 0, -1), 1, ISECT_ENTER);
    HIT(&h[1], -3.0, V3(0, 0, 2), V3(0, 0, 1), 2, ISECT_EXIT);
}

/* Parallel to the axis: |d x a| <= eps |d||a| -> the side is not hit. */
static void test_cylinder_parallel(void)
{
    isect_hit h[4];
    isect_ray r = ray_make(0.5, 0, -3, 0, 0, 1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], 3.0, V3(0.5, 0, 0), V3(0, 0, -1), 1, ISECT_ENTER);
    HIT(&h[1], 5.0, V3(0.5, 0, 2), V3(0, 0, 1), 2, ISECT_EXIT);
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 0); /* open: no side hit */
    /* downwards, dir (0, 0, -4): caps at z = 2, 0 reached at t = 0.75, 1.25 */
    r = ray_make(0.5, 0, 5, 0, 0, -4);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], 0.75, V3(0.5, 0, 2), V3(0, 0, 1), 2, ISECT_ENTER);
    HIT(&h[1], 1.25, V3(0.5, 0, 0), V3(0, 0, -1), 1, ISECT_EXIT);
    /* outside, parallel: nothing */
    r = ray_make(2, 0, -3, 0, 0, 1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 0);
    /* on the side surface itself (distance = r): inside the closed solid,
     * enters and leaves through the cap rims */
    r = ray_make(1, 0, -3, 0, 0, 1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], 3.0, V3(1, 0, 0), V3(0, 0, -1), 1, ISECT_ENTER);
    HIT(&h[1], 5.0, V3(1, 0, 2), V3(0, 0, 1), 2, ISECT_EXIT);
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 0);

    /* nearly parallel: |d x a|/(|d||a|) ~ 1e-13 <= 1e-12 -> parallel; the
     * caps are still crossed (z = 0, 2 at t = 3, 5; x moves by 5e-13) */
    r = ray_make(0.5, 0, -3, 1e-13, 0, 1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    CHECK_EQ_INT(h[0].prim, 1);
    CHECK_EQ_INT(h[1].prim, 2);
    CHECK_NEAR(h[0].t, 3.0, TOL);
    CHECK_NEAR(h[1].t, 5.0, TOL);
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 0);
    /* with eps = 0 the same ray is not parallel; it stays inside the side
     * between the caps (x = 0.5 + 1e-13 t), so still the two caps */
    isect_opts eps0 = opts_eps(0.0);
    CHECK_EQ_INT(cyl(&r, 1, &eps0, h), 2);
    CHECK_EQ_INT(h[0].prim, 1);
    CHECK_EQ_INT(h[1].prim, 2);
    /* ... and the open cylinder's side is met far away, x = +-1 at
     * t = (+-1 - 0.5)/1e-13, outside the caps: nothing */
    CHECK_EQ_INT(cyl(&r, 0, &eps0, h), 0);

    /* a slanted axis: p0 = (1,1,1), p1 = (3,3,3), ray along it from 0:
     * d x a = 0 exactly; caps where (x - p0).a = 0 and (x - p1).a = 0 */
    r = ray_make(0, 0, 0, 1, 1, 1);
    CHECK_EQ_INT(isect_ray_cylinder(&r, V3(1, 1, 1), V3(3, 3, 3), 0.5, 1, NULL, h, 4), 2);
    double k = 1.0 / sqrt(3.0);
    HIT(&h[0], 1.0, V3(1, 1, 1), V3(-k, -k, -k), 1, ISECT_ENTER);
    HIT(&h[1], 3.0, V3(3, 3, 3), V3(k, k, k), 2, ISECT_EXIT);
}

/* Rims: the circles where the side meets a cap. */
static void test_cylinder_rims(void)
{
    isect_hit h[4];
    /* (2 - t, 0, 3 - t): through the rim at p1, (1, 0, 2), at t = 1, and the
     * rim at p0, (-1, 0, 0), at t = 3. The side and the cap tie at both
     * ends; the side (prim 0) takes the tie. */
    isect_ray r = ray_make(2, 0, 3, -1, 0, -1);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], 1.0, V3(1, 0, 2), V3(1, 0, 0), 0, ISECT_ENTER);
    HIT(&h[1], 3.0, V3(-1, 0, 0), V3(-1, 0, 0), 0, ISECT_EXIT);
    /* open: both side crossings lie on the cap planes, which count (closed) */
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 2);
    HIT(&h[0], 1.0, V3(1, 0, 2), V3(1, 0, 0), 0, ISECT_ENTER);
    HIT(&h[1], 3.0, V3(-1, 0, 0), V3(-1, 0, 0), 0, ISECT_EXIT);

    /* (t, 0, 4 - 2t) meets the solid only at the rim point (1, 0, 2), t = 1:
     * inside the side for t in [-1, 1], between the caps for t in [1, 2].
     * Capped: entry (cap at p1, t = 1) == exit (side, t = 1): one TOUCH with
     * the entry's prim and normal, as for a convex polyhedron. */
    r = ray_make(0, 0, 4, 1, 0, -2);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 1);
    HIT(&h[0], 1.0, V3(1, 0, 2), V3(0, 0, 1), 2, ISECT_TOUCH);
    /* open: the side crossing at t = 1 is on the cap plane (kept), leaving
     * the infinite cylinder: EXIT; the one at t = -1 (z = 6) is clipped */
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 1);
    HIT(&h[0], 1.0, V3(1, 0, 2), V3(1, 0, 0), 0, ISECT_EXIT);

    /* just outside the rim: (t, 0, 4 + 2^-40 - 2t) is between the caps only
     * for t >= 1 + 2^-41, inside the side only for t <= 1 */
    r = ray_make(0, 0, 4.0 + ldexp(1, -40), 1, 0, -2);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 0);
}

/* Side tangency: |r^2 - h^2| <= eps r^2, h the line-axis distance. */
static void test_cylinder_tangency(void)
{
    isect_hit h[4];
    isect_opts eps0 = opts_eps(0.0);
    isect_ray r = ray_make(-5, 1, 1, 1, 0, 0);
    for (int capped = 0; capped <= 1; capped++) {
        CHECK_EQ_INT(cyl(&r, capped, NULL, h), 1);
        HIT(&h[0], 5.0, V3(0, 1, 1), V3(0, 1, 0), 0, ISECT_TOUCH);
        CHECK_EQ_INT(cyl(&r, capped, &eps0, h), 1);
    }
    /* y = 1 - 2^-42: |1 - y^2| ~ 2^-41 < 1e-12: TOUCH; eps = 0: two */
    r = ray_make(-5, 1.0 - ldexp(1, -42), 1, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_TOUCH);
    CHECK_EQ_INT(cyl(&r, 1, &eps0, h), 2);
    /* y = 1 - 2^-40: ~ 2^-39 > 1e-12: two hits at 5 -+ sqrt(2^-39 - 2^-80) */
    double y = 1.0 - ldexp(1, -40), w = sqrt(ldexp(1, -39) - ldexp(1, -80));
    r = ray_make(-5, y, 1, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], 5.0 - w, V3(-w, y, 1), V3(-w, y, 0), 0, ISECT_ENTER);
    HIT(&h[1], 5.0 + w, V3(w, y, 1), V3(w, y, 0), 0, ISECT_EXIT);
    /* y = 1 + 2^-42: TOUCH; y = 1 + 2^-40: miss */
    r = ray_make(-5, 1.0 + ldexp(1, -42), 1, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 1);
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 1);
    r = ray_make(-5, 1.0 + ldexp(1, -40), 1, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 0);

    /* tangent in the cap plane z = 2: the cap plane is parallel to the ray and
     * the origin is on it (inside): TOUCH on the side */
    r = ray_make(-5, 1, 2, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 1);
    HIT(&h[0], 5.0, V3(0, 1, 2), V3(0, 1, 0), 0, ISECT_TOUCH);
    /* across the cap disk inside its plane: in and out through the side */
    r = ray_make(-5, 0, 2, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 2);
    HIT(&h[0], 4.0, V3(-1, 0, 2), V3(-1, 0, 0), 0, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(1, 0, 2), V3(1, 0, 0), 0, ISECT_EXIT);
    /* tangent line outside the slab: nothing */
    r = ray_make(-5, 1, 3, 1, 0, 0);
    CHECK_EQ_INT(cyl(&r, 1, NULL, h), 0);
    CHECK_EQ_INT(cyl(&r, 0, NULL, h), 0);
}

static void test_cylinder_degenerate_and_bad(void)
{
    isect_hit h[4];
    isect_ray r = ray_make(-5, 0, 1, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_cylinder(&r, cyl_p0, cyl_p1, 0.0, 1, NULL, h, 4), 0);
    CHECK_EQ_INT(isect_ray_cylinder(&r, V3(0, 0, 1), V3(0, 0, 1), 1.0, 1, NULL, h, 4), 0);
    CHECK_EQ_INT(isect_ray_cylinder(&r, V3(0, 0, 1), V3(0, 0, 1), 1.0, 0, NULL, h, 4), 0);
    CHECK_EQ_INT(isect_ray_cylinder(&r, cyl_p0, cyl_p1, -1.0, 1, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_cylinder(&r, cyl_p0, cyl_p1, 1.0, 2, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_cylinder(&r, cyl_p0, cyl_p1, 1.0, -1, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_cylinder(&r, V3(NAN, 0, 0), cyl_p1, 1.0, 1, NULL, h, 4),
                 ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_cylinder(&r, cyl_p0, cyl_p1, INFINITY, 0, NULL, h, 4),
                 ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_cylinder(&r, NULL, cyl_p1, 1.0, 1, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_cylinder(&r, cyl_p0, NULL, 1.0, 1, NULL, h, 4), ISECT_E_ARG);

    const double data[7] = { 0, 0, 0, 0, 0, 2, 1 };
    isect_shape s = { ISECT_CYLINDER, 0, 4, 0, data, NULL, NULL };
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 4), ISECT_E_ARG); /* unknown flag */
    s.flags = 0;
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 1)), ISECT_E_ARG); /* open: thin */
    const double flat[7] = { 0, 0, 1, 0, 0, 1, 1 };
    s.data = flat;
    s.flags = ISECT_CAPPED;
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 1)), 0); /* degenerate */
}

static void test_cylinder_contains(void)
{
    const double data[7] = { 0, 0, 0, 0, 0, 2, 1 };
    isect_shape s = { ISECT_CYLINDER, 0, ISECT_CAPPED, 0, data, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 1)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 0)), 1); /* cap centre */
    CHECK_EQ_INT(isect_contains(&s, V3(1, 0, 1)), 1); /* side */
    CHECK_EQ_INT(isect_contains(&s, V3(0, -1, 2)), 1); /* rim */
    CHECK_EQ_INT(isect_contains(&s, V3(0.5, 0.5, 1.5)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(nextafter(1.0, 2.0), 0, 1)), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, nextafter(2.0, 3.0))), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, -ldexp(1, -1000))), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(0.8, 0.8, 1)), 0); /* 1.28 > 1 */

    /* slanted: p0 = (0,0,0), p1 = (4,4,0), r = 1; (2, 2, 1) is at distance 1
     * from the axis (along z) and between the caps: on the side */
    const double slanted[7] = { 0, 0, 0, 4, 4, 0, 1 };
    s.data = slanted;
    CHECK_EQ_INT(isect_contains(&s, V3(2, 2, 1)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(2, 2, nextafter(1.0, 2.0))), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(-0.5, -0.5, 0)), 0); /* before the cap at p0 */
    CHECK_EQ_INT(isect_contains(&s, V3(4, 4, 0)), 1);

    /* a boundary decided below the rounding of r|a|: axis (1, 1, 1), point
     * (1, 0, 0) at distance sqrt(2/3) from it, r = RN(sqrt(2/3)) =
     * 0x1.a20bd700c2c3ep-1, for which 3r^2 - 2 = +8.5e-18 exactly (rational
     * arithmetic), so the point is inside; one ulp less and 3r^2 - 2 < 0 */
    const double diag[7] = { 0, 0, 0, 1, 1, 1, 0x1.a20bd700c2c3ep-1 };
    s.data = diag;
    CHECK_EQ_INT(isect_contains(&s, V3(1, 0, 0)), 1);
    const double diag_less[7] = { 0, 0, 0, 1, 1, 1, 0x1.a20bd700c2c3dp-1 };
    s.data = diag_less;
    CHECK_EQ_INT(isect_contains(&s, V3(1, 0, 0)), 0);
}

static void test_cylinder_infinite(void)
{
    isect_hit h[4];
    const double axis_z[3] = { 0, 0, 5 }; /* any nonzero length */
    /* r = 2: x = -5 + t = -+2 at t = 3, 7, whatever the height */
    isect_ray r = ray_make(-5, 0, 100, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 2.0, NULL, h, 4), 2);
    HIT(&h[0], 3.0, V3(-2, 0, 100), V3(-1, 0, 0), 0, ISECT_ENTER);
    HIT(&h[1], 7.0, V3(2, 0, 100), V3(1, 0, 0), 0, ISECT_EXIT);
    /* oblique (-4 + t, 0, t): x = -+2 at t = 2, 6 */
    r = ray_make(-4, 0, 0, 1, 0, 1);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 2.0, NULL, h, 4), 2);
    HIT(&h[0], 2.0, V3(-2, 0, 2), V3(-1, 0, 0), 0, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(2, 0, 6), V3(1, 0, 0), 0, ISECT_EXIT);
    /* parallel, inside or outside: no crossing */
    r = ray_make(0, 0, 0, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 2.0, NULL, h, 4), 0);
    r = ray_make(3, 0, 0, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 2.0, NULL, h, 4), 0);
    /* nearly parallel (1e-13 <= eps): none; eps = 0: x = 1e-13 t = -+2 at
     * t = -+2e13 */
    r = line_make(0, 0, 0, 1e-13, 0, 1);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 2.0, NULL, h, 4), 0);
    isect_opts eps0 = opts_eps(0.0);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 2.0, &eps0, h, 4), 2);
    CHECK_NEAR(h[0].t, -2e13, TOL);
    CHECK_NEAR(h[1].t, 2e13, TOL);
    /* tangent */
    r = ray_make(-5, 2, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 2.0, NULL, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, 2, 0), V3(0, 1, 0), 0, ISECT_TOUCH);

    /* diagonal axis (1, 1, 0) through the origin, r = 1; the line
     * (0, 0, -5 + t) has distance |z| to the axis: t = 4, 6 */
    r = ray_make(0, 0, -5, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, V3(1, 1, 0), 1.0, NULL, h, 4), 2);
    HIT_TOL(&h[0], 4.0, V3(0, 0, -1), V3(0, 0, -1), 0, ISECT_ENTER, 1e-15);
    HIT_TOL(&h[1], 6.0, V3(0, 0, 1), V3(0, 0, 1), 0, ISECT_EXIT, 1e-15);
    /* ... and a line across it in the plane z = 0: (t, -t, 0) + (0, 0, 0)
     * shifted to start at (-3, 3, 0); distance to the axis sqrt(2)|t'| with
     * x = -3 + t: |(x, -x)| = sqrt(2)|x| = 1 at x = -+1/sqrt(2) */
    r = ray_make(-3, 3, 0, 1, -1, 0);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, V3(1, 1, 0), 1.0, NULL, h, 4), 2);
    double s = 1.0 / sqrt(2.0);
    HIT_TOL(&h[0], 3.0 - s, V3(-s, s, 0), V3(-s, s, 0), 0, ISECT_ENTER, 1e-15);
    HIT_TOL(&h[1], 3.0 + s, V3(s, -s, 0), V3(s, -s, 0), 0, ISECT_EXIT, 1e-15);

    /* degenerate and bad */
    r = ray_make(-5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, origin, 2.0, NULL, h, 4), 0);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, 0.0, NULL, h, 4), 0);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, axis_z, -2.0, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, origin, V3(0, NAN, 1), 2.0, NULL, h, 4),
                 ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_cylinder_inf(&r, NULL, axis_z, 2.0, NULL, h, 4), ISECT_E_ARG);

    /* contains */
    const double data[7] = { 0, 0, 0, 0, 0, 5, 2 };
    isect_shape sh = { ISECT_CYLINDER_INF, 0, 0, 0, data, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&sh, V3(2, 0, 1e6)), 1); /* boundary */
    CHECK_EQ_INT(isect_contains(&sh, V3(1, 1, -1e9)), 1);
    CHECK_EQ_INT(isect_contains(&sh, V3(2, 1e-8, 0)), 0);
    const double no_axis[7] = { 0, 0, 0, 0, 0, 0, 2 };
    sh.data = no_axis;
    CHECK_EQ_INT(isect_contains(&sh, V3(0, 0, 0)), 0);
}

/* --------------------------------------------------------------- quadric */

static void test_quadric_sphere_and_hyperboloid(void)
{
    isect_hit h[4];
    /* x^2 + y^2 + z^2 - 1 */
    const double unit_sphere[10] = { 1, 1, 1, 0, 0, 0, 0, 0, 0, -1 };
    isect_ray r = ray_make(-5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, NULL, h, 4), 2);
    HIT(&h[0], 4.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(1, 0, 0), V3(1, 0, 0), -1, ISECT_EXIT);
    /* (3, 4, 0) on x^2 + y^2 + z^2 = 25, going -x: t = 0 and 6 */
    const double sphere5[10] = { 1, 1, 1, 0, 0, 0, 0, 0, 0, -25 };
    r = ray_make(3, 4, 0, -1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, sphere5, NULL, h, 4), 2);
    HIT(&h[0], 0.0, V3(3, 4, 0), V3(0.6, 0.8, 0), -1, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(-3, 4, 0), V3(-0.6, 0.8, 0), -1, ISECT_EXIT);

    /* hyperboloid of one sheet x^2 + y^2 - z^2 - 1 (inside: around the axis).
     * Across the waist: x = -5 + t = -+1 at t = 4, 6. */
    const double hyper[10] = { 1, 1, -1, 0, 0, 0, 0, 0, 0, -1 };
    r = ray_make(-5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, hyper, NULL, h, 4), 2);
    HIT(&h[0], 4.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(1, 0, 0), V3(1, 0, 0), -1, ISECT_EXIT);
    /* up the line x = 2: Q = 3 - z^2, z = -5 + t = -+sqrt(3): a = -1 < 0, so
     * the line leaves the inside at t = 5 - sqrt(3) and re-enters at
     * 5 + sqrt(3); grad Q = (2x, 2y, -2z) = (4, 0, +-2 sqrt(3)) */
    r = ray_make(2, 0, -5, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, hyper, NULL, h, 4), 2);
    double s3 = sqrt(3.0), s7 = sqrt(7.0);
    HIT(&h[0], 5.0 - s3, V3(2, 0, -s3), V3(2 / s7, 0, s3 / s7), -1, ISECT_EXIT);
    HIT(&h[1], 5.0 + s3, V3(2, 0, s3), V3(2 / s7, 0, -s3 / s7), -1, ISECT_ENTER);
    /* along the axis: Q = -(t - 5)^2 - 1 < 0 throughout, no real root */
    r = ray_make(0, 0, -5, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, hyper, NULL, h, 4), 0);
}

static void test_quadric_paraboloid_and_saddle(void)
{
    isect_hit h[4];
    /* paraboloid x^2 + y^2 - z (inside: above the bowl) */
    const double bowl[10] = { 1, 1, 0, 0, 0, 0, 0, 0, -1, 0 };
    /* down the axis: a = 0 (linear case), b = grad Q(org).dir = 1, c = -5:
     * t = 5 at the apex, leaving (b > 0) */
    isect_ray r = ray_make(0, 0, 5, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_quadric(&r, bowl, NULL, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, 0, 0), V3(0, 0, -1), -1, ISECT_EXIT);
    /* across at z = 4: x = -5 + t = -+2 at t = 3, 7; grad (2x, 0, -1) */
    r = ray_make(-5, 0, 4, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, bowl, NULL, h, 4), 2);
    double s17 = sqrt(17.0);
    HIT(&h[0], 3.0, V3(-2, 0, 4), V3(-4 / s17, 0, -1 / s17), -1, ISECT_ENTER);
    HIT(&h[1], 7.0, V3(2, 0, 4), V3(4 / s17, 0, -1 / s17), -1, ISECT_EXIT);

    /* hyperbolic paraboloid xy - z (D = 1, I = -1): down x = y = 1 is linear,
     * b = 1, c = 1 - 5: t = 4 at (1, 1, 1), grad (y, x, -1) */
    const double saddle[10] = { 0, 0, 0, 1, 0, 0, 0, 0, -1, 0 };
    r = ray_make(1, 1, 5, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_quadric(&r, saddle, NULL, h, 4), 1);
    double k = 1.0 / sqrt(3.0);
    HIT(&h[0], 4.0, V3(1, 1, 1), V3(k, k, -k), -1, ISECT_EXIT);
    /* along (1, 1, 0) at z = 1 from (-3, -3, 1): Q = (t - 3)^2 - 1, t = 2, 4 */
    r = ray_make(-3, -3, 1, 1, 1, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, saddle, NULL, h, 4), 2);
    HIT(&h[0], 2.0, V3(-1, -1, 1), V3(-k, -k, -k), -1, ISECT_ENTER);
    HIT(&h[1], 4.0, V3(1, 1, 1), V3(k, k, -k), -1, ISECT_EXIT);
}

static void test_quadric_cone(void)
{
    isect_hit h[4];
    /* double cone x^2 + y^2 - z^2 (inside: around the axis) */
    const double cone[10] = { 1, 1, -1, 0, 0, 0, 0, 0, 0, 0 };
    double k = 1.0 / sqrt(2.0);
    /* parallel to the generator (-1, 0, 1): a = 0, linear. From (1, 0, 0):
     * b = (2, 0, 0).(-1, 0, 1) = -2, c = 1: t = 0.5 at (0.5, 0, 0.5),
     * entering; grad (2x, 2y, -2z) = (1, 0, -1) */
    isect_ray r = ray_make(1, 0, 0, -1, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, NULL, h, 4), 1);
    HIT(&h[0], 0.5, V3(0.5, 0, 0.5), V3(k, 0, -k), -1, ISECT_ENTER);
    isect_opts eps0 = opts_eps(0.0);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, &eps0, h, 4), 1); /* a == 0 exactly */
    /* parallel to a generator and missing: Q = 1 along (t, 1, t) (a = b = 0) */
    r = line_make(0, 1, 0, 1, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, NULL, h, 4), 0);
    /* a generator itself, through the apex: Q = 0 along it, a = b = c = 0 */
    r = line_make(0, 0, 0, 1, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, NULL, h, 4), 0);

    /* nearly parallel: dir (-1, 0, 1 + e), e = 2^-45. Exactly,
     * a = -(2e + e^2), b = -2, c = 1 with roots 1/(2 + e) and -1/e.
     * |a| ~ 5.7e-14 <= eps S |d|^2 ~ 2e-12: the linear case, t = -c/b = 0.5;
     * with eps = 0, both roots. */
    double e = ldexp(1, -45);
    r = line_make(1, 0, 0, -1, 0, 1.0 + e);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, NULL, h, 4), 1);
    CHECK_NEAR(h[0].t, 0.5, TOL);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, &eps0, h, 4), 2);
    CHECK_NEAR(h[0].t / ldexp(1, 45), -1.0, 1e-12); /* -1/e */
    CHECK_NEAR(h[1].t, 1.0 / (2.0 + e), TOL);
    CHECK_EQ_INT(h[1].kind, ISECT_ENTER);
    /* a < 0: the line is inside before -1/e, outside between, inside after */
    CHECK_EQ_INT(h[0].kind, ISECT_EXIT);

    /* across the upper nappe at z = 1: x = -5 + t = -+1 at t = 4, 6;
     * grad (2x, 0, -2) */
    r = ray_make(-5, 0, 1, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, NULL, h, 4), 2);
    HIT(&h[0], 4.0, V3(-1, 0, 1), V3(-k, 0, -k), -1, ISECT_ENTER);
    HIT(&h[1], 6.0, V3(1, 0, 1), V3(k, 0, -k), -1, ISECT_EXIT);

    /* along the axis through the apex: Q = -(t - 2)^2, a double root at the
     * apex, where grad Q = 0: TOUCH, normal facing the ray */
    r = ray_make(0, 0, -2, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, NULL, h, 4), 1);
    HIT(&h[0], 2.0, V3(0, 0, 0), V3(0, 0, -1), -1, ISECT_TOUCH);
    /* obliquely through the apex from (-1, 0, -2) along (1, 0, 2):
     * Q = -3 (t - 1)^2 */
    r = ray_make(-1, 0, -2, 1, 0, 2);
    CHECK_EQ_INT(isect_ray_quadric(&r, cone, NULL, h, 4), 1);
    CHECK_NEAR(h[0].t, 1.0, TOL);
    CHECK_EQ_INT(h[0].kind, ISECT_TOUCH);
    CHECK(h[0].normal[0] * 1 + h[0].normal[2] * 2 < 0.0);
}

/* TOUCH when |b^2 - 4ac| <= eps (b^2 + 4|ac|). For the unit-sphere quadric
 * and the line (-5 + t, y, 0): a = 1, b = -10, c = 24 + y^2, so
 * b^2 - 4ac = 4(1 - y^2) and b^2 + 4|ac| ~ 200. */
static void test_quadric_tangency(void)
{
    isect_hit h[4];
    const double unit_sphere[10] = { 1, 1, 1, 0, 0, 0, 0, 0, 0, -1 };
    isect_opts eps0 = opts_eps(0.0);
    isect_ray r = ray_make(-5, 1, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, NULL, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, 1, 0), V3(0, 1, 0), -1, ISECT_TOUCH);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, &eps0, h, 4), 1);
    /* y = 1 - 2^-38: 4(1 - y^2) ~ 2^-35 = 2.9e-11, relative 1.5e-13: TOUCH */
    double y = 1.0 - ldexp(1, -38);
    r = ray_make(-5, y, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, NULL, h, 4), 1);
    HIT(&h[0], 5.0, V3(0, y, 0), V3(0, 1, 0), -1, ISECT_TOUCH);
    /* eps = 0: two roots 5 -+ sqrt(1 - y^2) = 5 -+ sqrt(2^-37 - 2^-76),
     * accurate because a, b, c and the discriminant are */
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, &eps0, h, 4), 2);
    double w = sqrt(ldexp(1, -37) - ldexp(1, -76));
    CHECK_NEAR(h[0].t, 5.0 - w, 1e-14);
    CHECK_NEAR(h[1].t, 5.0 + w, 1e-14);
    /* y = 1 - 2^-30: relative 3.7e-11 > 1e-12: two roots */
    y = 1.0 - ldexp(1, -30);
    w = sqrt(ldexp(1, -29) - ldexp(1, -60));
    r = ray_make(-5, y, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, NULL, h, 4), 2);
    HIT(&h[0], 5.0 - w, V3(-w, y, 0), V3(-w, y, 0), -1, ISECT_ENTER);
    HIT(&h[1], 5.0 + w, V3(w, y, 0), V3(w, y, 0), -1, ISECT_EXIT);
    /* y = 1 - 1.1 * 2^-38 (rounded; x = 1 - y is then exact): c = 24 + y^2
     * needs ~106 bits, so rounded to one double it would be off by up to
     * ulp(25)/2 = 2^-49, i.e. ~2^-14 of b^2 - 4ac ~ 2^-35 and the roots off
     * by ~1e-10; with dir (3, 0, 0) the product 4ac is not exact either.
     * Expected: t = (5 -+ sqrt((1 - y)(1 + y)))/3, a few roundings. */
    y = 1.0 - ldexp(1.1, -38);
    w = sqrt((1.0 - y) * (1.0 + y));
    r = ray_make(-5, y, 0, 3, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, &eps0, h, 4), 2);
    CHECK_NEAR(h[0].t, (5.0 - w) / 3.0, 1e-15);
    CHECK_NEAR(h[1].t, (5.0 + w) / 3.0, 1e-15);
    /* the geometric sphere form gets it too */
    CHECK_EQ_INT(isect_ray_sphere(&r, origin, 1.0, &eps0, h, 4), 2);
    CHECK_NEAR(h[0].t, (5.0 - w) / 3.0, 1e-15);
    CHECK_NEAR(h[1].t, (5.0 + w) / 3.0, 1e-15);

    /* outside by 2^-38: TOUCH; by 2^-30: miss */
    r = ray_make(-5, 1.0 + ldexp(1, -38), 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, NULL, h, 4), 1);
    r = ray_make(-5, 1.0 + ldexp(1, -30), 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, unit_sphere, NULL, h, 4), 0);
}

static void test_quadric_plane_and_degenerate(void)
{
    isect_hit h[4];
    /* the plane z - 2 = 0 as a quadric (S = 0: always the linear case) */
    const double plane[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 1, -2 };
    isect_ray r = ray_make(0, 0, 0, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, plane, NULL, h, 4), 1);
    HIT(&h[0], 2.0, V3(0, 0, 2), V3(0, 0, 1), -1, ISECT_EXIT);
    r = ray_make(0, 0, 0, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_quadric(&r, plane, NULL, h, 4), 0); /* behind */
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_quadric(&r, plane, NULL, h, 4), 1);
    HIT(&h[0], -2.0, V3(0, 0, 2), V3(0, 0, 1), -1, ISECT_ENTER);
    /* in the plane, and parallel beside it: a = b = 0 */
    r = line_make(0, 0, 2, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, plane, NULL, h, 4), 0);
    r = line_make(0, 0, 1, 1, 1, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, plane, NULL, h, 4), 0);
    /* the same plane at scales 1e300 and 1e-300: the same hit */
    const double big[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 1e300, -2e300 };
    const double tiny[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 1e-300, -2e-300 };
    r = ray_make(0, 0, 0, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_quadric(&r, big, NULL, h, 4), 1);
    HIT(&h[0], 2.0, V3(0, 0, 2), V3(0, 0, 1), -1, ISECT_EXIT);
    CHECK_EQ_INT(isect_ray_quadric(&r, tiny, NULL, h, 4), 1);
    HIT(&h[0], 2.0, V3(0, 0, 2), V3(0, 0, 1), -1, ISECT_EXIT);
    /* a unit sphere scaled by 1e-200 in its coefficients: same roots */
    const double tiny_sphere[10] = { 1e-200, 1e-200, 1e-200, 0, 0, 0, 0, 0, 0, -1e-200 };
    r = ray_make(-5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_quadric(&r, tiny_sphere, NULL, h, 4), 2);
    HIT(&h[0], 4.0, V3(-1, 0, 0), V3(-1, 0, 0), -1, ISECT_ENTER);

    /* all zero: degenerate */
    const double zero[10] = { 0 };
    CHECK_EQ_INT(isect_ray_quadric(&r, zero, NULL, h, 4), 0);
    isect_shape s = { ISECT_QUADRIC, 0, 0, 0, zero, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 0)), 0);
    /* a constant: never zero; inside everywhere when negative */
    const double minus_one[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, -1 };
    const double plus_one[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 1 };
    CHECK_EQ_INT(isect_ray_quadric(&r, minus_one, NULL, h, 4), 0);
    s.data = minus_one;
    CHECK_EQ_INT(isect_contains(&s, V3(7, 8, 9)), 1);
    s.data = plus_one;
    CHECK_EQ_INT(isect_contains(&s, V3(7, 8, 9)), 0);

    /* bad input */
    double bad[10] = { 1, 1, 1, 0, 0, 0, 0, 0, 0, -1 };
    bad[4] = NAN;
    CHECK_EQ_INT(isect_ray_quadric(&r, bad, NULL, h, 4), ISECT_E_NONFINITE);
    bad[4] = INFINITY;
    CHECK_EQ_INT(isect_ray_quadric(&r, bad, NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_quadric(&r, NULL, NULL, h, 4), ISECT_E_ARG);
}

static void test_quadric_contains(void)
{
    const double sphere5[10] = { 1, 1, 1, 0, 0, 0, 0, 0, 0, -25 };
    isect_shape s = { ISECT_QUADRIC, 0, 0, 0, sphere5, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&s, V3(3, 4, 0)), 1); /* Q = 0: closed */
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 0)), 1);
    CHECK_EQ_INT(isect_contains(&s, V3(3, 4, 1e-9)), 0);
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, nextafter(5.0, 6.0))), 0);
    const double cone[10] = { 1, 1, -1, 0, 0, 0, 0, 0, 0, 0 };
    s.data = cone;
    CHECK_EQ_INT(isect_contains(&s, V3(0, 0, 0)), 1);   /* apex */
    CHECK_EQ_INT(isect_contains(&s, V3(3, 4, -5)), 1);  /* on the cone */
    CHECK_EQ_INT(isect_contains(&s, V3(3, 4, 4.5)), 0); /* outside */
    CHECK_EQ_INT(isect_contains(&s, V3(1e200, 0, 2e200)), 1); /* no overflow */
    CHECK_EQ_INT(isect_contains(&s, V3(2e200, 0, 1e200)), 0);
}

/* The dispatcher gives the same hits as the scalar calls, bit for bit. */
static void test_shape_matches_scalar(void)
{
    isect_hit a[4], b[4];
    isect_ray r = ray_make(-5, 0.25, 1, 1, 0.125, 0.0625);
    const double sphere[4] = { 0, 0, 1, 1 };
    isect_shape s = { ISECT_SPHERE, 0, 0, 0, sphere, NULL, NULL };
    int n = isect_ray_sphere(&r, sphere, sphere[3], NULL, a, 4);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, b, 4), n);
    CHECK(n == 2 && memcmp(a, b, sizeof(isect_hit) * 2) == 0);
    const double cylinder[7] = { 0, 0, 0, 0, 0, 2, 1 };
    isect_shape c = { ISECT_CYLINDER, 0, ISECT_CAPPED, 0, cylinder, NULL, NULL };
    n = isect_ray_cylinder(&r, cylinder, cylinder + 3, 1.0, 1, NULL, a, 4);
    CHECK_EQ_INT(isect_intersect(&c, &r, NULL, b, 4), n);
    CHECK(n == 2 && memcmp(a, b, sizeof(isect_hit) * 2) == 0);
}

int main(void)
{
    test_sphere_basic();
    test_sphere_on_surface();
    test_sphere_tangency();
    test_sphere_direction_scale();
    test_sphere_far_small();
    test_sphere_tiny_radius();
    test_sphere_touch_through_centre();
    test_sphere_degenerate_and_bad();
    test_sphere_contains();
    test_ellipsoid();
    test_ellipsoid_tangency();
    test_ellipsoid_degenerate_and_bad();
    test_ellipsoid_contains();
    test_cylinder_side_and_caps();
    test_cylinder_parallel();
    test_cylinder_rims();
    test_cylinder_tangency();
    test_cylinder_degenerate_and_bad();
    test_cylinder_contains();
    test_cylinder_infinite();
    test_quadric_sphere_and_hyperboloid();
    test_quadric_paraboloid_and_saddle();
    test_quadric_cone();
    test_quadric_tangency();
    test_quadric_plane_and_degenerate();
    test_quadric_contains();
    test_shape_matches_scalar();
    return check_summary();
}
