/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_api.c — the shared layer: struct layouts, version and status text,
 * argument checking in the dispatcher, batch semantics (MISS / INVALID
 * records, counts, nothing written on error, CSR offsets), containment
 * dispatch, transforms, and the snprintf-style cap.
 *
 * Expected values are closed-form (a unit sphere at a known place), never
 * taken from the library.
 */
#include "check.h"

#include <isect.h>

#include <stddef.h>
#include <string.h>

static const double unit_sphere[4] = { 0, 0, 0, 1 };

static isect_shape sphere_shape(const double *data)
{
    isect_shape s = { ISECT_SPHERE, 0, 0, 0, data, NULL, NULL };
    return s;
}

static isect_ray ray_make(double ox, double oy, double oz, double dx, double dy, double dz)
{
    isect_ray r = { { ox, oy, oz }, { dx, dy, dz }, 0.0, INFINITY };
    return r;
}

static void test_layout(void)
{
    /* SPEC: isect_ray 64 bytes, isect_hit 80, isect_shape 40 on 64-bit. */
    CHECK_EQ_INT(sizeof(isect_ray), 64);
    CHECK_EQ_INT(offsetof(isect_ray, org), 0);
    CHECK_EQ_INT(offsetof(isect_ray, dir), 24);
    CHECK_EQ_INT(offsetof(isect_ray, tmin), 48);
    CHECK_EQ_INT(offsetof(isect_ray, tmax), 56);
    CHECK_EQ_INT(sizeof(isect_hit), 80);
    CHECK_EQ_INT(offsetof(isect_hit, t), 0);
    CHECK_EQ_INT(offsetof(isect_hit, point), 8);
    CHECK_EQ_INT(offsetof(isect_hit, normal), 32);
    CHECK_EQ_INT(offsetof(isect_hit, uv), 56);
    CHECK_EQ_INT(offsetof(isect_hit, prim), 72);
    CHECK_EQ_INT(offsetof(isect_hit, kind), 76);
    CHECK_EQ_INT(sizeof(isect_opts), 16);
    CHECK_EQ_INT(offsetof(isect_opts, size), 0);
    CHECK_EQ_INT(offsetof(isect_opts, flags), 4);
    CHECK_EQ_INT(offsetof(isect_opts, eps), 8);
    CHECK_EQ_INT(sizeof(isect_xform), 256);
    CHECK_EQ_INT(offsetof(isect_xform, inv), 128);
    if (sizeof(void *) == 8) {
        CHECK_EQ_INT(sizeof(isect_shape), 40);
        CHECK_EQ_INT(offsetof(isect_shape, type), 0);
        CHECK_EQ_INT(offsetof(isect_shape, n), 4);
        CHECK_EQ_INT(offsetof(isect_shape, flags), 8);
        CHECK_EQ_INT(offsetof(isect_shape, reserved), 12);
        CHECK_EQ_INT(offsetof(isect_shape, data), 16);
        CHECK_EQ_INT(offsetof(isect_shape, mesh), 24);
        CHECK_EQ_INT(offsetof(isect_shape, xform), 32);
    }
}

static void test_version_and_status(void)
{
    CHECK_EQ_INT(isect_version(), ISECT_VERSION);
    CHECK_EQ_INT(isect_version(),
                 ISECT_VERSION_MAJOR * 10000 + ISECT_VERSION_MINOR * 100 + ISECT_VERSION_PATCH);
    CHECK(strcmp(isect_version_string(), ISECT_VERSION_STRING) == 0);
    CHECK_EQ_INT(isect_abi_version(), 1); /* libisect.so.1 */
    const int codes[] = { ISECT_OK, ISECT_E_ARG, ISECT_E_NONFINITE, ISECT_E_DEGENERATE,
                          ISECT_E_NOMEM };
    CHECK_EQ_INT(ISECT_E_ARG, -1);
    CHECK_EQ_INT(ISECT_E_NONFINITE, -2);
    CHECK_EQ_INT(ISECT_E_DEGENERATE, -3);
    CHECK_EQ_INT(ISECT_E_NOMEM, -4);
    for (int i = 0; i < 5; i++) {
        CHECK(isect_strerror(codes[i]) != NULL);
        CHECK(strcmp(isect_strerror(codes[i]), "unknown status") != 0);
        for (int j = 0; j < i; j++)
            CHECK(strcmp(isect_strerror(codes[i]), isect_strerror(codes[j])) != 0);
    }
    CHECK(strcmp(isect_strerror(-99), "unknown status") == 0);
    CHECK(strcmp(isect_strerror(7), "unknown status") == 0);
}

