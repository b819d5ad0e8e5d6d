/* SPDX-License-Identifier: Apache-2.0 */
/*
 * version.c — what the built library says about itself, and the text of its
 * status codes.
 */
#include "api/dispatch.h"

/* Compile-time checks of the layouts isect.h documents (C99 has no
 * static_assert: a negative array size stops the build). */
#define ISECT_LAYOUT_CHECK(name, cond) typedef char isect_layout_##name[(cond) ? 1 : -1]
ISECT_LAYOUT_CHECK(ray_size, sizeof(isect_ray) == 64);
ISECT_LAYOUT_CHECK(hit_size, sizeof(isect_hit) == 80);
ISECT_LAYOUT_CHECK(hit_prim, offsetof(isect_hit, prim) == 72);
ISECT_LAYOUT_CHECK(opts_size, sizeof(isect_opts) == 16);
ISECT_LAYOUT_CHECK(xform_size, sizeof(isect_xform) == 256);
ISECT_LAYOUT_CHECK(shape_size, sizeof(void *) != 8 || sizeof(isect_shape) == 40);
ISECT_LAYOUT_CHECK(shape_data, sizeof(void *) != 8 || offsetof(isect_shape, data) == 16);

ISECT_API unsigned isect_version(void)
{
    return ISECT_VERSION;
}

ISECT_API const char *isect_version_string(void)
{
    return ISECT_VERSION_STRING;
}

ISECT_API int isect_abi_version(void)
{
    return ISECT_ABI_VERSION;
}

ISECT_API const char *isect_strerror(int status)
{
    switch (status) {
    case ISECT_OK:           return "success";
    case ISECT_E_ARG:        return "invalid argument (NULL pointer, bad count, negative radius, "
                                    "bad eps, unknown shape type, rule or flag)";
    case ISECT_E_NONFINITE:  return "NaN or infinity where a finite number is required";
    case ISECT_E_DEGENERATE: return "degenerate input (zero ray direction, singular transform, or a "
                                    "zero-area polygon asked for its normal)";
    case ISECT_E_NOMEM:      return "out of memory";
    default:                 return "unknown status";
    }
}
