/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_polygon2.c — libFuzzer harness: the polygon helpers
 * isect_point_in_polygon2, isect_winding_number2 (and their batch forms),
 * isect_polygon_normal and isect_plane_from_points.
 *
 * Input (fuzz_input.h): a vertex count (including the invalid < 3 and
 * negative ones), 2D vertices, a rule, query points, then 3D vertices.
 *
 * Asserted: documented statuses; outputs untouched on error (a zero normal
 * and plane for E_DEGENERATE, as documented); for every point, the even-odd
 * answer is the winding number's parity and the nonzero answer is
 * winding != 0 (one exact rule decides all three); the batch forms equal
 * the scalar calls (INVALID / INT32_MIN for non-finite points); and the
 * winding number is additive: the polygon's equals the sum over the fan
 * triangles (v0, v[i], v[i+1]) — the half-open rule is a symbolic
 * perturbation of the point, so the identity of chains holds exactly, on
 * edges and at vertices too. The unit normal is finite and of length 1, and
 * plane_from_points' normal is polygon_normal's bit for bit.
 */
#include "fuzz_checks.h"
#include "fuzz_input.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_N 16
#define MAX_POINTS 8

static int finite2(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]);
}

static void check_2d(const double *poly, int n, int32_t rule, const double *pts, int m)
{
    int32_t wind[MAX_POINTS], wbatch[MAX_POINTS + 1];
    uint8_t ibatch[MAX_POINTS + 1];
    int inside[MAX_POINTS];
    int64_t r, count_in = 0, count_w = 0;
    int i, k;

    for (i = 0; i < m; i++) {
        const double *p = &pts[2 * i];
        int32_t w = (int32_t)0xA5A5A5A5;
        int st = isect_winding_number2(poly, n, p, &w);
        fuzz_require_status(st, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE, "isect_winding_number2");
        FUZZ_REQUIRE(st <= 0, "isect_winding_number2 returned %d", st);
        if (st < 0)
            FUZZ_REQUIRE(w == (int32_t)0xA5A5A5A5, "winding written on error %d", st);
        inside[i] = isect_point_in_polygon2(poly, n, p, rule);
        fuzz_require_status(inside[i], FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE,
                            "isect_point_in_polygon2");
        FUZZ_REQUIRE(inside[i] <= 1, "isect_point_in_polygon2 returned %d", inside[i]);
        wind[i] = st == ISECT_OK ? w : INT32_MIN;
        if (st == ISECT_OK && inside[i] >= 0) {
            if (rule == ISECT_EVEN_ODD)
                FUZZ_REQUIRE(inside[i] == (int)(w & 1), "even-odd %d, winding %d", inside[i],
                             (int)w);
            else
                FUZZ_REQUIRE(inside[i] == (w != 0), "nonzero %d, winding %d", inside[i], (int)w);
            /* A valid polygon, a finite point, a valid rule: nothing fails. */
        }
        if (st == ISECT_OK && n >= 3) {
            /* Additivity over the fan from vertex 0. */
            int64_t sum = 0;
            for (k = 1; k + 1 < n; k++) {
                double tri[6];
                int32_t wt = 0;
                memcpy(&tri[0], &poly[0], 2 * sizeof *tri);
                memcpy(&tri[2], &poly[2 * k], 2 * sizeof *tri);
                memcpy(&tri[4], &poly[2 * (k + 1)], 2 * sizeof *tri);
                FUZZ_REQUIRE(isect_winding_number2(tri, 3, p, &wt) == ISECT_OK,
                             "fan triangle %d rejected", k);
                sum += wt;
            }
            FUZZ_REQUIRE(sum == w, "winding %d, sum over the fan %lld", (int)w, (long long)sum);
        }
    }

    fuzz_canary_fill(ibatch, sizeof ibatch);
    r = isect_point_in_polygon2_batch(poly, n, pts, m, rule, ibatch);
    fuzz_require_status(r, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE, "point_in_polygon2_batch");
    if (r < 0) {
        FUZZ_REQUIRE(fuzz_canary_intact(ibatch, sizeof ibatch), "batch wrote and failed");
    } else {
        for (i = 0; i < m; i++) {
            if (!finite2(&pts[2 * i])) {
                FUZZ_REQUIRE(ibatch[i] == ISECT_INVALID, "point %d: non-finite, batch %d", i,
                             ibatch[i]);
                continue;
            }
            FUZZ_REQUIRE(ibatch[i] == inside[i], "point %d: batch %d, scalar %d", i, ibatch[i],
                         inside[i]);
            count_in += ibatch[i];
        }
        FUZZ_REQUIRE(r == count_in, "point_in_polygon2_batch returned %lld, %lld inside",
                     (long long)r, (long long)count_in);
        FUZZ_REQUIRE(fuzz_canary_intact(ibatch + m, sizeof ibatch - (size_t)m),
                     "point_in_polygon2_batch wrote beyond m");
    }

    fuzz_canary_fill(wbatch, sizeof wbatch);
    r = isect_winding_number2_batch(poly, n, pts, m, wbatch);
    fuzz_require_status(r, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE, "winding_number2_batch");
    if (r < 0) {
        FUZZ_REQUIRE(fuzz_canary_intact(wbatch, sizeof wbatch), "batch wrote and failed");
    } else {
        for (i = 0; i < m; i++) {
            if (!finite2(&pts[2 * i])) {
                FUZZ_REQUIRE(wbatch[i] == INT32_MIN, "point %d: non-finite, batch %d", i,
                             (int)wbatch[i]);
                continue;
            }
            FUZZ_REQUIRE(wbatch[i] == wind[i], "point %d: batch %d, scalar %d", i,
                         (int)wbatch[i], (int)wind[i]);
            count_w += wbatch[i] != 0;
        }
        FUZZ_REQUIRE(r == count_w, "winding_number2_batch returned %lld, %lld nonzero",
                     (long long)r, (long long)count_w);
        FUZZ_REQUIRE(fuzz_canary_intact(wbatch + m, sizeof wbatch - (size_t)m * sizeof *wbatch),
                     "winding_number2_batch wrote beyond m");
    }
}

