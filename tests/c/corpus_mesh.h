/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_mesh.h — a corpus "mesh" shape (tests/cases/README.md, "Meshes") as
 * the arrays isect_mesh_create takes, and the expected isect_mesh_report of
 * op "mesh_check".
 *
 * Parsing only collects the arrays; the mesh itself is built when the case
 * runs (mesh_setup in corpus_checks.h), because its creation status is part
 * of the case's result.
 */
#ifndef ISECT_CORPUS_MESH_H
#define ISECT_CORPUS_MESH_H

#include "corpus_json.h"
#include "isect.h"

#include <stdint.h>

/* The arguments of isect_mesh_create, all owned. */
typedef struct corpus_mesh_input {
    double  *verts;   /* [nv][3]; never NULL once parsed, even for nv = 0 */
    int64_t  nv;
    int32_t *idx;     /* the faces concatenated; never NULL once parsed */
    int64_t *offsets; /* [nf + 1], or NULL for the triangle layout */
    int64_t  nf;
} corpus_mesh_input;

/* Read shape.vertices and shape.faces. Every face of exactly 3 indices:
 * the triangle layout (offsets NULL); otherwise the CSR layout. An index
 * that is an integer in int32 range is passed as it is, however wrong for
 * the mesh (negative, >= nv); any other number has no int32 form and is
 * passed as -1, which no mesh accepts, so the library still gets to report
 * E_ARG. Returns 1, or 0 with *err set; corpus_mesh_input_free() is safe
 * either way (the struct must start zeroed). */
int corpus_mesh_parse(const cJSON *shape, corpus_mesh_input *in, cj_error *err);

void corpus_mesh_input_free(corpus_mesh_input *in);

/* The required object expect.report: every field of isect_mesh_report by
 * name (tests/cases/README.md, "Expectations"); reserved is left zero. */
int corpus_mesh_report_parse(const cJSON *expect, isect_mesh_report *report, cj_error *err);

#endif /* ISECT_CORPUS_MESH_H */
