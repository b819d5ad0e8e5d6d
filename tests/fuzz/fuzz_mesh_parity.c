/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_mesh_parity.c — libFuzzer harness: the exactly-once guarantee on
 * closed meshes whose vertices are fuzzed.
 *
 * The topology is fixed and closed (a tetrahedron, an octahedron, or a cube
 * of 12 triangles, all consistently oriented); only the vertex coordinates
 * come from the input: a base position on a small grid plus a fuzzed offset
 * (grid steps that make vertices, edges and faces coincide or line up,
 * huge and subnormal values), the whole mesh scaled by a power of two.
 * Rays start at fuzzed points, exactly at a vertex, or at an edge's
 * midpoint, in fuzzed directions.
 *
 * Asserted, from the documented guarantees (isect.h "Tie-breaking", README
 * "The exactly-once rule") only:
 *  - isect_mesh_check: closed, oriented, V, E, F of the topology, one
 *    component, Euler characteristic 2, genus 0;
 *  - along the whole line (tmin = -inf, tmax = +inf) a closed oriented
 *    surface is crossed an even number of times, as many ENTER as EXIT
 *    (the winding number is 0 far away on both sides);
 *  - from a point p (tmin = 0), the parity of the crossings equals
 *    isect_contains(p) (exact crossing parity), unless p is on the surface
 *    (a hit at t = 0, where the closed set and the ray disagree by design);
 *  - a ray spawned from a hit starts inside exactly when it points behind
 *    the hit's normal (isect_contains of its origin) and never meets the
 *    face it leaves again;
 *  - every query invariant of fuzz_checks.h.
 * Meshes with zero-area faces are held to all of them (issue 13 item 1,
 * exactly-once with degenerate faces). Problems spanning more than 2^400 skip the exactness
 * checks (fuzz_checks.h, FUZZ_MAX_SPREAD; -DFUZZ_ANY_RANGE).
 */
#include "fuzz_checks.h"
#include "fuzz_input.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_V 8
#define MAX_F 12
#define MAX_RAYS 4
#define HIT_CAP 64

typedef struct topology {
    int nv, nf, ne;
    double base[MAX_V][3];
    int32_t faces[MAX_F][3]; /* outward by the right-hand rule */
} topology;

static const topology topologies[3] = {
    { 4, 4, 6,
      { { 0, 0, 0 }, { 4, 0, 0 }, { 0, 4, 0 }, { 0, 0, 4 } },
      { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } } },
    { 6, 8, 12,
      { { 2, 0, 0 }, { -2, 0, 0 }, { 0, 2, 0 }, { 0, -2, 0 }, { 0, 0, 2 }, { 0, 0, -2 } },
      { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 },
        { 2, 0, 5 }, { 1, 2, 5 }, { 3, 1, 5 }, { 0, 3, 5 } } },
    { 8, 12, 18,
      { { 0, 0, 0 }, { 2, 0, 0 }, { 2, 2, 0 }, { 0, 2, 0 },
        { 0, 0, 2 }, { 2, 0, 2 }, { 2, 2, 2 }, { 0, 2, 2 } },
      { { 0, 3, 2 }, { 0, 2, 1 }, { 4, 5, 6 }, { 4, 6, 7 },
        { 0, 1, 5 }, { 0, 5, 4 }, { 2, 3, 7 }, { 2, 7, 6 },
        { 1, 2, 6 }, { 1, 6, 5 }, { 0, 4, 7 }, { 0, 7, 3 } } },
};

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void check_topology(const isect_mesh *mesh, const topology *t, isect_mesh_report *rep)
{
    int st = isect_mesh_check(mesh, rep);
    fuzz_require_status(st, FUZZ_ALLOW_NOMEM, "isect_mesh_check");
    if (st < 0)
        return;
    FUZZ_REQUIRE(rep->closed == 1 && rep->oriented == 1 && rep->boundary_edges == 0 &&
                     rep->nonmanifold_edges == 0 && rep->misoriented_edges == 0,
                 "a closed oriented topology reported closed %d oriented %d",
                 (int)rep->closed, (int)rep->oriented);
    FUZZ_REQUIRE(rep->vertices == t->nv && rep->faces == t->nf && rep->edges == t->ne &&
                     rep->components == 1 && rep->euler_characteristic == 2 && rep->genus == 0,
                 "report V %lld E %lld F %lld components %lld chi %lld genus %lld",
                 (long long)rep->vertices, (long long)rep->edges, (long long)rep->faces,
                 (long long)rep->components, (long long)rep->euler_characteristic,
                 (long long)rep->genus);
}

