/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_mesh.c — mesh shapes: their arrays from the JSON, building the mesh
 * when a case runs, and op "mesh_check"; see corpus_mesh.h.
 */
#include "corpus_mesh.h"

#include "corpus_checks.h"
#include "corpus_hits.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Report counts are JSON numbers; keep them where doubles hold integers exactly. */
#define MAX_EXACT_COUNT 9007199254740992LL
/* What an index without an int32 form is passed as (see corpus_mesh.h). */
#define NOT_AN_INDEX (-1)

/* ---------------------------------------------------------------- parsing */

static int32_t index_value(double v)
{
    /* The range test comes first so the cast is always defined; NaN fails it. */
    if (!(v >= (double)INT32_MIN && v <= (double)INT32_MAX) || v != (double)(int32_t)v)
        return NOT_AN_INDEX;
    return (int32_t)v;
}

/* The faces' sizes: how many indices in all, and whether every face is a
 * triangle (which picks the layout). Each face must be an array. */
static int faces_measure(const cJSON *faces, int64_t *nf, int64_t *corners, int *triangles,
                         cj_error *err)
{
    const cJSON *face;
    *nf = *corners = 0;
    *triangles = 1;
    cJSON_ArrayForEach(face, faces) {
        if (!cJSON_IsArray(face))
            return cj_fail(err, "field \"shape.faces[%lld]\" must be an array of indices",
                           (long long)*nf);
        *corners += cJSON_GetArraySize(face);
        if (cJSON_GetArraySize(face) != 3)
            *triangles = 0;
        (*nf)++;
    }
    return 1;
}

static int faces_parse(const cJSON *faces, corpus_mesh_input *in, cj_error *err)
{
    const cJSON *face, *index;
    int64_t corners = 0, f = 0, k = 0;
    int triangles = 1;

    if (faces == NULL)
        return cj_fail(err, "field \"shape.faces\" is missing");
    if (!cJSON_IsArray(faces))
        return cj_fail(err, "field \"shape.faces\" must be an array of index arrays");
    if (!faces_measure(faces, &in->nf, &corners, &triangles, err))
        return 0;
    /* One spare element so that no face at all still gives a valid pointer. */
    in->idx = malloc(((size_t)corners + 1) * sizeof *in->idx);
    if (!triangles)
        in->offsets = malloc(((size_t)in->nf + 1) * sizeof *in->offsets);
    if (in->idx == NULL || (!triangles && in->offsets == NULL))
        return cj_fail(err, "field \"shape.faces\": out of memory");
    if (in->offsets != NULL)
        in->offsets[0] = 0;
    cJSON_ArrayForEach(face, faces) {
        int i = 0;
        cJSON_ArrayForEach(index, face) {
            char path[96];
            double v;
            snprintf(path, sizeof path, "shape.faces[%lld][%d]", (long long)f, i);
            if (!cj_number_value(index, path, &v, err))
                return 0;
            in->idx[k++] = index_value(v);
            i++;
        }
        if (in->offsets != NULL)
            in->offsets[f + 1] = k;
        f++;
    }
    return 1;
}

int corpus_mesh_parse(const cJSON *shape, corpus_mesh_input *in, cj_error *err)
{
    int rows = 0;
    if (!cj_rows(shape, "shape", "vertices", 3, &in->verts, &rows, err))
        return 0;
    in->nv = rows;
    return faces_parse(cJSON_GetObjectItemCaseSensitive(shape, "faces"), in, err);
}

void corpus_mesh_input_free(corpus_mesh_input *in)
{
    free(in->verts);
    free(in->idx);
    free(in->offsets);
    in->verts = NULL;
    in->idx = NULL;
    in->offsets = NULL;
}

/* The int64 fields of isect_mesh_report, compared exactly. (closed and
 * oriented, int32, and the two measures are handled by name below.) */
typedef struct count_field {
    const char *name;
    size_t      offset;
} count_field;

static const count_field count_fields[] = {
    { "vertices", offsetof(isect_mesh_report, vertices) },
    { "edges", offsetof(isect_mesh_report, edges) },
    { "faces", offsetof(isect_mesh_report, faces) },
    { "boundary_edges", offsetof(isect_mesh_report, boundary_edges) },
    { "nonmanifold_edges", offsetof(isect_mesh_report, nonmanifold_edges) },
    { "misoriented_edges", offsetof(isect_mesh_report, misoriented_edges) },
    { "degenerate_faces", offsetof(isect_mesh_report, degenerate_faces) },
    { "components", offsetof(isect_mesh_report, components) },
    { "euler_characteristic", offsetof(isect_mesh_report, euler_characteristic) },
    { "genus", offsetof(isect_mesh_report, genus) },
};
#define COUNT_FIELDS ((int)(sizeof count_fields / sizeof count_fields[0]))

