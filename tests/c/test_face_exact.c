/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_face_exact.c — triangles, polygons and mesh faces are crossed
 * exactly when the sheared-frame test of isect.h ("Tie-breaking") says so
 * on the EXACT projected coordinates of the given doubles, not on their
 * rounded projection.
 *
 * The expected answers are computed here, independently of the library,
 * with exact_dyadic.h: the projection multiplied by |d[kz]| (which keeps
 * every sign), X = sign(d[kz]) ((v - o)[kx] d[kz] - d[kx] (v - o)[kz]) and
 * Y likewise with ky, then the 2D test at the origin with the symbolic
 * perturbation (-e^2, -e): orientation det(P, Q) = X_p Y_q - Y_p X_q, ties
 * by sign(X_p - X_q), then sign(Y_q - Y_p); a vertex is above the test
 * line when Y >= 0. The rays are adversarial: aimed at points within a few
 * ulps of an edge or a vertex, where the projection rounded to doubles (the
 * library's test before this revision, emulated here as it was: fma(-s, z,
 * x)) often puts the ray on the other side. Each part checks that it met
 * such rays (so it fails on the rounded test) and that the library agrees
 * with the exact answer on every ray:
 *
 *  - lone triangles (isect_ray_triangle, and isect_intersect_batch at every
 *    SIMD level, which must agree with the scalar call);
 *  - lone polygons, convex and concave, under both fill rules;
 *  - closed meshes of triangles and of (non-planar) quads: rays from inside
 *    aimed within ulps of edges and vertices cross the surface exactly once
 *    (an odd number of hits in [0, inf), an even number on the whole line),
 *    and the faces the mesh reports on the whole line are exactly the faces
 *    the exact test claims;
 *  - the closest hit of a mesh ray that grazes an edge, where two faces are
 *    crossed at parameters that round to the same double, is the face the
 *    exact crossing parameters put first.
 *
 *     test_face_exact [rays per part]     (default 8000)
 */
#define _POSIX_C_SOURCE 200809L

#include "check.h"
#include "exact_dyadic.h"
#include "mesh_fixtures.h"
#include "test_random.h"

#include <isect.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ----------------------------------------------- the reference test */

/* isect.h's frame: kz = the axis of the largest |d|, lowest index on ties;
 * kx, ky the next two, swapped when d[kz] < 0. */
typedef struct frame {
    int kx, ky, kz;
} frame;

static frame frame_of(const double d[3])
{
    frame f;
    f.kz = 0;
    if (fabs(d[1]) > fabs(d[f.kz]))
        f.kz = 1;
    if (fabs(d[2]) > fabs(d[f.kz]))
        f.kz = 2;
    f.kx = (f.kz + 1) % 3;
    f.ky = (f.kz + 2) % 3;
    if (d[f.kz] < 0.0) {
        int t = f.kx;
        f.kx = f.ky;
        f.ky = t;
    }
    return f;
}

/* |d[kz]| times the exact projection of v. */
static void exact_proj(const double v[3], const double o[3], const double d[3], frame f,
                       exq *X, exq *Y)
{
    exq A[3];
    ex_diff3(v, o, A);
    exq dz = ex_of(d[f.kz]);
    *X = ex_sub(ex_mul(A[f.kx], dz), ex_mul(ex_of(d[f.kx]), A[f.kz]));
    *Y = ex_sub(ex_mul(A[f.ky], dz), ex_mul(ex_of(d[f.ky]), A[f.kz]));
    if (d[f.kz] < 0.0) {
        *X = ex_neg(*X);
        *Y = ex_neg(*Y);
    }
}

/* The rounded projection the library used before (ray_frame_project). */
static void rounded_proj(const double v[3], const double o[3], const double d[3], frame f,
                         exq *X, exq *Y)
{
    double sx = d[f.kx] / d[f.kz], sy = d[f.ky] / d[f.kz];
    double px = v[f.kx] - o[f.kx], py = v[f.ky] - o[f.ky], pz = v[f.kz] - o[f.kz];
    *X = ex_of(fma(-sx, pz, px));
    *Y = ex_of(fma(-sy, pz, py));
}

