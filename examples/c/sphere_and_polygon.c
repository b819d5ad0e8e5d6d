/* SPDX-License-Identifier: Apache-2.0 */
/*
 * sphere_and_polygon.c — the first things to do with libisect from C: all
 * hits of a ray with a sphere, a concave polygon hit and missed, and an
 * error status.
 *
 *     cc sphere_and_polygon.c $(pkg-config --cflags --libs isect) -o sphere_and_polygon
 */
#include <isect.h>

#include <math.h>
#include <stdio.h>

/* libisect reports hit kinds as integers; name them for printing. */
static const char *kind_name(int32_t kind)
{
    switch (kind) {
    case ISECT_ENTER: return "enter";
    case ISECT_EXIT:  return "exit";
    case ISECT_TOUCH: return "touch";
    default:          return "other";
    }
}

/* Adding 0.0 turns a -0.0 into 0.0, so a zero prints as 0.000 either way. */
static void print_hits(const isect_hit *hits, int count)
{
    int i;
    for (i = 0; i < count; i++) {
        const isect_hit *h = &hits[i];
        printf("  hit %d: t = %.3f, %s, point (%.3f, %.3f, %.3f), normal (%.3f, %.3f, %.3f)\n",
               i + 1, h->t + 0.0, kind_name(h->kind), h->point[0] + 0.0, h->point[1] + 0.0,
               h->point[2] + 0.0, h->normal[0] + 0.0, h->normal[1] + 0.0, h->normal[2] + 0.0);
    }
}

int main(void)
{
    /* A ray is org + t*dir for tmin <= t <= tmax; tmax may be infinite. */
    isect_ray ray = { { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 1.0 }, 0.0, INFINITY };
    const double centre[3] = { 0.0, 0.0, 5.0 };
    /* An L-shaped hexagon in the plane z = 2: the square (0,0)-(2,2) without
     * its upper right quarter, counter-clockwise seen from +z, so its normal
     * (right-hand rule) is +z. v[n][3]: one vertex per row. */
    const double l_shape[6][3] = { { 0, 0, 2 }, { 2, 0, 2 }, { 2, 1, 2 },
                                   { 1, 1, 2 }, { 1, 2, 2 }, { 0, 2, 2 } };
    isect_hit hits[4];
    int count;

    printf("libisect %s (ABI %d)\n", isect_version_string(), isect_abi_version());

    /* Every hit along the ray, sorted by t; NULL options mean the defaults.
     * The return value is the number of hits (like snprintf, it may exceed
     * the buffer's capacity, 4 here), or a negative ISECT_E_* status. */
    count = isect_ray_sphere(&ray, centre, 1.0, NULL, hits, 4);
    printf("sphere: %d hits\n", count);
    print_hits(hits, count);

    /* Straight down onto the polygon: it is met on its front side. */
    ray.org[0] = 0.5; ray.org[1] = 0.5; ray.org[2] = 5.0;
    ray.dir[0] = 0.0; ray.dir[1] = 0.0; ray.dir[2] = -1.0;
    count = isect_ray_polygon(&ray, &l_shape[0][0], 6, ISECT_EVEN_ODD, NULL, hits, 4);
    printf("polygon at (0.5, 0.5): %d hits\n", count);
    print_hits(hits, count);

    /* (1.5, 1.5) lies in the notch: no hit. Counting only: hits NULL, cap 0. */
    ray.org[0] = 1.5; ray.org[1] = 1.5;
    count = isect_ray_polygon(&ray, &l_shape[0][0], 6, ISECT_EVEN_ODD, NULL, NULL, 0);
    printf("polygon at (1.5, 1.5): %d hits\n", count);

    /* Errors are negative statuses (isect_strerror() gives a message). */
    count = isect_ray_sphere(&ray, centre, -1.0, NULL, hits, 4);
    printf("negative radius: status %d (%s)\n", count,
           count == ISECT_E_ARG ? "ISECT_E_ARG" : "unexpected");
    return count == ISECT_E_ARG ? 0 : 1;
}
