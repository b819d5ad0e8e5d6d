/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_batch.c — op "intersect" through isect_intersect_batch and
 * isect_intersect_all_batch.
 *
 * Each case becomes a batch of BATCH_RAYS copies of its ray with one ray in
 * the middle made bad (a NaN origin), so every batch also shows that a bad
 * ray is marked INVALID while the rays around it are still answered.
 */
#include "corpus_checks.h"
#include "corpus_hits.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define BATCH_RAYS 5
#define BAD_RAY 2
/* Room for every ray's hits plus the bad ray's INVALID record. */
#define ALL_CAP (BATCH_RAYS * CORPUS_HIT_CAP + 1)

static void batch_rays_make(const isect_ray *ray, isect_ray rays[BATCH_RAYS])
{
    int i;
    for (i = 0; i < BATCH_RAYS; i++)
        rays[i] = *ray;
    rays[BAD_RAY].org[0] = NAN;
}

/* The status the header assigns to a bad ray (ISECT_OK for a good one):
 * NaN/Inf in org or dir, or NaN in tmin/tmax, is E_NONFINITE; a zero
 * direction is E_DEGENERATE. */
static int ray_status(const isect_ray *ray)
{
    int i;
    for (i = 0; i < 3; i++)
        if (!isfinite(ray->org[i]) || !isfinite(ray->dir[i]))
            return ISECT_E_NONFINITE;
    if (isnan(ray->tmin) || isnan(ray->tmax))
        return ISECT_E_NONFINITE;
    if (ray->dir[0] == 0.0 && ray->dir[1] == 0.0 && ray->dir[2] == 0.0)
        return ISECT_E_DEGENERATE;
    return ISECT_OK;
}

void check_batch_ok(case_report *r, const intersect_setup *s, const isect_hit *reference,
                    int ref_count)
{
    isect_ray rays[BATCH_RAYS];
    isect_hit closest[BATCH_RAYS + 1];
    char what[160];
    int64_t got;
    int i;

    batch_rays_make(&s->c->ray, rays);
    guard_fill(closest, sizeof closest);
    got = isect_intersect_batch(&s->shape, rays, BATCH_RAYS, s->opts, closest);
    report_int(r, "isect_intersect_batch: return (rays hit)", got,
               ref_count > 0 ? BATCH_RAYS - 1 : 0);
    if (got < 0)
        return;
    for (i = 0; i < BATCH_RAYS; i++) {
        if (i == BAD_RAY) {
            snprintf(what, sizeof what, "isect_intersect_batch: ray %d (NaN origin)", i);
            report_invalid_record(r, what, &closest[i]);
        } else if (ref_count > 0) {
            snprintf(what, sizeof what,
                     "isect_intersect_batch: ray %d closest vs isect_intersect's first hit", i);
            report_same_hit(r, what, &closest[i], &reference[0]);
        } else {
            snprintf(what, sizeof what, "isect_intersect_batch: ray %d (no hit)", i);
            report_miss_record(r, what, &closest[i]);
        }
    }
    report_guard(r, "isect_intersect_batch: record past n", &closest[BATCH_RAYS],
                 sizeof closest[BATCH_RAYS]);
}

/* offsets[0..BATCH_RAYS] must be 0, then grow by each ray's count, within
 * the `available` records written. Returns 1 when they do. */
static int check_offsets(case_report *r, const char *name, const int64_t *offsets,
                         int ref_count, int64_t available)
{
    char what[160];
    int i, ok = 1;
    snprintf(what, sizeof what, "%s: offsets[0]", name);
    ok &= report_int(r, what, offsets[0], 0);
    for (i = 0; i < BATCH_RAYS; i++) {
        snprintf(what, sizeof what, "%s: offsets[%d] - offsets[%d] (hits of ray %d)", name,
                 i + 1, i, i);
        ok &= report_int(r, what, offsets[i + 1] - offsets[i], i == BAD_RAY ? 1 : ref_count);
    }
    if (ok && offsets[BATCH_RAYS] > available) {
        report_fail(r, "%s: offsets[%d] = %lld is past the %lld records written", name,
                    BATCH_RAYS, (long long)offsets[BATCH_RAYS], (long long)available);
        ok = 0;
    }
    return ok;
}

