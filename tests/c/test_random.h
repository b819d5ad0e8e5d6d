/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_random.h — the C tests' seeded random numbers (xorshift64): the
 * same sequence on every platform and build, so a failing ray can be
 * reproduced from its index.
 */
#ifndef ISECT_TEST_RANDOM_H
#define ISECT_TEST_RANDOM_H

#include <math.h>
#include <stdint.h>

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;

static inline void rng_seed(uint64_t seed)
{
    rng_state = seed != 0 ? seed : 0x9E3779B97F4A7C15ull;
}

static inline uint64_t rng_next(void)
{
    uint64_t x = rng_state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    rng_state = x;
    return x;
}

/* Uniform in [-1, 1). */
static inline double rng_unit(void)
{
    return (double)(rng_next() >> 11) * 0x1p-52 - 1.0;
}

/* Uniform in [lo, hi]. */
static inline int rng_int(int lo, int hi)
{
    return lo + (int)(rng_next() % (uint64_t)(hi - lo + 1));
}

/* 2^k for k uniform in [lo, hi]. */
static inline double rng_scale(int lo, int hi)
{
    return ldexp(1.0, rng_int(lo, hi));
}

/* A uniformly distributed unit vector (rejection from the cube). */
static inline void rng_dir(double d[3])
{
    double len;
    do {
        for (int k = 0; k < 3; k++)
            d[k] = rng_unit();
        len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (len < 1e-3 || len > 1.0);
    for (int k = 0; k < 3; k++)
        d[k] /= len;
}

/* x moved by k ulps (k may be negative). */
static inline double ulps(double x, int k)
{
    for (; k > 0; k--)
        x = nextafter(x, INFINITY);
    for (; k < 0; k++)
        x = nextafter(x, -INFINITY);
    return x;
}

#endif /* ISECT_TEST_RANDOM_H */
