/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bvh.h — an 8-wide bounding-volume hierarchy over boxed items (the faces
 * of a mesh, the shapes of a scene): built as a binary tree by binned SAH
 * (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
 * IRT 2007), then collapsed to at most eight children per node, the shape
 * of least SAH cost found by the dynamic programme of Ylitie, Karras &
 * Laine (HPG 2017; it may also merge a small subtree into one leaf), about
 * a third of the binary depth: a traversal pays per node visited (a cache
 * miss on a large mesh, the branches of the visit on any), so fewer, wider
 * nodes are what makes it fast. Eight boxes are one
 * AVX register of floats or two SSE ones (measured on the icosphere
 * benchmark: with AVX 4-8 % faster than four children per node, with SSE
 * alone as fast).
 *
 * Layout. A node holds the boxes of its eight children in structure-of-
 * arrays form (bounds[plane][child]), so one visit tests all of them with
 * the same arithmetic on consecutive floats; a node is 256 bytes, four
 * cache lines, aligned. Boxes are stored in float, rounded outward from the
 * double geometry (lo down, hi up, out-of-range values widened to +-FLT_MAX
 * or infinity): every box contains its items exactly, so a test against it
 * in double arithmetic is conservative, at half the memory traffic of
 * double boxes. Nodes are in depth-first order.
 *
 * Depth. A split that SAH cannot make (all centroids in one bin) or any
 * split below binary depth BVH_MEDIAN_DEPTH halves the item range instead,
 * so the binary depth is at most BVH_MEDIAN_DEPTH + 32, and so is the depth
 * of the collapsed tree (each level consumes at least one binary level: a
 * node's children are binary descendants of the subtree it stands for); a
 * traversal that pushes at most seven children per level never needs more
 * than BVH_STACK_SIZE >= 7 (BVH_MEDIAN_DEPTH + 32) entries.
 */
#ifndef ISECT_BVH_H
#define ISECT_BVH_H

#include <stdint.h>

/* Largest number of items in one leaf (the counts are 8-bit). */
#define BVH_MAX_LEAF 8
#define BVH_MEDIAN_DEPTH 48
#define BVH_STACK_SIZE 576
#define BVH_WIDTH 8

/* Item flags, OR'ed over each child's subtree into bvh_node.flags. */
#define BVH_FLAG_LOOSE_T 0x1u /* an item whose reported t may lie outside its box
                                 (a polygon face: t from its plane): the
                                 traversal must not cull this child by t */

typedef struct bvh_node {
    float    bounds[6][BVH_WIDTH]; /* plane p of child c: bounds[p][c], planes lo x,
                                      y, z, hi x, y, z (outward-rounded); an
                                      empty child has lo = +inf, hi = -inf */
    int32_t  child[BVH_WIDTH];     /* >= 0: index of an inner node; < 0: a leaf
                                      holding items [~child, ~child + count) */
    uint8_t  count[BVH_WIDTH];     /* items in a leaf child (0: empty); 0 for inner */
    uint8_t  loose;                /* bit c: child c's subtree has an item with
                                      BVH_FLAG_LOOSE_T */
    uint8_t  reserved[23];         /* pads the node to 256 bytes */
} bvh_node;

typedef struct bvh {
    bvh_node *nodes;      /* nodes[0] is the root; always at least one node;
                             256-byte aligned inside storage */
    int64_t   node_count;
    void     *storage;    /* what was allocated */
} bvh;

/* The float box of a double box, rounded outward (lo[3], hi[3] -> box[6]). */
void bvh_box_from_double(const double lo[3], const double hi[3], float box[6]);

/* Build over n >= 0 items with boxes[n][6] (float, already outward) and
 * flags[n] (may be NULL), leaves of at most max_leaf items (clamped to
 * 1..BVH_MAX_LEAF: a mesh's faces are cheap to test and share leaves, a
 * scene's shapes are not and get a box each). On success order[0..n) is
 * the leaf order: leaf items [i, i + count) are the input items order[i
 * ..]. 0, or ISECT_E_NOMEM (nothing allocated). n must be below 2^31. */
int bvh_build(const float (*boxes)[6], const uint8_t *flags, int64_t n, int max_leaf,
              int32_t *order, bvh *out);

void bvh_free(bvh *b);

#endif /* ISECT_BVH_H */
