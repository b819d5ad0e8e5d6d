/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_hits.c — checks on hit buffers; see corpus_hits.h.
 */
#include "corpus_hits.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void guard_fill(void *buf, size_t bytes)
{
    memset(buf, CORPUS_GUARD_BYTE, bytes);
}

int guard_intact(const void *buf, size_t bytes)
{
    const unsigned char *p = buf;
    size_t i;
    for (i = 0; i < bytes; i++)
        if (p[i] != CORPUS_GUARD_BYTE)
            return 0;
    return 1;
}

int report_guard(case_report *r, const char *what, const void *buf, size_t bytes)
{
    if (guard_intact(buf, bytes))
        return 1;
    report_fail(r, "%s (expected untouched, got written)", what);
    return 0;
}

static int expected_hit_matches(case_report *r, const char *what, int index,
                                const corpus_expected_hit *want, const isect_hit *got,
                                const corpus_tolerance *tol)
{
    char field[160], want_kind[24], got_kind[24];
    int ok = 1;

    snprintf(field, sizeof field, "%s: hit %d kind", what, index);
    if (got->kind != want->kind) {
        report_fail(r, "%s (expected %s, got %s)", field,
                    corpus_kind_name(want->kind, want_kind, sizeof want_kind),
                    corpus_kind_name(got->kind, got_kind, sizeof got_kind));
        ok = 0;
    }
    snprintf(field, sizeof field, "%s: hit %d prim", what, index);
    ok &= report_int(r, field, got->prim, want->prim);
    snprintf(field, sizeof field, "%s: hit %d t", what, index);
    ok &= report_near(r, field, got->t, want->t, tol->t);
    snprintf(field, sizeof field, "%s: hit %d point", what, index);
    ok &= report_near_n(r, field, got->point, want->point, 3, tol->point);
    snprintf(field, sizeof field, "%s: hit %d normal", what, index);
    ok &= report_near_n(r, field, got->normal, want->normal, 3, tol->normal);
    if (want->has_uv) {
        snprintf(field, sizeof field, "%s: hit %d uv", what, index);
        ok &= report_near_n(r, field, got->uv, want->uv, 2, tol->uv);
    }
    return ok;
}

int report_expected_hits(case_report *r, const char *what, const corpus_case *c,
                         const isect_hit *hits, int count, int written)
{
    char field[160];
    int ok, i, n;

    snprintf(field, sizeof field, "%s: hit count", what);
    ok = report_int(r, field, count, c->count);
    if (!c->hits_listed)
        return ok;
    n = count < written ? count : written;
    if (n > c->count)
        n = c->count;
    for (i = 0; i < n; i++)
        ok &= expected_hit_matches(r, what, i, &c->hits[i], &hits[i], &c->tol);
    return ok;
}

/* Name and print the first field where two hits differ in their bits. */
static void describe_difference(case_report *r, const char *what, const isect_hit *got,
                                const isect_hit *want)
{
    const char *names[9] = { "t", "point[0]", "point[1]", "point[2]", "normal[0]",
                             "normal[1]", "normal[2]", "uv[0]", "uv[1]" };
    double got_values[9], want_values[9];
    int i;

    got_values[0] = got->t;
    want_values[0] = want->t;
    for (i = 0; i < 3; i++) {
        got_values[1 + i] = got->point[i];
        want_values[1 + i] = want->point[i];
        got_values[4 + i] = got->normal[i];
        want_values[4 + i] = want->normal[i];
    }
    for (i = 0; i < 2; i++) {
        got_values[7 + i] = got->uv[i];
        want_values[7 + i] = want->uv[i];
    }
    for (i = 0; i < 9; i++) {
        if (memcmp(&got_values[i], &want_values[i], sizeof got_values[i]) != 0) {
            report_fail(r, "%s: %s differs in its bits (expected %a, got %a)", what, names[i],
                        want_values[i], got_values[i]);
            return;
        }
    }
    if (got->prim != want->prim)
        report_fail(r, "%s: prim differs (expected %d, got %d)", what, (int)want->prim,
                    (int)got->prim);
    else
        report_fail(r, "%s: kind differs (expected %d, got %d)", what, (int)want->kind,
                    (int)got->kind);
}

int report_same_hit(case_report *r, const char *what, const isect_hit *got,
                    const isect_hit *want)
{
    if (memcmp(got, want, sizeof *got) == 0)
        return 1;
    describe_difference(r, what, got, want);
    return 0;
}

/* The fields a MISS or INVALID record must leave at zero. */
static int rest_is_zero(const isect_hit *h)
{
    int i;
    for (i = 0; i < 3; i++)
        if (h->point[i] != 0.0 || h->normal[i] != 0.0)
            return 0;
    return h->uv[0] == 0.0 && h->uv[1] == 0.0;
}

static int report_batch_record(case_report *r, const char *what, const isect_hit *h,
                               int32_t kind, int t_is_right, const char *t_text)
{
    char want_kind[24], got_kind[24];
    int ok = 1;
    if (h->kind != kind) {
        report_fail(r, "%s: kind (expected %s, got %s)", what,
                    corpus_kind_name(kind, want_kind, sizeof want_kind),
                    corpus_kind_name(h->kind, got_kind, sizeof got_kind));
        ok = 0;
    }
    if (!t_is_right) {
        report_fail(r, "%s: t (expected %s, got %.17g)", what, t_text, h->t);
        ok = 0;
    }
    if (h->prim != -1) {
        report_fail(r, "%s: prim (expected -1, got %d)", what, (int)h->prim);
        ok = 0;
    }
    if (!rest_is_zero(h)) {
        report_fail(r, "%s: point/normal/uv (expected all 0, got point %g %g %g normal %g %g %g "
                    "uv %g %g)", what, h->point[0], h->point[1], h->point[2], h->normal[0],
                    h->normal[1], h->normal[2], h->uv[0], h->uv[1]);
        ok = 0;
    }
    return ok;
}

int report_miss_record(case_report *r, const char *what, const isect_hit *h)
{
    return report_batch_record(r, what, h, ISECT_MISS, h->t == INFINITY, "+inf");
}

int report_invalid_record(case_report *r, const char *what, const isect_hit *h)
{
    return report_batch_record(r, what, h, ISECT_INVALID, isnan(h->t) != 0, "nan");
}