static void test_dispatch_rejects(void)
{
    isect_shape s = sphere_shape(unit_sphere);
    isect_ray r = ray_make(0, 0, -5, 0, 0, 1);
    isect_hit h[4];

    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 4), 2);
    CHECK_EQ_INT(isect_intersect(NULL, &r, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect(&s, NULL, NULL, h, 4), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, -1), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, NULL, 1), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, NULL, 0), 2); /* count only */

    isect_shape bad = s;
    bad.type = 0;
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);
    bad.type = 99;
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);
    bad.type = -3;
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);
    bad.type = ISECT_MESH; /* reserved: no mesh given */
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);
    bad = s;
    bad.reserved = 1;
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);
    bad = s;
    bad.data = NULL;
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);
    bad = s;
    bad.n = 3; /* a sphere has no count */
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);
    bad = s;
    bad.flags = ISECT_CAPPED; /* nor flags */
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_ARG);

    /* Options. */
    isect_opts o = ISECT_OPTS_INIT;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 4), 2);
    o.size = 0;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 4), ISECT_E_ARG);
    o.size = 8; /* an older, shorter struct: eps takes its default */
    o.eps = -1.0;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 4), 2);
    o = (isect_opts)ISECT_OPTS_INIT;
    o.flags = 0x80u;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 4), ISECT_E_ARG);
    o = (isect_opts)ISECT_OPTS_INIT;
    o.eps = -1e-9;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 4), ISECT_E_ARG);
    o.eps = NAN;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 4), ISECT_E_NONFINITE);
    o.eps = INFINITY;
    CHECK_EQ_INT(isect_intersect(&s, &r, &o, h, 4), ISECT_E_NONFINITE);

    /* Rays. */
    isect_ray br = r;
    br.org[1] = NAN;
    CHECK_EQ_INT(isect_intersect(&s, &br, NULL, h, 4), ISECT_E_NONFINITE);
    br = r;
    br.dir[0] = INFINITY;
    CHECK_EQ_INT(isect_intersect(&s, &br, NULL, h, 4), ISECT_E_NONFINITE);
    br = r;
    br.tmin = NAN;
    CHECK_EQ_INT(isect_intersect(&s, &br, NULL, h, 4), ISECT_E_NONFINITE);
    br = r;
    br.tmax = NAN;
    CHECK_EQ_INT(isect_intersect(&s, &br, NULL, h, 4), ISECT_E_NONFINITE);
    br = r;
    br.dir[2] = 0.0;
    CHECK_EQ_INT(isect_intersect(&s, &br, NULL, h, 4), ISECT_E_DEGENERATE);
    br = r;
    br.tmin = -INFINITY; /* infinite range limits are allowed */
    CHECK_EQ_INT(isect_intersect(&s, &br, NULL, h, 4), 2);
    br = r;
    br.tmin = 7.0;
    br.tmax = 3.0; /* tmin > tmax: no hits, not an error */
    CHECK_EQ_INT(isect_intersect(&s, &br, NULL, h, 4), 0);

    /* A descriptor whose transform holds NaN. */
    isect_xform x;
    memset(&x, 0, sizeof x);
    x.m[0] = NAN;
    bad = s;
    bad.xform = &x;
    CHECK_EQ_INT(isect_intersect(&bad, &r, NULL, h, 4), ISECT_E_NONFINITE);
}

static void test_cap_and_order(void)
{
    isect_shape s = sphere_shape(unit_sphere);
    isect_ray r = ray_make(0, 0, -5, 0, 0, 1);
    isect_hit h[3];
    memset(h, 0x5a, sizeof h);
    isect_hit guard = h[1];
    /* snprintf-style: the full count comes back, only cap records are written. */
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 1), 2);
    CHECK_NEAR(h[0].t, 4.0, 1e-15);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    CHECK(memcmp(&h[1], &guard, sizeof guard) == 0);
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 3), 2);
    CHECK(h[0].t < h[1].t);
    CHECK_NEAR(h[1].t, 6.0, 1e-15);
    CHECK_EQ_INT(h[1].kind, ISECT_EXIT);
    CHECK_NEAR(h[1].normal[2], 1.0, 1e-15);
    CHECK_EQ_INT(h[1].prim, -1);
    /* Origin inside: only the exit remains in [0, inf). */
    isect_ray in = ray_make(0, 0, 0, 0, 0, 2);
    CHECK_EQ_INT(isect_intersect(&s, &in, NULL, h, 3), 1);
    CHECK_NEAR(h[0].t, 0.5, 1e-15);
    CHECK_EQ_INT(h[0].kind, ISECT_EXIT);
}

