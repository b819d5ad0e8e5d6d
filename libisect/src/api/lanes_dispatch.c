/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes_dispatch.c — which copy of the lane batch runs (see api/lanes.h):
 * the widest instruction set the CPU supports, capped by the environment
 * variable ISECT_SIMD. The copies give the same bits, so the choice only
 * changes the speed; the variable exists to test exactly that, and to
 * rule it out when reproducing a result.
 */
#include "api/lanes.h"

#include <stdlib.h>
#include <string.h>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(ISECT_NO_SIMD)
#define LANES_X86 1
#else
#define LANES_X86 0
lanes_batch_fn lanes_batch_sse2(int32_t type)
{
    return lanes_batch_scalar(type);
}
lanes_batch_fn lanes_batch_avx2(int32_t type)
{
    return lanes_batch_scalar(type);
}
lanes_batch_fn lanes_batch_avx512(int32_t type)
{
    return lanes_batch_scalar(type);
}
#endif

/* The highest level the CPU runs. */
static enum lanes_level cpu_level(void)
{
#if LANES_X86
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2")
        && __builtin_cpu_supports("fma"))
        return LANES_AVX512;
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        return LANES_AVX2;
    return LANES_SSE2;
#else
    return LANES_SCALAR;
#endif
}

/* The cap named by ISECT_SIMD, or the highest level when it is unset or
 * names none. Read on every batch call (getenv is cheap next to a batch),
 * so nothing is cached in the library. */
static enum lanes_level env_cap(void)
{
    static const char *const names[] = { "scalar", "sse2", "avx2", "avx512" };
    const char *v = getenv("ISECT_SIMD");
    if (v != NULL)
        for (int i = 0; i < 4; i++)
            if (strcmp(v, names[i]) == 0)
                return (enum lanes_level)i;
    return LANES_AVX512;
}

enum lanes_level lanes_level_selected(void)
{
    enum lanes_level cpu = cpu_level(), cap = env_cap();
    return cpu < cap ? cpu : cap;
}

lanes_batch_fn lanes_batch_select(int32_t type)
{
    switch (lanes_level_selected()) {
    case LANES_AVX512:
        return lanes_batch_avx512(type);
    case LANES_AVX2:
        return lanes_batch_avx2(type);
    case LANES_SSE2:
        return lanes_batch_sse2(type);
    default:
        return lanes_batch_scalar(type);
    }
}