typedef void (*proj_fn)(const double v[3], const double o[3], const double d[3], frame f,
                        exq *X, exq *Y);

/* orient2 of p -> q about the perturbed origin. */
static int orient_perturbed(const exq *Xp, const exq *Yp, const exq *Xq, const exq *Yq)
{
    int s = ex_sign(ex_sub(ex_mul(*Xp, *Yq), ex_mul(*Yp, *Xq)));
    if (s != 0)
        return s;
    s = ex_sign(ex_sub(*Xp, *Xq));
    if (s != 0)
        return s;
    return ex_sign(ex_sub(*Yq, *Yp));
}

/* The winding number of the perturbed origin around the projected polygon
 * (n vertices at v + 3 idx[i], or v + 3 i). */
static int winding(const double *v, const int32_t *idx, int n, const double o[3],
                   const double d[3], proj_fn proj)
{
    frame f = frame_of(d);
    exq X[64], Y[64];
    for (int i = 0; i < n; i++)
        proj(v + 3 * (idx ? idx[i] : i), o, d, f, &X[i], &Y[i]);
    int w = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        int p_above = ex_sign(Y[i]) >= 0, q_above = ex_sign(Y[j]) >= 0;
        if (p_above == q_above)
            continue;
        int s = orient_perturbed(&X[i], &Y[i], &X[j], &Y[j]);
        if (!p_above)
            w += s > 0;
        else
            w -= s < 0;
    }
    return w;
}

/* The triangle test: all three perturbed orientations of one sign. */
static int triangle_inside(const double *a, const double *b, const double *c, const double o[3],
                           const double d[3], proj_fn proj)
{
    frame f = frame_of(d);
    exq X[3], Y[3];
    proj(a, o, d, f, &X[0], &Y[0]);
    proj(b, o, d, f, &X[1], &Y[1]);
    proj(c, o, d, f, &X[2], &Y[2]);
    int s0 = orient_perturbed(&X[0], &Y[0], &X[1], &Y[1]);
    int s1 = orient_perturbed(&X[1], &Y[1], &X[2], &Y[2]);
    int s2 = orient_perturbed(&X[2], &Y[2], &X[0], &Y[0]);
    return s0 != 0 && s0 == s1 && s1 == s2;
}

/* ----------------------------------------------------- ray making */

/* A point within a few ulps of: an edge of the polygon (half the time), a
 * vertex (a quarter), or a random point of it (the rest). */
static void near_boundary(const double *v, int n, double p[3])
{
    int i = rng_int(0, n - 1), j = (i + 1) % n, kind = rng_int(0, 3);
    double s = 0.5 * (rng_unit() + 1.0);
    const double *a = v + 3 * i, *b = v + 3 * j;
    for (int k = 0; k < 3; k++) {
        double x = kind == 0 ? a[k] : kind == 3 ? (a[k] + b[k] + v[3 * ((j + 1) % n) + k]) / 3.0
                                                : a[k] + s * (b[k] - a[k]);
        p[k] = kind == 3 ? x : ulps(x, rng_int(-3, 3));
    }
}

/* A ray through p from a random origin 1 to 2^20 sizes away (along the
 * whole line: tmin = -inf, tmax = inf, so only inclusion decides). */
static void ray_through(const double p[3], double size, isect_ray *r)
{
    double u[3];
    rng_dir(u);
    double dist = size * ldexp(1.0, rng_int(0, 20)), scale = ldexp(1.0, rng_int(-8, 8));
    for (int k = 0; k < 3; k++) {
        r->org[k] = p[k] + dist * u[k];
        r->dir[k] = (p[k] - r->org[k]) * scale;
    }
    r->tmin = -INFINITY;
    r->tmax = INFINITY;
}

