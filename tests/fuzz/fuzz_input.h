/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_input.h — turning a libFuzzer byte string into library inputs.
 *
 * Every harness reads its input through these functions, so the byte layout
 * is defined once and tests/fuzz/make_seeds.py can write seeds in it. Reads
 * past the end give zero bytes: every input, however short, decodes to
 * something, and the fuzzer never wastes executions on rejected inputs.
 *
 * A double is a tag byte and a payload, so that mutations reach the values
 * that matter for this library far more often than raw bit patterns would:
 *   tag % 4 == 0  the next 8 bytes, little-endian IEEE bits (any double;
 *                 the seeds use this form, so they decode bit for bit)
 *   tag % 4 == 1  a small grid value (int8) / 4: exact ties, shared vertices,
 *                 collinear and coplanar points
 *   tag % 4 == 2  a special value chosen by tag / 4: zeros, infinities, NaN,
 *                 DBL_MAX, DBL_MIN, subnormals, ...
 *   tag % 4 == 3  (int8) * 2^(8 * int8): huge and tiny magnitudes
 */
#ifndef ISECT_FUZZ_INPUT_H
#define ISECT_FUZZ_INPUT_H

#include "isect.h"

#include <stddef.h>
#include <stdint.h>

typedef struct fuzz_input {
    const uint8_t *data;
    size_t         size;
    size_t         pos;
} fuzz_input;

void     fuzz_input_init(fuzz_input *in, const uint8_t *data, size_t size);
int      fuzz_exhausted(const fuzz_input *in);
uint8_t  fuzz_u8(fuzz_input *in);
int32_t  fuzz_i32(fuzz_input *in); /* 4 bytes, little-endian */
double   fuzz_bits_double(fuzz_input *in); /* 8 bytes, little-endian IEEE bits */
double   fuzz_double(fuzz_input *in);      /* tagged, see above */
void     fuzz_doubles(fuzz_input *in, double *out, size_t n);

/* The number of doubles the documented data layout of a shape type holds
 * (isect.h, "shape types"), for n vertices or planes; 0 for a type with no
 * data or an unknown type. */
size_t fuzz_shape_data_count(int32_t type, int32_t n);

/* A fuzzed shape descriptor. The data array is allocated with exactly the
 * documented size, so AddressSanitizer reports any read beyond it. */
typedef struct fuzz_shape {
    isect_shape desc;
    double     *data;      /* owned (NULL when the layout is empty) */
    isect_xform xform;     /* desc.xform points here when set */
    int         xform_status; /* isect_xform_init's status, 1 when none was asked */
} fuzz_shape;

/* Layout: type, n, flags, a control byte (reserved field, NULL data, xform
 * wanted, xform's last row fuzzed), the data doubles, then 12 (or 16)
 * transform doubles when a transform is wanted. A mesh type gets `mesh`
 * (may be NULL) as its handle; other types get it only when the control
 * byte asks for a wrong one. */
void fuzz_take_shape(fuzz_input *in, fuzz_shape *s, const isect_mesh *mesh);
void fuzz_shape_free(fuzz_shape *s);

/* 1 when the shape's numbers, its transform and the rays span more than
 * 2^FUZZ_MAX_SPREAD (fuzz_checks.h: the open defects at such ranges). */
int fuzz_shape_wide(const fuzz_shape *s, const isect_ray *rays, int n);
/* The same with nextra more numbers in the range (a mesh's coordinates,
 * which its descriptor does not carry in data). */
int fuzz_shape_wide_with(const fuzz_shape *s, const isect_ray *rays, int n, const double *extra,
                         size_t nextra);

/* Options: NULL, or an isect_opts of a fuzzed size in a heap block of
 * exactly the bytes that size covers (at least the size field, at most the
 * struct), so reading an uncovered field is an ASan report. *effective
 * gets the flags the library should apply (0 for NULL). Free with free(). */
isect_opts *fuzz_take_opts(fuzz_input *in, uint32_t *effective_flags);

/* A ray from 8 tagged doubles; tmin and tmax are first decoded as a choice
 * (0 / -inf / +inf / fuzzed) so the common intervals stay common. */
void fuzz_take_ray(fuzz_input *in, isect_ray *ray);

#endif /* ISECT_FUZZ_INPUT_H */
