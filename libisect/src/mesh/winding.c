/* SPDX-License-Identifier: Apache-2.0 */
/*
 * winding.c — the generalized winding number of a mesh (Jacobson, Kavan &
 * Sorkine, "Robust inside-outside segmentation using generalized winding
 * numbers", SIGGRAPH 2013): w(q) = (1/4pi) sum over faces of the signed
 * solid angle the face subtends at q, by direct summation or by the
 * hierarchical far-field evaluation of Barill, Dickson, Schmidt, Levin &
 * Jacobson ("Fast winding numbers for soups and clouds", SIGGRAPH 2018)
 * over the mesh's BVH. For a closed, consistently oriented mesh the value
 * off the surface is an integer, which mesh_query.c computes exactly as the
 * signed crossing count; this file serves every other mesh and the points
 * on a closed mesh's surface (where w is the principal value: the mean of
 * the two sides, 1/2 on a face of a simple solid).
 *
 * One face's solid angle. A polygon face is the fan of triangles (v0, vi,
 * vi+1): their signed solid angles add up to the polygon's, concave or not.
 * For a triangle A, B, C and a = A - q, b = B - q, c = C - q (Van Oosterom
 * & Strackee, IEEE Trans. Biomed. Eng. 30, 1983):
 *     tan(Omega/2) = det[a b c] / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|),
 * taken as Omega = 2 atan2(num, den). The numerator is formed as a . n with
 * n = (B - A) x (C - A), which does not involve q: far from a small face
 * det[a b c] evaluated directly would cancel to nothing (its products are
 * |a|^3, the value |a| |n|), while a . n keeps its relative accuracy.
 *
 * Error bound (every face, in plain doubles; u = 2^-53). With P_k the
 * permanent of n_k (|e1_y e2_z| + |e1_z e2_y|, ...):
 *     |num - exact| <= E_num = 10u sum_k |a_k| P_k
 *     (a, e1, e2 each within u of their exact differences, n within 4u P,
 *     the dot product's own 3u),
 *     |den - exact| <= E_den = 64u |a||b||c|
 *     (four terms each bounded by |a||b||c|, each within 12u, three sums).
 * z = den + i num moves by at most E = E_num + E_den, so arg z moves by at
 * most asin(E/|z|) <= (pi/2) E/|z| while E <= |z|, and Omega = 2 arg z by
 * pi E/|z|, plus atan2's own rounding: |Omega - exact| <= pi E/|z| + 8 pi u.
 * |z| shrinks only near the face's edges and vertices, where the solid
 * angle itself varies fastest (|z|^2 = 2 (|a||b| + a.b)(|b||c| + b.c)
 * (|c||a| + c.a): zero exactly when q lies on an edge line between its
 * ends), so the bound follows the problem's own conditioning. Near the
 * face's plane inside it Omega is close to +-2 pi and its sign is the side
 * of q: where num is within E_num of 0, the sign of det[a b c] is taken
 * from the exact orient3 predicate, so q is never put on the wrong side
 * of the face (a jump of 4 pi); q exactly in the plane gives Omega = 0, the
 * principal value (on the face, the mean of -2 pi and 2 pi).
 *
 * Where that bound exceeds WINDING_REFINE (q near an edge: the fan
 * diagonals of a polygon and the shared edges of coplanar triangles
 * included, where the face's solid angle is smooth but its triangles' are
 * not), num and den are formed again as double-doubles from the exact
 * differences (core/ddx.h carries their error bounds), which brings E down
 * by a factor of about 2^53: a point 1e-12 from such an edge keeps ~1e-20.
 *
 * The sum is compensated (Neumaier), so the total error is the faces'
 * bounds summed plus about u |w|: |w - exact| <= (1/4pi) sum_f bound_f +
 * 2u |w|, the figure tests/c/test_winding.c checks against exact and
 * 60-digit references.
 *
 * Exact hierarchy (every batch). A cluster of faces S (a BVH child) and
 * the cap C over its boundary — the fan from one boundary vertex over the
 * boundary edges, reversed — form a closed surface inside the child's box,
 * whose winding number is 0 at every q outside that box (the outside is
 * connected to infinity). So there w_S(q) = -w_C(q): the cluster costs its
 * boundary edges (about the square root of its faces), not its faces, and
 * nothing is approximated (Jacobson, Kavan & Sorkine 2013, section 3.3).
 * Boundaries are the faces' directed edges with the uses a -> b and b -> a
 * cancelled (net counts, so non-manifold edges and soups are exact too),
 * merged bottom-up. Only the leaves whose box holds q are summed face by
 * face; the result equals the plain sum to the rounding of the terms.
 *
 * Far field (accuracy > 0). Each BVH child is a cluster of faces with
 * vector area N = sum a_f n_f (unit normals, areas a_f), area-weighted
 * centre p~, absolute area A_c and first moment M = sum a_f (c_f - p~)
 * n_f^T (c_f the face centroid). With K(y) = y/|y|^3 (the integrand is
 * n . K(x - q) / 4pi), Taylor's expansion about Y = p~ - q to second order
 * integrates exactly over flat faces:
 *     w_c ~ (1/4pi) [N . Y / |Y|^3 + tr(M) / |Y|^3 - 3 Y^T M Y / |Y|^5].
 * The remainder is the second derivative of n . K along x - p~, at most
 * 24 |x - p~|^2 / |xi|^4 per unit area (xi on the segment), so with r a
 * radius of the cluster about p~ (the farthest corner of its box):
 *     |w_c - exact| <= (1/4pi) A_c 12 r^2 / (|Y| - r)^4.
 * A cluster is expanded when that bound is at most a threshold tau; the
 * bounds of the expanded clusters are summed, and when the sum exceeds
 * `accuracy` the point is evaluated again with tau scaled down by the
 * excess (then, rarely, by direct summation), so |w - direct| <= accuracy
 * always (clusters share no face); the faces summed directly add their
 * own bounds above. tau starts at accuracy / 64 (a point meets a few dozen
 * clusters near the threshold). Clusters are computed per
 * call, bottom-up over the BVH (children before parents: nodes are in
 * depth-first order), their moments moved to the parent's centre by the
 * parallel-axis rule M = sum_i [M_i + (p~_i - p~) N_i^T].
 */
