/* SPDX-License-Identifier: Apache-2.0 */
/*
 * mesh_query.c — ray queries against a mesh through its BVH: closest hit,
 * all hits, any hit; and point containment by exact crossing parity.
 *
 * Every face decision is made by the shared exact tests (triangle_test.h's
 * triangle_hit, planar.h's polygon_hit_plane_framed) in the ray's sheared
 * frame, computed once per ray. Everything in front of them only skips
 * faces those tests would certainly reject, so the BVH changes the speed
 * and never the answer: a query returns bit for bit what testing every
 * face in turn would (the tests check this against brute force).
 *
 * Why no hit is lost between boxes: the node test (numerics)
 * ----------------------------------------------------------
 * Let D = (max|o_k| + max|vertex coordinate|)(1 + 4u), u = 2^-53, f =
 * 2^-24 (float). Every vertex-minus-origin difference is at most D. The
 * exact test claims a face only when the exact projection of the ray's
 * line meets it, i.e. when the line meets the face (a triangle: its exact
 * crossing with the plane lies in the closed triangle), and reports t
 * within 4 ulp of that crossing: org + t dir lies within 4u|t dir| <= 4uD
 * (1 + 2^-40) of a point of the face, hence of its box; the float boxes
 * are rounded outward and contain their faces exactly. Such a hit has
 * |t| max|dir| <= |t dir| <= D (1 + 2^-40).
 *
 * The test runs in float on eight children at once, in scaled time tau =
 * t 2^(ev - ed), where 2^ed <= D < 2^(ed+1) and 2^ev <= max|dir| <
 * 2^(ev+1) (both exponents in a range that keeps every quantity normal;
 * outside it every child passes). Every hit then has |tau| < 2, so tmin
 * and the current limit are clamped to [-4, 4] and rounded down and up
 * (slab_time_down/up) without losing one.
 *
 * Per steep axis (|dir_k| >= 2^-20 max|dir|) a plane b of a box gives
 * tau = fl(fl(b - on_k) inv_k), on_k = fl(o_k + pad) for the near plane
 * (o_k - pad for the far one, the sign by dir_k: the box grown by pad =
 * 2^-20 D), inv_k = fl(fl(1 / dir_k) 2^(ev - ed)). The numerator errs by
 * at most f D (on_k) + 2f D (the subtraction, |b - on_k| <= 2D), the
 * product by 2f relative (inv_k and the product), i.e. 4f D as a position
 * on the axis: 7f D < pad in all. So the computed entry is no later, and
 * the exit no earlier, than those of the box grown by pad - 7f D = 9f D,
 * which holds every hit of its faces. (The padding idea of Ize, "Robust
 * BVH Ray Traversal", JCGT 2013, made absolute because the errors here
 * scale with D, not with t; folded into the two shifted origins, so it
 * costs nothing per box.)
 *
 * A flat axis (|dir_k| < 2^-20 max|dir|) takes inv_k = +-inf: the slab
 * then passes every tau or none, by the side of the shifted origin, with
 * pad 2^-18 D; a hit moves along the axis by |t dir_k| < 2^-20 D (1 +
 * 2^-40) from o_k, well inside that pad. A NaN from 0 * inf (the shifted
 * origin exactly on a plane) is the first operand of max and min, which
 * return the second: that slab does not constrain the interval.
 *
 * A child passes when max(tmin, entries) <= min(limit, exits): every
 * child holding a hit that matters passes, and a stacked child is dropped
 * only when its entry lies beyond the limit, i.e. beyond every hit that
 * could still replace the closest one.
 *
 * Polygon faces take t from their plane, t = n.(c - o) / n.d, which for a
 * grazing ray may land far outside the face's box; subtrees holding a
 * polygon (BVH_FLAG_LOOSE_T) are therefore culled only laterally (the line
 * against the padded box), never by [tmin, tmax] or the current closest t.
 *
 * The triangle pre-filter
 * -----------------------
 * Before the exact test each triangle gets Woop's three edge functions in
 * plain double from projections computed without fma (so that x86-64
 * without -mfma never calls libm's fma in the loop). Each projection
 * differs from the exact projection the exact test decides on (x = A[kx] -
 * (d[kx]/d[kz]) A[kz] in real numbers, A = v - o) by at most 6.1uD: uD for
 * each rounded difference, u|S| <= u for the rounded shear S, then the
 * product and the subtraction, |x| <= 2D. So an edge function is off by at
 * most 4 (6.1uD)(2D) + 3 roundings of products below 8D^2, about 65uD^2;
 * with bound B = 128uD^2 (and a floor of 2^-1000, below which products may
 * be subnormal), two edge functions beyond +B and -B prove the exact test
 * rejects. The exact crossing of a claimed triangle lies in the closed
 * triangle, so its t lies in [min z, max z] of the exact sheared z =
 * A[kz]/d[kz]; the reported t is within 3.5u|t| of it and each computed z
 * within 3.1u|z| of the exact one: a triangle whose whole z range is
 * outside [tmin, current t] by 16u max|z| is skipped.
 *
 * Containment
 * -----------
 * Parity of crossings along the fixed ray from p in +x, with every decision
 * exact on the unrounded input: the 2D claims use orient2_sign_perturbed /
 * the winding rule at p's (y, z) (the same symbolic perturbation as the ray
 * tests, and the same predicates), and the side of p on which a claimed
 * face is crossed is the exact sign of orient3 (Shewchuk). Polygon faces
 * count as their fan from the first vertex: the fan's inner edges cancel in
 * pairs, so its crossing parity is the polygon's even-odd parity. Points on
 * the surface are inside (solids are closed sets, as for the analytic
 * shapes): see mesh_contains.
 */
#include "mesh/mesh.h"

#include "prim/planar.h"
#include "core/predicates.h"
#include "core/ray_frame.h"
#include "core/ratio.h"
#include "core/scaling.h"
#include "prim/triangle_test.h"
#include "core/vec3.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

/* The node test runs on eight children at once, as two halves of four
 * with SSE (every x86-64 has it); elsewhere, or with ISECT_NO_SIMD defined,
 * the same float operations one child at a time. */
#if defined(__SSE2__) && !defined(ISECT_NO_SIMD)
#define MESH_SSE 1
#include <emmintrin.h>
#else
#define MESH_SSE 0
#endif

/* On x86-64 with GCC or clang the traversal is compiled a second time for
 * CPUs with AVX2 and FMA (checked at run time, cpu_has_avx2_fma): the node
 * test on all eight children in one AVX register, and the exact face
 * tests' fma as instructions instead of libm calls. Both copies make the
 * same float and double operations in the same order (fma rounds correctly
 * either way; the library builds with -ffp-contract=off, so nothing else is
 * fused), so they give the same bits: the mesh tests compare this
 * traversal, which runs the AVX2 copy on such a CPU, with the lone triangle
 * and polygon tests, built for any x86-64; the test script also builds the
 * library with ISECT_NO_AVX2 (SSE2 only) and ISECT_NO_SIMD (portable) and
 * runs the mesh tests on each. */