static void test_batch(void)
{
    isect_shape s = sphere_shape(unit_sphere);
    isect_ray rays[5] = {
        ray_make(0, 0, -5, 0, 0, 1),  /* hit at 4 */
        ray_make(0, 3, -5, 0, 0, 1),  /* miss */
        ray_make(0, 0, -5, 0, 0, 0),  /* zero direction: invalid */
        ray_make(0, 0, -5, 0, 0, 1),
        ray_make(0, 0, 0, 1, 0, 0),   /* inside: exit at 1 */
    };
    rays[3].org[0] = NAN;             /* invalid */
    isect_hit out[5];
    CHECK_EQ_INT(isect_intersect_batch(&s, rays, 5, NULL, out), 2);
    CHECK_NEAR(out[0].t, 4.0, 1e-15);
    CHECK_EQ_INT(out[0].kind, ISECT_ENTER);
    CHECK_EQ_INT(out[1].kind, ISECT_MISS);
    CHECK(isinf(out[1].t) && out[1].t > 0);
    CHECK_EQ_INT(out[1].prim, -1);
    CHECK_EQ_INT(out[2].kind, ISECT_INVALID);
    CHECK(isnan(out[2].t));
    CHECK_EQ_INT(out[2].prim, -1);
    CHECK_EQ_INT(out[3].kind, ISECT_INVALID);
    CHECK_EQ_INT(out[4].kind, ISECT_EXIT);
    CHECK_NEAR(out[4].t, 1.0, 1e-15);

    /* Closest hit equals the first of all hits, bit for bit. */
    isect_hit all[4];
    CHECK_EQ_INT(isect_intersect(&s, &rays[0], NULL, all, 4), 2);
    CHECK(memcmp(&all[0], &out[0], sizeof all[0]) == 0);

    /* Errors write nothing. */
    isect_hit guard[5];
    memset(out, 0x77, sizeof out);
    memcpy(guard, out, sizeof out);
    isect_shape bad = s;
    bad.type = 42;
    CHECK_EQ_INT(isect_intersect_batch(&bad, rays, 5, NULL, out), ISECT_E_ARG);
    double negative[4] = { 0, 0, 0, -1 };
    bad = sphere_shape(negative);
    CHECK_EQ_INT(isect_intersect_batch(&bad, rays, 5, NULL, out), ISECT_E_ARG);
    isect_opts o = ISECT_OPTS_INIT;
    o.eps = NAN;
    CHECK_EQ_INT(isect_intersect_batch(&s, rays, 5, &o, out), ISECT_E_NONFINITE);
    CHECK(memcmp(out, guard, sizeof out) == 0);
    CHECK_EQ_INT(isect_intersect_batch(&s, rays, -1, NULL, out), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect_batch(&s, NULL, 5, NULL, out), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect_batch(&s, rays, 5, NULL, NULL), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect_batch(&s, NULL, 0, NULL, NULL), 0);

    /* Every hit, CSR style: 2 + 0 + invalid record + invalid record + 1. */
    int64_t off[6];
    isect_hit hits[8];
    CHECK_EQ_INT(isect_intersect_all_batch(&s, rays, 5, NULL, off, hits, 8), 5);
    const int64_t want[6] = { 0, 2, 2, 3, 4, 5 };
    for (int i = 0; i < 6; i++)
        CHECK_EQ_INT(off[i], want[i]);
    CHECK(memcmp(&hits[0], &all[0], 2 * sizeof all[0]) == 0);
    CHECK_EQ_INT(hits[2].kind, ISECT_INVALID);
    CHECK_EQ_INT(hits[4].kind, ISECT_EXIT);
    /* Too small a buffer: the total and the offsets are still complete. */
    memset(hits, 0x33, sizeof hits);
    isect_hit keep = hits[1];
    int64_t off2[6];
    CHECK_EQ_INT(isect_intersect_all_batch(&s, rays, 5, NULL, off2, hits, 1), 5);
    for (int i = 0; i < 6; i++)
        CHECK_EQ_INT(off2[i], want[i]);
    CHECK(memcmp(&hits[1], &keep, sizeof keep) == 0);
    CHECK_EQ_INT(isect_intersect_all_batch(&s, rays, 5, NULL, off2, NULL, 0), 5);
    CHECK_EQ_INT(isect_intersect_all_batch(&s, rays, 5, NULL, NULL, hits, 8), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect_all_batch(&s, rays, 5, NULL, off2, NULL, 3), ISECT_E_ARG);
    CHECK_EQ_INT(isect_intersect_all_batch(&s, rays, 5, NULL, off2, hits, -1), ISECT_E_ARG);
}