/* Crossings of the whole line: even, as many entries as exits. */
static void check_whole_line(const isect_shape *shape, const isect_ray *ray, int nf)
{
    isect_ray line = *ray;
    isect_hit hits[HIT_CAP];
    int n, i, enter = 0, exit_ = 0;

    line.tmin = -INFINITY;
    line.tmax = INFINITY;
    n = fuzz_check_intersect(shape, &line, NULL, 0, nf, hits, HIT_CAP);
    if (n < 0)
        return;
    FUZZ_REQUIRE(n <= HIT_CAP, "%d hits on a mesh of %d faces", n, nf);
    for (i = 0; i < n; i++) {
        enter += hits[i].kind == ISECT_ENTER;
        exit_ += hits[i].kind == ISECT_EXIT;
    }
    FUZZ_REQUIRE(n % 2 == 0, "the whole line crosses the closed mesh %d times", n);
    FUZZ_REQUIRE(enter == exit_, "the whole line enters %d and exits %d times", enter, exit_);
}

/* 1 when p is certainly off the surface: farther than 2^-30 of the scale
 * from every face's plane (in plain double, whose error is far below that).
 * On the surface (a face, an edge, a vertex) the closed set and the
 * crossings of a ray that grazes there or runs along a face disagree by
 * design; points that close are left to the whole-line and spawn checks. */
