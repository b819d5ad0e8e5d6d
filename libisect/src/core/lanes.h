/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lanes.h — LANE_W doubles at once: the one vocabulary the fast kernels
 * (prim/ *_lanes.h) are written in, so each kernel exists once and runs on
 * one ray at a time (the scalar calls, and every build without SIMD), two
 * (SSE2), four (AVX2 + FMA) or eight (AVX-512) rays at once.
 *
 * Include it after defining LANE_ISA to one of the LANE_ISA_* values below
 * (default LANE_ISA_SCALAR). A translation unit includes it once, for one
 * instruction set; the SSE2 / AVX2 / AVX-512 units (api/lanes_*.c) are
 * compiled for their instruction set by a target pragma, and chosen at run
 * time (api/lanes_dispatch.c), so no build flag is needed anywhere.
 *
 * Bit-identical by construction. Every operation below is one IEEE binary64
 * operation per lane, correctly rounded in round-to-nearest — add, sub,
 * mul, div, sqrt — or exact (neg, abs, copysign, min/max as selects,
 * comparisons), and the library is built with -ffp-contract=off, so a
 * kernel computes the same bits in every lane of every instruction set as
 * in the scalar build. The one fused operation, vd_prod_err(x, y, p), is
 * only ever the exact residual x*y - p of p = fl(x*y): an FMA instruction
 * where the CPU has one, else Dekker's TwoProduct where that is exact, else
 * the C library's fma(), which is correctly rounded, so all three agree
 * bit for bit (core/predicates.h: product_error).
 *
 * Semantics the kernels rely on (all instruction sets):
 *   vd_min(a, b) = a < b ? a : b,  vd_max(a, b) = a > b ? a : b
 *       (as minpd/maxpd: the second operand when either is NaN);
 *   comparisons are ordered: false when either operand is NaN;
 *   vd_sel(m, a, b) = m ? a : b lane by lane.
 */
#ifndef ISECT_LANES_H
#define ISECT_LANES_H

#include "core/core.h"
#include "core/predicates.h"

#define LANE_ISA_SCALAR 0
#define LANE_ISA_SSE2   1
#define LANE_ISA_AVX2   2
#define LANE_ISA_AVX512 3

#ifndef LANE_ISA
#define LANE_ISA LANE_ISA_SCALAR
#endif

#if LANE_ISA != LANE_ISA_SCALAR
#include <immintrin.h>
#endif

/* ------------------------------------------------------------- scalar */
#if LANE_ISA == LANE_ISA_SCALAR

#define LANE_W 1
typedef double vd;
typedef int    vm; /* 0 or 1 */