static void test_contains(void)
{
    isect_shape s = sphere_shape(unit_sphere);
    const double inside[3] = { 0.5, 0, 0 }, outside[3] = { 2, 0, 0 }, on[3] = { 0, 1, 0 };
    CHECK_EQ_INT(isect_contains(&s, inside), 1);
    CHECK_EQ_INT(isect_contains(&s, outside), 0);
    CHECK_EQ_INT(isect_contains(&s, on), 1); /* closed set */
    CHECK_EQ_INT(isect_contains(&s, NULL), ISECT_E_ARG);
    const double nan_point[3] = { NAN, 0, 0 };
    CHECK_EQ_INT(isect_contains(&s, nan_point), ISECT_E_NONFINITE);

    double pts[4][3] = { { 0, 0, 0 }, { 3, 0, 0 }, { NAN, 0, 0 }, { 0, 0, -0.99 } };
    uint8_t in[4];
    CHECK_EQ_INT(isect_contains_batch(&s, &pts[0][0], 4, in), 2);
    CHECK_EQ_INT(in[0], 1);
    CHECK_EQ_INT(in[1], 0);
    CHECK_EQ_INT(in[2], ISECT_INVALID);
    CHECK_EQ_INT(in[3], 1);

    /* Thin surfaces have no inside. */
    const double tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    isect_shape t = { ISECT_TRIANGLE, 0, 0, 0, tri, NULL, NULL };
    CHECK_EQ_INT(isect_contains(&t, inside), ISECT_E_ARG);
    memset(in, 9, sizeof in);
    CHECK_EQ_INT(isect_contains_batch(&t, &pts[0][0], 4, in), ISECT_E_ARG);
    CHECK_EQ_INT(in[0], 9); /* nothing written */
    const double cyl[7] = { 0, 0, 0, 0, 0, 1, 1 };
    isect_shape open_cyl = { ISECT_CYLINDER, 0, 0, 0, cyl, NULL, NULL };
    isect_shape capped_cyl = { ISECT_CYLINDER, 0, ISECT_CAPPED, 0, cyl, NULL, NULL };
    const double mid[3] = { 0, 0, 0.5 };
    CHECK_EQ_INT(isect_contains(&open_cyl, mid), ISECT_E_ARG);
    CHECK_EQ_INT(isect_contains(&capped_cyl, mid), 1);
}

