/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bvh_walk.h — what every traversal of a bvh (core/bvh.h) shares: the
 * conservative test of a ray against a node's eight float boxes, its
 * per-ray constants (slab_ray), the traversal stack, and the SIMD levels
 * it runs at. The mesh walks its faces with it (mesh/mesh_query.c), the
 * scene its shapes (scene/scene_query.c).
 *
 * Why no hit is lost between boxes: the node test (numerics)
 * ----------------------------------------------------------
 * Let D = (max|o_k| + B)(1 + 4u), u = 2^-53, f = 2^-24 (float), where B
 * bounds every finite coordinate of the items' boxes, and let g >= 0 be
 * the caller's extra pad (slab_init's extra_pad, in units of D; 0 for a
 * mesh). The test relies on one property of the items, which each caller
 * proves for its own: every hit that matters lies, as the point org + t
 * dir of its reported t, within 4uD (1 + 2^-40) + gD of its item's box
 * (the float boxes are rounded outward and contain their items exactly),
 * so that |t| max|dir| <= |t dir| <= D (1 + 2^-40 + g).
 *
 * The test runs in float on eight children at once, in scaled time tau =
 * t 2^(ev - ed), where 2^ed <= D < 2^(ed+1) and 2^ev <= max|dir| <
 * 2^(ev+1) (both exponents in a range that keeps every quantity normal;
 * outside it every child passes). Every hit then has |tau| < 2 (1 + g),
 * so tmin and the current limit are clamped to [-4, 4] and rounded down
 * and up (slab_time_down/up) without losing one while g <= 1/2 (callers
 * with a larger pad take slab_init_unbounded).
 *
 * Per steep axis (|dir_k| >= 2^-20 max|dir|) a plane b of a box gives
 * tau = fl(fl(b - on_k) inv_k), on_k = fl(o_k + pad) for the near plane
 * (o_k - pad for the far one, the sign by dir_k: the box grown by pad =
 * (2^-20 + g) D), inv_k = fl(fl(1 / dir_k) 2^(ev - ed)). The numerator
 * errs by at most f D (on_k) + 2f D (the subtraction, |b - on_k| <= 2D),
 * the product by 2f relative (inv_k and the product), i.e. 4f D as a
 * position on the axis: 7f D < 2^-20 D in all. So the computed entry is no
 * later, and the exit no earlier, than those of the box grown by pad - 7f
 * D = 9f D + g D, which holds every hit of its items. (The padding idea of
 * Ize, "Robust BVH Ray Traversal", JCGT 2013, made absolute because the
 * errors here scale with D, not with t; folded into the two shifted
 * origins, so it costs nothing per box.)
 *
 * A flat axis (|dir_k| < 2^-20 max|dir|) takes inv_k = +-inf: the slab
 * then passes every tau or none, by the side of the shifted origin, with
 * pad (2^-18 + g) D; a hit moves along the axis by |t dir_k| < 2^-20 D (1
 * + 2^-40 + g) from o_k and lies within 4uD + gD of the box, well inside
 * that pad. A NaN from 0 * inf (the shifted origin exactly on a plane) is
 * the first operand of max and min, which return the second: that slab
 * does not constrain the interval.
 *
 * A child passes when max(tmin, entries) <= min(limit, exits): every
 * child holding a hit that matters passes, and a stacked child is dropped
 * only when its entry lies beyond the limit, i.e. beyond every hit that
 * could still replace the closest one. A child flagged loose
 * (BVH_FLAG_LOOSE_T: an item whose t may lie outside its box) is culled
 * only laterally, never by tmin or the limit.
 */
#ifndef ISECT_BVH_WALK_H
#define ISECT_BVH_WALK_H

#include "core/bvh.h"
#include "core/core.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* The node test runs on eight children at once, as two halves of four
 * with SSE (every x86-64 has it); elsewhere, or with ISECT_NO_SIMD defined,
 * the same float operations one child at a time. */
#if defined(__SSE2__) && !defined(ISECT_NO_SIMD)
#define WALK_SSE 1
#include <emmintrin.h>
#else
#define WALK_SSE 0
#endif

