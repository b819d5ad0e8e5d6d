/*
 * lanes_batch.h — the lane batch loop, written once and compiled once per
 * instruction set: define LANE_ISA (core/lanes.h) and LANE_SUFFIX before
 * including it (api/lanes_*.c). See api/lanes.h for what it promises.
 */
#ifndef ISECT_LANES_BATCH_H
#define ISECT_LANES_BATCH_H

#include "api/lanes.h"
#include "prim/sphere_lanes.h"

#define LANES_CAT2(a, b) a##_##b
#define LANES_CAT(a, b) LANES_CAT2(a, b)
#define LANES_FN(name) LANES_CAT(name, LANE_SUFFIX)

/* A fast kernel, over the shape's constants `prep` (prepared once per
 * batch): a screen that clears the lanes certainly missing the shape
 * (NULL: none), and the first hit of LANE_W object-space rays. */
typedef vm (*lanes_screen)(const void *prep, const lane_ray *r);
typedef void (*lanes_kernel)(const void *prep, const lane_ray *r, lane_hit *h);

static ALWAYS_INLINE vm LANES_FN(screen_sphere)(const void *prep, const lane_ray *r)
{
    return sphere_lanes_screen((const sphere_prep *)prep, r);
}
static ALWAYS_INLINE void LANES_FN(kernel_sphere)(const void *prep, const lane_ray *r, lane_hit *h)
{
    sphere_lanes_first((const sphere_prep *)prep, r, h);
}

/* Rays are taken LANES_CHUNK at a time through two passes: the screen over
 * all of them (bad rays and certain misses are recorded there), then the
 * kernel over the rest, packed LANE_W to a block. */
#define LANES_CHUNK 256

/* The object-space rays of a chunk, field by field (org, dir, tmin, tmax). */
typedef struct lanes_scratch {
    double field[8][LANES_CHUNK];
} lanes_scratch;

static ALWAYS_INLINE void LANES_FN(scratch_put)(lanes_scratch *sc, int at, const lane_ray *lr)
{
    for (int k = 0; k < 3; k++) {
        vd_store(&sc->field[k][at], lr->org[k]);
        vd_store(&sc->field[3 + k][at], lr->dir[k]);
    }
    vd_store(&sc->field[6][at], lr->tmin);
    vd_store(&sc->field[7][at], lr->tmax);
}

/* Lane k of lr from entry idx[k] of the scratch. */
static ALWAYS_INLINE void LANES_FN(scratch_get)(const lanes_scratch *sc, const int idx[LANE_W],
                                                lane_ray *lr)
{
    vd v[8];
    for (int c = 0; c < 8; c++)
        v[c] = vd_gather_idx(sc->field[c], idx);
    for (int k = 0; k < 3; k++) {
        lr->org[k] = v[k];
        lr->dir[k] = v[3 + k];
    }
    lr->tmin = v[6];
    lr->tmax = v[7];
}

/* The miss record, written without a call (most rays of a batch). */
static ALWAYS_INLINE void LANES_FN(put_miss)(isect_hit *out)
{
    static const isect_hit miss = { INFINITY, { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 0.0 },
                                    { 0.0, 0.0 }, -1, ISECT_MISS };
    *out = miss;
}

/*
 * The loop. A transformed shape's rays are taken to object space in the
 * lanes, by the arithmetic of xform_ray_unchecked (a ray the transform
 * takes out of the finite doubles is INVALID, as shape_ray_first reports
 * it); a lane the kernel defers runs through shape_ray_first; so do the
 * last n mod LANE_W rays of the batch.
 */
