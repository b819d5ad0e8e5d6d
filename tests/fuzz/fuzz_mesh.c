/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_mesh.c — libFuzzer harness: isect_mesh_create, isect_mesh_check and
 * the mesh queries on fuzzed arrays.
 *
 * Input (fuzz_input.h): vertex count and coordinates (NaN / inf / huge /
 * subnormal included), a layout byte (triangles, or CSR offsets, possibly
 * malformed), face count and indices (mostly in range, sometimes not), then
 * options and rays for the queries.
 *
 * Asserted: create returns a documented status and *out is NULL on error;
 * the report of isect_mesh_check is consistent with itself and with the
 * input (faces = nf, vertices <= nv, euler = V - E + F, closed iff no
 * boundary and no non-manifold edge, oriented iff no misoriented edge,
 * genus -1 unless closed and oriented, area >= 0, reserved 0) and nothing is
 * written on error; the mesh queries pass every invariant of fuzz_checks.h;
 * containment is E_ARG exactly for a mesh that is not closed.
 */
#include "fuzz_checks.h"
#include "fuzz_input.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_VERTS 24
#define MAX_FACES 24
#define MAX_FACE_LEN 6
#define MAX_RAYS 4
#define HIT_CAP 64

/* A non-NULL pointer that is no mesh, to see that create overwrites it. */
static int unset_marker;
#define OUT_UNSET ((isect_mesh *)(void *)&unset_marker)

/* The measures are finite wherever the true values are (issue 13 item 3,
 * fixed in mesh_check.c: scaled sums), so they are checked at every scale. */
#define MEASURE_BOUND INFINITY

