/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes_batch.h — the lane batch loop, written once and compiled once per
 * instruction set: define LANE_ISA (core/lanes.h) and LANE_SUFFIX before
 * including it (api/lanes_*.c). See api/lanes.h for what it promises.
 */
#ifndef ISECT_LANES_BATCH_H
#define ISECT_LANES_BATCH_H

#include "api/lanes.h"
#include "prim/box_lanes.h"
#include "prim/convex_lanes.h"
#include "prim/plane_lanes.h"
#include "prim/sphere_lanes.h"
#include "prim/triangle_lanes.h"
#include "prim/polygon_lanes.h"
#include "prim/ellipsoid_lanes.h"
#include "prim/cylinder_lanes.h"
#include "prim/quadric_lanes.h"

#define LANES_CAT2(a, b) a##_##b
#define LANES_CAT(a, b) LANES_CAT2(a, b)
#define LANES_FN(name) LANES_CAT(name, LANE_SUFFIX)

/* A fast kernel, over the shape's constants `prep` (prepared once per
 * batch): a screen that clears the lanes certainly missing the shape
 * (NULL: none), and the first hit of LANE_W object-space rays. */
typedef vm (*lanes_screen)(const void *prep, const lane_ray *r);
typedef void (*lanes_kernel)(const void *prep, const lane_ray *r, lane_hit *h);

static ALWAYS_INLINE void LANES_FN(kernel_plane)(const void *prep, const lane_ray *r, lane_hit *h)
{
    plane_lanes_first((const plane_prep *)prep, r, h);
}

static ALWAYS_INLINE void LANES_FN(kernel_box)(const void *prep, const lane_ray *r, lane_hit *h)
{
    box_lanes_first((const box_prep *)prep, r, h);
}

static ALWAYS_INLINE void LANES_FN(kernel_convex)(const void *prep, const lane_ray *r, lane_hit *h)
{
    convex_lanes_first((const convex_prep *)prep, r, h);
}

static ALWAYS_INLINE vm LANES_FN(screen_triangle)(const void *prep, const lane_ray *r)
{
    return tri_lanes_screen((const tri_prep *)prep, r);
}
static ALWAYS_INLINE void LANES_FN(kernel_triangle)(const void *prep, const lane_ray *r, lane_hit *h)
{
    tri_lanes_first((const tri_prep *)prep, r, h);
}

static ALWAYS_INLINE void LANES_FN(kernel_polygon)(const void *prep, const lane_ray *r, lane_hit *h)
{
    poly_lanes_first((const poly_prep *)prep, r, h);
}

/* Rays are taken LANES_CHUNK at a time through two passes: the screen over
 * all of them (bad rays and certain misses are recorded there), then the
 * kernel over the rest, packed LANE_W to a block. */
#define LANES_CHUNK 256

/* LANE_W rays from the records at rows[k] (object space). */
static ALWAYS_INLINE void LANES_FN(load)(const isect_ray *const at[LANE_W], lane_ray *lr)
{
    const double *rows[LANE_W];
    for (int k = 0; k < LANE_W; k++)
        rows[k] = at[k]->org;
    vd col[8];
    vd_load_rows8(rows, col);
    lr->org[0] = col[0];
    lr->org[1] = col[1];
    lr->org[2] = col[2];
    lr->dir[0] = col[3];
    lr->dir[1] = col[4];
    lr->dir[2] = col[5];
    lr->tmin = col[6];
    lr->tmax = col[7];
}

/*
 * The records of LANE_W lanes: the hit where found, the miss record where
 * not (it is already there, written by pass 1; writing it again keeps the
 * stores unconditional). The first 64 bytes of each record (t, point,
 * normal, u) go out transposed, the last 16 (v, prim, kind) lane by lane.
 * Lanes may repeat a record (the padding of the last block): they write
 * the same bytes.
 */
