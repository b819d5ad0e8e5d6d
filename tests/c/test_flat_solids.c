/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_flat_solids.c — unit tests of the plane, the axis-aligned box and the
 * convex polyhedron, through the public API only.
 *
 * Every expected value is worked out by hand in the comment next to it (slab
 * intervals, plane values, enterMax/exitMin); none is computed by libisect.
 * The box used throughout is B = [0,1] x [0,2] x [0,4], faces 0..5 =
 * -x,+x,-y,+y,-z,+z; the cube C of the convex tests is [0,1]^3 written with
 * deliberately non-unit normals, planes in the same face order.
 */
#include "isect.h"
#include "check.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define TOL 1e-14

static const double B_LO[3] = { 0.0, 0.0, 0.0 };
static const double B_HI[3] = { 1.0, 2.0, 4.0 };

/* Outward unit normal of box face f. */
static const double FACE_NORMAL[6][3] = {
    { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 }, { 0, 0, -1 }, { 0, 0, 1 },
};

static isect_ray ray_of(double ox, double oy, double oz, double dx, double dy, double dz)
{
    isect_ray r = { { ox, oy, oz }, { dx, dy, dz }, 0.0, INFINITY };
    return r;
}

static isect_opts opts_of(uint32_t flags, double eps)
{
    isect_opts o = { (uint32_t)sizeof(isect_opts), flags, eps };
    return o;
}

/* No NaN or inf in any number of the first n hits. */
static int hits_finite(const isect_hit *h, int n)
{
    for (int i = 0; i < n; i++) {
        const double *x[3] = { h[i].point, h[i].normal, h[i].uv };
        int len[3] = { 3, 3, 2 };
        if (!isfinite(h[i].t))
            return 0;
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < len[k]; j++)
                if (!isfinite(x[k][j]))
                    return 0;
    }
    return 1;
}

#define CHECK_VEC(v, X, Y, Z)                                                        \
    do {                                                                             \
        CHECK_NEAR((v)[0], X, TOL);                                                  \
        CHECK_NEAR((v)[1], Y, TOL);                                                  \
        CHECK_NEAR((v)[2], Z, TOL);                                                  \
    } while (0)

/* One hit: t, point, unit normal, prim, kind; uv is always 0 here. */
#define CHECK_HIT(h, T, PX, PY, PZ, NX, NY, NZ, PRIM, KIND)                          \
    do {                                                                             \
        CHECK_NEAR((h).t, T, TOL);                                                   \
        CHECK_VEC((h).point, PX, PY, PZ);                                            \
        CHECK_VEC((h).normal, NX, NY, NZ);                                           \
        CHECK((h).uv[0] == 0.0 && (h).uv[1] == 0.0);                                 \
        CHECK_EQ_INT((h).prim, PRIM);                                                \
        CHECK_EQ_INT((h).kind, KIND);                                                \
    } while (0)

/* A box hit: the normal follows from the face. */
#define CHECK_BOX_HIT(h, T, PX, PY, PZ, FACE, KIND)                                  \
    CHECK_HIT(h, T, PX, PY, PZ, FACE_NORMAL[FACE][0], FACE_NORMAL[FACE][1],          \
              FACE_NORMAL[FACE][2], FACE, KIND)

/* |a - b| <= TOL |b|: for values far below 1, where CHECK_NEAR is absolute. */
#define CHECK_REL(a, b) CHECK_NEAR((a) / (b), 1.0, TOL)

/* A hit point of B lies on B: inside the closed box, whatever the rounding. */
static int on_box(const isect_hit *h, int n)
{
    for (int i = 0; i < n; i++)
        for (int a = 0; a < 3; a++)
            if (!(B_LO[a] <= h[i].point[a] && h[i].point[a] <= B_HI[a]))
                return 0;
    return 1;
}

static int box(const isect_ray *r, const isect_opts *o, isect_hit *h)
{
    int n = isect_ray_aabb(r, B_LO, B_HI, o, h, 4);
    CHECK(n < 0 || hits_finite(h, n < 4 ? n : 4));
    CHECK(n < 0 || r->tmin < 0 || on_box(h, n < 4 ? n : 4));
    return n;
}

/* ------------------------------------------------------------------ plane */

