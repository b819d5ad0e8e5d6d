/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_checks.c — the invariants of fuzz_checks.h.
 */
#include "fuzz_checks.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Room for the scalar hits of one ray; more hits than this (a mesh of many
 * faces) are compared up to here. */
#define SCALAR_CAP 256

void fuzz_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "\n%s:%d: invariant violated: ", file, line);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    abort();
}

/* Set per input by the harness (fuzz_set_wide_range). */
static int wide_range;

void fuzz_set_wide_range(int wide)
{
    wide_range = wide;
}

void fuzz_range_init(fuzz_range *r)
{
    r->lo = INT_MAX;
    r->hi = INT_MIN;
}

void fuzz_range_add(fuzz_range *r, const double *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        int e;
        if (v[i] == 0.0 || !isfinite(v[i]))
            continue;
        e = ilogb(v[i]);
        r->lo = e < r->lo ? e : r->lo;
        r->hi = e > r->hi ? e : r->hi;
    }
}

int fuzz_range_wide(const fuzz_range *r)
{
#ifdef FUZZ_ANY_RANGE
    (void)r;
    return 0;
#else
    return r->hi > r->lo && r->hi - r->lo > FUZZ_MAX_SPREAD;
#endif
}

void fuzz_canary_fill(void *p, size_t bytes)
{
    memset(p, FUZZ_CANARY, bytes);
}

int fuzz_canary_intact(const void *p, size_t bytes)
{
    const unsigned char *c = p;
    size_t i;
    for (i = 0; i < bytes; i++)
        if (c[i] != FUZZ_CANARY)
            return 0;
    return 1;
}

static void *xmalloc(size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    if (p == NULL)
        abort();
    return p;
}

void fuzz_require_status(int64_t status, unsigned allowed, const char *call)
{
    if (status >= 0)
        return;
    FUZZ_REQUIRE(status >= -4 && (allowed & (1u << (unsigned)(-status))) != 0,
                 "%s returned the undocumented status %lld", call, (long long)status);
}