static ALWAYS_INLINE void LANES_FN(store)(const lane_hit *h, isect_hit *const out[LANE_W])
{
    vm found = h->found;
    vd inf = vd_set1(INFINITY), zero = vd_zero();
    vd col[8] = { vd_sel(found, h->t, inf),
                  vd_sel(found, h->point[0], zero), vd_sel(found, h->point[1], zero),
                  vd_sel(found, h->point[2], zero), vd_sel(found, h->normal[0], zero),
                  vd_sel(found, h->normal[1], zero), vd_sel(found, h->normal[2], zero),
                  vd_sel(found, h->uv[0], zero) };
    double *rows[LANE_W];
    for (int k = 0; k < LANE_W; k++)
        rows[k] = &out[k]->t;
    vd_store_rows8(rows, col);
    double v[LANE_W], prim[LANE_W], kind[LANE_W];
    vd_store(v, vd_sel(found, h->uv[1], zero));
    vd_store(prim, vd_sel(found, h->prim, vd_set1(-1.0)));
    vd_store(kind, vd_sel(found, h->kind, vd_set1((double)ISECT_MISS)));
    for (int k = 0; k < LANE_W; k++) {
        out[k]->uv[1] = v[k];
        out[k]->prim = (int32_t)prim[k];
        out[k]->kind = (int32_t)kind[k];
    }
}

/* The miss record, written without a call (most rays of a batch). */
static ALWAYS_INLINE void LANES_FN(put_miss)(isect_hit *out)
{
    static const isect_hit miss = { INFINITY, { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 0.0 },
                                    { 0.0, 0.0 }, -1, ISECT_MISS };
    *out = miss;
}

/* The rays at[] in object space and which of them are valid (ray_check
 * of the world ray and, for a transformed shape, of the object ray). */
static ALWAYS_INLINE vm LANES_FN(load_object)(const isect_shape *s, const isect_ray *const at[LANE_W],
                                              lane_ray *lr)
{
    LANES_FN(load)(at, lr);
    vm valid = lane_ray_valid(lr);
    if (s->xform != NULL) {
        lane_ray_xform(s->xform, lr);
        valid = vm_and(valid, lane_ray_valid(lr));
    }
    return valid;
}

/* The kernel's records for lanes out[] (valid[] the lanes of good rays;
 * lanes beyond `lanes` repeat the last one), the deferred lanes through
 * shape_ray_first, bad rays INVALID; returns the hits among the first
 * `lanes`. cull_exit: ISECT_CULL_BACK on a thin surface, whose EXIT hits
 * the dispatcher drops (shape.c: analytic_hit_first), so a culled lane
 * gets the MISS record as there. */
static ALWAYS_INLINE int64_t LANES_FN(finish)(lane_hit *h, unsigned valid, int lanes,
                                              const shape_family *f, const isect_shape *s,
                                              const isect_ray *const world[LANE_W],
                                              isect_hit *const out[LANE_W],
                                              const isect_params *prm, int cull_exit)
{
    unsigned slow = vm_bits(h->slow) & valid;
    h->found = vm_andnot(h->found, h->slow);
    if (cull_exit)
        h->found = vm_andnot(h->found, vd_eq(h->kind, vd_set1((double)ISECT_EXIT)));
    if (s->xform != NULL)
        lane_hit_to_world(s->xform, h);
    LANES_FN(store)(h, out);
    unsigned real = (1u << lanes) - 1u;
    int64_t hits = lane_count(vm_bits(h->found) & valid & real);
    if (((slow | ~valid) & real) != 0) {
        for (int lane = 0; lane < lanes; lane++) {
            if (!(valid & (1u << lane)))
                hit_set_miss(out[lane], ISECT_INVALID);
            else if (slow & (1u << lane))
                hits += batch_record(out[lane], shape_ray_first(f, s, world[lane], prm, out[lane]));
        }
    }
    return hits;
}

/*
 * The loop. A transformed shape's rays are taken to object space in the
 * lanes, by the arithmetic of xform_ray_unchecked (a ray the transform
 * takes out of the finite doubles is INVALID, as shape_ray_first reports
 * it); a lane the kernel defers runs through shape_ray_first; so do the
 * last n mod LANE_W rays of the batch. Without a screen every ray goes
 * through the kernel in one pass; with one, in two (see LANES_CHUNK).
 */
