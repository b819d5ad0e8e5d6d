/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh_query.c — ray queries against a mesh through its BVH: closest hit,
 * all hits, any hit, one ray at a time or many interleaved (the batch).
 * Point containment is in mesh_contains.c.
 *
 * Every face decision is made by the shared exact tests (triangle_test.h's
 * triangle_hit, planar.h's polygon_hit_plane_framed) in the ray's sheared
 * frame, computed once per ray. Everything in front of them only skips
 * faces those tests would certainly reject, so the BVH changes the speed
 * and never the answer: a query returns bit for bit what testing every
 * face in turn would (the tests check this against brute force).
 *
 * Why no hit is lost between boxes
 * ---------------------------------
 * The node test (core/bvh_walk.h, which states its numerics) needs every
 * hit that matters to lie, as org + t dir, within 4uD (1 + 2^-40) of its
 * item's box, D = (max|o_k| + max|vertex coordinate|)(1 + 4u). Every
 * vertex-minus-origin difference is at most D. The exact test claims a
 * face only when the exact projection of the ray's line meets it, i.e.
 * when the line meets the face (a triangle: its exact crossing with the
 * plane lies in the closed triangle), and reports t within 4 ulp of that
 * crossing: org + t dir lies within 4u|t dir| <= 4uD (1 + 2^-40) of a
 * point of the face, hence of its box.
 *
 * Polygon faces take t from their plane, t = n.(c - o) / n.d, which for a
 * grazing ray may land far outside the face's box; subtrees holding a
 * polygon (BVH_FLAG_LOOSE_T) are therefore culled only laterally (the line
 * against the padded box), never by [tmin, tmax] or the current closest t.
 *
 * The triangle pre-filter
 * -----------------------
 * Before the exact test each triangle gets Woop's three edge functions in
 * plain double from projections computed without fma (so that x86-64
 * without -mfma never calls libm's fma in the loop). Each projection
 * differs from the exact projection the exact test decides on (x = A[kx] -
 * (d[kx]/d[kz]) A[kz] in real numbers, A = v - o) by at most 6.1uD: uD for
 * each rounded difference, u|S| <= u for the rounded shear S, then the
 * product and the subtraction, |x| <= 2D. So an edge function is off by at
 * most 4 (6.1uD)(2D) + 3 roundings of products below 8D^2, about 65uD^2;
 * with bound B = 128uD^2 (and a floor of 2^-1000, below which products may
 * be subnormal), two edge functions beyond +B and -B prove the exact test
 * rejects. The exact crossing of a claimed triangle lies in the closed
 * triangle, so its t lies in [min z, max z] of the exact sheared z =
 * A[kz]/d[kz]; the reported t is within 3.5u|t| of it and each computed z
 * within 3.1u|z| of the exact one: a triangle whose whole z range is
 * outside [tmin, current t] by 16u max|z| is skipped.
 */
#include "mesh/mesh.h"

#include "core/bvh_walk.h"

#include "prim/planar.h"
#include "core/predicates.h"
#include "core/ray_frame.h"
#include "core/ratio.h"
#include "core/scaling.h"
#include "prim/triangle_test.h"
#include "core/vec3.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>


/* The edge-function and t bounds of the pre-filter in units of u*D^2 and
 * u*max|z| (see above). */
#define EDGE_BOUND_ULPS 128.0
#define EDGE_BOUND_FLOOR 0x1p-1000
#define T_SLACK_ULPS 16.0

enum query_mode { QUERY_CLOSEST, QUERY_ALL, QUERY_ANY };

typedef struct query {
    const isect_mesh   *mesh;
    const bvh_node     *nodes;  /* the mesh's, for the traversal */
    const mesh_prim    *prims;
    const isect_ray    *ray;
    const isect_params *prm;
    lane_ray  lane;        /* the ray as one lane, and whether it and the
                              faces lie in face_lanes.h's fast range: 1 all
                              faces, -1 to be checked per face (a vertex
                              beyond it), 0 none (made with the frame) */
    int       fast_range;
    ray_frame frame;       /* made at the first leaf (frame_ready): a ray that
                              misses every box never pays for it */
    int       frame_ready;
    slab_ray  slab;        /* the node test's constants (core/bvh_walk.h) */
    /* Pre-filter (set with the frame, at the first leaf). */
    double edge_bound;
    int    cull_back;
    /* Results. */
    double     t_limit;   /* closest: t of the best hit so far (else tmax) */
    isect_hit  best;
    int        found;
    int64_t    count;     /* all: hits found */
    isect_hit *hits;      /* all: max-heap of the best min(count, cap) */
    int64_t    cap;
} query;

static void query_init(query *q, const isect_mesh *m, const isect_ray *ray,
                       const isect_params *prm)
{
    q->mesh = m;
    q->nodes = m->tree.nodes;
    q->prims = m->prims;
    q->ray = ray;
    q->prm = prm;
    q->frame_ready = 0;
    q->t_limit = ray->tmax;
    q->found = 0;
    q->count = 0;
    q->hits = NULL;
    q->cap = 0;
    slab_init(&q->slab, m->coord_bound, 0.0, ray);
}

/* What the faces' tests need, made at the first leaf: the frame, the ray
 * as one lane with its fast-range verdict, and the pre-filter's bound.
 * d * d may overflow (infinite bound: every triangle goes to the exact
 * test) or, near zero, underflow below the floor. */
static void query_leaf_init(query *q)
{
    ray_frame_shear(q->ray, &q->frame);
    q->frame_ready = 1;
    lane_ray_from(&q->lane, q->ray);
    q->fast_range = !lane_ray_in_range(&q->lane, 0x1p200) ? 0
                  : q->mesh->coord_bound <= 0x1p200     ? 1
                                                        : -1;
    q->edge_bound = EDGE_BOUND_ULPS * UNIT_ROUNDOFF * q->slab.d * q->slab.d;
    if (!(q->edge_bound > EDGE_BOUND_FLOOR))
        q->edge_bound = isnan(q->edge_bound) ? INFINITY : EDGE_BOUND_FLOOR;
    q->cull_back = (q->prm->flags & ISECT_CULL_BACK) != 0;
}

/* 0 when the exact triangle test certainly rejects the triangle or its
 * hit lies certainly outside [t_lo, t_hi]; 1 when it must be run. */
static ALWAYS_INLINE int triangle_candidate(const query *q, const double *v, double t_lo,
                                            double t_hi)
{
    const ray_frame *f = &q->frame;
    const int kx = f->kx, ky = f->ky, kz = f->kz;
    double az = v[kz] - f->org[kz], bz = v[3 + kz] - f->org[kz], cz = v[6 + kz] - f->org[kz];
    double ax = (v[kx] - f->org[kx]) - f->sx * az, ay = (v[ky] - f->org[ky]) - f->sy * az;
    double bx = (v[3 + kx] - f->org[kx]) - f->sx * bz;
    double by = (v[3 + ky] - f->org[ky]) - f->sy * bz;
    double cx = (v[6 + kx] - f->org[kx]) - f->sx * cz;
    double cy = (v[6 + ky] - f->org[ky]) - f->sy * cz;
    double e_bc = bx * cy - by * cx;
    double e_ca = cx * ay - cy * ax;
    double e_ab = ax * by - ay * bx;
    double bound = q->edge_bound;
    int negative = (e_bc < -bound) | (e_ca < -bound) | (e_ab < -bound);
    int positive = (e_bc > bound) | (e_ca > bound) | (e_ab > bound);
    if (negative & positive)
        return 0;
    /* z exactly as the exact test computes it: (p - org)[kz] * sz. */
    double za = az * f->sz, zb = bz * f->sz, zc = cz * f->sz;
    /* Comparisons, not fmin/fmax: those are libm calls without -ffast-math. */
    double z_min = za < zb ? za : zb, z_max = za < zb ? zb : za;
    z_min = zc < z_min ? zc : z_min;
    z_max = zc > z_max ? zc : z_max;
    double z_abs = -z_min > z_max ? -z_min : z_max;
    double slack = T_SLACK_ULPS * UNIT_ROUNDOFF * z_abs;
    return !(z_min - slack > t_hi || z_max + slack < t_lo);
}

/* The largest |coordinate| of face f's vertices. */
static double face_extent(const isect_mesh *m, int32_t f)
{
    const int32_t *c = m->idx + mesh_face_start(m, f);
    int size = mesh_face_size(m, f);
    double e = 0.0;
    for (int i = 0; i < size; i++)
        e = fmax_nan(e, max_abs3(mesh_vertex(m, c[i])));
    return e;
}

/* The exact crossing of face f's plane (the plane its test takes t from)
 * with the line of ray, in the scaled units of planar.h's *_crossing_xp. */
static void face_crossing_xp(const isect_mesh *m, const isect_ray *ray, int32_t f, int e,
                             int e_dir, xp *num, xp *den)
{
    const int32_t *c = m->idx + mesh_face_start(m, f);
    int size = mesh_face_size(m, f);
    if (size == 3)
        triangle_crossing_xp(ray, mesh_vertex(m, c[0]), mesh_vertex(m, c[1]),
                             mesh_vertex(m, c[2]), e, e_dir, num, den);
    else
        polygon_crossing_xp(ray, m->verts, c, size, e, e_dir, num, den);
}

/*
 * (a.t, a.prim) before (b.t, b.prim), where a t rounded alike is told apart
 * by the exact crossing parameters of the two faces (SPEC, accuracy
 * contract: the closest hit is the exactly closest one; a ray grazing a
 * silhouette edge enters one face and leaves the next within a fraction
 * of an ulp), and exactly equal ones by the face index. Both records are
 * hits, so neither face is parallel to the ray (den != 0); one scaling for
 * both faces lets core/ratio.c compare them exactly. Rounded ties are
 * rare, so the exact comparison costs nothing on the whole.
 */
static int hit_before(const query *q, const isect_hit *a, const isect_hit *b)
{
    if (a->t != b->t)
        return a->t < b->t;
    if (a->prim == b->prim)
        return 0;
    const isect_mesh *m = q->mesh;
    const isect_ray *ray = q->ray;
    double ext = fmax_nan(max_abs3(ray->org),
                          fmax_nan(face_extent(m, a->prim), face_extent(m, b->prim)));
    int e = pow2_exponent(ext), e_dir = pow2_exponent(max_abs3(ray->dir));
    xp na, da, nb, db;
    face_crossing_xp(m, ray, a->prim, e, e_dir, &na, &da);
    face_crossing_xp(m, ray, b->prim, e, e_dir, &nb, &db);
    int c = ratio_cmp(&na, &da, &nb, &db);
    return c != 0 ? c < 0 : a->prim < b->prim;
}

/* The max-heap of the best cap hits (by hit_before), at hits[0..n). */
static void heap_sift_down(const query *q, isect_hit *h, int64_t n, int64_t i)
{
    for (;;) {
        int64_t l = 2 * i + 1, r = l + 1, top = i;
        if (l < n && hit_before(q, &h[top], &h[l]))
            top = l;
        if (r < n && hit_before(q, &h[top], &h[r]))
            top = r;
        if (top == i)
            return;
        isect_hit tmp = h[i];
        h[i] = h[top];
        h[top] = tmp;
        i = top;
    }
}

static void heap_push(const query *q, isect_hit *h, int64_t n, const isect_hit *x)
{
    int64_t i = n;
    h[i] = *x;
    while (i > 0) {
        int64_t parent = (i - 1) / 2;
        if (!hit_before(q, &h[parent], &h[i]))
            return;
        isect_hit tmp = h[i];
        h[i] = h[parent];
        h[parent] = tmp;
        i = parent;
    }
}

/* In place ascending order of a max-heap of n hits. */
static void heap_sort(const query *q, isect_hit *h, int64_t n)
{
    for (int64_t end = n - 1; end > 0; end--) {
        isect_hit tmp = h[0];
        h[0] = h[end];
        h[end] = tmp;
        heap_sift_down(q, h, end, 0);
    }
}

/* Records a hit of the exact test that is in range and survives culling;
 * 1 when the traversal can stop (any hit). */
static int query_take(query *q, int mode, const isect_hit *h)
{
    switch (mode) {
    case QUERY_CLOSEST:
        if (!q->found || hit_before(q, h, &q->best)) {
            q->best = *h;
            q->found = 1;
            q->t_limit = h->t;
            slab_set_limit(&q->slab, h->t);
        }
        return 0;
    case QUERY_ALL: {
        int64_t kept = q->count < q->cap ? q->count : q->cap;
        if (q->count < q->cap) {
            heap_push(q, q->hits, kept, h);
        } else if (q->cap > 0 && hit_before(q, h, &q->hits[0])) {
            q->hits[0] = *h;
            heap_sift_down(q, q->hits, kept, 0);
        }
        q->count++;
        return 0;
    }
    default:
        q->best = *h;
        q->found = 1;
        return 1;
    }
}

/* The faces of one leaf; 1 when the traversal can stop. */
static ALWAYS_INLINE int query_leaf_body(query *q, int mode, int32_t first, int32_t count)
{
    const isect_mesh *m = q->mesh;
    const isect_ray *ray = q->ray;
    if (!q->frame_ready)
        query_leaf_init(q);
    for (int32_t i = 0; i < count; i++) {
        const mesh_prim *p = &q->prims[first + i];
        isect_hit h;
        int hit;
        if (p->nverts == 3) {
            if (!triangle_candidate(q, p->v, ray->tmin, q->t_limit))
                continue;
            /* The plane precomputed. Zero only where the exact normal
             * could not be rounded to a unit vector: never for a face of
             * nonzero area within the exact range (planar.h,
             * xp_normalize_up), and zero-area faces, which the exact test
             * never claims, are not in the BVH. */
            if (p->n[0] == 0.0 && p->n[1] == 0.0 && p->n[2] == 0.0)
                continue;
            int fast = q->fast_range >= 0 ? q->fast_range
                                          : triangle_fast_range(&q->lane, p->v, p->v + 3, p->v + 6);
            hit = triangle_hit(&q->frame, ray, &q->lane, fast, p->v, p->v + 3, p->v + 6, p->n, &h);
        } else {
            hit = polygon_hit_plane_framed(&q->frame, ray, m->verts,
                                           m->idx + mesh_face_start(m, p->face), p->nverts,
                                           ISECT_EVEN_ODD, &m->planes[p->face], &h);
        }
        /* The dispatcher's filter (hits_finish): NaN t never passes. */
        if (!hit || !(h.t >= ray->tmin && h.t <= ray->tmax))
            continue;
        if (q->cull_back && h.kind == ISECT_EXIT)
            continue;
        h.prim = p->face;
        if (query_take(q, mode, &h))
            return 1;
    }
    return 0;
}

/* The leaf loop, compiled for any x86-64 and (see WALK_AVX2) for AVX2 and
 * FMA, where the exact triangle test's nine fma are instructions instead
 * of libm calls; the walk's copy for each calls its own (query_leaf_for). */
static int query_leaf(query *q, int mode, int32_t first, int32_t count)
{
    return query_leaf_body(q, mode, first, count);
}

#if WALK_AVX2
WALK_TARGET_AVX2 static int query_leaf_avx2(query *q, int mode, int32_t first, int32_t count)
{
    return query_leaf_body(q, mode, first, count);
}
#endif

/* The leaf loop of the traversal's copy for any x86-64 (avx2 0) or for
 * AVX2 (avx2 1, a constant). */
static ALWAYS_INLINE int query_leaf_for(query *q, int mode, int32_t first, int32_t count,
                                        int avx2)
{
#if WALK_AVX2
    if (avx2)
        return query_leaf_avx2(q, mode, first, count);
#endif
    (void)avx2;
    return query_leaf(q, mode, first, count);
}

/* Asks for the first 256 bytes at the memory reference r (as in
 * node_ref) points at: a whole inner node, or a leaf's first prims (two
 * and a half: most leaves hold one to three; the hardware prefetcher
 * follows a larger leaf's in-order reads). The same four lines for both,
 * with no loop over a leaf's lines, which cost more than it saved
 * (measured on the icosphere benchmark: 2-5 % faster on every ray set
 * than asking for every line of a leaf; picking the address by an integer
 * mask instead of the conditional, which compiles to a branch, was 3-4 %
 * slower). */
static ALWAYS_INLINE void prefetch_ref(const query *q, int32_t r)
{
    const char *at = r >= 0 ? (const char *)&q->nodes[r] : (const char *)&q->prims[~r];
    PREFETCH(at);
    PREFETCH(at + 128);
}

/*
 * A depth-first traversal, nearest child first, from where w stands: a
 * node's hit children are ordered by entry, the nearest visited next and
 * the others stacked (farthest deepest); a leaf's faces are tested; a
 * stacked subtree is dropped when the closest hit found since lies before
 * its entry. Returns 0 when the traversal is over. With yield set it also
 * stops (returning 1, w saved) each time it has moved to a child just
 * asked for: the batch then runs other traversals while that child's
 * memory arrives. Stacked references are not yielded on (they were asked
 * for when pushed). The state lives in locals in between (registers).
 *
 * walk is written once and compiled eight times: for the scalar queries
 * and for the batch (its yield argument), each with and without the loose
 * handling (may_loose), each for any x86-64 and for AVX2 (avx2), the three
 * a constant in each copy.
 */
static ALWAYS_INLINE int walk(query *q, walker *w, int mode, int yield, int may_loose,
                              int avx2)
{
    const bvh_node *nodes = q->nodes;
    int32_t ref = w->ref, count = w->count;
    int sp = w->sp;
    for (;;) {
        if (ref >= 0) {
            const bvh_node *n = &nodes[ref];
            float tn[BVH_WIDTH];
#if WALK_AVX2
            unsigned mask = avx2 ? node_test_avx2(&q->slab, n, tn, may_loose)
                                 : node_test(&q->slab, n, tn, may_loose);
#else
            unsigned mask = node_test(&q->slab, n, tn, may_loose);
            (void)avx2;
#endif
            if (mask != 0) {
                /* Every hit child's memory is asked for as it is met: the
                 * nearest is needed at once, the others when popped. Most
                 * visits hit one or two children: those without a sort;
                 * three or more by insertion. */
                int first = lowest_bit(mask);
                unsigned rest = mask & (mask - 1);
                ref = n->child[first];
                count = n->count[first];
                prefetch_ref(q, ref);
                if (rest != 0) {
                    node_ref a = { ref, count, tn[first] };
                    node_ref near;
                    if ((rest & (rest - 1)) == 0) {
                        int second = lowest_bit(rest);
                        node_ref b = { n->child[second], n->count[second], tn[second] };
                        prefetch_ref(q, b.ref);
                        int swap = b.entry < a.entry;
                        w->stack[sp++] = swap ? a : b;
                        near = swap ? b : a;
                    } else {
                        node_ref next[BVH_WIDTH];
                        next[0] = a;
                        int k = 1;
                        for (unsigned m = rest; m != 0; m &= m - 1) {
                            int c = lowest_bit(m);
                            node_ref r = { n->child[c], n->count[c], tn[c] };
                            prefetch_ref(q, r.ref);
                            int j = k++;
                            for (; j > 0 && next[j - 1].entry > r.entry; j--)
                                next[j] = next[j - 1];
                            next[j] = r;
                        }
                        for (int j = k - 1; j > 0; j--)
                            w->stack[sp++] = next[j];
                        near = next[0];
                    }
                    ref = near.ref;
                    count = near.count;
                }
                if (yield) {
                    w->ref = ref;
                    w->count = count;
                    w->sp = sp;
                    return 1;
                }
                continue;
            }
        } else if (count > 0 && query_leaf_for(q, mode, ~ref, count, avx2)) {
            return 0;
        }
        for (;;) {
            if (sp == 0)
                return 0;
            node_ref r = w->stack[--sp];
            if (!(r.entry > q->slab.limit)) {
                ref = r.ref;
                count = r.count;
                break;
            }
        }
    }
}

/* 1 when some node of the mesh is loose (the root's flags are the OR of
 * all): the traversal is compiled with and without the loose handling. */
static int mesh_has_loose(const isect_mesh *m)
{
    return m->tree.nodes[0].loose != 0;
}

#if WALK_AVX2
WALK_TARGET_AVX2 static void query_run_avx2(query *q, walker *w, int mode)
{
    if (mesh_has_loose(q->mesh))
        walk(q, w, mode, 0, 1, 1);
    else
        walk(q, w, mode, 0, 0, 1);
}
#endif

/* The whole traversal of q, by the copy for AVX2 when avx2 is set (the
 * caller's walk_cpu_has_avx2_fma, asked once per call or batch). */
static void query_run(query *q, int mode, int avx2)
{
    walker w;
    walker_init(&w);
#if WALK_AVX2
    if (avx2) {
        query_run_avx2(q, &w, mode);
        return;
    }
#else
    (void)avx2;
#endif
    if (mesh_has_loose(q->mesh))
        walk(q, &w, mode, 0, 1, 0);
    else
        walk(q, &w, mode, 0, 0, 0);
}

int64_t mesh_hits_all(const isect_shape *s, const isect_ray *ray,
                      const isect_params *prm, isect_hit *hits, int64_t cap)
{
    query q;
    query_init(&q, s->mesh, ray, prm);
    if (!(ray->tmin <= ray->tmax))
        return 0;
    if (prm->flags & ISECT_ANY_HIT) {
        /* Occlusion: the first hit found, as mesh_hit_first gives it. */
        query_run(&q, QUERY_ANY, walk_cpu_has_avx2_fma());
        if (q.found && cap > 0)
            hits[0] = q.best;
        return q.found;
    }
    q.hits = hits;
    q.cap = cap;
    query_run(&q, QUERY_ALL, walk_cpu_has_avx2_fma());
    heap_sort(&q, hits, q.count < cap ? q.count : cap);
    return q.count;
}

int mesh_hit_first(const isect_shape *s, const isect_ray *ray,
                   const isect_params *prm, isect_hit *out)
{
    query q;
    query_init(&q, s->mesh, ray, prm);
    if (!(ray->tmin <= ray->tmax))
        return 0;
    int mode = (prm->flags & ISECT_ANY_HIT) ? QUERY_ANY : QUERY_CLOSEST;
    query_run(&q, mode, walk_cpu_has_avx2_fma());
    if (q.found)
        *out = q.best;
    return q.found;
}

/* ---------------------------------------------------------------- batch
 *
 * isect_intersect_batch for a mesh (the family's first_batch): closest (or
 * any) hits of many rays, BATCH_LANES traversals in flight at once, taking
 * one step each in turn. A large mesh's traversal waits on one cache miss
 * per node; the prefetch a step issues for its next node completes while
 * the other lanes step, so the misses of several rays overlap.
 *
 * A ray that follows its predecessor closely (ray_follows: coherent rays,
 * such as a camera's neighbouring pixels) is instead traced at once, start
 * to end: it visits nearly the nodes and faces the predecessor has just
 * brought into cache, so there are no misses to overlap, and interleaving
 * it with other traversals would only cost the stepping and the branch
 * predictor's memory of the path (measured: the camera rays of
 * bench_mesh on 82k triangles take 20 % longer in lanes than traced at
 * once, random rays 30-50 % longer traced at once). So is every ray of a
 * mesh whose nodes and faces take less than LANES_MIN_BYTES: its
 * traversals find most of what they need in cache anyway (measured on
 * icospheres, random rays, against lanes: 4-7 % faster at 5,120
 * triangles, 0.8 MB, and 1-4 % at 20,480, 3 MB; 14 % slower at 81,920,
 * 12 MB; on a CPU with a 16 MB L3).
 *
 * Either way each ray runs exactly the steps mesh_hit_first runs
 * (query_init, the tmin > tmax miss, query_run's steps, at once or one at a
 * time; no traversal state is shared between rays, ray_follows only picks
 * which way), and each ray passes ray_check, xform_object_ray,
 * batch_record and xform_hits_to_world as batch.c's per-ray loop over
 * shape_ray_first does, so every record and the returned count are bit for
 * bit that loop's. Rays finish out of order; each writes only its own
 * record.
 */
#define BATCH_LANES 8
#define LANES_MIN_BYTES ((int64_t)6 << 20)

/* Rays count as close when they stay within 2^-7 of the mesh box's largest
 * side of each other across the box (see ray_follows). */
#define FOLLOW_REACH 0x1p-7

typedef struct lane {
    query     q;
    walker    w;
    isect_ray object; /* the transformed ray, if the shape has a transform */
    int64_t   index;
} lane;

/* What the batch's rays share: the input, the output, and what ray_follows
 * needs (the mesh box, the previous ray started). */
typedef struct batch {
    const isect_shape  *s;
    const isect_ray    *rays;
    int64_t             n, next, hit_count;
    const isect_params *prm;
    isect_hit          *closest;
    int                 mode;
    double              center[3], extent; /* the mesh box (extent: largest side) */
    double              prev_org[3], prev_dir[3]; /* the last ray started (object
                                                     space); NaN before the first */
    int                 direct_only;       /* 1: every ray traced at once */
    int                 avx2;              /* walk_cpu_has_avx2_fma() */
} batch;

/* The mesh box from the root's children (empty children have lo > hi).
 * Out-of-range coordinates give an infinite or NaN extent: ray_follows
 * then says no, and every ray runs in a lane. */
static void batch_mesh_box(batch *b, const isect_mesh *m)
{
    const bvh_node *root = &m->tree.nodes[0];
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int c = 0; c < BVH_WIDTH; c++)
        for (int k = 0; k < 3; k++) {
            double l = root->bounds[k][c], h = root->bounds[3 + k][c];
            if (l <= h) {
                lo[k] = l < lo[k] ? l : lo[k];
                hi[k] = h > hi[k] ? h : hi[k];
            }
        }
    b->extent = 0.0;
    for (int k = 0; k < 3; k++) {
        b->center[k] = 0.5 * lo[k] + 0.5 * hi[k];
        b->extent = hi[k] - lo[k] > b->extent ? hi[k] - lo[k] : b->extent;
    }
    if (!(b->extent < INFINITY))
        b->extent = NAN;
}

/* 1 when ray r stays close to the previous ray across the mesh box: with
 * origins dO apart (max norm) and directions at angle a, the rays are at
 * most dO + sin(a) L apart within the box, L = max|o - center| + extent
 * bounding the distance from o to any point of it; sin(a) = |d x p| /
 * (|d| |p|) <= sqrt(3) |d x p|_max / (max|d| max|p|). Same heading only
 * (d . p > 0). Written without a division; a NaN or overflow says no. Only
 * the speed depends on it. */
static int ray_follows(const batch *b, const isect_ray *r)
{
    const double *o = r->org, *d = r->dir, *po = b->prev_org, *pd = b->prev_dir;
    double reach = FOLLOW_REACH * b->extent;
    /* Origins apart by more than the reach: no (most incoherent rays). */
    double v[3];
    v3_sub(v, o, po);
    double gap = v3_max_abs_finite(v);
    if (!(gap <= reach))
        return 0;
    /* Straight-line code (vec3.h): every coherent ray pays for this, and a
     * loop over k with (k + 1) % 3 indices stayed a loop (a third of the
     * set-up of a ray that misses the mesh). The first ray meets the NaN
     * prev_org: gap is NaN and the answer no. */
    v3_cross(v, d, pd);
    double cross = v3_max_abs_finite(v);
    v3_sub(v, o, b->center);
    double span = v3_max_abs_finite(v);
    double norms = v3_max_abs_finite(d) * v3_max_abs_finite(pd);
    double dot = v3_dot(d, pd);
    return dot > 0.0
        && gap * norms + 1.7320508075688773 * cross * (span + b->extent) <= reach * norms;
}

/* The record of lane l's finished traversal; its hit count (0 or 1). */
static int64_t lane_finish(const lane *l, const batch *b)
{
    isect_hit *out = &b->closest[l->index];
    int found = l->q.found;
    if (found) {
        *out = l->q.best;
        xform_hits_to_world(b->s->xform, out, 1);
    }
    return batch_record(out, found);
}

/* Starts the next ray that needs a traversal in lane l, writing the
 * records of the ones that do not (misses or invalid: none counts as a
 * hit) and tracing those that follow their predecessor at once; 0 when
 * there is none left. */
static int lane_start(lane *l, batch *b)
{
    while (b->next < b->n) {
        int64_t i = b->next++;
        const isect_ray *r = &b->rays[i];
        int status = ray_check(r);
        if (status == ISECT_OK)
            status = xform_object_ray(b->s->xform, r, &l->object, &r);
        if (status != ISECT_OK) {
            batch_record(&b->closest[i], status);
            continue;
        }
        /* mesh_hit_first's early miss: found 0. */
        if (!(r->tmin <= r->tmax)) {
            batch_record(&b->closest[i], 0);
            continue;
        }
        query_init(&l->q, b->s->mesh, r, b->prm);
        l->index = i;
        int follows = ray_follows(b, r);
        memcpy(b->prev_org, r->org, sizeof b->prev_org);
        memcpy(b->prev_dir, r->dir, sizeof b->prev_dir);
        if (!follows && !b->direct_only) {
            walker_init(&l->w);
            return 1;
        }
        query_run(&l->q, b->mode, b->avx2); /* as mesh_hit_first */
        b->hit_count += lane_finish(l, b);
    }
    return 0;
}

/* The batch loop over lanes[count] (count <= BATCH_LANES), compiled with
 * and without the loose handling, for any x86-64 and for AVX2. */
static ALWAYS_INLINE int64_t batch_run(batch *b, lane *lanes, int count, int may_loose,
                                       int avx2)
{
    int active[BATCH_LANES], live = 0;
    for (int l = 0; l < count; l++) {
        active[l] = lane_start(&lanes[l], b);
        live += active[l];
    }
    while (live > 0) {
        for (int l = 0; l < count; l++) {
            if (!active[l] || walk(&lanes[l].q, &lanes[l].w, b->mode, 1, may_loose, avx2))
                continue;
            b->hit_count += lane_finish(&lanes[l], b);
            active[l] = lane_start(&lanes[l], b);
            live -= !active[l];
        }
    }
    return b->hit_count;
}

#if WALK_AVX2
WALK_TARGET_AVX2 static int64_t batch_run_avx2(batch *b, lane *lanes, int count)
{
    if (mesh_has_loose(b->s->mesh))
        return batch_run(b, lanes, count, 1, 1);
    return batch_run(b, lanes, count, 0, 1);
}
#endif

int64_t mesh_hit_first_batch(const isect_shape *s,
                             const isect_ray *rays, int64_t n, const isect_params *prm,
                             isect_hit *closest)
{
    batch b;
    b.s = s;
    b.rays = rays;
    b.n = n;
    b.next = 0;
    b.hit_count = 0;
    b.prm = prm;
    b.closest = closest;
    b.mode = (prm->flags & ISECT_ANY_HIT) ? QUERY_ANY : QUERY_CLOSEST;
    b.avx2 = walk_cpu_has_avx2_fma();
    for (int k = 0; k < 3; k++)
        b.prev_org[k] = b.prev_dir[k] = NAN;
    batch_mesh_box(&b, s->mesh);
    /* The lanes (7 KB each, mostly the traversal stack) on the heap, not
     * on a thread's stack, for a mesh of at least LANES_MIN_BYTES; for a
     * smaller one, or without memory, every ray is traced at once in one
     * lane on the stack (the same records, without the overlap). A test
     * build defines ISECT_TEST_NO_LANES to take that path always. */
    int64_t bytes = mesh_traversal_bytes(s->mesh);
    int count = n < BATCH_LANES ? (int)n : BATCH_LANES;
#ifdef ISECT_TEST_NO_LANES
    lane *lanes = NULL;
    (void)bytes;
#else
    lane *lanes = count > 0 && bytes >= LANES_MIN_BYTES ? malloc((size_t)count * sizeof *lanes)
                                                        : NULL;
#endif
    lane one;
    b.direct_only = lanes == NULL;
    if (lanes == NULL) {
        lanes = &one;
        count = 1;
    }
    int64_t hits;
#if WALK_AVX2
    if (b.avx2)
        hits = batch_run_avx2(&b, lanes, count);
    else
#endif
    if (mesh_has_loose(s->mesh))
        hits = batch_run(&b, lanes, count, 1, 0);
    else
        hits = batch_run(&b, lanes, count, 0, 0);
    if (lanes != &one)
        free(lanes);
    return hits;
}