static void test_xform(void)
{
    isect_xform x;
    const double singular[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1 };
    const double projective[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1 };
    double with_nan[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    with_nan[5] = NAN;
    CHECK_EQ_INT(isect_xform_init(&x, singular), ISECT_E_DEGENERATE);
    CHECK_EQ_INT(isect_xform_init(&x, projective), ISECT_E_ARG);
    CHECK_EQ_INT(isect_xform_init(&x, with_nan), ISECT_E_NONFINITE);
    CHECK_EQ_INT(isect_xform_init(NULL, projective), ISECT_E_ARG);
    CHECK_EQ_INT(isect_xform_init(&x, NULL), ISECT_E_ARG);
    /* Tiny but well-conditioned: the singularity test is scale-invariant. */
    const double tiny[16] = { 1e-200, 0, 0, 0, 0, 1e-200, 0, 0, 0, 0, 1e-200, 0, 0, 0, 0, 1 };
    CHECK_EQ_INT(isect_xform_init(&x, tiny), ISECT_OK);

    /* Translate by (10, 0, 0) and scale z by 2: the unit sphere becomes the
     * ellipsoid centred at (10,0,0) with radii (1,1,2). */
    const double m[16] = { 1, 0, 0, 10, 0, 1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 };
    CHECK_EQ_INT(isect_xform_init(&x, m), ISECT_OK);
    CHECK_NEAR(x.inv[3], -10.0, 0);
    CHECK_NEAR(x.inv[10], 0.5, 0);
    isect_shape s = sphere_shape(unit_sphere);
    s.xform = &x;
    isect_ray r = ray_make(10, 0, -10, 0, 0, 1);
    isect_hit h[4];
    CHECK_EQ_INT(isect_intersect(&s, &r, NULL, h, 4), 2);
    CHECK_NEAR(h[0].t, 8.0, 1e-15);
    CHECK_NEAR(h[0].point[2], -2.0, 1e-15);
    CHECK_NEAR(h[0].normal[2], -1.0, 1e-15);
    CHECK_NEAR(h[1].t, 12.0, 1e-15);
    /* Oblique ray: compare with the direct ellipsoid (t is preserved). */
    const double ell[6] = { 10, 0, 0, 1, 1, 2 };
    isect_shape e = { ISECT_ELLIPSOID, 0, 0, 0, ell, NULL, NULL };
    isect_ray ob = ray_make(8, 1, -3, 1, -0.25, 1.5);
    isect_hit he[4];
    int ne = isect_intersect(&e, &ob, NULL, he, 4);
    CHECK_EQ_INT(isect_intersect(&s, &ob, NULL, h, 4), ne);
    for (int i = 0; i < ne && i < 4; i++) {
        CHECK_NEAR(h[i].t, he[i].t, 1e-14);
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(h[i].point[k], he[i].point[k], 1e-13);
            CHECK_NEAR(h[i].normal[k], he[i].normal[k], 1e-13);
        }
        CHECK_EQ_INT(h[i].kind, he[i].kind);
    }
    /* contains through the transform */
    const double p_in[3] = { 10, 0, 1.9 }, p_out[3] = { 10, 0, 2.1 };
    CHECK_EQ_INT(isect_contains(&s, p_in), 1);
    CHECK_EQ_INT(isect_contains(&s, p_out), 0);

    /* A mirror keeps outward normals outward: still ENTER then EXIT. */
    const double mirror[16] = { -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    CHECK_EQ_INT(isect_xform_init(&x, mirror), ISECT_OK);
    isect_ray mr = ray_make(-5, 0, 0, 1, 0, 0);
    CHECK_EQ_INT(isect_intersect(&s, &mr, NULL, h, 4), 2);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    CHECK_NEAR(h[0].normal[0], -1.0, 1e-15);
    CHECK_EQ_INT(h[1].kind, ISECT_EXIT);

    /* The helpers on their own. */
    CHECK_EQ_INT(isect_xform_init(&x, m), ISECT_OK);
    isect_ray obj;
    CHECK_EQ_INT(isect_xform_ray(&x, &r, &obj), ISECT_OK);
    CHECK_NEAR(obj.org[0], 0.0, 0);
    CHECK_NEAR(obj.org[2], -5.0, 0);
    CHECK_NEAR(obj.dir[2], 0.5, 0); /* not renormalised */
    CHECK_EQ_INT(isect_xform_ray(NULL, &r, &obj), ISECT_E_ARG);
    CHECK_EQ_INT(isect_xform_hits(&x, NULL, 1), ISECT_E_ARG);
    CHECK_EQ_INT(isect_xform_hits(&x, h, -1), ISECT_E_ARG);
    CHECK_EQ_INT(isect_xform_hits(&x, NULL, 0), ISECT_OK);
}

static void test_cull_back(void)
{
    /* Thin surfaces lose their EXIT (back-side) hits; solids keep theirs. */
    const double tri[9] = { -1, -1, 0, 1, -1, 0, 0, 1, 0 }; /* normal +z */
    isect_shape t = { ISECT_TRIANGLE, 0, 0, 0, tri, NULL, NULL };
    isect_ray down = ray_make(0, 0, 1, 0, 0, -1), up = ray_make(0, 0, -1, 0, 0, 1);
    isect_opts cull = ISECT_OPTS_INIT;
    cull.flags = ISECT_CULL_BACK;
    isect_hit h[4];
    CHECK_EQ_INT(isect_intersect(&t, &down, &cull, h, 4), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_ENTER);
    CHECK_EQ_INT(isect_intersect(&t, &up, NULL, h, 4), 1);
    CHECK_EQ_INT(h[0].kind, ISECT_EXIT);
    CHECK_EQ_INT(isect_intersect(&t, &up, &cull, h, 4), 0);
    isect_shape s = sphere_shape(unit_sphere);
    isect_ray r = ray_make(0, 0, -5, 0, 0, 1);
    CHECK_EQ_INT(isect_intersect(&s, &r, &cull, h, 4), 2);
}

int main(void)
{
    test_layout();
    test_version_and_status();
    test_dispatch_rejects();
    test_cap_and_order();
    test_batch();
    test_contains();
    test_xform();
    test_cull_back();
    return check_summary();
}