static ALWAYS_INLINE vd vd_set1(double x) { return x; }
static ALWAYS_INLINE vd vd_add(vd a, vd b) { return a + b; }
static ALWAYS_INLINE vd vd_sub(vd a, vd b) { return a - b; }
static ALWAYS_INLINE vd vd_mul(vd a, vd b) { return a * b; }
static ALWAYS_INLINE vd vd_div(vd a, vd b) { return a / b; }
static ALWAYS_INLINE vd vd_sqrt(vd a) { return sqrt(a); }
static ALWAYS_INLINE vd vd_neg(vd a) { return -a; }
static ALWAYS_INLINE vd vd_abs(vd a) { return fabs(a); }
static ALWAYS_INLINE vd vd_min(vd a, vd b) { return a < b ? a : b; }
static ALWAYS_INLINE vd vd_max(vd a, vd b) { return a > b ? a : b; }
static ALWAYS_INLINE vd vd_copysign(vd mag, vd sgn) { return copysign(mag, sgn); }
static ALWAYS_INLINE vd vd_prod_err(vd x, vd y, vd p) { return product_error(x, y, p); }
static ALWAYS_INLINE vm vd_lt(vd a, vd b) { return a < b; }
static ALWAYS_INLINE vm vd_le(vd a, vd b) { return a <= b; }
static ALWAYS_INLINE vm vd_gt(vd a, vd b) { return a > b; }
static ALWAYS_INLINE vm vd_ge(vd a, vd b) { return a >= b; }
static ALWAYS_INLINE vm vd_eq(vd a, vd b) { return a == b; }
static ALWAYS_INLINE vd vd_sel(vm m, vd a, vd b) { return m ? a : b; }
static ALWAYS_INLINE vm vm_and(vm a, vm b) { return a & b; }
static ALWAYS_INLINE vm vm_or(vm a, vm b) { return a | b; }
static ALWAYS_INLINE vm vm_andnot(vm a, vm b) { return a & !b; } /* a and not b */
static ALWAYS_INLINE vm vm_not(vm a) { return !a; }
static ALWAYS_INLINE unsigned vm_bits(vm a) { return (unsigned)a; }
static ALWAYS_INLINE vm vm_true(void) { return 1; }
static ALWAYS_INLINE vm vm_false(void) { return 0; }
static ALWAYS_INLINE double vd_lane(vd a, int i) { (void)i; return a; }
static ALWAYS_INLINE void vd_store(double *to, vd a) { to[0] = a; }
static ALWAYS_INLINE vd vd_loadu(const double *from) { return from[0]; }
/* lane k = base[idx[k]] */
static ALWAYS_INLINE vd vd_gather_idx(const double *base, const int idx[LANE_W]) { return base[idx[0]]; }
/* Column c of the W rows of 8 doubles at rows[k]: out[c] lane k =
 * rows[k][c] (W records of 64 bytes, transposed). */
static ALWAYS_INLINE void vd_load_rows8(const double *const rows[LANE_W], vd out[8])
{
    for (int c = 0; c < 8; c++)
        out[c] = rows[0][c];
}
/* The inverse: rows[k][c] = lane k of in[c]. */
static ALWAYS_INLINE void vd_store_rows8(double *const rows[LANE_W], const vd in[8])
{
    for (int c = 0; c < 8; c++)
        rows[0][c] = in[c];
}

/* --------------------------------------------------------------- SSE2 */
#elif LANE_ISA == LANE_ISA_SSE2

#define LANE_W 2
typedef __m128d vd;
typedef __m128d vm; /* all bits of a lane set, or clear */

