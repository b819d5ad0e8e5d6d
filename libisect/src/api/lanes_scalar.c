/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes_scalar.c — the lane batch one ray at a time (LANE_W = 1), in
 * portable C: the batch of every build without SIMD, and of every CPU
 * without SSE2 support in the library. See api/lanes.h.
 */
#define LANE_ISA    LANE_ISA_SCALAR
#define LANE_SUFFIX scalar
#include "api/lanes_batch.h"
