/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_shape.c — libFuzzer harness: the shape queries on fuzzed descriptors.
 *
 * Input (fuzz_input.h): a shape descriptor (any type, n, flags, reserved,
 * data with NaN / inf / huge / subnormal values, an optional transform),
 * options (NULL or any size, flags and eps), up to 8 rays and up to 4 extra
 * points. Every ray goes through isect_intersect (status, canary, hits in
 * [tmin, tmax] and sorted, count-only == full count, cap prefix, ANY_HIT),
 * all rays through isect_intersect_batch and isect_intersect_all_batch
 * (records equal to the scalar calls bit for bit), and the ray origins and
 * extra points through isect_contains and isect_contains_batch.
 *
 * ISECT_MESH descriptors refer to one fixed tetrahedron built at start-up:
 * the mesh family itself is fuzzed by fuzz_mesh and fuzz_mesh_parity.
 */
#include "fuzz_checks.h"
#include "fuzz_input.h"

#include <stdlib.h>

#define MAX_RAYS   8
#define MAX_POINTS (MAX_RAYS + 4)
#define HIT_CAP    8

static isect_mesh *tetrahedron;

static void build_tetrahedron(void)
{
    static const double v[12] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    /* Outward by the right-hand rule. */
    static const int32_t f[12] = { 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3 };
    if (isect_mesh_create(v, 4, f, NULL, 4, &tetrahedron) != ISECT_OK)
        abort();
}

/* fuzz_shape_wide over the rays (and transform) with the tetrahedron's
 * coordinates, which a mesh descriptor does not carry in data: subnormal
 * rays at a unit mesh span 2^1074 (found: ties at t = 0 ordered apart by
 * batch and scalar there, the documented range limit of fuzz_checks.h). */
static int mesh_wide(const fuzz_shape *s, const isect_ray *rays, int n)
{
    static const double unit = 1.0;
    fuzz_range r;
    int i;
    if (s->desc.type != ISECT_MESH)
        return 0;
    fuzz_range_init(&r);
    fuzz_range_add(&r, &unit, 1);
    if (s->desc.xform != NULL)
        fuzz_range_add(&r, s->xform.m, 16);
    for (i = 0; i < n; i++) {
        fuzz_range_add(&r, rays[i].org, 3);
        fuzz_range_add(&r, rays[i].dir, 3);
    }
    return fuzz_range_wide(&r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in;
    fuzz_shape s;
    isect_opts *opts;
    uint32_t flags;
    isect_ray rays[MAX_RAYS];
    double points[3 * MAX_POINTS];
    int inside[MAX_POINTS];
    int nrays, nextra, npoints, i;
    int64_t nprim;

    if (tetrahedron == NULL)
        build_tetrahedron();
    fuzz_input_init(&in, data, size);
    fuzz_take_shape(&in, &s, tetrahedron);
    if (s.xform_status != 1)
        fuzz_require_status(s.xform_status,
                            FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE | FUZZ_ALLOW_DEGENERATE,
                            "isect_xform_init");
    opts = fuzz_take_opts(&in, &flags);
    nrays = 1 + fuzz_u8(&in) % MAX_RAYS;
    for (i = 0; i < nrays; i++)
        fuzz_take_ray(&in, &rays[i]);
    nextra = fuzz_u8(&in) % 5;

    nprim = s.desc.type == ISECT_MESH ? 4 : s.desc.n;
    fuzz_set_wide_range(fuzz_shape_wide(&s, rays, nrays) || mesh_wide(&s, rays, nrays));
    for (i = 0; i < nrays; i++)
        fuzz_check_intersect(&s.desc, &rays[i], opts, flags, nprim, NULL, HIT_CAP);
    fuzz_check_batches(&s.desc, rays, nrays, opts);

    /* Containment at the ray origins (often on or near the surface when the
     * fuzzer aims a ray at it) and at the extra points. */
    npoints = 0;
    for (i = 0; i < nrays; i++, npoints++) {
        points[3 * npoints + 0] = rays[i].org[0];
        points[3 * npoints + 1] = rays[i].org[1];
        points[3 * npoints + 2] = rays[i].org[2];
    }
    for (i = 0; i < nextra; i++, npoints++)
        fuzz_doubles(&in, &points[3 * npoints], 3);
    fuzz_check_contains(&s.desc, points, npoints, inside);

    free(opts);
    fuzz_shape_free(&s);
    return 0;
}
