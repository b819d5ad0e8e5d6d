/*
 * polygon.c — planar polygons (convex, concave, self-intersecting): the
 * plane by Newell's method, the inside test as the exact winding number of
 * the sheared frame's origin; the public isect_ray_polygon,
 * isect_polygon_normal and isect_plane_from_points.
 */
#include "prim/planar.h"
#include "core/expansion.h"
#include "core/predicates.h"
#include "core/quadratic.h"
#include "core/vec3.h"

#include <stddef.h>

static const double frame_origin[2] = { 0.0, 0.0 };

static const double *vertex_at(const double *v, const int32_t *idx, int i)
{
    return v + 3 * (ptrdiff_t)(idx != NULL ? idx[i] : i);
}

static void vertex_centroid(const double *v, const int32_t *idx, int n, double centroid[3])
{
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (int i = 0; i < n; i++)
        v3_add(sum, sum, vertex_at(v, idx, i));
    v3_scale(centroid, sum, 1.0 / n);
    if (isfinite(centroid[0]) && isfinite(centroid[1]) && isfinite(centroid[2]))
        return;
    /* The sum overflowed (coordinates near DBL_MAX): average in scaled steps. */
    v3_set(centroid, 0.0, 0.0, 0.0);
    for (int i = 0; i < n; i++)
        v3_madd(centroid, centroid, 1.0 / n, vertex_at(v, idx, i));
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

/* (p - centroid) * pre * scale, pre and scale powers of two. */
static void relative_scaled(const double p[3], const double centroid[3], double pre,
                            double scale, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = (p[k] * pre - centroid[k] * pre) * scale;
}

/* The largest |(p - centroid) * pre| coordinate over the vertices. */
static double relative_extent(const double *v, const int32_t *idx, int n,
                              const double centroid[3], double pre)
{
    double extent = 0.0, rel[3];
    for (int i = 0; i < n; i++) {
        relative_scaled(vertex_at(v, idx, i), centroid, pre, 1.0, rel);
        extent = fmax(extent, fmax(fabs(rel[0]), fmax(fabs(rel[1]), fabs(rel[2]))));
    }
    return extent;
}

int polygon_plane(const double *v, const int32_t *idx, int n, double normal[3],
                  double centroid[3])
{
    vertex_centroid(v, idx, n, centroid);
    /* Relative to the centroid the Newell sums do not cancel the absolute
     * position away (accurate far from the origin); a power-of-two scale
     * keeps the products clear of overflow and underflow for any finite
     * input without changing the direction. pre = 1/4 only when the plain
     * difference of two finite coordinates overflows. */
    double pre = 1.0;
    double extent = relative_extent(v, idx, n, centroid, pre);
    if (!isfinite(extent)) {
        pre = 0.25;
        extent = relative_extent(v, idx, n, centroid, pre);
    }
    double newell[3] = { 0.0, 0.0, 0.0 }, magnitude[3] = { 0.0, 0.0, 0.0 };
    if (extent > 0.0) {
        int e = ilogb(extent);
        double scale = ldexp(1.0, e > 1000 ? -1000 : e < -1000 ? 1000 : -e);
        double prev[3], cur[3];
        relative_scaled(vertex_at(v, idx, n - 1), centroid, pre, scale, prev);
        for (int i = 0; i < n; i++) {
            relative_scaled(vertex_at(v, idx, i), centroid, pre, scale, cur);
            /* Newell: twice the vector area, the sum over edges i -> j of
             * (y_i - y_j)(z_i + z_j), (z_i - z_j)(x_i + x_j), (x_i - x_j)(y_i + y_j). */
            double term[3] = { (prev[1] - cur[1]) * (prev[2] + cur[2]),
                               (prev[2] - cur[2]) * (prev[0] + cur[0]),
                               (prev[0] - cur[0]) * (prev[1] + cur[1]) };
            for (int k = 0; k < 3; k++) {
                newell[k] += term[k];
                magnitude[k] += fabs(term[k]);
            }
            v3_copy(prev, cur);
        }
    }
    /* A sliver whose every Newell component is within the rounding error
     * of its own sum has a normal with no correct digit (the error of each
     * term is at most ~3u of it after the centroid-relative rounding, the
     * recursive sum adds (n-1)u of the sum of magnitudes): its plane, and so
     * any hit on it, would be noise. It counts as zero area. */
    const double noise = (n + 4) * 0x1p-52;
    int has_digits = 0;
    for (int k = 0; k < 3; k++)
        has_digits |= fabs(newell[k]) > noise * magnitude[k];
    double len = v3_normalize(normal, newell);
    if (has_digits && len > 0.0 && isfinite(len) && !vertices_collinear(v, idx, n))
        return 1;
    v3_set(normal, 0.0, 0.0, 0.0);
    v3_set(centroid, 0.0, 0.0, 0.0);
    return 0;
}

/* Winding number of the perturbed frame origin around the projected
 * polygon; each vertex is projected once, by the same arithmetic as in
 * every other face that uses it. */
static int32_t frame_winding(const ray_frame *f, const double *v, const int32_t *idx, int n)
{
    double prev[3], cur[3];
    ray_frame_project(f, vertex_at(v, idx, n - 1), prev);
    int32_t winding = 0;
    for (int i = 0; i < n; i++) {
        ray_frame_project(f, vertex_at(v, idx, i), cur);
        winding += winding_edge(prev, cur, frame_origin);
        v3_copy(prev, cur);
    }
    return winding;
}

int polygon_hit_plane_framed(const ray_frame *f, const isect_ray *ray,
                             const isect_params *prm, const double *v, const int32_t *idx,
                             int n, int rule, const double normal[3],
                             const double centroid[3], isect_hit *out)
{
    /* Epsilon policy (normal is unit or zero; zero never passes). */
    double nd = v3_dot(normal, ray->dir);
    if (!(fabs(nd) > prm->eps * f->dir_len))
        return 0;
    if (!fill_rule_inside(frame_winding(f, v, idx, n), rule))
        return 0;
    double to_plane[3];
    v3_sub(to_plane, centroid, ray->org);
    double t = v3_dot(normal, to_plane) / nd;
    hit_set(out, ray, t, normal, -1, hit_kind_from_normal(ray->dir, normal));
    return 1;
}

int polygon_hit_framed(const ray_frame *f, const isect_ray *ray, const isect_params *prm,
                       const double *v, const int32_t *idx, int n, int rule,
                       isect_hit *out)
{
    double normal[3], centroid[3];
    if (!polygon_plane(v, idx, n, normal, centroid))
        return 0;
    return polygon_hit_plane_framed(f, ray, prm, v, idx, n, rule, normal, centroid, out);
}

int polygon_check(const isect_shape *s)
{
    if (s->n < 3 || !fill_rule_valid(s->flags))
        return ISECT_E_ARG;
    return all_finite(s->data, 3 * (int64_t)s->n) ? ISECT_OK : ISECT_E_NONFINITE;
}

int polygon_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                 isect_hit out[ISECT_MAX_HITS])
{
    ray_frame f;
    ray_frame_shear(ray, &f);
    return polygon_hit_framed(&f, ray, prm, s->data, NULL, s->n, s->flags, &out[0]);
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
    double centroid[3];
    return polygon_plane(v, NULL, n, normal, centroid) ? ISECT_OK : ISECT_E_DEGENERATE;
}

