/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes_avx512.c — the lane batch eight rays at once (CPUs with AVX-512F). The whole unit is compiled for
 * that instruction set by a target pragma, so no build flag is needed; it
 * only runs where api/lanes_dispatch.c has checked the CPU. See api/lanes.h.
 */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(ISECT_NO_SIMD)

#include <immintrin.h>
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma,avx512f"))), apply_to = function)
#else
#pragma GCC target("avx2,fma,avx512f")
#endif

#define LANE_ISA    LANE_ISA_AVX512
#define LANE_SUFFIX avx512
#include "api/lanes_batch.h"

#if defined(__clang__)
#pragma clang attribute pop
#endif

#else
/* Not built for this target (ISO C wants something in every unit). */
typedef int lanes_avx512_not_built;
#endif