/* Each ray's hits in the CSR output equal isect_intersect's, bit for bit;
 * the bad ray has one INVALID record. Offsets are already checked. */
static void check_csr_hits(case_report *r, const int64_t *offsets, const isect_hit *hits,
                           const isect_hit *reference)
{
    char what[192];
    int i;
    int64_t j;
    for (i = 0; i < BATCH_RAYS; i++) {
        for (j = offsets[i]; j < offsets[i + 1]; j++) {
            snprintf(what, sizeof what, "isect_intersect_all_batch: ray %d hit %lld", i,
                     (long long)(j - offsets[i]));
            if (i == BAD_RAY) {
                if (!report_invalid_record(r, what, &hits[j]))
                    return;
            } else if (!report_same_hit(r, what, &hits[j], &reference[j - offsets[i]])) {
                return;
            }
        }
    }
}

/* A retry with a too-small cap: the total and the offsets are complete and
 * equal the full call's, only the first `cap` hits are written. With cap 0
 * the hit buffer is NULL (the count-only form). */
static void check_all_batch_short(case_report *r, const intersect_setup *s,
                                  const isect_ray *rays, int64_t cap, int64_t total,
                                  const int64_t *full_offsets, const isect_hit *full_hits)
{
    int64_t offsets[BATCH_RAYS + 2];
    isect_hit hits[ALL_CAP + 1];
    char name[96], what[192];
    int64_t got, i;

    snprintf(name, sizeof name, "isect_intersect_all_batch with cap %lld%s", (long long)cap,
             cap == 0 ? " and hits NULL" : " (too small)");
    guard_fill(offsets, sizeof offsets);
    guard_fill(hits, sizeof hits);
    got = isect_intersect_all_batch(&s->shape, rays, BATCH_RAYS, s->opts, offsets,
                                    cap == 0 ? NULL : hits, cap);
    snprintf(what, sizeof what, "%s: return (the full total)", name);
    if (!report_int(r, what, got, total) || got < 0)
        return;
    for (i = 0; i <= BATCH_RAYS; i++) {
        snprintf(what, sizeof what, "%s: offsets[%lld] vs the full call", name, (long long)i);
        report_int(r, what, offsets[i], full_offsets[i]);
    }
    snprintf(what, sizeof what, "%s: offsets[n+1] (past the end)", name);
    report_guard(r, what, &offsets[BATCH_RAYS + 1], sizeof offsets[BATCH_RAYS + 1]);
    for (i = 0; i < cap; i++) {
        snprintf(what, sizeof what, "%s: hit record %lld vs the full call", name, (long long)i);
        if (!report_same_hit(r, what, &hits[i], &full_hits[i]))
            break;
    }
    snprintf(what, sizeof what, "%s: records from cap on", name);
    report_guard(r, what, &hits[cap], (size_t)(ALL_CAP + 1 - cap) * sizeof hits[0]);
}

void check_all_batch_ok(case_report *r, const intersect_setup *s,
                        const isect_hit *reference, int ref_count)
{
    static const char name[] = "isect_intersect_all_batch";
    isect_ray rays[BATCH_RAYS];
    int64_t offsets[BATCH_RAYS + 2];
    isect_hit hits[ALL_CAP + 1];
    int64_t got, total = (int64_t)(BATCH_RAYS - 1) * ref_count + 1, written;
    char what[160];

    batch_rays_make(&s->c->ray, rays);
    guard_fill(offsets, sizeof offsets);
    guard_fill(hits, sizeof hits);
    got = isect_intersect_all_batch(&s->shape, rays, BATCH_RAYS, s->opts, offsets, hits,
                                    ALL_CAP);
    if (!report_int(r, "isect_intersect_all_batch: return (total hits)", got, total) ||
        got < 0)
        return;
    written = got < ALL_CAP ? got : ALL_CAP;
    if (check_offsets(r, name, offsets, ref_count, written))
        check_csr_hits(r, offsets, hits, reference);
    report_guard(r, "isect_intersect_all_batch: offsets[n+1] (past the end)",
                 &offsets[BATCH_RAYS + 1], sizeof offsets[BATCH_RAYS + 1]);
    snprintf(what, sizeof what, "isect_intersect_all_batch: records past the %lld written",
             (long long)written);
    report_guard(r, what, &hits[written], (size_t)(ALL_CAP + 1 - written) * sizeof hits[0]);

    /* total >= 1 always (the bad ray's record), so total - 1 is a valid cap. */
    check_all_batch_short(r, s, rays, total - 1, total, offsets, hits);
    if (total - 1 != 0)
        check_all_batch_short(r, s, rays, 0, total, offsets, hits);
}

