/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_winding.c — libFuzzer harness: isect_winding_number_batch and the
 * mesh containment rules on fuzzed meshes and points.
 *
 * Input (fuzz_input.h): a mode byte (the mesh: a triangle soup of fuzzed
 * vertices and indices, or an octahedron — closed, with one face removed,
 * or turned inside out — whose vertices are the unit axis points times 2
 * plus fuzzed offsets; and a transform: none, a mirror, or a scaling by a
 * power of two), the vertex numbers, the faces, an accuracy choice, then
 * points (fuzzed, or exactly at a vertex, or at an edge's midpoint).
 *
 * Asserted, from isect.h only:
 *  - documented statuses; nothing written on error; E_ARG exactly for a
 *    negative or NaN accuracy;
 *  - w[i] is NaN exactly for a non-finite point;
 *  - a batch of fewer than 8 points is the one-point calls bit for bit (the
 *    cluster sums start at 8);
 *  - a mirroring transform negates w and a power-of-two scaling keeps it,
 *    exactly, at the world images of the same object-space points;
 *  - accuracy > 0 stays within accuracy of accuracy 0 (for problems
 *    spanning at most 2^40, where both are far more accurate than that);
 *  - a closed, consistently oriented mesh (isect_mesh_check) gives, at a
 *    point clearly off every face's plane, an integer, the same at every
 *    accuracy and in every call, and the containment rules agree with it:
 *    even-odd with its parity, nonzero with w != 0, winding with w >= 1;
 *  - |w| <= faces / 2 (each face's solid angle is at most 2 pi).
 * The checks of values (not of statuses and NaN) skip problems spanning
 * more than 2^FUZZ_MAX_SPREAD, as the other harnesses do.
 */
#include "fuzz_checks.h"
#include "fuzz_input.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_V 12
#define MAX_F 12
#define MAX_P 12

/* The octahedron's faces, outward by the right-hand rule: vertex 2a is
 * +axis a, 2a+1 is -axis a; face (sx, sy, sz) joins the x, y and z
 * vertices of those signs, ordered x, y, z when the signs' product is
 * positive and reversed otherwise. */
static int octahedron(int32_t faces[8][3], int inside_out)
{
    for (int f = 0; f < 8; f++) {
        int sx = f & 1, sy = (f >> 1) & 1, sz = (f >> 2) & 1;
        int32_t x = sx, y = 2 + sy, z = 4 + sz;
        int flip = ((sx + sy + sz) & 1) ^ inside_out;
        faces[f][0] = x;
        faces[f][1] = flip ? z : y;
        faces[f][2] = flip ? y : z;
    }
    return 8;
}

/* 1 when p is off the plane of triangle abc by far more than a double
 * evaluation of its orientation can be wrong (a margin of 2^-40 of the
 * products' magnitude against an error of a few u of it). */
static int clearly_off_plane(const double *a, const double *b, const double *c, const double *p)
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = p[k] - a[k];
    }
    double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0] };
    double mag = 0.0;
    for (int k = 0; k < 3; k++)
        mag += (fabs(u[(k + 1) % 3] * v[(k + 2) % 3]) + fabs(u[(k + 2) % 3] * v[(k + 1) % 3]))
             * fabs(w[k]);
    double det = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
    return isfinite(mag) && fabs(det) > 0x1p-40 * mag;
}

static int winding(const isect_shape *s, const double *p, int n, double accuracy, double *w)
{
    fuzz_canary_fill(w, (size_t)n * sizeof *w);
    int st = isect_winding_number_batch(s, p, n, accuracy, w);
    fuzz_require_status(st, FUZZ_ALLOW_ARG | FUZZ_ALLOW_NOMEM, "isect_winding_number_batch");
    int accuracy_ok = accuracy >= 0.0;
    FUZZ_REQUIRE((st == ISECT_E_ARG) == !accuracy_ok, "accuracy %a: status %d", accuracy, st);
    if (st < 0)
        FUZZ_REQUIRE(fuzz_canary_intact(w, (size_t)n * sizeof *w),
                     "isect_winding_number_batch wrote w and returned %d", st);
    return st;
}