static ALWAYS_INLINE vd vd_set1(double x) { return _mm_set1_pd(x); }
static ALWAYS_INLINE vd vd_add(vd a, vd b) { return _mm_add_pd(a, b); }
static ALWAYS_INLINE vd vd_sub(vd a, vd b) { return _mm_sub_pd(a, b); }
static ALWAYS_INLINE vd vd_mul(vd a, vd b) { return _mm_mul_pd(a, b); }
static ALWAYS_INLINE vd vd_div(vd a, vd b) { return _mm_div_pd(a, b); }
static ALWAYS_INLINE vd vd_sqrt(vd a) { return _mm_sqrt_pd(a); }
static ALWAYS_INLINE vd vd_neg(vd a) { return _mm_xor_pd(a, _mm_set1_pd(-0.0)); }
static ALWAYS_INLINE vd vd_abs(vd a) { return _mm_andnot_pd(_mm_set1_pd(-0.0), a); }
static ALWAYS_INLINE vd vd_min(vd a, vd b) { return _mm_min_pd(a, b); }
static ALWAYS_INLINE vd vd_max(vd a, vd b) { return _mm_max_pd(a, b); }
static ALWAYS_INLINE vd vd_copysign(vd mag, vd sgn)
{
    __m128d sign = _mm_set1_pd(-0.0);
    return _mm_or_pd(_mm_andnot_pd(sign, mag), _mm_and_pd(sign, sgn));
}
static ALWAYS_INLINE vm vd_lt(vd a, vd b) { return _mm_cmplt_pd(a, b); }
static ALWAYS_INLINE vm vd_le(vd a, vd b) { return _mm_cmple_pd(a, b); }
static ALWAYS_INLINE vm vd_gt(vd a, vd b) { return _mm_cmpgt_pd(a, b); }
static ALWAYS_INLINE vm vd_ge(vd a, vd b) { return _mm_cmpge_pd(a, b); }
static ALWAYS_INLINE vm vd_eq(vd a, vd b) { return _mm_cmpeq_pd(a, b); }
static ALWAYS_INLINE vd vd_sel(vm m, vd a, vd b) { return _mm_or_pd(_mm_and_pd(m, a), _mm_andnot_pd(m, b)); }
static ALWAYS_INLINE vm vm_and(vm a, vm b) { return _mm_and_pd(a, b); }
static ALWAYS_INLINE vm vm_or(vm a, vm b) { return _mm_or_pd(a, b); }
static ALWAYS_INLINE vm vm_andnot(vm a, vm b) { return _mm_andnot_pd(b, a); }
static ALWAYS_INLINE vm vm_not(vm a) { return _mm_xor_pd(a, _mm_castsi128_pd(_mm_set1_epi32(-1))); }
static ALWAYS_INLINE unsigned vm_bits(vm a) { return (unsigned)_mm_movemask_pd(a); }
static ALWAYS_INLINE vm vm_true(void) { return _mm_castsi128_pd(_mm_set1_epi32(-1)); }
static ALWAYS_INLINE vm vm_false(void) { return _mm_setzero_pd(); }
static ALWAYS_INLINE double vd_lane(vd a, int i)
{
    double tmp[2];
    _mm_storeu_pd(tmp, a);
    return tmp[i];
}
static ALWAYS_INLINE void vd_store(double *to, vd a) { _mm_storeu_pd(to, a); }
static ALWAYS_INLINE vd vd_loadu(const double *from) { return _mm_loadu_pd(from); }
static ALWAYS_INLINE vd vd_gather_idx(const double *base, const int idx[LANE_W])
{
    return _mm_set_pd(base[idx[1]], base[idx[0]]);
}
static ALWAYS_INLINE void vd_load_rows8(const double *const rows[LANE_W], vd out[8])
{
    for (int c = 0; c < 8; c += 2) {
        __m128d a = _mm_loadu_pd(rows[0] + c), b = _mm_loadu_pd(rows[1] + c);
        out[c] = _mm_unpacklo_pd(a, b);
        out[c + 1] = _mm_unpackhi_pd(a, b);
    }
}
static ALWAYS_INLINE void vd_store_rows8(double *const rows[LANE_W], const vd in[8])
{
    for (int c = 0; c < 8; c += 2) {
        _mm_storeu_pd(rows[0] + c, _mm_unpacklo_pd(in[c], in[c + 1]));
        _mm_storeu_pd(rows[1] + c, _mm_unpackhi_pd(in[c], in[c + 1]));
    }
}
/*
 * Dekker's TwoProduct on both lanes; a lane outside the range where it is
 * exact (|x|, |y| <= 2^995, 2^-860 <= |p| <= 2^1000: predicates.h) takes
 * the C library's fma instead, as product_error does, so the result is the
 * exact residual (or, out of range, fma's correctly rounded one) either way.
 */
