/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bvh.c — binned SAH construction of the binary tree and its collapse to
 * the 8-wide nodes of bvh.h.
 *
 * Top-down: each range of item references is binned by centroid along the
 * axis of its centroids' largest extent, the split plane between bins with
 * the least surface-area cost (MacDonald & Booth 1990) is taken, and the
 * range is partitioned in place. Bins keep the union of their items' boxes
 * and of their centroids, so both sides' boxes and centroid boxes come from
 * the bins and no other sweep is needed. A range becomes a leaf when it is
 * small enough and no split is cheaper than testing every item.
 */
#include "core/bvh.h"

#include "isect.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The boxes of the build grow four lanes at once with SSE (every x86-64
 * has it); elsewhere, or with ISECT_NO_SIMD defined, lane by lane. Both
 * compute the same float minima, maxima and centroids. */
#if defined(__SSE2__) && !defined(ISECT_NO_SIMD)
#define BVH_SSE 1
#include <emmintrin.h>
#else
#define BVH_SSE 0
#endif

/* 32 bins for large ranges, 16 below (Wald 2007: 16 lose little quality). */
#define BINS_MAX 32
#define BINS_SMALL 16
#define BINS_SMALL_BELOW 4096

/* SAH costs in units of one item test. A binary node becomes a third of a
 * level of an 8-wide node, whose eight boxes are tested at once (SIMD):
 * measured on the icosphere benchmark, 1.5 gives the fastest traversal (1
 * and 2.5 are 2-5 % slower at 82k triangles; 3 was best with the earliest,
 * one-box-at-a-time node test). */
#define COST_TRAVERSE 1.5

/* One item during the build: its box and where it came from. 32 bytes;
 * lo and hi each start a 16-byte group (loaded as four lanes, the fourth
 * masked off). */
typedef struct build_ref {
    float   lo[3];
    int32_t item;
    float   hi[3];
    uint32_t flags;
} build_ref;

/* A box; the fourth lane of each corner is padding for the SSE code. */
typedef struct aabbf {
    float lo[4], hi[4];
} aabbf;

/* A node of the binary tree: the boxes of its two children. */
typedef struct bin_node {
    float   bounds[2][6]; /* child c: lo x, y, z, hi x, y, z */
    int32_t child[2];     /* >= 0 inner node, < 0 leaf ~first */
    uint8_t count[2];
    uint8_t flags[2];
} bin_node;

typedef struct builder {
    build_ref *refs;
    bin_node  *nodes;
    int64_t    node_count;
    int        max_leaf; /* items a leaf may hold, 1..BVH_MAX_LEAF */
} builder;

typedef struct split {
    int    axis;     /* -1: halve the range (no SAH split) */
    int    bin;      /* items with bin index < bin go left; -1: the range is
                        sorted (sweep_split) and its first `left` go left */
    int64_t left;
    int    bins;
    float  origin;   /* centroid binning along axis: (c - origin) * scale */
    float  scale;
    double cost;     /* aL nL + aR nR (half areas) */
    aabbf  box[2];   /* the sides' boxes and centroid boxes (unions of bins) */
    aabbf  cbox[2];
} split;

/* The next float toward -inf / +inf of a finite float (not NaN), by its
 * bits: nextafterf is a libm call and this runs six times per item. */
