/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes_avx2.c — the lane batch four rays at once (CPUs with AVX2 and FMA). The whole unit is compiled for
 * that instruction set by a target pragma, so no build flag is needed; it
 * only runs where api/lanes_dispatch.c has checked the CPU. See api/lanes.h.
 */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(ISECT_NO_SIMD)

#include <immintrin.h>
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#else
#pragma GCC target("avx2,fma")
#endif

#define LANE_ISA    LANE_ISA_AVX2
#define LANE_SUFFIX avx2
#include "api/lanes_batch.h"

#if defined(__clang__)
#pragma clang attribute pop
#endif

#else
/* Not built for this target (ISO C wants something in every unit). */
typedef int lanes_avx2_not_built;
#endif