static void test_plane(void)
{
    const double z2[3] = { 0, 0, 1 }; /* with d = -2: the plane z = 2 */
    isect_hit h[2];
    isect_ray r;
    isect_opts o;

    /* From the origin up: n.dir = 1 > 0, back side: EXIT at t = 2. */
    r = ray_of(0, 0, 0, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 1);
    CHECK_HIT(h[0], 2, 0, 0, 2, 0, 0, 1, -1, ISECT_EXIT);

    /* From (1,2,5) down: t = -(-2 + 5)/(-1) = 3, front side: ENTER. */
    r = ray_of(1, 2, 5, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 1);
    CHECK_HIT(h[0], 3, 1, 2, 2, 0, 0, 1, -1, ISECT_ENTER);

    /* Same plane as 4z - 8 = 0, dir (0,0,-0.5) from z = 5:
     * t = -(-8 + 20)/(-2) = 6; the normal is still unit. */
    {
        const double n4[3] = { 0, 0, 4 };
        r = ray_of(0, 0, 5, 0, 0, -0.5);
        CHECK_EQ_INT(isect_ray_plane(&r, n4, -8, NULL, h, 2), 1);
        CHECK_HIT(h[0], 6, 0, 0, 2, 0, 0, 1, -1, ISECT_ENTER);
    }

    /* Oblique: x + y - 2 = 0, dir (3,1,0) from 0: n.dir = 4, t = 2/4 = 0.5,
     * point (1.5, 0.5, 0), normal (1,1,0)/sqrt2, EXIT. */
    {
        const double n11[3] = { 1, 1, 0 };
        r = ray_of(0, 0, 0, 3, 1, 0);
        CHECK_EQ_INT(isect_ray_plane(&r, n11, -2, NULL, h, 2), 1);
        CHECK_HIT(h[0], 0.5, 1.5, 0.5, 0, 0.70710678118654752, 0.70710678118654752, 0, -1,
                  ISECT_EXIT);
    }

    /* Behind: from z = 5 going up, t = -3 < tmin = 0. */
    r = ray_of(0, 0, 5, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 1);
    CHECK_HIT(h[0], -3, 0, 0, 2, 0, 0, 1, -1, ISECT_EXIT);

    /* Beyond tmax. */
    r = ray_of(0, 0, 0, 0, 0, 1);
    r.tmax = 1.5;
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 0);

    /* Parallel (a miss), and lying in the plane: no hit either way. */
    r = ray_of(0, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 0);
    r = ray_of(3, 4, 2, 1, 1, 0);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 0);

    /* Near-parallel: |n.d| = 1e-13 against eps |n||d| ~ 1e-12 -> parallel;
     * with eps = 0 or 1e-14 a hit at t = 2/1e-13 = 2e13. */
    r = ray_of(0, 0, 0, 1, 0, 1e-13);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), 0);
    o = opts_of(0, 0.0);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, &o, h, 2), 1);
    CHECK_NEAR(h[0].t, 2e13, TOL);
    CHECK_NEAR(h[0].point[2], 2, 1e-12);
    o = opts_of(0, 1e-14);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, &o, h, 2), 1);

    /* The parallel test is inclusive: dir (0,3,4) makes |n.d|/(|n||d|) =
     * 4/5, which equals eps = 0.8 (as a double, 0.8 + 4e-17 >= 4/5). */
    r = ray_of(0, 0, 0, 0, 3, 4);
    o = opts_of(0, 0.8);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, &o, h, 2), 0);
    o = opts_of(0, 0.79); /* t = 2/4 = 0.5, point (0, 1.5, 2) */
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, &o, h, 2), 1);
    CHECK_HIT(h[0], 0.5, 0, 1.5, 2, 0, 0, 1, -1, ISECT_EXIT);

    /* CULL_BACK drops the EXIT hit of a thin surface, keeps ENTER. */
    o = opts_of(ISECT_CULL_BACK, ISECT_EPS_DEFAULT);
    r = ray_of(0, 0, 0, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, &o, h, 2), 0);
    r = ray_of(0, 0, 5, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, &o, h, 2), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);

    /* Zero normal: degenerate, never hit, not an error. */
    {
        const double zero[3] = { 0, 0, 0 };
        r = ray_of(0, 0, 0, 0, 0, 1);
        CHECK_EQ_INT(isect_ray_plane(&r, zero, 1, NULL, h, 2), 0);
        CHECK_EQ_INT(isect_ray_plane(&r, zero, 0, NULL, h, 2), 0);
    }

    /* Scale: normal 1e300, plane x = 3, dir (1e300,0,0): n.dir would
     * overflow; t = 3/1e300 = 3e-300, point (3,0,0), EXIT. */
    {
        const double big[3] = { 1e300, 0, 0 };
        r = ray_of(0, 0, 0, 1e300, 0, 0);
        CHECK_EQ_INT(isect_ray_plane(&r, big, -3e300, NULL, h, 2), 1);
        CHECK_REL(h[0].t, 3e-300);
        CHECK_VEC(h[0].point, 3, 0, 0);
        CHECK_VEC(h[0].normal, 1, 0, 0);
        CHECK_EQ_INT(h[0].kind, ISECT_EXIT);
    }
    /* Normal 1e-300 (|n|^2 underflows): plane z = 2, t = 2, unit normal. */
    {
        const double tiny[3] = { 0, 0, 1e-300 };
        r = ray_of(0, 0, 0, 0, 0, 1);
        CHECK_EQ_INT(isect_ray_plane(&r, tiny, -2e-300, NULL, h, 2), 1);
        CHECK_HIT(h[0], 2, 0, 0, 2, 0, 0, 1, -1, ISECT_EXIT);
    }
    /* In-plane at scale 1e200: n.dir = 1e400 - 1e400 would be inf - inf. */
    {
        const double big[3] = { 1e200, 1e200, 0 };
        r = ray_of(1, -1, 0, 1e200, -1e200, 0);
        CHECK_EQ_INT(isect_ray_plane(&r, big, 0, NULL, h, 2), 0);
    }

    /* Count only, and errors. */
    r = ray_of(0, 0, 0, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, NULL, 0), 1);
    CHECK_EQ_INT(isect_ray_plane(&r, NULL, -2, NULL, h, 2), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_plane(NULL, z2, -2, NULL, h, 2), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, NAN, NULL, h, 2), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, INFINITY, NULL, h, 2), ISECT_E_NONFINITE);
    {
        const double bad[3] = { 0, NAN, 1 };
        CHECK_EQ_INT(isect_ray_plane(&r, bad, -2, NULL, h, 2), ISECT_E_NONFINITE);
    }
    r = ray_of(0, 0, 0, 0, 0, 0);
    CHECK_EQ_INT(isect_ray_plane(&r, z2, -2, NULL, h, 2), ISECT_E_DEGENERATE);

    /* The shape path gives the same hit; a plane contains nothing. */
    {
        const double data[4] = { 0, 0, 1, -2 };
        const double p[3] = { 0, 0, 2 };
        isect_shape s = { ISECT_PLANE, 0, 0, 0, data, NULL, NULL };
        r = ray_of(0, 0, 5, 0, 0, -1);
        CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 2), 1);
        CHECK_HIT(h[0], 3, 0, 0, 2, 0, 0, 1, -1, ISECT_ENTER);
        CHECK_EQ_INT(isect_contains(&s, p), ISECT_E_ARG);
    }
}

/* -------------------------------------------------------------------- box */