/* On x86-64 with GCC or clang the traversal is compiled a second time for
 * CPUs with AVX2 and FMA (checked at run time, walk_cpu_has_avx2_fma): the node
 * test on all eight children in one AVX register, and the exact face
 * tests' fma as instructions instead of libm calls. Both copies make the
 * same float and double operations in the same order (fma rounds correctly
 * either way; the library builds with -ffp-contract=off, so nothing else is
 * fused), so they give the same bits: the mesh tests compare this
 * traversal, which runs the AVX2 copy on such a CPU, with the lone triangle
 * and polygon tests, built for any x86-64; the test script also builds the
 * library with ISECT_NO_AVX2 (SSE2 only) and ISECT_NO_SIMD (portable) and
 * runs the mesh tests on each. */
#if WALK_SSE && !defined(ISECT_NO_AVX2) && defined(__x86_64__) \
    && (defined(__GNUC__) || defined(__clang__))
#define WALK_AVX2 1
#include <immintrin.h>
#define WALK_TARGET_AVX2 __attribute__((target("avx2,fma")))
static inline int walk_cpu_has_avx2_fma(void)
{
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}
#else
#define WALK_AVX2 0
static inline int walk_cpu_has_avx2_fma(void)
{
    return 0;
}
#endif

#ifndef UNIT_ROUNDOFF
#define UNIT_ROUNDOFF (DBL_EPSILON / 2.0)
#endif

/* The node test's range (the binary exponents of D and of max|dir|), its
 * origin shifts in units of D (steep and flat axes), the ratio below which
 * a direction component counts as flat, and the bound it puts on scaled
 * times (see "The node test" above). */
#define SLAB_D_EXP_MIN (-100)
#define SLAB_D_EXP_MAX 99
#define SLAB_DIR_EXP_MIN (-900)
#define SLAB_DIR_EXP_MAX 899
#define SLAB_PAD 0x1p-20
#define SLAB_PAD_FLAT 0x1p-18
#define SLAB_FLAT 0x1p-20
#define SLAB_TIME_BOUND 4.0

/* A node or leaf reference as the traversal stacks it. */
typedef struct node_ref {
    int32_t ref;   /* >= 0 inner node, < 0 leaf ~first */
    int32_t count; /* leaf size; 0 for an inner node */
    float   entry; /* where the ray enters its box (scaled time, rounded
                      down); -inf: never culled by t */
} node_ref;

/* The node test's constants of one ray (float, scaled time): per axis x,
 * y, z (the fourth float is padding) the origin moved toward the near and
 * toward the far plane and the reciprocal of the scaled direction,
 * broadcast to the eight children by the node test (one load either way;
 * repeated copies cost a ray's set-up 350 bytes of stores). */
typedef struct slab_ray {
    float   org_near[4], org_far[4], inv[4];
    float   tmin, limit;     /* tmin and the current limit as scaled times,
                                rounded down and up */
    double  scale;           /* 1 / sigma; 0: the node test culls nothing */
    int32_t plane_offset[6]; /* byte offsets in bvh_node.bounds of the near
                                planes x, y, z, then the far ones */
    double  d;               /* D, as the bounds above use it */
} slab_ray;

/* |x| = m 2^k, 1 <= m < 2, for a normal positive double: k (C99's ilogb
 * is a libm call). */
static inline int exponent_of(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return (int)((bits >> 52) & 0x7ff) - 1023;
}