static ALWAYS_INLINE vd vd_prod_err(vd x, vd y, vd p)
{
    const __m128d split = _mm_set1_pd(134217729.0); /* 2^27 + 1 */
    __m128d cx = _mm_mul_pd(split, x), cy = _mm_mul_pd(split, y);
    __m128d xh = _mm_sub_pd(cx, _mm_sub_pd(cx, x)), yh = _mm_sub_pd(cy, _mm_sub_pd(cy, y));
    __m128d xl = _mm_sub_pd(x, xh), yl = _mm_sub_pd(y, yh);
    __m128d err = _mm_add_pd(_mm_add_pd(_mm_add_pd(_mm_sub_pd(_mm_mul_pd(xh, yh), p),
                                                   _mm_mul_pd(xh, yl)),
                                        _mm_mul_pd(xl, yh)),
                             _mm_mul_pd(xl, yl));
    __m128d ap = vd_abs(p);
    vm exact = vm_and(vm_and(vd_le(vd_abs(x), _mm_set1_pd(0x1p995)),
                             vd_le(vd_abs(y), _mm_set1_pd(0x1p995))),
                      vm_and(vd_ge(ap, _mm_set1_pd(0x1p-860)), vd_le(ap, _mm_set1_pd(0x1p1000))));
    unsigned out = 3u & ~vm_bits(exact);
    if (out != 0) {
        double e[2], xs[2], ys[2], ps[2];
        _mm_storeu_pd(e, err);
        _mm_storeu_pd(xs, x);
        _mm_storeu_pd(ys, y);
        _mm_storeu_pd(ps, p);
        for (int i = 0; i < 2; i++)
            if (out & (1u << i))
                e[i] = fma(xs[i], ys[i], -ps[i]);
        err = _mm_loadu_pd(e);
    }
    return err;
}

/* --------------------------------------------------------------- AVX2 */
#elif LANE_ISA == LANE_ISA_AVX2

#define LANE_W 4
typedef __m256d vd;
typedef __m256d vm;