/* Straight through each pair of faces; slab intervals in the comments. */
static void test_box_faces(void)
{
    static const struct {
        double org[3], dir[3];
        double t_in, p_in[3];
        int f_in;
        double t_out, p_out[3];
        int f_out;
    } cases[] = {
        /* x: [(0+1)/1, (1+1)/1] = [1, 2] */
        { { -1, 1, 2 }, { 1, 0, 0 }, 1, { 0, 1, 2 }, 0, 2, { 1, 1, 2 }, 1 },
        /* x, backwards: hi first, (1-3)/-2 = 1, (0-3)/-2 = 1.5 */
        { { 3, 1, 2 }, { -2, 0, 0 }, 1, { 1, 1, 2 }, 1, 1.5, { 0, 1, 2 }, 0 },
        /* y: [1, 3] */
        { { 0.5, -1, 2 }, { 0, 1, 0 }, 1, { 0.5, 0, 2 }, 2, 3, { 0.5, 2, 2 }, 3 },
        /* y backwards from 5: (2-5)/-1 = 3, (0-5)/-1 = 5 */
        { { 0.5, 5, 2 }, { 0, -1, 0 }, 3, { 0.5, 2, 2 }, 3, 5, { 0.5, 0, 2 }, 2 },
        /* z with dir 0.5: [(0+2)/0.5, (4+2)/0.5] = [4, 12] */
        { { 0.5, 1, -2 }, { 0, 0, 0.5 }, 4, { 0.5, 1, 0 }, 4, 12, { 0.5, 1, 4 }, 5 },
        /* z backwards, dir -4 from 10: (4-10)/-4 = 1.5, (0-10)/-4 = 2.5 */
        { { 0.5, 1, 10 }, { 0, 0, -4 }, 1.5, { 0.5, 1, 4 }, 5, 2.5, { 0.5, 1, 0 }, 4 },
        /* oblique (2,1,1) from (-1,0.5,1): x [0.5,1], y [-0.5,1.5], z [-1,3]
         * -> in 0.5 at (0,1,1.5) face 0, out 1 at (1,1.5,2) face 1 */
        { { -1, 0.5, 1 }, { 2, 1, 1 }, 0.5, { 0, 1, 1.5 }, 0, 1, { 1, 1.5, 2 }, 1 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        isect_hit h[4];
        isect_ray r = ray_of(cases[i].org[0], cases[i].org[1], cases[i].org[2],
                             cases[i].dir[0], cases[i].dir[1], cases[i].dir[2]);
        CHECK_EQ_INT(box(&r, NULL, h), 2);
        CHECK_BOX_HIT(h[0], cases[i].t_in, cases[i].p_in[0], cases[i].p_in[1],
                      cases[i].p_in[2], cases[i].f_in, ISECT_ENTER);
        CHECK_BOX_HIT(h[1], cases[i].t_out, cases[i].p_out[0], cases[i].p_out[1],
                      cases[i].p_out[2], cases[i].f_out, ISECT_EXIT);
    }
}

static void test_box_edges_corners(void)
{
    isect_hit h[4];
    isect_ray r;

    /* Corner (0,0,0) on entry: x [1,2], y [1,3], z [1,5]; faces 0, 2, 4 tie
     * at t = 1 -> 0; exit t = 2 at (1,1,1), face 1. */
    r = ray_of(-1, -1, -1, 1, 1, 1);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 1, 0, 0, 0, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 2, 1, 1, 1, 1, ISECT_EXIT);

    /* Corner (1,2,4) on entry, backwards: x [1,2] (in by face 1), y [1,3]
     * (face 3), z [1,5] (face 5); tie 1, 3, 5 -> 1; exit t = 2 at (0,1,3),
     * face 0. */
    r = ray_of(2, 3, 5, -1, -1, -1);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 1, 1, 2, 4, 1, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 2, 0, 1, 3, 0, ISECT_EXIT);

    /* Edge x = y = 0 on entry: x [1,2], y [1,3], z parallel inside; faces 0
     * and 2 tie -> 0. */
    r = ray_of(-1, -1, 2, 1, 1, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 1, 0, 0, 2, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 2, 1, 1, 2, 1, ISECT_EXIT);

    /* Edge x = 1, y = 2 on exit: dir (2,3,0) from (-1,-1,2): x [0.5, 1],
     * y [1/3, 1]; in at 0.5 (0, 0.5, 2) face 0; faces 1 and 3 tie -> 1. */
    r = ray_of(-1, -1, 2, 2, 3, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 0.5, 0, 0.5, 2, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 1, 1, 2, 2, 1, ISECT_EXIT);

    /* Edge x = 0, y = 2 on exit, from (3,-1,2) along (-1,1,0): x in by face
     * 1 at t = 2, out by face 0 at 3; y in by face 2 at 1, out by face 3 at
     * 3. In at 2 (1,1,2) face 1; faces 0 and 3 tie at 3 -> 0 (lowest index,
     * not the first axis to be met). */
    r = ray_of(3, -1, 2, -1, 1, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 2, 1, 1, 2, 1, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 3, 0, 2, 2, 0, ISECT_EXIT);

    /* Grazing the edge x = 0, y = 2: dir (1,2,0) from (-1,0,2): x [1,2],
     * y [0,1] -> entry 1 (face 0) == exit 1 (face 3): one TOUCH, the lower
     * index 0. */
    r = ray_of(-1, 0, 2, 1, 2, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 1, 0, 2, 2, 0, ISECT_TOUCH);

    /* Grazing the edge x = 1, y = 2 from the other side: dir (1,-1,0) from
     * (0,3,2): x [0,1] (out by face 1), y in by face 3 at 1 -> entry 1
     * (face 3) == exit 1 (face 1): TOUCH with the lower index, the exit
     * face 1. */
    r = ray_of(0, 3, 2, 1, -1, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 1, 1, 2, 2, 1, ISECT_TOUCH);

    /* Grazing the corner (0,0,0): dir (1,1,-1) from (-1,-1,1): x [1,2],
     * y [1,3], z in by face 5 at -3, out by face 4 at 1 -> entry 1 (faces 0,
     * 2 tie -> 0) == exit 1: TOUCH, face 0. */
    r = ray_of(-1, -1, 1, 1, 1, -1);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 1, 0, 0, 0, 0, ISECT_TOUCH);

    /* Out near the edge x = 1, y = 2 with inexact data: dir (1.1,4.4,0)
     * from (-0.1,-2.4,2): x [1/11, 1], y [6/11, 1] in real numbers, but the
     * given doubles put the y exit (2 + 2.4)/4.4 about 2.5e-17 before the x
     * exit (1 + 0.1)/1.1 (exact rationals; both round to 1 - 2^-53), so the
     * exit is face 3, decided exactly, not a tie of rounded values. In by
     * face 2 at (0.5,0,2); out at (1,2,2) (-2.4 + t*4.4 would round above
     * 2, outside the box, so the point must be pulled back onto it). */
    r = ray_of(-0.1, -2.4, 2, 1.1, 4.4, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 6.0 / 11.0, 0.5, 0, 2, 2, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 1, 1, 2, 2, 3, ISECT_EXIT);
    CHECK(h[1].point[1] <= 2.0);

    /* Just past that edge: dir (1,2.5,0) from (-1,0,2): x [1,2], y [0,0.8]. */
    r = ray_of(-1, 0, 2, 1, 2.5, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 0);
}

