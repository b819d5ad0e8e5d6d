/* SPDX-License-Identifier: Apache-2.0 */
/*
 * batch.c — the loops over many rays or points, written once for every shape.
 *
 * The shape and options are validated once per call; a bad ray or point only
 * marks its own record (ISECT_INVALID) and the loop goes on. Each ray runs
 * through the same shape_ray_hits() / shape_ray_first() as isect_intersect,
 * so a batch closest hit is bit for bit the first hit of the scalar call. A
 * family may run isect_intersect_batch's rays its own way (the mesh keeps
 * several traversals in flight) but must write exactly these records.
 */
#include "api/dispatch.h"
#include "api/lanes.h"
#include "mesh/mesh.h"

#include <math.h>

#include <string.h>

static int batch_args_ok(const void *in, int64_t n, const void *out)
{
    return n >= 0 && (n == 0 || (in != NULL && out != NULL));
}

ISECT_API int64_t isect_intersect_batch(const isect_shape *shape, const isect_ray *rays,
                                        int64_t n, const isect_opts *opts,
                                        isect_hit *closest)
{
    if (!batch_args_ok(rays, n, closest))
        return ISECT_E_ARG;
    isect_params prm;
    int status;
    const shape_family *f = query_prepare(shape, opts, &prm, &status);
    if (f == NULL)
        return status;

    /* A family with its own loop (the mesh) gives the same records. */
    first_batch_fn first_batch = shape_first_batch(f);
    if (first_batch != NULL)
        return first_batch(f, shape, rays, n, &prm, closest);
    /* The analytic shapes with a fast kernel run it on several rays at once. */
    lanes_batch_fn lanes = lanes_batch_select(shape->type);
    if (lanes != NULL)
        return lanes(f, shape, rays, n, &prm, closest);
    int64_t hit_count = 0;
    for (int64_t i = 0; i < n; i++) {
        int found = ray_check(&rays[i]);
        if (found == ISECT_OK)
            found = shape_ray_first(f, shape, &rays[i], &prm, &closest[i]);
        hit_count += batch_record(&closest[i], found);
    }
    return hit_count;
}

ISECT_API int64_t isect_intersect_all_batch(const isect_shape *shape, const isect_ray *rays,
                                            int64_t n, const isect_opts *opts,
                                            int64_t *offsets, isect_hit *hits, int64_t cap)
{
    if (offsets == NULL || n < 0 || (n > 0 && rays == NULL) || cap < 0
        || (cap > 0 && hits == NULL))
        return ISECT_E_ARG;
    isect_params prm;
    int status;
    const shape_family *f = query_prepare(shape, opts, &prm, &status);
    if (f == NULL)
        return status;

    int64_t total = 0;
    offsets[0] = 0;
    for (int64_t i = 0; i < n; i++) {
        /* Hits go straight into the caller's buffer while it has room; past
         * cap they are only counted, so offsets stay complete. */
        int64_t room = total < cap ? cap - total : 0;
        isect_hit *dest = room > 0 ? hits + total : NULL;
        int64_t count = ray_check(&rays[i]);
        if (count == ISECT_OK)
            count = shape_ray_hits(f, shape, &rays[i], &prm, dest, room);
        if (count < 0) {
            /* One record says "this ray was bad" so it is not mistaken for a miss. */
            if (room > 0)
                hit_set_miss(dest, ISECT_INVALID);
            count = 1;
        }
        total += count;
        offsets[i + 1] = total;
    }
    return total;
}

ISECT_API int64_t isect_contains_batch(const isect_shape *shape, const double *p, int64_t n,
                                       uint8_t *inside)
{
    if (!batch_args_ok(p, n, inside))
        return ISECT_E_ARG;
    int status;
    const shape_family *f = shape_prepare(shape, &status);
    if (f == NULL)
        return status;
    if (!shape_can_contain(f, shape))
        return ISECT_E_ARG;

    int64_t inside_count = 0;
    for (int64_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        int in = all_finite(q, 3) ? shape_point_inside(f, shape, q) : ISECT_E_NONFINITE;
        inside[i] = in < 0 ? (uint8_t)ISECT_INVALID : (uint8_t)in;
        inside_count += in == 1;
    }
    return inside_count;
}

ISECT_API int isect_winding_number_batch(const isect_shape *shape, const double *p, int64_t n,
                                         double accuracy, double *w)
{
    if (!batch_args_ok(p, n, w) || !(accuracy >= 0.0))
        return ISECT_E_ARG;
    int status;
    const shape_family *f = shape_prepare(shape, &status);
    if (f == NULL)
        return status;
    if (shape->type != ISECT_MESH)
        return ISECT_E_ARG;
    const isect_mesh *m = shape->mesh;
    /* the cluster tree where the exact integer does not apply, for a batch
     * that repays building it (its cost is a few direct sums) */
    mesh_winding_tree *tree = NULL;
    if (!mesh_is_oriented(m) && (n >= 8 || (accuracy > 0.0 && n > 0))
        && (shape->xform == NULL || xform_is_similarity(shape->xform))) {
        status = mesh_winding_tree_build(m, &tree);
        if (status != ISECT_OK)
            return status;
    }
    int orientation = shape->xform != NULL ? xform_orientation(shape->xform) : 1;
    /* a similarity keeps solid angles: the sums run in object space;
     * another transform bends them, and the sum runs over the faces' world
     * images (the exact integer of a closed, oriented mesh is the same in
     * both: a crossing count) */
    int world = shape->xform != NULL && !xform_is_similarity(shape->xform);
    for (int64_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        double obj[3];
        int64_t count;
        if (shape->xform != NULL && all_finite(q, 3)) {
            xform_point_to_object(shape->xform, q, obj);
            q = obj;
        }
        if (!all_finite(q, 3))
            w[i] = NAN;
        else if (world)
            w[i] = mesh_is_oriented(m) && mesh_crossing_count(m, q, &count) == 0
                 ? (double)(orientation * count)
                 : mesh_winding_direct_world(m, shape->xform, p + 3 * i);
        else if (tree != NULL)
            w[i] = orientation * mesh_winding_far(m, tree, q, isfinite(accuracy) ? accuracy : 0.0,
                                                  NULL);
        else
            w[i] = orientation * mesh_generalized_winding(m, q, NULL);
    }
    mesh_winding_tree_free(tree);
    return ISECT_OK;
}
