/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_report.h — the failure lines of one case, in the runner's format
 *
 *     FAIL file:id name: what (expected X, got Y)
 *
 * and the scalar comparisons that produce them. Each compare function
 * returns 1 when the value is right and otherwise prints a line and
 * returns 0, so checks can go on and report everything that is wrong.
 */
#ifndef ISECT_CORPUS_REPORT_H
#define ISECT_CORPUS_REPORT_H

#include <stddef.h>

/* After this many lines a case's further failures are only counted, so one
 * broken primitive does not bury the rest of the output. */
#define CORPUS_REPORT_MAX_LINES 12

typedef struct case_report {
    const char *file;
    char        label[32]; /* the case id, or "[index]" when the id is unusable */
    const char *name;
    int         failures;
} case_report;

void report_begin(case_report *r, const char *file, const char *label, const char *name);

/* Print one failure line (the message follows "name: "). */
void report_fail(case_report *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* At the end of a case: a note for the lines that were not printed. */
void report_end(case_report *r);

/* Statuses by name ("ok", "E_ARG", ...). */
int report_status(case_report *r, const char *what, int got, int want);

int report_int(case_report *r, const char *what, long long got, long long want);

/* |got - want| <= tol * max(1, |want|); an infinite want must be matched
 * exactly and a NaN want by a NaN (the corpus's tolerance rule). */
int corpus_near(double got, double want, double tol);
int report_near(case_report *r, const char *what, double got, double want, double tol);

/* Component-wise corpus_near over n values; names the first bad index. */
int report_near_n(case_report *r, const char *what, const double *got, const double *want,
                  int n, double tol);

#endif /* ISECT_CORPUS_REPORT_H */
