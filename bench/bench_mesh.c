/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bench_mesh.c — libisect's mesh BVH against Embree 3 on one core.
 *
 * Meshes: the icosphere (unit sphere, the icosahedron subdivided) at 81,920
 * triangles (level 6) and 1,310,720 (level 8). Ray sets, 10^6 rays each,
 * the same rays for both libraries (Embree gets them rounded to float):
 *   outside  origins on the sphere of radius 3, aimed at uniform points of
 *            the ball of radius 1.2 (most hit, some graze or miss);
 *   inside   origins uniform in the ball of radius 0.9, uniform directions
 *            (every ray hits once);
 *   camera   a pinhole at (0, 0.5, 3) looking at the origin, 1000 x 1000
 *            pixels, 60 degree field of view.
 * libisect: isect_intersect_batch (closest hit, float64, one thread).
 * Embree: rtcIntersect1 per ray on a device made with "threads=1" (its
 * builder then runs on this thread too), RTC_BUILD_QUALITY_MEDIUM (the
 * default). Build time: isect_mesh_create (copying the input, degeneracy
 * tests, BVH, the edge pass for closedness) against setting Embree's
 * buffers and rtcCommitScene. Memory: isect_mesh_bytes against the bytes
 * Embree's memory monitor reports for the scene. Each time is the median
 * of RUNS runs. A sanity column counts rays where the two disagree on
 * hit/miss or on t beyond float precision (1e-4 relative).
 *
 *     bench_mesh [--rays N] [--runs K] [--small-only] [results.json]
 *     (default results file bench/results/mesh.json)
 */
#define _POSIX_C_SOURCE 200809L

#include "isect.h"
#include "mesh_fixtures.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define DEFAULT_RAYS 1000000
#define DEFAULT_RUNS 5
#define DEFAULT_RESULTS "bench/results/mesh.json"

/* ------------------------------------------------------------- helpers */

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, compare_double);
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

static void *xmalloc(size_t bytes)
{
    void *p = malloc(bytes);
    if (p == NULL) {
        fprintf(stderr, "bench_mesh: out of memory\n");
        exit(1);
    }
    return p;
}

/* xorshift64*: uniform doubles in [0, 1). */
static double rng_uniform(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 0x2545F4914F6CDD1DULL) >> 11) * 0x1p-53;
}

static void rng_unit_vector(uint64_t *s, double v[3])
{
    for (;;) {
        double len2 = 0.0;
        for (int k = 0; k < 3; k++) {
            v[k] = 2.0 * rng_uniform(s) - 1.0;
            len2 += v[k] * v[k];
        }
        if (len2 > 1e-6 && len2 <= 1.0) {
            double len = sqrt(len2);
            for (int k = 0; k < 3; k++)
                v[k] /= len;
            return;
        }
    }
}

static void rng_in_ball(uint64_t *s, double r, double v[3])
{
    for (;;) {
        double len2 = 0.0;
        for (int k = 0; k < 3; k++) {
            v[k] = 2.0 * rng_uniform(s) - 1.0;
            len2 += v[k] * v[k];
        }
        if (len2 <= 1.0) {
            for (int k = 0; k < 3; k++)
                v[k] *= r;
            return;
        }
    }
}

/* ------------------------------------------------------------- ray sets */

enum { SET_OUTSIDE, SET_INSIDE, SET_CAMERA, SETS };
static const char *const set_names[SETS] = { "outside", "inside", "camera" };

static void make_rays(int set, int64_t n, isect_ray *rays)
{
    uint64_t seed = 0x9E3779B97F4A7C15ULL + (uint64_t)set * 0x632BE59BD9B4E019ULL;
    int64_t side = (int64_t)ceil(sqrt((double)n));
    const double eye[3] = { 0.0, 0.5, 3.0 };
    /* Camera basis: forward to the origin, right, up. */
    double fwd[3] = { -eye[0], -eye[1], -eye[2] }, up0[3] = { 0.0, 1.0, 0.0 };
    double fl = sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]);
    for (int k = 0; k < 3; k++)
        fwd[k] /= fl;
    double right[3] = { fwd[1] * up0[2] - fwd[2] * up0[1], fwd[2] * up0[0] - fwd[0] * up0[2],
                        fwd[0] * up0[1] - fwd[1] * up0[0] };
    double rl = sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
    for (int k = 0; k < 3; k++)
        right[k] /= rl;
    double up[3] = { right[1] * fwd[2] - right[2] * fwd[1], right[2] * fwd[0] - right[0] * fwd[2],
                     right[0] * fwd[1] - right[1] * fwd[0] };
    double half = tan(30.0 * 3.14159265358979323846 / 180.0);
    for (int64_t i = 0; i < n; i++) {
        isect_ray *r = &rays[i];
        r->tmin = 0.0;
        r->tmax = INFINITY;
        if (set == SET_OUTSIDE) {
            double o[3], target[3];
            rng_unit_vector(&seed, o);
            rng_in_ball(&seed, 1.2, target);
            for (int k = 0; k < 3; k++) {
                r->org[k] = 3.0 * o[k];
                r->dir[k] = target[k] - r->org[k];
            }
        } else if (set == SET_INSIDE) {
            rng_in_ball(&seed, 0.9, r->org);
            rng_unit_vector(&seed, r->dir);
        } else {
            double px = ((double)(i % side) + 0.5) / (double)side * 2.0 - 1.0;
            double py = ((double)(i / side) + 0.5) / (double)side * 2.0 - 1.0;
            for (int k = 0; k < 3; k++) {
                r->org[k] = eye[k];
                r->dir[k] = fwd[k] + half * (px * right[k] + py * up[k]);
            }
        }
    }
}

