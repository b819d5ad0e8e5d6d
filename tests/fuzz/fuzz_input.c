/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_input.c — the byte layout of the harnesses' inputs; see fuzz_input.h.
 */
#include "fuzz_input.h"

#include "fuzz_checks.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* FUZZ_VERBOSE=1 in the environment prints every decoded input to stderr,
 * so a crash file can be read as the call it made (hex floats: exact). */
static int verbose(void)
{
    static int v = -1;
    if (v < 0)
        v = getenv("FUZZ_VERBOSE") != NULL;
    return v;
}

static void print_doubles(const char *what, const double *v, size_t n)
{
    size_t i;
    fprintf(stderr, "%s", what);
    for (i = 0; i < n; i++)
        fprintf(stderr, " %a", v[i]);
    fputc('\n', stderr);
}

void fuzz_input_init(fuzz_input *in, const uint8_t *data, size_t size)
{
    in->data = data;
    in->size = size;
    in->pos = 0;
}

int fuzz_exhausted(const fuzz_input *in)
{
    return in->pos >= in->size;
}

uint8_t fuzz_u8(fuzz_input *in)
{
    return in->pos < in->size ? in->data[in->pos++] : 0;
}

int32_t fuzz_i32(fuzz_input *in)
{
    uint32_t u = 0;
    int i;
    for (i = 0; i < 4; i++)
        u |= (uint32_t)fuzz_u8(in) << (8 * i);
    /* memcpy, not a cast: the conversion of a large uint32_t to int32_t is
     * implementation-defined. */
    {
        int32_t v;
        memcpy(&v, &u, sizeof v);
        return v;
    }
}

double fuzz_bits_double(fuzz_input *in)
{
    uint64_t u = 0;
    double d;
    int i;
    for (i = 0; i < 8; i++)
        u |= (uint64_t)fuzz_u8(in) << (8 * i);
    memcpy(&d, &u, sizeof d);
    return d;
}

/* The values where floating-point code usually breaks. */
static double special_value(unsigned k)
{
    static const double table[16] = {
        0.0, -0.0, INFINITY, -INFINITY, NAN, DBL_MAX, -DBL_MAX, DBL_MIN,
        0x1p-1074, -0x1p-1074, 1.0, -1.0, 0.5, 1e-300, 1e300, DBL_EPSILON
    };
    return table[k % 16];
}

double fuzz_double(fuzz_input *in)
{
    uint8_t tag = fuzz_u8(in);
    switch (tag % 4) {
    case 0:
        return fuzz_bits_double(in);
    case 1:
        return (double)(int8_t)fuzz_u8(in) / 4.0;
    case 2:
        return special_value((unsigned)tag / 4);
    default: {
        double m = (double)(int8_t)fuzz_u8(in);
        int e = 8 * (int)(int8_t)fuzz_u8(in);
        return ldexp(m, e);
    }
    }
}

void fuzz_doubles(fuzz_input *in, double *out, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        out[i] = fuzz_double(in);
}

size_t fuzz_shape_data_count(int32_t type, int32_t n)
{
    switch (type) {
    case ISECT_PLANE:
    case ISECT_SPHERE:
        return 4;
    case ISECT_AABB:
    case ISECT_ELLIPSOID:
        return 6;
    case ISECT_TRIANGLE:
        return 9;
    case ISECT_POLYGON:
        return n > 0 ? 3 * (size_t)n : 0;
    case ISECT_CONVEX:
        return n > 0 ? 4 * (size_t)n : 0;
    case ISECT_CYLINDER:
    case ISECT_CYLINDER_INF:
        return 7;
    case ISECT_QUADRIC:
        return 10;
    default:
        return 0;
    }
}

/* Control byte bits of a shape; the rarer error cases need two bits set, so
 * random mutations leave most descriptors well formed. */
#define CTRL_XFORM       0x01
#define CTRL_XFORM_ROW3  0x02
#define CTRL_NULL_DATA   0x84
#define CTRL_WRONG_MESH  0x18
#define CTRL_RESERVED    0x60