static ALWAYS_INLINE vd vd_set1(double x) { return _mm256_set1_pd(x); }
static ALWAYS_INLINE vd vd_add(vd a, vd b) { return _mm256_add_pd(a, b); }
static ALWAYS_INLINE vd vd_sub(vd a, vd b) { return _mm256_sub_pd(a, b); }
static ALWAYS_INLINE vd vd_mul(vd a, vd b) { return _mm256_mul_pd(a, b); }
static ALWAYS_INLINE vd vd_div(vd a, vd b) { return _mm256_div_pd(a, b); }
static ALWAYS_INLINE vd vd_sqrt(vd a) { return _mm256_sqrt_pd(a); }
static ALWAYS_INLINE vd vd_neg(vd a) { return _mm256_xor_pd(a, _mm256_set1_pd(-0.0)); }
static ALWAYS_INLINE vd vd_abs(vd a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
static ALWAYS_INLINE vd vd_min(vd a, vd b) { return _mm256_min_pd(a, b); }
static ALWAYS_INLINE vd vd_max(vd a, vd b) { return _mm256_max_pd(a, b); }
static ALWAYS_INLINE vd vd_copysign(vd mag, vd sgn)
{
    __m256d sign = _mm256_set1_pd(-0.0);
    return _mm256_or_pd(_mm256_andnot_pd(sign, mag), _mm256_and_pd(sign, sgn));
}
/* fma(x, y, -p): the exact residual of p = fl(x*y) wherever it is
 * representable, and correctly rounded like fma() elsewhere. */
static ALWAYS_INLINE vd vd_prod_err(vd x, vd y, vd p) { return _mm256_fmsub_pd(x, y, p); }
static ALWAYS_INLINE vm vd_lt(vd a, vd b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }
static ALWAYS_INLINE vm vd_le(vd a, vd b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
static ALWAYS_INLINE vm vd_gt(vd a, vd b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }
static ALWAYS_INLINE vm vd_ge(vd a, vd b) { return _mm256_cmp_pd(a, b, _CMP_GE_OQ); }
static ALWAYS_INLINE vm vd_eq(vd a, vd b) { return _mm256_cmp_pd(a, b, _CMP_EQ_OQ); }
static ALWAYS_INLINE vd vd_sel(vm m, vd a, vd b) { return _mm256_blendv_pd(b, a, m); }
static ALWAYS_INLINE vm vm_and(vm a, vm b) { return _mm256_and_pd(a, b); }
static ALWAYS_INLINE vm vm_or(vm a, vm b) { return _mm256_or_pd(a, b); }
static ALWAYS_INLINE vm vm_andnot(vm a, vm b) { return _mm256_andnot_pd(b, a); }
static ALWAYS_INLINE vm vm_not(vm a) { return _mm256_xor_pd(a, _mm256_castsi256_pd(_mm256_set1_epi64x(-1))); }
static ALWAYS_INLINE unsigned vm_bits(vm a) { return (unsigned)_mm256_movemask_pd(a); }
static ALWAYS_INLINE vm vm_true(void) { return _mm256_castsi256_pd(_mm256_set1_epi64x(-1)); }
static ALWAYS_INLINE vm vm_false(void) { return _mm256_setzero_pd(); }
static ALWAYS_INLINE double vd_lane(vd a, int i)
{
    double tmp[4];
    _mm256_storeu_pd(tmp, a);
    return tmp[i];
}
static ALWAYS_INLINE void vd_store(double *to, vd a) { _mm256_storeu_pd(to, a); }
static ALWAYS_INLINE vd vd_loadu(const double *from) { return _mm256_loadu_pd(from); }
static ALWAYS_INLINE vd vd_gather_idx(const double *base, const int idx[LANE_W])
{
    return _mm256_i32gather_pd(base, _mm_loadu_si128((const __m128i *)(const void *)idx), 8);
}
static ALWAYS_INLINE void vd_transpose4(__m256d r0, __m256d r1, __m256d r2, __m256d r3,
                                        vd out[4])
{
    __m256d lo01 = _mm256_unpacklo_pd(r0, r1), hi01 = _mm256_unpackhi_pd(r0, r1);
    __m256d lo23 = _mm256_unpacklo_pd(r2, r3), hi23 = _mm256_unpackhi_pd(r2, r3);
    out[0] = _mm256_permute2f128_pd(lo01, lo23, 0x20);
    out[1] = _mm256_permute2f128_pd(hi01, hi23, 0x20);
    out[2] = _mm256_permute2f128_pd(lo01, lo23, 0x31);
    out[3] = _mm256_permute2f128_pd(hi01, hi23, 0x31);
}
static ALWAYS_INLINE void vd_load_rows8(const double *const rows[LANE_W], vd out[8])
{
    vd_transpose4(_mm256_loadu_pd(rows[0]), _mm256_loadu_pd(rows[1]),
                  _mm256_loadu_pd(rows[2]), _mm256_loadu_pd(rows[3]), out);
    vd_transpose4(_mm256_loadu_pd(rows[0] + 4), _mm256_loadu_pd(rows[1] + 4),
                  _mm256_loadu_pd(rows[2] + 4), _mm256_loadu_pd(rows[3] + 4), out + 4);
}
static ALWAYS_INLINE void vd_store_rows8(double *const rows[LANE_W], const vd in[8])
{
    vd r[4];
    vd_transpose4(in[0], in[1], in[2], in[3], r);
    for (int k = 0; k < 4; k++)
        _mm256_storeu_pd(rows[k], r[k]);
    vd_transpose4(in[4], in[5], in[6], in[7], r);
    for (int k = 0; k < 4; k++)
        _mm256_storeu_pd(rows[k] + 4, r[k]);
}

/* ------------------------------------------------------------ AVX-512 */
#elif LANE_ISA == LANE_ISA_AVX512

#define LANE_W 8
typedef __m512d  vd;
typedef __mmask8 vm;

static ALWAYS_INLINE vd vd_set1(double x) { return _mm512_set1_pd(x); }
static ALWAYS_INLINE vd vd_add(vd a, vd b) { return _mm512_add_pd(a, b); }
static ALWAYS_INLINE vd vd_sub(vd a, vd b) { return _mm512_sub_pd(a, b); }
static ALWAYS_INLINE vd vd_mul(vd a, vd b) { return _mm512_mul_pd(a, b); }
static ALWAYS_INLINE vd vd_div(vd a, vd b) { return _mm512_div_pd(a, b); }
static ALWAYS_INLINE vd vd_sqrt(vd a) { return _mm512_sqrt_pd(a); }
static ALWAYS_INLINE vd vd_neg(vd a)
{
    return _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(a),
                                                _mm512_set1_epi64((long long)0x8000000000000000ull)));
}
static ALWAYS_INLINE vd vd_abs(vd a)
{
    return _mm512_castsi512_pd(_mm512_and_si512(_mm512_castpd_si512(a),
                                                _mm512_set1_epi64(0x7fffffffffffffffll)));
}
/* written as compare-and-blend: vminpd / vmaxpd have the same semantics
 * (second operand on NaN), but the blends make them obvious */