static float float_below(float f)
{
    if (f == 0.0f)
        return -FLT_MIN * FLT_EPSILON; /* the largest negative subnormal */
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits = f > 0.0f ? bits - 1u : bits + 1u;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static float float_above(float f)
{
    return -float_below(-f);
}

void bvh_box_from_double(const double lo[3], const double hi[3], float box[6])
{
    for (int k = 0; k < 3; k++) {
        /* Conversions out of float range are undefined in C: clamp first. */
        double l = lo[k], h = hi[k];
        float fl, fh;
        if (l > FLT_MAX)
            fl = FLT_MAX;
        else if (l < -FLT_MAX)
            fl = -INFINITY;
        else {
            fl = (float)l;
            if ((double)fl > l)
                fl = float_below(fl);
        }
        if (h < -FLT_MAX)
            fh = -FLT_MAX;
        else if (h > FLT_MAX)
            fh = INFINITY;
        else {
            fh = (float)h;
            if ((double)fh < h)
                fh = float_above(fh);
        }
        box[k] = fl;
        box[k + 3] = fh;
    }
}

static void aabb_empty(aabbf *b)
{
    for (int k = 0; k < 4; k++) {
        b->lo[k] = INFINITY;
        b->hi[k] = -INFINITY;
    }
}

#if BVH_SSE
/* Four floats from p with lane 3 zeroed (in a ref that lane holds the item
 * or flags bits, which as floats can be subnormal: slow on some
 * processors, and never wanted). */
static inline __m128 load_lanes3(const float *p)
{
    return _mm_and_ps(_mm_loadu_ps(p), _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1)));
}
#endif

/* Grows b by the box lo, hi; each points at four floats, lane 3 ignored. */
static inline void aabb_grow(aabbf *b, const float *lo, const float *hi)
{
#if BVH_SSE
    _mm_storeu_ps(b->lo, _mm_min_ps(load_lanes3(lo), _mm_loadu_ps(b->lo)));
    _mm_storeu_ps(b->hi, _mm_max_ps(load_lanes3(hi), _mm_loadu_ps(b->hi)));
#else
    for (int k = 0; k < 3; k++) {
        b->lo[k] = lo[k] < b->lo[k] ? lo[k] : b->lo[k];
        b->hi[k] = hi[k] > b->hi[k] ? hi[k] : b->hi[k];
    }
#endif
}

/* The centroid of a ref's box, 0.5 lo + 0.5 hi (halved terms cannot
 * overflow), in c[0..3); c[3] = 0. */
static inline void ref_centroid(const build_ref *r, float c[4])
{
#if BVH_SSE
    const __m128 half = _mm_set1_ps(0.5f);
    _mm_storeu_ps(c, _mm_add_ps(_mm_mul_ps(half, load_lanes3(r->lo)),
                                _mm_mul_ps(half, load_lanes3(r->hi))));
#else
    for (int k = 0; k < 3; k++)
        c[k] = 0.5f * r->lo[k] + 0.5f * r->hi[k];
    c[3] = 0.0f;
#endif
}

/* Grows box by the ref's box and cen by its centroid. */
static inline void aabb_grow_ref(aabbf *box, aabbf *cen, const build_ref *r)
{
    float c[4];
    ref_centroid(r, c);
    aabb_grow(box, r->lo, r->hi);
    aabb_grow(cen, c, c);
}

static void aabb_union(aabbf *r, const aabbf *a, const aabbf *b)
{
    for (int k = 0; k < 4; k++) {
        r->lo[k] = a->lo[k] < b->lo[k] ? a->lo[k] : b->lo[k];
        r->hi[k] = a->hi[k] > b->hi[k] ? a->hi[k] : b->hi[k];
    }
}

/* Half the surface area (in double: float extents cannot overflow it). An
 * empty box has area 0; NaN (infinite boxes) makes every comparison fail,
 * which only ever leads to the median split. */
static double half_area(const aabbf *b)
{
    double dx = (double)b->hi[0] - b->lo[0];
    double dy = (double)b->hi[1] - b->lo[1];
    double dz = (double)b->hi[2] - b->lo[2];
    if (dx < 0.0 || dy < 0.0 || dz < 0.0)
        return 0.0;
    return dx * dy + dy * dz + dz * dx;
}

/* One coordinate of the centroid, as ref_centroid computes it. */
static inline float ref_centroid_axis(const build_ref *r, int k)
{
    return 0.5f * r->lo[k] + 0.5f * r->hi[k];
}

