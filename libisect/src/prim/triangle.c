/*
 * triangle.c — the triangle primitive and the public isect_ray_triangle, on
 * the watertight test of triangle_test.h, and the per-face plane
 * (triangle_plane) that test and the mesh share.
 */
#include "prim/triangle_test.h"

#include <string.h>

/*
 * 1 when the exact (b - a) x (c - a) is certainly nonzero, judged from the
 * rounded cross product n of the rounded edges e1 = fl(b - a), e2 = fl(c - a)
 * (n_k = fl(p - q), p = fl(e1_i e2_j), q = fl(e1_j e2_i)), so that the exact
 * collinear3 test, which would return 0, can be skipped.
 *
 * Numerics. Let E1, E2 be the exact edges and N = E1 x E2. While nothing
 * underflows, p = P (1 + t1), q = Q (1 + t2) with |t1|, |t2| <= 3u + O(u^2)
 * (one rounding per edge component, one per product), P = E1_i E2_j,
 * Q = E1_j E2_i. If N_k = 0 then P = Q, so |n_k| <= (1 + u) |P| (6u + 2u^3)
 * while |p| + |q| >= 2 |P| (1 - u)^3: |n_k| <= 3.01u (|p| + |q|) <
 * 2^-50 (|p| + |q|). If instead |p| + |q| < 2^-900 (products possibly
 * subnormal), |n_k| <= (1 + u)(|p| + |q|) < 2^-800. So |n_k| >= 2^-800 and
 * |n_k| > 2^-50 (|p| + |q|) prove N_k != 0; then also |N_k| > |n_k| / 2
 * (its error is at most u|n_k| + 3.02u (|p| + |q|) < 0.4 |n_k|).
 *
 * collinear3 decides each N_k with orient2_sign, whose exact path scales the
 * coordinates so the largest is in [1, 2) and loses at most ~2^-1070 to
 * underflowed product tails. With every coordinate |x| <= 2^100 the scaled
 * |N_k| is above 2^-801 2^-200, far above that: orient2_sign returns the
 * true nonzero sign and collinear3 returns 0. Outside that range (and on the
 * rescaled path of triangle_plane) the exact test always runs.
 */
static int cross_certainly_nonzero(const double a[3], const double b[3], const double c[3],
                                   const double p[3], const double q[3], const double n[3])
{
    int moderate = 1;
    for (int k = 0; k < 3; k++)
        moderate &= (fabs(a[k]) <= 0x1p100) & (fabs(b[k]) <= 0x1p100) & (fabs(c[k]) <= 0x1p100);
    if (!moderate)
        return 0;
    for (int k = 0; k < 3; k++)
        if (fabs(n[k]) >= 0x1p-800 && fabs(n[k]) > 0x1p-50 * (fabs(p[k]) + fabs(q[k])))
            return 1;
    return 0;
}

/* normal = unit((b - a) x (c - a)); returns 0 for a zero cross product.
 * Where the plain products overflow (coordinates beyond ~1e150) or
 * underflow, the vertices are first scaled by one power of two (exact up to
 * subnormal tails), which leaves the direction unchanged. *nonzero is 1
 * when the exact cross product is certainly nonzero (see above), else 0. */
int triangle_plane(const double a[3], const double b[3], const double c[3], double normal[3],
                   int *nonzero)
{
    double e1[3], e2[3], n[3], p[3], q[3];
    *nonzero = 0;
    v3_sub(e1, b, a);
    v3_sub(e2, c, a);
    /* v3_cross written out (the same operations, so the same bits) to keep
     * the two products of each component for cross_certainly_nonzero. */
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        p[k] = e1[i] * e2[j];
        q[k] = e1[j] * e2[i];
        n[k] = p[k] - q[k];
    }
    double len = v3_normalize(normal, n);
    if (len > 0.0 && len <= DBL_MAX) {
        *nonzero = cross_certainly_nonzero(a, b, c, p, q, n);
        return 1;
    }
    double m = fmax(fabs(a[0]), fmax(fabs(a[1]), fabs(a[2])));
    m = fmax(m, fmax(fabs(b[0]), fmax(fabs(b[1]), fabs(b[2]))));
    m = fmax(m, fmax(fabs(c[0]), fmax(fabs(c[1]), fabs(c[2]))));
    if (m == 0.0)
        return 0;
    int e = -ilogb(m);
    for (int k = 0; k < 3; k++) {
        double ak = ldexp(a[k], e);
        e1[k] = ldexp(b[k], e) - ak;
        e2[k] = ldexp(c[k], e) - ak;
    }
    v3_cross(n, e1, e2);
    len = v3_normalize(normal, n);
    return len > 0.0 && len <= DBL_MAX;
}

int triangle_hit_framed(const ray_frame *f, const isect_ray *ray, const isect_params *prm,
                        const double a[3], const double b[3], const double c[3],
                        isect_hit *out)
{
    return triangle_hit(f, ray, prm, a, b, c, NULL, 0, out);
}

int triangle_check(const isect_shape *s)
{
    return all_finite(s->data, 9) ? ISECT_OK : ISECT_E_NONFINITE;
}

int triangle_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                  isect_hit out[ISECT_MAX_HITS])
{
    ray_frame f;
    ray_frame_shear_no_len(ray, &f); /* |dir| only if needed (not_parallel) */
    return triangle_hit_framed(&f, ray, prm, s->data, s->data + 3, s->data + 6, &out[0]);
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
