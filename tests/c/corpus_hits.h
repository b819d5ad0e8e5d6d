/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_hits.h — checks on isect_hit buffers: against the corpus's expected
 * hits (within tolerance), against another call's hits (bit for bit), the
 * documented MISS / INVALID batch records, and guard records that must stay
 * untouched (nothing written past cap, nothing written on error).
 */
#ifndef ISECT_CORPUS_HITS_H
#define ISECT_CORPUS_HITS_H

#include "corpus_case.h"
#include "corpus_report.h"
#include "isect.h"

#include <stddef.h>
#include <stdint.h>

/* A byte pattern no library writes by accident: every double in it is a
 * large negative number and every int32 a large negative index. */
#define CORPUS_GUARD_BYTE 0xA5

void guard_fill(void *buf, size_t bytes);

/* 1 when every byte of buf still holds the guard pattern. */
int guard_intact(const void *buf, size_t bytes);

/* Reports "what: ... written" when bytes [0, bytes) of buf were touched. */
int report_guard(case_report *r, const char *what, const void *buf, size_t bytes);

/* The call returned `count` and wrote hits[0 .. min(count, written)):
 * count must be the case's, and each hit must match the listed expectation
 * (prim and kind exactly; t, point, normal, uv within the case's tolerance). */
int report_expected_hits(case_report *r, const char *what, const corpus_case *c,
                         const isect_hit *hits, int count, int written);

/* got and want must be the same bytes. */
int report_same_hit(case_report *r, const char *what, const isect_hit *got,
                    const isect_hit *want);

/* Batch records: MISS is t = +inf, prim = -1, kind MISS, everything else 0;
 * INVALID is t = NaN, prim = -1, kind INVALID, everything else 0. */
int report_miss_record(case_report *r, const char *what, const isect_hit *h);
int report_invalid_record(case_report *r, const char *what, const isect_hit *h);

#endif /* ISECT_CORPUS_HITS_H */
