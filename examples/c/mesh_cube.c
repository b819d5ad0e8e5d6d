/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh_cube.c — a polygon mesh: the cube [-1, 1]^3 as 6 quads, built with
 * isect_mesh_create, checked with isect_mesh_check, hit by a ray through an
 * ISECT_MESH shape descriptor, asked for a point, and freed.
 *
 *     cc mesh_cube.c $(pkg-config --cflags --libs isect) -o mesh_cube
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
    /* Vertex i = x + 2y + 4z for the corner (x, y, z) in {0, 1}^3, scaled
     * to [-1, 1]^3. verts[nv][3]: one vertex per row. */
    const double verts[8][3] = { { -1, -1, -1 }, { 1, -1, -1 }, { -1, 1, -1 }, { 1, 1, -1 },
                                 { -1, -1, 1 },  { 1, -1, 1 },  { -1, 1, 1 },  { 1, 1, 1 } };
    /* Six quads, each counter-clockwise seen from outside, so their normals
     * (right-hand rule) point outward: -z, +z, -y, +y, -x, +x. Face f is
     * idx[offsets[f] .. offsets[f+1]). */
    const int32_t idx[24] = { 0, 2, 3, 1,  4, 5, 7, 6,  0, 1, 5, 4,
                              2, 6, 7, 3,  0, 4, 6, 2,  1, 3, 7, 5 };
    const int64_t offsets[7] = { 0, 4, 8, 12, 16, 20, 24 };
    const double centre[3] = { 0.0, 0.0, 0.0 };
    isect_ray ray = { { 0.25, 0.5, -5.0 }, { 0.0, 0.0, 1.0 }, 0.0, INFINITY };
    isect_shape shape = { 0 };
    isect_mesh_report report;
    isect_mesh *mesh = NULL;
    isect_hit hits[4];
    int status, count;

    /* The input is copied; the mesh is immutable and owns its BVH. */
    status = isect_mesh_create(&verts[0][0], 8, idx, offsets, 6, &mesh);
    if (status != ISECT_OK) {
        printf("isect_mesh_create: %s\n", isect_strerror(status));
        return 1;
    }
    status = isect_mesh_check(mesh, &report);
    if (status != ISECT_OK) {
        printf("isect_mesh_check: %s\n", isect_strerror(status));
        isect_mesh_destroy(mesh);
        return 1;
    }
    printf("mesh: %lld vertices, %lld edges, %lld faces, euler characteristic %lld\n",
           (long long)report.vertices, (long long)report.edges, (long long)report.faces,
           (long long)report.euler_characteristic);
    printf("closed %d, oriented %d, volume %.3f, area %.3f\n", (int)report.closed,
           (int)report.oriented, report.volume, report.area);

    /* A mesh is queried through a shape descriptor: type ISECT_MESH, data
     * NULL, mesh the handle. */
    shape.type = ISECT_MESH;
    shape.mesh = mesh;
    count = isect_intersect(&shape, &ray, NULL, hits, 4);
    print_hits("along z", hits, count);
    printf("contains (0, 0, 0): %d\n", isect_contains(&shape, centre));

    isect_mesh_destroy(mesh);
    return count == 2 ? 0 : 1;
}
