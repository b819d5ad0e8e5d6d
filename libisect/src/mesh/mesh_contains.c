/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh_contains.c — point containment in a mesh: the exact signed count
 * of crossings along +x (mesh_crossing_count, which the winding numbers
 * use too) and the three rules of isect_shape.flags (mesh_contains).
 *
 * Parity of crossings along the fixed ray from p in +x, with every decision
 * exact on the unrounded input: the 2D claims use orient2_sign_perturbed /
 * the winding rule at p's (y, z) (the same symbolic perturbation as the ray
 * tests, and the same predicates), and the side of p on which a claimed
 * face is crossed is the exact sign of orient3 (Shewchuk). Polygon faces
 * count as their fan from the first vertex: the fan's inner edges cancel in
 * pairs, so its crossing parity is the polygon's even-odd parity. Points on
 * the surface are inside (solids are closed sets, as for the analytic
 * shapes): see mesh_contains.
 *
 * In detail: p is inside when it lies on the surface (the solid is a closed set, as
 * the analytic solids are) or when the fixed ray from p in +x crosses the
 * surface an odd number of times. Every decision is exact on the input as
 * given (no rounded projection): in the +x frame a point's 2D coordinates
 * are its own (y, z), so orient2_sign_perturbed can take p's (y, z) as the
 * query point and the perturbed line through it crosses each fan triangle
 * or not, consistently across shared edges; orient3_sign then says on
 * which side of p the crossing is. A claimed fan triangle whose plane
 * passes through p has p in it (closed) and is found by the on-surface
 * test instead; it is not a crossing beyond p.
 */
#include "mesh/mesh.h"

#include "core/predicates.h"

/* The +x ray's 2D coordinates of a point. */
static void yz_of(const double v[3], double out[2])
{
    out[0] = v[1];
    out[1] = v[2];
}

/* 1 when p lies in the closed triangle a, b, c (exactly); 0 also for a
 * triangle of zero area. */
static int point_in_closed_triangle(const double a[3], const double b[3], const double c[3],
                                    const double p[3])
{
    if (orient3_sign(a, b, c, p) != 0)
        return 0;
    /* A coordinate plane onto which the triangle projects with nonzero
     * area: its normal's largest component (approximately) first. */
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
    }
    n[0] = fabs(e1[1] * e2[2] - e1[2] * e2[1]);
    n[1] = fabs(e1[2] * e2[0] - e1[0] * e2[2]);
    n[2] = fabs(e1[0] * e2[1] - e1[1] * e2[0]);
    int order[3] = { 0, 1, 2 };
    for (int i = 1; i < 3; i++)
        for (int j = i; j > 0 && n[order[j]] > n[order[j - 1]]; j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    for (int i = 0; i < 3; i++) {
        int drop = order[i], u = (drop + 1) % 3, w = (drop + 2) % 3;
        const double a2[2] = { a[u], a[w] }, b2[2] = { b[u], b[w] }, c2[2] = { c[u], c[w] };
        const double p2[2] = { p[u], p[w] };
        int s = orient2_sign(a2, b2, c2);
        if (s == 0)
            continue;
        return orient2_sign(a2, b2, p2) != -s && orient2_sign(b2, c2, p2) != -s
            && orient2_sign(c2, a2, p2) != -s;
    }
    return 0;
}

/* 1 when p lies on the closed segment a-b. */
static int point_on_segment(const double a[3], const double b[3], const double p[3])
{
    for (int k = 0; k < 3; k++)
        if (p[k] < (a[k] < b[k] ? a[k] : b[k]) || p[k] > (a[k] < b[k] ? b[k] : a[k]))
            return 0;
    return collinear3(a, b, p);
}

/* The face's vertex i. */
static const double *face_vertex(const isect_mesh *m, const mesh_prim *pr, int i)
{
    if (pr->nverts == 3)
        return pr->v + 3 * i;
    return mesh_vertex(m, m->idx[mesh_face_start(m, pr->face) + i]);
}

/* p on the closed face: for a triangle, in it; for a polygon, on one of its
 * edges, or on one of its fan triangles and inside its outline seen along
 * that triangle's normal (the even-odd rule, with the library's perturbed
 * rule for points on a projected edge line). For a planar polygon this is
 * exactly the closed polygon; fold regions of a concave fan (covered twice,
 * with opposite orientations) are excluded. */
static int point_on_face(const isect_mesh *m, const mesh_prim *pr, const double p[3])
{
    int n = pr->nverts;
    if (n == 3)
        return point_in_closed_triangle(pr->v, pr->v + 3, pr->v + 6, p);
    for (int i = 0; i < n; i++)
        if (point_on_segment(face_vertex(m, pr, i), face_vertex(m, pr, (i + 1) % n), p))
            return 1;
    const double *v0 = face_vertex(m, pr, 0);
    for (int i = 1; i + 1 < n; i++) {
        const double *b = face_vertex(m, pr, i), *c = face_vertex(m, pr, i + 1);
        if (!point_in_closed_triangle(v0, b, c, p))
            continue;
        /* Project along the axis of the fan triangle's largest normal
         * component (nonzero: the triangle has area). */
        double e1[3], e2[3], nrm[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = b[k] - v0[k];
            e2[k] = c[k] - v0[k];
        }
        nrm[0] = fabs(e1[1] * e2[2] - e1[2] * e2[1]);
        nrm[1] = fabs(e1[2] * e2[0] - e1[0] * e2[2]);
        nrm[2] = fabs(e1[0] * e2[1] - e1[1] * e2[0]);
        int drop = nrm[1] > nrm[0] ? 1 : 0;
        drop = nrm[2] > nrm[drop] ? 2 : drop;
        int u = (drop + 1) % 3, w = (drop + 2) % 3;
        const double p2[2] = { p[u], p[w] };
        int32_t winding = 0;
        const double *prev = face_vertex(m, pr, n - 1);
        for (int j = 0; j < n; j++) {
            const double *cur = face_vertex(m, pr, j);
            const double q0[2] = { prev[u], prev[w] }, q1[2] = { cur[u], cur[w] };
            winding += winding_edge(q0, q1, p2);
            prev = cur;
        }
        return fill_rule_inside(winding, ISECT_EVEN_ODD);
    }
    return 0;
}

