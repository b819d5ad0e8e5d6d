/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_intersect.c — op "intersect": the type's scalar function and
 * isect_intersect, each with a large buffer, counting only (hits NULL,
 * cap 0) and cap 1; then the batch paths (corpus_batch.c).
 *
 * A mesh has no scalar function (isect_ray_*); its hits exist only through
 * isect_intersect. So for a mesh the object-space path below calls
 * isect_intersect on the untransformed descriptor instead, and an
 * untransformed mesh case has no second path at all: it would repeat the
 * isect_intersect call exactly. Every other check runs for meshes as for
 * any shape.
 */
#include "corpus_checks.h"
#include "corpus_hits.h"
#include "corpus_shape.h"

#include <stdio.h>
#include <string.h>

int transform_setup(const corpus_case *c, case_report *r, isect_xform *x,
                    const isect_xform **bound)
{
    int status;
    *bound = NULL;
    if (!c->has_transform)
        return 1;
    status = isect_xform_init(x, c->transform);
    if (status != ISECT_OK) {
        report_status(r, "isect_xform_init", status, c->status);
        return 0;
    }
    *bound = x;
    return 1;
}

/* One way of computing a case's hits: same contract as isect_intersect. */
typedef int (*hits_path)(const intersect_setup *s, isect_hit *hits, int cap);

static int via_shape(const intersect_setup *s, isect_hit *hits, int cap)
{
    return isect_intersect(&s->shape, &s->c->ray, s->opts, hits, cap);
}

/* The hits of the untransformed shape: its scalar function, or for a mesh
 * isect_intersect without the xform. */
static int object_space_call(const intersect_setup *s, const isect_ray *ray, isect_hit *hits,
                             int cap)
{
    isect_shape plain = s->shape;
    if (s->c->shape.scalar)
        return corpus_shape_scalar(&s->shape, ray, s->opts, hits, cap);
    plain.xform = NULL;
    return isect_intersect(&plain, ray, s->opts, hits, cap);
}

/* Whether a case has the object-space path (see the top of the file). Raw
 * integer types have no scalar function either. */
static int has_object_space_path(const intersect_setup *s)
{
    const corpus_shape *shape = &s->c->shape;
    return shape->scalar || (shape->named && shape->is_mesh && s->xform != NULL);
}

/* The object-space call; for a transformed case composed by hand the way
 * the header describes it: ray to object space, the call, hits to world. */
static int via_object_space(const intersect_setup *s, isect_hit *hits, int cap)
{
    isect_ray ray = s->c->ray;
    int count, status;
    if (s->xform != NULL) {
        status = isect_xform_ray(s->xform, &s->c->ray, &ray);
        if (status < 0)
            return status;
    }
    count = object_space_call(s, &ray, hits, cap);
    if (count > 0 && cap > 0 && s->xform != NULL) {
        status = isect_xform_hits(s->xform, hits, count < cap ? count : cap);
        if (status < 0)
            return status;
    }
    return count;
}

static void object_space_path_name(char *out, size_t size, const intersect_setup *s)
{
    const char *scalar = s->c->shape.scalar ? corpus_shape_scalar_name(s->shape.type)
                                            : "isect_intersect(xform NULL)";
    if (s->xform != NULL)
        snprintf(out, size, "isect_xform_ray+%s+isect_xform_hits", scalar);
    else
        snprintf(out, size, "%s", scalar);
}

/* A path on a case expected to succeed. Returns the hit count (its hits in
 * out), or -1 when the call failed or overflowed the buffer. */