/* A random frame for a face: centre c, orthonormal-ish u, v, size. */
static void random_plane(double c[3], double u[3], double w[3], double *size)
{
    *size = ldexp(1.0, rng_int(-8, 8));
    double place = ldexp(1.0, rng_int(-4, 24));
    rng_dir(c);
    for (int k = 0; k < 3; k++)
        c[k] *= place;
    double t[3];
    rng_dir(u);
    rng_dir(t);
    w[0] = u[1] * t[2] - u[2] * t[1];
    w[1] = u[2] * t[0] - u[0] * t[2];
    w[2] = u[0] * t[1] - u[1] * t[0];
    double len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int k = 0; k < 3; k++)
        w[k] /= len;
}

/* --------------------------------------------------------- the parts */

enum { BLOCK = 64 }; /* rays per batch call */

/* The batch at every SIMD level on BLOCK rays: how many hit/miss decisions
 * differ from the exact ones in expect[] (summed over the levels). */
static int batch_decisions_wrong(const isect_shape *s, const isect_ray *block, const int *expect)
{
    static const char *const levels[] = { "scalar", "sse2", "avx2", "avx512" };
    isect_hit out[BLOCK];
    int wrong = 0;
    for (int lv = 0; lv < 4; lv++) {
        setenv("ISECT_SIMD", levels[lv], 1);
        isect_intersect_batch(s, block, BLOCK, NULL, out);
        for (int j = 0; j < BLOCK; j++)
            wrong += (out[j].kind != ISECT_MISS) != expect[j];
    }
    unsetenv("ISECT_SIMD");
    return wrong;
}

static double face_size; /* of the current triangle or polygon */

static void test_triangles(int rays)
{
    int differs = 0, wrong = 0, hits = 0, batch_wrong = 0;
    isect_ray block[BLOCK];
    int expect[BLOCK];
    double tri[9];
    for (int i = 0; i < rays; i++) {
        if (i % BLOCK == 0) {
            double c[3], u[3], w[3], size;
            random_plane(c, u, w, &size);
            face_size = size;
            for (int j = 0; j < 3; j++) {
                double a = rng_unit() * size, b = rng_unit() * size;
                for (int k = 0; k < 3; k++)
                    tri[3 * j + k] = c[k] + a * u[k] + b * w[k];
            }
        }
        double p[3];
        near_boundary(tri, 3, p);
        isect_ray *r = &block[i % BLOCK];
        ray_through(p, face_size, r);
        int exact = triangle_inside(tri, tri + 3, tri + 6, r->org, r->dir, exact_proj);
        int rounded = triangle_inside(tri, tri + 3, tri + 6, r->org, r->dir, rounded_proj);
        isect_hit h;
        int got = isect_ray_triangle(r, tri, tri + 3, tri + 6, NULL, &h, 1);
        differs += exact != rounded;
        hits += exact;
        if (got != exact && wrong++ < 3)
            fprintf(stderr, "triangle: ray org %a %a %a dir %a %a %a: library %d, exact %d\n",
                    r->org[0], r->org[1], r->org[2], r->dir[0], r->dir[1], r->dir[2], got, exact);
        expect[i % BLOCK] = exact;
        if (i % BLOCK == BLOCK - 1) {
            isect_shape s = { ISECT_TRIANGLE, 0, 0, 0, tri, NULL, NULL };
            batch_wrong += batch_decisions_wrong(&s, block, expect);
        }
    }
    printf("triangles: %d rays near edges and vertices, %d hit, %d where the rounded "
           "projection decides otherwise, %d wrong, %d wrong in batches\n",
           rays, hits, differs, wrong, batch_wrong);
    CHECK(differs >= rays / 100);
    CHECK_EQ_INT(wrong, 0);
    CHECK_EQ_INT(batch_wrong, 0);
}

/* A polygon of n vertices in the plane (c; u, w): convex (a rounded
 * regular n-gon) or concave (a star). */
