/*
 * triangle_test.h — the watertight ray/triangle test (Woop, Benthin & Wald
 * 2013) with exact, perturbed edge signs, as static inline functions.
 *
 * triangle.c builds the public triangle tests on it; the mesh traversal
 * (mesh_query.c) includes it too, so that its leaf loop can be compiled a
 * second time for CPUs with FMA (x86-64 without -mfma otherwise calls libm
 * for each of the test's fma operations). fma is correctly rounded either
 * way, so both copies give the same bits.
 */
#ifndef ISECT_TRIANGLE_TEST_H
#define ISECT_TRIANGLE_TEST_H

#include "prim/planar.h"
#include "core/predicates.h"
#include "core/vec3.h"

#include <float.h>

/* orient(p, q, origin) = p.x q.y - p.y q.x by det2_accurate, to 2u
 * relative error. */
static ALWAYS_INLINE double edge_det(const double p[2], const double q[2])
{
    return det2_accurate(p[0], p[1], q[0], q[1]);
}

/*
 * The sign of the frame origin against the edge p -> q under the
 * perturbation (orient2_sign_perturbed), taking it from w = edge_det(p, q)
 * where that is certain. det2_accurate errs by at most 2u|x| on the exact
 * x = p.x q.y - p.y q.x when no operation under- or overflows (Jeannerod,
 * Louvet & Muller, Math. Comp. 2013); an underflowed product or error term
 * adds at most a few 2^-1075 in absolute value. So 2^-900 <= |w| <= DBL_MAX
 * proves x nonzero with the sign of w: the exact orient2_sign is that sign
 * and the perturbation is not consulted. Otherwise (w zero, tiny, infinite
 * or NaN) the exact predicate decides.
 */
static ALWAYS_INLINE int edge_sign(double w, const double p[2], const double q[2])
{
    static const double frame_origin[2] = { 0.0, 0.0 };
    if (fabs(w) >= 0x1p-900 && fabs(w) <= DBL_MAX)
        return w > 0.0 ? 1 : -1;
    return orient2_sign_perturbed(p, q, frame_origin);
}

/* A weight against the exact sign can only come from underflow outside
 * the predicates' range; it is taken as 0 so all weights keep one sign
 * (the weight is 0 exactly where the perturbation decided). */
static ALWAYS_INLINE double edge_weight(double w, int sign)
{
    return (sign > 0 ? w < 0.0 : w > 0.0) ? 0.0 : w;
}

/* The barycentric weights of the frame origin in the projected triangle,
 * normalised to sum 1; s is the common sign of the three edge tests and
 * det[] the edge determinants of (pb, pc), (pc, pa), (pa, pb). 2D
 * coordinates beyond ~1e150 (or tiny ones) would overflow (underflow) the
 * products, so then they are rescaled by one power of two, which scales
 * every weight alike. 0 when no weight survives (outside the predicates'
 * exact range only). */
static ALWAYS_INLINE int barycentric_weights(const double pa[2], const double pb[2], const double pc[2],
                                             int s, const double det[3], double w[3])
{
    double qa[2] = { pa[0], pa[1] }, qb[2] = { pb[0], pb[1] }, qc[2] = { pc[0], pc[1] };
    for (int attempt = 0; attempt < 2; attempt++) {
        if (attempt == 0) {
            w[0] = edge_weight(det[0], s);
            w[1] = edge_weight(det[1], s);
            w[2] = edge_weight(det[2], s);
        } else {
            w[0] = edge_weight(edge_det(qb, qc), s);
            w[1] = edge_weight(edge_det(qc, qa), s);
            w[2] = edge_weight(edge_det(qa, qb), s);
        }
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

/* The side of the frame origin against all three edges: the common sign
 * (see triangle_hit_framed) or 0, with the projected vertices and the edge
 * determinants of (pb, pc), (pc, pa), (pa, pb) for the weights. */
static ALWAYS_INLINE int triangle_side(const ray_frame *f, const double a[3], const double b[3],
                                       const double c[3], double pa[3], double pb[3], double pc[3],
                                       double det[3])
{
    ray_frame_project(f, a, pa);
    ray_frame_project(f, b, pb);
    ray_frame_project(f, c, pc);
    /* Inside iff the perturbed origin is strictly on one side of all three
     * edges: +1 (counter-clockwise in the frame) is the back side, -1 the
     * front. A neighbour sharing edge p-q tests q-p and gets the opposite
     * sign, so exactly one of them claims any ray through the edge. The
     * signs are orient2_sign_perturbed's, mostly read off the determinants
     * the barycentric weights need anyway (edge_sign). */
    det[0] = edge_det(pb, pc);
    det[1] = edge_det(pc, pa);
    det[2] = edge_det(pa, pb);
    int s = edge_sign(det[2], pa, pb);
    if (s == 0 || edge_sign(det[0], pb, pc) != s || edge_sign(det[1], pc, pa) != s)
        return 0;
    return s;
}

/* The test: the sides (triangle_side) decide whether the ray crosses the
 * triangle — no epsilon (revision 2), the exact test alone; then, for the
 * few faces whose sides agree, triangle_record finds where (the crossing
 * parameter to within 4 ulp, decided exactly against [tmin, tmax]) and
 * writes the record. normal: the face's unit normal if the caller keeps it
 * (a mesh; then nonzero is 1), or NULL. */
static ALWAYS_INLINE int triangle_hit(const ray_frame *f, const isect_ray *ray, const isect_params *prm,
                                      const double a[3], const double b[3], const double c[3],
                                      const double *normal, int nonzero, isect_hit *out)
{
    (void)prm;
    double pa[3], pb[3], pc[3], det[3];
    int s = triangle_side(f, a, b, c, pa, pb, pc, det);
    if (s == 0)
        return 0;
    /* Rounding can leave a nonzero 2D sliver for exactly collinear
     * vertices; zero area is decided exactly. */
    if (!nonzero && collinear3(a, b, c))
        return 0;
    double w[3];
    if (!barycentric_weights(pa, pb, pc, s, det, w))
        return 0;
    return triangle_record(ray, a, b, c, normal, w[1], w[2], out);
}

#endif /* ISECT_TRIANGLE_TEST_H */
