/* SPDX-License-Identifier: Apache-2.0 */
/*
 * triangle.c — the triangle primitive, on the watertight test of
 * triangle_test.h, and what that test and the mesh share: the per-face
 * plane (triangle_plane) and the crossing's record (triangle_record, with
 * its exact path).
 */
#include "prim/triangle_test.h"
#include "prim/triangle_lanes.h"
#include "core/expansion.h"
#include "core/scaling.h"
#include "core/ratio.h"
#include "core/vec3.h"

#include <string.h>

/* The plane of a, b, c as double-doubles (triangle_lanes.h, one lane). */
static void triangle_plane_dd(const double a[3], const double b[3], const double c[3],
                              tri_plane *tp)
{
    vd av[3] = { a[0], a[1], a[2] }, bv[3] = { b[0], b[1], b[2] }, cv[3] = { c[0], c[1], c[2] };
    tri_plane_make(av, bv, cv, tp);
}

/* 1 when every coordinate is within the fast kernel's range (2^200). */
static int triangle_in_range(const double a[3], const double b[3], const double c[3])
{
    return fmax_nan(max_abs3(a), fmax_nan(max_abs3(b), max_abs3(c))) <= 0x1p200;
}

/* The exact cross product (b - a) x (c - a), scaled by one power of two
 * (the edges, then the normal, brought near 1: planar.h, xp_normalize_up). */
static void triangle_normal_exact(const double a[3], const double b[3], const double c[3], xp n[3])
{
    int e = pow2_exponent(fmax_nan(max_abs3(a), fmax_nan(max_abs3(b), max_abs3(c))));
    xp edges[6], *e1 = edges, *e2 = edges + 3, tmp;
    for (int k = 0; k < 3; k++) {
        double ak = pow2_scale(a[k], -e);
        xp_diff(&e1[k], pow2_scale(b[k], -e), ak);
        xp_diff(&e2[k], pow2_scale(c[k], -e), ak);
    }
    xp_normalize_up(edges, 6, XP_SHIFT_LIMIT);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        xp_mul(&n[k], &e1[i], &e2[j]);
        xp_mul(&tmp, &e1[j], &e2[i]);
        xp_sub(&n[k], &n[k], &tmp);
    }
    xp_normalize_up(n, 3, XP_SHIFT_LIMIT);
}

int triangle_plane(const double a[3], const double b[3], const double c[3], double normal[3],
                   int *nonzero)
{
    /* The double-double plane where it is good to ~2^-20 relative (its
     * largest component above 2^20 times every component's error bound);
     * else the exact one: tiny triangles (products below the underflow
     * threshold), huge coordinates, near-collinear vertices. */
    if (triangle_in_range(a, b, c)) {
        tri_plane tp;
        triangle_plane_dd(a, b, c, &tp);
        double v[3], big = 0.0, err = 0.0;
        for (int k = 0; k < 3; k++) {
            v[k] = tp.n[k].hi;
            big = fmax_nan(big, fabs(v[k]));
            err = fmax_nan(err, tp.err[k]);
        }
        if (big > 0x1p20 * err) {
            *nonzero = 1;
            return unit3_accurate(normal, v);
        }
    }
    xp n[3];
    triangle_normal_exact(a, b, c, n);
    double v[3];
    for (int k = 0; k < 3; k++) {
        double lo;
        xp_dd(&n[k], &v[k], &lo);
    }
    *nonzero = xp_sign(&n[0]) != 0 || xp_sign(&n[1]) != 0 || xp_sign(&n[2]) != 0;
    return *nonzero && unit3_accurate(normal, v);
}