static int all_finite3(const double *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in;
    double verts[MAX_V * 3], pts[MAX_P * 3], w[MAX_P], w0[MAX_P], one, wx[MAX_P];
    int32_t faces[MAX_F][3];
    int nv, nf, np, closed_kind;
    isect_mesh *mesh = NULL;
    isect_mesh_report rep;

    fuzz_input_init(&in, data, size);
    uint8_t mode = fuzz_u8(&in);
    int kind = mode & 3, xform_kind = (mode >> 2) % 3;
    if (kind == 0) {
        nv = 3 + fuzz_u8(&in) % (MAX_V - 2);
        fuzz_doubles(&in, verts, (size_t)nv * 3);
        nf = 1 + fuzz_u8(&in) % MAX_F;
        for (int f = 0; f < nf; f++)
            for (int k = 0; k < 3; k++)
                faces[f][k] = fuzz_u8(&in) % nv;
    } else {
        nv = 6;
        for (int i = 0; i < nv; i++)
            for (int k = 0; k < 3; k++)
                verts[3 * i + k] = (k == i / 2 ? (i & 1 ? -2.0 : 2.0) : 0.0) + fuzz_double(&in);
        nf = octahedron(faces, kind == 3);
        if (kind == 2) {
            int drop = fuzz_u8(&in) % 8;
            memmove(faces[drop], faces[drop + 1], (size_t)(7 - drop) * sizeof faces[0]);
            nf = 7;
        }
    }
    closed_kind = kind != 0 && kind != 2;
    int st = isect_mesh_create(verts, nv, &faces[0][0], NULL, nf, &mesh);
    fuzz_require_status(st, FUZZ_ALLOW_NONFINITE | FUZZ_ALLOW_NOMEM | FUZZ_ALLOW_ARG,
                        "isect_mesh_create");
    if (st < 0)
        return 0;
    st = isect_mesh_check(mesh, &rep);
    fuzz_require_status(st, FUZZ_ALLOW_NOMEM, "isect_mesh_check");
    int exact_integers = st == ISECT_OK && rep.closed && rep.oriented;
    if (closed_kind && st == ISECT_OK)
        FUZZ_REQUIRE(rep.closed && rep.oriented, "the octahedron is not closed and oriented");

    static const double accuracies[4] = { 0.0, 1e-3, 0.25, 0.0 };
    uint8_t acc_sel = fuzz_u8(&in);
    double accuracy = acc_sel % 5 < 4 ? accuracies[acc_sel % 5] : fuzz_double(&in);

    np = 1 + fuzz_u8(&in) % MAX_P;
    for (int i = 0; i < np; i++) {
        uint8_t how = fuzz_u8(&in);
        double *p = pts + 3 * i;
        const double *a = verts + 3 * (how / 4 % nv), *b = verts + 3 * (how / 32 % nv);
        if (how % 4 == 1) {
            memcpy(p, a, 3 * sizeof *p);
        } else if (how % 4 == 2) {
            for (int k = 0; k < 3; k++)
                p[k] = 0.5 * a[k] + 0.5 * b[k];
        } else {
            fuzz_doubles(&in, p, 3);
        }
    }
    fuzz_range range;
    fuzz_range_init(&range);
    fuzz_range_add(&range, verts, (size_t)nv * 3);
    fuzz_range_add(&range, pts, (size_t)np * 3);
    int wide = fuzz_range_wide(&range);

    isect_shape shape = { ISECT_MESH, 0, ISECT_EVEN_ODD, 0, NULL, mesh, NULL };
    if (winding(&shape, pts, np, 0.0, w0) < 0)
        goto done;
    if (getenv("FUZZ_VERBOSE") != NULL) {
        fprintf(stderr, "mode %d nv %d nf %d wide %d accuracy %a\n", mode, nv, nf, wide, accuracy);
        for (int i = 0; i < nv; i++)
            fprintf(stderr, "v%d %a %a %a\n", i, verts[3 * i], verts[3 * i + 1], verts[3 * i + 2]);
        for (int f = 0; f < nf; f++)
            fprintf(stderr, "f%d %d %d %d\n", f, (int)faces[f][0], (int)faces[f][1],
                    (int)faces[f][2]);
        for (int i = 0; i < np; i++)
            fprintf(stderr, "p%d %a %a %a: w %a\n", i, pts[3 * i], pts[3 * i + 1], pts[3 * i + 2],
                    w0[i]);
    }
    for (int i = 0; i < np; i++) {
        FUZZ_REQUIRE(isnan(w0[i]) == !all_finite3(pts + 3 * i), "point %d: w %a", i, w0[i]);
        if (!wide && !isnan(w0[i]))
            FUZZ_REQUIRE(fabs(w0[i]) <= 0.5 * nf * (1.0 + 1e-9), "point %d: |w| = %a > faces / 2",
                         i, w0[i]);
    }
    /* below the cluster batch size, each point alone gives the same bits */
    if (np < 8) {
        for (int i = 0; i < np; i++) {
            if (winding(&shape, pts + 3 * i, 1, 0.0, &one) < 0)
                goto done;
            FUZZ_REQUIRE(memcmp(&one, &w0[i], sizeof one) == 0,
                         "point %d: alone %a, in the batch %a", i, one, w0[i]);
        }
    }
    /* accuracy > 0 against accuracy 0: both are within their rounding
     * bounds of the exact value (isect.h), and those bounds stay far below
     * any accuracy asked for only while the faces are not extreme slivers
     * seen from beside them (a triangle 2^200 long passing a point at
     * distance 8 cancels num and den beyond double-double, and the direct
     * sum is then the less accurate of the two): held where vertices and
     * points span at most 2^40 */
    fuzz_range moderate;
    fuzz_range_init(&moderate);
    fuzz_range_add(&moderate, verts, (size_t)nv * 3);
    fuzz_range_add(&moderate, pts, (size_t)np * 3);
    int acc_st = winding(&shape, pts, np, accuracy, w);
    if (acc_st == ISECT_OK && accuracy > 0.0 && !wide
        && (moderate.hi < moderate.lo || (int64_t)moderate.hi - moderate.lo <= 40)) {
        for (int i = 0; i < np; i++)
            if (!isnan(w0[i]))
                FUZZ_REQUIRE(fabs(w[i] - w0[i]) <= accuracy,
                             "point %d: accuracy %a gives %a, direct %a", i, accuracy, w[i], w0[i]);
    }

    /* closed and oriented: integers off the surface, and the rules agree */
    for (int i = 0; exact_integers && !wide && i < np; i++) {
        const double *p = pts + 3 * i;
        int off = all_finite3(p);
        for (int f = 0; f < nf && off; f++)
            off = clearly_off_plane(verts + 3 * faces[f][0], verts + 3 * faces[f][1],
                                    verts + 3 * faces[f][2], p);
        if (!off)
            continue;
        FUZZ_REQUIRE(w0[i] == nearbyint(w0[i]), "point %d off a closed mesh: w = %a", i, w0[i]);
        FUZZ_REQUIRE(acc_st != ISECT_OK || w[i] == w0[i],
                     "point %d: accuracy %a gives %a, not the integer %a", i, accuracy, w[i],
                     w0[i]);
        static const int32_t rules[3] = { ISECT_EVEN_ODD, ISECT_NONZERO, ISECT_WINDING };
        for (int r = 0; r < 3; r++) {
            isect_shape ruled = shape;
            ruled.flags = rules[r];
            int inside = isect_contains(&ruled, p);
            long long wi = (long long)w0[i];
            int want = r == 0 ? (int)(wi & 1) : r == 1 ? wi != 0 : wi >= 1;
            FUZZ_REQUIRE(inside == want, "point %d, w = %lld: rule %d says %d", i, wi,
                         (int)rules[r], inside);
        }
    }

    /* a transform: the world images of the same object-space points */
    if (xform_kind != 0 && !wide) {
        int e = xform_kind == 2 ? (int)(fuzz_u8(&in) % 16) - 8 : 0;
        double s = ldexp(1.0, e);
        double m[16] = { xform_kind == 1 ? -1.0 : s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0,
                         0, 0, 0, 1 };
        isect_xform x;
        FUZZ_REQUIRE(isect_xform_init(&x, m) == ISECT_OK, "a mirror or scaling is singular");
        double world[MAX_P * 3];
        int exact = 1;
        for (int i = 0; i < 3 * np; i++) {
            world[i] = pts[i] * m[5 * (i % 3)];
            exact &= world[i] / m[5 * (i % 3)] == pts[i] || isnan(pts[i]);
        }
        isect_shape placed = shape;
        placed.xform = &x;
        if (exact && winding(&placed, world, np, 0.0, wx) == ISECT_OK) {
            for (int i = 0; i < np; i++) {
                double want = xform_kind == 1 ? -w0[i] : w0[i];
                FUZZ_REQUIRE(wx[i] == want || (isnan(want) && isnan(wx[i])),
                             "point %d: transformed %a, object space %a", i, wx[i], w0[i]);
            }
        }
    }
done:
    isect_mesh_destroy(mesh);
    return 0;
}
