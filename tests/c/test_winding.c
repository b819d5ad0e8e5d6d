/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_winding.c — winding numbers and the mesh containment rules
 * (isect_winding_number_batch, isect_contains with ISECT_EVEN_ODD,
 * ISECT_NONZERO, ISECT_WINDING), through the public API.
 *
 * Expected values are worked out by hand, not by libisect: integers for
 * closed meshes (nested and reversed shells), the principal values on a
 * cube's face, edge and vertex (the fraction of directions pointing inside:
 * 1/2, 1/4, 1/8), and for a cube without its top face the closed cube's
 * value minus the top square's solid angle, which on the square's axis at
 * distance d is 4 asin(1 / (1 + 4 d^2)) for a unit square (the rectangle
 * formula), evaluated with libm's asin.
 */
#include "isect.h"
#include "check.h"
#include "mesh_fixtures.h"
#include "test_random.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* Unit cube [0,1]^3 scaled by s about the origin and moved by (off, 0, 0),
 * appended to m: vertex (x, y, z) is index base + x + 2y + 4z; quads with
 * outward right-hand normals (reversed: inward), the top face (z = 1) left
 * out when drop_top, the top face alone reversed when flip_top. */
static void add_cube(fx_mesh *m, double s, double off, int split, int reversed, int drop_top,
                     int flip_top)
{
    static const int32_t quads[6][4] = {
        { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 },
    };
    int32_t base = (int32_t)m->nv;
    for (int i = 0; i < 8; i++)
        fx_vertex(m, off + s * (i & 1), s * ((i >> 1) & 1), s * ((i >> 2) & 1));
    for (int f = 0; f < 6; f++) {
        if (f == 1 && drop_top)
            continue;
        int32_t q[4];
        int rev = reversed ^ (f == 1 && flip_top);
        for (int k = 0; k < 4; k++)
            q[k] = base + quads[f][rev ? 3 - k : k];
        fx_quad(m, q[0], q[1], q[2], q[3], split);
    }
}

static isect_shape mesh_shape_rule(const isect_mesh *mesh, int32_t rule)
{
    isect_shape s = { ISECT_MESH, 0, rule, 0, NULL, mesh, NULL };
    return s;
}

static double winding_at(const isect_shape *s, double x, double y, double z, double accuracy)
{
    const double p[3] = { x, y, z };
    double w = -99.0;
    CHECK_EQ_INT(isect_winding_number_batch(s, p, 1, accuracy, &w), ISECT_OK);
    return w;
}

static int contains_at(const isect_shape *s, double x, double y, double z)
{
    const double p[3] = { x, y, z };
    return isect_contains(s, p);
}

/* The signed solid angle of the unit top square (z = 1, normal +z) seen
 * from the point on its axis at height z: positive from below. */
static double top_square_angle(double z)
{
    double d = fabs(1.0 - z);
    double omega = 4.0 * asin(1.0 / (1.0 + 4.0 * d * d));
    return z < 1.0 ? omega : -omega;
}