#include "mesh/mesh.h"
#include "core/scaling.h"
#include "core/ddx.h"
#include "core/predicates.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define WINDING_U 0x1p-53
#define WINDING_PI 3.14159265358979323846
#define WINDING_TINY 0x1p-1000
#define WINDING_REFINE 0x1p-40 /* rad: refine a triangle's angle beyond this bound */
/* A cluster's cap stands in for its faces only while the cap's own error
 * bound is at most this (in units of w): then the exact hierarchy keeps
 * the value of the plain sum to about its rounding. */
#define WINDING_CAP_TOLERANCE 0x1p-40

/* The angles' compensated sum (core/scaling.h) and their bounds' sum. */
typedef struct angle_sum {
    comp_sum angles;
    double   bound;
} angle_sum;

static void angle_sum_add(angle_sum *s, double x, double bound)
{
    comp_add(&s->angles, x);
    s->bound += bound;
}

static void sub3(const double x[3], const double y[3], double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = x[k] - y[k];
}

static double dot3(const double x[3], const double y[3])
{
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

/* The solid angle 2 atan2(num, den), num's sign made exact near 0 (e_num
 * and e_den bound the errors of num and den). *bound: pi E/(|z| - E) + 8 pi
 * u with E = e_num + e_den (4 pi when E >= |z|); computed only where
 * `want_bound` or where it may exceed WINDING_REFINE (then *refine = 1). */
static double solid_angle_of(double num, double e_num, double den, double e_den,
                             const double A[3], const double B[3], const double C[3],
                             const double q[3], int want_bound, double *bound, int *refine)
{
    *refine = 0;
    *bound = 0.0;
    if (fabs(num) <= e_num) {
        /* q near the face's plane: its side exactly (sign of det[a b c]) */
        int side = orient3_sign(A, B, C, q);
        if (side == 0)
            return 0.0; /* in the plane: 0, the principal value on the face */
        num = copysign(fabs(num), (double)side);
    }
    /* |z|^2, scaled to keep the squares finite and normal (num and den
     * are products of three differences) */
    double e = e_num + e_den, an = fabs(num), ad = fabs(den);
    double big = an > ad ? an : ad;
    double scale = big > 0x1p300 ? 0x1p-600 : big < 0x1p-300 ? 0x1p600 : 1.0;
    double ns = num * scale, ds = den * scale, es = e * scale;
    double rho2 = (ns * ns + ds * ds) * (1.0 - 4.0 * WINDING_U);
    /* pi E/(|z| - E) > 2^-40 needs E > |z| 2^-41.66, i.e. E^2 > |z|^2 2^-83.4 */
    *refine = es * es > rho2 * 0x1p-84;
    if (want_bound || *refine) {
        double rho = sqrt(rho2);
        *bound = es < rho ? WINDING_PI * es / (rho - es) + 8.0 * WINDING_PI * WINDING_U
                          : 4.0 * WINDING_PI;
    }
    return 2.0 * atan2(num, den);
}

static ddx ddx_dot3(const ddx x[3], const ddx y[3])
{
    return ddx_add(ddx_add(ddx_mul(x[0], y[0]), ddx_mul(x[1], y[1])), ddx_mul(x[2], y[2]));
}

/* The same from double-double num and den (see the top of the file). */
static double triangle_solid_angle_dd(const double A[3], const double B[3], const double C[3],
                                      const double q[3], double *bound)
{
    ddx a[3], b[3], c[3], e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        a[k] = ddx_diff(A[k], q[k]);
        b[k] = ddx_diff(B[k], q[k]);
        c[k] = ddx_diff(C[k], q[k]);
        e1[k] = ddx_diff(B[k], A[k]);
        e2[k] = ddx_diff(C[k], A[k]);
    }
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        n[k] = ddx_sub(ddx_mul(e1[i], e2[j]), ddx_mul(e1[j], e2[i]));
    }
    ddx num = ddx_dot3(a, n);
    ddx aa = ddx_dot3(a, a), bb = ddx_dot3(b, b), cc = ddx_dot3(c, c);
    ddx la = ddx_sqrt(aa, aa.hi - aa.err), lb = ddx_sqrt(bb, bb.hi - bb.err);
    ddx lc = ddx_sqrt(cc, cc.hi - cc.err);
    ddx den = ddx_add(ddx_add(ddx_mul(ddx_mul(la, lb), lc), ddx_mul(ddx_dot3(a, b), lc)),
                      ddx_add(ddx_mul(ddx_dot3(a, c), lb), ddx_mul(ddx_dot3(b, c), la)));
    /* the dd values rounded to doubles: u |x| more each */
    double num_d = num.hi + num.lo, den_d = den.hi + den.lo;
    int refine;
    return solid_angle_of(num_d, num.err + DDX_U * fabs(num_d), den_d,
                          den.err + DDX_U * fabs(den_d), A, B, C, q, 1, bound, &refine);
}

