/* SPDX-License-Identifier: Apache-2.0 */
/*
 * polygon2d.c — 2D point in polygon and winding number, single and batch,
 * all through one loop over winding_edge (exact, half-open rule).
 */
#include "prim/prim.h"
#include "core/predicates.h"

#include <stddef.h>

static int polygon2_check(const double *poly, int n)
{
    if (poly == NULL || n < 3)
        return ISECT_E_ARG;
    return all_finite(poly, 2 * (int64_t)n) ? ISECT_OK : ISECT_E_NONFINITE;
}

static int32_t winding2(const double *poly, int n, const double p[2])
{
    const double *prev = poly + 2 * (ptrdiff_t)(n - 1);
    int32_t winding = 0;
    for (int i = 0; i < n; i++) {
        const double *cur = poly + 2 * (ptrdiff_t)i;
        winding += winding_edge(prev, cur, p);
        prev = cur;
    }
    return winding;
}

ISECT_API int isect_point_in_polygon2(const double *poly, int n, const double p[2], int rule)
{
    if (p == NULL || !fill_rule_valid(rule))
        return ISECT_E_ARG;
    int status = polygon2_check(poly, n);
    if (status != ISECT_OK)
        return status;
    if (!all_finite(p, 2))
        return ISECT_E_NONFINITE;
    return fill_rule_inside(winding2(poly, n, p), rule);
}

ISECT_API int isect_winding_number2(const double *poly, int n, const double p[2],
                                    int32_t *winding)
{
    if (p == NULL || winding == NULL)
        return ISECT_E_ARG;
    int status = polygon2_check(poly, n);
    if (status != ISECT_OK)
        return status;
    if (!all_finite(p, 2))
        return ISECT_E_NONFINITE;
    *winding = winding2(poly, n, p);
    return ISECT_OK;
}

/* Batch: a NULL point or output array is allowed only for m == 0. */
static int batch_check(const double *poly, int n, const double *pts, int64_t m,
                       const void *out)
{
    if (m < 0 || (m > 0 && (pts == NULL || out == NULL)))
        return ISECT_E_ARG;
    return polygon2_check(poly, n);
}

ISECT_API int64_t isect_point_in_polygon2_batch(const double *poly, int n, const double *pts,
                                                int64_t m, int rule, uint8_t *inside)
{
    if (!fill_rule_valid(rule))
        return ISECT_E_ARG;
    int status = batch_check(poly, n, pts, m, inside);
    if (status != ISECT_OK)
        return status;
    int64_t count = 0;
    for (int64_t i = 0; i < m; i++) {
        const double *p = pts + 2 * i;
        if (!all_finite(p, 2)) {
            inside[i] = ISECT_INVALID;
            continue;
        }
        int in = fill_rule_inside(winding2(poly, n, p), rule);
        inside[i] = (uint8_t)in;
        count += in;
    }
    return count;
}

ISECT_API int64_t isect_winding_number2_batch(const double *poly, int n, const double *pts,
                                              int64_t m, int32_t *winding)
{
    int status = batch_check(poly, n, pts, m, winding);
    if (status != ISECT_OK)
        return status;
    int64_t count = 0;
    for (int64_t i = 0; i < m; i++) {
        const double *p = pts + 2 * i;
        if (!all_finite(p, 2)) {
            winding[i] = INT32_MIN;
            continue;
        }
        winding[i] = winding2(poly, n, p);
        count += winding[i] != 0;
    }
    return count;
}