/* The bin of a centroid; NaN and out-of-range values clamp (the float to
 * int conversion is only done on values in range). Written as selects the
 * compiler turns into max and min, not branches. */
static inline int bin_index(float c, float origin, float scale, int bins)
{
    float f = (c - origin) * scale;
    f = f > 0.0f ? f : 0.0f;
    float last = (float)(bins - 1);
    f = f < last ? f : last;
    return (int)f;
}

/* The axis of the centroids' largest extent, or -1 when the centroids
 * coincide (or their box is not finite): no split can separate them. */
static int split_axis(const aabbf *cbox)
{
    int k = 0;
    for (int a = 1; a < 3; a++)
        if (cbox->hi[a] - cbox->lo[a] > cbox->hi[k] - cbox->lo[k])
            k = a;
    float extent = cbox->hi[k] - cbox->lo[k];
    return extent > 0.0f && extent < INFINITY ? k : -1;
}

/* The cheapest SAH plane between n units in order along the axis (bins,
 * or single items sorted by centroid): units [0, i) go left. The units'
 * boxes and item counts; returns i (1 <= i < n) with *cost = aL nL +
 * aR nR (half areas), or 0 when no plane has items on both sides. A
 * right-to-left sweep gives the area and count of units [i, n); the
 * left-to-right sweep evaluates every plane. */
static int sah_sweep(const aabbf *box, const int64_t *count, int n, double *cost)
{
    double right_area[BINS_MAX];
    int64_t right_count[BINS_MAX];
    aabbf acc;
    aabb_empty(&acc);
    int64_t items = 0;
    for (int i = n - 1; i > 0; i--) {
        aabb_union(&acc, &acc, &box[i]);
        items += count[i];
        right_area[i] = half_area(&acc);
        right_count[i] = items;
    }
    aabb_empty(&acc);
    items = 0;
    int plane = 0;
    *cost = INFINITY;
    for (int i = 1; i < n; i++) {
        aabb_union(&acc, &acc, &box[i - 1]);
        items += count[i - 1];
        if (items == 0 || right_count[i] == 0)
            continue;
        double c = half_area(&acc) * (double)items + right_area[i] * (double)right_count[i];
        if (c < *cost) {
            *cost = c;
            plane = i;
        }
    }
    return plane;
}

/* The cheapest binned SAH split of refs[begin, end) with centroid box cbox
 * along the axis of the centroids' largest extent, or axis -1 if the
 * centroids coincide. Binning one axis instead of three makes the build
 * about 1.4x faster; on the benchmark meshes the trees trace as fast (the
 * longest axis is nearly always the one the three-axis search picks). */
static void find_split(const builder *b, int64_t begin, int64_t end, const aabbf *cbox,
                       split *best)
{
    int bins = end - begin >= BINS_SMALL_BELOW ? BINS_MAX : BINS_SMALL;
    best->axis = -1;
    best->cost = INFINITY;
    best->bins = bins;
    int k = split_axis(cbox);
    if (k < 0)
        return;
    float origin = cbox->lo[k];
    /* The factor just below 1 keeps the largest centroid in the last bin. */
    float scale = (float)bins * 0.99999f / (cbox->hi[k] - cbox->lo[k]);
    /* Each bin: the union of its items' boxes and of their centroids. */
    aabbf box[BINS_MAX], cen[BINS_MAX];
    int64_t count[BINS_MAX];
    for (int i = 0; i < bins; i++) {
        aabb_empty(&box[i]);
        aabb_empty(&cen[i]);
        count[i] = 0;
    }
    for (int64_t i = begin; i < end; i++) {
        const build_ref *r = &b->refs[i];
        float c[4];
        ref_centroid(r, c);
        int j = bin_index(c[k], origin, scale, bins);
        count[j]++;
        aabb_grow(&box[j], r->lo, r->hi);
        aabb_grow(&cen[j], c, c);
    }
    int plane = sah_sweep(box, count, bins, &best->cost);
    if (plane == 0)
        return;
    best->axis = k;
    best->bin = plane;
    best->origin = origin;
    best->scale = scale;
    for (int side = 0; side < 2; side++) {
        aabb_empty(&best->box[side]);
        aabb_empty(&best->cbox[side]);
    }
    for (int i = 0; i < bins; i++) {
        int side = i >= plane;
        aabb_union(&best->box[side], &best->box[side], &box[i]);
        aabb_union(&best->cbox[side], &best->cbox[side], &cen[i]);
    }
}