void triangle_crossing_xp(const isect_ray *ray, const double a[3], const double b[3],
                          const double c[3], int e, int e_dir, xp *num, xp *den)
{
    xp edges[6], *e1 = edges, *e2 = edges + 3, A[3], n[3], tmp;
    for (int k = 0; k < 3; k++) {
        double ak = pow2_scale(a[k], -e);
        xp_diff(&e1[k], pow2_scale(b[k], -e), ak);
        xp_diff(&e2[k], pow2_scale(c[k], -e), ak);
        xp_diff(&A[k], ak, pow2_scale(ray->org[k], -e));
    }
    /* Each vector brought near 1 (planar.h, xp_normalize_up): N's scale
     * cancels in num/den, A's is matched on den, so num/den (and core/
     * ratio.c's comparisons of two crossings) keep their value. */
    xp_normalize_up(edges, 6, XP_SHIFT_LIMIT);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        xp_mul(&n[k], &e1[i], &e2[j]);
        xp_mul(&tmp, &e1[j], &e2[i]);
        xp_sub(&n[k], &n[k], &tmp);
    }
    xp_normalize_up(n, 3, XP_SHIFT_LIMIT);
    int shift_a = xp_normalize_up(A, 3, XP_SHIFT_LIMIT);
    xp_set(num, 0.0);
    xp_set(den, 0.0);
    for (int k = 0; k < 3; k++) {
        xp_add_mul(num, &n[k], &A[k]);
        xp_scale(&tmp, &n[k], pow2_scale(ray->dir[k], -e_dir));
        xp_add(den, den, &tmp);
    }
    for (int j = 0; j < den->n; j++)
        den->p[j] = pow2_scale(den->p[j], shift_a);
}

/*
 * The exact path of the crossing parameter: every coordinate scaled by one
 * power of two (the ray's direction by its own), the edges and a - o exact
 * as two parts, N = e1 x e2, num = N.(a - o) and den = N.dir as exact
 * expansions (triangle_crossing_xp); core/ratio.c decides den != 0 and
 * tmin <= t <= tmax exactly and rounds t = num/den to a double-double;
 * t = t' 2^(e - e_dir).
 */
static int triangle_crossing_exact(const isect_ray *ray, const double a[3], const double b[3],
                                   const double c[3], double *t_hi, double *t_lo, int *enter,
                                   int *t_shift_out, int *e_out)
{
    double m = fmax_nan(max_abs3(ray->org), fmax_nan(max_abs3(a), fmax_nan(max_abs3(b), max_abs3(c))));
    int e = pow2_exponent(m), e_dir = pow2_exponent(max_abs3(ray->dir));
    int t_shift = e - e_dir;
    xp num, den;
    triangle_crossing_xp(ray, a, b, c, e, e_dir, &num, &den);
    int in_range;
    if (!ratio_decide(&num, &den, pow2_scale(ray->tmin, -t_shift),
                      pow2_scale(ray->tmax, -t_shift), &in_range, t_hi, t_lo)
        || !in_range)
        return 0;
    *enter = xp_sign(&den) < 0;
    *t_shift_out = t_shift;
    *e_out = e;
    return 1;
}

