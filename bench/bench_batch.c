/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bench_batch.c — throughput of isect_intersect_batch against the memory
 * traffic it cannot avoid.
 *
 * A batch call reads N rays (64 bytes each) and writes N closest hits (80
 * bytes each). The baseline is a plain streaming loop that does exactly that
 * traffic and no arithmetic: it reads every ray and writes a hit-sized record
 * built from it. batch_time / copy_time says how far the intersection code is
 * from the memory limit; the target is <= 1.5 at N = 4M rays, where neither
 * buffer fits in any cache.
 *
 * For each shape (sphere, box, triangle) and N (4096 and 4M) the two are
 * timed in the same run, interleaved (alternating which goes first, so drift
 * and turbo effects hit both alike), repeated, and reported as medians.
 * Rays come from a fixed-seed xorshift generator: origins on a sphere of
 * radius 4 around the shape, aimed at points in a cube sized so that about
 * half of them hit, in random order (no branch pattern to learn).
 *
 *     bench_batch [results.json]     (default bench/results/batch.json)
 *
 * Prints a table and writes the same numbers as JSON. Exit status 1 only if
 * something failed (allocation, a library error, the results file).
 */
#define _POSIX_C_SOURCE 200809L

#include "isect.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define SMALL_N 4096
#define LARGE_N (4 * 1024 * 1024)
/* Many repetitions where one call takes tens of microseconds, few where it
 * takes a large fraction of a second; both give a stable median. */
#define SMALL_REPS 1001
#define LARGE_REPS 7
#define RATIO_TARGET 1.5
#define DEFAULT_RESULTS "bench/results/batch.json"
#define RESULTS_DIR "bench/results"
#define RNG_SEED 0x9E3779B97F4A7C15ull
#define ORIGIN_RADIUS 4.0

typedef struct bench_shape {
    const char *name;
    int32_t     type;
    double      data[9];
    /* Half-width of the cube of aim points that makes about half the rays
     * hit (measured; the printed hit fraction shows the actual value). */
    double      aim_half_width;
} bench_shape;

static const bench_shape shapes[] = {
    { "sphere", ISECT_SPHERE, { 0, 0, 0, 1 }, 1.33 },
    { "box", ISECT_AABB, { -1, -1, -1, 1, 1, 1 }, 1.85 },
    { "triangle", ISECT_TRIANGLE, { -1, -1, 0, 1, -1, 0, 0, 1, 0 }, 0.58 },
};
#define SHAPE_COUNT ((int)(sizeof shapes / sizeof shapes[0]))

typedef struct bench_result {
    const char *shape;
    int64_t     n;
    int         reps;
    double      hit_fraction;
    double      batch_median; /* seconds per call */
    double      copy_median;
} bench_result;

/* ------------------------------------------------------------ rays */

/* xorshift64: reproducible on every platform, cheap, good enough to
 * scatter rays. */
static uint64_t rng_next(uint64_t *state)
{
    uint64_t x = *state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    *state = x;
    return x;
}

/* Uniform in [-1, 1). */
static double rng_signed_unit(uint64_t *state)
{
    return (double)(rng_next(state) >> 11) * 0x1p-52 - 1.0;
}

/* Uniform on the sphere of the given radius (rejection from the cube). */
static void rng_on_sphere(uint64_t *state, double radius, double out[3])
{
    double len2;
    do {
        out[0] = rng_signed_unit(state);
        out[1] = rng_signed_unit(state);
        out[2] = rng_signed_unit(state);
        len2 = out[0] * out[0] + out[1] * out[1] + out[2] * out[2];
    } while (len2 > 1.0 || len2 < 1e-6);
    len2 = radius / sqrt(len2);
    out[0] *= len2;
    out[1] *= len2;
    out[2] *= len2;
}

static void rays_generate(isect_ray *rays, int64_t n, double aim_half_width)
{
    uint64_t state = RNG_SEED;
    int64_t i;
    int k;
    for (i = 0; i < n; i++) {
        isect_ray *r = &rays[i];
        rng_on_sphere(&state, ORIGIN_RADIUS, r->org);
        for (k = 0; k < 3; k++)
            r->dir[k] = aim_half_width * rng_signed_unit(&state) - r->org[k];
        r->tmin = 0.0;
        r->tmax = INFINITY;
    }
}

/* ------------------------------------------------------------ timing */

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The baseline: the batch call's memory traffic and nothing else. Every
 * byte of every ray is read and every byte of every hit record written. */
