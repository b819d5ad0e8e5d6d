/* SPDX-License-Identifier: Apache-2.0 */
/*
 * hits.c — filling hit records and putting a kernel's hits in the order and
 * range the API promises. Kernels report every intersection of the ray's
 * whole line; the range filter, back-face culling and ordering live here.
 */
#include "prim/prim.h"

#include "core/predicates.h"
#include "core/vec3.h"

#include <string.h>

void hit_set(isect_hit *h, const isect_ray *ray, double t, const double normal[3],
             int32_t prim, int32_t kind)
{
    h->t = t;
    v3_madd(h->point, ray->org, t, ray->dir);
    v3_copy(h->normal, normal);
    h->uv[0] = 0.0;
    h->uv[1] = 0.0;
    h->prim = prim;
    h->kind = kind;
}

void hit_set_dd(isect_hit *h, const isect_ray *ray, double t_hi, double t_lo,
                const double normal[3], int32_t prim, int32_t kind)
{
    hit_set(h, ray, fmin(fmax(t_hi, ray->tmin), ray->tmax), normal, prim, kind);
    for (int k = 0; k < 3; k++) {
        double p = t_hi * ray->dir[k];
        double p_err = product_error(t_hi, ray->dir[k], p);
        double s = ray->org[k] + p;
        double s_virtual = s - ray->org[k];
        double s_err = (ray->org[k] - (s - s_virtual)) + (p - s_virtual);
        h->point[k] = s + ((s_err + p_err) + t_lo * ray->dir[k]);
    }
}

int hits_merge(const isect_hit rec[2], const int decided[2], const int in[2],
               const int32_t kind[2], const isect_hit *exact, int exact_count,
               isect_hit out[ISECT_MAX_HITS])
{
    int count = 0;
    for (int i = 0; i < 2; i++) {
        if (decided[i]) {
            if (in[i])
                out[count++] = rec[i];
            continue;
        }
        for (int k = 0; k < exact_count && count < ISECT_MAX_HITS; k++)
            if (exact[k].kind == kind[i])
                out[count++] = exact[k];
    }
    return count;
}

int32_t hit_kind_from_normal(const double dir[3], const double normal[3])
{
    return v3_dot(dir, normal) < 0.0 ? ISECT_ENTER : ISECT_EXIT;
}

void hit_set_miss(isect_hit *h, int32_t kind)
{
    memset(h, 0, sizeof *h);
    h->t = kind == ISECT_INVALID ? NAN : INFINITY;
    h->prim = -1;
    h->kind = kind;
}

/* By t alone: the sort is stable, and every kernel emits its crossings in
 * their exact order (ties by prim), so crossings whose t round to the same
 * double keep that order (an entry before its exit). */
static int hit_before(const isect_hit *a, const isect_hit *b)
{
    return a->t < b->t;
}

int hits_finish(isect_hit *h, int count, const isect_ray *ray, const isect_params *prm,
                int thin)
{
    int kept = 0;
    for (int i = 0; i < count; i++) {
        /* The comparison is false for NaN, so a NaN t can never escape. */
        if (!(h[i].t >= ray->tmin && h[i].t <= ray->tmax))
            continue;
        if (thin && (prm->flags & ISECT_CULL_BACK) && h[i].kind == ISECT_EXIT)
            continue;
        h[kept++] = h[i];
    }
    /* At most ISECT_MAX_HITS records: insertion sort, stable for equal keys. */
    for (int i = 1; i < kept; i++) {
        isect_hit x = h[i];
        int j = i;
        for (; j > 0 && hit_before(&x, &h[j - 1]); j--)
            h[j] = h[j - 1];
        h[j] = x;
    }
    return kept;
}