static void test_box_inside_and_parallel(void)
{
    isect_hit h[4];
    isect_ray r;

    /* Origin inside: the entry at -0.5 is before tmin; only the EXIT. */
    r = ray_of(0.5, 1, 2, 1, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 0.5, 1, 1, 2, 1, ISECT_EXIT);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], -0.5, 0, 1, 2, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 0.5, 1, 1, 2, 1, ISECT_EXIT);

    /* Origin on face 0, going in: ENTER at t = 0 (tmin is inclusive). */
    r = ray_of(0, 1, 2, 1, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 0, 0, 1, 2, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 1, 1, 1, 2, 1, ISECT_EXIT);

    /* Origin on face 0, going out: x in by face 1 at (1-0)/-1 = -1, out by
     * face 0 at (0-0)/-1 = -0: one EXIT at t = +0. */
    r = ray_of(0, 1, 2, -1, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 0, 0, 1, 2, 0, ISECT_EXIT);
    CHECK(!signbit(h[0].t));

    /* Ray in the face plane z = 0, inside the face: the box is closed. */
    r = ray_of(-1, 1, 0, 1, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 1, 0, 1, 0, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 2, 1, 1, 0, 1, ISECT_EXIT);
    /* ... along the edge y = z = 0 ... */
    r = ray_of(-1, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 1, 0, 0, 0, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 2, 1, 0, 0, 1, ISECT_EXIT);
    /* ... and in the face plane but beside the face (y = 3 > 2). */
    r = ray_of(-1, 3, 0, 1, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 0);

    /* Origin on the slab plane x = 0, ray parallel to it (dir x = 0, and
     * -0.0): the x slab holds the whole line; y [-1, 1] -> EXIT at 1 by face 3
     * (an inverse-direction kernel would form (0-0)*inf = NaN here). */
    r = ray_of(0, 1, 2, 0, 1, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 1, 0, 2, 2, 3, ISECT_EXIT);
    r = ray_of(0, 1, 2, -0.0, 1, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 1, 0, 2, 2, 3, ISECT_EXIT);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], -1, 0, 0, 2, 2, ISECT_ENTER);
    /* On the plane x = 1 (hi), going down z: z out by face 4 at (0-2)/-1 = 2. */
    r = ray_of(1, 1, 2, 0, 0, -1);
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 2, 1, 1, 0, 4, ISECT_EXIT);
    /* Parallel to a slab and outside it: no hit at any t. */
    r = ray_of(-0.5, 1, 2, 0, 1, 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(box(&r, NULL, h), 0);
    r = ray_of(1.5, 1, 2, 0, 0, 1);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(box(&r, NULL, h), 0);

    /* Behind: from x = 5 going +x, x [-5, -4]. */
    r = ray_of(5, 1, 2, 1, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], -5, 0, 1, 2, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], -4, 1, 1, 2, 1, ISECT_EXIT);

    /* CULL_BACK is for thin surfaces only: a box keeps its EXIT. */
    {
        isect_opts o = opts_of(ISECT_CULL_BACK, ISECT_EPS_DEFAULT);
        r = ray_of(-1, 1, 2, 1, 0, 0);
        CHECK_EQ_INT(box(&r, &o, h), 2);
        CHECK_EQ_INT(h[1].kind, ISECT_EXIT);
    }
}

static void test_box_clipping(void)
{
    isect_hit h[4];
    isect_ray r = ray_of(-1, 1, 2, 1, 0, 0); /* hits at t = 1 and 2 */

    r.tmax = 1.5;
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 1, 0, 1, 2, 0, ISECT_ENTER);
    r.tmin = 1.5;
    r.tmax = INFINITY;
    CHECK_EQ_INT(box(&r, NULL, h), 1);
    CHECK_BOX_HIT(h[0], 2, 1, 1, 2, 1, ISECT_EXIT);
    r.tmin = 1; /* both ends inclusive */
    r.tmax = 2;
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    r.tmin = 1.25;
    r.tmax = 1.75;
    CHECK_EQ_INT(box(&r, NULL, h), 0);
    r.tmin = 3; /* tmin > tmax */
    r.tmax = 1;
    CHECK_EQ_INT(box(&r, NULL, h), 0);

    /* Count only; cap 1 returns the count and writes only the first hit. */
    r = ray_of(-1, 1, 2, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, B_HI, NULL, NULL, 0), 2);
    memset(h, 0, sizeof h);
    h[1].prim = 99;
    CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, B_HI, NULL, h, 1), 2);
    CHECK_BOX_HIT(h[0], 1, 0, 1, 2, 0, ISECT_ENTER);
    CHECK_EQ_INT(h[1].prim, 99);
}