/* Ranges of at most SWEEP_MAX items, the bulk of the calls (a tree over n
 * items has about n/2 of them): binning would spend more on its bins than
 * on the items, so the range is sorted by centroid along the axis of the
 * centroids' largest extent and every one of its n - 1 object splits is
 * evaluated (the exact SAH sweep of MacDonald & Booth on that axis). The
 * sort is the partition. */
#define SWEEP_MAX 16
typedef char sweep_fits_the_sweep_arrays[SWEEP_MAX <= BINS_MAX ? 1 : -1];

static void sweep_split(builder *b, int64_t begin, int64_t end, const aabbf *cbox,
                        split *best)
{
    best->axis = -1;
    best->cost = INFINITY;
    int k = split_axis(cbox);
    if (k < 0)
        return;
    build_ref *r = b->refs + begin;
    int n = (int)(end - begin);
    /* Insertion sort, stable: equal centroids keep their order. */
    for (int i = 1; i < n; i++) {
        build_ref x = r[i];
        float key = ref_centroid_axis(&x, k);
        int j = i;
        for (; j > 0 && ref_centroid_axis(&r[j - 1], k) > key; j--)
            r[j] = r[j - 1];
        r[j] = x;
    }
    aabbf box[SWEEP_MAX];
    int64_t count[SWEEP_MAX];
    for (int i = 0; i < n; i++) {
        aabb_empty(&box[i]);
        aabb_grow(&box[i], r[i].lo, r[i].hi);
        count[i] = 1;
    }
    int plane = sah_sweep(box, count, n, &best->cost);
    if (plane == 0)
        return;
    best->axis = k;
    best->bin = -1;
    best->left = plane;
    for (int side = 0; side < 2; side++) {
        aabb_empty(&best->box[side]);
        aabb_empty(&best->cbox[side]);
    }
    for (int i = 0; i < n; i++)
        aabb_grow_ref(&best->box[i >= plane], &best->cbox[i >= plane], &r[i]);
}

/* Partition refs[begin, end) by the split (or halve it for axis -1) and
 * return the boundary; the sides' boxes and centroid boxes are the split's
 * (from the bins) or, for a halving, computed here. */
static int64_t partition(builder *b, int64_t begin, int64_t end, const split *s,
                         aabbf box[2], aabbf cbox[2])
{
    if (s->axis < 0) {
        for (int side = 0; side < 2; side++) {
            aabb_empty(&box[side]);
            aabb_empty(&cbox[side]);
        }
        int64_t mid = begin + (end - begin) / 2;
        for (int64_t i = begin; i < end; i++) {
            const build_ref *r = &b->refs[i];
            aabb_grow_ref(&box[i >= mid], &cbox[i >= mid], r);
        }
        return mid;
    }
    for (int side = 0; side < 2; side++) {
        box[side] = s->box[side];
        cbox[side] = s->cbox[side];
    }
    if (s->bin < 0)
        return begin + s->left; /* sorted by sweep_split */
    /* Lomuto's scheme without a branch: every item is swapped with the
     * first right-side one (itself or another right-side item when it goes
     * right) and the boundary moves by its side. Which side an item takes
     * is as random as the items' order, so a branch on it would be
     * mispredicted half the time. */
    build_ref *r = b->refs;
    int64_t mid = begin;
    for (int64_t i = begin; i < end; i++) {
        build_ref x = r[i];
        int left = bin_index(ref_centroid_axis(&x, s->axis), s->origin, s->scale, s->bins)
                 < s->bin;
        r[i] = r[mid];
        r[mid] = x;
        mid += left;
    }
    return mid;
}