#if MESH_SSE && !defined(ISECT_NO_AVX2) && defined(__x86_64__) \
    && (defined(__GNUC__) || defined(__clang__))
#define MESH_AVX2 1
#include <immintrin.h>
#define MESH_TARGET_AVX2 __attribute__((target("avx2,fma")))
static int cpu_has_avx2_fma(void)
{
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}
#else
#define MESH_AVX2 0
static int cpu_has_avx2_fma(void)
{
    return 0;
}
#endif

#define UNIT_ROUNDOFF (DBL_EPSILON / 2.0)

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

/* The edge-function and t bounds of the pre-filter in units of u*D^2 and
 * u*max|z| (see above). */
#define EDGE_BOUND_ULPS 128.0
#define EDGE_BOUND_FLOOR 0x1p-1000
#define T_SLACK_ULPS 16.0

enum query_mode { QUERY_CLOSEST, QUERY_ALL, QUERY_ANY };

/* A node or leaf reference as the traversal stacks it. */
typedef struct node_ref {
    int32_t ref;   /* >= 0 inner node, < 0 leaf ~first */
    int32_t count; /* leaf size; 0 for an inner node */
    float   entry; /* where the ray enters its box (scaled time, rounded
                      down); -inf: never culled by t */
} node_ref;

typedef struct query {
    const isect_mesh   *mesh;
    const bvh_node     *nodes;  /* the mesh's, for the traversal */
    const mesh_prim    *prims;
    const isect_ray    *ray;
    const isect_params *prm;
    lane_ray  lane;        /* the ray as one lane, and whether it and the
                              faces lie in face_lanes.h's fast range: 1 all
                              faces, -1 to be checked per face (a vertex
                              beyond it), 0 none (made with the frame) */
    int       fast_range;
    ray_frame frame;       /* made at the first leaf (frame_ready): a ray that
                              misses every box never pays for it */
    int       frame_ready;
    /* Node test (float, scaled time): per axis x, y, z (the fourth float
     * is padding) the origin moved toward the near and toward the far
     * plane and the reciprocal of the scaled direction, broadcast to the
     * eight children by the node test (one load either way; repeated
     * copies cost the ray's set-up 350 bytes of stores); */
    float  slab_org_near[4], slab_org_far[4], slab_inv[4];
    float  slab_tmin, slab_limit; /* tmin and t_limit as scaled times, rounded
                                     down and up */
    double slab_scale;            /* 1 / sigma; 0: the node test culls nothing */
    int32_t plane_offset[6];      /* byte offsets in bvh_node.bounds of the near
                                     planes x, y, z, then the far ones */
    double d;                     /* D, as the bounds above use it */
    /* Pre-filter (set with the frame, at the first leaf). */
    double edge_bound;
    int    cull_back;
    /* Results. */
    double     t_limit;   /* closest: t of the best hit so far (else tmax) */
    isect_hit  best;
    int        found;
    int64_t    count;     /* all: hits found */
    isect_hit *hits;      /* all: max-heap of the best min(count, cap) */
    int64_t    cap;
} query;

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
static inline void slab_set_limit(query *q, double t)
{
    q->slab_limit = q->slab_scale != 0.0 ? slab_time_up(t * q->slab_scale) : INFINITY;
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
static void slab_init_unbounded(query *q)
{
    memset(q->slab_org_near, 0, sizeof q->slab_org_near);
    memset(q->slab_org_far, 0, sizeof q->slab_org_far);
    memset(q->slab_inv, 0, sizeof q->slab_inv);
    q->slab_tmin = -INFINITY;
    q->slab_limit = INFINITY;
    q->slab_scale = 0.0;
    memcpy(q->plane_offset, plane_offsets[0], sizeof q->plane_offset);
}

/* The node test's constants for a ray (see "The node test" above): D;
 * sigma = 2^e with e the difference of the exponents of D and max|dir|;
 * per axis, flat when |dir_k| < 2^-20 max|dir|, the origin moved by the
 * pad (flat: the flat pad) toward the near and toward the far plane, and
 * the scaled reciprocal 1 / (dir_k sigma): fl(1 / dir_k) 2^-e exactly for
 * a steep axis (a power of two, no under- or overflow in range), +-inf by
 * the sign of dir_k for a flat one. */
static void slab_init(query *q, double coord_bound, const isect_ray *ray)
{
#if MESH_SSE
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
    q->d = d;
    /* In range when both exponents are (zero, subnormal, infinite: not). */
    int ed = exponent_of(d), ev = exponent_of(dir_max);
    if ((unsigned)(ed - SLAB_D_EXP_MIN) > (unsigned)(SLAB_D_EXP_MAX - SLAB_D_EXP_MIN)
        || (unsigned)(ev - SLAB_DIR_EXP_MIN) > (unsigned)(SLAB_DIR_EXP_MAX - SLAB_DIR_EXP_MIN)) {
        slab_init_unbounded(q);
        return;
    }
    double scale = power_of_two(ev - ed), flat_below = SLAB_FLAT * dir_max;
    q->slab_scale = scale;
#if MESH_SSE
    __m128d vfb = _mm_set1_pd(flat_below), vscale = _mm_set1_pd(scale);
    __m128d flat_xy = _mm_cmplt_pd(adxy, vfb), flat_zz = _mm_cmplt_pd(adzz, vfb);
    __m128d pad = _mm_set1_pd(SLAB_PAD * d), pad_flat = _mm_set1_pd(SLAB_PAD_FLAT * d);
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
    _mm_storeu_ps(q->slab_org_near, on);
    _mm_storeu_ps(q->slab_org_far, of);
    _mm_storeu_ps(q->slab_inv, inv);
    int negative = _mm_movemask_pd(dxy) | (_mm_movemask_pd(dzz) & 1) << 2;
    q->slab_tmin = slab_time_down(ray->tmin * scale);
    q->slab_limit = slab_time_up(ray->tmax * scale);
#else
    int negative = 0;
    for (int k = 0; k < 3; k++) {
        double dk = ray->dir[k];
        int flat = fabs(dk) < flat_below;
        double toward = copysign((flat ? SLAB_PAD_FLAT : SLAB_PAD) * d, dk);
        float on = (float)(ray->org[k] + toward), of = (float)(ray->org[k] - toward);
        float ik = flat ? copysignf(INFINITY, (float)dk) : (float)(1.0 / dk * scale);
        q->slab_org_near[k] = on;
        q->slab_org_far[k] = of;
        q->slab_inv[k] = ik;
        negative |= (signbit(dk) != 0) << k;
    }
    q->slab_org_near[3] = q->slab_org_far[3] = q->slab_inv[3] = 0.0f;
    q->slab_tmin = slab_time_down(ray->tmin * scale);
    q->slab_limit = slab_time_up(ray->tmax * scale);
#endif
    memcpy(q->plane_offset, plane_offsets[negative], sizeof q->plane_offset);
}

static void query_init(query *q, const isect_mesh *m, const isect_ray *ray,
                       const isect_params *prm)
{
    q->mesh = m;
    q->nodes = m->tree.nodes;
    q->prims = m->prims;
    q->ray = ray;
    q->prm = prm;
    q->frame_ready = 0;
    q->t_limit = ray->tmax;
    q->found = 0;
    q->count = 0;
    q->hits = NULL;
    q->cap = 0;
    slab_init(q, m->coord_bound, ray);
}

/* What the faces' tests need, made at the first leaf: the frame, the ray
 * as one lane with its fast-range verdict, and the pre-filter's bound.
 * d * d may overflow (infinite bound: every triangle goes to the exact
 * test) or, near zero, underflow below the floor. */
static void query_leaf_init(query *q)
{
    ray_frame_shear(q->ray, &q->frame);
    q->frame_ready = 1;
    lane_ray_from(&q->lane, q->ray);
    q->fast_range = !lane_ray_in_range(&q->lane, 0x1p200) ? 0
                  : q->mesh->coord_bound <= 0x1p200     ? 1
                                                        : -1;
    q->edge_bound = EDGE_BOUND_ULPS * UNIT_ROUNDOFF * q->d * q->d;
    if (!(q->edge_bound > EDGE_BOUND_FLOOR))
        q->edge_bound = isnan(q->edge_bound) ? INFINITY : EDGE_BOUND_FLOOR;
    q->cull_back = (q->prm->flags & ISECT_CULL_BACK) != 0;
}

/* 0 when the exact triangle test certainly rejects the triangle or its
 * hit lies certainly outside [t_lo, t_hi]; 1 when it must be run. */
static ALWAYS_INLINE int triangle_candidate(const query *q, const double *v, double t_lo,
                                            double t_hi)
{
    const ray_frame *f = &q->frame;
    const int kx = f->kx, ky = f->ky, kz = f->kz;
    double az = v[kz] - f->org[kz], bz = v[3 + kz] - f->org[kz], cz = v[6 + kz] - f->org[kz];
    double ax = (v[kx] - f->org[kx]) - f->sx * az, ay = (v[ky] - f->org[ky]) - f->sy * az;
    double bx = (v[3 + kx] - f->org[kx]) - f->sx * bz;
    double by = (v[3 + ky] - f->org[ky]) - f->sy * bz;
    double cx = (v[6 + kx] - f->org[kx]) - f->sx * cz;
    double cy = (v[6 + ky] - f->org[ky]) - f->sy * cz;
    double e_bc = bx * cy - by * cx;
    double e_ca = cx * ay - cy * ax;
    double e_ab = ax * by - ay * bx;
    double bound = q->edge_bound;
    int negative = (e_bc < -bound) | (e_ca < -bound) | (e_ab < -bound);
    int positive = (e_bc > bound) | (e_ca > bound) | (e_ab > bound);
    if (negative & positive)
        return 0;
    /* z exactly as the exact test computes it: (p - org)[kz] * sz. */
    double za = az * f->sz, zb = bz * f->sz, zc = cz * f->sz;
    /* Comparisons, not fmin/fmax: those are libm calls without -ffast-math. */
    double z_min = za < zb ? za : zb, z_max = za < zb ? zb : za;
    z_min = zc < z_min ? zc : z_min;
    z_max = zc > z_max ? zc : z_max;
    double z_abs = -z_min > z_max ? -z_min : z_max;
    double slack = T_SLACK_ULPS * UNIT_ROUNDOFF * z_abs;
    return !(z_min - slack > t_hi || z_max + slack < t_lo);
}

/* The largest |coordinate| of face f's vertices. */
static double face_extent(const isect_mesh *m, int32_t f)
{
    const int32_t *c = m->idx + mesh_face_start(m, f);
    int size = mesh_face_size(m, f);
    double e = 0.0;
    for (int i = 0; i < size; i++)
        e = fmax_nan(e, max_abs3(mesh_vertex(m, c[i])));
    return e;
}

/* The exact crossing of face f's plane (the plane its test takes t from)
 * with the line of ray, in the scaled units of planar.h's *_crossing_xp. */
static void face_crossing_xp(const isect_mesh *m, const isect_ray *ray, int32_t f, int e,
                             int e_dir, xp *num, xp *den)
{
    const int32_t *c = m->idx + mesh_face_start(m, f);
    int size = mesh_face_size(m, f);
    if (size == 3)
        triangle_crossing_xp(ray, mesh_vertex(m, c[0]), mesh_vertex(m, c[1]),
                             mesh_vertex(m, c[2]), e, e_dir, num, den);
    else
        polygon_crossing_xp(ray, m->verts, c, size, e, e_dir, num, den);
}

/*
 * (a.t, a.prim) before (b.t, b.prim), where a t rounded alike is told apart
 * by the exact crossing parameters of the two faces (SPEC, accuracy
 * contract: the closest hit is the exactly closest one; a ray grazing a
 * silhouette edge enters one face and leaves the next within a fraction
 * of an ulp), and exactly equal ones by the face index. Both records are
 * hits, so neither face is parallel to the ray (den != 0); one scaling for
 * both faces lets core/ratio.c compare them exactly. Rounded ties are
 * rare, so the exact comparison costs nothing on the whole.
 */
static int hit_before(const query *q, const isect_hit *a, const isect_hit *b)
{
    if (a->t != b->t)
        return a->t < b->t;
    if (a->prim == b->prim)
        return 0;
    const isect_mesh *m = q->mesh;
    const isect_ray *ray = q->ray;
    double ext = fmax_nan(max_abs3(ray->org),
                          fmax_nan(face_extent(m, a->prim), face_extent(m, b->prim)));
    int e = pow2_exponent(ext), e_dir = pow2_exponent(max_abs3(ray->dir));
    xp na, da, nb, db;
    face_crossing_xp(m, ray, a->prim, e, e_dir, &na, &da);
    face_crossing_xp(m, ray, b->prim, e, e_dir, &nb, &db);
    int c = ratio_cmp(&na, &da, &nb, &db);
    return c != 0 ? c < 0 : a->prim < b->prim;
}

/* The max-heap of the best cap hits (by hit_before), at hits[0..n). */
static void heap_sift_down(const query *q, isect_hit *h, int64_t n, int64_t i)
{
    for (;;) {
        int64_t l = 2 * i + 1, r = l + 1, top = i;
        if (l < n && hit_before(q, &h[top], &h[l]))
            top = l;
        if (r < n && hit_before(q, &h[top], &h[r]))
            top = r;
        if (top == i)
            return;
        isect_hit tmp = h[i];
        h[i] = h[top];
        h[top] = tmp;
        i = top;
    }
}

static void heap_push(const query *q, isect_hit *h, int64_t n, const isect_hit *x)
{
    int64_t i = n;
    h[i] = *x;
    while (i > 0) {
        int64_t parent = (i - 1) / 2;
        if (!hit_before(q, &h[parent], &h[i]))
            return;
        isect_hit tmp = h[i];
        h[i] = h[parent];
        h[parent] = tmp;
        i = parent;
    }
}

/* In place ascending order of a max-heap of n hits. */
static void heap_sort(const query *q, isect_hit *h, int64_t n)
{
    for (int64_t end = n - 1; end > 0; end--) {
        isect_hit tmp = h[0];
        h[0] = h[end];
        h[end] = tmp;
        heap_sift_down(q, h, end, 0);
    }
}

/* Records a hit of the exact test that is in range and survives culling;
 * 1 when the traversal can stop (any hit). */
static int query_take(query *q, int mode, const isect_hit *h)
{
    switch (mode) {
    case QUERY_CLOSEST:
        if (!q->found || hit_before(q, h, &q->best)) {
            q->best = *h;
            q->found = 1;
            q->t_limit = h->t;
            slab_set_limit(q, h->t);
        }
        return 0;
    case QUERY_ALL: {
        int64_t kept = q->count < q->cap ? q->count : q->cap;
        if (q->count < q->cap) {
            heap_push(q, q->hits, kept, h);
        } else if (q->cap > 0 && hit_before(q, h, &q->hits[0])) {
            q->hits[0] = *h;
            heap_sift_down(q, q->hits, kept, 0);
        }
        q->count++;
        return 0;
    }
    default:
        q->best = *h;
        q->found = 1;
        return 1;
    }
}

/* The faces of one leaf; 1 when the traversal can stop. */
static ALWAYS_INLINE int query_leaf_body(query *q, int mode, int32_t first, int32_t count)
{
    const isect_mesh *m = q->mesh;
    const isect_ray *ray = q->ray;
    if (!q->frame_ready)
        query_leaf_init(q);
    for (int32_t i = 0; i < count; i++) {
        const mesh_prim *p = &q->prims[first + i];
        isect_hit h;
        int hit;
        if (p->nverts == 3) {
            if (!triangle_candidate(q, p->v, ray->tmin, q->t_limit))
                continue;
            /* The plane precomputed. Zero only where the exact normal
             * could not be rounded to a unit vector: never for a face of
             * nonzero area within the exact range (planar.h,
             * xp_normalize_up), and zero-area faces, which the exact test
             * never claims, are not in the BVH. */
            if (p->n[0] == 0.0 && p->n[1] == 0.0 && p->n[2] == 0.0)
                continue;
            int fast = q->fast_range >= 0 ? q->fast_range
                                          : triangle_fast_range(&q->lane, p->v, p->v + 3, p->v + 6);
            hit = triangle_hit(&q->frame, ray, &q->lane, fast, p->v, p->v + 3, p->v + 6, p->n, &h);
        } else {
            hit = polygon_hit_plane_framed(&q->frame, ray, m->verts,
                                           m->idx + mesh_face_start(m, p->face), p->nverts,
                                           ISECT_EVEN_ODD, &m->planes[p->face], &h);
        }
        /* The dispatcher's filter (hits_finish): NaN t never passes. */
        if (!hit || !(h.t >= ray->tmin && h.t <= ray->tmax))
            continue;
        if (q->cull_back && h.kind == ISECT_EXIT)
            continue;
        h.prim = p->face;
        if (query_take(q, mode, &h))
            return 1;
    }
    return 0;
}

/* The leaf loop, compiled for any x86-64 and (see MESH_AVX2) for AVX2 and
 * FMA, where the exact triangle test's nine fma are instructions instead
 * of libm calls; the walk's copy for each calls its own (query_leaf_for). */
static int query_leaf(query *q, int mode, int32_t first, int32_t count)
{
    return query_leaf_body(q, mode, first, count);
}

#if MESH_AVX2
MESH_TARGET_AVX2 static int query_leaf_avx2(query *q, int mode, int32_t first, int32_t count)
{
    return query_leaf_body(q, mode, first, count);
}
#endif

/* The leaf loop of the traversal's copy for any x86-64 (avx2 0) or for
 * AVX2 (avx2 1, a constant). */
static ALWAYS_INLINE int query_leaf_for(query *q, int mode, int32_t first, int32_t count,
                                        int avx2)
{
#if MESH_AVX2
    if (avx2)
        return query_leaf_avx2(q, mode, first, count);
#endif
    (void)avx2;
    return query_leaf(q, mode, first, count);
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

static void walker_init(walker *w)
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

#if MESH_SSE
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
static ALWAYS_INLINE unsigned node_test(const query *q, const bvh_node *n,
                                        float entry[BVH_WIDTH], int may_loose)
{
#if MESH_SSE
    unsigned mask = 0;
    for (int h = 0; h < BVH_WIDTH / 4; h++) {
        __m128 tn = _mm_set1_ps(q->slab_tmin), tf = _mm_set1_ps(q->slab_limit);
        __m128 loose = _mm_setzero_ps();
        if (may_loose && n->loose != 0) {
            loose = lane_mask4(((unsigned)n->loose >> (4 * h)) & 15u);
            tn = lane_select4(loose, tn, _mm_set1_ps(-INFINITY));
            tf = lane_select4(loose, tf, _mm_set1_ps(INFINITY));
        }
        /* Written out per axis (the compiler keeps the loop otherwise). */
#define SLAB_AXIS(k)                                                                      \
    tn = _mm_max_ps(                                                                      \
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node_plane(n, q->plane_offset[k]) + 4 * h),     \
                              _mm_set1_ps(q->slab_org_near[k])),                          \
                   _mm_set1_ps(q->slab_inv[k])),                                          \
        tn);                                                                              \
    tf = _mm_min_ps(                                                                      \
        _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node_plane(n, q->plane_offset[3 + k]) + 4 * h), \
                              _mm_set1_ps(q->slab_org_far[k])),                           \
                   _mm_set1_ps(q->slab_inv[k])),                                          \
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
        entry[c] = lc ? -INFINITY : q->slab_tmin;
        tf[c] = lc ? INFINITY : q->slab_limit;
    }
    for (int k = 0; k < 3; k++) {
        const float *near = node_plane(n, q->plane_offset[k]);
        const float *far = node_plane(n, q->plane_offset[3 + k]);
        float on = q->slab_org_near[k], of = q->slab_org_far[k];
        float inv = q->slab_inv[k];
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

#if MESH_AVX2
/* node_test with the eight children in one AVX register: the same float
 * operations lane by lane (vmaxps and vminps return the second operand for
 * a NaN as maxps and minps do), so the same mask and entries. Not forced
 * inline: it is inlined into the AVX2 copies of the traversal and never
 * runs elsewhere. */
MESH_TARGET_AVX2 static inline unsigned node_test_avx2(const query *q, const bvh_node *n,
                                                       float entry[BVH_WIDTH], int may_loose)
{
    __m256 tn = _mm256_broadcast_ss(&q->slab_tmin), tf = _mm256_broadcast_ss(&q->slab_limit);
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
        _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node_plane(n, q->plane_offset[k])),    \
                                    _mm256_broadcast_ss(&q->slab_org_near[k])),           \
                      _mm256_broadcast_ss(&q->slab_inv[k])),                              \
        tn);                                                                              \
    tf = _mm256_min_ps(                                                                   \
        _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node_plane(n, q->plane_offset[3 + k])), \
                                    _mm256_broadcast_ss(&q->slab_org_far[k])),            \
                      _mm256_broadcast_ss(&q->slab_inv[k])),                              \
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

