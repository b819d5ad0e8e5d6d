/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_spawn.c — libFuzzer harness: isect_spawn_ray on fuzzed shapes, hits
 * and directions.
 *
 * Input (fuzz_input.h): a shape descriptor, a primary ray, a mode byte and
 * a direction. The hit is the primary ray's first hit as the library gives
 * it (the documented use), or — when the mode asks — a fuzzed record (any
 * kind, prim, point and normal), which must be rejected or handled with a
 * documented status.
 *
 * Asserted: documented statuses only; on error *out is left as it was; on
 * success out->dir is dir bit for bit, tmin = 0, tmax = +inf, org finite;
 * for a flat surface (plane, triangle, polygon; transformed too) the spawned
 * ray never meets the surface again, at any t >= 0 — its origin is strictly
 * on the side dir points into and a plane is met at most once; and the
 * spawned ray's own queries pass every invariant of fuzz_checks.h.
 */
#include "fuzz_checks.h"
#include "fuzz_input.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define HIT_CAP 8

static int is_flat(const isect_shape *shape)
{
    return shape->type == ISECT_PLANE || shape->type == ISECT_TRIANGLE ||
           shape->type == ISECT_POLYGON;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in;
    fuzz_shape s;
    isect_ray ray, out, before;
    isect_hit hits[HIT_CAP], hit;
    double dir[3];
    uint8_t mode;
    int count, st, again;

    fuzz_input_init(&in, data, size);
    /* No mesh here: a mesh type's NULL handle is an error path; meshes are
     * spawned from in fuzz_mesh_parity. */
    fuzz_take_shape(&in, &s, NULL);
    fuzz_take_ray(&in, &ray);
    mode = fuzz_u8(&in);
    fuzz_doubles(&in, dir, 3);

    count = isect_intersect(&s.desc, &ray, NULL, hits, HIT_CAP);
    fuzz_set_wide_range(fuzz_shape_wide(&s, &ray, 1));
    if (mode & 1) {
        /* A record the library never made: every field fuzzed. */
        hit.t = fuzz_double(&in);
        fuzz_doubles(&in, hit.point, 3);
        fuzz_doubles(&in, hit.normal, 3);
        fuzz_doubles(&in, hit.uv, 2);
        hit.prim = (int32_t)(int8_t)fuzz_u8(&in);
        hit.kind = (int32_t)(fuzz_u8(&in) % 6);
    } else if (count > 0) {
        /* The mode's upper bits pick one of the hits. */
        hit = hits[(mode >> 1) % (count < HIT_CAP ? count : HIT_CAP)];
    } else {
        fuzz_shape_free(&s);
        return 0;
    }

    fuzz_canary_fill(&out, sizeof out);
    st = isect_spawn_ray(&s.desc, &hit, dir, &out);
    if (getenv("FUZZ_VERBOSE") != NULL) {
        fprintf(stderr, "hit t %a point %a %a %a normal %a %a %a prim %d kind %d\n", hit.t,
                hit.point[0], hit.point[1], hit.point[2], hit.normal[0], hit.normal[1],
                hit.normal[2], (int)hit.prim, (int)hit.kind);
        fprintf(stderr, "dir %a %a %a -> status %d org %a %a %a\n", dir[0], dir[1], dir[2], st,
                out.org[0], out.org[1], out.org[2]);
    }
    fuzz_require_status(st, FUZZ_QUERY_ERRORS, "isect_spawn_ray");
    if (st < 0) {
        FUZZ_REQUIRE(fuzz_canary_intact(&out, sizeof out), "isect_spawn_ray wrote *out and returned %d",
                     st);
        fuzz_shape_free(&s);
        return 0;
    }
    FUZZ_REQUIRE(memcmp(out.dir, dir, sizeof dir) == 0, "out.dir is not dir bit for bit");
    FUZZ_REQUIRE(out.tmin == 0.0 && out.tmax == INFINITY, "out interval [%a, %a]", out.tmin,
                 out.tmax);
    FUZZ_REQUIRE(isfinite(out.org[0]) && isfinite(out.org[1]) && isfinite(out.org[2]),
                 "out.org not finite");
    /* The same call again gives the same ray (no hidden state). */
    before = out;
    again = isect_spawn_ray(&s.desc, &hit, dir, &out);
    FUZZ_REQUIRE(again == st && memcmp(&before, &out, sizeof out) == 0,
                 "a second isect_spawn_ray call differs");

    if (!(mode & 1)) {
        /* Only library-made hits: the spawned ray leaves the surface. */
        count = fuzz_check_intersect(&s.desc, &out, NULL, 0, s.desc.n, hits, HIT_CAP);
        /* Only a transform can make a good world ray bad (its object-space
         * image overflows or underflows). */
        FUZZ_REQUIRE(count >= 0 || (s.desc.xform != NULL && (count == ISECT_E_NONFINITE ||
                                                            count == ISECT_E_DEGENERATE)),
                     "the spawned ray is rejected (%d)", count);
        if (count > 0 && is_flat(&s.desc) && !fuzz_shape_wide(&s, &out, 1))
            FUZZ_REQUIRE(count == 0, "the ray spawned from a flat surface meets it again "
                                     "(%d hits, first t = %a)", count, hits[0].t);
    }
    fuzz_shape_free(&s);
    return 0;
}