static void check_normal(const double *v, int n)
{
    double normal[3], plane[4];
    int st, sp;

    fuzz_canary_fill(normal, sizeof normal);
    st = isect_polygon_normal(v, n, normal);
    fuzz_require_status(st, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE | FUZZ_ALLOW_DEGENERATE,
                        "isect_polygon_normal");
    FUZZ_REQUIRE(st <= 0, "isect_polygon_normal returned %d", st);
    fuzz_canary_fill(plane, sizeof plane);
    sp = isect_plane_from_points(v, n, plane);
    fuzz_require_status(sp, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE | FUZZ_ALLOW_DEGENERATE,
                        "isect_plane_from_points");
    FUZZ_REQUIRE(sp == st, "plane_from_points %d, polygon_normal %d", sp, st);
    if (st == ISECT_OK) {
        double len = sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
        FUZZ_REQUIRE(fabs(len - 1.0) <= 1e-13, "normal of length %.17g", len);
        FUZZ_REQUIRE(memcmp(plane, normal, sizeof normal) == 0,
                     "plane_from_points' normal differs from polygon_normal's");
        FUZZ_REQUIRE(!isnan(plane[3]), "plane d is NaN");
    } else if (st == ISECT_E_DEGENERATE) {
        FUZZ_REQUIRE(normal[0] == 0 && normal[1] == 0 && normal[2] == 0,
                     "E_DEGENERATE without a zero normal");
        FUZZ_REQUIRE(plane[0] == 0 && plane[1] == 0 && plane[2] == 0 && plane[3] == 0,
                     "E_DEGENERATE without a zero plane");
    } else {
        FUZZ_REQUIRE(fuzz_canary_intact(normal, sizeof normal) &&
                         fuzz_canary_intact(plane, sizeof plane),
                     "normal or plane written on error %d", st);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in;
    double poly[2 * MAX_N], pts[2 * MAX_POINTS];
    double *v3, *v2;
    uint8_t b;
    int n, m, alloc_n;
    int32_t rule;

    fuzz_input_init(&in, data, size);
    b = fuzz_u8(&in);
    /* 0..MAX_N mostly; bytes >= 0x80 give negative counts. */
    n = b < 0x80 ? b % (MAX_N + 1) : (int)(int8_t)b;
    alloc_n = n > 0 ? n : 0;
    fuzz_doubles(&in, poly, (size_t)(2 * alloc_n));
    b = fuzz_u8(&in);
    rule = b < 0x80 ? (int32_t)(b & 1) : (int32_t)(int8_t)b;
    m = fuzz_u8(&in) % (MAX_POINTS + 1);
    fuzz_doubles(&in, pts, (size_t)(2 * m));
    /* Exactly n vertices on the heap, so reading past them is a report. */
    v2 = malloc((size_t)(2 * alloc_n + 1) * sizeof *v2);
    if (v2 == NULL)
        abort();
    memcpy(v2, poly, (size_t)(2 * alloc_n) * sizeof *v2);
    check_2d(v2, n, rule, pts, m);
    free(v2);

    v3 = malloc((size_t)(3 * alloc_n + 1) * sizeof *v3);
    if (v3 == NULL)
        abort();
    fuzz_doubles(&in, v3, (size_t)(3 * alloc_n));
    check_normal(v3, n);
    free(v3);
    return 0;
}