/* Asks for the first 256 bytes at the memory reference r (as in
 * node_ref) points at: a whole inner node, or a leaf's first prims (two
 * and a half: most leaves hold one to three; the hardware prefetcher
 * follows a larger leaf's in-order reads). The same four lines for both,
 * with no loop over a leaf's lines, which cost more than it saved
 * (measured on the icosphere benchmark: 2-5 % faster on every ray set
 * than asking for every line of a leaf; picking the address by an integer
 * mask instead of the conditional, which compiles to a branch, was 3-4 %
 * slower). */
static ALWAYS_INLINE void prefetch_ref(const query *q, int32_t r)
{
    const char *at = r >= 0 ? (const char *)&q->nodes[r] : (const char *)&q->prims[~r];
    PREFETCH(at);
    PREFETCH(at + 128);
}

/*
 * A depth-first traversal, nearest child first, from where w stands: a
 * node's hit children are ordered by entry, the nearest visited next and
 * the others stacked (farthest deepest); a leaf's faces are tested; a
 * stacked subtree is dropped when the closest hit found since lies before
 * its entry. Returns 0 when the traversal is over. With yield set it also
 * stops (returning 1, w saved) each time it has moved to a child just
 * asked for: the batch then runs other traversals while that child's
 * memory arrives. Stacked references are not yielded on (they were asked
 * for when pushed). The state lives in locals in between (registers).
 *
 * walk is written once and compiled eight times: for the scalar queries
 * and for the batch (its yield argument), each with and without the loose
 * handling (may_loose), each for any x86-64 and for AVX2 (avx2), the three
 * a constant in each copy.
 */