/* Through memcpy, so the offset table needs no pointer casts. */
static int64_t count_get(const isect_mesh_report *report, const count_field *field)
{
    int64_t value;
    memcpy(&value, (const char *)report + field->offset, sizeof value);
    return value;
}

static void count_set(isect_mesh_report *report, const count_field *field, int64_t value)
{
    memcpy((char *)report + field->offset, &value, sizeof value);
}

static int flag_parse(const cJSON *obj, const char *key, int32_t *out, cj_error *err)
{
    long long value = 0;
    if (!cj_integer(obj, "expect.report", key, 0, 1, &value, err))
        return 0;
    *out = (int32_t)value;
    return 1;
}

int corpus_mesh_report_parse(const cJSON *expect, isect_mesh_report *report, cj_error *err)
{
    const cJSON *obj = cJSON_GetObjectItemCaseSensitive(expect, "report");
    long long value = 0;
    int i;

    memset(report, 0, sizeof *report);
    if (obj == NULL)
        return cj_fail(err, "field \"expect.report\" is missing");
    if (!cJSON_IsObject(obj))
        return cj_fail(err, "field \"expect.report\" must be an object");
    for (i = 0; i < COUNT_FIELDS; i++) {
        if (!cj_integer(obj, "expect.report", count_fields[i].name, -MAX_EXACT_COUNT,
                        MAX_EXACT_COUNT, &value, err))
            return 0;
        count_set(report, &count_fields[i], (int64_t)value);
    }
    return flag_parse(obj, "closed", &report->closed, err) &&
           flag_parse(obj, "oriented", &report->oriented, err) &&
           cj_number(obj, "expect.report", "volume", &report->volume, err) &&
           cj_number(obj, "expect.report", "area", &report->area, err);
}

/* ---------------------------------------------------------------- running */

/* What *out holds before isect_mesh_create: not NULL and not a mesh, so a
 * call that leaves *out alone is told apart from one that sets it. (A union
 * of the widest types, so the pointer is aligned for whatever a mesh is.) */
static union {
    long double ld;
    int64_t     i;
    void       *p;
} out_unset;
#define OUT_UNSET ((isect_mesh *)(void *)&out_unset)

int mesh_setup(corpus_case *c, case_report *r)
{
    corpus_shape *s = &c->shape;
    const corpus_mesh_input *in = &s->mesh_input;
    isect_mesh *mesh = OUT_UNSET;
    int64_t bytes;
    int status;

    if (!s->is_mesh)
        return 1;
    status = isect_mesh_create(in->verts, in->nv, in->idx, in->offsets, in->nf, &mesh);
    if (status != ISECT_OK) {
        report_status(r, "isect_mesh_create", status, c->status);
        /* Never destroyed: after an error *out is no mesh of ours. */
        if (mesh != NULL)
            report_fail(r, "isect_mesh_create: *out after an error (expected NULL, got %s)",
                        mesh == OUT_UNSET ? "it left unset" : "a pointer");
        return 0;
    }
    if (mesh == NULL || mesh == OUT_UNSET) {
        report_fail(r, "isect_mesh_create: ok, but *out (expected a mesh, got %s)",
                    mesh == NULL ? "NULL" : "it left unset");
        return 0;
    }
    s->mesh = mesh; /* from here on corpus_case_free destroys it */
    s->desc.mesh = mesh;
    bytes = isect_mesh_bytes(mesh);
    if (bytes <= 0)
        report_fail(r, "isect_mesh_bytes (expected > 0, got %lld)", (long long)bytes);
    return 1;
}

void check_mesh_check_case(const corpus_case *c, case_report *r)
{
    isect_mesh_report got;
    const isect_mesh_report *want = &c->report;
    char what[96];
    int status, i;

    guard_fill(&got, sizeof got);
    status = isect_mesh_check(c->shape.mesh, &got);
    if (!report_status(r, "isect_mesh_check", status, c->status) || status != ISECT_OK)
        return;
    for (i = 0; i < COUNT_FIELDS; i++) {
        snprintf(what, sizeof what, "isect_mesh_check: report.%s", count_fields[i].name);
        report_int(r, what, count_get(&got, &count_fields[i]),
                   count_get(want, &count_fields[i]));
    }
    report_int(r, "isect_mesh_check: report.closed", got.closed, want->closed);
    report_int(r, "isect_mesh_check: report.oriented", got.oriented, want->oriented);
    report_near(r, "isect_mesh_check: report.volume", got.volume, want->volume, c->tol.volume);
    report_near(r, "isect_mesh_check: report.area", got.area, want->area, c->tol.area);
}
