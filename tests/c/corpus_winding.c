/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_winding.c — op "winding_number": isect_winding_number_batch on the
 * case's points (tests/cases/README.md, "Expectations").
 *
 * The library chooses its method by the batch as well as by the mesh: on a
 * mesh that is not closed and oriented, a batch of 8 points or more sums
 * whole clusters of faces through their boundaries and a smaller one sums
 * face by face (isect.h). Both must meet the case's tolerance, so every case
 * runs three batches: all its points at once, each point alone, and all its
 * points with a NaN point inserted in the middle (which must get NaN while
 * the others keep their values).
 */
#include "corpus_checks.h"
#include "corpus_hits.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int point_finite(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* One batch call on points[n][3] into w[n] (one guard element after them).
 * want[i] is point i's expected w, or NaN where the point is not finite
 * (the library writes NaN there and goes on). */
static void check_batch(case_report *r, const char *what, const isect_shape *shape,
                        const double *points, int n, double accuracy, const double *want,
                        double tol)
{
    char label[160];
    double *w = malloc(((size_t)n + 1) * sizeof *w);
    int status, i;

    if (w == NULL) {
        report_fail(r, "%s: out of memory in the runner", what);
        return;
    }
    guard_fill(w, ((size_t)n + 1) * sizeof *w);
    status = isect_winding_number_batch(shape, points, n, accuracy, w);
    snprintf(label, sizeof label, "%s: status", what);
    if (report_status(r, label, status, ISECT_OK)) {
        for (i = 0; i < n; i++) {
            snprintf(label, sizeof label, "%s: w[%d]", what, i);
            if (isnan(want[i])) {
                if (!isnan(w[i]))
                    report_fail(r, "%s (non-finite point: expected NaN, got %.17g)", label, w[i]);
            } else {
                report_near(r, label, w[i], want[i], tol);
            }
        }
        if (!guard_intact(&w[n], sizeof *w))
            report_fail(r, "%s: element past n (expected untouched, got written)", what);
    }
    free(w);
}

/* An expected error that the points do not cause: the call fails with it
 * and writes nothing. */
static void winding_batch_error(case_report *r, const isect_shape *shape, const corpus_case *c)
{
    double *w = malloc(((size_t)c->points_n + 1) * sizeof *w);
    int status;

    if (w == NULL) {
        report_fail(r, "isect_winding_number_batch: out of memory in the runner");
        return;
    }
    guard_fill(w, ((size_t)c->points_n + 1) * sizeof *w);
    status = isect_winding_number_batch(shape, c->points, c->points_n, c->accuracy, w);
    report_status(r, "isect_winding_number_batch", status, c->status);
    if (status < 0 && !guard_intact(w, ((size_t)c->points_n + 1) * sizeof *w))
        report_fail(r, "isect_winding_number_batch: output after an error (expected untouched, "
                       "got written)");
    free(w);
}

/* Status ok: all the points, each alone, and all with a NaN one at n/2. */
static void check_values(case_report *r, const isect_shape *shape, const corpus_case *c)
{
    int n = c->points_n, i, k;
    double *with_nan = malloc(((size_t)n + 1) * 3 * sizeof *with_nan);
    double *want_nan = malloc(((size_t)n + 1) * sizeof *want_nan);
    char what[96];

    snprintf(what, sizeof what, "isect_winding_number_batch (all %d points)", n);
    check_batch(r, what, shape, c->points, n, c->accuracy, c->windings, c->tol.winding);
    for (i = 0; i < n; i++) {
        snprintf(what, sizeof what, "isect_winding_number_batch (point %d alone)", i);
        check_batch(r, what, shape, c->points + 3 * i, 1, c->accuracy, &c->windings[i],
                    c->tol.winding);
    }
    if (with_nan == NULL || want_nan == NULL) {
        report_fail(r, "out of memory in the runner");
    } else {
        for (i = 0, k = 0; i <= n; i++) {
            if (i == n / 2) {
                with_nan[3 * i] = NAN;
                with_nan[3 * i + 1] = with_nan[3 * i + 2] = 0.0;
                want_nan[i] = NAN;
                continue;
            }
            memcpy(&with_nan[3 * i], c->points + 3 * k, 3 * sizeof *with_nan);
            want_nan[i] = c->windings[k++];
        }
        snprintf(what, sizeof what, "isect_winding_number_batch (a NaN point at %d)", n / 2);
        check_batch(r, what, shape, with_nan, n + 1, c->accuracy, want_nan, c->tol.winding);
    }
    free(with_nan);
    free(want_nan);
}

/* E_NONFINITE caused by the points: the call succeeds, NaN at those points
 * and a finite w elsewhere (the finite points' values are not part of an
 * error case). */
static void check_nonfinite_points(case_report *r, const isect_shape *shape, const corpus_case *c)
{
    int n = c->points_n, status, i;
    double *w = malloc(((size_t)n + 1) * sizeof *w);

    if (w == NULL) {
        report_fail(r, "out of memory in the runner");
        return;
    }
    status = isect_winding_number_batch(shape, c->points, n, c->accuracy, w);
    if (report_status(r, "isect_winding_number_batch (non-finite points: ok, NaN there)", status,
                      ISECT_OK)) {
        for (i = 0; i < n; i++) {
            int finite = point_finite(c->points + 3 * i);
            if (finite ? !isfinite(w[i]) : !isnan(w[i]))
                report_fail(r, "isect_winding_number_batch: w[%d] (expected %s, got %.17g)", i,
                            finite ? "a finite number" : "NaN", w[i]);
        }
    }
    free(w);
}

void check_winding_number_case(const corpus_case *c, case_report *r)
{
    isect_xform xform;
    isect_shape shape = c->shape.desc;
    int any_bad = 0, i;

    if (!transform_setup(c, r, &xform, &shape.xform))
        return;
    for (i = 0; i < c->points_n; i++)
        any_bad |= !point_finite(c->points + 3 * i);
    /* A non-finite point is no error of the call (isect.h): it gets NaN
     * and the batch goes on. Other errors fail the whole call. */
    if (c->status == ISECT_OK)
        check_values(r, &shape, c);
    else if (c->status == ISECT_E_NONFINITE && any_bad)
        check_nonfinite_points(r, &shape, c);
    else
        winding_batch_error(r, &shape, c);
}