static int check_path_ok(case_report *r, const char *name, hits_path path,
                         const intersect_setup *s, isect_hit out[CORPUS_HIT_CAP])
{
    isect_hit buf[CORPUS_HIT_CAP], pair[2];
    char what[192];
    int count, written, again;

    guard_fill(buf, sizeof buf);
    count = path(s, buf, CORPUS_HIT_CAP);
    if (count < 0) {
        report_status(r, name, count, ISECT_OK);
        return -1;
    }
    report_expected_hits(r, name, s->c, buf, count, CORPUS_HIT_CAP);
    written = count < CORPUS_HIT_CAP ? count : CORPUS_HIT_CAP;
    snprintf(what, sizeof what, "%s: records past its %d hits", name, written);
    report_guard(r, what, buf + written, (size_t)(CORPUS_HIT_CAP - written) * sizeof *buf);
    memcpy(out, buf, sizeof buf);
    if (count > CORPUS_HIT_CAP) {
        report_fail(r, "%s: %d hits, more than the runner's buffer of %d", name, count,
                    CORPUS_HIT_CAP);
        return -1;
    }

    snprintf(what, sizeof what, "%s with hits NULL, cap 0: return", name);
    report_int(r, what, path(s, NULL, 0), count);

    guard_fill(pair, sizeof pair);
    again = path(s, pair, 1);
    snprintf(what, sizeof what, "%s with cap 1: return", name);
    report_int(r, what, again, count);
    if (count >= 1) {
        snprintf(what, sizeof what, "%s with cap 1: hit 0 vs the large-buffer call", name);
        report_same_hit(r, what, &pair[0], &buf[0]);
    } else {
        snprintf(what, sizeof what, "%s with cap 1 and no hits: record 0", name);
        report_guard(r, what, &pair[0], sizeof pair[0]);
    }
    snprintf(what, sizeof what, "%s with cap 1: record 1 (past cap)", name);
    report_guard(r, what, &pair[1], sizeof pair[1]);
    return count;
}

/* A path on a case expected to fail: the status, and nothing written. */
static void check_path_error(case_report *r, const char *name, hits_path path,
                             const intersect_setup *s)
{
    isect_hit buf[CORPUS_HIT_CAP];
    char what[192];
    int status;

    guard_fill(buf, sizeof buf);
    status = path(s, buf, CORPUS_HIT_CAP);
    report_status(r, name, status, s->c->status);
    if (status < 0) {
        snprintf(what, sizeof what, "%s: hit buffer after an error", name);
        report_guard(r, what, buf, sizeof buf);
    }
    snprintf(what, sizeof what, "%s with hits NULL, cap 0", name);
    report_status(r, what, path(s, NULL, 0), s->c->status);
}

/* Untransformed, isect_intersect is documented to give the scalar
 * function's hits, so the two must agree in every bit. */
static void check_paths_agree(case_report *r, const char *scalar_name,
                              const isect_hit *shape_hits, const isect_hit *scalar_hits,
                              int count)
{
    char what[192];
    int i;
    for (i = 0; i < count; i++) {
        snprintf(what, sizeof what, "isect_intersect hit %d vs %s hit %d", i, scalar_name, i);
        if (!report_same_hit(r, what, &shape_hits[i], &scalar_hits[i]))
            return;
    }
}

void check_intersect_case(const corpus_case *c, case_report *r)
{
    isect_xform xform;
    intersect_setup s;
    isect_hit reference[CORPUS_HIT_CAP], object_hits[CORPUS_HIT_CAP];
    char object_name[128];
    int ref_count, object_count;

    s.c = c;
    s.shape = c->shape.desc;
    s.opts = c->has_opts ? &c->opts : NULL;
    if (!transform_setup(c, r, &xform, &s.xform))
        return;
    s.shape.xform = s.xform;
    object_space_path_name(object_name, sizeof object_name, &s);

    if (c->status != ISECT_OK) {
        check_path_error(r, "isect_intersect", via_shape, &s);
        if (has_object_space_path(&s))
            check_path_error(r, object_name, via_object_space, &s);
        check_batch_error(r, &s);
        return;
    }

    ref_count = check_path_ok(r, "isect_intersect", via_shape, &s, reference);
    if (has_object_space_path(&s)) {
        object_count = check_path_ok(r, object_name, via_object_space, &s, object_hits);
        if (s.xform == NULL && ref_count >= 0 && object_count == ref_count)
            check_paths_agree(r, object_name, reference, object_hits, ref_count);
    }
    /* The batch results are defined as isect_intersect's; without them
     * there is nothing to compare against (the failure is reported). */
    if (ref_count < 0)
        return;
    check_batch_ok(r, &s, reference, ref_count);
    check_all_batch_ok(r, &s, reference, ref_count);
}