static ALWAYS_INLINE int64_t LANES_FN(loop)(lanes_screen screen, lanes_kernel kernel,
                                            const void *prep, const shape_family *f,
                                            const isect_shape *s,
                                            const isect_ray *rays, int64_t n,
                                            const isect_params *prm, isect_hit *closest)
{
    int64_t hit_count = 0, base = 0;
    int64_t full = n - n % LANE_W;
    lanes_scratch sc;
    for (; base < full; base += LANES_CHUNK) {
        int chunk = full - base < LANES_CHUNK ? (int)(full - base) : LANES_CHUNK;
        int cand[LANES_CHUNK];
        int cand_count = 0;

        /* Pass 1: validity, object space, screen. */
        for (int i = 0; i < chunk; i += LANE_W) {
            const isect_ray *at[LANE_W];
            for (int lane = 0; lane < LANE_W; lane++)
                at[lane] = &rays[base + i + lane];
            lane_ray lr;
            lane_ray_load(at, &lr);
            vm valid = lane_ray_valid(&lr);
            if (s->xform != NULL) {
                lane_ray_xform(s->xform, &lr);
                valid = vm_and(valid, lane_ray_valid(&lr));
            }
            unsigned ok = vm_bits(valid);
            unsigned maybe = (screen != NULL ? vm_bits(screen(prep, &lr)) : LANE_ALL) & ok;
            LANES_FN(scratch_put)(&sc, i, &lr);
            /* Without branches on the outcome (random rays would
             * mispredict half of them): every record starts as a miss,
             * candidates are appended by a counted store, and the kernel
             * overwrites the records of the candidates it finds hits for. */
            for (int lane = 0; lane < LANE_W; lane++) {
                LANES_FN(put_miss)(&closest[base + i + lane]);
                cand[cand_count] = i + lane;
                cand_count += (int)((maybe >> lane) & 1u);
            }
            if (ok != LANE_ALL)
                for (int lane = 0; lane < LANE_W; lane++)
                    if (!(ok & (1u << lane)))
                        hit_set_miss(&closest[base + i + lane], ISECT_INVALID);
        }

        /* Pass 2: the kernel on the candidates, the last block padded with
         * copies of the last candidate (computed, not written). */
        for (int c = 0; c < cand_count; c += LANE_W) {
            int idx[LANE_W];
            for (int lane = 0; lane < LANE_W; lane++)
                idx[lane] = cand[c + lane < cand_count ? c + lane : cand_count - 1];
            lane_ray lr;
            LANES_FN(scratch_get)(&sc, idx, &lr);
            lane_hit h;
            kernel(prep, &lr, &h);

            enum { T, PX, PY, PZ, NX, NY, NZ, U, V, PRIM, KIND, FIELDS };
            double field[FIELDS][LANE_W];
            const vd *src[FIELDS] = { &h.t, &h.point[0], &h.point[1], &h.point[2], &h.normal[0],
                                      &h.normal[1], &h.normal[2], &h.uv[0], &h.uv[1], &h.prim,
                                      &h.kind };
            for (int k = 0; k < FIELDS; k++)
                vd_store(field[k], *src[k]);
            unsigned found = vm_bits(h.found), slow = vm_bits(h.slow);
            int lanes = cand_count - c < LANE_W ? cand_count - c : LANE_W;
            for (int lane = 0; lane < lanes; lane++) {
                int64_t i = base + idx[lane];
                isect_hit *out = &closest[i];
                if (slow & (1u << lane)) {
                    hit_count += batch_record(out, shape_ray_first(f, s, &rays[i], prm, out));
                } else if (found & (1u << lane)) {
                    out->t = field[T][lane];
                    out->point[0] = field[PX][lane];
                    out->point[1] = field[PY][lane];
                    out->point[2] = field[PZ][lane];
                    out->normal[0] = field[NX][lane];
                    out->normal[1] = field[NY][lane];
                    out->normal[2] = field[NZ][lane];
                    out->uv[0] = field[U][lane];
                    out->uv[1] = field[V][lane];
                    out->prim = (int32_t)field[PRIM][lane];
                    out->kind = (int32_t)field[KIND][lane];
                    shape_hits_to_world(s, out, 1);
                    hit_count++;
                } /* else: the miss record of pass 1 stands */
            }
        }
    }
    for (int64_t i = full; i < n; i++) {
        int found = ray_check(&rays[i]);
        if (found == ISECT_OK)
            found = shape_ray_first(f, s, &rays[i], prm, &closest[i]);
        hit_count += batch_record(&closest[i], found);
    }
    return hit_count;
}

static int64_t LANES_FN(batch_sphere)(const shape_family *f, const isect_shape *s,
                                      const isect_ray *rays, int64_t n, const isect_params *prm,
                                      isect_hit *closest)
{
    sphere_prep sp;
    sphere_prepare(s->data, prm->eps, &sp);
    return LANES_FN(loop)(LANES_FN(screen_sphere), LANES_FN(kernel_sphere), &sp, f, s, rays, n,
                          prm, closest);
}

lanes_batch_fn LANES_FN(lanes_batch)(int32_t type)
{
    switch (type) {
    case ISECT_SPHERE:
        return LANES_FN(batch_sphere);
    default:
        return NULL;
    }
}

#endif /* ISECT_LANES_BATCH_H */