/* The signed solid angle of triangle A, B, C at q, and its error bound
 * when want_bound (see the top of the file). */
static double triangle_solid_angle(const double A[3], const double B[3], const double C[3],
                                   const double q[3], int want_bound, double *bound)
{
    double a[3], b[3], c[3], e1[3], e2[3], n[3], perm[3];
    sub3(A, q, a);
    sub3(B, q, b);
    sub3(C, q, c);
    sub3(B, A, e1);
    sub3(C, A, e2);
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    perm[0] = fabs(e1[1] * e2[2]) + fabs(e1[2] * e2[1]);
    perm[1] = fabs(e1[2] * e2[0]) + fabs(e1[0] * e2[2]);
    perm[2] = fabs(e1[0] * e2[1]) + fabs(e1[1] * e2[0]);
    double num = dot3(a, n);
    double e_num = 10.0 * WINDING_U * (fabs(a[0]) * perm[0] + fabs(a[1]) * perm[1]
                                       + fabs(a[2]) * perm[2])
                 + WINDING_TINY;
    double la = sqrt(dot3(a, a)), lb = sqrt(dot3(b, b)), lc = sqrt(dot3(c, c));
    double den = la * lb * lc + dot3(a, b) * lc + dot3(a, c) * lb + dot3(b, c) * la;
    double e_den = 64.0 * WINDING_U * la * lb * lc + WINDING_TINY;
    /* num and den are forms of degree 3 in the coordinates, so Omega is
     * unchanged when all four points are scaled by one power of two. Where
     * the triple products overflowed (num, den or a bound not finite:
     * beyond ~2^341) or |a||b||c| fell toward underflow (all within 2^-300
     * of q),
     * the four points are scaled to a largest coordinate near 1 (exact, but
     * for bits of coordinates 2^1000 below the largest) and evaluated again;
     * the test on the result costs the common case nothing measurable. */
    double lll = la * lb * lc;
    if (!(e_num + e_den <= 0x1p1000 && fabs(num) + fabs(den) + lll <= 0x1p1000
          && lll >= 0x1p-900)) {
        double m = fmax_nan(fmax_nan(max_abs3(A), max_abs3(B)), fmax_nan(max_abs3(C), max_abs3(q)));
        int e = pow2_exponent(m);
        if (m > 0.0 && (e > 8 || e < -8)) {
            double As[3], Bs[3], Cs[3], qs[3];
            scale3(As, A, e);
            scale3(Bs, B, e);
            scale3(Cs, C, e);
            scale3(qs, q, e);
            return triangle_solid_angle(As, Bs, Cs, qs, want_bound, bound);
        }
    }
    int refine;
    double omega = solid_angle_of(num, e_num, den, e_den, A, B, C, q, want_bound, bound, &refine);
    if (refine) {
        double bound_dd;
        double omega_dd = triangle_solid_angle_dd(A, B, C, q, &bound_dd);
        if (bound_dd < *bound) {
            *bound = bound_dd;
            return omega_dd;
        }
    }
    return omega;
}