ISECT_API int isect_plane_from_points(const double *v, int n, double plane[4])
{
    if (plane == NULL)
        return ISECT_E_ARG;
    int status = points_check(v, n);
    if (status != ISECT_OK)
        return status;
    double centroid[3];
    if (!polygon_plane(v, NULL, n, plane, centroid)) {
        plane[3] = 0.0;
        return ISECT_E_DEGENERATE;
    }
    plane[3] = -v3_dot(plane, centroid);
    return ISECT_OK;
}

/*
 * sign(N.(p - m)) with N = sum_i v_i x v_{i+1} (Newell) and m the vertex
 * centroid, both exact: n N.(p - m) = sum_k N_k (n p_k - sum_i v_ik). All
 * coordinates are first scaled by one power of two (degree 3: the sign is
 * kept).
 */
int polygon_plane_side(const double *v, const int32_t *idx, int n, const double p[3])
{
    double m = max_abs3(p);
    for (int i = 0; i < n; i++)
        m = fmax_nan(m, max_abs3(vertex_at(v, idx, i)));
    int e = pow2_exponent(m);
    xp normal[3], t[3], tmp, tmp2;
    for (int k = 0; k < 3; k++) {
        xp_set(&normal[k], 0.0);
        xp_set(&t[k], (double)n);
        xp_scale(&t[k], &t[k], pow2_scale(p[k], -e));
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
            xp_add_d(&t[k], -b[k]);
        }
        prev = cur;
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
    return polygon_plane_side(s->data, NULL, s->n, p);
}
