/* SPDX-License-Identifier: Apache-2.0 */
/*
 * transformed_ellipsoid.c — a shape descriptor (isect_shape) with an
 * object-to-world transform: an ellipsoid with radii (2, 1, 1), turned by 90
 * degrees about z (its long axis now along y) and moved to (10, 0, 0).
 *
 *     cc transformed_ellipsoid.c $(pkg-config --cflags --libs isect) -o transformed_ellipsoid
 */
#include <isect.h>

#include <math.h>
#include <stdio.h>

static void print_hits(const char *label, const isect_hit *hits, int count)
{
    int i;
    printf("%s: %d hits\n", label, count);
    for (i = 0; i < count; i++) {
        const isect_hit *h = &hits[i];
        printf("  hit %d: t = %.3f, %s, point (%.3f, %.3f, %.3f), normal (%.3f, %.3f, %.3f)\n",
               i + 1, h->t + 0.0, h->kind == ISECT_ENTER ? "enter" : "exit",
               h->point[0] + 0.0, h->point[1] + 0.0, h->point[2] + 0.0,
               h->normal[0] + 0.0, h->normal[1] + 0.0, h->normal[2] + 0.0);
    }
}

int main(void)
{
    /* Row-major object-to-world matrix: x' = -y + 10, y' = x, z' = z. */
    const double m[16] = { 0, -1, 0, 10,
                           1,  0, 0,  0,
                           0,  0, 1,  0,
                           0,  0, 0,  1 };
    /* The ellipsoid's numbers in the order of isect_ray_ellipsoid's
     * arguments: centre, then radii. The descriptor points at them (and at
     * the transform) without copying, so they must outlive it. */
    const double ellipsoid[6] = { 0, 0, 0, 2, 1, 1 };
    isect_xform xform;
    isect_shape shape = { 0 };
    isect_hit hits[4];
    isect_ray along_y = { { 10, -5, 0 }, { 0, 1, 0 }, 0.0, INFINITY };
    isect_ray along_x = { { 0, 0, 0 }, { 1, 0, 0 }, 0.0, INFINITY };
    const double inside_point[3] = { 10, 1.5, 0 }, outside_point[3] = { 11.5, 0, 0 };
    int status;

    /* isect_xform_init also computes the inverse; it rejects a singular
     * matrix (ISECT_E_DEGENERATE) and a last row other than 0 0 0 1. */
    status = isect_xform_init(&xform, m);
    if (status != ISECT_OK) {
        printf("isect_xform_init: %s\n", isect_strerror(status));
        return 1;
    }
    shape.type = ISECT_ELLIPSOID;
    shape.data = ellipsoid;
    shape.xform = &xform;

    /* Hits come back in world space with t unchanged: along y the long
     * axis is crossed (|y| <= 2), along x the short one (|x - 10| <= 1). */
    print_hits("along y", hits, isect_intersect(&shape, &along_y, NULL, hits, 4));
    print_hits("along x", hits, isect_intersect(&shape, &along_x, NULL, hits, 4));

    printf("contains (10, 1.5, 0): %d\n", isect_contains(&shape, inside_point));
    printf("contains (11.5, 0, 0): %d\n", isect_contains(&shape, outside_point));
    return 0;
}