/* Vertex i of BVH prim pr. */
static const double *prim_vertex(const isect_mesh *m, const mesh_prim *pr, int i)
{
    if (pr->nverts == 3)
        return pr->v + 3 * i;
    return mesh_vertex(m, m->idx[mesh_face_start(m, pr->face) + i]);
}

/* Adds prim pr's solid angle at q (its fan's), and its bound when
 * want_bound. */
static void prim_solid_angle(const isect_mesh *m, const mesh_prim *pr, const isect_xform *x,
                             const double q[3], int want_bound, angle_sum *s)
{
    /* x: the vertices' world images, each rounded once (x NULL: as stored) */
    double v[3][3];
    const double *v0 = prim_vertex(m, pr, 0), *v1, *v2 = prim_vertex(m, pr, 1);
    if (x != NULL) {
        xform_point_to_world(x, v0, v[0]);
        xform_point_to_world(x, v2, v[2]);
        v0 = v[0];
        v2 = v[2];
    }
    for (int j = 1; j + 1 < pr->nverts; j++) {
        double bound;
        v1 = v2;
        v2 = prim_vertex(m, pr, j + 1);
        if (x != NULL) {
            memcpy(v[1], v1, sizeof v[1]);
            xform_point_to_world(x, v2, v[2]);
            v1 = v[1];
            v2 = v[2];
        }
        double omega = triangle_solid_angle(v0, v1, v2, q, want_bound, &bound);
        angle_sum_add(s, omega, bound);
    }
}

static double winding_of(const angle_sum *s, double *bound)
{
    double w = comp_value(&s->angles) / (4.0 * WINDING_PI);
    if (bound != NULL)
        *bound = s->bound / (4.0 * WINDING_PI) + 2.0 * WINDING_U * fabs(w);
    return w;
}

/* Every face's angle at q, through x (NULL: object space). */
static double direct_sum(const isect_mesh *m, const isect_xform *x, const double q[3],
                         double *bound)
{
    /* Faces of zero area (left out of the BVH's prims) subtend none. */
    angle_sum s = { { 0.0, 0.0 }, 0.0 };
    for (int64_t i = 0; i < m->prim_count; i++)
        prim_solid_angle(m, &m->prims[i], x, q, bound != NULL, &s);
    return winding_of(&s, bound);
}

double mesh_winding_direct(const isect_mesh *m, const double q[3], double *bound)
{
    return direct_sum(m, NULL, q, bound);
}

/* Direct summation over the faces mapped to world space by x (q a world
 * point): a transform that is not a similarity (a non-uniform scaling, a
 * shear) changes the solid angles an open surface subtends, so its sum
 * cannot be taken in object space. Each vertex image is rounded once (to
 * about 2u of its coordinates), then the faces are summed as above. */
double mesh_winding_direct_world(const isect_mesh *m, const isect_xform *x, const double q[3])
{
    return direct_sum(m, x, q, NULL);
}

/* ----------------------------------------------------------- far field */

/* A cluster: the faces below one BVH child. */
typedef struct winding_cluster {
    double n[3];      /* sum a_f n_f: the vector area */
    double center[3]; /* area-weighted centroid (the box centre if no area) */
    double area;      /* sum a_f */
    double m[9];      /* sum a_f (c_f - center) n_f^T, row-major */
    double radius;    /* max distance from center to the child's box */
    int64_t edge_first; /* its boundary: edges[edge_first .. + edge_count) */
    int64_t edge_count;
    int64_t fans;       /* fan triangles below it (the direct sum's cost) */
} winding_cluster;