static void check_report(const isect_mesh *mesh, int64_t nv, int64_t nf, double max_coord,
                         isect_mesh_report *rep)
{
    isect_mesh_report copy;
    int st;

    fuzz_canary_fill(rep, sizeof *rep);
    st = isect_mesh_check(mesh, rep);
    fuzz_require_status(st, FUZZ_ALLOW_NOMEM, "isect_mesh_check");
    if (st < 0) {
        FUZZ_REQUIRE(fuzz_canary_intact(rep, sizeof *rep), "isect_mesh_check wrote and failed");
        return;
    }
    FUZZ_REQUIRE(st == ISECT_OK, "isect_mesh_check returned %d", st);
    FUZZ_REQUIRE(rep->faces == nf, "report faces %lld, nf %lld", (long long)rep->faces,
                 (long long)nf);
    FUZZ_REQUIRE(rep->vertices >= 0 && rep->vertices <= nv, "report vertices %lld, nv %lld",
                 (long long)rep->vertices, (long long)nv);
    FUZZ_REQUIRE(rep->edges >= 0 && rep->boundary_edges >= 0 && rep->nonmanifold_edges >= 0 &&
                     rep->misoriented_edges >= 0 &&
                     rep->boundary_edges + rep->nonmanifold_edges <= rep->edges &&
                     rep->misoriented_edges <= rep->edges,
                 "report edge counts inconsistent");
    FUZZ_REQUIRE(rep->degenerate_faces >= 0 && rep->degenerate_faces <= rep->faces,
                 "report degenerate_faces %lld", (long long)rep->degenerate_faces);
    FUZZ_REQUIRE(rep->components >= 0 && rep->components <= rep->faces,
                 "report components %lld", (long long)rep->components);
    FUZZ_REQUIRE(rep->euler_characteristic == rep->vertices - rep->edges + rep->faces,
                 "report euler %lld != V - E + F", (long long)rep->euler_characteristic);
    FUZZ_REQUIRE(rep->closed == (rep->boundary_edges == 0 && rep->nonmanifold_edges == 0),
                 "report closed %d", (int)rep->closed);
    FUZZ_REQUIRE(rep->oriented == (rep->misoriented_edges == 0), "report oriented %d",
                 (int)rep->oriented);
    if (!(rep->closed && rep->oriented))
        FUZZ_REQUIRE(rep->genus == -1, "report genus %lld of an open or unoriented mesh",
                     (long long)rep->genus);
    else
        FUZZ_REQUIRE(rep->genus >= 0, "report genus %lld", (long long)rep->genus);
    /* NaN is not >= 0: a NaN area from finite input is a failure
     * (issue 13, item 3). */
    if (max_coord <= MEASURE_BOUND) {
        FUZZ_REQUIRE(rep->area >= 0.0, "report area %a", rep->area);
        FUZZ_REQUIRE(!isnan(rep->volume), "report volume NaN");
    }
    FUZZ_REQUIRE(rep->reserved[0] == 0 && rep->reserved[1] == 0 && rep->reserved[2] == 0,
                 "report reserved fields not 0");
    /* Immutable: a second check gives the same report. */
    st = isect_mesh_check(mesh, &copy);
    FUZZ_REQUIRE(st == ISECT_OK && memcmp(&copy, rep, sizeof copy) == 0,
                 "a second isect_mesh_check differs");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in;
    double verts[3 * MAX_VERTS];
    int32_t idx[MAX_FACES * MAX_FACE_LEN];
    int64_t offsets[MAX_FACES + 1];
    int64_t nv, nf, nidx = 0, f;
    uint8_t layout;
    isect_mesh *mesh = OUT_UNSET;
    isect_mesh_report rep;
    isect_shape shape;
    isect_opts *opts;
    uint32_t flags;
    isect_ray rays[MAX_RAYS];
    double points[3 * MAX_RAYS];
    int inside[MAX_RAYS];
    int nrays, i, st;

    fuzz_input_init(&in, data, size);
    nv = fuzz_u8(&in) % (MAX_VERTS + 1);
    fuzz_doubles(&in, verts, (size_t)(3 * nv));
    layout = fuzz_u8(&in);
    nf = fuzz_u8(&in) % (MAX_FACES + 1);
    offsets[0] = 0;
    for (f = 0; f < nf; f++) {
        int len = 3;
        int k;
        if (layout & 1) {
            /* CSR: lengths 3..MAX_FACE_LEN; layout bit 1 allows 0..2
             * (malformed offsets). */
            uint8_t b = fuzz_u8(&in);
            len = (layout & 2) ? b % (MAX_FACE_LEN + 1) : 3 + b % (MAX_FACE_LEN - 2);
        }
        for (k = 0; k < len; k++) {
            uint8_t b = fuzz_u8(&in);
            /* Indices in range mostly; 0xFF reads a raw one. */
            idx[nidx++] = b == 0xFF ? fuzz_i32(&in) : (int32_t)(nv > 0 ? b % nv : b);
        }
        offsets[f + 1] = nidx;
    }
    if ((layout & 5) == 5 && nf > 0)
        offsets[0] = fuzz_u8(&in) % 3; /* a bad first offset */

    if (getenv("FUZZ_VERBOSE") != NULL) {
        fprintf(stderr, "mesh nv %lld nf %lld layout %s\n", (long long)nv, (long long)nf,
                (layout & 1) ? "csr" : "triangles");
        for (i = 0; i < nv; i++)
            fprintf(stderr, "v%d %a %a %a\n", i, verts[3 * i], verts[3 * i + 1], verts[3 * i + 2]);
        for (f = 0; f < nf; f++) {
            int64_t k;
            fprintf(stderr, "f%lld:", (long long)f);
            for (k = offsets[f]; k < offsets[f + 1]; k++)
                fprintf(stderr, " %d", (int)idx[k]);
            fputc('\n', stderr);
        }
    }
    st = isect_mesh_create(verts, nv, idx, (layout & 1) ? offsets : NULL, nf, &mesh);
    fuzz_require_status(st, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE | FUZZ_ALLOW_NOMEM,
                        "isect_mesh_create");
    if (st != ISECT_OK) {
        FUZZ_REQUIRE(mesh == NULL, "isect_mesh_create failed (%d) and left *out non-NULL", st);
        return 0;
    }
    FUZZ_REQUIRE(mesh != NULL && mesh != OUT_UNSET, "isect_mesh_create: OK without a mesh");
    FUZZ_REQUIRE(isect_mesh_bytes(mesh) > 0, "isect_mesh_bytes not positive");
    {
        double max_coord = 0.0;
        for (i = 0; i < 3 * nv; i++)
            max_coord = fmax(max_coord, fabs(verts[i]));
        check_report(mesh, nv, nf, max_coord, &rep);
    }

    memset(&shape, 0, sizeof shape);
    shape.type = ISECT_MESH;
    shape.mesh = mesh;
    opts = fuzz_take_opts(&in, &flags);
    nrays = 1 + fuzz_u8(&in) % MAX_RAYS;
    for (i = 0; i < nrays; i++)
        fuzz_take_ray(&in, &rays[i]);
    {
        fuzz_range range;
        fuzz_range_init(&range);
        fuzz_range_add(&range, verts, (size_t)(3 * nv));
        for (i = 0; i < nrays; i++) {
            fuzz_range_add(&range, rays[i].org, 3);
            fuzz_range_add(&range, rays[i].dir, 3);
        }
        fuzz_set_wide_range(fuzz_range_wide(&range));
    }
    for (i = 0; i < nrays; i++) {
        fuzz_check_intersect(&shape, &rays[i], opts, flags, nf, NULL, HIT_CAP);
        memcpy(&points[3 * i], rays[i].org, sizeof rays[i].org);
    }
    fuzz_check_batches(&shape, rays, nrays, opts);
    fuzz_check_contains(&shape, points, nrays, inside);
    for (i = 0; i < nrays; i++)
        if (isfinite(points[3 * i]) && isfinite(points[3 * i + 1]) && isfinite(points[3 * i + 2]))
            FUZZ_REQUIRE((inside[i] == ISECT_E_ARG) == !rep.closed,
                         "contains %d on a mesh with closed = %d", inside[i], (int)rep.closed);
    free(opts);
    isect_mesh_destroy(mesh);
    return 0;
}