/* Every ray in the batch is bad: each gets INVALID and the calls succeed. */
static void check_batch_all_invalid(case_report *r, const intersect_setup *s,
                                    const isect_ray *rays)
{
    isect_hit closest[BATCH_RAYS + 1], hits[BATCH_RAYS + 1];
    int64_t offsets[BATCH_RAYS + 2], got;
    char what[160];
    int i;

    guard_fill(closest, sizeof closest);
    got = isect_intersect_batch(&s->shape, rays, BATCH_RAYS, s->opts, closest);
    if (report_int(r, "isect_intersect_batch with only bad rays: return", got, 0)) {
        for (i = 0; i < BATCH_RAYS; i++) {
            snprintf(what, sizeof what, "isect_intersect_batch: bad ray %d", i);
            report_invalid_record(r, what, &closest[i]);
        }
    }
    guard_fill(offsets, sizeof offsets);
    guard_fill(hits, sizeof hits);
    got = isect_intersect_all_batch(&s->shape, rays, BATCH_RAYS, s->opts, offsets, hits,
                                    BATCH_RAYS + 1);
    if (!report_int(r, "isect_intersect_all_batch with only bad rays: return", got,
                    BATCH_RAYS))
        return;
    for (i = 0; i <= BATCH_RAYS; i++) {
        snprintf(what, sizeof what, "isect_intersect_all_batch with only bad rays: offsets[%d]",
                 i);
        report_int(r, what, offsets[i], i);
    }
    for (i = 0; i < BATCH_RAYS; i++) {
        snprintf(what, sizeof what, "isect_intersect_all_batch: bad ray %d record", i);
        report_invalid_record(r, what, &hits[i]);
    }
}

/* A bad shape or opts: both calls fail with the case's status and write
 * nothing at all. */
static void check_batch_rejected(case_report *r, const intersect_setup *s,
                                 const isect_ray *rays)
{
    isect_hit closest[BATCH_RAYS + 1], hits[ALL_CAP + 1];
    int64_t offsets[BATCH_RAYS + 2], got;

    guard_fill(closest, sizeof closest);
    got = isect_intersect_batch(&s->shape, rays, BATCH_RAYS, s->opts, closest);
    report_status(r, "isect_intersect_batch", (int)got, s->c->status);
    if (got < 0)
        report_guard(r, "isect_intersect_batch: output after an error", closest,
                     sizeof closest);
    guard_fill(offsets, sizeof offsets);
    guard_fill(hits, sizeof hits);
    got = isect_intersect_all_batch(&s->shape, rays, BATCH_RAYS, s->opts, offsets, hits,
                                    ALL_CAP);
    report_status(r, "isect_intersect_all_batch", (int)got, s->c->status);
    if (got < 0) {
        report_guard(r, "isect_intersect_all_batch: offsets after an error", offsets,
                     sizeof offsets);
        report_guard(r, "isect_intersect_all_batch: hits after an error", hits, sizeof hits);
    }
}

void check_batch_error(case_report *r, const intersect_setup *s)
{
    isect_ray rays[BATCH_RAYS];
    int bad_ray = ray_status(&s->c->ray);

    batch_rays_make(&s->c->ray, rays);
    /* When the case's own ray is bad and that is the expected error, the
     * batch calls mark rays instead of failing. (A case whose shape is bad
     * in the same way as its ray would be ambiguous; the corpus has none.) */
    if (bad_ray != ISECT_OK && bad_ray == s->c->status)
        check_batch_all_invalid(r, s, rays);
    else
        check_batch_rejected(r, s, rays);
}