/* A boundary edge of a cluster: vertices a < b and the net number of its
 * uses a -> b minus b -> a by the cluster's faces (0: interior, dropped). */
typedef struct boundary_edge {
    int32_t a, b, count;
} boundary_edge;

struct mesh_winding_tree {
    winding_cluster *clusters; /* [node_count][BVH_WIDTH] */
    boundary_edge   *edges;    /* every cluster's boundary, by edge_first */
};

/* Fan triangle A, B, C as a one-face cluster about the origin's frame:
 * vector area v = (B - A) x (C - A) / 2, centroid c. */
static void fan_moments(const double A[3], const double B[3], const double C[3], double v[3],
                        double c[3])
{
    double e1[3], e2[3];
    sub3(B, A, e1);
    sub3(C, A, e2);
    v[0] = 0.5 * (e1[1] * e2[2] - e1[2] * e2[1]);
    v[1] = 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]);
    v[2] = 0.5 * (e1[0] * e2[1] - e1[1] * e2[0]);
    for (int k = 0; k < 3; k++)
        c[k] = (A[k] + B[k] + C[k]) / 3.0;
}

/* Accumulates parts (vector area n, centre, area, moment m about that
 * centre) into out, whose centre is fixed first: the area-weighted mean of
 * the parts' centres, or `fallback` without area. */
static void cluster_merge(winding_cluster *out, const winding_cluster *parts, int count,
                          const double fallback[3])
{
    double area = 0.0, center[3] = { 0.0, 0.0, 0.0 };
    for (int i = 0; i < count; i++) {
        area += parts[i].area;
        for (int k = 0; k < 3; k++)
            center[k] += parts[i].area * parts[i].center[k];
    }
    for (int k = 0; k < 3; k++)
        out->center[k] = area > 0.0 ? center[k] / area : fallback[k];
    out->area = area;
    for (int k = 0; k < 3; k++)
        out->n[k] = 0.0;
    for (int k = 0; k < 9; k++)
        out->m[k] = 0.0;
    for (int i = 0; i < count; i++) {
        double shift[3];
        sub3(parts[i].center, out->center, shift);
        for (int r = 0; r < 3; r++) {
            out->n[r] += parts[i].n[r];
            for (int c = 0; c < 3; c++)
                out->m[3 * r + c] += parts[i].m[3 * r + c] + shift[r] * parts[i].n[c];
        }
    }
}

/* The cluster of the items [first, first + count) of a leaf child. */
static int leaf_cluster(const isect_mesh *m, int32_t first, int count, const double fallback[3],
                        winding_cluster *out)
{
    /* One part per fan triangle (each its own centre, no moment). */
    int parts_count = 0;
    for (int i = 0; i < count; i++)
        parts_count += m->prims[first + i].nverts - 2;
    winding_cluster stack_parts[3 * BVH_MAX_LEAF];
    memset(stack_parts, 0, sizeof stack_parts); /* quiets -Wmaybe-uninitialized */
    winding_cluster *parts = parts_count <= 3 * BVH_MAX_LEAF
                           ? stack_parts : malloc((size_t)parts_count * sizeof *parts);
    if (parts == NULL)
        return ISECT_E_NOMEM;
    int k = 0;
    for (int i = 0; i < count; i++) {
        const mesh_prim *pr = &m->prims[first + i];
        const double *v0 = prim_vertex(m, pr, 0);
        for (int j = 1; j + 1 < pr->nverts; j++, k++) {
            winding_cluster *p = &parts[k];
            fan_moments(v0, prim_vertex(m, pr, j), prim_vertex(m, pr, j + 1), p->n, p->center);
            p->area = sqrt(dot3(p->n, p->n));
            for (int e = 0; e < 9; e++)
                p->m[e] = 0.0;
        }
    }
    cluster_merge(out, parts, parts_count, fallback);
    if (parts != stack_parts)
        free(parts);
    return ISECT_OK;
}

