/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_checks.h — running one parsed case through every API path that
 * computes its answer, reporting each disagreement through case_report.
 *
 *   corpus_intersect.c  op "intersect": scalar function and isect_intersect
 *   corpus_batch.c      op "intersect": isect_intersect_batch, _all_batch
 *   corpus_mesh.c       building a case's mesh; op "mesh_check"
 *   corpus_ops.c        the other ops (contains, 2D helpers, normals)
 *   corpus_spawn.c      op "spawn": isect_spawn_ray and the secondary ray
 *   corpus_winding.c    op "winding_number": isect_winding_number_batch
 */
#ifndef ISECT_CORPUS_CHECKS_H
#define ISECT_CORPUS_CHECKS_H

#include "corpus_case.h"
#include "corpus_report.h"
#include "isect.h"

/* Room for every hit any case can have; a count above it is a failure. */
#define CORPUS_HIT_CAP 64

/* What every path of an intersect case shares. */
typedef struct intersect_setup {
    const corpus_case *c;
    isect_shape        shape; /* the case's descriptor with xform set */
    const isect_xform *xform; /* NULL when the case has no transform */
    const isect_opts  *opts;  /* NULL (the defaults) when the case has no opts */
} intersect_setup;

/* Initialise *x from the case's transform and set *bound to it (NULL when
 * there is none). When isect_xform_init fails, its status is the case's
 * result: it is checked against the expected status and 0 is returned (the
 * case is finished); otherwise 1. */
int transform_setup(const corpus_case *c, case_report *r, isect_xform *x,
                    const isect_xform **bound);

void check_intersect_case(const corpus_case *c, case_report *r);

/* Batch paths of a case expected to succeed; reference[0 .. ref_count) are
 * the hits isect_intersect reported, which the batch results must equal
 * bit for bit. */
void check_batch_ok(case_report *r, const intersect_setup *s, const isect_hit *reference,
                    int ref_count);
void check_all_batch_ok(case_report *r, const intersect_setup *s,
                        const isect_hit *reference, int ref_count);

/* Batch paths of a case expected to fail: a bad shape or opts fails the
 * whole call and writes nothing; a bad ray only marks that ray INVALID. */
void check_batch_error(case_report *r, const intersect_setup *s);

/* Build the case's mesh when its shape is one, before any op runs, and put
 * it into c->shape (corpus_case_free destroys it). When isect_mesh_create
 * fails, that status is the case's result whatever the op: it is checked
 * against the expected status and 0 is returned (the case is finished);
 * otherwise 1. Also checks isect_mesh_bytes of the new mesh. */
int mesh_setup(corpus_case *c, case_report *r);

void check_mesh_check_case(const corpus_case *c, case_report *r);
void check_contains_case(const corpus_case *c, case_report *r);
void check_point_in_polygon2_case(const corpus_case *c, case_report *r);
void check_winding_number2_case(const corpus_case *c, case_report *r);
void check_polygon_normal_case(const corpus_case *c, case_report *r);
void check_plane_from_points_case(const corpus_case *c, case_report *r);
void check_spawn_case(const corpus_case *c, case_report *r);
void check_winding_number_case(const corpus_case *c, case_report *r);

#endif /* ISECT_CORPUS_CHECKS_H */