/* Builds refs[begin, end) (box: their union) and returns the reference a
 * parent stores for it (*count: the leaf size, 0 for an inner node); the
 * result is the OR of the items' flags. */
static uint8_t build_range(builder *b, int64_t begin, int64_t end, const aabbf *box,
                           const aabbf *cbox, int depth, int32_t *ref, uint8_t *count)
{
    int64_t n = end - begin;
    split s;
    s.axis = -1;
    s.cost = INFINITY;
    if (n > 1 && depth < BVH_MEDIAN_DEPTH) {
        if (n <= SWEEP_MAX)
            sweep_split(b, begin, end, cbox, &s);
        else
            find_split(b, begin, end, cbox, &s);
    }
    /* Leaf when small and no split beats testing every item:
     * n <= COST_TRAVERSE + (aL nL + aR nR) / a (all in item-test units). */
    if (n <= b->max_leaf
        && (s.axis < 0 || !(s.cost < half_area(box) * ((double)n - COST_TRAVERSE)))) {
        uint8_t flags = 0;
        for (int64_t i = begin; i < end; i++)
            flags |= (uint8_t)b->refs[i].flags;
        *ref = ~(int32_t)begin;
        *count = (uint8_t)n;
        return flags;
    }
    aabbf child_box[2], child_cbox[2];
    int64_t mid = partition(b, begin, end, &s, child_box, child_cbox);
    int64_t index = b->node_count++;
    int32_t child_ref[2];
    uint8_t child_count[2], child_flags[2];
    child_flags[0] = build_range(b, begin, mid, &child_box[0], &child_cbox[0], depth + 1,
                                 &child_ref[0], &child_count[0]);
    child_flags[1] = build_range(b, mid, end, &child_box[1], &child_cbox[1], depth + 1,
                                 &child_ref[1], &child_count[1]);
    bin_node *node = &b->nodes[index];
    for (int c = 0; c < 2; c++) {
        memcpy(node->bounds[c], child_box[c].lo, 3 * sizeof(float));
        memcpy(node->bounds[c] + 3, child_box[c].hi, 3 * sizeof(float));
        node->child[c] = child_ref[c];
        node->count[c] = child_count[c];
        node->flags[c] = child_flags[c];
    }
    *ref = (int32_t)index;
    *count = 0;
    return (uint8_t)(child_flags[0] | child_flags[1]);
}

/* ------------------------------------------------------------ collapse
 *
 * The 8-wide tree is chosen from the binary one by the dynamic programme
 * of Ylitie, Karras & Laine ("Efficient Incoherent Ray Traversal on GPUs
 * Through Compressed Wide BVHs", HPG 2017): for every binary subtree n and
 * every i = 1..8, cost[n][i] is the least SAH cost of representing n by at
 * most i children of a wide node (each a leaf or a wide node's subtree),
 * with
 *   cost[n][1] = min(leaf: A(n) COLLAPSE_ITEM items(n), when items(n) <=
 *                    BVH_MAX_LEAF; node: A(n) COLLAPSE_NODE + D(n, 8)),
 *   cost[n][i] = min(cost[n][i - 1], D(n, i)),
 *   D(n, j)    = min over 0 < k < j of cost[left][k] + cost[right][j - k],
 * a binary leaf costing A COLLAPSE_ITEM items for any i. The greedy rule
 * it replaces (open the widest inner child until eight) left the bottom
 * nodes half empty (4.0 children per node at 82k triangles) and could not
 * merge small leaves. The costs only choose the shape: any choice is a
 * valid tree (and a NaN or infinite cost, from an unbounded box, leaves the
 * default: a node, the first split).
 */