static ALWAYS_INLINE int walk(query *q, walker *w, int mode, int yield, int may_loose,
                              int avx2)
{
    const bvh_node *nodes = q->nodes;
    int32_t ref = w->ref, count = w->count;
    int sp = w->sp;
    for (;;) {
        if (ref >= 0) {
            const bvh_node *n = &nodes[ref];
            float tn[BVH_WIDTH];
#if MESH_AVX2
            unsigned mask = avx2 ? node_test_avx2(q, n, tn, may_loose)
                                 : node_test(q, n, tn, may_loose);
#else
            unsigned mask = node_test(q, n, tn, may_loose);
            (void)avx2;
#endif
            if (mask != 0) {
                /* Every hit child's memory is asked for as it is met: the
                 * nearest is needed at once, the others when popped. Most
                 * visits hit one or two children: those without a sort;
                 * three or more by insertion. */
                int first = lowest_bit(mask);
                unsigned rest = mask & (mask - 1);
                ref = n->child[first];
                count = n->count[first];
                prefetch_ref(q, ref);
                if (rest != 0) {
                    node_ref a = { ref, count, tn[first] };
                    node_ref near;
                    if ((rest & (rest - 1)) == 0) {
                        int second = lowest_bit(rest);
                        node_ref b = { n->child[second], n->count[second], tn[second] };
                        prefetch_ref(q, b.ref);
                        int swap = b.entry < a.entry;
                        w->stack[sp++] = swap ? a : b;
                        near = swap ? b : a;
                    } else {
                        node_ref next[BVH_WIDTH];
                        next[0] = a;
                        int k = 1;
                        for (unsigned m = rest; m != 0; m &= m - 1) {
                            int c = lowest_bit(m);
                            node_ref r = { n->child[c], n->count[c], tn[c] };
                            prefetch_ref(q, r.ref);
                            int j = k++;
                            for (; j > 0 && next[j - 1].entry > r.entry; j--)
                                next[j] = next[j - 1];
                            next[j] = r;
                        }
                        for (int j = k - 1; j > 0; j--)
                            w->stack[sp++] = next[j];
                        near = next[0];
                    }
                    ref = near.ref;
                    count = near.count;
                }
                if (yield) {
                    w->ref = ref;
                    w->count = count;
                    w->sp = sp;
                    return 1;
                }
                continue;
            }
        } else if (count > 0 && query_leaf_for(q, mode, ~ref, count, avx2)) {
            return 0;
        }
        for (;;) {
            if (sp == 0)
                return 0;
            node_ref r = w->stack[--sp];
            if (!(r.entry > q->slab_limit)) {
                ref = r.ref;
                count = r.count;
                break;
            }
        }
    }
}

