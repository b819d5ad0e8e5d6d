/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_mesh_exactly_once.c — the headline guarantee for meshes: a ray that
 * crosses a closed surface through a shared edge or vertex is counted
 * exactly once, so the number of hits in [0, inf) is even from outside and
 * odd from inside, for triangle and for polygon faces.
 *
 * Rays are aimed at every vertex and every edge midpoint of closed meshes —
 * an icosphere, a torus (genus 1) of triangles and of non-planar quads, a
 * cube of quads, an L-shaped prism whose caps are concave hexagons (also
 * rotated, so its faces are no longer exactly planar), and a genus-2 block
 * of quads and of triangles — from random points outside and inside. The
 * integer-coordinate meshes get dyadic origins, so the ray passes EXACTLY
 * through the vertex or midpoint; the others pass within an ulp. The whole
 * line (tmin = -inf) must give an even count too.
 *
 *     test_mesh_exactly_once [rays]    (default 1000000; also read from
 *                                       ISECT_EXACTLY_ONCE_RAYS)
 *
 * Prints the number of rays and of exceptions per mesh and in total.
 */
#include "check.h"

#include <isect.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_fixtures.h"

/* ------------------------------------------------------------- the test */

typedef struct lcg {
    uint64_t state;
} lcg;

static double lcg_uniform(lcg *g) /* in [0, 1) */
{
    g->state = g->state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(g->state >> 11) * 0x1p-53;
}

/* The targets: every vertex and every edge midpoint (each undirected edge
 * once; the same face-boundary pairs as the report's edges). */
static double *targets_of(const fx_mesh *m, int64_t *count)
{
    int64_t cap = m->nv + m->nidx, n = 0;
    double *t = malloc((size_t)(3 * cap) * sizeof *t);
    for (int64_t i = 0; i < m->nv; i++, n++)
        memcpy(t + 3 * n, m->v + 3 * i, 3 * sizeof(double));
    for (int64_t f = 0; f < m->nf; f++) {
        int size = (int)(m->off[f + 1] - m->off[f]);
        const int32_t *c = m->idx + m->off[f];
        for (int i = 0; i < size; i++) {
            int32_t a = c[i], b = c[(i + 1) % size];
            if (a > b) /* each interior edge once: the use with a < b */
                continue;
            for (int k = 0; k < 3; k++)
                t[3 * n + k] = 0.5 * (m->v[3 * a + k] + m->v[3 * b + k]);
            n++;
        }
    }
    *count = n;
    return t;
}

/* How a mesh's random interior points are drawn. */
enum interior { IN_BALL, IN_TORUS, IN_BOX, IN_L, IN_GENUS2 };

typedef struct case_def {
    const char   *name;
    fx_mesh       mesh;
    enum interior interior;
    double        param[4];   /* ball: centre, radius; torus: R, r; box/L: size, height */
    int           dyadic;     /* integer vertices: dyadic origins, exact aim */
    double        rot[9];     /* rotation applied to mesh and interior points (or identity) */
} case_def;