static ALWAYS_INLINE vd vd_min(vd a, vd b) { return _mm512_mask_blend_pd(_mm512_cmp_pd_mask(a, b, _CMP_LT_OQ), b, a); }
static ALWAYS_INLINE vd vd_max(vd a, vd b) { return _mm512_mask_blend_pd(_mm512_cmp_pd_mask(a, b, _CMP_GT_OQ), b, a); }
static ALWAYS_INLINE vd vd_copysign(vd mag, vd sgn)
{
    __m512i sign = _mm512_set1_epi64((long long)0x8000000000000000ull);
    __m512i m = _mm512_andnot_si512(sign, _mm512_castpd_si512(mag));
    __m512i s = _mm512_and_si512(sign, _mm512_castpd_si512(sgn));
    return _mm512_castsi512_pd(_mm512_or_si512(m, s));
}
static ALWAYS_INLINE vd vd_prod_err(vd x, vd y, vd p) { return _mm512_fmsub_pd(x, y, p); }
static ALWAYS_INLINE vm vd_lt(vd a, vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ); }
static ALWAYS_INLINE vm vd_le(vd a, vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ); }
static ALWAYS_INLINE vm vd_gt(vd a, vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ); }
static ALWAYS_INLINE vm vd_ge(vd a, vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_GE_OQ); }
static ALWAYS_INLINE vm vd_eq(vd a, vd b) { return _mm512_cmp_pd_mask(a, b, _CMP_EQ_OQ); }
static ALWAYS_INLINE vd vd_sel(vm m, vd a, vd b) { return _mm512_mask_blend_pd(m, b, a); }
static ALWAYS_INLINE vm vm_and(vm a, vm b) { return (vm)(a & b); }
static ALWAYS_INLINE vm vm_or(vm a, vm b) { return (vm)(a | b); }
static ALWAYS_INLINE vm vm_andnot(vm a, vm b) { return (vm)(a & ~b); }
static ALWAYS_INLINE vm vm_not(vm a) { return (vm)~a; }
static ALWAYS_INLINE unsigned vm_bits(vm a) { return (unsigned)a; }
static ALWAYS_INLINE vm vm_true(void) { return (vm)0xff; }
static ALWAYS_INLINE vm vm_false(void) { return (vm)0; }
static ALWAYS_INLINE double vd_lane(vd a, int i)
{
    double tmp[8];
    _mm512_storeu_pd(tmp, a);
    return tmp[i];
}
static ALWAYS_INLINE void vd_store(double *to, vd a) { _mm512_storeu_pd(to, a); }
static ALWAYS_INLINE vd vd_loadu(const double *from) { return _mm512_loadu_pd(from); }
static ALWAYS_INLINE vd vd_gather_idx(const double *base, const int idx[LANE_W])
{
    return _mm512_i32gather_pd(_mm256_loadu_si256((const __m256i *)(const void *)idx), base, 8);
}
/* 8x8 transpose: pairs interleaved (unpacklo / unpackhi), then 128-bit
 * blocks gathered in two rounds of shuffle_f64x2 (0x88: blocks 0 and 2 of
 * each source, 0xDD: blocks 1 and 3). Written out: GCC keeps loops over
 * vector arrays in memory. */