/* 1 when some node of the mesh is loose (the root's flags are the OR of
 * all): the traversal is compiled with and without the loose handling. */
static int mesh_has_loose(const isect_mesh *m)
{
    return m->tree.nodes[0].loose != 0;
}

#if MESH_AVX2
MESH_TARGET_AVX2 static void query_run_avx2(query *q, walker *w, int mode)
{
    if (mesh_has_loose(q->mesh))
        walk(q, w, mode, 0, 1, 1);
    else
        walk(q, w, mode, 0, 0, 1);
}
#endif

/* The whole traversal of q, by the copy for AVX2 when avx2 is set (the
 * caller's cpu_has_avx2_fma, asked once per call or batch). */
static void query_run(query *q, int mode, int avx2)
{
    walker w;
    walker_init(&w);
#if MESH_AVX2
    if (avx2) {
        query_run_avx2(q, &w, mode);
        return;
    }
#else
    (void)avx2;
#endif
    if (mesh_has_loose(q->mesh))
        walk(q, &w, mode, 0, 1, 0);
    else
        walk(q, &w, mode, 0, 0, 0);
}

int64_t mesh_hits_all(const isect_shape *s, const isect_ray *ray,
                      const isect_params *prm, isect_hit *hits, int64_t cap)
{
    query q;
    query_init(&q, s->mesh, ray, prm);
    if (!(ray->tmin <= ray->tmax))
        return 0;
    if (prm->flags & ISECT_ANY_HIT) {
        /* Occlusion: the first hit found, as mesh_hit_first gives it. */
        query_run(&q, QUERY_ANY, cpu_has_avx2_fma());
        if (q.found && cap > 0)
            hits[0] = q.best;
        return q.found;
    }
    q.hits = hits;
    q.cap = cap;
    query_run(&q, QUERY_ALL, cpu_has_avx2_fma());
    heap_sort(&q, hits, q.count < cap ? q.count : cap);
    return q.count;
}

int mesh_hit_first(const isect_shape *s, const isect_ray *ray,
                   const isect_params *prm, isect_hit *out)
{
    query q;
    query_init(&q, s->mesh, ray, prm);
    if (!(ray->tmin <= ray->tmax))
        return 0;
    int mode = (prm->flags & ISECT_ANY_HIT) ? QUERY_ANY : QUERY_CLOSEST;
    query_run(&q, mode, cpu_has_avx2_fma());
    if (q.found)
        *out = q.best;
    return q.found;
}