static int off_surface(const double *verts, const topology *t, const double p[3])
{
    double scale = fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
    int f, k;
    for (k = 0; k < 3 * t->nv; k++)
        scale = fmax(scale, fabs(verts[k]));
    for (f = 0; f < t->nf; f++) {
        const double *a = &verts[3 * t->faces[f][0]], *b = &verts[3 * t->faces[f][1]],
                     *c = &verts[3 * t->faces[f][2]];
        double e1[3], e2[3], n[3], ap[3], len, dist;
        for (k = 0; k < 3; k++) {
            e1[k] = b[k] - a[k];
            e2[k] = c[k] - a[k];
            ap[k] = p[k] - a[k];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        len = sqrt(dot3(n, n));
        dist = fabs(dot3(n, ap)) / len;
        /* A sliver's plane is too uncertain to clear p from it. */
        if (!(len > 0x1p-30 * scale * scale) || !(dist > 0x1p-30 * scale))
            return 0;
    }
    return 1;
}

/* Crossing parity from the origin == containment of the origin. */
static void check_parity(const isect_shape *shape, const isect_ray *ray, int nf,
                         const double *verts, const topology *t)
{
    isect_ray half = *ray;
    isect_hit hits[HIT_CAP];
    int n, inside;

    half.tmin = 0.0;
    half.tmax = INFINITY;
    n = fuzz_check_intersect(shape, &half, NULL, 0, nf, hits, HIT_CAP);
    if (n < 0 || !off_surface(verts, t, half.org))
        return;
    inside = isect_contains(shape, half.org);
    FUZZ_REQUIRE(inside == 0 || inside == 1, "isect_contains on a closed mesh: %d", inside);
    FUZZ_REQUIRE(n % 2 == inside, "%d crossings from a point with contains = %d", n, inside);
}

/* Rays spawned from the hits of `ray` in direction `dir`. */
static void check_spawn(const isect_shape *shape, const isect_ray *ray, const double dir[3],
                        const double *verts, int nv, int nf, int wide)
{
    isect_hit hits[HIT_CAP], again[HIT_CAP];
    int n, i, k;

    n = isect_intersect(shape, ray, NULL, hits, HIT_CAP);
    for (i = 0; i < n && i < HIT_CAP; i++) {
        isect_ray out;
        double d = dot3(dir, hits[i].normal);
        int st = isect_spawn_ray(shape, &hits[i], dir, &out), inside, m;
        fuzz_require_status(st, FUZZ_QUERY_ERRORS, "isect_spawn_ray");
        if (getenv("FUZZ_VERBOSE") != NULL)
            fprintf(stderr, "spawn from t %a prim %d kind %d point %a %a %a normal %a %a %a dir "
                            "%a %a %a: status %d org %a %a %a\n",
                    hits[i].t, (int)hits[i].prim, (int)hits[i].kind, hits[i].point[0],
                    hits[i].point[1], hits[i].point[2], hits[i].normal[0], hits[i].normal[1],
                    hits[i].normal[2], dir[0], dir[1], dir[2], st, out.org[0], out.org[1],
                    out.org[2]);
        if (st != ISECT_OK)
            continue;
        FUZZ_REQUIRE(memcmp(out.dir, dir, sizeof out.dir) == 0 && out.tmin == 0.0 &&
                         out.tmax == INFINITY,
                     "spawned ray: dir or interval not as documented");
        inside = isect_contains(shape, out.org);
        /* held where d's sign is certain in doubles (the library takes the
         * exact sign; a plain d of tiny components can underflow to 0) */
        if (fabs(d) > 0x1p-50 * (fabs(dir[0] * hits[i].normal[0]) + fabs(dir[1] * hits[i].normal[1])
                                 + fabs(dir[2] * hits[i].normal[2])) + 0x1p-1000)
            FUZZ_REQUIRE(inside == (d < 0.0), "spawned origin: contains %d, dir.normal %a", inside,
                         d);
        /* A direction clearly off the face's plane never meets that face
         * again (its origin is strictly on the side dir points into). */
        if (wide || fabs(d) <= 1e-9 * sqrt(dot3(dir, dir)))
            continue;
        /* The spawned origin itself may be subnormal (a hit at the
         * coordinate origin moves by 2^-1074): the range gate covers it. */
        {
            fuzz_range range;
            fuzz_range_init(&range);
            fuzz_range_add(&range, verts, (size_t)(3 * nv));
            fuzz_range_add(&range, out.org, 3);
            fuzz_range_add(&range, dir, 3);
            if (fuzz_range_wide(&range))
                continue;
        }
        m = fuzz_check_intersect(shape, &out, NULL, 0, nf, again, HIT_CAP);
        for (k = 0; k < m && k < HIT_CAP; k++)
            FUZZ_REQUIRE(again[k].prim != hits[i].prim,
                         "the ray spawned from face %d meets it again at t = %a",
                         (int)hits[i].prim, again[k].t);
    }
}

/* 1 when every crossing's t is a finite double: the line's points within
 * the mesh's reach lie at |t| <= about 2 max|coordinate| / max|dir[k]|. A
 * crossing beyond DBL_MAX has no double t (the library leaves it out; the
 * header does not say), so the counting checks skip such rays: a subnormal
 * direction through a mesh of size 2^60 crosses at t ~ 2^1134. */
static int t_fits(const double *verts, int nv, const isect_ray *ray)
{
    double maxc = 0.0, maxd = 0.0;
    int i;
    for (i = 0; i < 3 * nv; i++)
        maxc = fmax(maxc, fabs(verts[i]));
    for (i = 0; i < 3; i++) {
        maxc = fmax(maxc, fabs(ray->org[i]));
        maxd = fmax(maxd, fabs(ray->dir[i]));
    }
    return maxc == 0.0 || ilogb(maxc) - ilogb(maxd) < 1000;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in;
    const topology *t;
    double verts[3 * MAX_V];
    isect_mesh *mesh = NULL;
    isect_mesh_report rep;
    isect_shape shape;
    isect_ray rays[MAX_RAYS];
    int scale, nrays, i, k, st, wide;
    fuzz_range range;

    fuzz_input_init(&in, data, size);
    t = &topologies[fuzz_u8(&in) % 3];
    scale = (int)(int8_t)fuzz_u8(&in);
    for (i = 0; i < t->nv; i++)
        for (k = 0; k < 3; k++)
            verts[3 * i + k] = ldexp(t->base[i][k] + fuzz_double(&in), scale);
    st = isect_mesh_create(verts, t->nv, &t->faces[0][0], NULL, t->nf, &mesh);
    fuzz_require_status(st, FUZZ_ALLOW_NONFINITE | FUZZ_ALLOW_NOMEM, "isect_mesh_create");
    if (st != ISECT_OK)
        return 0;
    memset(&rep, 0, sizeof rep);
    check_topology(mesh, t, &rep);
    if (getenv("FUZZ_VERBOSE") != NULL) {
        fprintf(stderr, "topology nv %d nf %d, degenerate faces %lld\n", t->nv, t->nf,
                (long long)rep.degenerate_faces);
        for (i = 0; i < t->nv; i++)
            fprintf(stderr, "v%d %a %a %a\n", i, verts[3 * i], verts[3 * i + 1], verts[3 * i + 2]);
    }

    memset(&shape, 0, sizeof shape);
    shape.type = ISECT_MESH;
    shape.mesh = mesh;
    nrays = 1 + fuzz_u8(&in) % MAX_RAYS;
    for (i = 0; i < nrays; i++) {
        uint8_t aim = fuzz_u8(&in);
        double dir[3];
        fuzz_take_ray(&in, &rays[i]);
        /* Aim: from a vertex exactly, or from an edge's midpoint. */
        if (aim % 4 == 1) {
            memcpy(rays[i].org, &verts[3 * ((aim / 4) % t->nv)], sizeof rays[i].org);
        } else if (aim % 4 == 2) {
            const int32_t *f = t->faces[(aim / 4) % t->nf];
            for (k = 0; k < 3; k++)
                rays[i].org[k] = verts[3 * f[0] + k] / 2 + verts[3 * f[1] + k] / 2;
        }
        fuzz_range_init(&range);
        fuzz_range_add(&range, verts, (size_t)(3 * t->nv));
        fuzz_range_add(&range, rays[i].org, 3);
        fuzz_range_add(&range, rays[i].dir, 3);
        wide = fuzz_range_wide(&range);
        fuzz_set_wide_range(wide);
        if (getenv("FUZZ_VERBOSE") != NULL)
            fprintf(stderr, "ray %d org %a %a %a dir %a %a %a wide %d\n", i, rays[i].org[0],
                    rays[i].org[1], rays[i].org[2], rays[i].dir[0], rays[i].dir[1],
                    rays[i].dir[2], wide);
        if (!fuzz_ray_valid(&rays[i]))
            continue;
        if (!wide && t_fits(verts, t->nv, &rays[i])) {
            check_whole_line(&shape, &rays[i], t->nf);
            check_parity(&shape, &rays[i], t->nf, verts, t);
        }
        fuzz_doubles(&in, dir, 3);
        check_spawn(&shape, &rays[i], dir, verts, t->nv, t->nf, wide);
    }
    fuzz_range_init(&range);
    fuzz_range_add(&range, verts, (size_t)(3 * t->nv));
    for (i = 0; i < nrays; i++) {
        fuzz_range_add(&range, rays[i].org, 3);
        fuzz_range_add(&range, rays[i].dir, 3);
    }
    fuzz_set_wide_range(fuzz_range_wide(&range));
    fuzz_check_batches(&shape, rays, nrays, NULL);
    isect_mesh_destroy(mesh);
    return 0;
}
