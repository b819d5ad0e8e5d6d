/* SPDX-License-Identifier: Apache-2.0 */
/*
 * polygon.c — planar polygons (convex, concave, self-intersecting): the
 * plane by Newell's method, the inside test as the exact winding number of
 * the sheared frame's origin; the public isect_ray_polygon,
 * isect_polygon_normal and isect_plane_from_points.
 */
#include "prim/planar.h"
#include "prim/polygon_lanes.h"
#include "core/frame_signs.h"
#include "core/ratio.h"
#include "core/dyadic_sum.h"
#include "core/expansion.h"
#include "core/predicates.h"
#include "core/scaling.h"
#include "core/vec3.h"

#include <stddef.h>
#include <string.h>

static const double *vertex_at(const double *v, const int32_t *idx, int i)
{
    return v + 3 * (ptrdiff_t)(idx != NULL ? idx[i] : i);
}

/* 1 when every vertex lies exactly on one line (or all coincide). Stops at
 * the first triple that is not collinear, which for real faces is almost
 * always the first. */
static int vertices_collinear(const double *v, const int32_t *idx, int n)
{
    const double *p0 = vertex_at(v, idx, 0);
    int j = 1;
    while (j < n) {
        const double *pj = vertex_at(v, idx, j);
        if (pj[0] != p0[0] || pj[1] != p0[1] || pj[2] != p0[2])
            break;
        j++;
    }
    for (int k = j + 1; k < n; k++)
        if (!collinear3(p0, vertex_at(v, idx, j), vertex_at(v, idx, k)))
            return 0;
    return 1;
}

/* The largest |coordinate| of the vertices. */
static double vertex_extent(const double *v, const int32_t *idx, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m = fmax_nan(m, max_abs3(vertex_at(v, idx, i)));
    return m;
}

/* The plane exactly: N = sum (v_i - v_0) x (v_{i+1} - v_0) and the sum of
 * the vertices, as expansions of the coordinates scaled by 2^-e (the sum
 * then scaled by 2^-e; N by some power of two: the edges v_i - v_0 are
 * brought near 1 before their products, and N itself after, as planar.h's
 * xp_normalize_up does for a triangle, so that a polygon far smaller than
 * its coordinates keeps its normal above the underflow threshold. N's
 * scale cancels in every use: its direction, and num/den.) */
static void polygon_plane_exact(const double *v, const int32_t *idx, int n, int e, xp normal[3],
                                xp sum[3])
{
    const double *p0 = vertex_at(v, idx, 0);
    xp prev[3], cur[3], tmp, tmp2;
    double reach = 0.0; /* the largest |v_i - v_0| (rounded: it only picks s) */
    for (int i = 1; i < n; i++)
        for (int k = 0; k < 3; k++)
            reach = fmax(reach, fabs(pow2_scale(vertex_at(v, idx, i)[k], -e) - pow2_scale(p0[k], -e)));
    int s = reach > 0.0 ? -pow2_exponent(reach) : 0;
    s = s > 0 && s <= XP_SHIFT_LIMIT ? s : 0; /* (only up: exact) */
    for (int k = 0; k < 3; k++) {
        xp_set(&normal[k], 0.0);
        xp_set(&sum[k], pow2_scale(p0[k], -e));
        xp_set(&prev[k], 0.0);
    }
    for (int i = 1; i < n; i++) {
        const double *pi = vertex_at(v, idx, i);
        for (int k = 0; k < 3; k++) {
            xp_diff(&cur[k], pow2_scale(pi[k], -e), pow2_scale(p0[k], -e));
            for (int j = 0; j < cur[k].n; j++)
                cur[k].p[j] = pow2_scale(cur[k].p[j], s);
            xp_add_d(&sum[k], pow2_scale(pi[k], -e));
        }
        for (int k = 0; k < 3; k++) {
            int a = (k + 1) % 3, b = (k + 2) % 3;
            xp_mul(&tmp, &prev[a], &cur[b]);
            xp_mul(&tmp2, &prev[b], &cur[a]);
            xp_sub(&tmp, &tmp, &tmp2);
            xp_add(&normal[k], &normal[k], &tmp);
        }
        for (int k = 0; k < 3; k++)
            prev[k] = cur[k];
    }
    xp_normalize_up(normal, 3, XP_SHIFT_LIMIT);
}