/* SAH weights of a wide node's visit and of one item test. Measured on
 * the icosphere benchmark (process-alternating runs, medians): against the
 * greedy collapse, an item weight of 0.4 is 2.5-3.5 % faster at 82k
 * triangles on every ray set and 2-20 % at 1.3M, with 6.5 children per
 * node (was 4.0) and half the nodes; 0.2 merges more leaves (7.6 children,
 * a third of the nodes) but gains only 1 % at 82k; 0.7 merges none. */
#define COLLAPSE_NODE 1.0
#define COLLAPSE_ITEM 0.4

/* The SAH cost of a leaf of the given items in a box of that half area. */
static double leaf_cost(double area, int64_t items)
{
    return area * COLLAPSE_ITEM * (double)items;
}

/* The programme's table for one binary inner node. */
typedef struct collapse_entry {
    float   cost[BVH_WIDTH];  /* cost[i - 1]: at most i children */
    uint8_t split[BVH_WIDTH]; /* split[i - 1]: 0 for i = 1 or when i - 1 children
                                 do as well; else the left side's share k */
    uint8_t node_split;       /* the left side's share of the eight children of
                                 b's own wide node */
    uint8_t leaf;             /* with one child: the whole subtree is one leaf */
    uint8_t flags;            /* OR of the items' flags */
    int32_t first, items;     /* the subtree's items [first, first + items) */
} collapse_entry;

/* One child slot of an 8-wide node being written. */
typedef struct slot {
    const float *box;
    int32_t ref;
    uint8_t count, flags;
} slot;

typedef struct collapser {
    const bin_node *bin;
    collapse_entry *table; /* per binary inner node */
    bvh_node       *nodes; /* NULL: the counting pass */
    int64_t         node_count;
    int             max_leaf;
} collapser;

static double box6_area(const float box[6])
{
    aabbf b;
    memcpy(b.lo, box, 3 * sizeof(float));
    memcpy(b.hi, box + 3, 3 * sizeof(float));
    return half_area(&b);
}

/* out[i - 1]: the cost of child side of binary node b with at most i
 * children, i = 1..7 (the other side takes at least one). */
static void side_costs(const collapser *c, int32_t b, int side, double out[BVH_WIDTH - 1])
{
    const bin_node *n = &c->bin[b];
    double leaf = 0.0; /* an empty side (the root of an empty or one-leaf tree) */
    if (n->child[side] >= 0) {
        for (int i = 0; i < BVH_WIDTH - 1; i++)
            out[i] = c->table[n->child[side]].cost[i];
        return;
    }
    if (n->count[side] != 0)
        leaf = leaf_cost(box6_area(n->bounds[side]), n->count[side]);
    for (int i = 0; i < BVH_WIDTH - 1; i++)
        out[i] = leaf;
}