static void test_box_extremes(void)
{
    isect_hit h[4];
    isect_ray r;
    const double smallest = 4.9406564584124654e-324; /* 2^-1074 */

    /* Huge box: x [1e300, 2e300] from 0 along (1,0,0). */
    {
        const double lo[3] = { 1e300, -1e300, -1e300 }, hi[3] = { 2e300, 1e300, 1e300 };
        r = ray_of(0, 0, 0, 1, 0, 0);
        CHECK_EQ_INT(isect_ray_aabb(&r, lo, hi, NULL, h, 4), 2);
        CHECK_REL(h[0].t, 1e300);
        CHECK_REL(h[0].point[0], 1e300);
        CHECK_EQ_INT(h[0].prim, 0);
        CHECK_REL(h[1].t, 2e300);
        CHECK_EQ_INT(h[1].prim, 1);
        CHECK(hits_finite(h, 2));
    }
    /* hi - org and lo - org beyond DBL_MAX: x in [-1.7e308, 1e308] from
     * 1.7e308 along -4: in by face 1 at (1e308 - 1.7e308)/-4 = 1.75e307, out
     * by face 0 at (-1.7e308 - 1.7e308)/-4 = 8.5e307 (numerator -3.4e308
     * overflows; t does not). Points snap onto the faces. */
    {
        const double lo[3] = { -1.7e308, -1, -1 }, hi[3] = { 1e308, 1, 1 };
        r = ray_of(1.7e308, 0, 0, -4, 0, 0);
        CHECK_EQ_INT(isect_ray_aabb(&r, lo, hi, NULL, h, 4), 2);
        CHECK(hits_finite(h, 2));
        CHECK_REL(h[0].t, 1.75e307);
        CHECK(h[0].point[0] == 1e308);
        CHECK_EQ_INT(h[0].prim, 1);
        CHECK_REL(h[1].t, 8.5e307);
        CHECK(h[1].point[0] == -1.7e308);
        CHECK_EQ_INT(h[1].prim, 0);
        CHECK_EQ_INT(h[1].kind, ISECT_EXIT);
    }
    /* Tiny box: [1e-300, 3e-300]^3 along (1e-300,0,0): t 1 and 3. */
    {
        const double lo[3] = { 1e-300, 1e-300, 1e-300 }, hi[3] = { 3e-300, 3e-300, 3e-300 };
        r = ray_of(0, 2e-300, 2e-300, 1e-300, 0, 0);
        CHECK_EQ_INT(isect_ray_aabb(&r, lo, hi, NULL, h, 4), 2);
        CHECK_NEAR(h[0].t, 1, TOL);
        CHECK(h[0].point[0] == 1e-300);
        CHECK_REL(h[0].point[1], 2e-300);
        CHECK_EQ_INT(h[0].prim, 0);
        CHECK_NEAR(h[1].t, 3, TOL);
        CHECK(h[1].point[0] == 3e-300);
        CHECK_EQ_INT(h[1].prim, 1);
    }
    /* Subnormal direction: the crossings are at 1/2^-1074, beyond the double
     * range: no hit (and no inf/NaN hit). */
    r = ray_of(-1, 1, 2, smallest, 0, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 0);
    /* Subnormal x direction with the origin on the plane x = 0: x slab
     * [0/2^-1074, 1/2^-1074] = [0, inf), y [-1, 1] -> ENTER at 0 by face 0,
     * EXIT at 1 by face 3 (1/dir would give (0-0)*inf = NaN). */
    r = ray_of(0, 1, 2, smallest, 1, 0);
    CHECK_EQ_INT(box(&r, NULL, h), 2);
    CHECK_BOX_HIT(h[0], 0, 0, 1, 2, 0, ISECT_ENTER);
    CHECK_BOX_HIT(h[1], 1, 0, 2, 2, 3, ISECT_EXIT);
}

static void test_box_degenerate_and_errors(void)
{
    isect_hit h[4];
    isect_ray r = ray_of(-1, 1, 2, 1, 0, 0);
    const double flat_lo[3] = { 0, 0, 0 }, flat_hi[3] = { 1, 0, 1 };

    /* Flat (y thickness 0): never hit, even by a ray in its plane. */
    r = ray_of(0.5, -1, 0.5, 0, 1, 0);
    CHECK_EQ_INT(isect_ray_aabb(&r, flat_lo, flat_hi, NULL, h, 4), 0);
    r = ray_of(-1, 0, 0.5, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_aabb(&r, flat_lo, flat_hi, NULL, h, 4), 0);

    r = ray_of(-1, 1, 2, 1, 0, 0);
    {
        const double bad_hi[3] = { 1, -1, 1 }; /* lo > hi in y */
        const double nan_lo[3] = { 0, NAN, 0 }, inf_hi[3] = { 1, 2, INFINITY };
        CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, bad_hi, NULL, h, 4), ISECT_E_ARG);
        CHECK_EQ_INT(isect_ray_aabb(&r, nan_lo, B_HI, NULL, h, 4), ISECT_E_NONFINITE);
        CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, inf_hi, NULL, h, 4), ISECT_E_NONFINITE);
    }
    CHECK_EQ_INT(isect_ray_aabb(&r, NULL, B_HI, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, NULL, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_aabb(NULL, B_LO, B_HI, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, B_HI, NULL, h, -1), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, B_HI, NULL, NULL, 1), ISECT_E_ARG);
    r.org[1] = NAN;
    CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, B_HI, NULL, h, 4), ISECT_E_NONFINITE);
    r = ray_of(-1, 1, 2, 0, 0, 0);
    CHECK_EQ_INT(isect_ray_aabb(&r, B_LO, B_HI, NULL, h, 4), ISECT_E_DEGENERATE);
}

static void test_box_contains(void)
{
    const double data[6] = { 0, 0, 0, 1, 2, 4 };
    const double flat[6] = { 0, 0, 0, 1, 0, 1 };
    isect_shape s = { ISECT_AABB, 0, 0, 0, data, NULL, NULL };
    isect_shape f = { ISECT_AABB, 0, 0, 0, flat, NULL, NULL };
    const double inside[3] = { 0.5, 1, 2 }, on_face[3] = { 1, 1, 2 };
    const double corner_lo[3] = { 0, 0, 0 }, corner_hi[3] = { 1, 2, 4 };
    const double past[3] = { 1.0000000000000002, 1, 2 }; /* 1 + 2^-52 */
    const double below[3] = { 0.5, -1e-300, 2 };
    const double in_flat[3] = { 0.5, 0, 0.5 };
    const double nan_p[3] = { 0.5, NAN, 2 };

    CHECK_EQ_INT(isect_contains(&s, inside), 1);
    CHECK_EQ_INT(isect_contains(&s, on_face), 1);
    CHECK_EQ_INT(isect_contains(&s, corner_lo), 1);
    CHECK_EQ_INT(isect_contains(&s, corner_hi), 1);
    CHECK_EQ_INT(isect_contains(&s, past), 0);
    CHECK_EQ_INT(isect_contains(&s, below), 0);
    CHECK_EQ_INT(isect_contains(&f, in_flat), 0);
    CHECK_EQ_INT(isect_contains(&s, nan_p), ISECT_E_NONFINITE);
}

/* ----------------------------------------------------------------- convex */

/* [0,1]^3, planes in box-face order, normals of lengths 1, 2, 3, 1, 0.5, 4. */
static const double CUBE[6 * 4] = {
    -1, 0, 0, 0,   2, 0, 0, -2,   0, -3, 0, 0,
    0, 1, 0, -1,   0, 0, -0.5, 0, 0, 0, 4, -4,
};
/* Tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1): x, y, z >= 0, x+y+z <= 1. */
static const double TETRA[4 * 4] = {
    -1, 0, 0, 0,   0, -1, 0, 0,   0, 0, -1, 0,   1, 1, 1, -1,
};
#define INV_SQRT3 0.57735026918962576

