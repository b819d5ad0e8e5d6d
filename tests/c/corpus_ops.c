/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_ops.c — the ops other than "intersect" and "mesh_check": contains,
 * the 2D polygon helpers, polygon_normal and plane_from_points.
 *
 * Point queries are also run as a batch of POINT_BATCH copies of the point
 * with a NaN point in the middle, which the batch must mark ISECT_INVALID
 * (contains, point_in_polygon2) or INT32_MIN (winding_number2) while it
 * still answers the others.
 */
#include "corpus_checks.h"
#include "corpus_hits.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#define POINT_BATCH 4
#define BAD_POINT 2

static int all_finite(const double *x, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

/* POINT_BATCH copies of the case's point (dim numbers each), one NaN. */
static void point_batch_make(const double *point, int dim, double *points)
{
    int i, k;
    for (i = 0; i < POINT_BATCH; i++)
        for (k = 0; k < dim; k++)
            points[i * dim + k] = point[k];
    points[BAD_POINT * dim] = NAN;
}

/* What one point-batch call returned: `got`, the per-point results as
 * integers, and whether its output buffer was touched. */
typedef struct point_batch_result {
    const char *name;
    int64_t     got;
    long long   value[POINT_BATCH];
    int         past_end_untouched; /* the element after the last point */
    int         all_untouched;      /* every element, for error returns */
} point_batch_result;

/* The per-point answer of a good point is `answer`; a bad point gets
 * `invalid`; the call returns `ok_return`. An expected error caused by the
 * point itself (E_NONFINITE for a non-finite point) marks every point
 * invalid instead; any other error fails the call and writes nothing. */
static void check_point_batch(case_report *r, const corpus_case *c, int dim,
                              const point_batch_result *b, long long answer,
                              long long invalid, int64_t ok_return)
{
    char what[160];
    int i, point_caused;

    if (c->status != ISECT_OK) {
        point_caused = !all_finite(c->point, dim) && c->status == ISECT_E_NONFINITE;
        if (!point_caused) {
            report_status(r, b->name, (int)b->got, c->status);
            if (b->got < 0 && !b->all_untouched)
                report_fail(r, "%s: output after an error (expected untouched, got written)",
                            b->name);
            return;
        }
        answer = invalid;
        ok_return = 0;
    }
    snprintf(what, sizeof what, "%s: return", b->name);
    if (!report_int(r, what, b->got, ok_return) || b->got < 0)
        return;
    for (i = 0; i < POINT_BATCH; i++) {
        snprintf(what, sizeof what, "%s: point %d%s", b->name, i,
                 i == BAD_POINT ? " (NaN)" : "");
        report_int(r, what, b->value[i], i == BAD_POINT ? invalid : answer);
    }
    if (!b->past_end_untouched)
        report_fail(r, "%s: element past n (expected untouched, got written)", b->name);
}

/* A scalar answer: the expected value, or the expected error status. */
static void check_answer(case_report *r, const char *name, const corpus_case *c, int got,
                         long long answer)
{
    if (c->status == ISECT_OK && got >= 0)
        report_int(r, name, got, answer);
    else
        report_status(r, name, got, c->status);
}

/* A mesh shape arrives built (mesh_setup), so its descriptor is complete
 * here; an open mesh is E_ARG like a thin surface, from both calls. */
void check_contains_case(const corpus_case *c, case_report *r)
{
    isect_xform xform;
    isect_shape shape = c->shape.desc;
    double points[POINT_BATCH * 3];
    uint8_t inside[POINT_BATCH + 1];
    point_batch_result b;
    int i;

    if (!transform_setup(c, r, &xform, &shape.xform))
        return;
    check_answer(r, "isect_contains", c, isect_contains(&shape, c->point), c->inside);

    point_batch_make(c->point, 3, points);
    guard_fill(inside, sizeof inside);
    b.name = "isect_contains_batch";
    b.got = isect_contains_batch(&shape, points, POINT_BATCH, inside);
    for (i = 0; i < POINT_BATCH; i++)
        b.value[i] = inside[i];
    b.past_end_untouched = guard_intact(&inside[POINT_BATCH], 1);
    b.all_untouched = guard_intact(inside, sizeof inside);
    check_point_batch(r, c, 3, &b, c->inside, ISECT_INVALID,
                      (int64_t)(POINT_BATCH - 1) * c->inside);
}

void check_point_in_polygon2_case(const corpus_case *c, case_report *r)
{
    double points[POINT_BATCH * 2];
    uint8_t inside[POINT_BATCH + 1];
    point_batch_result b;
    int i;

    check_answer(r, "isect_point_in_polygon2", c,
                 isect_point_in_polygon2(c->polygon2, c->polygon2_n, c->point, c->rule),
                 c->inside);

    point_batch_make(c->point, 2, points);
    guard_fill(inside, sizeof inside);
    b.name = "isect_point_in_polygon2_batch";
    b.got = isect_point_in_polygon2_batch(c->polygon2, c->polygon2_n, points, POINT_BATCH,
                                          c->rule, inside);
    for (i = 0; i < POINT_BATCH; i++)
        b.value[i] = inside[i];
    b.past_end_untouched = guard_intact(&inside[POINT_BATCH], 1);
    b.all_untouched = guard_intact(inside, sizeof inside);
    check_point_batch(r, c, 2, &b, c->inside, ISECT_INVALID,
                      (int64_t)(POINT_BATCH - 1) * c->inside);
}

void check_winding_number2_case(const corpus_case *c, case_report *r)
{
    double points[POINT_BATCH * 2];
    int32_t winding = 0, windings[POINT_BATCH + 1];
    point_batch_result b;
    int status, i;

    status = isect_winding_number2(c->polygon2, c->polygon2_n, c->point, &winding);
    if (report_status(r, "isect_winding_number2", status, c->status) && status == ISECT_OK)
        report_int(r, "isect_winding_number2: winding", winding, c->winding);

    point_batch_make(c->point, 2, points);
    guard_fill(windings, sizeof windings);
    b.name = "isect_winding_number2_batch";
    b.got = isect_winding_number2_batch(c->polygon2, c->polygon2_n, points, POINT_BATCH,
                                        windings);
    for (i = 0; i < POINT_BATCH; i++)
        b.value[i] = windings[i];
    b.past_end_untouched = guard_intact(&windings[POINT_BATCH], sizeof windings[0]);
    b.all_untouched = guard_intact(windings, sizeof windings);
    check_point_batch(r, c, 2, &b, c->winding, INT32_MIN,
                      c->winding != 0 ? POINT_BATCH - 1 : 0);
}

void check_polygon_normal_case(const corpus_case *c, case_report *r)
{
    double normal[3];
    int status = isect_polygon_normal(c->vertices, c->vertices_n, normal);
    if (report_status(r, "isect_polygon_normal", status, c->status) && status == ISECT_OK)
        report_near_n(r, "isect_polygon_normal: normal", normal, c->normal, 3, c->tol.normal);
}

/* The plane (a, b, c, d) is judged with the "normal" tolerance throughout:
 * the schema has no key of its own for it, and d is relative to max(1, |d|)
 * like every other value. */
void check_plane_from_points_case(const corpus_case *c, case_report *r)
{
    double plane[4];
    int status = isect_plane_from_points(c->vertices, c->vertices_n, plane);
    if (report_status(r, "isect_plane_from_points", status, c->status) && status == ISECT_OK)
        report_near_n(r, "isect_plane_from_points: plane", plane, c->plane, 4, c->tol.normal);
}