/* ---------------------------------------------------------------- batch
 *
 * isect_intersect_batch for a mesh (the family's first_batch): closest (or
 * any) hits of many rays, BATCH_LANES traversals in flight at once, taking
 * one step each in turn. A large mesh's traversal waits on one cache miss
 * per node; the prefetch a step issues for its next node completes while
 * the other lanes step, so the misses of several rays overlap.
 *
 * A ray that follows its predecessor closely (ray_follows: coherent rays,
 * such as a camera's neighbouring pixels) is instead traced at once, start
 * to end: it visits nearly the nodes and faces the predecessor has just
 * brought into cache, so there are no misses to overlap, and interleaving
 * it with other traversals would only cost the stepping and the branch
 * predictor's memory of the path (measured: the camera rays of
 * bench_mesh on 82k triangles take 20 % longer in lanes than traced at
 * once, random rays 30-50 % longer traced at once). So is every ray of a
 * mesh whose nodes and faces take less than LANES_MIN_BYTES: its
 * traversals find most of what they need in cache anyway (measured on
 * icospheres, random rays, against lanes: 4-7 % faster at 5,120
 * triangles, 0.8 MB, and 1-4 % at 20,480, 3 MB; 14 % slower at 81,920,
 * 12 MB; on a CPU with a 16 MB L3).
 *
 * Either way each ray runs exactly the steps mesh_hit_first runs
 * (query_init, the tmin > tmax miss, query_run's steps, at once or one at a
 * time; no traversal state is shared between rays, ray_follows only picks
 * which way), and each ray passes ray_check, xform_object_ray,
 * batch_record and xform_hits_to_world as batch.c's per-ray loop over
 * shape_ray_first does, so every record and the returned count are bit for
 * bit that loop's. Rays finish out of order; each writes only its own
 * record.
 */
#define BATCH_LANES 8
#define LANES_MIN_BYTES ((int64_t)6 << 20)

/* Rays count as close when they stay within 2^-7 of the mesh box's largest
 * side of each other across the box (see ray_follows). */
#define FOLLOW_REACH 0x1p-7

typedef struct lane {
    query     q;
    walker    w;
    isect_ray object; /* the transformed ray, if the shape has a transform */
    int64_t   index;
} lane;

/* What the batch's rays share: the input, the output, and what ray_follows
 * needs (the mesh box, the previous ray started). */
typedef struct batch {
    const isect_shape  *s;
    const isect_ray    *rays;
    int64_t             n, next, hit_count;
    const isect_params *prm;
    isect_hit          *closest;
    int                 mode;
    double              center[3], extent; /* the mesh box (extent: largest side) */
    double              prev_org[3], prev_dir[3]; /* the last ray started (object
                                                     space); NaN before the first */
    int                 direct_only;       /* 1: every ray traced at once */
    int                 avx2;              /* cpu_has_avx2_fma() */
} batch;

/* The mesh box from the root's children (empty children have lo > hi).
 * Out-of-range coordinates give an infinite or NaN extent: ray_follows
 * then says no, and every ray runs in a lane. */
static void batch_mesh_box(batch *b, const isect_mesh *m)
{
    const bvh_node *root = &m->tree.nodes[0];
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int c = 0; c < BVH_WIDTH; c++)
        for (int k = 0; k < 3; k++) {
            double l = root->bounds[k][c], h = root->bounds[3 + k][c];
            if (l <= h) {
                lo[k] = l < lo[k] ? l : lo[k];
                hi[k] = h > hi[k] ? h : hi[k];
            }
        }
    b->extent = 0.0;
    for (int k = 0; k < 3; k++) {
        b->center[k] = 0.5 * lo[k] + 0.5 * hi[k];
        b->extent = hi[k] - lo[k] > b->extent ? hi[k] - lo[k] : b->extent;
    }
    if (!(b->extent < INFINITY))
        b->extent = NAN;
}

/* 1 when ray r stays close to the previous ray across the mesh box: with
 * origins dO apart (max norm) and directions at angle a, the rays are at
 * most dO + sin(a) L apart within the box, L = max|o - center| + extent
 * bounding the distance from o to any point of it; sin(a) = |d x p| /
 * (|d| |p|) <= sqrt(3) |d x p|_max / (max|d| max|p|). Same heading only
 * (d . p > 0). Written without a division; a NaN or overflow says no. Only
 * the speed depends on it. */
static int ray_follows(const batch *b, const isect_ray *r)
{
    const double *o = r->org, *d = r->dir, *po = b->prev_org, *pd = b->prev_dir;
    double reach = FOLLOW_REACH * b->extent;
    /* Origins apart by more than the reach: no (most incoherent rays). */
    double v[3];
    v3_sub(v, o, po);
    double gap = v3_max_abs_finite(v);
    if (!(gap <= reach))
        return 0;
    /* Straight-line code (vec3.h): every coherent ray pays for this, and a
     * loop over k with (k + 1) % 3 indices stayed a loop (a third of the
     * set-up of a ray that misses the mesh). The first ray meets the NaN
     * prev_org: gap is NaN and the answer no. */
    v3_cross(v, d, pd);
    double cross = v3_max_abs_finite(v);
    v3_sub(v, o, b->center);
    double span = v3_max_abs_finite(v);
    double norms = v3_max_abs_finite(d) * v3_max_abs_finite(pd);
    double dot = v3_dot(d, pd);
    return dot > 0.0
        && gap * norms + 1.7320508075688773 * cross * (span + b->extent) <= reach * norms;
}

/* The record of lane l's finished traversal; its hit count (0 or 1). */
static int64_t lane_finish(const lane *l, const batch *b)
{
    isect_hit *out = &b->closest[l->index];
    int found = l->q.found;
    if (found) {
        *out = l->q.best;
        xform_hits_to_world(b->s->xform, out, 1);
    }
    return batch_record(out, found);
}

/* Starts the next ray that needs a traversal in lane l, writing the
 * records of the ones that do not (misses or invalid: none counts as a
 * hit) and tracing those that follow their predecessor at once; 0 when
 * there is none left. */
static int lane_start(lane *l, batch *b)
{
    while (b->next < b->n) {
        int64_t i = b->next++;
        const isect_ray *r = &b->rays[i];
        int status = ray_check(r);
        if (status == ISECT_OK)
            status = xform_object_ray(b->s->xform, r, &l->object, &r);
        if (status != ISECT_OK) {
            batch_record(&b->closest[i], status);
            continue;
        }
        /* mesh_hit_first's early miss: found 0. */
        if (!(r->tmin <= r->tmax)) {
            batch_record(&b->closest[i], 0);
            continue;
        }
        query_init(&l->q, b->s->mesh, r, b->prm);
        l->index = i;
        int follows = ray_follows(b, r);
        memcpy(b->prev_org, r->org, sizeof b->prev_org);
        memcpy(b->prev_dir, r->dir, sizeof b->prev_dir);
        if (!follows && !b->direct_only) {
            walker_init(&l->w);
            return 1;
        }
        query_run(&l->q, b->mode, b->avx2); /* as mesh_hit_first */
        b->hit_count += lane_finish(l, b);
    }
    return 0;
}