static int all_finite(const double *v, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

int fuzz_ray_valid(const isect_ray *ray)
{
    return all_finite(ray->org, 3) && all_finite(ray->dir, 3) &&
           !(ray->dir[0] == 0.0 && ray->dir[1] == 0.0 && ray->dir[2] == 0.0) &&
           !isnan(ray->tmin) && !isnan(ray->tmax);
}

int fuzz_shape_is_thin(const isect_shape *shape)
{
    switch (shape->type) {
    case ISECT_PLANE:
    case ISECT_TRIANGLE:
    case ISECT_POLYGON:
        return 1;
    case ISECT_CYLINDER:
        return shape->flags == 0;
    default:
        return 0;
    }
}

/* [lo, hi] of a hit's prim for the shape type (isect.h, isect_hit.prim). */
static void prim_range(const isect_shape *shape, int64_t nprim, int64_t *lo, int64_t *hi)
{
    *lo = -1;
    *hi = -1;
    switch (shape->type) {
    case ISECT_AABB:
        *lo = 0;
        *hi = 5;
        break;
    case ISECT_CONVEX:
    case ISECT_MESH:
        *lo = 0;
        *hi = nprim - 1;
        break;
    case ISECT_CYLINDER:
        *lo = 0;
        *hi = shape->flags ? 2 : 0;
        break;
    case ISECT_CYLINDER_INF:
        *lo = 0;
        *hi = 0;
        break;
    default:
        break;
    }
}

void fuzz_check_hits(const isect_shape *shape, const isect_ray *ray, uint32_t flags,
                     int64_t nprim, const isect_hit *hits, int count)
{
    int64_t lo, hi;
    int i;
    int has_uv = shape->type == ISECT_TRIANGLE || shape->type == ISECT_MESH;
    int culls = fuzz_shape_is_thin(shape) || shape->type == ISECT_MESH;

    prim_range(shape, nprim, &lo, &hi);
    /* isect.h: ANY_HIT stops "batch and mesh" queries at the first hit found;
     * an analytic shape's scalar call still lists all of its hits. */
    if ((flags & ISECT_ANY_HIT) && shape->type == ISECT_MESH)
        FUZZ_REQUIRE(count <= 1, "ANY_HIT gave %d mesh hits", count);
    for (i = 0; i < count; i++) {
        const isect_hit *h = &hits[i];
        double len;
        FUZZ_REQUIRE(h->kind == ISECT_ENTER || h->kind == ISECT_EXIT || h->kind == ISECT_TOUCH,
                     "hit %d: kind %d", i, (int)h->kind);
        FUZZ_REQUIRE(!isnan(h->t) && h->t >= ray->tmin && h->t <= ray->tmax,
                     "hit %d: t = %a outside [%a, %a]", i, h->t, ray->tmin, ray->tmax);
        if (i > 0)
            FUZZ_REQUIRE(hits[i - 1].t <= h->t, "hits %d, %d not sorted by t (%a > %a)",
                         i - 1, i, hits[i - 1].t, h->t);
        FUZZ_REQUIRE(wide_range || all_finite(h->normal, 3), "hit %d: non-finite normal", i);
        len = sqrt(h->normal[0] * h->normal[0] + h->normal[1] * h->normal[1] +
                   h->normal[2] * h->normal[2]);
        FUZZ_REQUIRE(wide_range || fabs(len - 1.0) <= 1e-13, "hit %d: normal of length %.17g",
                     i, len);
        FUZZ_REQUIRE(h->prim >= lo && h->prim <= hi, "hit %d: prim %d outside [%lld, %lld]",
                     i, (int)h->prim, (long long)lo, (long long)hi);
        if (has_uv)
            FUZZ_REQUIRE(all_finite(h->uv, 2), "hit %d: non-finite uv", i);
        else
            FUZZ_REQUIRE(h->uv[0] == 0.0 && h->uv[1] == 0.0, "hit %d: uv (%a, %a) not 0 for type %d",
                         i, h->uv[0], h->uv[1], (int)shape->type);
        if ((flags & ISECT_CULL_BACK) && culls)
            FUZZ_REQUIRE(h->kind != ISECT_EXIT, "hit %d: EXIT kept under CULL_BACK", i);
    }
}

static void print_hit(const char *what, const isect_hit *h)
{
    fprintf(stderr, "%s: t %a point %a %a %a normal %a %a %a uv %a %a prim %d kind %d\n", what,
            h->t, h->point[0], h->point[1], h->point[2], h->normal[0], h->normal[1],
            h->normal[2], h->uv[0], h->uv[1], (int)h->prim, (int)h->kind);
}

/* Bit-for-bit equality of two records, printing both when they differ. */
static int same_record(const isect_hit *a, const char *what_a, const isect_hit *b,
                       const char *what_b)
{
    if (memcmp(a, b, sizeof *a) == 0)
        return 1;
    print_hit(what_a, a);
    print_hit(what_b, b);
    return 0;
}

/* The opts of the same call with ANY_HIT added (the defaults where the
 * given size does not cover a field). */
static isect_opts with_any_hit(const isect_opts *opts, uint32_t flags)
{
    isect_opts o = ISECT_OPTS_INIT;
    o.flags = flags | ISECT_ANY_HIT;
    if (opts != NULL && opts->size >= sizeof(isect_opts))
        o.eps = opts->eps;
    return o;
}

int fuzz_check_intersect(const isect_shape *shape, const isect_ray *ray, const isect_opts *opts,
                         uint32_t flags, int64_t nprim, isect_hit *hits, int cap)
{
    size_t room = (size_t)cap + 1;
    isect_hit *buf = xmalloc(room * sizeof *buf);
    int st, again, written;

    fuzz_canary_fill(buf, room * sizeof *buf);
    st = isect_intersect(shape, ray, opts, buf, cap);
    fuzz_require_status(st, FUZZ_QUERY_ERRORS, "isect_intersect");
    if (st < 0) {
        FUZZ_REQUIRE(fuzz_canary_intact(buf, room * sizeof *buf),
                     "isect_intersect wrote hits and returned %d", st);
        FUZZ_REQUIRE(isect_intersect(shape, ray, opts, NULL, 0) == st,
                     "the count-only call's status differs from %d", st);
        free(buf);
        return st;
    }
    written = st < cap ? st : cap;
    FUZZ_REQUIRE(fuzz_canary_intact(buf + written, (room - (size_t)written) * sizeof *buf),
                 "isect_intersect wrote beyond min(count %d, cap %d)", st, cap);
    fuzz_check_hits(shape, ray, flags, nprim, buf, written);

    again = isect_intersect(shape, ray, opts, NULL, 0);
    FUZZ_REQUIRE(again == st, "count-only call: %d, full call: %d", again, st);

    /* A cap one short of the count writes the same leading hits. */
    if (written == st && st >= 1) {
        int k = st - 1;
        isect_hit *part = xmalloc(((size_t)k + 1) * sizeof *part);
        fuzz_canary_fill(part, ((size_t)k + 1) * sizeof *part);
        again = isect_intersect(shape, ray, opts, part, k);
        FUZZ_REQUIRE(again == st, "cap %d call: %d, full call: %d", k, again, st);
        FUZZ_REQUIRE(wide_range || memcmp(part, buf, (size_t)k * sizeof *part) == 0,
                     "cap %d call wrote other hits than the full call", k);
        FUZZ_REQUIRE(fuzz_canary_intact(part + k, sizeof *part), "cap %d call wrote hit %d", k, k);
        free(part);
    }

    /* ANY_HIT: a mesh reports 0 or 1 hit, one of the hits; an analytic
     * shape's first hit is the closest one. */
    if (!(flags & ISECT_ANY_HIT) && written == st) {
        isect_opts any = with_any_hit(opts, flags);
        isect_hit one;
        int got = isect_intersect(shape, ray, &any, &one, 1);
        if (shape->type == ISECT_MESH) {
            int i, found;
            FUZZ_REQUIRE(got == (st > 0 ? 1 : 0), "ANY_HIT mesh call: %d, full call: %d", got, st);
            for (i = 0, found = got == 0 || wide_range; i < st && !found; i++)
                found = memcmp(&one, &buf[i], sizeof one) == 0;
            FUZZ_REQUIRE(found, "ANY_HIT mesh hit is none of the %d hits", st);
        } else {
            FUZZ_REQUIRE((got > 0) == (st > 0), "ANY_HIT call: %d, full call: %d", got, st);
            if (got > 0)
                FUZZ_REQUIRE(same_record(&one, "any_hit", &buf[0], "closest"),
                             "ANY_HIT first hit differs from the closest hit");
        }
    }
    if (hits != NULL)
        memcpy(hits, buf, (size_t)written * sizeof *buf);
    free(buf);
    return st;
}

static void require_record(const isect_hit *h, int32_t kind, const char *what, int i)
{
    FUZZ_REQUIRE(h->kind == kind && h->prim == -1, "%s record %d: kind %d prim %d", what, i,
                 (int)h->kind, (int)h->prim);
    if (kind == ISECT_MISS)
        FUZZ_REQUIRE(h->t == INFINITY, "MISS record %d: t = %a", i, h->t);
    else
        FUZZ_REQUIRE(isnan(h->t), "INVALID record %d: t = %a", i, h->t);
    FUZZ_REQUIRE(h->point[0] == 0 && h->point[1] == 0 && h->point[2] == 0 &&
                     h->normal[0] == 0 && h->normal[1] == 0 && h->normal[2] == 0 &&
                     h->uv[0] == 0 && h->uv[1] == 0,
                 "%s record %d: fields other than t, prim, kind not 0", what, i);
}

typedef struct scalar_result {
    int       status;
    int       stored; /* min(status, SCALAR_CAP) */
    isect_hit hits[SCALAR_CAP];
} scalar_result;

/* The CSR layout the scalar results imply: a bad ray gets one record. */
static int64_t expected_hits_of(const scalar_result *s)
{
    return s->status >= 0 ? s->status : 1;
}

static void check_all_batch(const isect_shape *shape, const isect_ray *rays, int n,
                            const isect_opts *opts, const scalar_result *sr, int64_t batch_status)
{
    int64_t total = 0, cap2, r, r2;
    int64_t *offsets = xmalloc(((size_t)n + 2) * sizeof *offsets);
    int64_t *offsets2 = xmalloc(((size_t)n + 2) * sizeof *offsets2);
    isect_hit *hits, *hits2;
    int i;

    for (i = 0; i < n; i++)
        total += expected_hits_of(&sr[i]);
    hits = xmalloc(((size_t)total + 1) * sizeof *hits);
    fuzz_canary_fill(offsets, ((size_t)n + 2) * sizeof *offsets);
    fuzz_canary_fill(hits, ((size_t)total + 1) * sizeof *hits);
    r = isect_intersect_all_batch(shape, rays, n, opts, offsets, hits, total);
    fuzz_require_status(r, FUZZ_QUERY_ERRORS, "isect_intersect_all_batch");
    if (batch_status < 0 || r < 0) {
        FUZZ_REQUIRE(r == batch_status, "all_batch returned %lld, the closest-hit batch %lld",
                     (long long)r, (long long)batch_status);
        FUZZ_REQUIRE(fuzz_canary_intact(offsets, ((size_t)n + 2) * sizeof *offsets) &&
                         fuzz_canary_intact(hits, ((size_t)total + 1) * sizeof *hits),
                     "all_batch wrote output and returned %lld", (long long)r);
        goto done;
    }
    FUZZ_REQUIRE(r == total, "all_batch total %lld, scalar calls %lld", (long long)r,
                 (long long)total);
    FUZZ_REQUIRE(offsets[0] == 0, "offsets[0] = %lld", (long long)offsets[0]);
    for (i = 0; i < n; i++) {
        int64_t want = expected_hits_of(&sr[i]);
        int64_t k;
        FUZZ_REQUIRE(offsets[i + 1] - offsets[i] == want, "ray %d: %lld hits in CSR, %lld scalar",
                     i, (long long)(offsets[i + 1] - offsets[i]), (long long)want);
        if (sr[i].status < 0) {
            require_record(&hits[offsets[i]], ISECT_INVALID, "all_batch INVALID", i);
            continue;
        }
        for (k = 0; k < sr[i].stored; k++)
            FUZZ_REQUIRE(wide_range ||
                             same_record(&hits[offsets[i] + k], "all_batch", &sr[i].hits[k], "scalar"),
                         "ray %d hit %lld: all_batch record differs from the scalar call", i,
                         (long long)k);
    }
    FUZZ_REQUIRE(fuzz_canary_intact(offsets + n + 1, sizeof *offsets), "offsets[n+1] written");
    FUZZ_REQUIRE(fuzz_canary_intact(hits + total, sizeof *hits), "hits[cap] written");

    /* Half the room: complete offsets, the same first records, nothing more. */
    cap2 = total / 2;
    hits2 = xmalloc(((size_t)cap2 + 1) * sizeof *hits2);
    fuzz_canary_fill(hits2, ((size_t)cap2 + 1) * sizeof *hits2);
    fuzz_canary_fill(offsets2, ((size_t)n + 2) * sizeof *offsets2);
    r2 = isect_intersect_all_batch(shape, rays, n, opts, offsets2, hits2, cap2);
    FUZZ_REQUIRE(r2 == total, "all_batch with cap %lld: %lld, full %lld", (long long)cap2,
                 (long long)r2, (long long)total);
    FUZZ_REQUIRE(memcmp(offsets2, offsets, ((size_t)n + 1) * sizeof *offsets) == 0,
                 "all_batch offsets depend on cap");
    FUZZ_REQUIRE(wide_range || memcmp(hits2, hits, (size_t)cap2 * sizeof *hits) == 0,
                 "all_batch with cap %lld wrote other records", (long long)cap2);
    FUZZ_REQUIRE(fuzz_canary_intact(hits2 + cap2, sizeof *hits2),
                 "all_batch wrote beyond cap %lld", (long long)cap2);
    free(hits2);
done:
    free(hits);
    free(offsets);
    free(offsets2);
}

void fuzz_check_batches(const isect_shape *shape, const isect_ray *rays, int n,
                        const isect_opts *opts)
{
    scalar_result *sr = xmalloc(((size_t)n + 1) * sizeof *sr);
    isect_hit *closest = xmalloc(((size_t)n + 1) * sizeof *closest);
    int64_t r, hit_rays = 0;
    int i;

    for (i = 0; i < n; i++) {
        sr[i].status = isect_intersect(shape, &rays[i], opts, sr[i].hits, SCALAR_CAP);
        sr[i].stored = sr[i].status < 0 ? 0 : (sr[i].status < SCALAR_CAP ? sr[i].status : SCALAR_CAP);
    }
    fuzz_canary_fill(closest, ((size_t)n + 1) * sizeof *closest);
    r = isect_intersect_batch(shape, rays, n, opts, closest);
    fuzz_require_status(r, FUZZ_QUERY_ERRORS, "isect_intersect_batch");
    if (r < 0) {
        FUZZ_REQUIRE(fuzz_canary_intact(closest, ((size_t)n + 1) * sizeof *closest),
                     "isect_intersect_batch wrote records and returned %lld", (long long)r);
        /* The batch rejected the shape or options: so does every scalar call
         * whose ray is good, with the same status. */
        for (i = 0; i < n; i++)
            if (fuzz_ray_valid(&rays[i]))
                FUZZ_REQUIRE(sr[i].status == r, "batch status %lld, scalar ray %d status %d",
                             (long long)r, i, sr[i].status);
    } else {
        for (i = 0; i < n; i++) {
            if (sr[i].status > 0) {
                hit_rays++;
                FUZZ_REQUIRE(wide_range || same_record(&closest[i], "batch", &sr[i].hits[0], "scalar"),
                             "ray %d: batch record differs from the scalar call's first hit", i);
            } else if (sr[i].status == 0) {
                require_record(&closest[i], ISECT_MISS, "batch MISS", i);
            } else {
                /* A ray-level error: a bad ray, or (transformed shapes) one whose
                 * object-space image is bad: the batch's INVALID. */
                FUZZ_REQUIRE(!fuzz_ray_valid(&rays[i]) ||
                                 (shape->xform != NULL && (sr[i].status == ISECT_E_NONFINITE ||
                                                           sr[i].status == ISECT_E_DEGENERATE)),
                             "ray %d is good, the batch accepted the shape, the scalar call "
                             "returned %d", i, sr[i].status);
                require_record(&closest[i], ISECT_INVALID, "batch INVALID", i);
            }
        }
        FUZZ_REQUIRE(r == hit_rays, "batch returned %lld, %lld rays hit", (long long)r,
                     (long long)hit_rays);
        FUZZ_REQUIRE(fuzz_canary_intact(closest + n, sizeof *closest), "batch wrote record n");
    }
    if (n > 0)
        check_all_batch(shape, rays, n, opts, sr, r);
    free(sr);
    free(closest);
}

void fuzz_check_contains(const isect_shape *shape, const double *points, int n, int *inside)
{
    uint8_t *batch = xmalloc((size_t)n + 1);
    int64_t r, count = 0;
    int i;

    for (i = 0; i < n; i++) {
        inside[i] = isect_contains(shape, &points[3 * i]);
        fuzz_require_status(inside[i], FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE, "isect_contains");
        FUZZ_REQUIRE(inside[i] <= 1, "isect_contains returned %d", inside[i]);
        if (fuzz_shape_is_thin(shape))
            FUZZ_REQUIRE(inside[i] < 0, "isect_contains of a thin surface returned %d",
                         inside[i]);
    }
    fuzz_canary_fill(batch, (size_t)n + 1);
    r = isect_contains_batch(shape, points, n, batch);
    fuzz_require_status(r, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NONFINITE, "isect_contains_batch");
    if (r < 0) {
        FUZZ_REQUIRE(fuzz_canary_intact(batch, (size_t)n + 1),
                     "isect_contains_batch wrote output and returned %lld", (long long)r);
        for (i = 0; i < n; i++)
            if (all_finite(&points[3 * i], 3))
                FUZZ_REQUIRE(inside[i] == r, "contains_batch %lld, point %d scalar %d",
                             (long long)r, i, inside[i]);
    } else {
        for (i = 0; i < n; i++) {
            if (!all_finite(&points[3 * i], 3)) {
                FUZZ_REQUIRE(batch[i] == ISECT_INVALID, "point %d: non-finite, batch gave %d", i,
                             batch[i]);
                continue;
            }
            /* A finite point whose object-space image is not (a transformed
             * shape): the scalar call's E_NONFINITE is the batch's INVALID. */
            if (shape->xform != NULL && inside[i] == ISECT_E_NONFINITE) {
                FUZZ_REQUIRE(batch[i] == ISECT_INVALID, "point %d: scalar E_NONFINITE, batch %d",
                             i, batch[i]);
                continue;
            }
            FUZZ_REQUIRE(inside[i] >= 0, "contains_batch accepted the shape, point %d scalar %d",
                         i, inside[i]);
            FUZZ_REQUIRE(batch[i] == inside[i], "point %d: batch %d, scalar %d", i, batch[i],
                         inside[i]);
            count += batch[i];
        }
        FUZZ_REQUIRE(r == count, "contains_batch returned %lld, %lld inside", (long long)r,
                     (long long)count);
        FUZZ_REQUIRE(fuzz_canary_intact(batch + n, 1), "contains_batch wrote inside[n]");
    }
    free(batch);
}