static ALWAYS_INLINE int64_t LANES_FN(loop)(lanes_screen screen, lanes_kernel kernel,
                                            const void *prep, const shape_family *f,
                                            const isect_shape *s, const isect_ray *rays,
                                            int64_t n, const isect_params *prm,
                                            isect_hit *closest)
{
    int64_t hit_count = 0, base = 0;
    int64_t full = n - n % LANE_W;
    int cull_exit = (prm->flags & ISECT_CULL_BACK) && !shape_is_solid(f, s);
    if (screen == NULL) {
        for (int64_t i = 0; i < full; i += LANE_W) {
            const isect_ray *at[LANE_W];
            isect_hit *out[LANE_W];
            for (int lane = 0; lane < LANE_W; lane++) {
                at[lane] = &rays[i + lane];
                out[lane] = &closest[i + lane];
            }
            lane_ray lr;
            unsigned valid = vm_bits(LANES_FN(load_object)(s, at, &lr));
            lane_hit h;
            kernel(prep, &lr, &h);
            hit_count += LANES_FN(finish)(&h, valid, LANE_W, f, s, at, out, prm, cull_exit);
        }
        base = full;
    }
    isect_ray object[LANES_CHUNK];
    for (; base < full; base += LANES_CHUNK) {
        int chunk = full - base < LANES_CHUNK ? (int)(full - base) : LANES_CHUNK;
        const isect_ray *src = s->xform != NULL ? object : rays + base;
        int cand[LANES_CHUNK + LANE_W];
        int cand_count = 0;

        /* Pass 1: validity, object space, screen. */
        for (int i = 0; i < chunk; i += LANE_W) {
            const isect_ray *at[LANE_W];
            for (int lane = 0; lane < LANE_W; lane++)
                at[lane] = &rays[base + i + lane];
            lane_ray lr;
            unsigned ok = vm_bits(LANES_FN(load_object)(s, at, &lr));
            if (s->xform != NULL) {
                double *rows[LANE_W];
                for (int lane = 0; lane < LANE_W; lane++)
                    rows[lane] = object[i + lane].org;
                const vd col[8] = { lr.org[0], lr.org[1], lr.org[2], lr.dir[0],
                                    lr.dir[1], lr.dir[2], lr.tmin, lr.tmax };
                vd_store_rows8(rows, col);
            }
            unsigned maybe = vm_bits(screen(prep, &lr)) & ok;
            /* Without branches on the outcome (random rays would
             * mispredict half of them): every record starts as a miss,
             * candidates are appended by a counted store, and the kernel
             * overwrites the records of the candidates. */
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
         * copies of the last candidate. */
        for (int c = cand_count; c < cand_count + LANE_W; c++)
            cand[c] = cand_count > 0 ? cand[cand_count - 1] : 0;
        for (int c = 0; c < cand_count; c += LANE_W) {
            const isect_ray *at[LANE_W], *world[LANE_W];
            isect_hit *out[LANE_W];
            for (int lane = 0; lane < LANE_W; lane++) {
                at[lane] = &src[cand[c + lane]];
                world[lane] = &rays[base + cand[c + lane]];
                out[lane] = &closest[base + cand[c + lane]];
            }
            lane_ray lr;
            LANES_FN(load)(at, &lr);
            lane_hit h;
            kernel(prep, &lr, &h);
            int lanes = cand_count - c < LANE_W ? cand_count - c : LANE_W;
            hit_count += LANES_FN(finish)(&h, LANE_ALL, lanes, f, s, world, out, prm, cull_exit);
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

/*
 * A shape with a screen: X_lanes_screen and X_lanes_first over its
 * constants (type PREP_T), prepared once per batch by the statement
 * PREPARE (of s, prm, prep), run by the loop.
 */
#define LANES_SHAPE(X, PREP_T, PREPARE)                                                        \
    static ALWAYS_INLINE vm LANES_FN(screen_##X)(const void *prep, const lane_ray *r)         \
    {                                                                                          \
        return X##_lanes_screen((const PREP_T *)prep, r);                                      \
    }                                                                                          \
    static ALWAYS_INLINE void LANES_FN(kernel_##X)(const void *prep, const lane_ray *r,       \
                                                   lane_hit *h)                                \
    {                                                                                          \
        X##_lanes_first((const PREP_T *)prep, r, h);                                           \
    }                                                                                          \
    static int64_t LANES_FN(batch_##X)(const shape_family *f, const isect_shape *s,           \
                                       const isect_ray *rays, int64_t n,                       \
                                       const isect_params *prm, isect_hit *closest)            \
    {                                                                                          \
        PREP_T prep;                                                                           \
        PREPARE;                                                                               \
        return LANES_FN(loop)(LANES_FN(screen_##X), LANES_FN(kernel_##X), &prep, f, s, rays,   \
                              n, prm, closest);                                                \
    }

LANES_SHAPE(sphere, sphere_prep, sphere_prepare(s->data, prm->eps, &prep))
LANES_SHAPE(ellipsoid, ellipsoid_prep, ellipsoid_prepare(s->data, prm->eps, &prep))
LANES_SHAPE(cylinder, cylinder_prep,
            cylinder_prepare(s->data, cylinder_kind(s->type, s->flags), prm->eps, &prep))
LANES_SHAPE(quadric, quadric_prep, quadric_prepare(s->data, prm->eps, &prep))

static int64_t LANES_FN(batch_plane)(const shape_family *f, const isect_shape *s,
                                     const isect_ray *rays, int64_t n, const isect_params *prm,
                                     isect_hit *closest)
{
    plane_prep pp;
    plane_prepare(s->data, prm->eps, &pp);
    return LANES_FN(loop)(NULL, LANES_FN(kernel_plane), &pp, f, s, rays, n, prm, closest);
}

static int64_t LANES_FN(batch_box)(const shape_family *f, const isect_shape *s,
                                   const isect_ray *rays, int64_t n, const isect_params *prm,
                                   isect_hit *closest)
{
    box_prep bp;
    box_prepare(s->data, &bp);
    return LANES_FN(loop)(NULL, LANES_FN(kernel_box), &bp, f, s, rays, n, prm, closest);
}

static int64_t LANES_FN(batch_convex)(const shape_family *f, const isect_shape *s,
                                      const isect_ray *rays, int64_t n, const isect_params *prm,
                                      isect_hit *closest)
{
    convex_prep cp;
    convex_prepare(s->data, s->n, prm->eps, &cp);
    return LANES_FN(loop)(NULL, LANES_FN(kernel_convex), &cp, f, s, rays, n, prm, closest);
}

static int64_t LANES_FN(batch_triangle)(const shape_family *f, const isect_shape *s,
                                        const isect_ray *rays, int64_t n, const isect_params *prm,
                                        isect_hit *closest)
{
    tri_prep tp;
    triangle_prepare(s->data, &tp);
    return LANES_FN(loop)(LANES_FN(screen_triangle), LANES_FN(kernel_triangle), &tp, f, s, rays, n,
                          prm, closest);
}

static int64_t LANES_FN(batch_polygon)(const shape_family *f, const isect_shape *s,
                                       const isect_ray *rays, int64_t n, const isect_params *prm,
                                       isect_hit *closest)
{
    poly_prep pp;
    polygon_prepare(s->data, s->n, s->flags, &pp);
    return LANES_FN(loop)(NULL, LANES_FN(kernel_polygon), &pp, f, s, rays, n, prm, closest);
}

lanes_batch_fn LANES_FN(lanes_batch)(int32_t type)
{
    switch (type) {
    case ISECT_TRIANGLE:
        return LANES_FN(batch_triangle);
    case ISECT_POLYGON:
        return LANES_FN(batch_polygon);
    case ISECT_PLANE:
        return LANES_FN(batch_plane);
    case ISECT_SPHERE:
        return LANES_FN(batch_sphere);
    case ISECT_AABB:
        return LANES_FN(batch_box);
    case ISECT_CONVEX:
        return LANES_FN(batch_convex);
    case ISECT_ELLIPSOID:
        return LANES_FN(batch_ellipsoid);
    case ISECT_CYLINDER:
    case ISECT_CYLINDER_INF:
        return LANES_FN(batch_cylinder);
    case ISECT_QUADRIC:
        return LANES_FN(batch_quadric);
    default:
        return NULL;
    }
}

#endif /* ISECT_LANES_BATCH_H */