/* 2^k for -1022 <= k <= 1023. */
static inline double power_of_two(int k)
{
    uint64_t bits = (uint64_t)(k + 1023) << 52;
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

/* A scaled time x (any double but NaN) clamped to the bound and rounded to
 * a float below (above) it. In [-4, 4] the float conversion errs by at
 * most 2^-24 |y| + 2^-150, which the margin |x| 2^-22 + 2^-140 exceeds. */
static inline float slab_time_down(double x)
{
    x = x < -SLAB_TIME_BOUND ? -SLAB_TIME_BOUND : x > SLAB_TIME_BOUND ? SLAB_TIME_BOUND : x;
    return (float)(x - (fabs(x) * 0x1p-22 + 0x1p-140));
}

static inline float slab_time_up(double x)
{
    x = x < -SLAB_TIME_BOUND ? -SLAB_TIME_BOUND : x > SLAB_TIME_BOUND ? SLAB_TIME_BOUND : x;
    return (float)(x + (fabs(x) * 0x1p-22 + 0x1p-140));
}

/* The node test's bound for t_limit = t. */
static inline void slab_set_limit(slab_ray *s, double t)
{
    s->limit = s->scale != 0.0 ? slab_time_up(t * s->scale) : INFINITY;
}

/* plane_offset for the signs of dir (bit k set: dir_k < 0): the near plane
 * of axis k is lo_k for a positive component and hi_k for a negative one. */
#define PLANE_BYTES ((int32_t)sizeof(((bvh_node *)0)->bounds[0]))
#define PLANE_OFFSETS(o)                                                              \
    { PLANE_BYTES * (0 + 3 * ((o) & 1)), PLANE_BYTES * (1 + 3 * ((o) >> 1 & 1)),      \
      PLANE_BYTES * (2 + 3 * ((o) >> 2 & 1)), PLANE_BYTES * (3 - 3 * ((o) & 1)),      \
      PLANE_BYTES * (4 - 3 * ((o) >> 1 & 1)), PLANE_BYTES * (5 - 3 * ((o) >> 2 & 1)) }
static const int32_t plane_offsets[8][6] = {
    PLANE_OFFSETS(0), PLANE_OFFSETS(1), PLANE_OFFSETS(2), PLANE_OFFSETS(3),
    PLANE_OFFSETS(4), PLANE_OFFSETS(5), PLANE_OFFSETS(6), PLANE_OFFSETS(7),
};

/* Outside the node test's range: a test that passes every child. With a
 * zero origin and reciprocal each slab time is (b - 0) * 0, which is 0 for
 * a finite bound and NaN (no constraint) for an infinite one; with tmin
 * -inf and limit +inf every child passes. */
static inline void slab_init_unbounded(slab_ray *s)
{
    memset(s->org_near, 0, sizeof s->org_near);
    memset(s->org_far, 0, sizeof s->org_far);
    memset(s->inv, 0, sizeof s->inv);
    s->tmin = -INFINITY;
    s->limit = INFINITY;
    s->scale = 0.0;
    memcpy(s->plane_offset, plane_offsets[0], sizeof s->plane_offset);
}

/* The node test's constants for a ray (see "The node test" above): D;
 * sigma = 2^e with e the difference of the exponents of D and max|dir|;
 * per axis, flat when |dir_k| < 2^-20 max|dir|, the origin moved by the
 * pad (flat: the flat pad) toward the near and toward the far plane, and
 * the scaled reciprocal 1 / (dir_k sigma): fl(1 / dir_k) 2^-e exactly for
 * a steep axis (a power of two, no under- or overflow in range), +-inf by
 * the sign of dir_k for a flat one. */
static inline void slab_init(slab_ray *s, double coord_bound, double extra_pad,
                             const isect_ray *ray)
{
#if WALK_SSE
    /* Axes x, y in one register and z in the low lane of another: the
     * same double operations as the portable code below, without its
     * branches. */
    const __m128d sign = _mm_set1_pd(-0.0);
    __m128d dxy = _mm_loadu_pd(ray->dir), dzz = _mm_load1_pd(ray->dir + 2);
    __m128d oxy = _mm_loadu_pd(ray->org), ozz = _mm_load1_pd(ray->org + 2);
    __m128d adxy = _mm_andnot_pd(sign, dxy), adzz = _mm_andnot_pd(sign, dzz);
    __m128d ao = _mm_max_pd(_mm_andnot_pd(sign, oxy), _mm_andnot_pd(sign, ozz));
    __m128d ad = _mm_max_pd(adxy, adzz);
    double org_max = _mm_cvtsd_f64(_mm_max_sd(ao, _mm_unpackhi_pd(ao, ao)));
    double dir_max = _mm_cvtsd_f64(_mm_max_sd(ad, _mm_unpackhi_pd(ad, ad)));
#else
    double org_max = 0.0, dir_max = 0.0;
    for (int k = 0; k < 3; k++) {
        org_max = fabs(ray->org[k]) > org_max ? fabs(ray->org[k]) : org_max;
        dir_max = fabs(ray->dir[k]) > dir_max ? fabs(ray->dir[k]) : dir_max;
    }
#endif
    double d = (org_max + coord_bound) * (1.0 + 4.0 * UNIT_ROUNDOFF);
    s->d = d;
    /* In range when both exponents are (zero, subnormal, infinite: not). */
    int ed = exponent_of(d), ev = exponent_of(dir_max);
    if ((unsigned)(ed - SLAB_D_EXP_MIN) > (unsigned)(SLAB_D_EXP_MAX - SLAB_D_EXP_MIN)
        || (unsigned)(ev - SLAB_DIR_EXP_MIN) > (unsigned)(SLAB_DIR_EXP_MAX - SLAB_DIR_EXP_MIN)) {
        slab_init_unbounded(s);
        return;
    }
    double scale = power_of_two(ev - ed), flat_below = SLAB_FLAT * dir_max;
    s->scale = scale;
#if WALK_SSE
    __m128d vfb = _mm_set1_pd(flat_below), vscale = _mm_set1_pd(scale);
    __m128d flat_xy = _mm_cmplt_pd(adxy, vfb), flat_zz = _mm_cmplt_pd(adzz, vfb);
    __m128d pad = _mm_set1_pd((SLAB_PAD + extra_pad) * d), pad_flat = _mm_set1_pd((SLAB_PAD_FLAT + extra_pad) * d);
    __m128d toward_xy = _mm_or_pd(_mm_or_pd(_mm_and_pd(flat_xy, pad_flat),
                                            _mm_andnot_pd(flat_xy, pad)),
                                  _mm_and_pd(sign, dxy));
    __m128d toward_zz = _mm_or_pd(_mm_or_pd(_mm_and_pd(flat_zz, pad_flat),
                                            _mm_andnot_pd(flat_zz, pad)),
                                  _mm_and_pd(sign, dzz));
    /* Floats [x, y, z, z]. */
    __m128 on = _mm_movelh_ps(_mm_cvtpd_ps(_mm_add_pd(oxy, toward_xy)),
                              _mm_cvtpd_ps(_mm_add_pd(ozz, toward_zz)));
    __m128 of = _mm_movelh_ps(_mm_cvtpd_ps(_mm_sub_pd(oxy, toward_xy)),
                              _mm_cvtpd_ps(_mm_sub_pd(ozz, toward_zz)));
    __m128d one = _mm_set1_pd(1.0);
    __m128 steep_inv = _mm_movelh_ps(_mm_cvtpd_ps(_mm_mul_pd(_mm_div_pd(one, dxy), vscale)),
                                     _mm_cvtpd_ps(_mm_mul_pd(_mm_div_pd(one, dzz), vscale)));
    __m128 flat_inv = _mm_or_ps(_mm_set1_ps(INFINITY),
                                _mm_and_ps(_mm_set1_ps(-0.0f),
                                           _mm_movelh_ps(_mm_cvtpd_ps(dxy), _mm_cvtpd_ps(dzz))));
    /* The double masks' low halves as float lanes [x, y, z, z]. */
    __m128 flat = _mm_castsi128_ps(_mm_unpacklo_epi64(
        _mm_shuffle_epi32(_mm_castpd_si128(flat_xy), _MM_SHUFFLE(2, 0, 2, 0)),
        _mm_shuffle_epi32(_mm_castpd_si128(flat_zz), _MM_SHUFFLE(2, 0, 2, 0))));
    __m128 inv = _mm_or_ps(_mm_and_ps(flat, flat_inv), _mm_andnot_ps(flat, steep_inv));
    _mm_storeu_ps(s->org_near, on);
    _mm_storeu_ps(s->org_far, of);
    _mm_storeu_ps(s->inv, inv);
    int negative = _mm_movemask_pd(dxy) | (_mm_movemask_pd(dzz) & 1) << 2;
    s->tmin = slab_time_down(ray->tmin * scale);
    s->limit = slab_time_up(ray->tmax * scale);
#else
    int negative = 0;
    for (int k = 0; k < 3; k++) {
        double dk = ray->dir[k];
        int flat = fabs(dk) < flat_below;
        double toward = copysign(((flat ? SLAB_PAD_FLAT : SLAB_PAD) + extra_pad) * d, dk);
        float on = (float)(ray->org[k] + toward), of = (float)(ray->org[k] - toward);
        float ik = flat ? copysignf(INFINITY, (float)dk) : (float)(1.0 / dk * scale);
        s->org_near[k] = on;
        s->org_far[k] = of;
        s->inv[k] = ik;
        negative |= (signbit(dk) != 0) << k;
    }
    s->org_near[3] = s->org_far[3] = s->inv[3] = 0.0f;
    s->tmin = slab_time_down(ray->tmin * scale);
    s->limit = slab_time_up(ray->tmax * scale);
#endif
    memcpy(s->plane_offset, plane_offsets[negative], sizeof s->plane_offset);
}

/* A hint to start loading memory the traversal will soon read: two cache
 * lines (half a node, or two lines of prims). Traversal of a large mesh is
 * bound by the latency of these loads; the hint overlaps them with other
 * work. GCC and clang only; elsewhere nothing. */
#if defined(__GNUC__) || defined(__clang__)
#define PREFETCH(p) (__builtin_prefetch(p), __builtin_prefetch((p) + 64))
#else
#define PREFETCH(p) ((void)(p))
#endif

/* The index of the lowest set bit of a nonzero child mask. */
static inline int lowest_bit(unsigned m)
{
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctz(m);
#else
    int i = 0;
    for (; (m & 1u) == 0; m >>= 1)
        i++;
    return i;
#endif
}

/* Where a traversal is: the reference it visits next (ref, count as in
 * node_ref) and the stacked ones it will come back to. */
typedef struct walker {
    int32_t  ref, count;
    int      sp;
    node_ref stack[BVH_STACK_SIZE];
} walker;

static inline void walker_init(walker *w)
{
    w->ref = 0;
    w->count = 0;
    w->sp = 0;
}

/* The eight floats of a plane of node n's bounds, by byte offset. */
static inline const float *node_plane(const bvh_node *n, int32_t offset)
{
    return (const float *)(const void *)((const char *)n->bounds + offset);
}

#if WALK_SSE
/* All ones in lane c where bit c of the 4-bit m is set. */
static inline __m128 lane_mask4(unsigned m)
{
    const __m128i bit = _mm_set_epi32(8, 4, 2, 1);
    return _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)m), bit), bit));
}

