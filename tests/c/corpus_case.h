/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_case.h — one corpus case parsed into the library's inputs and the
 * expected results (schema isect-cases/1, tests/cases/README.md).
 *
 * Parsing is complete before anything runs, so a malformed case is reported
 * by its field and never half-executed.
 */
#ifndef ISECT_CORPUS_CASE_H
#define ISECT_CORPUS_CASE_H

#include "corpus_json.h"
#include "corpus_shape.h"
#include "isect.h"

typedef enum corpus_op {
    CORPUS_INTERSECT,
    CORPUS_CONTAINS,
    CORPUS_MESH_CHECK,
    CORPUS_POINT_IN_POLYGON2,
    CORPUS_WINDING_NUMBER2,
    CORPUS_POLYGON_NORMAL,
    CORPUS_PLANE_FROM_POINTS,
    CORPUS_SPAWN,
    CORPUS_WINDING_NUMBER
} corpus_op;

/* Relative tolerances of "tol"; each defaults to 1e-12. */
typedef struct corpus_tolerance {
    double t, point, normal, uv;
    double volume, area; /* mesh_check */
    double winding;      /* winding_number (0: exact) */
} corpus_tolerance;

typedef struct corpus_expected_hit {
    double  t;
    double  point[3];
    double  normal[3];
    double  uv[2];
    int     has_uv; /* uv is optional in the corpus; unchecked when absent */
    int32_t prim;
    int32_t kind;
} corpus_expected_hit;

typedef struct corpus_case {
    const char *name; /* points into the JSON document */
    corpus_op   op;

    /* intersect / contains / mesh_check (only the shape) / spawn / winding_number */
    corpus_shape shape;
    int          has_transform;
    double       transform[16];
    isect_ray    ray;          /* intersect; spawn: the primary ray */
    double       spawn_dir[3]; /* spawn: the secondary direction */
    int          has_opts; /* absent "opts": the checks pass NULL (the defaults) */
    isect_opts   opts;

    double  point[3];      /* contains: 3 numbers; 2D ops: the first 2 */
    double *polygon2;      /* point_in_polygon2 / winding_number2: [polygon2_n][2] */
    int     polygon2_n;
    int32_t rule;          /* point_in_polygon2 */
    double *vertices;      /* polygon_normal / plane_from_points: [vertices_n][3] */
    int     vertices_n;
    double *points;        /* winding_number: [points_n][3] */
    int     points_n;
    double  accuracy;      /* winding_number; 0 when absent */

    /* expect */
    int                  status; /* ISECT_OK or ISECT_E_* */
    int                  count;  /* intersect; spawn: the secondary ray's hits */
    int                  hits_listed; /* "hits" present (its length is count) */
    corpus_expected_hit *hits;
    int                  inside;  /* contains / point_in_polygon2 */
    int32_t              winding; /* winding_number2 */
    double              *windings; /* winding_number: [points_n], w at each point */
    double               normal[3];
    double               plane[4];
    isect_mesh_report    report;  /* mesh_check; reserved left 0 */
    corpus_tolerance     tol;
} corpus_case;

/* Fill *c from the case object (everything but "id", which the runner reads
 * first to name the case). Returns 1, or 0 with the offending field in *err;
 * corpus_case_free() is safe either way. */
int corpus_case_parse(const cJSON *item, corpus_case *c, cj_error *err);

void corpus_case_free(corpus_case *c);

/* "ok", "E_ARG", ... ; "status N" for an unknown value (buf used then). */
const char *corpus_status_name(int status, char *buf, size_t size);

/* "miss", "enter", ... ; "kind N" for an unknown value (buf used then). */
const char *corpus_kind_name(int32_t kind, char *buf, size_t size);

#endif /* ISECT_CORPUS_CASE_H */