static void test_convex_cube(void)
{
    isect_hit h[4];
    isect_ray r;

    /* Plane 0: side -(-1) = 1, n.d = -1 -> enters at 1; plane 1: side
     * 2(-1) - 2 = -4, n.d = 2 -> leaves at 2; the others are parallel with
     * the origin inside. */
    r = ray_of(-1, 0.5, 0.5, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 0, 0.5, 0.5, -1, 0, 0, 0, ISECT_ENTER);
    CHECK_HIT(h[1], 2, 1, 0.5, 0.5, 1, 0, 0, 1, ISECT_EXIT);

    /* From z = 3 along (0,0,-2): plane 5 side 12 - 4 = 8, n.d = -8 -> in at
     * 1; plane 4 side -1.5, n.d = 1 -> out at 1.5. */
    r = ray_of(0.5, 0.5, 3, 0, 0, -2);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 0.5, 0.5, 1, 0, 0, 1, 5, ISECT_ENTER);
    CHECK_HIT(h[1], 1.5, 0.5, 0.5, 0, 0, 0, -1, 4, ISECT_EXIT);

    /* Corner: planes 0, 2, 4 all enter at t = 1 (1/1, 3/3, 0.5/0.5) -> 0;
     * planes 1, 3, 5 all leave at 2 (4/2, 2/1, 8/4) -> 1. */
    r = ray_of(-1, -1, -1, 1, 1, 1);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 0, 0, 0, -1, 0, 0, 0, ISECT_ENTER);
    CHECK_HIT(h[1], 2, 1, 1, 1, 1, 0, 0, 1, ISECT_EXIT);

    /* TOUCH at the edge x = 1, y = 1: dir (1,-1,0) from (0,2,0.5). Entering:
     * plane 0 at 0, plane 3 (side 1, n.d -1) at 1 -> enterMax 1, plane 3;
     * leaving: plane 1 (side -2, n.d 2) at 1, plane 2 (side -6, n.d 3) at 2
     * -> exitMin 1, plane 1. Equal: one TOUCH with the lower index, plane 1
     * (normal +x). */
    r = ray_of(0, 2, 0.5, 1, -1, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 1);
    CHECK_HIT(h[0], 1, 1, 1, 0.5, 1, 0, 0, 1, ISECT_TOUCH);
    /* The same edge grazed the other way round, dir (-1,1,0) from (2,0,0.5):
     * plane 1 (side 2, n.d -2) enters at 1, plane 3 (side -1, n.d 1) leaves
     * at 1 -> TOUCH, plane 1 again. */
    r = ray_of(2, 0, 0.5, -1, 1, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 1);
    CHECK_HIT(h[0], 1, 1, 1, 0.5, 1, 0, 0, 1, ISECT_TOUCH);

    /* Origin inside: only the EXIT. */
    r = ray_of(0.5, 0.5, 0.5, 0, 1, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 1);
    CHECK_HIT(h[0], 0.5, 0.5, 1, 0.5, 0, 1, 0, 3, ISECT_EXIT);

    /* Solid: CULL_BACK keeps the EXIT. */
    {
        isect_opts o = opts_of(ISECT_CULL_BACK, ISECT_EPS_DEFAULT);
        r = ray_of(-1, 0.5, 0.5, 1, 0, 0);
        CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, &o, h, 4), 2);
    }
}

static void test_convex_parallel(void)
{
    isect_hit h[4];
    isect_ray r;
    isect_opts o;

    /* In the face plane z = 1 (plane 5: side 4 - 4 = 0, on it = inside). */
    r = ray_of(-1, 0.5, 1, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 0, 0.5, 1, -1, 0, 0, 0, ISECT_ENTER);
    CHECK_HIT(h[1], 2, 1, 0.5, 1, 1, 0, 0, 1, ISECT_EXIT);

    /* Parallel above it (side 6 - 4 = 2 > 0): the whole line misses. */
    r = ray_of(-1, 0.5, 1.5, 1, 0, 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 0);

    /* Nearly parallel, dir (1,0,1e-13) from (-1,0.5,1): |n.d|/(|n||d|) ~ 1e-13
     * <= eps = 1e-12, so planes 4 and 5 count as parallel with the origin on
     * or inside them: in at 1 by plane 0, out at 2 by plane 1. With eps = 0
     * plane 5 (side 0, n.d = 4e-13 > 0) is left at t = 0 < enterMax = 1: miss. */
    r = ray_of(-1, 0.5, 1, 1, 0, 1e-13);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, h, 4), 2);
    CHECK_EQ_INT(h[0].prim, 0);
    CHECK_NEAR(h[0].t, 1, TOL);
    CHECK_EQ_INT(h[1].prim, 1);
    CHECK_NEAR(h[1].t, 2, TOL);
    o = opts_of(0, 0.0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, &o, h, 4), 0);

    /* The parallel test is inclusive, as for the plane: z <= 2 with dir
     * (0,3,4), |n.d|/(|n||d|) = 4/5 <= eps = 0.8 (as a double): parallel,
     * origin inside, no crossing. With eps = 0.79 it is left at t = 0.5. */
    {
        static const double below2[4] = { 0, 0, 1, -2 };
        r = ray_of(0, 0, 0, 0, 3, 4);
        o = opts_of(0, 0.8);
        CHECK_EQ_INT(isect_ray_convex(&r, below2, 1, &o, h, 4), 0);
        o = opts_of(0, 0.79);
        CHECK_EQ_INT(isect_ray_convex(&r, below2, 1, &o, h, 4), 1);
        CHECK_HIT(h[0], 0.5, 0, 1.5, 2, 0, 0, 1, 0, ISECT_EXIT);
    }

    /* A parallel plane whose side rounds the wrong way. Plane 0 is
     * x + y + z <= 2^54 - 2; dir (1,-1,0) is exactly parallel to it, and the
     * origin (2^54, -1, -1) lies exactly on it (side 0: inside). Summed left
     * to right in doubles, 2^54 - 1 rounds back to 2^54 twice (ties to even),
     * so the plain side is +2: "outside". The kernel must not trust that
     * sign (its bound is ~4u 2^55). Planes 1 and 2 are x <= 2^54 + 8 and
     * x >= 2^54 - 8: out at t = 8 by plane 1 (in at t = -8 behind). */
    {
        const double big = 0x1p54;
        const double slab[3 * 4] = { 1, 1, 1, -(big - 2), 1, 0, 0, -(big + 8), -1, 0, 0, big - 8 };
        r = ray_of(big, -1, -1, 1, -1, 0);
        CHECK_EQ_INT(isect_ray_convex(&r, slab, 3, NULL, h, 4), 1);
        CHECK_EQ_INT(h[0].prim, 1);
        CHECK_EQ_INT(h[0].kind, ISECT_EXIT);
        CHECK(h[0].t == 8.0);
        CHECK(h[0].point[0] == big + 8 && h[0].point[1] == -9.0 && h[0].point[2] == -1.0);
        r.tmin = -INFINITY;
        CHECK_EQ_INT(isect_ray_convex(&r, slab, 3, NULL, h, 4), 2);
        CHECK(h[0].t == -8.0 && h[0].prim == 2 && h[0].kind == ISECT_ENTER);
        /* moved 4 beyond the plane (side exactly +4, plain +4 too): no hit */
        r.org[0] = big + 4;
        CHECK_EQ_INT(isect_ray_convex(&r, slab, 3, NULL, h, 4), 0);
    }
}