/* The plane's double-double form from exact expansions (normal scaled so
 * its largest component lies in [0.5, 1)): 1, or 0 when N == 0. */
static int polygon_plane_from_exact(const double *v, const int32_t *idx, int n, poly_plane *pp)
{
    int e = pow2_exponent(vertex_extent(v, idx, n));
    xp normal[3], sum[3];
    polygon_plane_exact(v, idx, n, e, normal, sum);
    double hi[3], lo[3];
    for (int k = 0; k < 3; k++)
        xp_dd(&normal[k], &hi[k], &lo[k]);
    if (max_abs3(hi) == 0.0)
        return 0;
    int en = pow2_exponent(max_abs3(hi));
    for (int k = 0; k < 3; k++) {
        pp->n_hi[k] = pow2_scale(hi[k], -en);
        pp->n_lo[k] = pow2_scale(lo[k], -en);
        pp->n_err[k] = 4.0 * 0x1p-106 * fabs(pp->n_hi[k]) + 0x1p-960;
        /* the centroid: the exact sum over n, to a double-double */
        double sh, sl;
        xp_dd(&sum[k], &sh, &sl);
        double q = sh / n;
        vdd qn = two_prod(q, (double)n); /* q n needs more than 53 bits */
        double r = ((sh - qn.hi) - qn.lo) + sl;
        pp->m_hi[k] = pow2_scale(q, e);
        pp->m_lo[k] = pow2_scale(r / n, e);
    }
    pp->m_err = 8.0 * 0x1p-106 * max_abs3(pp->m_hi) + 0x1p-960;
    return unit3_accurate(pp->unit, pp->n_hi);
}

int polygon_plane(const double *v, const int32_t *idx, int n, poly_plane *pp)
{
    /* Fast: the fan from v_0 as double-doubles (triangle_lanes.h's cross
     * components, summed with TwoSum; error bound accumulated), taken when
     * its largest component beats 2^20 times the error bound; else the
     * exact plane (near-collinear or tiny polygons, huge coordinates). */
    double extent = vertex_extent(v, idx, n);
    if (extent <= 0x1p200 && extent >= 0x1p-200) {
        const double *p0 = vertex_at(v, idx, 0);
        vdd prev[3], cur[3], acc[3];
        vd err[3] = { 0.0, 0.0, 0.0 };
        double mag = 0.0;
        for (int k = 0; k < 3; k++) {
            prev[k].hi = prev[k].lo = 0.0;
            acc[k].hi = acc[k].lo = 0.0;
        }
        vdd sum[3] = { { p0[0], 0.0 }, { p0[1], 0.0 }, { p0[2], 0.0 } };
        for (int i = 1; i < n; i++) {
            const double *pi = vertex_at(v, idx, i);
            for (int k = 0; k < 3; k++) {
                cur[k] = two_sum(pi[k], -p0[k]);
                vdd sk = two_sum(sum[k].hi, pi[k]);
                sum[k].hi = sk.hi;
                sum[k].lo += sk.lo;
            }
            for (int k = 0; k < 3; k++) {
                int a = (k + 1) % 3, b = (k + 2) % 3;
                vd e;
                vdd term = tri_cross_comp(prev[a], prev[b], cur[a], cur[b], &e);
                vdd s2 = two_sum(acc[k].hi, term.hi);
                acc[k].hi = s2.hi;
                acc[k].lo += s2.lo + term.lo;
                err[k] += e;
                mag = fmax_nan(mag, fabs(acc[k].hi));
            }
            for (int k = 0; k < 3; k++)
                prev[k] = cur[k];
        }
        /* the lows' own rounding: n additions of terms below u |acc| */
        double big = 0.0, worst = 0.0;
        for (int k = 0; k < 3; k++) {
            acc[k] = two_sum(acc[k].hi, acc[k].lo);
            err[k] = err[k] * (1.0 + 0x1p-40) + 4.0 * n * 0x1p-106 * mag;
            big = fmax_nan(big, fabs(acc[k].hi));
            worst = fmax_nan(worst, err[k]);
        }
        if (big > 0x1p20 * worst && big >= 0x1p-400) {
            int en = pow2_exponent(big);
            for (int k = 0; k < 3; k++) {
                pp->n_hi[k] = pow2_scale(acc[k].hi, -en);
                pp->n_lo[k] = pow2_scale(acc[k].lo, -en);
                pp->n_err[k] = pow2_scale(err[k], -en) * (1.0 + 0x1p-40);
                double q = sum[k].hi / n;
                vdd qn = two_prod(q, (double)n);
                double r = ((sum[k].hi - qn.hi) - qn.lo) + sum[k].lo;
                pp->m_hi[k] = q;
                pp->m_lo[k] = r / n;
            }
            pp->m_err = (2.0 * n + 8.0) * 0x1p-106 * extent + 0x1p-960;
            return unit3_accurate(pp->unit, pp->n_hi);
        }
    }
    if (vertices_collinear(v, idx, n))
        return 0;
    return polygon_plane_from_exact(v, idx, n, pp);
}