/* x where mask is clear, y where it is set. */
static inline __m128 lane_select4(__m128 mask, __m128 x, __m128 y)
{
    return _mm_or_ps(_mm_and_ps(mask, y), _mm_andnot_ps(mask, x));
}
#endif

/* The node test of node n's eight children: bit c set when child c may
 * hold a hit that matters, entry[c] where the ray enters its padded box
 * (scaled time, -inf for a loose child). A NaN from 0 * inf (a flat axis
 * on a slab plane) is the first operand of max and min, which then return
 * the second: that slab does not constrain the interval. A loose child's
 * interval starts as the whole line (it is culled only by its box's
 * slabs), and it is stacked with entry -inf (never dropped). may_loose is a
 * constant: 0 for a mesh without polygon faces (no node is loose). */
static ALWAYS_INLINE unsigned node_test(const slab_ray *s, const bvh_node *n,
                                        float entry[BVH_WIDTH], int may_loose)
{
#if WALK_SSE
    unsigned mask = 0;
    for (int h = 0; h < BVH_WIDTH / 4; h++) {
        __m128 tn = _mm_set1_ps(s->tmin), tf = _mm_set1_ps(s->limit);
        __m128 loose = _mm_setzero_ps();
        if (may_loose && n->loose != 0) {
            loose = lane_mask4(((unsigned)n->loose >> (4 * h)) & 15u);
            tn = lane_select4(loose, tn, _mm_set1_ps(-INFINITY));
            tf = lane_select4(loose, tf, _mm_set1_ps(INFINITY));
        }
        /* Written out per axis (the compiler keeps the loop otherwise). */
#define SLAB_AXIS(k)                                                                      \
    tn = _mm_max_ps(                                                                      \
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node_plane(n, s->plane_offset[k]) + 4 * h),     \
                              _mm_set1_ps(s->org_near[k])),                          \
                   _mm_set1_ps(s->inv[k])),                                          \
        tn);                                                                              \
    tf = _mm_min_ps(                                                                      \
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node_plane(n, s->plane_offset[3 + k]) + 4 * h), \
                              _mm_set1_ps(s->org_far[k])),                           \
                   _mm_set1_ps(s->inv[k])),                                          \
        tf)
        SLAB_AXIS(0);
        SLAB_AXIS(1);
        SLAB_AXIS(2);