/* The crossing of the perturbed +x ray from p with fan triangle a, b, c
 * beyond p: 0 for none; else the sign of the triangle's normal's x
 * component (+1: the ray leaves through the triangle's front, -1: it
 * enters through it). */
static int fan_crossing(const double a[3], const double b[3], const double c[3],
                        const double p[3], const double p2[2])
{
    /* Cheap rejections first: the triangle's (y, z) box must hold p's
     * (y, z) (a point strictly outside stays outside when perturbed), and
     * some vertex must lie at x >= p.x. */
    if ((a[1] < p[1] && b[1] < p[1] && c[1] < p[1]) || (a[1] > p[1] && b[1] > p[1] && c[1] > p[1])
        || (a[2] < p[2] && b[2] < p[2] && c[2] < p[2]) || (a[2] > p[2] && b[2] > p[2] && c[2] > p[2])
        || (a[0] < p[0] && b[0] < p[0] && c[0] < p[0]))
        return 0;
    double a2[2], b2[2], c2[2];
    yz_of(a, a2);
    yz_of(b, b2);
    yz_of(c, c2);
    int s = orient2_sign_perturbed(a2, b2, p2);
    if (s == 0 || orient2_sign_perturbed(b2, c2, p2) != s
        || orient2_sign_perturbed(c2, a2, p2) != s)
        return 0;
    /* Claimed; s is the sign of the normal's x component, so the crossing
     * lies beyond p exactly when det(a-p, b-p, c-p) has the sign s. */
    return orient3_sign(a, b, c, p) == s ? s : 0;
}

int mesh_crossing_count(const isect_mesh *m, const double p[3], int64_t *count)
{
    const bvh_node *nodes = m->tree.nodes;
    double p2[2];
    yz_of(p, p2);
    int32_t stack[BVH_STACK_SIZE];
    int sp = 0;
    int32_t cur = 0;
    int64_t crossings = 0;
    for (;;) {
        const bvh_node *n = &nodes[cur];
        /* Children met by the ray from p in +x, or holding p: closed boxes
         * (conservative, the perturbation being infinitesimal). */
        for (int c = 0; c < BVH_WIDTH; c++) {
            if (!(n->bounds[1][c] <= p[1] && p[1] <= n->bounds[4][c]
                  && n->bounds[2][c] <= p[2] && p[2] <= n->bounds[5][c]
                  && p[0] <= n->bounds[3][c]))
                continue;
            if (n->child[c] >= 0) {
                stack[sp++] = n->child[c];
                continue;
            }
            int32_t first = ~n->child[c];
            for (int i = 0; i < n->count[c]; i++) {
                const mesh_prim *pr = &m->prims[first + i];
                int nv = pr->nverts;
                /* On the surface: the closed set says inside. Only faces
                 * whose box holds p can hold it. */
                double lo[3], hi[3];
                for (int k = 0; k < 3; k++)
                    lo[k] = hi[k] = face_vertex(m, pr, 0)[k];
                for (int j = 1; j < nv; j++) {
                    const double *v = face_vertex(m, pr, j);
                    for (int k = 0; k < 3; k++) {
                        lo[k] = v[k] < lo[k] ? v[k] : lo[k];
                        hi[k] = v[k] > hi[k] ? v[k] : hi[k];
                    }
                }
                if (lo[0] <= p[0] && p[0] <= hi[0] && lo[1] <= p[1] && p[1] <= hi[1]
                    && lo[2] <= p[2] && p[2] <= hi[2] && point_on_face(m, pr, p))
                    return 1;
                const double *v0 = face_vertex(m, pr, 0);
                for (int j = 1; j + 1 < nv; j++)
                    crossings += fan_crossing(v0, face_vertex(m, pr, j), face_vertex(m, pr, j + 1),
                                              p, p2);
            }
        }
        if (sp == 0)
            break;
        cur = stack[--sp];
    }
    *count = crossings;
    return 0;
}

/* The rules (isect_shape.flags): EVEN_ODD, the parity of the crossings;
 * NONZERO, a nonzero integer winding number (oriented meshes); WINDING,
 * w >= 1/2 in world space (a mirroring transform negates w), exact on an
 * oriented mesh, else the directly summed generalized winding number. A
 * point on a closed mesh's surface is inside (closed sets). */
int mesh_contains(const isect_shape *s, const double p[3])
{
    const isect_mesh *m = s->mesh;
    int orientation = s->xform != NULL ? xform_orientation(s->xform) : 1;
    if (s->flags == ISECT_WINDING && !m->oriented) {
        if (s->xform != NULL && !xform_is_similarity(s->xform)) {
            /* solid angles bend under this transform: summed over the
             * faces' world images, at p's (its world point, round trip) */
            double world[3];
            xform_point_to_world(s->xform, p, world);
            return mesh_winding_direct_world(m, s->xform, world) >= 0.5;
        }
        return orientation * mesh_winding_direct(m, p, NULL) >= 0.5;
    }
    int64_t count;
    if (mesh_crossing_count(m, p, &count))
        return 1;
    return s->flags == ISECT_EVEN_ODD ? (int)(count & 1)
         : s->flags == ISECT_NONZERO  ? count != 0
                                      : orientation * count >= 1;
}