int polygon_plane_exact_dd(const double *v, const int32_t *idx, int n, poly_plane *pp)
{
    if (vertices_collinear(v, idx, n))
        return 0;
    return polygon_plane_from_exact(v, idx, n, pp);
}

/*
 * The winding number of the perturbed frame origin around the exact
 * projection of the polygon (isect.h, "Tie-breaking"): face_lanes.h's
 * count where every sign it used was certified; otherwise the same count
 * with each uncertain sign (a vertex's side of the test line, the
 * orientation of an edge crossing it) decided exactly by
 * core/frame_signs.c. Either way each vertex's and each edge's verdict is a
 * function of it and the ray alone, so faces sharing them agree.
 */
static int32_t frame_winding(const ray_frame *f, const lane_ray *lr, const double *v,
                             const int32_t *idx, int n)
{
    int fast = vertex_extent(v, idx, n) <= 0x1p200 && lane_ray_in_range(lr, 0x1p200);
    face_axes fa;
    face_axes_make(lr, &fa);
    if (fast) {
        face_winding fw;
        face_winding_lanes(v, idx, n, lr, &fa, &fw);
        if (fw.certain)
            return (int32_t)fw.winding;
    }
    const double *p = vertex_at(v, idx, n - 1);
    face_wrel prev, cur;
    face_wrel_make(p, lr, &fa, &prev);
    int p_above = fast && prev.sure ? prev.above : frame_above_exact(f, p);
    int32_t winding = 0;
    for (int i = 0; i < n; i++) {
        const double *q = vertex_at(v, idx, i);
        face_wrel_make(q, lr, &fa, &cur);
        int q_above = fast && cur.sure ? cur.above : frame_above_exact(f, q);
        if (p_above != q_above) {
            double w = face_dot(prev.p.a, cur.x);
            double e = face_orient_bound(fa.m_d, prev.p.n1, cur.p.n1);
            int side = fast && w > e ? 1 : fast && w < -e ? -1 : frame_orient_exact(f, p, q);
            if (!p_above)
                winding += side > 0;  /* upward, origin on the left */
            else
                winding -= side < 0;  /* downward, origin on the right */
        }
        prev = cur;
        p = q;
        p_above = q_above;
    }
    return winding;
}

