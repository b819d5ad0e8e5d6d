/* SPDX-License-Identifier: Apache-2.0 */
/*
 * check.h — the assertion helpers of the C unit tests. Each test program
 * includes it once, calls CHECK* as often as it likes and ends main() with
 * `return check_summary();`, which prints "N passed, N failed" and returns
 * non-zero on any failure.
 */
#ifndef ISECT_TEST_CHECK_H
#define ISECT_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_passed, check_failed;

static void check_record(int ok, const char *file, int line, const char *what)
{
    if (ok) {
        check_passed++;
    } else {
        check_failed++;
        fprintf(stderr, "%s:%d: FAILED: %s\n", file, line, what);
    }
}

#define CHECK(cond) check_record(!!(cond), __FILE__, __LINE__, #cond)

/* |a - b| <= tol * max(1, |b|) — the corpus rule. */
#define CHECK_NEAR(a, b, tol)                                                        \
    do {                                                                             \
        double check_a_ = (a), check_b_ = (b);                                       \
        int check_ok_ = fabs(check_a_ - check_b_) <= (tol) * fmax(1.0, fabs(check_b_)); \
        if (!check_ok_)                                                              \
            fprintf(stderr, "    %s = %.17g, expected %.17g\n", #a, check_a_, check_b_); \
        check_record(check_ok_, __FILE__, __LINE__, #a " ~ " #b);                     \
    } while (0)

#define CHECK_EQ_INT(a, b)                                                           \
    do {                                                                             \
        long long check_a_ = (long long)(a), check_b_ = (long long)(b);              \
        if (check_a_ != check_b_)                                                    \
            fprintf(stderr, "    %s = %lld, expected %lld\n", #a, check_a_, check_b_); \
        check_record(check_a_ == check_b_, __FILE__, __LINE__, #a " == " #b);         \
    } while (0)

static int check_summary(void)
{
    printf("%d passed, %d failed\n", check_passed, check_failed);
    return check_failed != 0;
}

#endif