#undef SLAB_AXIS
        mask |= (unsigned)_mm_movemask_ps(_mm_cmple_ps(tn, tf)) << (4 * h);
        if (may_loose && n->loose != 0)
            tn = lane_select4(loose, tn, _mm_set1_ps(-INFINITY));
        _mm_storeu_ps(entry + 4 * h, tn);
    }
    return mask;
#else
    float tf[BVH_WIDTH];
    unsigned loose = may_loose ? n->loose : 0u;
    for (int c = 0; c < BVH_WIDTH; c++) {
        int lc = (loose >> c) & 1u;
        entry[c] = lc ? -INFINITY : s->tmin;
        tf[c] = lc ? INFINITY : s->limit;
    }
    for (int k = 0; k < 3; k++) {
        const float *near = node_plane(n, s->plane_offset[k]);
        const float *far = node_plane(n, s->plane_offset[3 + k]);
        float on = s->org_near[k], of = s->org_far[k];
        float inv = s->inv[k];
        for (int c = 0; c < BVH_WIDTH; c++) {
            float t0 = (near[c] - on) * inv, t1 = (far[c] - of) * inv;
            entry[c] = t0 > entry[c] ? t0 : entry[c];
            tf[c] = t1 < tf[c] ? t1 : tf[c];
        }
    }
    unsigned mask = 0;
    for (int c = 0; c < BVH_WIDTH; c++) {
        mask |= (unsigned)(entry[c] <= tf[c]) << c;
        if ((loose >> c) & 1u)
            entry[c] = -INFINITY;
    }
    return mask;