static void stream_copy(const isect_ray *rays, int64_t n, isect_hit *out)
{
    int64_t i;
    for (i = 0; i < n; i++) {
        const isect_ray *r = &rays[i];
        isect_hit *h = &out[i];
        h->t = r->tmin;
        h->point[0] = r->org[0];
        h->point[1] = r->org[1];
        h->point[2] = r->org[2];
        h->normal[0] = r->dir[0];
        h->normal[1] = r->dir[1];
        h->normal[2] = r->dir[2];
        h->uv[0] = r->tmax;
        h->uv[1] = 0.0;
        h->prim = -1;
        h->kind = ISECT_MISS;
    }
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *values, int n)
{
    qsort(values, (size_t)n, sizeof *values, compare_doubles);
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/* Times one (shape, n) pair; rays and hits hold at least n records. */
static int bench_one(const bench_shape *bs, isect_ray *rays, isect_hit *hits, int64_t n,
                     int reps, bench_result *out)
{
    isect_shape shape;
    double *batch_times, *copy_times;
    int64_t rays_hit = 0;
    int rep;

    memset(&shape, 0, sizeof shape);
    shape.type = bs->type;
    shape.data = bs->data;
    batch_times = malloc((size_t)reps * sizeof *batch_times);
    copy_times = malloc((size_t)reps * sizeof *copy_times);
    if (batch_times == NULL || copy_times == NULL) {
        fprintf(stderr, "bench_batch: out of memory for timings\n");
        free(batch_times);
        free(copy_times);
        return 0;
    }

    rays_generate(rays, n, bs->aim_half_width);
    /* Warm-up, untimed: faults in every page of both buffers, fills caches
     * and branch predictors, and checks that the call works at all. */
    memset(hits, 0, (size_t)n * sizeof *hits);
    stream_copy(rays, n, hits);
    rays_hit = isect_intersect_batch(&shape, rays, n, NULL, hits);
    if (rays_hit < 0) {
        fprintf(stderr, "bench_batch: isect_intersect_batch(%s) failed: %s\n", bs->name,
                isect_strerror((int)rays_hit));
        free(batch_times);
        free(copy_times);
        return 0;
    }

    for (rep = 0; rep < reps; rep++) {
        int copy_first = rep % 2 == 0;
        double t0, t1, t2;
        t0 = now_seconds();
        if (copy_first)
            stream_copy(rays, n, hits);
        else
            rays_hit = isect_intersect_batch(&shape, rays, n, NULL, hits);
        t1 = now_seconds();
        if (copy_first)
            rays_hit = isect_intersect_batch(&shape, rays, n, NULL, hits);
        else
            stream_copy(rays, n, hits);
        t2 = now_seconds();
        copy_times[rep] = copy_first ? t1 - t0 : t2 - t1;
        batch_times[rep] = copy_first ? t2 - t1 : t1 - t0;
    }

    out->shape = bs->name;
    out->n = n;
    out->reps = reps;
    out->hit_fraction = (double)rays_hit / (double)n;
    out->batch_median = median(batch_times, reps);
    out->copy_median = median(copy_times, reps);
    free(batch_times);
    free(copy_times);
    return 1;
}

/* ------------------------------------------------------------ output */

static void table_header(void)
{
    printf("libisect %s: isect_intersect_batch vs a streaming copy of the same bytes\n"
           "(copy: read N x %zu-byte rays, write N x %zu-byte hit records; medians)\n\n",
           isect_version_string(), sizeof(isect_ray), sizeof(isect_hit));
    printf("%-9s %9s %5s %6s %14s %14s %11s %11s\n", "shape", "N", "reps", "hit%",
           "batch rays/s", "copy rays/s", "copy GB/s", "batch/copy");
}

static void table_row(const bench_result *r)
{
    double bytes = (double)r->n * (double)(sizeof(isect_ray) + sizeof(isect_hit));
    printf("%-9s %9lld %5d %5.1f%% %14.4g %14.4g %11.2f %11.2f\n", r->shape, (long long)r->n,
           r->reps, 100.0 * r->hit_fraction, (double)r->n / r->batch_median,
           (double)r->n / r->copy_median, bytes / r->copy_median * 1e-9,
           r->batch_median / r->copy_median);
}

static void target_summary(const bench_result *results, int count)
{
    int i;
    printf("\ntarget: batch/copy <= %.1f at N = %d:", RATIO_TARGET, LARGE_N);
    for (i = 0; i < count; i++) {
        double ratio = results[i].batch_median / results[i].copy_median;
        if (results[i].n != LARGE_N)
            continue;
        printf(" %s %.2f (%s)", results[i].shape, ratio,
               ratio <= RATIO_TARGET ? "met" : "NOT met");
    }
    printf("\n");
}

/* Opened before the measurements so a bad path fails in a second, not
 * after the run. */
static FILE *results_open(const char *path)
{
    FILE *f;
    if (strcmp(path, DEFAULT_RESULTS) == 0 && mkdir(RESULTS_DIR, 0777) != 0 &&
        errno != EEXIST) {
        fprintf(stderr, "bench_batch: cannot create %s: %s\n", RESULTS_DIR, strerror(errno));
        return NULL;
    }
    f = fopen(path, "w");
    if (f == NULL)
        fprintf(stderr, "bench_batch: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

/* Writes the results and closes f. */
static int results_write(FILE *f, const char *path, const bench_result *results, int count)
{
    int i;

    fprintf(f, "{\n  \"benchmark\": \"bench_batch\",\n  \"library_version\": \"%s\",\n",
            isect_version_string());
    fprintf(f, "  \"ray_bytes\": %zu,\n  \"hit_bytes\": %zu,\n", sizeof(isect_ray),
            sizeof(isect_hit));
    fprintf(f, "  \"baseline\": \"read each ray, write a hit-sized record\",\n");
    fprintf(f, "  \"statistic\": \"median\",\n");
    fprintf(f, "  \"target\": {\"n\": %d, \"max_ratio\": %.2f},\n", LARGE_N, RATIO_TARGET);
    fprintf(f, "  \"results\": [\n");
    for (i = 0; i < count; i++) {
        const bench_result *r = &results[i];
        double ratio = r->batch_median / r->copy_median;
        fprintf(f,
                "    {\"shape\": \"%s\", \"n\": %lld, \"repetitions\": %d, "
                "\"hit_fraction\": %.4f, \"batch_seconds\": %.9g, \"copy_seconds\": %.9g, "
                "\"batch_rays_per_second\": %.6g, \"copy_rays_per_second\": %.6g, "
                "\"ratio\": %.4f, \"meets_target\": %s}%s\n",
                r->shape, (long long)r->n, r->reps, r->hit_fraction, r->batch_median,
                r->copy_median, (double)r->n / r->batch_median, (double)r->n / r->copy_median,
                ratio, r->n != LARGE_N ? "null" : ratio <= RATIO_TARGET ? "true" : "false",
                i + 1 < count ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    if (fclose(f) != 0) {
        fprintf(stderr, "bench_batch: cannot write %s\n", path);
        return 0;
    }
    printf("results: %s\n", path);
    return 1;
}

int main(int argc, char **argv)
{
    static const int64_t sizes[2] = { SMALL_N, LARGE_N };
    static const int reps[2] = { SMALL_REPS, LARGE_REPS };
    bench_result results[2 * SHAPE_COUNT];
    const char *path = argc > 1 ? argv[1] : DEFAULT_RESULTS;
    FILE *results_file;
    isect_ray *rays;
    isect_hit *hits;
    int count = 0, s, z, ok = 1;

    results_file = results_open(path);
    if (results_file == NULL)
        return 1;
    rays = malloc((size_t)LARGE_N * sizeof *rays);
    hits = malloc((size_t)LARGE_N * sizeof *hits);
    if (rays == NULL || hits == NULL) {
        fprintf(stderr, "bench_batch: cannot allocate %d rays and hits\n", LARGE_N);
        ok = 0;
    }
    if (ok)
        table_header();
    for (z = 0; z < 2 && ok; z++) {
        for (s = 0; s < SHAPE_COUNT && ok; s++) {
            ok = bench_one(&shapes[s], rays, hits, sizes[z], reps[z], &results[count]);
            if (ok) {
                table_row(&results[count]);
                fflush(stdout);
                count++;
            }
        }
    }
    if (ok)
        target_summary(results, count);
    /* Written even after a failure, so the file never holds stale numbers
     * from an earlier run. */
    if (!results_write(results_file, path, results, count))
        ok = 0;
    free(rays);
    free(hits);
    return ok ? 0 : 1;
}
