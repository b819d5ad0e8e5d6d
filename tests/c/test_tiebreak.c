/* SPDX-License-Identifier: Apache-2.0 */
/*
 * test_tiebreak.c — the exactly-once guarantee of isect.h's "Tie-breaking"
 * section, tested where it is hardest: rays through shared vertices and
 * edges of closed, consistently oriented surfaces, and 2D query points on
 * the edges and corners of tilings.
 *
 * Coordinates are integers or dyadic fractions so that "through the vertex"
 * and "on the edge" are exact statements; the expected counts follow from
 * topology alone (a ray from inside a closed surface crosses it an odd
 * number of times, once for a star-shaped solid seen from its centre; from
 * outside an even number; a whole line an even number), never from the
 * library.
 */
#include "check.h"

#include <isect.h>

#include <stdint.h>
#include <string.h>

/* ------------------------------------------------------------- helpers */

/* A deterministic generator for generic (non-dyadic) test points. */
typedef struct lcg {
    uint64_t state;
} lcg;

static double lcg_uniform(lcg *g) /* in [-1, 1) */
{
    g->state = g->state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(g->state >> 11) * 0x1p-52 - 1.0;
}

static isect_ray ray_toward(const double org[3], const double target[3], double scale,
                            double tmin)
{
    isect_ray r;
    for (int k = 0; k < 3; k++) {
        r.org[k] = org[k];
        r.dir[k] = (target[k] - org[k]) * scale;
    }
    r.tmin = tmin;
    r.tmax = INFINITY;
    return r;
}

static void report_ray(const char *what, const isect_ray *r, int got)
{
    fprintf(stderr, "    %s: org (%.17g, %.17g, %.17g) dir (%.17g, %.17g, %.17g) tmin %g -> %d hits\n",
            what, r->org[0], r->org[1], r->org[2], r->dir[0], r->dir[1], r->dir[2], r->tmin, got);
}

/* How a face list is intersected: every face as a triangle, every face as
 * a polygon under either rule, or alternating triangle / polygon (the two
 * paths must agree on every ray for the mixture to stay watertight). */
enum face_mode { AS_TRIANGLES, AS_POLYGONS_EVEN_ODD, AS_POLYGONS_NONZERO, AS_MIXED, MODES };

/* A surface of polygonal faces: face f is verts[start[f] .. start[f+1]). */
#define MAX_FACES 32
#define MAX_CORNERS 128
typedef struct surface {
    int    faces;
    int    start[MAX_FACES + 1];
    double verts[MAX_CORNERS][3];
} surface;

static void surface_add_face(surface *s, const double *const *corners, int n)
{
    int at = s->start[s->faces];
    for (int i = 0; i < n; i++)
        memcpy(s->verts[at + i], corners[i], sizeof s->verts[0]);
    s->faces++;
    s->start[s->faces] = at + n;
}

/* Total hits over all faces; the kind of the last hit in *kind. -1000 on
 * an error status (which would fail every expectation). */
static int surface_count(const surface *s, const isect_ray *r, enum face_mode mode, int *kind)
{
    int total = 0;
    for (int f = 0; f < s->faces; f++) {
        const double *v = s->verts[s->start[f]];
        int n = s->start[f + 1] - s->start[f];
        int as_triangle = n == 3 && (mode == AS_TRIANGLES || (mode == AS_MIXED && f % 2 == 0));
        int rule = mode == AS_POLYGONS_NONZERO || (mode == AS_MIXED && f % 4 == 1)
                       ? ISECT_NONZERO : ISECT_EVEN_ODD;
        isect_hit h[2];
        int c = as_triangle ? isect_ray_triangle(r, v, v + 3, v + 6, NULL, h, 2)
                            : isect_ray_polygon(r, v, n, rule, NULL, h, 2);
        if (c < 0)
            return -1000;
        if (c > 0 && kind != NULL)
            *kind = h[0].kind;
        total += c;
    }
    return total;
}

/* Each expectation is one CHECK; the failing ray is printed. */
static void expect_exactly(const char *what, const surface *s, const isect_ray *r,
                           enum face_mode mode, int want)
{
    int got = surface_count(s, r, mode, NULL);
    if (got != want)
        report_ray(what, r, got);
    check_record(got == want, __FILE__, __LINE__, what);
}

static void expect_even(const char *what, const surface *s, const isect_ray *r,
                        enum face_mode mode)
{
    int got = surface_count(s, r, mode, NULL);
    int ok = got >= 0 && got % 2 == 0;
    if (!ok)
        report_ray(what, r, got);
    check_record(ok, __FILE__, __LINE__, what);
}

static void expect_odd(const char *what, const surface *s, const isect_ray *r,
                       enum face_mode mode)
{
    int got = surface_count(s, r, mode, NULL);
    int ok = got > 0 && got % 2 == 1;
    if (!ok)
        report_ray(what, r, got);
    check_record(ok, __FILE__, __LINE__, what);
}

