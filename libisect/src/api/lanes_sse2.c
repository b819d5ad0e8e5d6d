/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes_sse2.c — the lane batch two rays at once (every x86-64 CPU). The whole unit is compiled for
 * that instruction set by a target pragma, so no build flag is needed; it
 * only runs where api/lanes_dispatch.c has checked the CPU. See api/lanes.h.
 */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(ISECT_NO_SIMD)

#include <immintrin.h>
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("sse2"))), apply_to = function)
#else
#pragma GCC target("sse2")
#endif

#define LANE_ISA    LANE_ISA_SSE2
#define LANE_SUFFIX sse2
#include "api/lanes_batch.h"

#if defined(__clang__)
#pragma clang attribute pop
#endif

#else
/* Not built for this target (ISO C wants something in every unit). */
typedef int lanes_sse2_not_built;
#endif