int triangle_record(const isect_ray *ray, const double a[3], const double b[3], const double c[3],
                    const double *normal, double u, double v, isect_hit *out)
{
    double own_normal[3];
    if (normal == NULL) {
        int nonzero;
        if (!triangle_plane(a, b, c, own_normal, &nonzero))
            return 0;
        normal = own_normal;
    }
    lane_ray lr;
    lane_ray_from(&lr, ray);
    vdd t;
    int enter;
    double point[3];
    int fast = 0;
    if (triangle_in_range(a, b, c) && lane_ray_in_range(&lr, 0x1p200)) {
        tri_plane tp;
        triangle_plane_dd(a, b, c, &tp);
        tri_crossing tc;
        const vd av[3] = { a[0], a[1], a[2] }, zero[3] = { 0.0, 0.0, 0.0 };
        tri_crossing_solve(&tp, av, zero, 0.0, &lr, &tc);
        if (tc.out)
            return 0;
        if (tc.in) {
            fast = 1;
            t = tc.t;
            enter = tc.enter;
            lane_point_on_ray(&lr, t, point);
        }
    }
    if (!fast) {
        int t_shift, e;
        if (!triangle_crossing_exact(ray, a, b, c, &t.hi, &t.lo, &enter, &t_shift, &e))
            return 0;
        /* the point from t as a double-double, in the scaled units */
        isect_ray scaled;
        for (int k = 0; k < 3; k++) {
            scaled.org[k] = pow2_scale(ray->org[k], -e);
            scaled.dir[k] = pow2_scale(ray->dir[k], -(e - t_shift));
        }
        scaled.tmin = -INFINITY;
        scaled.tmax = INFINITY;
        lane_ray sl;
        lane_ray_from(&sl, &scaled);
        lane_point_on_ray(&sl, t, point);
        for (int k = 0; k < 3; k++)
            point[k] = pow2_scale(point[k], e);
        t.hi = pow2_scale(t.hi, t_shift);
        if (!isfinite(t.hi))
            return 0; /* beyond the double range: not a point of the ray */
    }
    out->t = fmin(fmax(t.hi, ray->tmin), ray->tmax) + 0.0;
    v3_copy(out->point, point);
    v3_copy(out->normal, normal);
    out->uv[0] = u;
    out->uv[1] = v;
    out->prim = -1;
    out->kind = enter ? ISECT_ENTER : ISECT_EXIT;
    return 1;
}

void triangle_prepare(const double *data, tri_prep *tp)
{
    const double *a = data, *b = data + 3, *c = data + 6;
    memcpy(tp->v, data, sizeof tp->v);
    tri_plane pl;
    triangle_plane_dd(a, b, c, &pl);
    for (int k = 0; k < 3; k++) {
        tp->n_hi[k] = pl.n[k].hi;
        tp->n_lo[k] = pl.n[k].lo;
        tp->n_err[k] = pl.err[k];
    }
    int nonzero;
    tp->degenerate = !triangle_plane(a, b, c, tp->normal, &nonzero);
    tp->in_range = triangle_in_range(a, b, c);
}

int triangle_check(const isect_shape *s)
{
    return all_finite(s->data, 9) ? ISECT_OK : ISECT_E_NONFINITE;
}

/* The fast kernel at LANE_W = 1 (the batch's, so both give the same
 * record), then for the rays it leaves undecided the exact path: the same
 * signs, each uncertain one decided exactly, and triangle_record. A ray
 * the certified signs put outside returns before the plane is prepared
 * (most rays of a scalar or all-hits call miss). */
int triangle_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                  isect_hit out[ISECT_MAX_HITS])
{
    (void)prm; /* no epsilon for faces (revision 2) */
    const double *a = s->data, *b = s->data + 3, *c = s->data + 6;
    lane_ray lr;
    lane_ray_from(&lr, ray);
    int fast_range = triangle_fast_range(&lr, a, b, c);
    if (fast_range && !tri_lanes_inside_maybe(a, b, c, &lr))
        return 0; /* the kernel's verdict too, without preparing the plane */
    tri_prep tp;
    triangle_prepare(s->data, &tp);
    if (tp.degenerate)
        return 0;
    lane_hit h;
    tri_lanes_first(&tp, &lr, &h);
    if (!h.slow) {
        if (!h.found)
            return 0;
        lane_hit_store(&h, 0, &out[0]);
        return 1;
    }
    ray_frame f;
    ray_frame_shear(ray, &f);
    return triangle_hit(&f, ray, &lr, fast_range, a, b, c, tp.normal, &out[0]);
}

/* In front of the right-hand normal of a, b, c: orient3_sign is +1 below. */
int triangle_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    const double *a = s->data, *b = s->data + 3, *c = s->data + 6;
    if (collinear3(a, b, c))
        return 1; /* degenerate */
    return -orient3_sign(a, b, c, p);
}

int triangle_tangent_side(const isect_shape *s, const double d[3], int32_t prim)
{
    (void)prim;
    if (collinear3(s->data, s->data + 3, s->data + 6))
        return 0; /* degenerate: never hit */
    return polygon_plane_sign(s->data, NULL, 3, d, 0);
}