static void test_convex_tetra(void)
{
    isect_hit h[4];
    isect_ray r;

    /* Up through the base: planes 0, 1 parallel (side -0.25); plane 2 side
     * 1, n.d -1 -> in at 1; plane 3 side 0.25+0.25-1-1 = -1.5, n.d 1 -> out
     * at 1.5, point (0.25,0.25,0.5), normal (1,1,1)/sqrt3. */
    r = ray_of(0.25, 0.25, -1, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_convex(&r, TETRA, 4, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 0.25, 0.25, 0, 0, 0, -1, 2, ISECT_ENTER);
    CHECK_HIT(h[1], 1.5, 0.25, 0.25, 0.5, INV_SQRT3, INV_SQRT3, INV_SQRT3, 3, ISECT_EXIT);

    /* Through the vertex (0,0,0) along (1,1,1): planes 0, 1, 2 enter at 1
     * -> 0; plane 3 side -3-1 = -4, n.d 3 -> out at 4/3. */
    r = ray_of(-1, -1, -1, 1, 1, 1);
    CHECK_EQ_INT(isect_ray_convex(&r, TETRA, 4, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 0, 0, 0, -1, 0, 0, 0, ISECT_ENTER);
    CHECK_HIT(h[1], 4.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, INV_SQRT3, INV_SQRT3,
              INV_SQRT3, 3, ISECT_EXIT);

    /* Along the edge (1,0,0)-(0,0,1): dir (-1,0,1) from (2,0,-1) lies in
     * planes 1 (side 0) and 3 (n.d = -1+1 = 0, side 2-1-1 = 0): parallel, on
     * them. Plane 2 (side 1, n.d -1) in at 1; plane 0 (side -2, n.d 1) out
     * at 2. */
    r = ray_of(2, 0, -1, -1, 0, 1);
    CHECK_EQ_INT(isect_ray_convex(&r, TETRA, 4, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 1, 0, 0, 0, 0, -1, 2, ISECT_ENTER);
    CHECK_HIT(h[1], 2, 0, 0, 1, -1, 0, 0, 0, ISECT_EXIT);

    /* TOUCH at the vertex (0,0,1): dir (1,1,0) from (-1,-1,1). Planes 0 and 1
     * enter at 1 (tie -> 0), plane 2 parallel (side -1), plane 3 (side
     * -1-1+1-1 = -2, n.d 2) leaves at 1: TOUCH, lowest index 0. */
    r = ray_of(-1, -1, 1, 1, 1, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, TETRA, 4, NULL, h, 4), 1);
    CHECK_HIT(h[0], 1, 0, 0, 1, -1, 0, 0, 0, ISECT_TOUCH);

    /* Miss: from (1,1,1) along +x, plane 0 enters at -1, plane 3 (side 2)
     * leaves at -2 < -1. */
    r = ray_of(1, 1, 1, 1, 0, 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_convex(&r, TETRA, 4, NULL, h, 4), 0);
}

static void test_convex_unbounded(void)
{
    static const double half[4] = { 0, 0, 1, 0 };                /* z <= 0 */
    static const double slab[8] = { 0, 0, -1, 0, 0, 0, 1, -1 }; /* 0 <= z <= 1 */
    static const double empty[8] = { 0, 0, 1, 0, 0, 0, 0, 1 };  /* 0 <= -1 */
    static const double full[8] = { 0, 0, 1, 0, 0, 0, 0, -1 };  /* 0 <= 1 */
    static const double everything[4] = { 0, 0, 0, 0 };         /* 0 <= 0 */
    isect_hit h[4];
    isect_ray r;

    /* Half-space z <= 0: only an ENTER from above, only an EXIT from below. */
    r = ray_of(0, 0, 5, 0, 0, -1);
    CHECK_EQ_INT(isect_ray_convex(&r, half, 1, NULL, h, 4), 1);
    CHECK_HIT(h[0], 5, 0, 0, 0, 0, 0, 1, 0, ISECT_ENTER);
    r = ray_of(0, 0, -5, 0, 0, 1);
    CHECK_EQ_INT(isect_ray_convex(&r, half, 1, NULL, h, 4), 1);
    CHECK_HIT(h[0], 5, 0, 0, 0, 0, 0, 1, 0, ISECT_EXIT);
    r = ray_of(0, 0, -5, 0, 0, -1); /* going deeper: the line entered at t = -5 */
    CHECK_EQ_INT(isect_ray_convex(&r, half, 1, NULL, h, 4), 0);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_convex(&r, half, 1, NULL, h, 4), 1);
    CHECK_HIT(h[0], -5, 0, 0, 0, 0, 0, 1, 0, ISECT_ENTER);
    r = ray_of(0, 0, -1, 1, 0, 0); /* inside, parallel: the line never leaves */
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_convex(&r, half, 1, NULL, h, 4), 0);

    /* Slab 0 <= z <= 1 along (1,0,1) from (0,0,-1): in at 1, out at 2. */
    r = ray_of(0, 0, -1, 1, 0, 1);
    CHECK_EQ_INT(isect_ray_convex(&r, slab, 2, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 1, 0, 0, 0, 0, -1, 0, ISECT_ENTER);
    CHECK_HIT(h[1], 2, 2, 0, 1, 0, 0, 1, 1, ISECT_EXIT);

    /* Zero-normal planes go through the parallel branch: d > 0 is empty. */
    r = ray_of(0, 0, 5, 0, 0, -1);
    r.tmin = -INFINITY;
    CHECK_EQ_INT(isect_ray_convex(&r, empty, 2, NULL, h, 4), 0);
    CHECK_EQ_INT(isect_ray_convex(&r, full, 2, NULL, h, 4), 1);
    CHECK_HIT(h[0], 5, 0, 0, 0, 0, 0, 1, 0, ISECT_ENTER);
    CHECK_EQ_INT(isect_ray_convex(&r, everything, 1, NULL, h, 4), 0);
    {
        const double p[3] = { 1, 2, 3 };
        isect_shape e = { ISECT_CONVEX, 2, 0, 0, empty, NULL, NULL };
        isect_shape a = { ISECT_CONVEX, 1, 0, 0, everything, NULL, NULL };
        CHECK_EQ_INT(isect_contains(&e, p), 0);
        CHECK_EQ_INT(isect_contains(&a, p), 1);
    }
}

static void test_convex_scale(void)
{
    /* The cube with every coefficient times 1e300, and times 1e-300. */
    static const double big[6 * 4] = {
        -1e300, 0, 0, 0,   1e300, 0, 0, -1e300,   0, -1e300, 0, 0,
        0, 1e300, 0, -1e300,   0, 0, -1e300, 0,   0, 0, 1e300, -1e300,
    };
    static const double tiny[6 * 4] = {
        -1e-300, 0, 0, 0,   1e-300, 0, 0, -1e-300,   0, -1e-300, 0, 0,
        0, 1e-300, 0, -1e-300,   0, 0, -1e-300, 0,   0, 0, 1e-300, -1e-300,
    };
    isect_hit h[4];
    isect_ray r;

    /* dir 1e300 (n.d = 1e600 would overflow): x [1/1e300, 2/1e300]. */
    r = ray_of(-1, 0.5, 0.5, 1e300, 0, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, big, 6, NULL, h, 4), 2);
    CHECK(hits_finite(h, 2));
    CHECK_REL(h[0].t, 1e-300);
    CHECK_VEC(h[0].point, 0, 0.5, 0.5);
    CHECK_VEC(h[0].normal, -1, 0, 0);
    CHECK_EQ_INT(h[0].prim, 0);
    CHECK_REL(h[1].t, 2e-300);
    CHECK_VEC(h[1].point, 1, 0.5, 0.5);
    CHECK_EQ_INT(h[1].prim, 1);

    /* Normals 1e-300 (|n|^2 underflows to 0): in at 1, out at 2. */
    r = ray_of(-1, 0.5, 0.5, 1, 0, 0);
    CHECK_EQ_INT(isect_ray_convex(&r, tiny, 6, NULL, h, 4), 2);
    CHECK_HIT(h[0], 1, 0, 0.5, 0.5, -1, 0, 0, 0, ISECT_ENTER);
    CHECK_HIT(h[1], 2, 1, 0.5, 0.5, 1, 0, 0, 1, ISECT_EXIT);
}