/* ---------------------------------------------------------- octahedra */

/* The octahedron centre + M (|w1| + |w2| + |w3| <= 1): vertices
 * centre +- column k of the integer matrix M, eight faces oriented outward
 * (for M = I face (+,+,+) is (e1, e2, e3), normal (1,1,1)). */
typedef struct octahedron {
    double  vertex[6][3]; /* +col0, -col0, +col1, -col1, +col2, -col2 */
    double  centre[3];
    double  m[3][3];
    surface faces;
} octahedron;

static double det3(const double m[3][3])
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
         - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
         + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* centre + M w (exact for dyadic w and small integer M). */
static void octahedron_point(const octahedron *o, const double w[3], double p[3])
{
    for (int i = 0; i < 3; i++)
        p[i] = o->centre[i] + o->m[i][0] * w[0] + o->m[i][1] * w[1] + o->m[i][2] * w[2];
}

static void octahedron_make(octahedron *o, const double m[3][3], const double centre[3])
{
    memcpy(o->m, m, sizeof o->m);
    memcpy(o->centre, centre, sizeof o->centre);
    for (int k = 0; k < 3; k++) {
        for (int sgn = 0; sgn < 2; sgn++) {
            double w[3] = { 0, 0, 0 };
            w[k] = sgn ? -1.0 : 1.0;
            octahedron_point(o, w, o->vertex[2 * k + sgn]);
        }
    }
    int mirror = det3(m) < 0;
    o->faces.faces = 0;
    o->faces.start[0] = 0;
    for (int sx = 0; sx < 2; sx++)
        for (int sy = 0; sy < 2; sy++)
            for (int sz = 0; sz < 2; sz++) {
                const double *a = o->vertex[sx], *b = o->vertex[2 + sy], *c = o->vertex[4 + sz];
                int flip = ((sx + sy + sz) % 2 == 1) != mirror;
                const double *corners[3] = { a, flip ? c : b, flip ? b : c };
                surface_add_face(&o->faces, corners, 3);
            }
}

/* The 6 vertices and the 12 edge midpoints (all pairs but opposite ones). */
static int octahedron_targets(const octahedron *o, double targets[18][3])
{
    int n = 0;
    for (int i = 0; i < 6; i++)
        memcpy(targets[n++], o->vertex[i], sizeof targets[0]);
    for (int i = 0; i < 6; i++)
        for (int j = i + 1; j < 6; j++) {
            if (j == i + 1 && i % 2 == 0)
                continue; /* opposite vertices: no edge */
            for (int k = 0; k < 3; k++)
                targets[n][k] = 0.5 * (o->vertex[i][k] + o->vertex[j][k]);
            n++;
        }
    return n;
}