static void make_polygon(double *v, int n, int concave, const double c[3], const double u[3],
                         const double w[3], double size)
{
    for (int j = 0; j < n; j++) {
        double ang = 6.283185307179586 * j / n + 0.3 * rng_unit() / n;
        double rad = size * (concave && j % 2 ? 0.4 : 1.0) * (1.0 + 0.1 * rng_unit());
        double a = rad * cos(ang), b = rad * sin(ang);
        for (int k = 0; k < 3; k++)
            v[3 * j + k] = c[k] + a * u[k] + b * w[k];
    }
}

static void test_polygons(int rays)
{
    int differs = 0, wrong = 0, hits = 0, batch_wrong = 0;
    isect_ray block[BLOCK];
    int expect[BLOCK];
    double poly[3 * 12];
    int n = 3, concave = 0, rule = ISECT_EVEN_ODD;
    for (int i = 0; i < rays; i++) {
        if (i % BLOCK == 0) {
            double c[3], u[3], w[3], size;
            random_plane(c, u, w, &size);
            face_size = size;
            concave = rng_int(0, 1);
            n = concave ? 2 * rng_int(3, 6) : rng_int(3, 12);
            rule = rng_int(0, 1) ? ISECT_NONZERO : ISECT_EVEN_ODD;
            make_polygon(poly, n, concave, c, u, w, size);
        }
        double p[3];
        near_boundary(poly, n, p);
        isect_ray *r = &block[i % BLOCK];
        ray_through(p, face_size, r);
        int we = winding(poly, NULL, n, r->org, r->dir, exact_proj);
        int wr = winding(poly, NULL, n, r->org, r->dir, rounded_proj);
        int exact = rule == ISECT_NONZERO ? we != 0 : we % 2 != 0;
        int rounded = rule == ISECT_NONZERO ? wr != 0 : wr % 2 != 0;
        isect_hit h;
        int got = isect_ray_polygon(r, poly, n, rule, NULL, &h, 1);
        differs += exact != rounded;
        hits += exact;
        if (got != exact && wrong++ < 3)
            fprintf(stderr, "polygon (%d, concave %d): ray org %a %a %a dir %a %a %a: library "
                    "%d, exact %d\n", n, concave, r->org[0], r->org[1], r->org[2], r->dir[0],
                    r->dir[1], r->dir[2], got, exact);
        expect[i % BLOCK] = exact;
        if (i % BLOCK == BLOCK - 1) {
            isect_shape s = { ISECT_POLYGON, n, rule, 0, poly, NULL, NULL };
            batch_wrong += batch_decisions_wrong(&s, block, expect);
        }
    }
    printf("polygons: %d rays near edges and vertices, %d hit, %d where the rounded "
           "projection decides otherwise, %d wrong, %d wrong in batches\n",
           rays, hits, differs, wrong, batch_wrong);
    CHECK(differs >= rays / 100);
    CHECK_EQ_INT(wrong, 0);
    CHECK_EQ_INT(batch_wrong, 0);
}

/* Whether face f of m is crossed by the line of r: by the exact test, or
 * by the rounded one. */
static int face_claims(const fx_mesh *m, int64_t f, const isect_ray *r, proj_fn proj)
{
    const int32_t *c = m->idx + m->off[f];
    int size = (int)(m->off[f + 1] - m->off[f]);
    if (size == 3)
        return triangle_inside(m->v + 3 * c[0], m->v + 3 * c[1], m->v + 3 * c[2], r->org, r->dir,
                               proj);
    return winding(m->v, c, size, r->org, r->dir, proj) % 2 != 0;
}

/* A point moved off the dyadic grid: scaled by 0.7, rotated a little
 * about z, shifted by (0.1, -0.2, 0.3), each coordinate rounded. */
static void perturb_point(double v[3])
{
    const double c = cos(0.3), s = sin(0.3);
    double x = 0.7 * v[0], y = 0.7 * v[1], z = 0.7 * v[2];
    v[0] = c * x - s * y + 0.1;
    v[1] = s * x + c * y - 0.2;
    v[2] = z + 0.3;
}