/* The farthest corner of child c's (float) box from centre. */
static double box_radius(const bvh_node *n, int c, const double center[3])
{
    double r2 = 0.0;
    for (int k = 0; k < 3; k++) {
        double lo = fabs((double)n->bounds[k][c] - center[k]);
        double hi = fabs((double)n->bounds[k + 3][c] - center[k]);
        double d = lo > hi ? lo : hi;
        r2 += d * d;
    }
    return sqrt(r2) * (1.0 + 4.0 * WINDING_U);
}

static int edge_order(const void *x, const void *y)
{
    const boundary_edge *e = x, *f = y;
    if (e->a != f->a)
        return e->a < f->a ? -1 : 1;
    return (e->b > f->b) - (e->b < f->b);
}

/* A growable array of edges. */
typedef struct edge_list {
    boundary_edge *e;
    int64_t        used, cap;
} edge_list;

static int edge_list_reserve(edge_list *l, int64_t more)
{
    if (l->used + more <= l->cap)
        return ISECT_OK;
    int64_t cap = l->cap > 0 ? l->cap : 256;
    while (cap < l->used + more)
        cap *= 2;
    boundary_edge *e = realloc(l->e, (size_t)cap * sizeof *e);
    if (e == NULL)
        return ISECT_E_NOMEM;
    l->e = e;
    l->cap = cap;
    return ISECT_OK;
}

/* The directed edges of the faces of leaf items [first, first + count). */
static int leaf_edges(const isect_mesh *m, int32_t first, int count, edge_list *l)
{
    for (int i = 0; i < count; i++) {
        const mesh_prim *pr = &m->prims[first + i];
        const int32_t *corner = m->idx + mesh_face_start(m, pr->face);
        int k = pr->nverts;
        if (edge_list_reserve(l, k) != ISECT_OK)
            return ISECT_E_NOMEM;
        for (int j = 0; j < k; j++) {
            int32_t a = corner[j], b = corner[j + 1 < k ? j + 1 : 0];
            if (a == b)
                continue;
            boundary_edge e = { a < b ? a : b, a < b ? b : a, a < b ? 1 : -1 };
            l->e[l->used++] = e;
        }
    }
    return ISECT_OK;
}

/* Sorts l, merges equal edges (their counts summed) and drops the
 * interior ones (net count 0): the boundary of the union. */
static void edges_normalize(edge_list *l)
{
    if (l->used == 0)
        return;
    qsort(l->e, (size_t)l->used, sizeof *l->e, edge_order);
    int64_t out = 0;
    for (int64_t i = 0; i < l->used;) {
        boundary_edge e = l->e[i++];
        while (i < l->used && l->e[i].a == e.a && l->e[i].b == e.b)
            e.count += l->e[i++].count;
        if (e.count != 0)
            l->e[out++] = e;
    }
    l->used = out;
}