static void rotate(const double r[9], const double p[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = r[3 * i] * p[0] + r[3 * i + 1] * p[1] + r[3 * i + 2] * p[2];
}

static void interior_point(const case_def *c, lcg *g, double p[3])
{
    double q[3];
    switch (c->interior) {
    case IN_BALL: {
        for (;;) {
            double d2 = 0.0;
            for (int k = 0; k < 3; k++) {
                q[k] = 2.0 * lcg_uniform(g) - 1.0;
                d2 += q[k] * q[k];
            }
            if (d2 <= 1.0)
                break;
        }
        for (int k = 0; k < 3; k++)
            q[k] = c->param[k] + c->param[3] * q[k];
        break;
    }
    case IN_TORUS: {
        /* Within 0.8 of the tube radius of the core circle: inside the
         * tessellated tube too. */
        double u = 6.283185307179586 * lcg_uniform(g), w = 6.283185307179586 * lcg_uniform(g);
        double rho = 0.8 * c->param[1] * sqrt(lcg_uniform(g));
        double ring = c->param[0] + rho * cos(w);
        q[0] = ring * cos(u);
        q[1] = ring * sin(u);
        q[2] = rho * sin(w);
        break;
    }
    case IN_BOX:
        for (int k = 0; k < 3; k++)
            q[k] = c->param[k] * (0.001 + 0.998 * lcg_uniform(g));
        break;
    case IN_L:
        for (;;) {
            q[0] = 0.001 + 1.998 * lcg_uniform(g);
            q[1] = 0.001 + 1.998 * lcg_uniform(g);
            if (q[0] < 0.999 || q[1] < 0.999)
                break;
        }
        q[2] = c->param[0] * (0.001 + 0.998 * lcg_uniform(g));
        break;
    default: { /* genus 2: a random solid cell of the 5 x 3 block */
        int x, y;
        do {
            x = (int)(5.0 * lcg_uniform(g));
            y = (int)(3.0 * lcg_uniform(g));
        } while (y == 1 && (x == 1 || x == 3));
        q[0] = x + 0.001 + 0.998 * lcg_uniform(g);
        q[1] = y + 0.001 + 0.998 * lcg_uniform(g);
        q[2] = 0.001 + 0.998 * lcg_uniform(g);
        break;
    }
    }
    rotate(c->rot, q, p);
}

/* An origin for an exact aim: a multiple of 2^-12, so target - origin is
 * exact for targets on the half-integer grid and org + 1*dir == target. */
static void dyadic(double p[3])
{
    for (int k = 0; k < 3; k++)
        p[k] = ldexp(nearbyint(ldexp(p[k], 12)), -12);
}

typedef struct tally {
    int64_t rays, bad_outside, bad_inside, bad_line, errors;
} tally;

static void run_case(const case_def *c, int64_t rays, uint64_t seed, tally *t)
{
    isect_mesh *mesh = fx_build(&c->mesh);
    isect_shape s = { ISECT_MESH, 0, 0, 0, NULL, mesh, NULL };
    isect_mesh_report rep;
    CHECK_EQ_INT(isect_mesh_check(mesh, &rep), ISECT_OK);
    CHECK(rep.closed == 1 && rep.oriented == 1);
    int64_t ntargets;
    double *targets = targets_of(&c->mesh, &ntargets);
    /* Outside: points on a sphere three times the mesh's radius. */
    double centre[3] = { 0.0, 0.0, 0.0 }, radius = 0.0;
    for (int64_t i = 0; i < c->mesh.nv; i++)
        for (int k = 0; k < 3; k++)
            centre[k] += c->mesh.v[3 * i + k] / (double)c->mesh.nv;
    for (int64_t i = 0; i < c->mesh.nv; i++) {
        double d2 = 0.0;
        for (int k = 0; k < 3; k++)
            d2 += (c->mesh.v[3 * i + k] - centre[k]) * (c->mesh.v[3 * i + k] - centre[k]);
        radius = fmax(radius, sqrt(d2));
    }
    lcg g = { seed };
    tally local = { 0, 0, 0, 0, 0 };
    for (int64_t i = 0; i < rays; i++) {
        const double *target = targets + 3 * (i % ntargets);
        int inside = (i / ntargets) % 2 == 1;
        double org[3];
        if (inside) {
            interior_point(c, &g, org);
        } else {
            double d[3], len;
            do {
                len = 0.0;
                for (int k = 0; k < 3; k++) {
                    d[k] = 2.0 * lcg_uniform(&g) - 1.0;
                    len += d[k] * d[k];
                }
            } while (len > 1.0 || len < 1e-4);
            len = sqrt(len);
            for (int k = 0; k < 3; k++)
                org[k] = centre[k] + 3.0 * radius * d[k] / len;
        }
        if (c->dyadic)
            dyadic(org);
        isect_ray r;
        for (int k = 0; k < 3; k++) {
            r.org[k] = org[k];
            r.dir[k] = target[k] - org[k];
        }
        r.tmin = 0.0;
        r.tmax = INFINITY;
        int n = isect_intersect(&s, &r, NULL, NULL, 0);
        local.rays++;
        if (n < 0) {
            local.errors++;
            continue;
        }
        if (n % 2 != inside) {
            if (inside)
                local.bad_inside++;
            else
                local.bad_outside++;
            if (local.bad_inside + local.bad_outside <= 3)
                fprintf(stderr, "    %s: %s ray org (%.17g, %.17g, %.17g) dir (%.17g, %.17g, %.17g): %d hits\n",
                        c->name, inside ? "inside" : "outside", r.org[0], r.org[1], r.org[2],
                        r.dir[0], r.dir[1], r.dir[2], n);
        }
        /* The whole line crosses a closed surface an even number of times;
         * checked on every 16th ray (it costs a second query). */
        if (i % 16 == 0) {
            r.tmin = -INFINITY;
            n = isect_intersect(&s, &r, NULL, NULL, 0);
            if (n < 0 || n % 2 != 0)
                local.bad_line++;
        }
    }
    printf("  %-22s %8lld rays (%lld targets): %lld outside, %lld inside, %lld line exceptions\n",
           c->name, (long long)local.rays, (long long)ntargets, (long long)local.bad_outside,
           (long long)local.bad_inside, (long long)local.bad_line);
    CHECK_EQ_INT(local.errors, 0);
    CHECK_EQ_INT(local.bad_outside, 0);
    CHECK_EQ_INT(local.bad_inside, 0);
    CHECK_EQ_INT(local.bad_line, 0);
    t->rays += local.rays;
    t->bad_outside += local.bad_outside;
    t->bad_inside += local.bad_inside;
    t->bad_line += local.bad_line;
    t->errors += local.errors;
    free(targets);
    isect_mesh_destroy(mesh);
}

static void rotate_mesh(fx_mesh *m, const double r[9])
{
    for (int64_t i = 0; i < m->nv; i++) {
        double p[3];
        rotate(r, m->v + 3 * i, p);
        memcpy(m->v + 3 * i, p, sizeof p);
    }
}

int main(int argc, char **argv)
{
    int64_t total = 1000000;
    const char *env = getenv("ISECT_EXACTLY_ONCE_RAYS");
    if (argc > 1)
        total = atoll(argv[1]);
    else if (env != NULL && *env != '\0')
        total = atoll(env);
    if (total < 1) {
        fprintf(stderr, "usage: test_mesh_exactly_once [rays]\n");
        return 2;
    }
    const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    /* A rotation with no exactly representable structure (about (1,2,3)). */
    double rot[9];
    {
        double axis[3] = { 1.0, 2.0, 3.0 }, len = sqrt(14.0);
        for (int k = 0; k < 3; k++)
            axis[k] /= len;
        fx_rotation(axis, 0.61, rot);
    }
    const double ball_c[3] = { 0.25, -0.125, 0.5 };
    enum { CASES = 9 };
    case_def cases[CASES];
    memset(cases, 0, sizeof cases);
    cases[0].name = "icosphere (triangles)";
    cases[0].mesh = fx_icosphere(3, ball_c, 1.5);
    cases[0].interior = IN_BALL;
    cases[0].param[0] = ball_c[0];
    cases[0].param[1] = ball_c[1];
    cases[0].param[2] = ball_c[2];
    cases[0].param[3] = 1.2;
    cases[1].name = "torus (triangles)";
    cases[1].mesh = fx_torus(1.0, 0.4, 48, 24, 1);
    cases[1].interior = IN_TORUS;
    cases[1].param[0] = 1.0;
    cases[1].param[1] = 0.4;
    cases[2].name = "torus (quads)";
    cases[2].mesh = fx_torus(1.0, 0.4, 32, 16, 0);
    cases[2].interior = IN_TORUS;
    cases[2].param[0] = 1.0;
    cases[2].param[1] = 0.4;
    cases[3].name = "cube (quads)";
    cases[3].mesh = fx_cube(0);
    cases[3].interior = IN_BOX;
    cases[3].param[0] = cases[3].param[1] = cases[3].param[2] = 1.0;
    cases[3].dyadic = 1;
    cases[4].name = "cube (triangles)";
    cases[4].mesh = fx_cube(1);
    cases[4].interior = IN_BOX;
    cases[4].param[0] = cases[4].param[1] = cases[4].param[2] = 1.0;
    cases[4].dyadic = 1;
    cases[5].name = "L-prism (concave)";
    cases[5].mesh = fx_l_prism(1.0);
    cases[5].interior = IN_L;
    cases[5].param[0] = 1.0;
    cases[5].dyadic = 1;
    cases[6].name = "L-prism (rotated)";
    cases[6].mesh = fx_l_prism(1.0);
    cases[6].interior = IN_L;
    cases[6].param[0] = 1.0;
    cases[7].name = "genus 2 (quads)";
    cases[7].mesh = fx_genus2(0);
    cases[7].interior = IN_GENUS2;
    cases[7].dyadic = 1;
    cases[8].name = "genus 2 (triangles)";
    cases[8].mesh = fx_genus2(1);
    cases[8].interior = IN_GENUS2;
    cases[8].dyadic = 1;
    for (int i = 0; i < CASES; i++)
        memcpy(cases[i].rot, i == 6 ? rot : identity, sizeof identity);
    rotate_mesh(&cases[6].mesh, rot);

    /* The rays shared out evenly, at least a few per target. */
    tally t = { 0, 0, 0, 0, 0 };
    printf("exactly-once: %lld rays at vertices and edge midpoints\n", (long long)total);
    for (int i = 0; i < CASES; i++) {
        int64_t share = total / CASES + (i < total % CASES);
        run_case(&cases[i], share, 0x5DEECE66DULL + 977ULL * (uint64_t)i, &t);
        fx_free(&cases[i].mesh);
    }
    printf("exactly-once total: %lld rays, %lld exceptions (%lld outside, %lld inside, "
           "%lld whole-line, %lld errors)\n",
           (long long)t.rays,
           (long long)(t.bad_outside + t.bad_inside + t.bad_line + t.errors),
           (long long)t.bad_outside, (long long)t.bad_inside, (long long)t.bad_line,
           (long long)t.errors);
    return check_summary();
}