static void test_convex_contains_and_errors(void)
{
    isect_shape cube = { ISECT_CONVEX, 6, 0, 0, CUBE, NULL, NULL };
    isect_shape tetra = { ISECT_CONVEX, 4, 0, 0, TETRA, NULL, NULL };
    const double centre[3] = { 0.5, 0.5, 0.5 };
    const double on_face[3] = { 1, 0.5, 0.5 }; /* plane 1: 2*1 - 2 = 0 */
    const double corner[3] = { 1, 1, 1 };
    const double past[3] = { 1.0000000000000002, 0.5, 0.5 };
    const double under[3] = { 0.5, 0.5, -1e-300 }; /* plane 4: 5e-301 > 0 */
    const double t_face[3] = { 0.25, 0.25, 0.5 };  /* x+y+z-1 = 0 exactly */
    const double t_past[3] = { 0.25, 0.25, 0.50000000000000022 }; /* 0.5 + 2^-52 */
    const double t_vertex[3] = { 0, 0, 0 };
    isect_hit h[4];
    isect_ray r = ray_of(-1, 0.5, 0.5, 1, 0, 0);
    const double nan_planes[8] = { 0, 0, 1, 0, 0, NAN, 1, 0 };
    const double inf_planes[4] = { 0, 0, 1, -INFINITY };

    CHECK_EQ_INT(isect_contains(&cube, centre), 1);
    CHECK_EQ_INT(isect_contains(&cube, on_face), 1);
    CHECK_EQ_INT(isect_contains(&cube, corner), 1);
    CHECK_EQ_INT(isect_contains(&cube, past), 0);
    CHECK_EQ_INT(isect_contains(&cube, under), 0);
    CHECK_EQ_INT(isect_contains(&tetra, t_face), 1);
    CHECK_EQ_INT(isect_contains(&tetra, t_past), 0);
    CHECK_EQ_INT(isect_contains(&tetra, t_vertex), 1);

    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 0, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, -1, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_convex(&r, NULL, 6, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_convex(NULL, CUBE, 6, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_ray_convex(&r, nan_planes, 2, NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_convex(&r, inf_planes, 1, NULL, h, 4), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_ray_convex(&r, CUBE, 6, NULL, NULL, 0), 2);
}

int main(void)
{
    test_plane();
    test_box_faces();
    test_box_edges_corners();
    test_box_inside_and_parallel();
    test_box_clipping();
    test_box_extremes();
    test_box_degenerate_and_errors();
    test_box_contains();
    test_convex_cube();
    test_convex_parallel();
    test_convex_tetra();
    test_convex_unbounded();
    test_convex_scale();
    test_convex_contains_and_errors();
    return check_summary();
}
