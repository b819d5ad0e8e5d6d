/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_spawn.c — op "spawn": isect_spawn_ray from the first hit of the
 * primary ray, then the secondary ray (tests/cases/README.md, "spawn").
 *
 * The first hit is the closest-hit record of isect_intersect_batch (bit for
 * bit the first hit isect_intersect reports; the corpus checks that on every
 * intersect case), so a primary ray that misses hands isect_spawn_ray the
 * batch's MISS record, which it must refuse. A spawned ray must carry dir
 * unchanged, tmin = 0, tmax = +inf and an origin within SPAWN_MAX_ULPS ulps
 * (of the hit point's largest coordinate) of the hit point; its hits, through
 * isect_intersect and the closest-hit batch, are the case's expectation.
 */
#include "corpus_checks.h"
#include "corpus_hits.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* How far (in ulps of the hit point's largest coordinate) the spawned origin
 * may lie from the hit point, per coordinate. */
#define SPAWN_MAX_ULPS 8.0

/* The spacing of the doubles at m >= 0 (the smallest subnormal at 0). */
static double ulp_at(double m)
{
    return nextafter(m, INFINITY) - m;
}

/* out is the ray isect_spawn_ray made from hit with direction dir. */
static void check_spawned_ray(case_report *r, const isect_hit *hit, const double dir[3],
                              const isect_ray *out)
{
    double largest = 0.0, unit;
    int k;

    if (memcmp(out->dir, dir, sizeof out->dir) != 0)
        report_fail(r, "isect_spawn_ray: out.dir (expected %a %a %a, got %a %a %a)", dir[0], dir[1],
                    dir[2], out->dir[0], out->dir[1], out->dir[2]);
    if (!(out->tmin == 0.0))
        report_fail(r, "isect_spawn_ray: out.tmin (expected 0, got %a)", out->tmin);
    if (!(out->tmax == INFINITY))
        report_fail(r, "isect_spawn_ray: out.tmax (expected +inf, got %a)", out->tmax);
    for (k = 0; k < 3; k++)
        if (fabs(hit->point[k]) > largest)
            largest = fabs(hit->point[k]);
    unit = ulp_at(largest);
    for (k = 0; k < 3; k++) {
        double off = fabs(out->org[k] - hit->point[k]);
        if (!(off <= SPAWN_MAX_ULPS * unit))
            report_fail(r, "isect_spawn_ray: out.org[%d] %.17g is %.3g ulps from the hit point %.17g "
                        "(expected at most %g)", k, out->org[k], off / unit, hit->point[k],
                        SPAWN_MAX_ULPS);
    }
}

void check_spawn_case(const corpus_case *c, case_report *r)
{
    isect_xform xform;
    isect_shape shape = c->shape.desc;
    isect_hit first, hits[CORPUS_HIT_CAP], closest;
    isect_ray out;
    int64_t primary;
    int status, count, written;

    if (!transform_setup(c, r, &xform, &shape.xform))
        return;
    guard_fill(&first, sizeof first);
    primary = isect_intersect_batch(&shape, &c->ray, 1, NULL, &first);
    if (primary < 0) {
        report_fail(r, "isect_intersect_batch of the primary ray: status %lld (a spawn case's primary "
                    "ray must be valid)", (long long)primary);
        return;
    }

    guard_fill(&out, sizeof out);
    status = isect_spawn_ray(&shape, &first, c->spawn_dir, &out);
    if (!report_status(r, "isect_spawn_ray", status, c->status) || status != ISECT_OK)
        return;
    check_spawned_ray(r, &first, c->spawn_dir, &out);

    guard_fill(hits, sizeof hits);
    count = isect_intersect(&shape, &out, NULL, hits, CORPUS_HIT_CAP);
    if (count < 0) {
        report_status(r, "isect_intersect of the spawned ray", count, ISECT_OK);
        return;
    }
    written = count < CORPUS_HIT_CAP ? count : CORPUS_HIT_CAP;
    report_expected_hits(r, "isect_intersect of the spawned ray", c, hits, count, written);

    guard_fill(&closest, sizeof closest);
    if (isect_intersect_batch(&shape, &out, 1, NULL, &closest) < 0)
        report_fail(r, "isect_intersect_batch of the spawned ray failed");
    else if (count == 0)
        report_miss_record(r, "isect_intersect_batch of the spawned ray", &closest);
    else
        report_same_hit(r, "isect_intersect_batch of the spawned ray vs its first hit", &closest,
                        &hits[0]);
}