#endif
}

#if WALK_AVX2
/* node_test with the eight children in one AVX register: the same float
 * operations lane by lane (vmaxps and vminps return the second operand for
 * a NaN as maxps and minps do), so the same mask and entries. Not forced
 * inline: it is inlined into the AVX2 copies of the traversal and never
 * runs elsewhere. */
WALK_TARGET_AVX2 static inline unsigned node_test_avx2(const slab_ray *s, const bvh_node *n,
                                                       float entry[BVH_WIDTH], int may_loose)
{
    __m256 tn = _mm256_broadcast_ss(&s->tmin), tf = _mm256_broadcast_ss(&s->limit);
    __m256 loose = _mm256_setzero_ps();
    if (may_loose && n->loose != 0) {
        const __m256i bit = _mm256_set_epi32(128, 64, 32, 16, 8, 4, 2, 1);
        loose = _mm256_castsi256_ps(
            _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(n->loose), bit), bit));
        tn = _mm256_blendv_ps(tn, _mm256_set1_ps(-INFINITY), loose);
        tf = _mm256_blendv_ps(tf, _mm256_set1_ps(INFINITY), loose);
    }
#define SLAB_AXIS(k)                                                                      \
    tn = _mm256_max_ps(                                                                   \
        _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node_plane(n, s->plane_offset[k])),    \
                                    _mm256_broadcast_ss(&s->org_near[k])),           \
                      _mm256_broadcast_ss(&s->inv[k])),                              \
        tn);                                                                              \
    tf = _mm256_min_ps(                                                                   \
        _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node_plane(n, s->plane_offset[3 + k])), \
                                    _mm256_broadcast_ss(&s->org_far[k])),            \
                      _mm256_broadcast_ss(&s->inv[k])),                              \
        tf)
    SLAB_AXIS(0);
    SLAB_AXIS(1);
    SLAB_AXIS(2);
#undef SLAB_AXIS
    unsigned mask = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ));
    if (may_loose && n->loose != 0)
        tn = _mm256_blendv_ps(tn, _mm256_set1_ps(-INFINITY), loose);
    _mm256_storeu_ps(entry, tn);
    return mask;
}
#endif

#endif /* ISECT_BVH_WALK_H */
