/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_shape.h — a corpus "shape" object as an isect_shape descriptor, and
 * the call of the type's own scalar function (isect_ray_sphere etc.) on it.
 * A mesh shape carries the arrays of its mesh (corpus_mesh.h); the mesh is
 * built when the case runs (mesh_setup) and owned here from then on.
 */
#ifndef ISECT_CORPUS_SHAPE_H
#define ISECT_CORPUS_SHAPE_H

#include "corpus_json.h"
#include "corpus_mesh.h"
#include "isect.h"

typedef struct corpus_shape {
    isect_shape desc; /* xform is left NULL; the checks set it */
    double *data;     /* owned; desc.data points here (or is NULL) */
    int named;        /* 1 for a "type" given by name */
    int scalar;       /* 1 when the type has a scalar function: every name but "mesh" */
    int is_mesh;      /* "mesh", or a raw type with mesh keys: mesh_input is set */
    corpus_mesh_input mesh_input;
    isect_mesh *mesh; /* owned once built; desc.mesh points here (or is NULL) */
} corpus_shape;

/* Parse the case's "shape" object. A named type reads its keys as in
 * tests/cases/README.md. An integer type is passed through raw (bad-input
 * cases) and takes the key layout of the first named type whose keys are all
 * present, so {"type": 99, "center": .., "radius": ..} carries sphere data;
 * with no matching keys data is NULL. The data buffer is zero-padded so a
 * raw type that reads more numbers than its keys gave stays in bounds.
 * "mesh", and a raw type with the key "faces", read the mesh's vertices and
 * faces instead (data NULL, n 0; desc.mesh is set by mesh_setup); a "mesh"
 * takes its containment rule "rule" as flags, a raw type flags 0.
 * Returns 1, or 0 with *err set. */
int corpus_shape_parse(const cJSON *shape, corpus_shape *out, cj_error *err);

/* Frees the data and the mesh arrays, and destroys the mesh if one was built. */
void corpus_shape_free(corpus_shape *s);

/* Run the scalar function of a type that has one (corpus_shape.scalar) with
 * the descriptor's numbers, in the argument order the header gives; s->xform
 * is ignored. */
int corpus_shape_scalar(const isect_shape *s, const isect_ray *ray, const isect_opts *opts,
                        isect_hit *hits, int cap);

/* "isect_ray_sphere" etc. for a type, for messages. */
const char *corpus_shape_scalar_name(int32_t type);

/* A fill rule at obj[key]: "evenodd", "nonzero", "winding" (ISECT_WINDING,
 * a mesh's rule), or an integer passed through unchecked (bad-input cases);
 * ISECT_EVEN_ODD when absent. */
int corpus_rule_parse(const cJSON *obj, const char *parent, const char *key, int32_t *rule,
                      cj_error *err);

#endif /* ISECT_CORPUS_SHAPE_H */
