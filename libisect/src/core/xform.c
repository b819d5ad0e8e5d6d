/* SPDX-License-Identifier: Apache-2.0 */
/*
 * xform.c — affine object-to-world transforms (the seeds' "transformed
 * objects"): the ray goes to object space by M^-1, the primitive is hit there,
 * and the hits come back by M (points) and M^-T (normals). The direction is
 * mapped as a vector and never renormalised, so t means the same in both
 * spaces and hits of transformed shapes sort and clip exactly like the rest.
 */
#include "core/core.h"

#include "core/vec3.h"
#include "core/predicates.h"

#include <string.h>

/* Rows of the linear part are nearly dependent when the volume they span is
 * this small relative to the product of their lengths (Hadamard's bound makes
 * the ratio 1 for orthogonal rows). Scale-invariant; 2^-40 leaves ~12 good
 * digits in the inverse. */
#define XFORM_SINGULAR_RATIO 0x1p-40

static void affine_point(const double a[16], const double p[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a[4 * i] * p[0] + a[4 * i + 1] * p[1] + a[4 * i + 2] * p[2] + a[4 * i + 3];
    v3_copy(out, r);
}

static void affine_vector(const double a[16], const double v[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a[4 * i] * v[0] + a[4 * i + 1] * v[1] + a[4 * i + 2] * v[2];
    v3_copy(out, r);
}

/* n by the transpose of a's linear part: with a = M^-1 this is M^-T n, which
 * keeps n perpendicular to the mapped surface and on the same (outer) side.
 * Made unit by v3_normalize, then one Newton step for 1/|n| about 1,
 * n (3 - n.n)/2: v3_normalize alone leaves |n| - 1 up to ~1.0x ulp (its
 * square root and three divisions), the step takes it to the rounding of
 * the last multiplication. lane_hit_to_world repeats it bit for bit. */
static void affine_normal(const double a[16], const double n[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a[i] * n[0] + a[4 + i] * n[1] + a[8 + i] * n[2];
    v3_normalize(out, r);
    double f = 1.5 - 0.5 * v3_dot(out, out);
    for (int k = 0; k < 3; k++)
        out[k] *= f;
}

ISECT_API int isect_xform_init(isect_xform *x, const double m[16])
{
    if (x == NULL || m == NULL)
        return ISECT_E_ARG;
    if (!all_finite(m, 16))
        return ISECT_E_NONFINITE;
    if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0)
        return ISECT_E_ARG;

    /* Work on the rows scaled to unit length (A = diag(len) U): the
     * singularity test is then |det U| <= 2^-40 whatever the scale, and the
     * cofactors of U cannot overflow or underflow. A^-1 = U^-1 diag(1/len). */
    double len[3], u[9];
    for (int i = 0; i < 3; i++) {
        len[i] = v3_norm(&m[4 * i]);
        if (!(len[i] > 0.0))
            return ISECT_E_DEGENERATE;
        for (int j = 0; j < 3; j++)
            u[3 * i + j] = m[4 * i + j] / len[i];
    }
    /* Cofactors: c[i][j] is the cofactor of u[j][i], so U^-1 = c / det. */
    double c[9];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            c[3 * i + j] = u[3 * r0 + c0] * u[3 * r1 + c1] - u[3 * r0 + c1] * u[3 * r1 + c0];
        }
    }
    double det = u[0] * c[0] + u[1] * c[3] + u[2] * c[6];
    if (!(fabs(det) > XFORM_SINGULAR_RATIO))
        return ISECT_E_DEGENERATE;

    double inv[16] = {0};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            inv[4 * i + j] = c[3 * i + j] / det / len[j];
    /* Translation of the inverse: -A^-1 t. */
    double t[3] = { m[3], m[7], m[11] }, it[3];
    affine_vector(inv, t, it);
    inv[3] = -it[0];
    inv[7] = -it[1];
    inv[11] = -it[2];
    inv[15] = 1.0;
    if (!all_finite(inv, 16))
        return ISECT_E_DEGENERATE; /* an entry of the inverse overflowed */

    memcpy(x->m, m, sizeof x->m);
    memcpy(x->inv, inv, sizeof x->inv);
    return ISECT_OK;
}