int mesh_winding_tree_build(const isect_mesh *m, mesh_winding_tree **out)
{
    *out = NULL;
    mesh_winding_tree *t = malloc(sizeof *t);
    int64_t nodes = m->tree.node_count;
    winding_cluster *cl = malloc((size_t)(nodes > 0 ? nodes : 1) * BVH_WIDTH * sizeof *cl);
    if (t == NULL || cl == NULL) {
        free(t);
        free(cl);
        return ISECT_E_NOMEM;
    }
    t->clusters = cl;
    t->edges = NULL;
    edge_list all = { NULL, 0, 0 }, scratch = { NULL, 0, 0 };
    /* Children have larger indices than their parent (depth-first order). */
    for (int64_t i = nodes - 1; i >= 0; i--) {
        const bvh_node *n = &m->tree.nodes[i];
        for (int c = 0; c < BVH_WIDTH; c++) {
            winding_cluster *slot = &cl[i * BVH_WIDTH + c];
            double mid[3];
            for (int k = 0; k < 3; k++)
                mid[k] = 0.5 * ((double)n->bounds[k][c] + (double)n->bounds[k + 3][c]);
            if (n->child[c] < 0 && n->count[c] == 0) {
                /* empty: no faces, never expanded */
                slot->area = 0.0;
                slot->radius = 0.0;
                slot->edge_first = slot->edge_count = slot->fans = 0;
                for (int k = 0; k < 3; k++)
                    slot->n[k] = slot->center[k] = 0.0;
                for (int k = 0; k < 9; k++)
                    slot->m[k] = 0.0;
                continue;
            }
            if (!isfinite(mid[0] + mid[1] + mid[2]))
                mid[0] = mid[1] = mid[2] = 0.0;
            /* the moments, and the boundary: the children's boundaries
             * (or the leaf's face edges) merged */
            int status = ISECT_OK;
            scratch.used = 0;
            if (n->child[c] < 0) {
                status = leaf_cluster(m, ~n->child[c], n->count[c], mid, slot);
                if (status == ISECT_OK)
                    status = leaf_edges(m, ~n->child[c], n->count[c], &scratch);
                slot->fans = 0;
                for (int j = 0; j < n->count[c]; j++)
                    slot->fans += m->prims[~n->child[c] + j].nverts - 2;
            } else {
                const winding_cluster *kids = &cl[(int64_t)n->child[c] * BVH_WIDTH];
                cluster_merge(slot, kids, BVH_WIDTH, mid);
                slot->fans = 0;
                for (int j = 0; j < BVH_WIDTH && status == ISECT_OK; j++) {
                    slot->fans += kids[j].fans;
                    status = edge_list_reserve(&scratch, kids[j].edge_count);
                    if (status == ISECT_OK) {
                        memcpy(scratch.e + scratch.used, all.e + kids[j].edge_first,
                               (size_t)kids[j].edge_count * sizeof *scratch.e);
                        scratch.used += kids[j].edge_count;
                    }
                }
            }
            if (status == ISECT_OK) {
                edges_normalize(&scratch);
                status = edge_list_reserve(&all, scratch.used);
            }
            if (status != ISECT_OK) {
                free(all.e);
                free(scratch.e);
                mesh_winding_tree_free(t);
                return ISECT_E_NOMEM;
            }
            slot->edge_first = all.used;
            slot->edge_count = scratch.used;
            if (scratch.used > 0)
                memcpy(all.e + all.used, scratch.e, (size_t)scratch.used * sizeof *all.e);
            all.used += scratch.used;
            slot->radius = box_radius(n, c, slot->center);
        }
    }
    free(scratch.e);
    t->edges = all.e;
    *out = t;
    return ISECT_OK;
}

void mesh_winding_tree_free(mesh_winding_tree *t)
{
    if (t != NULL) {
        free(t->clusters);
        free(t->edges);
    }
    free(t);
}

/* The cluster's far-field value at q (the expansion at the top). */
static double cluster_far(const winding_cluster *c, const double q[3], double dist)
{
    double y[3];
    sub3(c->center, q, y);
    double d3 = dist * dist * dist, d5 = d3 * dist * dist;
    double my[3];
    for (int r = 0; r < 3; r++)
        my[r] = c->m[3 * r] * y[0] + c->m[3 * r + 1] * y[1] + c->m[3 * r + 2] * y[2];
    double trace = c->m[0] + c->m[4] + c->m[8];
    return dot3(c->n, y) / d3 + trace / d3 - 3.0 * dot3(y, my) / d5;
}

/* q strictly outside child c's (closed, outward-rounded) box. */
static int outside_box(const bvh_node *n, int c, const double q[3])
{
    for (int k = 0; k < 3; k++)
        if (q[k] < (double)n->bounds[k][c] || q[k] > (double)n->bounds[k + 3][c])
            return 1;
    return 0;
}

/* The cluster's solid angle at q through its boundary (see the top of the
 * file): the cap, the fan from one boundary vertex over the boundary
 * edges, closes the cluster inside its box, so for q outside the box the
 * cluster's angle is minus the cap's: sum count * Omega(apex, a, b) over
 * the directed boundary edges a -> b (the reversed cap). The
 * identity is exact, but the cap's triangles can be far worse conditioned
 * than the faces (a cluster of slivers 2^200 long seen from beside them:
 * its cap's angles cancel to nothing in double-double too), so it is
 * added to s only when its own error bound is at most `tolerance` (in
 * units of w; without want_bound, the bounds of the triangles refined
 * because theirs may exceed WINDING_REFINE); returns 1 then, else 0 (the
 * caller sums the faces). */