void polygon_crossing_xp(const isect_ray *ray, const double *v, const int32_t *idx, int n,
                         int e, int e_dir, xp *num, xp *den)
{
    xp normal[3], sum[3], rel[3], tmp;
    polygon_plane_exact(v, idx, n, e, normal, sum);
    /* rel = sum - n o; it and N brought near 1 as for a triangle
     * (planar.h, xp_normalize_up): N's scale cancels, rel's is matched on
     * den. */
    for (int k = 0; k < 3; k++) {
        xp_set(&rel[k], (double)n);
        xp_scale(&rel[k], &rel[k], -pow2_scale(ray->org[k], -e));
        xp_add(&rel[k], &rel[k], &sum[k]);
    }
    xp_normalize_up(normal, 3, XP_SHIFT_LIMIT);
    int shift_rel = xp_normalize_up(rel, 3, XP_SHIFT_LIMIT);
    xp_set(num, 0.0);
    xp_set(den, 0.0);
    for (int k = 0; k < 3; k++) {
        xp_add_mul(num, &normal[k], &rel[k]);
        xp_scale(&tmp, &normal[k], pow2_scale(ray->dir[k], -e_dir));
        xp_scale(&tmp, &tmp, (double)n); /* n d_k rounded would not be exact */
        xp_add(den, den, &tmp);
    }
    for (int j = 0; j < den->n; j++)
        den->p[j] = pow2_scale(den->p[j], shift_rel);
}

/*
 * The exact path of the crossing parameter: with the coordinates scaled by
 * 2^-e (the direction by its own power of two), n t = num/den with num =
 * sum_k N_k (sum_i v_ik - n o_k) and den = n N.dir, both exact expansions
 * (N the exact Newell normal; polygon_crossing_xp), decided by
 * core/ratio.c.
 */