static void perturb_vertices(fx_mesh *m)
{
    for (int64_t i = 0; i < m->nv; i++)
        perturb_point(m->v + 3 * i);
}

/* Points well inside the perturbed unit icosphere and the perturbed torus
 * (R = 1, r = 0.4, about z): near the centre, near the core circle. */
static void inside_sphere(double p[3])
{
    for (int k = 0; k < 3; k++)
        p[k] = 0.2 * rng_unit();
    perturb_point(p);
}

static void inside_torus(double p[3])
{
    double phi = 3.141592653589793 * rng_unit();
    p[0] = cos(phi) + 0.1 * rng_unit();
    p[1] = sin(phi) + 0.1 * rng_unit();
    p[2] = 0.1 * rng_unit();
    perturb_point(p);
}

static void test_mesh_part(const char *name, fx_mesh *m, void (*inside)(double p[3]), int rays)
{
    isect_mesh *mesh = fx_build(m);
    CHECK(mesh != NULL);
    if (mesh == NULL)
        return;
    isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, mesh, NULL };
    int parity_bad = 0, claims_bad = 0, differs = 0;
    enum { CAP = 64 };
    isect_hit hits[CAP];
    for (int i = 0; i < rays; i++) {
        /* a target within ulps of an edge or vertex of a random face */
        int64_t f = (int64_t)(rng_next() % (uint64_t)m->nf);
        int size = (int)(m->off[f + 1] - m->off[f]);
        double v[3 * 16], p[3];
        for (int j = 0; j < size; j++)
            memcpy(v + 3 * j, m->v + 3 * m->idx[m->off[f] + j], 3 * sizeof(double));
        near_boundary(v, size, p);
        isect_ray r;
        inside(r.org);
        for (int k = 0; k < 3; k++)
            r.dir[k] = p[k] - r.org[k];
        r.tmin = 0.0;
        r.tmax = INFINITY;
        int forward = isect_intersect(&s, &r, NULL, hits, CAP);
        r.tmin = -INFINITY;
        int line = isect_intersect(&s, &r, NULL, hits, CAP);
        if (forward % 2 != 1 || line % 2 != 0)
            parity_bad++;
        /* the faces claimed on the whole line: exactly the exact test's */
        int n_exact = 0, mismatch = 0, n_rounded_diff = 0;
        for (int64_t g = 0; g < m->nf; g++) {
            int e = face_claims(m, g, &r, exact_proj);
            n_exact += e;
            int reported = 0;
            for (int j = 0; j < line && j < CAP; j++)
                reported |= hits[j].prim == g;
            mismatch += reported != e;
            if (e != face_claims(m, g, &r, rounded_proj))
                n_rounded_diff++;
        }
        differs += n_rounded_diff > 0;
        if ((mismatch || n_exact != line) && claims_bad++ < 3)
            fprintf(stderr, "%s: ray org %a %a %a dir %a %a %a: %d faces reported, %d exact\n",
                    name, r.org[0], r.org[1], r.org[2], r.dir[0], r.dir[1], r.dir[2], line,
                    n_exact);
    }
    printf("%s: %d rays from inside at edges and vertices (within ulps), %d where the rounded "
           "projection claims other faces; %d parity errors, %d rays with other faces than the "
           "exact test's\n", name, rays, differs, parity_bad, claims_bad);
    CHECK(differs >= rays / 200);
    CHECK_EQ_INT(parity_bad, 0);
    CHECK_EQ_INT(claims_bad, 0);
    isect_mesh_destroy(mesh);
}

/*
 * Rays grazing an edge of a closed convex mesh, nudged by ulps: where both
 * faces of the edge are crossed and their t round alike, the closest hit
 * (isect_intersect_batch and the first of isect_intersect) must be the
 * face whose exact crossing parameter is smaller (ties: the lower index).
 */
