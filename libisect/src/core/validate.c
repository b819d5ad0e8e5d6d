/* SPDX-License-Identifier: Apache-2.0 */
/*
 * validate.c — the checks every entry point makes on what the caller passes:
 * options, rays, and runs of numbers that must be finite. Written once here
 * so that scalar, dispatch and batch calls reject exactly the same inputs.
 */
#include "core/core.h"

#include <string.h>

/* The bytes of isect_opts up to and including flags. A caller that fills
 * only size and flags (an older, shorter struct) is accepted; one that
 * covers less than that has not filled the struct at all. */
#define OPTS_MIN_SIZE (offsetof(isect_opts, flags) + sizeof(uint32_t))
#define OPTS_KNOWN_FLAGS (ISECT_CULL_BACK | ISECT_ANY_HIT)

int params_from_opts(const isect_opts *opts, isect_params *prm)
{
    prm->flags = 0;
    prm->eps = ISECT_EPS_DEFAULT;
    if (opts == NULL)
        return ISECT_OK;
    if (opts->size < OPTS_MIN_SIZE)
        return ISECT_E_ARG;
    if (opts->flags & ~OPTS_KNOWN_FLAGS)
        return ISECT_E_ARG;
    prm->flags = opts->flags;
    if (opts->size >= offsetof(isect_opts, eps) + sizeof(double)) {
        if (isnan(opts->eps) || isinf(opts->eps))
            return ISECT_E_NONFINITE;
        if (opts->eps < 0.0)
            return ISECT_E_ARG;
        prm->eps = opts->eps;
    }
    return ISECT_OK;
}

int all_finite(const double *x, int64_t n)
{
    /* Accumulating x*0 keeps the loop branch-free: it is 0 for finite x and
     * NaN for NaN or +-Inf, and NaN survives the sum. */
    double probe = 0.0;
    for (int64_t i = 0; i < n; i++)
        probe += x[i] * 0.0;
    return probe == 0.0;
}