static void test_closed_integers(void)
{
    for (int split = 0; split < 2; split++) {
        fx_mesh one = { 0 }, rev = { 0 }, nested = { 0 }, opposed = { 0 };
        add_cube(&one, 1.0, 0.0, split, 0, 0, 0);
        add_cube(&rev, 1.0, 0.0, split, 1, 0, 0);
        add_cube(&nested, 3.0, -1.0, split, 0, 0, 0); /* [-1,2] x [0,3] x [0,3] */
        add_cube(&nested, 1.0, 0.0, split, 0, 0, 0);
        add_cube(&opposed, 3.0, -1.0, split, 0, 0, 0);
        add_cube(&opposed, 1.0, 0.0, split, 1, 0, 0);
        isect_mesh *m1 = fx_build(&one), *mr = fx_build(&rev), *mn = fx_build(&nested);
        isect_mesh *mo = fx_build(&opposed);
        isect_shape s1 = mesh_shape_rule(m1, ISECT_EVEN_ODD), sr = mesh_shape_rule(mr, 0);
        isect_shape sn = mesh_shape_rule(mn, 0), so = mesh_shape_rule(mo, 0);
        /* exact integers off the surface, whatever the accuracy asked */
        for (int a = 0; a < 2; a++) {
            double acc = a ? 1e-3 : 0.0;
            CHECK(winding_at(&s1, 0.5, 0.25, 0.75, acc) == 1.0);
            CHECK(winding_at(&s1, 1.5, 0.25, 0.75, acc) == 0.0);
            CHECK(winding_at(&s1, 0.5, 0.5, 0x1p-1000, acc) == 1.0); /* just inside z = 0 */
            CHECK(winding_at(&s1, 0.5, 0.5, -0x1p-1000, acc) == 0.0);
            CHECK(winding_at(&sr, 0.5, 0.25, 0.75, acc) == -1.0);
            CHECK(winding_at(&sn, 0.5, 0.5, 0.5, acc) == 2.0);
            CHECK(winding_at(&sn, 1.5, 2.5, 2.5, acc) == 1.0);
            CHECK(winding_at(&so, 0.5, 0.5, 0.5, acc) == 0.0);
            CHECK(winding_at(&so, 1.5, 2.5, 2.5, acc) == 1.0);
        }
        /* on the surface: the principal value, the share of directions
         * that point inside */
        CHECK_NEAR(winding_at(&s1, 0.5, 0.5, 0.0, 0.0), 0.5, 1e-14);
        CHECK_NEAR(winding_at(&s1, 0.5, 0.0, 0.0, 0.0), 0.25, 1e-14);
        CHECK_NEAR(winding_at(&s1, 0.0, 0.0, 0.0, 0.0), 0.125, 1e-14);
        CHECK_NEAR(winding_at(&s1, 1.0, 1.0, 0.375, 0.0), 0.25, 1e-14);
        CHECK_NEAR(winding_at(&sr, 0.5, 0.5, 1.0, 0.0), -0.5, 1e-14);

        /* the rules: two nested outward shells hold the inner points twice */
        CHECK_EQ_INT(contains_at(&sn, 0.5, 0.5, 0.5), 0); /* even-odd: 2 crossings */
        sn.flags = ISECT_NONZERO;
        CHECK_EQ_INT(contains_at(&sn, 0.5, 0.5, 0.5), 1);
        sn.flags = ISECT_WINDING;
        CHECK_EQ_INT(contains_at(&sn, 0.5, 0.5, 0.5), 1);
        CHECK_EQ_INT(contains_at(&sn, 2.5, 0.5, 0.5), 0);
        /* an inner shell turned inside out cancels the outer one */
        so.flags = ISECT_NONZERO;
        CHECK_EQ_INT(contains_at(&so, 0.5, 0.5, 0.5), 0);
        CHECK_EQ_INT(contains_at(&so, 1.5, 2.5, 2.5), 1);
        so.flags = ISECT_EVEN_ODD;
        CHECK_EQ_INT(contains_at(&so, 0.5, 0.5, 0.5), 0);
        /* an inward cube: nonzero and even-odd hold its inside, winding
         * (w = -1 < 1/2) does not; its surface is inside by every rule */
        sr.flags = ISECT_NONZERO;
        CHECK_EQ_INT(contains_at(&sr, 0.5, 0.5, 0.5), 1);
        sr.flags = ISECT_WINDING;
        CHECK_EQ_INT(contains_at(&sr, 0.5, 0.5, 0.5), 0);
        CHECK_EQ_INT(contains_at(&sr, 0.5, 0.5, 1.0), 1);

        isect_mesh_destroy(m1);
        isect_mesh_destroy(mr);
        isect_mesh_destroy(mn);
        isect_mesh_destroy(mo);
        fx_free(&one);
        fx_free(&rev);
        fx_free(&nested);
        fx_free(&opposed);
    }
}

/* |got - want| within rel relative plus abs absolute. */
static void check_close(double got, double want, double rel, double abs_tol, const char *what)
{
    if (!(fabs(got - want) <= rel * fabs(want) + abs_tol)) {
        printf("  %s: got %.17g, want %.17g (diff %.3g)\n", what, got, want, got - want);
        CHECK(0);
    } else {
        CHECK(1);
    }
}