/* The batch loop over lanes[count] (count <= BATCH_LANES), compiled with
 * and without the loose handling, for any x86-64 and for AVX2. */
static ALWAYS_INLINE int64_t batch_run(batch *b, lane *lanes, int count, int may_loose,
                                       int avx2)
{
    int active[BATCH_LANES], live = 0;
    for (int l = 0; l < count; l++) {
        active[l] = lane_start(&lanes[l], b);
        live += active[l];
    }
    while (live > 0) {
        for (int l = 0; l < count; l++) {
            if (!active[l] || walk(&lanes[l].q, &lanes[l].w, b->mode, 1, may_loose, avx2))
                continue;
            b->hit_count += lane_finish(&lanes[l], b);
            active[l] = lane_start(&lanes[l], b);
            live -= !active[l];
        }
    }
    return b->hit_count;
}

#if MESH_AVX2
MESH_TARGET_AVX2 static int64_t batch_run_avx2(batch *b, lane *lanes, int count)
{
    if (mesh_has_loose(b->s->mesh))
        return batch_run(b, lanes, count, 1, 1);
    return batch_run(b, lanes, count, 0, 1);
}
#endif

int64_t mesh_hit_first_batch(const isect_shape *s,
                             const isect_ray *rays, int64_t n, const isect_params *prm,
                             isect_hit *closest)
{
    batch b;
    b.s = s;
    b.rays = rays;
    b.n = n;
    b.next = 0;
    b.hit_count = 0;
    b.prm = prm;
    b.closest = closest;
    b.mode = (prm->flags & ISECT_ANY_HIT) ? QUERY_ANY : QUERY_CLOSEST;
    b.avx2 = cpu_has_avx2_fma();
    for (int k = 0; k < 3; k++)
        b.prev_org[k] = b.prev_dir[k] = NAN;
    batch_mesh_box(&b, s->mesh);
    /* The lanes (7 KB each, mostly the traversal stack) on the heap, not
     * on a thread's stack, for a mesh of at least LANES_MIN_BYTES; for a
     * smaller one, or without memory, every ray is traced at once in one
     * lane on the stack (the same records, without the overlap). A test
     * build defines ISECT_TEST_NO_LANES to take that path always. */
    int64_t bytes = mesh_traversal_bytes(s->mesh);
    int count = n < BATCH_LANES ? (int)n : BATCH_LANES;
#ifdef ISECT_TEST_NO_LANES
    lane *lanes = NULL;
    (void)bytes;
#else
    lane *lanes = count > 0 && bytes >= LANES_MIN_BYTES ? malloc((size_t)count * sizeof *lanes)
                                                        : NULL;
#endif
    lane one;
    b.direct_only = lanes == NULL;
    if (lanes == NULL) {
        lanes = &one;
        count = 1;
    }
    int64_t hits;
#if MESH_AVX2
    if (b.avx2)
        hits = batch_run_avx2(&b, lanes, count);
    else
#endif
    if (mesh_has_loose(s->mesh))
        hits = batch_run(&b, lanes, count, 1, 0);
    else
        hits = batch_run(&b, lanes, count, 0, 0);
    if (lanes != &one)
        free(lanes);
    return hits;
}

/* ------------------------------------------------------------ containment
 *
 * p is inside when it lies on the surface (the solid is a closed set, as
 * the analytic solids are) or when the fixed ray from p in +x crosses the
 * surface an odd number of times. Every decision is exact on the input as
 * given (no rounded projection): in the +x frame a point's 2D coordinates
 * are its own (y, z), so orient2_sign_perturbed can take p's (y, z) as the
 * query point and the perturbed line through it crosses each fan triangle
 * or not, consistently across shared edges; orient3_sign then says on
 * which side of p the crossing is. A claimed fan triangle whose plane
 * passes through p has p in it (closed) and is found by the on-surface
 * test instead; it is not a crossing beyond p.
 */

/* The +x ray's 2D coordinates of a point. */
static void yz_of(const double v[3], double out[2])
{
    out[0] = v[1];
    out[1] = v[2];
}

/* 1 when p lies in the closed triangle a, b, c (exactly); 0 also for a
 * triangle of zero area. */
static int point_in_closed_triangle(const double a[3], const double b[3], const double c[3],
                                    const double p[3])
{
    if (orient3_sign(a, b, c, p) != 0)
        return 0;
    /* A coordinate plane onto which the triangle projects with nonzero
     * area: its normal's largest component (approximately) first. */
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
    }
    n[0] = fabs(e1[1] * e2[2] - e1[2] * e2[1]);
    n[1] = fabs(e1[2] * e2[0] - e1[0] * e2[2]);
    n[2] = fabs(e1[0] * e2[1] - e1[1] * e2[0]);
    int order[3] = { 0, 1, 2 };
    for (int i = 1; i < 3; i++)
        for (int j = i; j > 0 && n[order[j]] > n[order[j - 1]]; j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    for (int i = 0; i < 3; i++) {
        int drop = order[i], u = (drop + 1) % 3, w = (drop + 2) % 3;
        const double a2[2] = { a[u], a[w] }, b2[2] = { b[u], b[w] }, c2[2] = { c[u], c[w] };
        const double p2[2] = { p[u], p[w] };
        int s = orient2_sign(a2, b2, c2);
        if (s == 0)
            continue;
        return orient2_sign(a2, b2, p2) != -s && orient2_sign(b2, c2, p2) != -s
            && orient2_sign(c2, a2, p2) != -s;
    }
    return 0;
}

/* 1 when p lies on the closed segment a-b. */
static int point_on_segment(const double a[3], const double b[3], const double p[3])
{
    for (int k = 0; k < 3; k++)
        if (p[k] < (a[k] < b[k] ? a[k] : b[k]) || p[k] > (a[k] < b[k] ? b[k] : a[k]))
            return 0;
    return collinear3(a, b, p);
}

/* The face's vertex i. */
static const double *face_vertex(const isect_mesh *m, const mesh_prim *pr, int i)
{
    if (pr->nverts == 3)
        return pr->v + 3 * i;
    return mesh_vertex(m, m->idx[mesh_face_start(m, pr->face) + i]);
}

/* p on the closed face: for a triangle, in it; for a polygon, on one of its
 * edges, or on one of its fan triangles and inside its outline seen along
 * that triangle's normal (the even-odd rule, with the library's perturbed
 * rule for points on a projected edge line). For a planar polygon this is
 * exactly the closed polygon; fold regions of a concave fan (covered twice,
 * with opposite orientations) are excluded. */
