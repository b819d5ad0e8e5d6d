/*
 * triangle.c — the watertight ray/triangle test (Woop, Benthin & Wald 2013)
 * with exact, perturbed edge signs, and the public isect_ray_triangle.
 */
#include "planar.h"
#include "predicates.h"
#include "vec3.h"

#include <float.h>
#include <string.h>

static const double frame_origin[2] = { 0.0, 0.0 };

/* orient(p, q, origin) = p.x q.y - p.y q.x to 2u relative error, so its sign
 * is the exact one (the weight is 0 exactly where the perturbation decided).
 * A value against the exact sign can only come from underflow outside the
 * predicates' range; it is taken as 0 so all weights keep one sign. */
static double edge_weight(const double p[2], const double q[2], int sign)
{
    double w = det2_accurate(p[0], p[1], q[0], q[1]);
    return (sign > 0 ? w < 0.0 : w > 0.0) ? 0.0 : w;
}

/* The barycentric weights of the frame origin in the projected triangle,
 * normalised to sum 1; s is the common sign of the three edge tests. 2D
 * coordinates beyond ~1e150 (or tiny ones) would overflow (underflow) the
 * products, so then they are rescaled by one power of two, which scales
 * every weight alike. 0 when no weight survives (outside the predicates'
 * exact range only). */
static int barycentric_weights(const double pa[2], const double pb[2], const double pc[2],
                               int s, double w[3])
{
    double qa[2] = { pa[0], pa[1] }, qb[2] = { pb[0], pb[1] }, qc[2] = { pc[0], pc[1] };
    for (int attempt = 0; attempt < 2; attempt++) {
        w[0] = edge_weight(qb, qc, s);
        w[1] = edge_weight(qc, qa, s);
        w[2] = edge_weight(qa, qb, s);
        double sum = w[0] + w[1] + w[2];
        if (sum != 0.0 && fabs(sum) <= DBL_MAX) {
            for (int k = 0; k < 3; k++)
                w[k] /= sum;
            return 1;
        }
        double m = fmax(fmax(fabs(pa[0]), fabs(pa[1])),
                        fmax(fmax(fabs(pb[0]), fabs(pb[1])), fmax(fabs(pc[0]), fabs(pc[1]))));
        if (m == 0.0)
            return 0;
        int e = -ilogb(m);
        for (int k = 0; k < 2; k++) {
            qa[k] = ldexp(pa[k], e);
            qb[k] = ldexp(pb[k], e);
            qc[k] = ldexp(pc[k], e);
        }
    }
    return 0;
}

/* normal = unit((b - a) x (c - a)); returns 0 for a zero cross product.
 * Where the plain products overflow (coordinates beyond ~1e150) or
 * underflow, the vertices are first scaled by one power of two (exact up to
 * subnormal tails), which leaves the direction unchanged. */
static int triangle_normal(const double a[3], const double b[3], const double c[3],
                           double normal[3])
{
    double e1[3], e2[3], n[3];
    v3_sub(e1, b, a);
    v3_sub(e2, c, a);
    v3_cross(n, e1, e2);
    double len = v3_normalize(normal, n);
    if (len > 0.0 && len <= DBL_MAX)
        return 1;
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
    double pa[3], pb[3], pc[3];
    ray_frame_project(f, a, pa);
    ray_frame_project(f, b, pb);
    ray_frame_project(f, c, pc);
    /* Inside iff the perturbed origin is strictly on one side of all three
     * edges: +1 (counter-clockwise in the frame) is the back side, -1 the
     * front. A neighbour sharing edge p-q tests q-p and gets the opposite
     * sign, so exactly one of them claims any ray through the edge. */
    int s = orient2_sign_perturbed(pa, pb, frame_origin);
    if (s == 0 || orient2_sign_perturbed(pb, pc, frame_origin) != s
        || orient2_sign_perturbed(pc, pa, frame_origin) != s)
        return 0;

    double normal[3];
    if (!triangle_normal(a, b, c, normal))
        return 0;
    /* Epsilon policy: parallel when |n.d| <= eps |n| |d| (n is unit here). */
    if (!(fabs(v3_dot(normal, ray->dir)) > prm->eps * f->dir_len))
        return 0;
    /* Rounding can leave a nonzero cross product (and a 2D sliver) for
     * exactly collinear vertices; zero area is decided exactly. */
    if (collinear3(a, b, c))
        return 0;

    double w[3];
    if (!barycentric_weights(pa, pb, pc, s, w))
        return 0;
    /* Interpolating the sheared z gives t; at a vertex the weights are
     * exactly (1, 0, 0), so every face through it reports the same t. */
    double t = w[0] * pa[2] + w[1] * pb[2] + w[2] * pc[2];
    hit_set(out, ray, t, normal, -1, hit_kind_from_normal(ray->dir, normal));
    out->uv[0] = w[1];
    out->uv[1] = w[2];
    return 1;
}

int triangle_check(const isect_shape *s)
{
    return all_finite(s->data, 9) ? ISECT_OK : ISECT_E_NONFINITE;
}

int triangle_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                  isect_hit out[ISECT_MAX_HITS])
{
    ray_frame f;
    ray_frame_shear(ray, &f);
    return triangle_hit_framed(&f, ray, prm, s->data, s->data + 3, s->data + 6, &out[0]);
}

ISECT_API int isect_ray_triangle(const isect_ray *ray, const double a[3], const double b[3],
                                 const double c[3], const isect_opts *opts,
                                 isect_hit *hits, int cap)
{
    /* A NULL vertex leaves data NULL, which the dispatcher reports as
     * ISECT_E_ARG in its usual order of checks. */
    double abc[9];
    const double *data = NULL;
    if (a != NULL && b != NULL && c != NULL) {
        memcpy(abc, a, 3 * sizeof *abc);
        memcpy(abc + 3, b, 3 * sizeof *abc);
        memcpy(abc + 6, c, 3 * sizeof *abc);
        data = abc;
    }
    isect_shape s = { ISECT_TRIANGLE, 0, 0, 0, data, NULL, NULL };
    return scalar_intersect(&s, ray, opts, hits, cap);
}