void fuzz_take_shape(fuzz_input *in, fuzz_shape *s, const isect_mesh *mesh)
{
    uint8_t b;
    uint8_t ctrl;
    size_t count;
    int32_t type, n = 0, flags;

    memset(s, 0, sizeof *s);
    s->xform_status = 1;

    /* type: 0..15 covers every type, the invalid 0 and a few unknown ones;
     * 0xFF reads a raw 32-bit type. */
    b = fuzz_u8(in);
    type = b == 0xFF ? fuzz_i32(in) : (int32_t)(b % 16);
    /* n: a small count for the types that have one, 0 for the others;
     * bytes >= 0x80 give negative and raw values for every type. */
    b = fuzz_u8(in);
    if (b < 0x80)
        n = (type == ISECT_POLYGON || type == ISECT_CONVEX) ? (int32_t)(b % 24) : 0;
    else if (b == 0xFF)
        n = fuzz_i32(in);
    else
        n = (int32_t)(int8_t)b;
    /* flags: the valid 0 / 1 mostly, any value from bytes >= 0x80. */
    b = fuzz_u8(in);
    flags = b < 0x80 ? (int32_t)(b & 1) : (int32_t)(int8_t)b;
    ctrl = fuzz_u8(in);

    s->desc.type = type;
    s->desc.n = n;
    s->desc.flags = flags;
    s->desc.reserved = (ctrl & CTRL_RESERVED) == CTRL_RESERVED ? 1 : 0;
    /* Counts beyond what the fuzzer can fill are capped: the library must
     * reject or read exactly the documented layout, and a polygon of 127
     * vertices is as good a test as one of 10^9. */
    count = (n >= 0 && n <= 127) ? fuzz_shape_data_count(type, n) : 0;
    if (count > 0) {
        s->data = malloc(count * sizeof *s->data);
        if (s->data == NULL)
            abort();
        fuzz_doubles(in, s->data, count);
    }
    s->desc.data = (ctrl & CTRL_NULL_DATA) == CTRL_NULL_DATA ? NULL : s->data;
    if (type == ISECT_MESH)
        s->desc.mesh = (ctrl & CTRL_WRONG_MESH) == CTRL_WRONG_MESH ? NULL : mesh;
    else
        s->desc.mesh = (ctrl & CTRL_WRONG_MESH) == CTRL_WRONG_MESH ? mesh : NULL;

    if (ctrl & CTRL_XFORM) {
        double m[16] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1 };
        fuzz_doubles(in, m, (ctrl & CTRL_XFORM_ROW3) ? 16 : 12);
        s->xform_status = isect_xform_init(&s->xform, m);
        /* An xform that init rejected is not a valid argument; the shape
         * keeps no transform then, and the harness checks init's status. */
        if (s->xform_status == ISECT_OK)
            s->desc.xform = &s->xform;
        if (verbose()) {
            fprintf(stderr, "xform init status %d\n", s->xform_status);
            print_doubles("xform", m, 16);
        }
    }
    if (verbose()) {
        fprintf(stderr, "shape type %d n %d flags %d reserved %d data %s mesh %s\n",
                (int)type, (int)n, (int)flags, (int)s->desc.reserved,
                s->desc.data ? "set" : "NULL", s->desc.mesh ? "set" : "NULL");
        if (s->data != NULL)
            print_doubles("data", s->data, count);
    }
}

void fuzz_shape_free(fuzz_shape *s)
{
    free(s->data);
    s->data = NULL;
}

int fuzz_shape_wide(const fuzz_shape *s, const isect_ray *rays, int n)
{
    return fuzz_shape_wide_with(s, rays, n, NULL, 0);
}

int fuzz_shape_wide_with(const fuzz_shape *s, const isect_ray *rays, int n, const double *extra,
                         size_t nextra)
{
    fuzz_range r;
    int i;
    fuzz_range_init(&r);
    fuzz_range_add(&r, extra, nextra);
    if (s->data != NULL)
        fuzz_range_add(&r, s->data, fuzz_shape_data_count(s->desc.type, s->desc.n));
    if (s->desc.xform != NULL)
        fuzz_range_add(&r, s->xform.m, 16);
    for (i = 0; i < n; i++) {
        fuzz_range_add(&r, rays[i].org, 3);
        fuzz_range_add(&r, rays[i].dir, 3);
    }
    return fuzz_range_wide(&r);
}

isect_opts *fuzz_take_opts(fuzz_input *in, uint32_t *effective_flags)
{
    /* Sizes: the full struct mostly; then the sizes that cover the flags but
     * not eps, nothing, or more than the struct (a newer caller). */
    static const uint32_t sizes[8] = { 16, 16, 16, 8, 12, 4, 0, 64 };
    uint8_t sel = fuzz_u8(in);
    uint8_t fb;
    isect_opts full;
    isect_opts *opts;
    size_t bytes;

    *effective_flags = 0;
    if (sel % 4 == 0) {
        if (verbose())
            fprintf(stderr, "opts NULL\n");
        return NULL;
    }
    full.size = sizes[(sel / 4) % 8];
    fb = fuzz_u8(in);
    /* Known flags mostly; bytes >= 0x80 give unknown bits too. */
    full.flags = fb < 0x80 ? (uint32_t)(fb & (ISECT_CULL_BACK | ISECT_ANY_HIT)) : (uint32_t)fb;
    full.eps = fuzz_double(in);
    bytes = full.size < sizeof full.size ? sizeof full.size : full.size;
    if (bytes > sizeof full)
        bytes = sizeof full;
    opts = malloc(bytes);
    if (opts == NULL)
        abort();
    memcpy(opts, &full, bytes);
    if (full.size >= offsetof(isect_opts, eps))
        *effective_flags = full.flags;
    if (verbose())
        fprintf(stderr, "opts size %u flags %#x eps %a\n", (unsigned)full.size,
                (unsigned)full.flags, full.eps);
    return opts;
}

void fuzz_take_ray(fuzz_input *in, isect_ray *ray)
{
    uint8_t interval;
    fuzz_doubles(in, ray->org, 3);
    fuzz_doubles(in, ray->dir, 3);
    interval = fuzz_u8(in);
    switch (interval % 4) {
    case 0:
        ray->tmin = 0.0;
        ray->tmax = INFINITY;
        break;
    case 1:
        ray->tmin = -INFINITY;
        ray->tmax = INFINITY;
        break;
    case 2:
        ray->tmin = fuzz_double(in);
        ray->tmax = INFINITY;
        break;
    default:
        ray->tmin = fuzz_double(in);
        ray->tmax = fuzz_double(in);
        break;
    }
    if (verbose()) {
        print_doubles("ray org", ray->org, 3);
        print_doubles("ray dir", ray->dir, 3);
        fprintf(stderr, "ray tmin %a tmax %a\n", ray->tmin, ray->tmax);
    }
}