static int point_on_face(const isect_mesh *m, const mesh_prim *pr, const double p[3])
{
    int n = pr->nverts;
    if (n == 3)
        return point_in_closed_triangle(pr->v, pr->v + 3, pr->v + 6, p);
    for (int i = 0; i < n; i++)
        if (point_on_segment(face_vertex(m, pr, i), face_vertex(m, pr, (i + 1) % n), p))
            return 1;
    const double *v0 = face_vertex(m, pr, 0);
    for (int i = 1; i + 1 < n; i++) {
        const double *b = face_vertex(m, pr, i), *c = face_vertex(m, pr, i + 1);
        if (!point_in_closed_triangle(v0, b, c, p))
            continue;
        /* Project along the axis of the fan triangle's largest normal
         * component (nonzero: the triangle has area). */
        double e1[3], e2[3], nrm[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = b[k] - v0[k];
            e2[k] = c[k] - v0[k];
        }
        nrm[0] = fabs(e1[1] * e2[2] - e1[2] * e2[1]);
        nrm[1] = fabs(e1[2] * e2[0] - e1[0] * e2[2]);
        nrm[2] = fabs(e1[0] * e2[1] - e1[1] * e2[0]);
        int drop = nrm[1] > nrm[0] ? 1 : 0;
        drop = nrm[2] > nrm[drop] ? 2 : drop;
        int u = (drop + 1) % 3, w = (drop + 2) % 3;
        const double p2[2] = { p[u], p[w] };
        int32_t winding = 0;
        const double *prev = face_vertex(m, pr, n - 1);
        for (int j = 0; j < n; j++) {
            const double *cur = face_vertex(m, pr, j);
            const double q0[2] = { prev[u], prev[w] }, q1[2] = { cur[u], cur[w] };
            winding += winding_edge(q0, q1, p2);
            prev = cur;
        }
        return fill_rule_inside(winding, ISECT_EVEN_ODD);
    }
    return 0;
}

/* The crossing of the perturbed +x ray from p with fan triangle a, b, c
 * beyond p: 0 for none; else the sign of the triangle's normal's x
 * component (+1: the ray leaves through the triangle's front, -1: it
 * enters through it). */
static int fan_crossing(const double a[3], const double b[3], const double c[3],
                        const double p[3], const double p2[2])
{
    /* Cheap rejections first: the triangle's (y, z) box must hold p's
     * (y, z) (a point strictly outside stays outside when perturbed), and
     * some vertex must lie at x >= p.x. */
    if ((a[1] < p[1] && b[1] < p[1] && c[1] < p[1]) || (a[1] > p[1] && b[1] > p[1] && c[1] > p[1])
        || (a[2] < p[2] && b[2] < p[2] && c[2] < p[2]) || (a[2] > p[2] && b[2] > p[2] && c[2] > p[2])
        || (a[0] < p[0] && b[0] < p[0] && c[0] < p[0]))
        return 0;
    double a2[2], b2[2], c2[2];
    yz_of(a, a2);
    yz_of(b, b2);
    yz_of(c, c2);
    int s = orient2_sign_perturbed(a2, b2, p2);
    if (s == 0 || orient2_sign_perturbed(b2, c2, p2) != s
        || orient2_sign_perturbed(c2, a2, p2) != s)
        return 0;
    /* Claimed; s is the sign of the normal's x component, so the crossing
     * lies beyond p exactly when det(a-p, b-p, c-p) has the sign s. */
    return orient3_sign(a, b, c, p) == s ? s : 0;
}

int mesh_crossing_count(const isect_mesh *m, const double p[3], int64_t *count)
{
    const bvh_node *nodes = m->tree.nodes;
    double p2[2];
    yz_of(p, p2);
    int32_t stack[BVH_STACK_SIZE];
    int sp = 0;
    int32_t cur = 0;
    int64_t crossings = 0;
    for (;;) {
        const bvh_node *n = &nodes[cur];
        /* Children met by the ray from p in +x, or holding p: closed boxes
         * (conservative, the perturbation being infinitesimal). */
        for (int c = 0; c < BVH_WIDTH; c++) {
            if (!(n->bounds[1][c] <= p[1] && p[1] <= n->bounds[4][c]
                  && n->bounds[2][c] <= p[2] && p[2] <= n->bounds[5][c]
                  && p[0] <= n->bounds[3][c]))
                continue;
            if (n->child[c] >= 0) {
                stack[sp++] = n->child[c];
                continue;
            }
            int32_t first = ~n->child[c];
            for (int i = 0; i < n->count[c]; i++) {
                const mesh_prim *pr = &m->prims[first + i];
                int nv = pr->nverts;
                /* On the surface: the closed set says inside. Only faces
                 * whose box holds p can hold it. */
                double lo[3], hi[3];
                for (int k = 0; k < 3; k++)
                    lo[k] = hi[k] = face_vertex(m, pr, 0)[k];
                for (int j = 1; j < nv; j++) {
                    const double *v = face_vertex(m, pr, j);
                    for (int k = 0; k < 3; k++) {
                        lo[k] = v[k] < lo[k] ? v[k] : lo[k];
                        hi[k] = v[k] > hi[k] ? v[k] : hi[k];
                    }
                }
                if (lo[0] <= p[0] && p[0] <= hi[0] && lo[1] <= p[1] && p[1] <= hi[1]
                    && lo[2] <= p[2] && p[2] <= hi[2] && point_on_face(m, pr, p))
                    return 1;
                const double *v0 = face_vertex(m, pr, 0);
                for (int j = 1; j + 1 < nv; j++)
                    crossings += fan_crossing(v0, face_vertex(m, pr, j), face_vertex(m, pr, j + 1),
                                              p, p2);
            }
        }
        if (sp == 0)
            break;
        cur = stack[--sp];
    }
    *count = crossings;
    return 0;
}

/* The rules (isect_shape.flags): EVEN_ODD, the parity of the crossings;
 * NONZERO, a nonzero integer winding number (oriented meshes); WINDING,
 * w >= 1/2 in world space (a mirroring transform negates w), exact on an
 * oriented mesh, else the directly summed generalized winding number. A
 * point on a closed mesh's surface is inside (closed sets). */
int mesh_contains(const isect_shape *s, const double p[3])
{
    const isect_mesh *m = s->mesh;
    int orientation = s->xform != NULL ? xform_orientation(s->xform) : 1;
    if (s->flags == ISECT_WINDING && !m->oriented) {
        if (s->xform != NULL && !xform_is_similarity(s->xform)) {
            /* solid angles bend under this transform: summed over the
             * faces' world images, at p's (its world point, round trip) */
            double world[3];
            xform_point_to_world(s->xform, p, world);
            return mesh_winding_direct_world(m, s->xform, world) >= 0.5;
        }
        return orientation * mesh_winding_direct(m, p, NULL) >= 0.5;
    }
    int64_t count;
    if (mesh_crossing_count(m, p, &count))
        return 1;
    return s->flags == ISECT_EVEN_ODD ? (int)(count & 1)
         : s->flags == ISECT_NONZERO  ? count != 0
                                      : orientation * count >= 1;
}
