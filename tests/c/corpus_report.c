/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_report.c — failure lines and scalar comparisons; see corpus_report.h.
 */
#include "corpus_report.h"

#include "corpus_case.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void report_begin(case_report *r, const char *file, const char *label, const char *name)
{
    r->file = file;
    snprintf(r->label, sizeof r->label, "%s", label);
    r->name = name != NULL ? name : "(unnamed)";
    r->failures = 0;
}

void report_fail(case_report *r, const char *fmt, ...)
{
    va_list ap;
    r->failures++;
    if (r->failures > CORPUS_REPORT_MAX_LINES)
        return;
    printf("FAIL %s:%s %s: ", r->file, r->label, r->name);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    putchar('\n');
}

void report_end(case_report *r)
{
    if (r->failures > CORPUS_REPORT_MAX_LINES)
        printf("FAIL %s:%s %s: ... and %d more failures of this case not shown\n", r->file,
               r->label, r->name, r->failures - CORPUS_REPORT_MAX_LINES);
}

int report_status(case_report *r, const char *what, int got, int want)
{
    char got_buf[48], want_buf[32];
    const char *got_text = got_buf;
    if (got == want)
        return 1;
    /* A positive return is a count or an answer, not a status. */
    if (got > 0)
        snprintf(got_buf, sizeof got_buf, "%d, a success", got);
    else
        got_text = corpus_status_name(got, got_buf, sizeof got_buf);
    report_fail(r, "%s: wrong status (expected %s, got %s)", what,
                corpus_status_name(want, want_buf, sizeof want_buf), got_text);
    return 0;
}

int report_int(case_report *r, const char *what, long long got, long long want)
{
    if (got == want)
        return 1;
    report_fail(r, "%s (expected %lld, got %lld)", what, want, got);
    return 0;
}

int corpus_near(double got, double want, double tol)
{
    if (isnan(want))
        return isnan(got);
    if (isinf(want))
        return got == want;
    return fabs(got - want) <= tol * fmax(1.0, fabs(want));
}

int report_near(case_report *r, const char *what, double got, double want, double tol)
{
    if (corpus_near(got, want, tol))
        return 1;
    report_fail(r, "%s (expected %.17g, got %.17g; tol %g)", what, want, got, tol);
    return 0;
}

int report_near_n(case_report *r, const char *what, const double *got, const double *want,
                  int n, double tol)
{
    int i;
    for (i = 0; i < n; i++) {
        if (!corpus_near(got[i], want[i], tol)) {
            char component[96];
            snprintf(component, sizeof component, "%s[%d]", what, i);
            return report_near(r, component, got[i], want[i], tol);
        }
    }
    return 1;
}