/* Fills table[b] from its children's (post-order); area: A(b). */
static void collapse_cost(collapser *c, int32_t b, double area)
{
    const bin_node *n = &c->bin[b];
    collapse_entry *e = &c->table[b];
    e->flags = (uint8_t)(n->flags[0] | n->flags[1]);
    e->items = 0;
    for (int side = 0; side < 2; side++) {
        int32_t ch = n->child[side];
        if (ch >= 0) {
            collapse_cost(c, ch, box6_area(n->bounds[side]));
            if (side == 0)
                e->first = c->table[ch].first;
            e->items += c->table[ch].items;
        } else {
            if (side == 0)
                e->first = ~ch;
            e->items += n->count[side];
        }
    }
    double side[2][BVH_WIDTH - 1];
    side_costs(c, b, 0, side[0]);
    side_costs(c, b, 1, side[1]);
    double best_split[BVH_WIDTH + 1];
    uint8_t best_k[BVH_WIDTH + 1];
    for (int j = 2; j <= BVH_WIDTH; j++) {
        best_k[j] = 1;
        best_split[j] = side[0][0] + side[1][j - 2];
        for (int k = 2; k < j; k++) {
            double d = side[0][k - 1] + side[1][j - k - 1];
            if (d < best_split[j]) {
                best_split[j] = d;
                best_k[j] = (uint8_t)k;
            }
        }
    }
    double node = area * COLLAPSE_NODE + best_split[BVH_WIDTH];
    double one = node;
    e->leaf = 0;
    if (e->items <= c->max_leaf) {
        double leaf = leaf_cost(area, e->items);
        if (leaf < node) {
            one = leaf;
            e->leaf = 1;
        }
    }
    e->cost[0] = (float)one;
    e->split[0] = 0;
    for (int i = 2; i <= BVH_WIDTH; i++) {
        e->cost[i - 1] = e->cost[i - 2];
        e->split[i - 1] = 0;
        if (best_split[i] < e->cost[i - 2]) {
            e->cost[i - 1] = (float)best_split[i];
            e->split[i - 1] = best_k[i];
        }
    }
    e->node_split = best_k[BVH_WIDTH];
}

static int32_t collapse_node(collapser *c, int32_t b);

/* Appends the children that side of binary node b becomes with at most i
 * of them. */
static void collapse_side(collapser *c, int32_t b, int side, int i, slot *slots, int *n)
{
    const bin_node *bn = &c->bin[b];
    int32_t ch = bn->child[side];
    if (ch < 0) {
        if (bn->count[side] == 0)
            return;
        slot s = { bn->bounds[side], ch, bn->count[side], bn->flags[side] };
        slots[(*n)++] = s;
        return;
    }
    const collapse_entry *e = &c->table[ch];
    while (i > 1 && e->split[i - 1] == 0)
        i--;
    if (i == 1) {
        slot s = { bn->bounds[side], 0, 0, e->flags };
        if (e->leaf) {
            s.ref = ~e->first;
            s.count = (uint8_t)e->items;
        } else {
            s.ref = ch; /* made a wide node below, once the slots are known */
        }
        slots[(*n)++] = s;
        return;
    }
    int k = e->split[i - 1];
    collapse_side(c, ch, 0, k, slots, n);
    collapse_side(c, ch, 1, i - k, slots, n);
}

/* The 8-wide node standing for binary inner node b (its subtree spread
 * over at most eight children as the table says); returns its index. */
static int32_t collapse_node(collapser *c, int32_t b)
{
    slot slots[BVH_WIDTH];
    int n = 0, k = c->table[b].node_split;
    collapse_side(c, b, 0, k, slots, &n);
    collapse_side(c, b, 1, BVH_WIDTH - k, slots, &n);
    int32_t index = (int32_t)c->node_count++;
    int32_t child_ref[BVH_WIDTH];
    for (int i = 0; i < n; i++)
        child_ref[i] = slots[i].ref >= 0 ? collapse_node(c, slots[i].ref) : slots[i].ref;
    if (c->nodes == NULL)
        return index; /* the counting pass */
    bvh_node *node = &c->nodes[index];
    memset(node, 0, sizeof *node);
    for (int i = 0; i < BVH_WIDTH; i++) {
        for (int p = 0; p < 6; p++)
            node->bounds[p][i] = i < n ? slots[i].box[p] : (p < 3 ? INFINITY : -INFINITY);
        node->child[i] = i < n ? child_ref[i] : ~(int32_t)0;
        node->count[i] = i < n ? slots[i].count : 0;
        if (i < n && (slots[i].flags & BVH_FLAG_LOOSE_T))
            node->loose |= (uint8_t)(1u << i);
    }
    return index;
}