static void test_open_cube(void)
{
    for (int split = 0; split < 2; split++) {
        for (int shifted = 0; shifted < 2; shifted++) {
            /* far from the origin too: coordinates near 1e8, where the
             * differences to the point are still exact */
            double off = shifted ? 1e8 : 0.0;
            fx_mesh open = { 0 };
            add_cube(&open, 1.0, off, split, 0, 1, 0);
            isect_mesh *m = fx_build(&open);
            isect_shape s = mesh_shape_rule(m, ISECT_WINDING);
            static const double heights[] = { 0.5,  0.25, 0x1p-40, -0x1p-40, 0x1p-100, -0x1p-100,
                                              0.999, 1.5,  1e6,     -1e6,     3.0,       -7.5 };
            for (size_t i = 0; i < sizeof heights / sizeof heights[0]; i++) {
                double z = heights[i];
                double closed = z > 0.0 && z < 1.0 ? 1.0 : 0.0;
                double want = closed - top_square_angle(z) / (4.0 * PI);
                char what[96];
                snprintf(what, sizeof what, "open cube, z = %g (split %d, shift %g)", z, split, off);
                for (int a = 0; a < 3; a++) {
                    double acc = a == 0 ? 0.0 : a == 1 ? 1e-12 : 1e-6;
                    check_close(winding_at(&s, off + 0.5, 0.5, z, acc), want, 1e-13,
                                a == 2 ? 1e-6 : 1e-15, what);
                }
            }
            /* the rules: only WINDING applies to an open mesh */
            CHECK_EQ_INT(contains_at(&s, off + 0.5, 0.5, 0.5), 1);   /* w = 5/6 */
            CHECK_EQ_INT(contains_at(&s, off + 0.5, 0.5, 0.999), 1); /* w ~ 0.5009 */
            CHECK_EQ_INT(contains_at(&s, off + 0.5, 0.5, 1.5), 0);   /* w = 1/6 */
            CHECK_EQ_INT(contains_at(&s, off + 0.5, 0.5, -0.5), 0);
            s.flags = ISECT_EVEN_ODD;
            CHECK_EQ_INT(contains_at(&s, off + 0.5, 0.5, 0.5), ISECT_E_ARG);
            s.flags = ISECT_NONZERO;
            CHECK_EQ_INT(contains_at(&s, off + 0.5, 0.5, 0.5), ISECT_E_ARG);
            isect_mesh_destroy(m);
            fx_free(&open);
        }
    }
}

/* A closed cube whose top face is turned over: closed, not oriented. Its
 * generalized winding number at the centre is 1 - 2/6 (the top's 1/6
 * counted negative instead of positive). */
static void test_misoriented(void)
{
    fx_mesh flip = { 0 };
    add_cube(&flip, 1.0, 0.0, 0, 0, 0, 1);
    isect_mesh *m = fx_build(&flip);
    isect_shape s = mesh_shape_rule(m, ISECT_EVEN_ODD);
    check_close(winding_at(&s, 0.5, 0.5, 0.5, 0.0), 2.0 / 3.0, 1e-14, 0.0, "flipped top");
    CHECK_EQ_INT(contains_at(&s, 0.5, 0.5, 0.5), 1); /* parity needs no orientation */
    s.flags = ISECT_NONZERO;
    CHECK_EQ_INT(contains_at(&s, 0.5, 0.5, 0.5), ISECT_E_ARG);
    s.flags = ISECT_WINDING;
    CHECK_EQ_INT(contains_at(&s, 0.5, 0.5, 0.5), 1);
    isect_mesh_destroy(m);
    fx_free(&flip);
}

