/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes.h (api) — isect_intersect_batch for the analytic shapes, LANE_W
 * rays at a time through the fast kernels (prim/ *_lanes.h), compiled once
 * per instruction set (api/lanes_batch.h, included by lanes_scalar.c,
 * lanes_sse2.c, lanes_avx2.c, lanes_avx512.c) and chosen at run time.
 *
 * Every copy writes exactly the records and count of batch.c's per-ray loop
 * over shape_ray_first: a lane the kernel certifies is written from the
 * kernel, which is the same source the scalar path runs first; any other
 * ray (a lane the kernel defers, a bad ray, the last few rays of the
 * batch) goes through shape_ray_first itself.
 */
#ifndef ISECT_API_LANES_H
#define ISECT_API_LANES_H

#include "api/dispatch.h"

typedef int64_t (*lanes_batch_fn)(const shape_family *f, const isect_shape *s,
                                  const isect_ray *rays, int64_t n, const isect_params *prm,
                                  isect_hit *closest);

/* The instruction sets, in increasing order. */
enum lanes_level { LANES_SCALAR, LANES_SSE2, LANES_AVX2, LANES_AVX512 };

/* The batch of the best level this CPU runs (at most the level named by
 * the environment variable ISECT_SIMD: "scalar", "sse2", "avx2" or
 * "avx512", for testing and reproducing), or NULL when the shape type has
 * no fast kernel. */
lanes_batch_fn lanes_batch_select(int32_t type);

/* The level lanes_batch_select would use. */
enum lanes_level lanes_level_selected(void);

/* The copies (NULL for a type without a kernel); the SSE2, AVX2 and AVX-512
 * ones exist on x86-64 with GCC or clang unless ISECT_NO_SIMD is defined. */
lanes_batch_fn lanes_batch_scalar(int32_t type);
lanes_batch_fn lanes_batch_sse2(int32_t type);
lanes_batch_fn lanes_batch_avx2(int32_t type);
lanes_batch_fn lanes_batch_avx512(int32_t type);

#endif /* ISECT_API_LANES_H */