int bvh_build(const float (*boxes)[6], const uint8_t *flags, int64_t n, int max_leaf,
              int32_t *order, bvh *out)
{
    out->nodes = NULL;
    out->node_count = 0;
    out->storage = NULL;
    builder b;
    b.refs = malloc((size_t)(n > 0 ? n : 1) * sizeof *b.refs);
    /* At most n - 1 inner nodes, or the one root of a single leaf. */
    b.nodes = malloc((size_t)(n > 1 ? n - 1 : 1) * sizeof *b.nodes);
    b.node_count = 0;
    b.max_leaf = max_leaf < 1 ? 1 : max_leaf > BVH_MAX_LEAF ? BVH_MAX_LEAF : max_leaf;
    if (b.refs == NULL || b.nodes == NULL) {
        free(b.refs);
        free(b.nodes);
        return ISECT_E_NOMEM;
    }
    aabbf box, cbox;
    aabb_empty(&box);
    aabb_empty(&cbox);
    for (int64_t i = 0; i < n; i++) {
        build_ref *r = &b.refs[i];
        memcpy(r->lo, boxes[i], 3 * sizeof(float));
        memcpy(r->hi, boxes[i] + 3, 3 * sizeof(float));
        r->item = (int32_t)i;
        r->flags = flags != NULL ? flags[i] : 0u;
        aabb_grow_ref(&box, &cbox, r);
    }
    int32_t root_ref;
    uint8_t root_count;
    uint8_t root_flags = build_range(&b, 0, n, &box, &cbox, 0, &root_ref, &root_count);
    if (root_ref < 0) {
        /* The whole set is one leaf: a root whose second child is empty. */
        bin_node *root = &b.nodes[0];
        aabbf empty;
        aabb_empty(&empty);
        memcpy(root->bounds[0], box.lo, 3 * sizeof(float));
        memcpy(root->bounds[0] + 3, box.hi, 3 * sizeof(float));
        memcpy(root->bounds[1], empty.lo, 3 * sizeof(float));
        memcpy(root->bounds[1] + 3, empty.hi, 3 * sizeof(float));
        root->child[0] = root_ref;
        root->child[1] = ~(int32_t)0;
        root->count[0] = root_count;
        root->count[1] = 0;
        root->flags[0] = root_flags;
        root->flags[1] = 0;
        b.node_count = 1;
    }
    for (int64_t i = 0; i < n; i++)
        order[i] = b.refs[i].item;
    free(b.refs);

    /* The 8-wide nodes: counted by a first pass, then written into one
     * block aligned to 256 bytes (C99 has no aligned allocation:
     * over-allocate and round the address up). */
    collapser c;
    c.bin = b.nodes;
    c.table = malloc((size_t)b.node_count * sizeof *c.table);
    c.nodes = NULL;
    c.node_count = 0;
    c.max_leaf = b.max_leaf;
    if (c.table == NULL) {
        free(b.nodes);
        return ISECT_E_NOMEM;
    }
    collapse_cost(&c, 0, 0.0);
    collapse_node(&c, 0);
    unsigned char *storage = malloc((size_t)c.node_count * sizeof(bvh_node) + 255);
    if (storage == NULL) {
        free(c.table);
        free(b.nodes);
        return ISECT_E_NOMEM;
    }
    size_t misalign = (size_t)((uintptr_t)storage & 255u);
    c.nodes = (bvh_node *)(void *)(storage + (misalign != 0 ? 256 - misalign : 0));
    c.node_count = 0;
    collapse_node(&c, 0);
    free(c.table);
    free(b.nodes);
    out->storage = storage;
    out->nodes = c.nodes;
    out->node_count = c.node_count;
    return ISECT_OK;
}

void bvh_free(bvh *b)
{
    free(b->storage);
    b->storage = NULL;
    b->nodes = NULL;
    b->node_count = 0;
}

/* The node layout the traversal relies on: 256 bytes, four cache lines. */
typedef char bvh_node_is_256_bytes[sizeof(bvh_node) == 256 ? 1 : -1];