static ALWAYS_INLINE void vd_transpose8(__m512d r0, __m512d r1, __m512d r2, __m512d r3,
                                        __m512d r4, __m512d r5, __m512d r6, __m512d r7,
                                        vd out[8])
{
    /* lo01 block j = (rows 0, 1) at column 2j; hi01: column 2j + 1 */
    __m512d lo01 = _mm512_unpacklo_pd(r0, r1), hi01 = _mm512_unpackhi_pd(r0, r1);
    __m512d lo23 = _mm512_unpacklo_pd(r2, r3), hi23 = _mm512_unpackhi_pd(r2, r3);
    __m512d lo45 = _mm512_unpacklo_pd(r4, r5), hi45 = _mm512_unpackhi_pd(r4, r5);
    __m512d lo67 = _mm512_unpacklo_pd(r6, r7), hi67 = _mm512_unpackhi_pd(r6, r7);
    __m512d x04 = _mm512_shuffle_f64x2(lo01, lo23, 0x88); /* cols 0, 4 of rows 0-3 */
    __m512d x26 = _mm512_shuffle_f64x2(lo01, lo23, 0xDD); /* cols 2, 6 */
    __m512d x15 = _mm512_shuffle_f64x2(hi01, hi23, 0x88); /* cols 1, 5 */
    __m512d x37 = _mm512_shuffle_f64x2(hi01, hi23, 0xDD); /* cols 3, 7 */
    __m512d y04 = _mm512_shuffle_f64x2(lo45, lo67, 0x88); /* the same, rows 4-7 */
    __m512d y26 = _mm512_shuffle_f64x2(lo45, lo67, 0xDD);
    __m512d y15 = _mm512_shuffle_f64x2(hi45, hi67, 0x88);
    __m512d y37 = _mm512_shuffle_f64x2(hi45, hi67, 0xDD);
    out[0] = _mm512_shuffle_f64x2(x04, y04, 0x88);
    out[4] = _mm512_shuffle_f64x2(x04, y04, 0xDD);
    out[2] = _mm512_shuffle_f64x2(x26, y26, 0x88);
    out[6] = _mm512_shuffle_f64x2(x26, y26, 0xDD);
    out[1] = _mm512_shuffle_f64x2(x15, y15, 0x88);
    out[5] = _mm512_shuffle_f64x2(x15, y15, 0xDD);
    out[3] = _mm512_shuffle_f64x2(x37, y37, 0x88);
    out[7] = _mm512_shuffle_f64x2(x37, y37, 0xDD);
}
static ALWAYS_INLINE void vd_load_rows8(const double *const rows[LANE_W], vd out[8])
{
    vd_transpose8(_mm512_loadu_pd(rows[0]), _mm512_loadu_pd(rows[1]), _mm512_loadu_pd(rows[2]),
                  _mm512_loadu_pd(rows[3]), _mm512_loadu_pd(rows[4]), _mm512_loadu_pd(rows[5]),
                  _mm512_loadu_pd(rows[6]), _mm512_loadu_pd(rows[7]), out);
}
static ALWAYS_INLINE void vd_store_rows8(double *const rows[LANE_W], const vd in[8])
{
    vd r[8];
    vd_transpose8(in[0], in[1], in[2], in[3], in[4], in[5], in[6], in[7], r);
    _mm512_storeu_pd(rows[0], r[0]);
    _mm512_storeu_pd(rows[1], r[1]);
    _mm512_storeu_pd(rows[2], r[2]);
    _mm512_storeu_pd(rows[3], r[3]);
    _mm512_storeu_pd(rows[4], r[4]);
    _mm512_storeu_pd(rows[5], r[5]);
    _mm512_storeu_pd(rows[6], r[6]);
    _mm512_storeu_pd(rows[7], r[7]);
}

#else
#error "unknown LANE_ISA"
#endif

/* The lanes of a mask, as an int with bit k for lane k. */
#define LANE_ALL ((1u << LANE_W) - 1u)

static ALWAYS_INLINE vd vd_zero(void) { return vd_set1(0.0); }

static ALWAYS_INLINE int vm_any(vm a) { return vm_bits(a) != 0; }
static ALWAYS_INLINE int vm_all(vm a) { return vm_bits(a) == LANE_ALL; }

#endif /* ISECT_LANES_H */