static void test_grazing_ties(int rays)
{
    const double c0[3] = { 0.0, 0.0, 0.0 };
    fx_mesh m = fx_icosphere(1, c0, 1.0);
    perturb_vertices(&m);
    isect_mesh *mesh = fx_build(&m);
    isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, mesh, NULL };
    int ties = 0, wrong = 0;
    for (int i = 0; i < rays; i++) {
        int64_t f = (int64_t)(rng_next() % (uint64_t)m.nf);
        const int32_t *c = m.idx + m.off[f];
        int e = rng_int(0, 2);
        const double *a = m.v + 3 * c[e], *b = m.v + 3 * c[(e + 1) % 3];
        /* the edge's midpoint, the direction along the tangent plane at it:
         * perpendicular to the edge and to the outward radius */
        double mid[3], rad[3], t[3], dir[3];
        for (int k = 0; k < 3; k++) {
            mid[k] = 0.5 * (a[k] + b[k]);
            rad[k] = mid[k] - 0.3 * (k == 2) - 0.1 * (k == 0) + 0.2 * (k == 1);
            t[k] = b[k] - a[k];
        }
        dir[0] = t[1] * rad[2] - t[2] * rad[1];
        dir[1] = t[2] * rad[0] - t[0] * rad[2];
        dir[2] = t[0] * rad[1] - t[1] * rad[0];
        isect_ray r;
        for (int k = 0; k < 3; k++) {
            r.org[k] = ulps(mid[k] - 3.0 * dir[k], rng_int(-2, 2));
            r.dir[k] = dir[k];
        }
        r.tmin = 0.0;
        r.tmax = INFINITY;
        isect_hit all[8], first;
        int n = isect_intersect(&s, &r, NULL, all, 8);
        int64_t got = isect_intersect_batch(&s, &r, 1, NULL, &first);
        if (n < 2 || got != 1 || all[0].t != all[1].t || all[0].prim == all[1].prim)
            continue;
        ties++;
        exq na, da, nb, db;
        const int32_t *ca = m.idx + m.off[all[0].prim], *cb = m.idx + m.off[all[1].prim];
        ex_triangle_crossing(r.org, r.dir, m.v + 3 * ca[0], m.v + 3 * ca[1], m.v + 3 * ca[2],
                             &na, &da);
        ex_triangle_crossing(r.org, r.dir, m.v + 3 * cb[0], m.v + 3 * cb[1], m.v + 3 * cb[2],
                             &nb, &db);
        int cmp = ex_ratio_cmp(na, da, nb, db);
        int ok = cmp < 0 || (cmp == 0 && all[0].prim < all[1].prim);
        ok = ok && memcmp(&first, &all[0], sizeof first) == 0;
        if (!ok && wrong++ < 3)
            fprintf(stderr, "grazing tie: faces %d, %d at t %a: exact order %d\n", all[0].prim,
                    all[1].prim, all[0].t, cmp);
    }
    printf("grazing ties: %d rays, %d with two faces at one rounded t, %d in the wrong order\n",
           rays, ties, wrong);
    CHECK(ties >= rays / 100);
    CHECK_EQ_INT(wrong, 0);
    isect_mesh_destroy(mesh);
    fx_free(&m);
}

int main(int argc, char **argv)
{
    int rays = argc > 1 ? atoi(argv[1]) : 8000;
    if (rays < 1000)
        rays = 1000;
    test_triangles(rays);
    test_polygons(rays);
    const double c0[3] = { 0.0, 0.0, 0.0 };
    fx_mesh sphere = fx_icosphere(2, c0, 1.0);
    perturb_vertices(&sphere);
    test_mesh_part("icosphere (triangles)", &sphere, inside_sphere, rays / 4);
    fx_free(&sphere);
    fx_mesh torus = fx_torus(1.0, 0.4, 12, 8, 0);
    perturb_vertices(&torus);
    test_mesh_part("torus (non-planar quads)", &torus, inside_torus, rays / 4);
    fx_free(&torus);
    test_grazing_ties(rays);
    return check_summary();
}