static const double octa_matrices[4][3][3] = {
    { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
    { { 2, 1, 0 }, { 0, 1, 1 }, { 1, 0, 3 } },
    { { 3, -4, 0 }, { 4, 3, 0 }, { 0, 0, 5 } },   /* a rotation by atan(4/3), scaled */
    { { 1, 2, -1 }, { -2, 1, 3 }, { 1, -1, -2 } } /* det < 0: mirrored */
};
static const double octa_centres[4][3] = {
    { 0, 0, 0 }, { 0.375, -1.25, 2.5 }, { -3, 0.5, 0.25 }, { 1024.5, -2048.25, 4096.125 }
};

static void test_octahedron_from_inside(void)
{
    /* In the octahedron's own coordinates w: |w|_1 < 1 is inside. */
    static const double inside_w[5][3] = {
        { 0, 0, 0 }, { 0.25, -0.125, 0.0625 }, { -0.375, 0.25, 0.125 },
        { 0.0625, 0.5, -0.3125 }, { -0.125, -0.125, -0.5 }
    };
    lcg g = { 12345 };
    for (int mi = 0; mi < 4; mi++) {
        octahedron o;
        octahedron_make(&o, octa_matrices[mi], octa_centres[mi]);
        double targets[18][3];
        int nt = octahedron_targets(&o, targets);
        CHECK_EQ_INT(nt, 18);
        for (int pi = 0; pi < 8; pi++) {
            double w[3], org[3];
            if (pi < 5) {
                memcpy(w, inside_w[pi], sizeof w);
            } else { /* generic interior points, |w|_1 <= 0.9 */
                for (int k = 0; k < 3; k++)
                    w[k] = 0.3 * lcg_uniform(&g);
            }
            octahedron_point(&o, w, org);
            for (int ti = 0; ti < nt; ti++) {
                for (int mode = 0; mode < MODES; mode++) {
                    isect_ray r = ray_toward(org, targets[ti], 1.0, 0.0);
                    expect_exactly("octahedron, inside through vertex/edge: 1 hit",
                                   &o.faces, &r, (enum face_mode)mode, 1);
                    int kind = 0;
                    surface_count(&o.faces, &r, (enum face_mode)mode, &kind);
                    CHECK_EQ_INT(kind, ISECT_EXIT); /* outward faces, leaving */
                    r = ray_toward(org, targets[ti], 0x1p-20, 0.0);
                    expect_exactly("octahedron, inside, short dir: 1 hit", &o.faces, &r,
                                   (enum face_mode)mode, 1);
                    r = ray_toward(org, targets[ti], 3.0, -INFINITY);
                    expect_exactly("octahedron, whole line from inside: 2 hits", &o.faces,
                                   &r, (enum face_mode)mode, 2);
                }
            }
        }
    }
}

static void test_octahedron_from_outside(void)
{
    static const double outside_w[6][3] = {
        { 2, 0.5, 0.25 }, { -1.5, -1.5, 1 }, { 0.125, 3, -0.25 },
        { 0.5, 0.5, 0.5 }, { 0, 0, -2 }, { 1, 1, 0 }
    };
    for (int mi = 0; mi < 4; mi++) {
        octahedron o;
        octahedron_make(&o, octa_matrices[mi], octa_centres[mi]);
        double targets[18][3];
        int nt = octahedron_targets(&o, targets);
        for (int pi = 0; pi < 6; pi++) {
            double org[3];
            octahedron_point(&o, outside_w[pi], org);
            for (int ti = 0; ti < nt; ti++) {
                for (int mode = 0; mode < MODES; mode++) {
                    isect_ray r = ray_toward(org, targets[ti], 1.0, 0.0);
                    expect_even("octahedron, outside through vertex/edge: even", &o.faces,
                                &r, (enum face_mode)mode);
                    r = ray_toward(org, targets[ti], 1.0, -INFINITY);
                    expect_even("octahedron, whole line: even", &o.faces, &r,
                                (enum face_mode)mode);
                }
            }
        }
        /* Straight through the centre from an outside vertex direction:
         * exactly two (in at one vertex, out at the opposite one). */
        for (int v = 0; v < 6; v++) {
            double org[3];
            for (int k = 0; k < 3; k++)
                org[k] = o.centre[k] + 2.0 * (o.vertex[v][k] - o.centre[k]);
            isect_ray r = ray_toward(org, o.centre, 1.0, 0.0);
            for (int mode = 0; mode < MODES; mode++)
                expect_exactly("octahedron, vertex to opposite vertex: 2 hits", &o.faces, &r,
                               (enum face_mode)mode, 2);
        }
    }
}

/* A ray that only touches a silhouette vertex or edge, or lies along an
 * edge, meets the closed surface an even number of times. */
static void test_octahedron_grazing(void)
{
    for (int mi = 0; mi < 4; mi++) {
        octahedron o;
        octahedron_make(&o, octa_matrices[mi], octa_centres[mi]);
        /* At vertex +col0 (w = e1), directions d (in w coordinates) with
         * |d1| < |d2| + |d3| keep the line outside except at the vertex. */
        static const double vertex_dirs[6][3] = {
            { 0, 1, 0 }, { 0, 0, 1 }, { 0, 1, 1 }, { 0, 1, -0.5 }, { 0.5, 1, 0 },
            { -0.25, -0.5, 0.5 }
        };
        /* At the midpoint of edge (e1, e2), w = (1/2, 1/2, 0): directions in
         * the supporting plane w1 + w2 = 1 touch only the edge, and
         * (1, -1, 0) runs along it. */
        static const double edge_dirs[5][3] = {
            { 0, 0, 1 }, { 1, -1, 1 }, { 1, -1, -2 }, { -2, 2, 1 }, { 1, -1, 0 }
        };
        static const double vertex_w[3] = { 1, 0, 0 }, edge_w[3] = { 0.5, 0.5, 0 };
        for (int kind = 0; kind < 2; kind++) {
            const double *at_w = kind == 0 ? vertex_w : edge_w;
            int ndirs = kind == 0 ? 6 : 5;
            for (int di = 0; di < ndirs; di++) {
                const double *dw = kind == 0 ? vertex_dirs[di] : edge_dirs[di];
                for (int sign = -1; sign <= 1; sign += 2) {
                    double from_w[3], org[3], target[3];
                    for (int k = 0; k < 3; k++)
                        from_w[k] = at_w[k] - 4.0 * sign * dw[k];
                    octahedron_point(&o, from_w, org);
                    octahedron_point(&o, at_w, target);
                    for (int mode = 0; mode < MODES; mode++) {
                        isect_ray r = ray_toward(org, target, 1.0, 0.0);
                        expect_even("octahedron, grazing a silhouette vertex/edge: even",
                                    &o.faces, &r, (enum face_mode)mode);
                        r.tmin = -INFINITY;
                        expect_even("octahedron, grazing line: even", &o.faces, &r,
                                    (enum face_mode)mode);
                    }
                }
            }
        }
    }
}

/* Generic rays from generic interior points: one hit, for every mode. */
static void test_octahedron_generic(void)
{
    lcg g = { 777 };
    octahedron o;
    octahedron_make(&o, octa_matrices[1], octa_centres[1]);
    for (int i = 0; i < 400; i++) {
        double w[3], org[3], d[3];
        for (int k = 0; k < 3; k++) {
            w[k] = 0.3 * lcg_uniform(&g);
            d[k] = lcg_uniform(&g);
        }
        octahedron_point(&o, w, org);
        isect_ray r = { { org[0], org[1], org[2] }, { d[0], d[1], d[2] }, 0.0, INFINITY };
        for (int mode = 0; mode < MODES; mode++)
            expect_exactly("octahedron, generic ray from inside: 1 hit", &o.faces, &r,
                           (enum face_mode)mode, 1);
    }
}

/* ------------------------------------------------- star bipyramid (concave) */

/* A closed, concave solid: an equator of 2k points alternating between
 * radius 8 and 3 (a star), apexes above and below; 4k triangles. Star-shaped
 * around the origin, so a ray from the origin crosses it exactly once. */
static void star_bipyramid(int k, surface *s, double targets[][3], int *ntargets)
{
    static const double ring8[8][2] = { { 8, 0 }, { 6, 5 }, { 0, 8 }, { -6, 5 },
                                        { -8, 0 }, { -6, -5 }, { 0, -8 }, { 6, -5 } };
    static const double ring3[8][2] = { { 3, 1 }, { 2, 3 }, { -1, 3 }, { -3, 2 },
                                        { -3, -1 }, { -2, -3 }, { 1, -3 }, { 3, -2 } };
    double eq[16][3];
    int n = 2 * k;
    for (int i = 0; i < k; i++) {
        /* k of the 8 directions, in counter-clockwise order. */
        int j = i * 8 / k;
        eq[2 * i][0] = ring8[j][0];
        eq[2 * i][1] = ring8[j][1];
        eq[2 * i][2] = (i % 3) - 1;
        /* ring3[j] lies angularly between ring8[j] and ring8[j + 1]. */
        eq[2 * i + 1][0] = ring3[j][0];
        eq[2 * i + 1][1] = ring3[j][1];
        eq[2 * i + 1][2] = 0.5;
    }
    static const double top[3] = { 0.5, -0.25, 7 }, bottom[3] = { -0.25, 0.5, -6 };
    s->faces = 0;
    s->start[0] = 0;
    *ntargets = 0;
    for (int i = 0; i < n; i++) {
        const double *p = eq[i], *q = eq[(i + 1) % n];
        const double *up[3] = { p, q, top }, *down[3] = { q, p, bottom };
        surface_add_face(s, up, 3);
        surface_add_face(s, down, 3);
        memcpy(targets[(*ntargets)++], p, sizeof targets[0]);
        for (int c = 0; c < 3; c++) {
            const double *other = c == 0 ? q : c == 1 ? top : bottom;
            for (int d = 0; d < 3; d++)
                targets[*ntargets][d] = 0.5 * (p[d] + other[d]);
            (*ntargets)++;
        }
    }
    memcpy(targets[(*ntargets)++], top, sizeof targets[0]);
    memcpy(targets[(*ntargets)++], bottom, sizeof targets[0]);
}

static void test_star_bipyramid(void)
{
    for (int k = 3; k <= 8; k++) {
        surface s;
        double targets[70][3];
        int nt;
        star_bipyramid(k, &s, targets, &nt);
        static const double origin[3] = { 0, 0, 0 };
        static const double outside[3][3] = { { 20, 1, 0.5 }, { -3, 2, 30 }, { 0.25, -40, -2 } };
        for (int ti = 0; ti < nt; ti++) {
            for (int mode = 0; mode < MODES; mode++) {
                isect_ray r = ray_toward(origin, targets[ti], 1.0, 0.0);
                expect_exactly("star bipyramid, centre through vertex/edge: 1 hit", &s, &r,
                               (enum face_mode)mode, 1);
                r.tmin = -INFINITY;
                expect_even("star bipyramid, whole line: even", &s, &r, (enum face_mode)mode);
                for (int oi = 0; oi < 3; oi++) {
                    r = ray_toward(outside[oi], targets[ti], 1.0, 0.0);
                    expect_even("star bipyramid, from outside: even", &s, &r,
                                (enum face_mode)mode);
                }
                /* The same direction from another interior point. */
                static const double inner[3] = { 0.125, -0.0625, 0.25 };
                r = ray_toward(origin, targets[ti], 1.0, 0.0);
                memcpy(r.org, inner, sizeof r.org);
                expect_odd("star bipyramid, from inside: odd", &s, &r, (enum face_mode)mode);
            }
        }
    }
}

/* -------------------------------------------------------------- fans */

/* n wedges around a shared vertex o: wedge i is the planar quadrilateral
 * o, p_i, q_i, p_{i+1} with q_i = o + a (p_i - o) + a (p_{i+1} - o): a = 3/4
 * is a convex wedge, a = 1/4 a concave one (reflex at q_i), a = 0 leaves the
 * triangle o, p_i, p_{i+1}. Counter-clockwise seen from above (or all
 * clockwise with reversed = 1). Heights vary so the fan is not flat. */
static void fan_make(int n, double a, int reversed, const double o[3], surface *s,
                     double ring[8][3])
{
    /* Integer points in counter-clockwise order around o, each wedge under
     * 180 degrees. */
    static const double dirs[8][8][2] = {
        { { 0 } }, { { 0 } }, { { 0 } },
        { { 8, 0 }, { -4, 7 }, { -4, -7 } },
        { { 8, 1 }, { -1, 8 }, { -8, -1 }, { 1, -8 } },
        { { 8, 0 }, { 2, 8 }, { -6, 5 }, { -6, -5 }, { 3, -8 } },
        { { 8, 0 }, { 4, 7 }, { -4, 7 }, { -8, 0 }, { -4, -7 }, { 4, -7 } },
        { { 8, 0 }, { 5, 6 }, { -2, 8 }, { -7, 3 }, { -7, -3 }, { -2, -8 }, { 5, -6 } },
    };
    static const double dirs8[8][2] = { { 8, 0 }, { 6, 6 }, { 0, 8 }, { -5, 6 },
                                        { -8, 0 }, { -6, -6 }, { 0, -8 }, { 6, -5 } };
    for (int i = 0; i < n; i++) {
        const double *d = n == 8 ? dirs8[i] : dirs[n][i];
        ring[i][0] = o[0] + d[0];
        ring[i][1] = o[1] + d[1];
        ring[i][2] = o[2] + (double)((i * 5) % 3 - 1) * 1.5;
    }
    s->faces = 0;
    s->start[0] = 0;
    for (int i = 0; i < n; i++) {
        const double *p = ring[i], *q = ring[(i + 1) % n];
        double mid[3];
        for (int k = 0; k < 3; k++)
            mid[k] = o[k] + a * (p[k] - o[k]) + a * (q[k] - o[k]);
        const double *quad[4] = { o, p, mid, q };
        const double *quad_r[4] = { q, mid, p, o };
        const double *tri[3] = { o, p, q };
        const double *tri_r[3] = { q, p, o };
        if (a == 0.0)
            surface_add_face(s, reversed ? tri_r : tri, 3);
        else
            surface_add_face(s, reversed ? quad_r : quad, 4);
    }
}

static void test_fans(void)
{
    static const double o[3] = { 0.5, -0.25, 1.0 };
    static const double offsets[5][2] = { { 0, 0 }, { 0.5, 0 }, { -1.25, 0.75 },
                                          { 3, -2 }, { 0.0625, 2.5 } };
    static const double wedge_a[3] = { 0.0, 0.75, 0.25 };
    for (int n = 3; n <= 8; n++) {
        for (int ai = 0; ai < 3; ai++) {
            for (int reversed = 0; reversed < 2; reversed++) {
                surface s;
                double ring[8][3];
                fan_make(n, wedge_a[ai], reversed, o, &s, ring);
                /* Targets: the shared vertex, and points at 1/2 and 1/4 of
                 * every shared edge o-p_i. */
                double targets[17][3];
                int nt = 0;
                memcpy(targets[nt++], o, sizeof targets[0]);
                for (int i = 0; i < n; i++)
                    for (int f = 1; f <= 2; f++) {
                        double frac = f == 1 ? 0.5 : 0.25;
                        for (int k = 0; k < 3; k++)
                            targets[nt][k] = o[k] + frac * (ring[i][k] - o[k]);
                        nt++;
                    }
                for (int ti = 0; ti < nt; ti++)
                    for (int oi = 0; oi < 5; oi++)
                        for (int side = -1; side <= 1; side += 2) {
                            double org[3] = { targets[ti][0] + offsets[oi][0],
                                              targets[ti][1] + offsets[oi][1],
                                              targets[ti][2] + 16.0 * side };
                            for (int mode = 0; mode < MODES; mode++) {
                                isect_ray r = ray_toward(org, targets[ti], 1.0, 0.0);
                                expect_exactly("fan, through shared vertex/edge: 1 hit", &s,
                                               &r, (enum face_mode)mode, 1);
                            }
                        }
            }
        }
    }
}

/* ------------------------------------------------------- 2D tilings */

/* The N x N grid of unit squares (or of triangles, each square cut along
 * alternating diagonals) mapped by x -> M x + t. M integer, so corners are
 * exact; tiles alternate between counter-clockwise and clockwise when
 * mixed_orientation is set. Every query point u in the open square (0, N)^2
 * on a quarter-integer lattice (corners, edge points, interior points) and
 * a set of generic points must be inside exactly one tile, by both rules,
 * with |winding| 1 there and 0 elsewhere. */
#define GRID 4
typedef struct tiling {
    int    tiles;
    int    corners[2 * GRID * GRID];
    double poly[2 * GRID * GRID][4][2];
} tiling;

static void tiling_map(const double m[2][2], const double t[2], double scale, double u,
                       double v, double out[2])
{
    out[0] = t[0] + scale * (m[0][0] * u + m[0][1] * v);
    out[1] = t[1] + scale * (m[1][0] * u + m[1][1] * v);
}

static void tiling_make(tiling *tl, int triangles, int mixed_orientation, const double m[2][2],
                        const double t[2], double scale)
{
    tl->tiles = 0;
    for (int i = 0; i < GRID; i++)
        for (int j = 0; j < GRID; j++) {
            double c[4][2];
            tiling_map(m, t, scale, i, j, c[0]);
            tiling_map(m, t, scale, i + 1, j, c[1]);
            tiling_map(m, t, scale, i + 1, j + 1, c[2]);
            tiling_map(m, t, scale, i, j + 1, c[3]);
            int pieces[2][4], sizes[2], count;
            if (!triangles) {
                count = 1;
                sizes[0] = 4;
                for (int k = 0; k < 4; k++)
                    pieces[0][k] = k;
            } else if ((i + j) % 2 == 0) { /* diagonal c0-c2 */
                count = 2;
                sizes[0] = sizes[1] = 3;
                int a[4] = { 0, 1, 2, -1 }, b[4] = { 0, 2, 3, -1 };
                memcpy(pieces[0], a, sizeof a);
                memcpy(pieces[1], b, sizeof b);
            } else {                       /* diagonal c1-c3 */
                count = 2;
                sizes[0] = sizes[1] = 3;
                int a[4] = { 0, 1, 3, -1 }, b[4] = { 1, 2, 3, -1 };
                memcpy(pieces[0], a, sizeof a);
                memcpy(pieces[1], b, sizeof b);
            }
            for (int p = 0; p < count; p++) {
                int reverse = mixed_orientation && (tl->tiles % 2 == 1);
                int n = sizes[p];
                for (int k = 0; k < n; k++) {
                    int src = pieces[p][reverse ? n - 1 - k : k];
                    tl->poly[tl->tiles][k][0] = c[src][0];
                    tl->poly[tl->tiles][k][1] = c[src][1];
                }
                tl->corners[tl->tiles] = n;
                tl->tiles++;
            }
        }
}

static void expect_one_tile(const tiling *tl, const double q[2], int *failures)
{
    int even_odd = 0, nonzero = 0, winding_ones = 0, winding_other = 0, errors = 0;
    for (int i = 0; i < tl->tiles; i++) {
        const double *poly = &tl->poly[i][0][0];
        int n = tl->corners[i];
        int eo = isect_point_in_polygon2(poly, n, q, ISECT_EVEN_ODD);
        int nz = isect_point_in_polygon2(poly, n, q, ISECT_NONZERO);
        int32_t w = 99;
        int st = isect_winding_number2(poly, n, q, &w);
        if (eo < 0 || nz < 0 || st != ISECT_OK) {
            errors++;
            continue;
        }
        even_odd += eo;
        nonzero += nz;
        if (w == 1 || w == -1)
            winding_ones++;
        else if (w != 0)
            winding_other++;
        if ((w != 0) != (eo == 1) || (w != 0) != (nz == 1))
            errors++;
    }
    int ok = errors == 0 && even_odd == 1 && nonzero == 1 && winding_ones == 1
          && winding_other == 0;
    if (!ok) {
        if (*failures < 5)
            fprintf(stderr, "    point (%.17g, %.17g): even-odd in %d tiles, nonzero in %d, "
                            "|winding| 1 in %d, errors %d\n",
                    q[0], q[1], even_odd, nonzero, winding_ones, errors);
        (*failures)++;
    }
}

static void test_tilings(void)
{
    static const double maps[5][2][2] = {
        { { 1, 0 }, { 0, 1 } },
        { { 0, -1 }, { 1, 0 } },  /* rotated 90 degrees */
        { { 3, -4 }, { 4, 3 } },  /* rotated by atan(4/3), scaled by 5 */
        { { 2, 1 }, { 1, 3 } },   /* sheared */
        { { -1, 0 }, { 0, 1 } }   /* mirrored: tiles clockwise */
    };
    static const double shifts[3][2] = { { 0, 0 }, { 0.375, -1.25 }, { 0x1p40, -0x1p38 } };
    static const double scales[2] = { 1.0, 0x1p-30 };
    lcg g = { 4242 };
    for (int triangles = 0; triangles < 2; triangles++)
        for (int mixed = 0; mixed < 2; mixed++)
            for (int mi = 0; mi < 5; mi++)
                for (int si = 0; si < 3; si++)
                    for (int sc = 0; sc < 2; sc++) {
                        if (si == 2 && sc == 1)
                            continue; /* 2^40 + 2^-30 k is not a double */
                        tiling tl;
                        tiling_make(&tl, triangles, mixed, maps[mi], shifts[si], scales[sc]);
                        int failures = 0, points = 0;
                        /* Quarter lattice strictly inside the grid. */
                        for (int iu = 1; iu < 4 * GRID; iu++)
                            for (int iv = 1; iv < 4 * GRID; iv++) {
                                double q[2];
                                tiling_map(maps[mi], shifts[si], scales[sc], iu * 0.25,
                                           iv * 0.25, q);
                                expect_one_tile(&tl, q, &failures);
                                points++;
                            }
                        /* Generic points (not on any edge in general) and
                         * points at non-dyadic fractions of edges. */
                        for (int k = 0; k < 60; k++) {
                            double u = GRID * 0.5 * (1.0 + 0.98 * lcg_uniform(&g));
                            double v = k % 2 ? (double)(1 + k % (GRID - 1))
                                             : GRID * 0.5 * (1.0 + 0.98 * lcg_uniform(&g));
                            if (k % 3 == 0)
                                u = 1.0 / 3.0 + (k % GRID == 0 ? 1 : k % GRID);
                            double q[2];
                            tiling_map(maps[mi], shifts[si], scales[sc], u, v, q);
                            expect_one_tile(&tl, q, &failures);
                            points++;
                        }
                        check_record(failures == 0, __FILE__, __LINE__,
                                     "tiling: every point in exactly one tile");
                        CHECK(points > 200);
                    }
}

/* Batch calls give the single-call answers, point for point. */
static void test_tiling_batch_agrees(void)
{
    static const double m[2][2] = { { 3, -4 }, { 4, 3 } }, t[2] = { 0.375, -1.25 };
    tiling tl;
    tiling_make(&tl, 1, 1, m, t, 1.0);
    double pts[225][2];
    int np = 0;
    for (int iu = 1; iu < 16; iu++)
        for (int iv = 1; iv < 16; iv++)
            tiling_map(m, t, 1.0, iu * 0.25, iv * 0.25, pts[np++]);
    int64_t total_inside = 0;
    for (int i = 0; i < tl.tiles; i++) {
        const double *poly = &tl.poly[i][0][0];
        int n = tl.corners[i];
        uint8_t inside[225];
        int32_t winding[225];
        int64_t ins = isect_point_in_polygon2_batch(poly, n, &pts[0][0], np, ISECT_EVEN_ODD,
                                                    inside);
        int64_t nz = isect_winding_number2_batch(poly, n, &pts[0][0], np, winding);
        CHECK(ins >= 0);
        CHECK_EQ_INT(ins, nz);
        int mismatches = 0;
        for (int k = 0; k < np; k++) {
            int32_t w;
            isect_winding_number2(poly, n, pts[k], &w);
            mismatches += winding[k] != w
                       || inside[k] != isect_point_in_polygon2(poly, n, pts[k], ISECT_EVEN_ODD);
        }
        CHECK_EQ_INT(mismatches, 0);
        total_inside += ins;
    }
    CHECK_EQ_INT(total_inside, np); /* each point in exactly one tile */
}


/* ------------------------------------------------ exact signs, known answers */

/* The half-open rule on the unit square, by the documented perturbation
 * (-e^2, -e): points on the bottom and left edges (and the corners (0,0),
 * (1,0), (0,1)) are outside, points on the top and right edges and the
 * corner (1,1) inside; same for rays along +-z through the square in 3D. */
static void test_half_open_rule(void)
{
    static const double square2[8] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    static const double square3[12] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
    static const struct { double x, y; int inside; } cases[] = {
        { 0.5, 0, 0 }, { 0, 0.5, 0 }, { 0.5, 1, 1 }, { 1, 0.5, 1 },
        { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 1 }, { 0.5, 0.5, 1 },
        { 0x1p-60, 0.5, 1 }, { -0x1p-60, 0.5, 0 }, { 0.5, 1 + 0x1p-52, 0 }
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double q[2] = { cases[i].x, cases[i].y };
        CHECK_EQ_INT(isect_point_in_polygon2(square2, 4, q, ISECT_EVEN_ODD), cases[i].inside);
        CHECK_EQ_INT(isect_point_in_polygon2(square2, 4, q, ISECT_NONZERO), cases[i].inside);
        for (int up = 0; up < 2; up++) {
            isect_ray r = { { q[0], q[1], up ? -1.0 : 1.0 }, { 0, 0, up ? 1.0 : -1.0 },
                            0.0, INFINITY };
            CHECK_EQ_INT(isect_ray_polygon(&r, square3, 4, ISECT_EVEN_ODD, NULL, NULL, 0),
                         cases[i].inside);
            int tri = isect_ray_triangle(&r, square3, square3 + 3, square3 + 6, NULL, NULL, 0)
                    + isect_ray_triangle(&r, square3, square3 + 6, square3 + 9, NULL, NULL, 0);
            CHECK_EQ_INT(tri, cases[i].inside);
        }
    }
}

/* Points within a few ulps of a line through two full-precision points,
 * where a plain floating-point determinant gets the sign wrong: the line
 * y = m x (m a power of two, so points (t, m t) lie on it exactly) and the
 * triangle above it; a point j ulps above the line is inside iff j > 0
 * (j == 0: on the line, perturbed downwards, outside). */
static void test_exact_signs_2d(void)
{
    static const double slopes[4] = { 1.0, 2.0, 0.5, -4.0 };
    lcg g = { 99 };
    int wrong = 0, total = 0;
    for (int si = 0; si < 4; si++) {
        double m = slopes[si];
        for (int trial = 0; trial < 200; trial++) {
            double t1 = -1.0 - 3.0 * (1.0 + lcg_uniform(&g));
            double t2 = 1.0 + 3.0 * (1.0 + lcg_uniform(&g));
            /* The triangle above y = m x, counter-clockwise: the third
             * corner is (t1, m t2) for m > 0 and (t2, m t1) for m < 0. */
            double tri[6] = { t1, m * t1, t2, m * t2, 0, 0 };
            if (m > 0) {
                tri[4] = t1;
                tri[5] = m * t2;
            } else {
                tri[4] = t2;
                tri[5] = m * t1;
            }
            double s = 0.8 * lcg_uniform(&g);
            double ys = m * s;
            double ulp = nextafter(ys, INFINITY) - ys;
            for (int j = -3; j <= 3; j++) {
                double q[2] = { s, ys + j * ulp };
                int want = j > 0;
                int eo = isect_point_in_polygon2(tri, 3, q, ISECT_EVEN_ODD);
                int32_t w = 0;
                isect_winding_number2(tri, 3, q, &w);
                wrong += eo != want || w != want; /* counter-clockwise: winding 1 */
                total++;
            }
        }
    }
    check_record(wrong == 0, __FILE__, __LINE__, "near-collinear 2D points: exact side");
    CHECK_EQ_INT(total, 4 * 200 * 7);
}

/* The same in 3D with the ray along +z from below the origin: the sheared
 * frame is then the identity on (x, y), so the projected vertices are the
 * input exactly and the answer is known. The edge p1 -> p2 passes within a
 * few ulps of the origin: p1 = (t1, m t1 + j1 ulp), p2 = (t2, m t2 + j2 ulp)
 * with t1 < 0 < t2, so orient(p1, p2, 0) = t1 j2 ulp2 - j1 ulp1 t2: negative
 * when j1, j2 >= 0 (not both 0), positive when both <= 0, and on the line
 * for j1 = j2 = 0 (perturbed: sign(t1 - t2) < 0). The triangle above the
 * edge contains the origin iff orient > 0; its mirror image below shares
 * the edge, and exactly one of the two is hit. */
static void test_exact_signs_3d(void)
{
    lcg g = { 2024 };
    int wrong = 0, total = 0;
    for (int trial = 0; trial < 300; trial++) {
        double m = trial % 2 ? 1.0 : 0.5;
        double t1 = -0.5 - (1.0 + lcg_uniform(&g));
        double t2 = 0.5 + 2.0 * (1.0 + lcg_uniform(&g));
        double y1 = m * t1, y2 = m * t2;
        double u1 = nextafter(y1, INFINITY) - y1, u2 = nextafter(y2, INFINITY) - y2;
        for (int j1 = -2; j1 <= 2; j1++)
            for (int j2 = -2; j2 <= 2; j2++) {
                if ((j1 > 0 && j2 < 0) || (j1 < 0 && j2 > 0))
                    continue; /* sign not known without exact arithmetic */
                double p1[3] = { t1, y1 + j1 * u1, 0 }, p2[3] = { t2, y2 + j2 * u2, 0 };
                double above[3] = { t1, y2, 0 }, below[3] = { t2, y1, 0 };
                int want_above = j1 <= 0 && j2 <= 0 && (j1 != 0 || j2 != 0);
                isect_ray r = { { 0, 0, -1 }, { 0, 0, 1 }, 0.0, INFINITY };
                int a = isect_ray_triangle(&r, p1, p2, above, NULL, NULL, 0);
                int b = isect_ray_triangle(&r, p2, p1, below, NULL, NULL, 0);
                double quad_above[9] = { p1[0], p1[1], 0, p2[0], p2[1], 0, t1, y2, 0 };
                int pa = isect_ray_polygon(&r, quad_above, 3, ISECT_NONZERO, NULL, NULL, 0);
                wrong += a != want_above || b != !want_above || pa != want_above;
                total++;
            }
    }
    check_record(wrong == 0, __FILE__, __LINE__, "near-degenerate 3D edges: exact side");
    CHECK(total > 3000);
}

int main(void)
{
    test_half_open_rule();
    test_exact_signs_2d();
    test_exact_signs_3d();
    test_octahedron_from_inside();
    test_octahedron_from_outside();
    test_octahedron_grazing();
    test_octahedron_generic();
    test_star_bipyramid();
    test_fans();
    test_tilings();
    test_tiling_batch_agrees();
    return check_summary();
}