static int cluster_cap(const isect_mesh *m, const mesh_winding_tree *t, const winding_cluster *cl,
                       const double q[3], int want_bound, double tolerance, angle_sum *s)
{
    if (cl->edge_count == 0)
        return 1; /* no boundary: a closed cluster, 0 outside its box (and the
                     tree may hold no edges at all: t->edges NULL) */
    const boundary_edge *e = t->edges + cl->edge_first;
    const double *apex = mesh_vertex(m, e[0].a);
    angle_sum cap = { { 0.0, 0.0 }, 0.0 };
    for (int64_t i = 0; i < cl->edge_count; i++) {
        if (e[i].a == e[0].a)
            continue; /* a fan triangle with two corners at the apex: 0 */
        double bound;
        /* without want_bound, a bound is computed only for a triangle
         * whose angle may be off by more than WINDING_REFINE: those alone
         * can reject the cap, and the test costs no square root */
        double omega = triangle_solid_angle(apex, mesh_vertex(m, e[i].a), mesh_vertex(m, e[i].b), q,
                                            want_bound, &bound);
        angle_sum_add(&cap, e[i].count * omega, fabs((double)e[i].count) * bound);
    }
    if (!(cap.bound <= 4.0 * WINDING_PI * tolerance))
        return 0;
    /* e[i].count * Omega over the boundary's directed edges is already the
     * reversed cap's angle: the cluster's */
    comp_add(&s->angles, cap.angles.hi);
    comp_add(&s->angles, cap.angles.lo);
    s->bound += cap.bound;
    return 1;
}

/* One pass: clusters expanded where their bound is at most tau; *far_sum
 * the sum of those bounds. */
static double winding_far_pass(const isect_mesh *m, const mesh_winding_tree *t, const double q[3],
                               double tau, double *far_sum, double *bound)
{
    /* bound = 12 A_c r^2 / (4 pi (|Y| - r)^4), in units of w */
    const double k = 12.0 / (4.0 * WINDING_PI);
    angle_sum s = { { 0.0, 0.0 }, 0.0 };
    double far = 0.0;
    int32_t stack[BVH_STACK_SIZE];
    int sp = 0;
    int32_t cur = 0;
    for (;;) {
        const bvh_node *n = &m->tree.nodes[cur];
        const winding_cluster *cl = &t->clusters[(int64_t)cur * BVH_WIDTH];
        for (int c = 0; c < BVH_WIDTH; c++) {
            if (n->child[c] < 0 && n->count[c] == 0)
                continue;
            double y[3];
            sub3(cl[c].center, q, y);
            double dist = sqrt(dot3(y, y)), gap = dist - cl[c].radius;
            double g2 = gap * gap;
            double e = gap > 0.0 ? k * cl[c].area * cl[c].radius * cl[c].radius / (g2 * g2) : INFINITY;
            if (e <= tau) {
                angle_sum_add(&s, cluster_far(&cl[c], q, dist), 0.0);
                far += e;
            } else if (cl[c].edge_count < cl[c].fans && outside_box(n, c, q)
                       && cluster_cap(m, t, &cl[c], q, bound != NULL, WINDING_CAP_TOLERANCE, &s)) {
                /* the cluster through its boundary */
            } else if (n->child[c] >= 0) {
                stack[sp++] = n->child[c];
            } else {
                int32_t first = ~n->child[c];
                for (int i = 0; i < n->count[c]; i++)
                    prim_solid_angle(m, &m->prims[first + i], NULL, q, bound != NULL, &s);
            }
        }
        if (sp == 0)
            break;
        cur = stack[--sp];
    }
    *far_sum = far;
    double w = winding_of(&s, bound);
    if (bound != NULL)
        *bound += far;
    return w;
}

double mesh_winding_far(const isect_mesh *m, const mesh_winding_tree *t, const double q[3],
                        double accuracy, double *bound)
{
    if (accuracy == 0.0) {
        double far;
        return winding_far_pass(m, t, q, -1.0, &far, bound); /* exact: caps, no expansion */
    }
    double tau = accuracy / 64.0;
    for (int pass = 0; pass < 4; pass++) {
        double far;
        double w = winding_far_pass(m, t, q, tau, &far, bound);
        if (far <= accuracy)
            return w;
        /* the sum falls about as sqrt(tau) (bounds ~ r^4, cluster counts
         * ~ 1/r^2 on a surface) */
        double f = 0.7 * accuracy / far;
        tau *= f * f;
    }
    return mesh_winding_direct(m, q, bound);
}

double mesh_generalized_winding(const isect_mesh *m, const double q[3], double *bound)
{
    int64_t count;
    if (m->oriented && mesh_crossing_count(m, q, &count) == 0) {
        if (bound != NULL)
            *bound = 0.0;
        return (double)count; /* exact */
    }
    return mesh_winding_direct(m, q, bound);
}