static int polygon_crossing_exact(const isect_ray *ray, const double *v, const int32_t *idx,
                                  int n, double *t_hi, double *t_lo, int *enter, int *t_shift_out,
                                  int *e_out)
{
    int e = pow2_exponent(fmax_nan(vertex_extent(v, idx, n), max_abs3(ray->org)));
    int e_dir = pow2_exponent(max_abs3(ray->dir));
    int t_shift = e - e_dir;
    xp num, den;
    polygon_crossing_xp(ray, v, idx, n, e, e_dir, &num, &den);
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

int polygon_hit_plane_framed(const ray_frame *f, const isect_ray *ray, const double *v,
                             const int32_t *idx, int n, int rule, const poly_plane *pp,
                             isect_hit *out)
{
    /* Revision 2: no epsilon; the exact winding number alone decides. */
    lane_ray lr;
    lane_ray_from(&lr, ray);
    if (!fill_rule_inside(frame_winding(f, &lr, v, idx, n), rule))
        return 0;
    vdd t;
    int enter;
    double point[3];
    int fast = 0;
    if (lane_ray_in_range(&lr, 0x1p200) && max_abs3(pp->m_hi) <= 0x1p200) {
        tri_plane tp;
        for (int k = 0; k < 3; k++) {
            tp.n[k].hi = pp->n_hi[k];
            tp.n[k].lo = pp->n_lo[k];
            tp.err[k] = pp->n_err[k];
        }
        tri_crossing tc;
        tri_crossing_solve(&tp, pp->m_hi, pp->m_lo, pp->m_err, &lr, &tc);
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
        if (!polygon_crossing_exact(ray, v, idx, n, &t.hi, &t.lo, &enter, &t_shift, &e))
            return 0;
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
            return 0;
    }
    out->t = fmin(fmax(t.hi, ray->tmin), ray->tmax) + 0.0;
    v3_copy(out->point, point);
    v3_copy(out->normal, pp->unit);
    out->uv[0] = out->uv[1] = 0.0;
    out->prim = -1;
    out->kind = enter ? ISECT_ENTER : ISECT_EXIT;
    return 1;
}

int polygon_hit_framed(const ray_frame *f, const isect_ray *ray, const double *v,
                       const int32_t *idx, int n, int rule, isect_hit *out)
{
    poly_plane pp;
    if (!polygon_plane(v, idx, n, &pp))
        return 0;
    return polygon_hit_plane_framed(f, ray, v, idx, n, rule, &pp, out);
}

int polygon_check(const isect_shape *s)
{
    if (s->n < 3 || !fill_rule_valid(s->flags))
        return ISECT_E_ARG;
    return all_finite(s->data, 3 * (int64_t)s->n) ? ISECT_OK : ISECT_E_NONFINITE;
}

void polygon_prepare(const double *v, int n, int rule, poly_prep *pp)
{
    pp->v = v;
    pp->n = n;
    pp->rule = rule;
    pp->degenerate = !polygon_plane(v, NULL, n, &pp->plane);
    if (pp->degenerate)
        memset(&pp->plane, 0, sizeof pp->plane);
    pp->in_range = vertex_extent(v, NULL, n) <= 0x1p200 && max_abs3(pp->plane.m_hi) <= 0x1p200;
}

/* The fast kernel at LANE_W = 1 (the batch's), then for the rays it leaves
 * undecided the exact path from the same plane. */
int polygon_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                 isect_hit out[ISECT_MAX_HITS])
{
    (void)prm; /* no epsilon for faces (revision 2) */
    lane_ray lr;
    lane_ray_from(&lr, ray);
    if (vertex_extent(s->data, NULL, s->n) <= 0x1p200 && lane_ray_in_range(&lr, 0x1p200)) {
        /* the kernel's verdict for a certainly outside ray, before the
         * plane is prepared (most rays of a scalar or all-hits call miss) */
        face_axes fa;
        face_axes_make(&lr, &fa);
        face_winding fw;
        face_winding_lanes(s->data, NULL, s->n, &lr, &fa, &fw);
        int inside = s->flags == ISECT_NONZERO ? fw.winding != 0.0 : fw.odd > 0.0;
        if (fw.certain && !inside)
            return 0;
    }
    poly_prep pp;
    polygon_prepare(s->data, s->n, s->flags, &pp);
    if (pp.degenerate)
        return 0;
    lane_hit h;
    poly_lanes_first(&pp, &lr, &h);
    if (!h.slow) {
        if (!h.found)
            return 0;
        lane_hit_store(&h, 0, &out[0]);
        return 1;
    }
    ray_frame f;
    ray_frame_shear(ray, &f);
    return polygon_hit_plane_framed(&f, ray, s->data, NULL, s->n, s->flags, &pp.plane, &out[0]);
}

/* Shared checks of the two helpers: ISECT_OK, or the error to return. */
static int points_check(const double *v, int n)
{
    if (v == NULL || n < 3)
        return ISECT_E_ARG;
    return all_finite(v, 3 * (int64_t)n) ? ISECT_OK : ISECT_E_NONFINITE;
}

ISECT_API int isect_polygon_normal(const double *v, int n, double normal[3])
{
    if (normal == NULL)
        return ISECT_E_ARG;
    int status = points_check(v, n);
    if (status != ISECT_OK)
        return status;
    poly_plane pp;
    if (!polygon_plane(v, NULL, n, &pp)) {
        v3_set(normal, 0.0, 0.0, 0.0);
        return ISECT_E_DEGENERATE;
    }
    v3_copy(normal, pp.unit);
    return ISECT_OK;
}

ISECT_API int isect_plane_from_points(const double *v, int n, double plane[4])
{
    if (plane == NULL)
        return ISECT_E_ARG;
    int status = points_check(v, n);
    if (status != ISECT_OK)
        return status;
    poly_plane pp;
    if (!polygon_plane(v, NULL, n, &pp)) {
        plane[0] = plane[1] = plane[2] = plane[3] = 0.0;
        return ISECT_E_DEGENERATE;
    }
    v3_copy(plane, pp.unit);
    plane[3] = -v3_dot(plane, pp.m_hi);
    return ISECT_OK;
}