/* --------------------------------------------------------------- Embree */

typedef struct embree_scene {
    RTCDevice device;
    RTCScene  scene;
} embree_scene;

static int64_t embree_bytes; /* the memory monitor's running total */

static bool embree_monitor(void *user, ssize_t bytes, bool post)
{
    (void)user;
    (void)post;
    embree_bytes += (int64_t)bytes;
    return true;
}

static RTCScene embree_build(RTCDevice device, const fx_mesh *m)
{
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), (size_t)m->nv);
    for (int64_t i = 0; i < 3 * m->nv; i++)
        vb[i] = (float)m->v[i];
    unsigned *ib = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), (size_t)m->nf);
    for (int64_t i = 0; i < 3 * m->nf; i++)
        ib[i] = (unsigned)m->idx[i];
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    return scene;
}

static int64_t embree_trace(RTCScene scene, const isect_ray *rays, int64_t n, float *t_out)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    int64_t hits = 0;
    for (int64_t i = 0; i < n; i++) {
        struct RTCRayHit rh;
        rh.ray.org_x = (float)rays[i].org[0];
        rh.ray.org_y = (float)rays[i].org[1];
        rh.ray.org_z = (float)rays[i].org[2];
        rh.ray.dir_x = (float)rays[i].dir[0];
        rh.ray.dir_y = (float)rays[i].dir[1];
        rh.ray.dir_z = (float)rays[i].dir[2];
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = INFINITY;
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        int hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        hits += hit;
        t_out[i] = hit ? rh.ray.tfar : INFINITY;
    }
    return hits;
}

/* ----------------------------------------------------------------- main */

typedef struct row {
    int64_t triangles;
    double  isect_build_ns, embree_build_ns; /* per triangle */
    double  isect_bytes, embree_bytes;       /* per triangle */
    double  isect_rate[SETS], embree_rate[SETS];
    int64_t disagree[SETS], hits[SETS];
} row;

static void bench_mesh(int level, int64_t nrays, int runs, RTCDevice device, row *out)
{
    const double origin[3] = { 0, 0, 0 };
    fx_mesh m = fx_icosphere(level, origin, 1.0);
    out->triangles = m.nf;
    double *times = xmalloc((size_t)runs * sizeof *times);

    /* Builds. */
    isect_mesh *mesh = NULL;
    for (int r = 0; r < runs; r++) {
        if (mesh != NULL)
            isect_mesh_destroy(mesh);
        double t0 = now_seconds();
        int status = isect_mesh_create(m.v, m.nv, m.idx, NULL, m.nf, &mesh);
        times[r] = now_seconds() - t0;
        if (status != ISECT_OK) {
            fprintf(stderr, "isect_mesh_create: %s\n", isect_strerror(status));
            exit(1);
        }
    }
    out->isect_build_ns = median(times, runs) * 1e9 / (double)m.nf;
    out->isect_bytes = (double)isect_mesh_bytes(mesh) / (double)m.nf;
    RTCScene scene = NULL;
    for (int r = 0; r < runs; r++) {
        if (scene != NULL)
            rtcReleaseScene(scene);
        int64_t before = embree_bytes;
        double t0 = now_seconds();
        scene = embree_build(device, &m);
        times[r] = now_seconds() - t0;
        out->embree_bytes = (double)(embree_bytes - before) / (double)m.nf;
    }
    out->embree_build_ns = median(times, runs) * 1e9 / (double)m.nf;

    /* Queries. */
    isect_ray *rays = xmalloc((size_t)nrays * sizeof *rays);
    isect_hit *hits = xmalloc((size_t)nrays * sizeof *hits);
    float *et = xmalloc((size_t)nrays * sizeof *et);
    isect_shape shape = { ISECT_MESH, 0, 0, 0, NULL, mesh, NULL };
    for (int set = 0; set < SETS; set++) {
        make_rays(set, nrays, rays);
        double *etimes = xmalloc((size_t)runs * sizeof *etimes);
        for (int r = 0; r < runs; r++) {
            /* Interleaved, so drift and turbo affect both alike. */
            double t0 = now_seconds();
            int64_t n = isect_intersect_batch(&shape, rays, nrays, NULL, hits);
            times[r] = now_seconds() - t0;
            if (n < 0) {
                fprintf(stderr, "isect_intersect_batch: %s\n", isect_strerror((int)n));
                exit(1);
            }
            out->hits[set] = n;
            t0 = now_seconds();
            embree_trace(scene, rays, nrays, et);
            etimes[r] = now_seconds() - t0;
        }
        out->isect_rate[set] = (double)nrays / median(times, runs);
        out->embree_rate[set] = (double)nrays / median(etimes, runs);
        free(etimes);
        int64_t disagree = 0;
        for (int64_t i = 0; i < nrays; i++) {
            int ih = hits[i].kind != ISECT_MISS, eh = et[i] != INFINITY;
            if (ih != eh || (ih && fabs(hits[i].t - et[i]) > 1e-4 * fabs(hits[i].t)))
                disagree++;
        }
        out->disagree[set] = disagree;
    }
    free(rays);
    free(hits);
    free(et);
    free(times);
    rtcReleaseScene(scene);
    isect_mesh_destroy(mesh);
    fx_free(&m);
}