/* A world point to object space: the inverse's linear part applied to
 * p - T (T the transform's translation), not inv p + inv's translation:
 * the two agree in exact arithmetic, but a small object placed far away
 * (T ~ 1e6, scale 1e-3) near a ray origin makes inv p and -inv T each ~1e9
 * and their sum ~1, losing 1e-7 of it; p - T is exact there (Sterbenz) or
 * rounded once relative to its own size. Each coordinate is ((a0 r0 + a1
 * r1) + a2 r2), r = p - T, in that order (lane_ray_xform matches it). */
static void inverse_point(const isect_xform *x, const double p[3], double out[3])
{
    const double r[3] = { p[0] - x->m[3], p[1] - x->m[7], p[2] - x->m[11] };
    affine_vector(x->inv, r, out);
}

void xform_ray_unchecked(const isect_xform *x, const isect_ray *in, isect_ray *out)
{
    double org[3], dir[3];
    inverse_point(x, in->org, org);
    affine_vector(x->inv, in->dir, dir);
    v3_copy(out->org, org);
    v3_copy(out->dir, dir);
    out->tmin = in->tmin;
    out->tmax = in->tmax;
}

void xform_point_to_object(const isect_xform *x, const double p[3], double out[3])
{
    inverse_point(x, p, out);
}

void xform_vector_to_object(const isect_xform *x, const double v[3], double out[3])
{
    affine_vector(x->inv, v, out);
}

void xform_point_to_world(const isect_xform *x, const double p[3], double out[3])
{
    affine_point(x->m, p, out);
}

int xform_is_similarity(const isect_xform *x)
{
    /* L^T L = s^2 I to a relative 2^-40: columns orthogonal and of one
     * length (a rotation or mirror times a uniform scale) */
    double g[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            g[i][j] = x->m[i] * x->m[j] + x->m[4 + i] * x->m[4 + j] + x->m[8 + i] * x->m[8 + j];
    double s2 = (g[0][0] + g[1][1] + g[2][2]) / 3.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (!(fabs(g[i][j] - (i == j ? s2 : 0.0)) <= 0x1p-40 * s2))
                return 0; /* NaN (an overflowed square) included */
    return 1;
}

int xform_orientation(const isect_xform *x)
{
    /* det of the rows = orient3 of the rows against the origin (orient3's
     * differences with 0 are exact); nonzero: isect_xform_init refuses a
     * singular matrix */
    const double r0[3] = { x->m[0], x->m[1], x->m[2] }, r1[3] = { x->m[4], x->m[5], x->m[6] };
    const double r2[3] = { x->m[8], x->m[9], x->m[10] }, zero[3] = { 0.0, 0.0, 0.0 };
    return orient3_sign(r0, r1, r2, zero) < 0 ? -1 : 1;
}

void xform_hits_unchecked(const isect_xform *x, isect_hit *hits, int n)
{
    for (int i = 0; i < n; i++) {
        if (hits[i].kind == ISECT_MISS || hits[i].kind == ISECT_INVALID)
            continue;
        affine_point(x->m, hits[i].point, hits[i].point);
        affine_normal(x->inv, hits[i].normal, hits[i].normal);
    }
}

ISECT_API int isect_xform_ray(const isect_xform *x, const isect_ray *world_ray,
                              isect_ray *object_ray)
{
    if (x == NULL || world_ray == NULL || object_ray == NULL)
        return ISECT_E_ARG;
    xform_ray_unchecked(x, world_ray, object_ray);
    return ISECT_OK;
}

ISECT_API int isect_xform_hits(const isect_xform *x, isect_hit *hits, int n)
{
    if (x == NULL || n < 0 || (n > 0 && hits == NULL))
        return ISECT_E_ARG;
    xform_hits_unchecked(x, hits, n);
    return ISECT_OK;
}