/* A mirroring transform turns an outward cube inward: w = -1 inside. */
static void test_mirrored(void)
{
    fx_mesh cube = { 0 };
    add_cube(&cube, 1.0, 0.0, 1, 0, 0, 0);
    isect_mesh *m = fx_build(&cube);
    const double mat[16] = { -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    isect_xform x;
    CHECK_EQ_INT(isect_xform_init(&x, mat), ISECT_OK);
    isect_shape s = mesh_shape_rule(m, ISECT_EVEN_ODD);
    s.xform = &x;
    CHECK(winding_at(&s, -0.5, 0.5, 0.5, 0.0) == -1.0);
    CHECK(winding_at(&s, 0.5, 0.5, 0.5, 0.0) == 0.0);
    CHECK_EQ_INT(contains_at(&s, -0.5, 0.5, 0.5), 1);
    s.flags = ISECT_NONZERO;
    CHECK_EQ_INT(contains_at(&s, -0.5, 0.5, 0.5), 1);
    s.flags = ISECT_WINDING;
    CHECK_EQ_INT(contains_at(&s, -0.5, 0.5, 0.5), 0);
    isect_mesh_destroy(m);
    fx_free(&cube);
}

/* On an open icosphere (its cap above z = 0.6 removed) at random points:
 * the exact hierarchy against the flat sum, and the far field against it
 * within the accuracy asked. */
static void test_far_field(int points)
{
    fx_mesh sphere = fx_icosphere(4, (const double[3]){ 0.0, 0.0, 0.0 }, 1.0);
    fx_mesh open = { 0 };
    for (int64_t i = 0; i < sphere.nv; i++)
        fx_vertex(&open, sphere.v[3 * i], sphere.v[3 * i + 1], sphere.v[3 * i + 2]);
    for (int64_t f = 0; f < sphere.nf; f++) {
        const int32_t *c = sphere.idx + sphere.off[f];
        double z = (sphere.v[3 * c[0] + 2] + sphere.v[3 * c[1] + 2] + sphere.v[3 * c[2] + 2]) / 3.0;
        if (z <= 0.6)
            fx_tri(&open, c[0], c[1], c[2]);
    }
    isect_mesh *m = fx_build(&open);
    isect_shape s = mesh_shape_rule(m, ISECT_WINDING);
    double *p = malloc((size_t)points * 3 * sizeof *p);
    double *direct = malloc((size_t)points * sizeof *direct);
    double *far = malloc((size_t)points * sizeof *far);
    rng_seed(7);
    for (int i = 0; i < 3 * points; i++)
        p[i] = 4.0 * rng_unit() - 2.0;
    /* accuracy 0 over a batch: the exact hierarchy (clusters through their
     * boundary caps) against the plain sum over every face (a batch of
     * fewer than 8 points builds no tree) */
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, points, 0.0, direct), ISECT_OK);
    double worst_cap = 0.0;
    for (int i = 0; i < points; i++) {
        double flat;
        CHECK_EQ_INT(isect_winding_number_batch(&s, p + 3 * i, 1, 0.0, &flat), ISECT_OK);
        worst_cap = fmax(worst_cap, fabs(flat - direct[i]));
    }
    printf("exact hierarchy: worst |caps - flat sum| = %.3g over %d points\n", worst_cap, points);
    CHECK(worst_cap <= 1e-13);
    static const double accuracies[] = { 1e-2, 1e-4, 1e-8, 1e-12 };
    for (int a = 0; a < 4; a++) {
        CHECK_EQ_INT(isect_winding_number_batch(&s, p, points, accuracies[a], far), ISECT_OK);
        double worst = 0.0;
        for (int i = 0; i < points; i++)
            worst = fmax(worst, fabs(far[i] - direct[i]));
        printf("far field, accuracy %g: worst |far - direct| = %.3g over %d points\n",
               accuracies[a], worst, points);
        CHECK(worst <= accuracies[a] + 1e-12);
    }
    /* the points inside the bowl and outside: direct values near 1 and 0
     * where the cap is far (sanity of the test itself) */
    double centre = winding_at(&s, 0.0, 0.0, -0.5, 0.0);
    CHECK(centre > 0.85 && centre < 1.0);
    free(p);
    free(direct);
    free(far);
    isect_mesh_destroy(m);
    fx_free(&open);
    fx_free(&sphere);
}

static void test_errors(void)
{
    fx_mesh cube = { 0 };
    add_cube(&cube, 1.0, 0.0, 0, 0, 1, 0);
    isect_mesh *m = fx_build(&cube);
    isect_shape s = mesh_shape_rule(m, ISECT_WINDING);
    double p[6] = { 0.5, 0.5, 0.5, NAN, 0.0, 0.0 }, w[2] = { 7.0, 7.0 };
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, 2, 0.0, w), ISECT_OK);
    CHECK(isnan(w[1]) && w[0] > 0.8);
    p[3] = INFINITY;
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, 2, 1e-3, w), ISECT_OK);
    CHECK(isnan(w[1]));
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, 1, -1.0, w), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, 1, NAN, w), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, -1, 0.0, w), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number_batch(&s, NULL, 1, 0.0, w), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, 1, 0.0, NULL), ISECT_E_ARG);
    CHECK_EQ_INT(isect_winding_number_batch(&s, NULL, 0, 0.0, NULL), ISECT_OK);
    CHECK_EQ_INT(isect_winding_number_batch(NULL, p, 1, 0.0, w), ISECT_E_ARG);
    s.flags = 3;
    CHECK_EQ_INT(isect_winding_number_batch(&s, p, 1, 0.0, w), ISECT_E_ARG);
    const double sphere[4] = { 0, 0, 0, 1 };
    isect_shape ball = { ISECT_SPHERE, 0, 0, 0, sphere, NULL, NULL };
    CHECK_EQ_INT(isect_winding_number_batch(&ball, p, 1, 0.0, w), ISECT_E_ARG);
    /* contains_batch follows the rule too */
    uint8_t in[2];
    s.flags = ISECT_WINDING;
    p[3] = 0.5;
    p[4] = 0.5;
    p[5] = 1.5;
    CHECK(isect_contains_batch(&s, p, 2, in) == 1);
    CHECK(in[0] == 1 && in[1] == 0);
    s.flags = ISECT_EVEN_ODD;
    CHECK(isect_contains_batch(&s, p, 2, in) == ISECT_E_ARG);
    isect_mesh_destroy(m);
    fx_free(&cube);
}

int main(int argc, char **argv)
{
    int points = argc > 1 ? atoi(argv[1]) : 2000;
    test_closed_integers();
    test_open_cube();
    test_misoriented();
    test_mirrored();
    test_far_field(points);
    test_errors();
    return check_summary();
}