/*
 * sign(N.(p - m)) with N = sum_i v_i x v_{i+1} (Newell) and m the vertex
 * centroid, both exact: n N.(p - m) = sum_k N_k (n p_k - sum_i v_ik). All
 * coordinates are first scaled by one power of two (degree 3: the sign is
 * kept). A direction (w = 0) has no centroid term: sign(N.d), d kept
 * apart from the vertex scaling, as its magnitude is unrelated to theirs.
 */
int polygon_plane_sign(const double *v, const int32_t *idx, int n, const double p[3], int w)
{
    double m = w ? max_abs3(p) : 0.0;
    for (int i = 0; i < n; i++)
        m = fmax_nan(m, max_abs3(vertex_at(v, idx, i)));
    int e = pow2_exponent(m);
    int e_p = w ? e : pow2_exponent(max_abs3(p));
    xp normal[3], t[3], tmp, tmp2;
    for (int k = 0; k < 3; k++) {
        xp_set(&normal[k], 0.0);
        xp_set(&t[k], (double)n);
        xp_scale(&t[k], &t[k], pow2_scale(p[k], -e_p));
    }
    const double *prev = vertex_at(v, idx, n - 1);
    for (int i = 0; i < n; i++) {
        const double *cur = vertex_at(v, idx, i);
        double a[3], b[3];
        scale3(a, prev, e);
        scale3(b, cur, e);
        for (int k = 0; k < 3; k++) {
            int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
            xp_set(&tmp, a[i1]);
            xp_scale(&tmp, &tmp, b[i2]);
            xp_set(&tmp2, a[i2]);
            xp_scale(&tmp2, &tmp2, b[i1]);
            xp_sub(&tmp, &tmp, &tmp2);
            xp_add(&normal[k], &normal[k], &tmp);
            if (w)
                xp_add_d(&t[k], -b[k]);
        }
        prev = cur;
    }
    if (!w) {
        /* N.d for a direction: its components can span any range (a
         * subnormal one beside 2^100), which one power-of-two scaling of d
         * would underflow; dyadic_sum takes each N_k part times d_k exactly
         * whatever the exponents. A polygon whose N has more parts than it
         * holds (not seen for faces of a few vertices) takes the scaled
         * sum below, with a tiny N first scaled up to a largest part near 1
         * (only up: no part loses a bit). */
        if (normal[0].n + normal[1].n + normal[2].n <= DYADIC_SUM_TERMS) {
            dyadic_sum dot;
            dyadic_init(&dot);
            for (int k = 0; k < 3; k++)
                for (int i = 0; i < normal[k].n; i++)
                    dyadic_add3(&dot, 1.0, normal[k].p[i], p[k], 1.0);
            return dyadic_sign(&dot);
        }
        double top = 0.0;
        for (int k = 0; k < 3; k++)
            if (normal[k].n > 0)
                top = fmax_nan(top, fabs(normal[k].p[normal[k].n - 1]));
        int e_n = pow2_exponent(top);
        for (int k = 0; k < 3 && e_n < 0; k++)
            for (int i = 0; i < normal[k].n; i++)
                normal[k].p[i] = pow2_scale(normal[k].p[i], -e_n);
    }
    xp sum;
    xp_set(&sum, 0.0);
    for (int k = 0; k < 3; k++)
        xp_add_mul(&sum, &normal[k], &t[k]);
    return xp_sign(&sum);
}

int polygon_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    if (vertices_collinear(s->data, NULL, s->n))
        return 1; /* degenerate */
    return polygon_plane_sign(s->data, NULL, s->n, p, 1);
}

int polygon_tangent_side(const isect_shape *s, const double d[3], int32_t prim)
{
    (void)prim;
    if (vertices_collinear(s->data, NULL, s->n))
        return 0; /* degenerate: never hit */
    return polygon_plane_sign(s->data, NULL, s->n, d, 0);
}