int main(int argc, char **argv)
{
    int64_t nrays = DEFAULT_RAYS;
    int runs = DEFAULT_RUNS, small_only = 0;
    const char *results = DEFAULT_RESULTS;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--rays") == 0 && i + 1 < argc)
            nrays = atoll(argv[++i]);
        else if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc)
            runs = atoi(argv[++i]);
        else if (strcmp(argv[i], "--small-only") == 0)
            small_only = 1;
        else
            results = argv[i];
    }
    if (nrays < 1 || runs < 1) {
        fprintf(stderr, "usage: bench_mesh [--rays N] [--runs K] [--small-only] [results.json]\n");
        return 1;
    }
    RTCDevice device = rtcNewDevice("threads=1");
    if (device == NULL) {
        fprintf(stderr, "bench_mesh: rtcNewDevice failed\n");
        return 1;
    }
    rtcSetDeviceMemoryMonitorFunction(device, embree_monitor, NULL);

    const int levels[2] = { 6, 8 };
    int nlevels = small_only ? 1 : 2;
    row rows[2];
    printf("mesh benchmark: icosphere, %lld rays per set, median of %d runs, one thread\n",
           (long long)nrays, runs);
    printf("%10s %-8s %14s %14s %7s %9s %9s\n", "triangles", "rays", "libisect ray/s",
           "Embree ray/s", "ratio", "hit", "disagree");
    for (int l = 0; l < nlevels; l++) {
        bench_mesh(levels[l], nrays, runs, device, &rows[l]);
        const row *r = &rows[l];
        for (int set = 0; set < SETS; set++)
            printf("%10lld %-8s %14.4g %14.4g %7.3f %8.1f%% %9lld\n", (long long)r->triangles,
                   set_names[set], r->isect_rate[set], r->embree_rate[set],
                   r->isect_rate[set] / r->embree_rate[set],
                   100.0 * (double)r->hits[set] / (double)nrays, (long long)r->disagree[set]);
        printf("%10lld build ns/triangle: libisect %.1f, Embree %.1f (ratio %.2f); "
               "bytes/triangle: libisect %.1f, Embree %.1f\n",
               (long long)r->triangles, r->isect_build_ns, r->embree_build_ns,
               r->isect_build_ns / r->embree_build_ns, r->isect_bytes, r->embree_bytes);
    }
    rtcReleaseDevice(device);

    FILE *fp = fopen(results, "w");
    if (fp == NULL) {
        fprintf(stderr, "bench_mesh: cannot write %s (table above is complete)\n", results);
        return 0;
    }
    fprintf(fp, "{\n  \"rays_per_set\": %lld,\n  \"runs\": %d,\n  \"meshes\": [\n",
            (long long)nrays, runs);
    for (int l = 0; l < nlevels; l++) {
        const row *r = &rows[l];
        fprintf(fp, "    {\"triangles\": %lld, \"build_ns_per_triangle\": "
                    "{\"libisect\": %.2f, \"embree\": %.2f}, \"bytes_per_triangle\": "
                    "{\"libisect\": %.2f, \"embree\": %.2f}, \"rays_per_second\": {",
                (long long)r->triangles, r->isect_build_ns, r->embree_build_ns, r->isect_bytes,
                r->embree_bytes);
        for (int set = 0; set < SETS; set++)
            fprintf(fp, "%s\"%s\": {\"libisect\": %.0f, \"embree\": %.0f, \"disagree\": %lld}",
                    set ? ", " : "", set_names[set], r->isect_rate[set], r->embree_rate[set],
                    (long long)r->disagree[set]);
        fprintf(fp, "}}%s\n", l + 1 < nlevels ? "," : "");
    }
    fprintf(fp, "  ]\n}\n");
    fclose(fp);
    return 0;
}
