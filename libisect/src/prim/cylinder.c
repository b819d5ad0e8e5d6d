/* SPDX-License-Identifier: Apache-2.0 */
/*
 * cylinder.c — the finite cylinder of radius r around the segment p0-p1
 * (ISECT_CYLINDER, data = p0[3], p1[3], r; flags ISECT_CAPPED or 0) and the
 * infinite cylinder around the line p + s*axis (ISECT_CYLINDER_INF, data =
 * p[3], axis[3], r).
 *
 * The side, as in the seeds: project onto the plane across the axis. With a
 * the axis vector and f = org - p0, the cross products
 *     m = f x a,   n = dir x a
 * are the projected origin and direction turned by 90 degrees and scaled by
 * |a|, so the side along the line is the quadratic (core/quad_line.h)
 *     Q(t) = |m + t n|^2 - r^2 |a|^2:  A = n.n,  B = m.n,  C = m.m - r^2 a.a,
 *     G = B^2 - A C = a.a (r^2 A - (f.n)^2)
 * (|m x n| = |a| |f.n|: the discriminant as the distance between the line
 * and the axis, free of the cancellation of B^2 - AC for a ray from afar).
 * Caps: the planes (x - p0).a = 0 and (x - p1).a = 0, crossed at
 * t = -F0/D and -F1/D, F0 = f.a, F1 = (org - p1).a, D = dir.a.
 *
 * Numerics. Positions (org, p0, p1, r) share the power of two that brings
 * the largest into [0.5, 1); dir and the infinite cylinder's axis get their
 * own (all exact). f, org - p1 and a are exact as double-doubles; every
 * quantity above is formed as a double-double with an error bound
 * (core/ddx.h), the side roots are certified by quad_line_certify, and every
 * decision — parallel or not, which end of the solid is the latest entry or
 * earliest exit, in [tmin, tmax] or not — is taken on the certified values
 * where their bounds separate them, and exactly otherwise (the same
 * quantities as expansions, built once per ray when first needed; a side
 * root against a cap by quad_line_cmp). So the decisions are exact, and
 * each t is within 1.5 ulp of its exact value.
 *
 * Rules (isect.h):
 *  - Side tangency: |G| <= eps r^2 a.a A (|r^2 - h^2| <= eps r^2, h the
 *    distance between the line and the axis): one TOUCH at -B/A.
 *  - Parallel to the axis, |dir x a| <= eps |dir| |a| (A <= eps^2 d.d a.a):
 *    the side is not hit; the line is inside the infinite solid iff C <= 0.
 *  - Capped: a convex solid, the side's interval intersected with the slab
 *    between the cap planes. A cap plane parallel to the ray by the epsilon
 *    policy, |D| <= eps |dir| |a|, is not crossed and constrains by the side
 *    the origin is on (on the plane = inside), as a convex-polyhedron face.
 *    Entry = the latest entry, exit = the earliest exit; ties go to the
 *    lowest prim (side 0 before the caps 1, 2: a ray through the rim is
 *    reported on the side); entry == exit is one TOUCH with the entry's prim
 *    and normal.
 *  - Open: the side only, a thin surface with the outward radial normal,
 *    each crossing kept when it lies between the cap planes (closed; no
 *    epsilon: D == 0 exactly means the slab test is the origin's).
 *  - r = 0 or p0 == p1 (axis = 0): degenerate, no hits, nothing inside.
 *
 * Records: t from the double-double root; the point org + t dir from it
 * (hit_set_dd); the side's normal unit(a x (m + t n)), radial at the exact
 * point to a few ulps; a cap's normal -+unit(a).
 */
#include "prim/prim.h"
#include "prim/cylinder_lanes.h"
#include "core/ddx.h"
#include "core/expansion.h"
#include "core/quad_line.h"
#include "core/ratio.h"
#include "core/scaling.h"
#include "core/vec3.h"

/* The problem in scaled units; t = t' * 2^t_shift. */
typedef struct cyl_frame {
    ddx    f[3];    /* org - p0 (exact) */
    ddx    g[3];    /* org - p1 (exact; the infinite cylinder: f) */
    ddx    a[3];    /* axis (exact) */
    double d[3];    /* dir */
    double r;
    int    t_shift;
} cyl_frame;

/* The positions' exponent e, scaled copies of org and dir (dir may be NULL:
 * containment only). */
static void frame_common(cyl_frame *fr, int e, const double org[3], const double dir[3],
                         double o_s[3])
{
    int e_dir = dir != NULL ? pow2_exponent(max_abs3(dir)) : 0;
    scale3(o_s, org, e);
    for (int k = 0; k < 3; k++)
        fr->d[k] = dir != NULL ? pow2_scale(dir[k], -e_dir) : 0.0;
    fr->t_shift = e - e_dir;
}

/* Finite cylinder frame. 0 when degenerate. */
static int frame_finite(const double *data, const double org[3], const double dir[3],
                        cyl_frame *fr)
{
    const double *p0 = data, *p1 = data + 3;
    double r = data[6];
    int e = pow2_exponent(fmax_nan(fmax_nan(r, max_abs3(org)), fmax_nan(max_abs3(p0), max_abs3(p1))));
    double o_s[3];
    frame_common(fr, e, org, dir, o_s);
    int zero_axis = 1;
    for (int k = 0; k < 3; k++) {
        double p0k = pow2_scale(p0[k], -e), p1k = pow2_scale(p1[k], -e);
        fr->f[k] = ddx_diff(o_s[k], p0k);
        fr->g[k] = ddx_diff(o_s[k], p1k);
        fr->a[k] = ddx_diff(p1k, p0k);
        zero_axis &= fr->a[k].hi == 0.0;
    }
    fr->r = pow2_scale(r, -e);
    return fr->r > 0.0 && !zero_axis;
}

/* Infinite cylinder frame; the axis is a direction with its own scale. */
static int frame_infinite(const double *data, const double org[3], const double dir[3],
                          cyl_frame *fr)
{
    const double *p = data, *axis = data + 3;
    double r = data[6];
    int e = pow2_exponent(fmax_nan(r, fmax_nan(max_abs3(org), max_abs3(p))));
    int e_axis = pow2_exponent(max_abs3(axis));
    double o_s[3];
    frame_common(fr, e, org, dir, o_s);
    for (int k = 0; k < 3; k++) {
        fr->f[k] = ddx_diff(o_s[k], pow2_scale(p[k], -e));
        fr->g[k] = fr->f[k];
        fr->a[k] = ddx_of(pow2_scale(axis[k], -e_axis));
    }
    fr->r = pow2_scale(r, -e);
    return fr->r > 0.0 && max_abs3(axis) > 0.0;
}

static ddx ddx_dot3(const ddx x[3], const ddx y[3])
{
    return ddx_add(ddx_add(ddx_mul(x[0], y[0]), ddx_mul(x[1], y[1])), ddx_mul(x[2], y[2]));
}

static void ddx_cross3(ddx out[3], const ddx x[3], const ddx y[3])
{
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        out[k] = ddx_sub(ddx_mul(x[i], y[j]), ddx_mul(x[j], y[i]));
    }
}

/* The same quantities as exact expansions. */
typedef struct cyl_exact {
    xp a, b, c, thr;  /* the side's line function, the tangency threshold */
    xp par;           /* A - eps^2 d.d a.a (<= 0: parallel to the axis) */
    xp f0, f1, dot;   /* F0, F1, D */
    xp aa, dd;        /* a.a, d.d */
} cyl_exact;

static void exact_make(const cyl_frame *fr, double eps, cyl_exact *x)
{
    xp f[3], a[3], m[3], n[3], tmp;
    xp_set(&x->f0, 0.0);
    xp_set(&x->f1, 0.0);
    xp_set(&x->dot, 0.0);
    xp_set(&x->aa, 0.0);
    xp_set(&x->dd, 0.0);
    for (int k = 0; k < 3; k++) {
        xp g;
        xp_set2(&f[k], fr->f[k].hi, fr->f[k].lo);
        xp_set2(&g, fr->g[k].hi, fr->g[k].lo);
        xp_set2(&a[k], fr->a[k].hi, fr->a[k].lo);
        xp_add_mul(&x->f0, &f[k], &a[k]);
        xp_add_mul(&x->f1, &g, &a[k]);
        xp_add_mul(&x->aa, &a[k], &a[k]);
        xp_scale(&tmp, &a[k], fr->d[k]);
        xp_add(&x->dot, &x->dot, &tmp);
        xp_set(&tmp, fr->d[k]);
        xp_scale(&tmp, &tmp, fr->d[k]);
        xp_add(&x->dd, &x->dd, &tmp);
    }
    xp_set(&x->a, 0.0);
    xp_set(&x->b, 0.0);
    xp_set(&x->c, 0.0);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        xp_mul(&m[k], &f[i], &a[j]);
        xp_mul(&tmp, &f[j], &a[i]);
        xp_sub(&m[k], &m[k], &tmp);
        xp_scale(&n[k], &a[j], fr->d[i]);
        xp_scale(&tmp, &a[i], fr->d[j]);
        xp_sub(&n[k], &n[k], &tmp);
        xp_add_mul(&x->a, &n[k], &n[k]);
        xp_add_mul(&x->b, &m[k], &n[k]);
        xp_add_mul(&x->c, &m[k], &m[k]);
    }
    xp rr;
    xp_set(&rr, fr->r);
    xp_scale(&rr, &rr, fr->r);
    xp_mul(&tmp, &rr, &x->aa);   /* r^2 a.a */
    xp_sub(&x->c, &x->c, &tmp);
    xp_mul(&x->thr, &tmp, &x->a);
    xp_scale(&x->thr, &x->thr, eps);
    xp_mul(&tmp, &x->dd, &x->aa);
    xp_scale(&tmp, &tmp, eps);
    xp_scale(&tmp, &tmp, eps);
    xp_sub(&x->par, &x->a, &tmp);
}

/* One ray against one cylinder: the certified quantities, and the exact
 * ones once a decision needs them. */
typedef struct cyl_line {
    const cyl_frame *fr;
    double eps;
    quad_line_dd side;   /* A, B, C, G, T */
    ddx m[3], n[3];
    ddx f0, f1, dot, aa, dd;
    cyl_exact *x;        /* NULL until needed */
    cyl_exact storage;
} cyl_line;

static void line_make(const cyl_frame *fr, double eps, cyl_line *ln)
{
    ln->fr = fr;
    ln->eps = eps;
    ln->x = NULL;
    ddx d[3] = { ddx_of(fr->d[0]), ddx_of(fr->d[1]), ddx_of(fr->d[2]) };
    ddx_cross3(ln->m, fr->f, fr->a);
    ddx_cross3(ln->n, d, fr->a);
    ln->aa = ddx_dot3(fr->a, fr->a);
    ln->dd = ddx_dot3(d, d);
    ln->f0 = ddx_dot3(fr->f, fr->a);
    ln->f1 = ddx_dot3(fr->g, fr->a);
    ln->dot = ddx_dot3(d, fr->a);
    ddx a = ddx_dot3(ln->n, ln->n), b = ddx_dot3(ln->m, ln->n);
    ddx rr = ddx_sqr(ddx_of(fr->r));
    ddx rr_aa = ddx_mul(rr, ln->aa);
    ddx c = ddx_sub(ddx_dot3(ln->m, ln->m), rr_aa);
    ddx fn = ddx_dot3(fr->f, ln->n);
    ddx g = ddx_mul(ln->aa, ddx_sub(ddx_mul(rr, a), ddx_sqr(fn)));
    ln->side = (quad_line_dd){ a, b, c, g, 0.0, 0.0 };
    ln->side.t_thr = eps * (ddx_abs(rr_aa) + rr_aa.err) * (ddx_abs(a) + a.err) * (1.0 + 8.0 * DDX_U);
}

static const cyl_exact *line_exact(cyl_line *ln)
{
    if (ln->x == NULL) {
        exact_make(ln->fr, ln->eps, &ln->storage);
        ln->x = &ln->storage;
    }
    return ln->x;
}

/* The sign of a certified quantity, 2 when its bound straddles 0. */
static int ddx_sign_certain(ddx v)
{
    if (fabs(v.hi) * (1.0 - 2.0 * DDX_U) > v.err)
        return v.hi > 0.0 ? 1 : -1;
    return v.err == 0.0 ? (v.hi > 0.0) - (v.hi < 0.0) : 2;
}

/* The quantities whose signs decide (certified, else exact). */
enum { Q_C, Q_F0, Q_F1, Q_DOT, Q_AXIS_PARALLEL, Q_CAP_PARALLEL };

static int sign_of(cyl_line *ln, int which)
{
    ddx v;
    switch (which) {
    case Q_C:  v = ln->side.c; break;
    case Q_F0: v = ln->f0; break;
    case Q_F1: v = ln->f1; break;
    case Q_DOT: v = ln->dot; break;
    case Q_AXIS_PARALLEL: /* A - eps^2 d.d a.a */
        v = ddx_sub(ln->side.a, ddx_mul(ddx_mul(ln->dd, ln->aa), ddx_sqr(ddx_of(ln->eps))));
        break;
    default: /* Q_CAP_PARALLEL: D^2 - eps^2 d.d a.a */
        v = ddx_sub(ddx_sqr(ln->dot), ddx_mul(ddx_mul(ln->dd, ln->aa), ddx_sqr(ddx_of(ln->eps))));
        break;
    }
    int sign = ddx_sign_certain(v);
    if (sign != 2)
        return sign;
    const cyl_exact *x = line_exact(ln);
    switch (which) {
    case Q_C:  return xp_sign(&x->c);
    case Q_F0: return xp_sign(&x->f0);
    case Q_F1: return xp_sign(&x->f1);
    case Q_DOT: return xp_sign(&x->dot);
    case Q_AXIS_PARALLEL: return xp_sign(&x->par);
    default:   return parallel_exact(&x->dot, &x->aa, &x->dd, ln->eps) ? -1 : 1;
    }
}

/* ----------------------------------------------------- crossings, ends */

enum { END_NONE, END_SIDE, END_CAP0, END_CAP1 };

/* A crossing of the line, or an open end of the inside interval. */
typedef struct cyl_end {
    int    src;            /* END_*; END_NONE: t = -inf or +inf (`inf`) */
    int    inf;            /* END_NONE: -1 or +1 */
    int    which;          /* END_SIDE: QL_ROOT_* */
    ddx    t;              /* its parameter, certified (err may be +inf) */
} cyl_end;

/* F and D of a cap crossing t = -F/D, exactly. */
static void cap_ratio(cyl_line *ln, int src, xp *num, const xp **den)
{
    const cyl_exact *x = line_exact(ln);
    xp_scale(num, src == END_CAP0 ? &x->f0 : &x->f1, -1.0);
    *den = &x->dot;
}

/* sign(t_e - num/den) exactly (den != 0) */
static int end_cmp_ratio_exact(cyl_line *ln, const cyl_end *e, const xp *num, const xp *den)
{
    if (e->src == END_NONE)
        return e->inf;
    const cyl_exact *x = line_exact(ln);
    if (e->src == END_SIDE)
        return quad_line_cmp(&x->a, &x->b, &x->c, e->which, num, den);
    xp e_num, diff, tmp;
    const xp *e_den;
    cap_ratio(ln, e->src, &e_num, &e_den);
    /* both over the same D: sign(e_num - num) sign(D) for den == D, else
     * sign(e_num den - num D) sign(D den) */
    xp_mul(&diff, &e_num, den);
    xp_mul(&tmp, num, e_den);
    xp_sub(&diff, &diff, &tmp);
    return xp_sign(&diff) * xp_sign(e_den) * xp_sign(den);
}

/* sign(t_e - t_f) */
static int end_cmp(cyl_line *ln, const cyl_end *e, const cyl_end *f)
{
    if (e->src == END_NONE || f->src == END_NONE) {
        int ie = e->src == END_NONE ? e->inf : 0, jf = f->src == END_NONE ? f->inf : 0;
        return (ie > jf) - (ie < jf);
    }
    ddx diff = ddx_sub(e->t, f->t);
    double bound = e->t.err + f->t.err + diff.err;
    if (fabs(diff.hi) * (1.0 - 2.0 * DDX_U) > bound)
        return diff.hi > 0.0 ? 1 : -1;
    if (e->src == END_SIDE && f->src == END_SIDE) /* roots of one quadratic, A > 0 */
        return (e->which > f->which) - (e->which < f->which);
    if (f->src == END_SIDE)
        return -end_cmp(ln, f, e);
    xp num;
    const xp *den;
    cap_ratio(ln, f->src, &num, &den);
    return end_cmp_ratio_exact(ln, e, &num, den);
}

/* sign(t_e - tau) */
static int end_cmp_tau(cyl_line *ln, const cyl_end *e, double tau)
{
    if (isinf(tau))
        return tau < 0.0 ? 1 : -1;
    if (e->src == END_NONE)
        return e->inf;
    ddx diff = ddx_sub(e->t, ddx_of(tau));
    if (fabs(diff.hi) * (1.0 - 2.0 * DDX_U) > e->t.err + diff.err)
        return diff.hi > 0.0 ? 1 : -1;
    xp num, one;
    xp_set(&num, tau);
    xp_set(&one, 1.0);
    return end_cmp_ratio_exact(ln, e, &num, &one);
}

static cyl_end side_end(const quad_line_roots *roots, int i)
{
    cyl_end e = { END_SIDE, 0, roots->which[i], { roots->t_hi[i], roots->t_lo[i], roots->err[i] } };
    return e;
}

static cyl_end cap_end(const cyl_line *ln, int src)
{
    cyl_end e = { src, 0, 0, ddx_div(ddx_neg(src == END_CAP0 ? ln->f0 : ln->f1), ln->dot) };
    return e;
}

/* The side: parallel to the axis (and then whether the line is inside), or
 * its crossings. */
typedef struct cyl_side {
    int parallel, inside;
    quad_line_roots roots;
} cyl_side;

static void side_solve(cyl_line *ln, cyl_side *side)
{
    side->roots.count = 0;
    side->roots.touch = 0;
    side->parallel = sign_of(ln, Q_AXIS_PARALLEL) <= 0;
    side->inside = side->parallel && sign_of(ln, Q_C) <= 0;
    if (side->parallel)
        return;
    if (!quad_line_certify(&ln->side, -INFINITY, INFINITY, &side->roots)) {
        const cyl_exact *x = line_exact(ln);
        quad_line_exact(&x->a, &x->b, &x->c, &x->thr, NULL, -INFINITY, INFINITY, &side->roots);
    }
}

/* One end as a hit, when it lies in [tmin, tmax] (exactly) and its t in the
 * double range. */
static int end_emit(cyl_line *ln, const cyl_end *e, const isect_ray *ray, int32_t kind,
                    isect_hit *out)
{
    const cyl_frame *fr = ln->fr;
    if (e->src == END_NONE)
        return 0;
    double tmin = pow2_scale(ray->tmin, -fr->t_shift), tmax = pow2_scale(ray->tmax, -fr->t_shift);
    if (end_cmp_tau(ln, e, tmin) < 0 || end_cmp_tau(ln, e, tmax) > 0)
        return 0;
    double t_hi = pow2_scale(e->t.hi, fr->t_shift) + 0.0, t_lo = pow2_scale(e->t.lo, fr->t_shift);
    if (!isfinite(t_hi))
        return 0;
    double a[3] = { fr->a[0].hi, fr->a[1].hi, fr->a[2].hi }, normal[3];
    if (e->src == END_SIDE) {
        /* radial: a x (m + t n), m + t n = (f + t d) x a at the crossing */
        double mt[3], radial[3];
        for (int k = 0; k < 3; k++) {
            ddx v = ddx_add(ln->m[k], ddx_mul(e->t, ln->n[k]));
            mt[k] = v.hi;
        }
        cross_accurate(radial, a, mt);
        if (!unit3_accurate(normal, radial))
            normal_or_facing(normal, radial, ray->dir, kind);
    } else {
        unit3_accurate(normal, a);
        if (e->src == END_CAP0)
            v3_set(normal, 0.0 - normal[0], 0.0 - normal[1], 0.0 - normal[2]);
    }
    int32_t prim = e->src == END_SIDE ? 0 : e->src == END_CAP0 ? 1 : 2;
    hit_set_dd(out, ray, t_hi, t_lo, normal, prim, kind);
    return 1;
}

/* Capped: the convex solid's entry and exit (see the top of the file). */
static int capped_hits(cyl_line *ln, const isect_ray *ray, isect_hit out[ISECT_MAX_HITS])
{
    cyl_end enter = { END_NONE, -1, 0, { 0.0, 0.0, 0.0 } };
    cyl_end leave = { END_NONE, 1, 0, { 0.0, 0.0, 0.0 } };
    cyl_side side;
    side_solve(ln, &side);
    if (side.parallel ? !side.inside : side.roots.count == 0)
        return 0;
    if (!side.parallel) { /* a tangent line enters and leaves at its touch */
        enter = side_end(&side.roots, 0);
        leave = side_end(&side.roots, side.roots.count - 1);
    }
    if (sign_of(ln, Q_CAP_PARALLEL) <= 0) {
        if (sign_of(ln, Q_F0) < 0 || sign_of(ln, Q_F1) > 0)
            return 0; /* origin beyond a parallel cap plane */
    } else {
        cyl_end cap0 = cap_end(ln, END_CAP0), cap1 = cap_end(ln, END_CAP1);
        int up = sign_of(ln, Q_DOT) > 0; /* then cap 0 is crossed first */
        const cyl_end *cap_in = up ? &cap0 : &cap1, *cap_out = up ? &cap1 : &cap0;
        /* strictly later / earlier only: the side (prim 0) keeps ties */
        if (end_cmp(ln, cap_in, &enter) > 0)
            enter = *cap_in;
        if (end_cmp(ln, cap_out, &leave) < 0)
            leave = *cap_out;
    }
    int order = end_cmp(ln, &enter, &leave);
    if (order > 0)
        return 0;
    if (order == 0)
        return end_emit(ln, &enter, ray, ISECT_TOUCH, &out[0]);
    int count = end_emit(ln, &enter, ray, ISECT_ENTER, &out[0]);
    return count + end_emit(ln, &leave, ray, ISECT_EXIT, &out[count]);
}

/* Between the cap planes (closed), exactly. */
static int in_slab(cyl_line *ln, const cyl_end *e)
{
    int dot = sign_of(ln, Q_DOT);
    if (dot == 0)
        return sign_of(ln, Q_F0) >= 0 && sign_of(ln, Q_F1) <= 0;
    cyl_end cap0 = cap_end(ln, END_CAP0), cap1 = cap_end(ln, END_CAP1);
    const cyl_end *lo = dot > 0 ? &cap0 : &cap1, *hi = dot > 0 ? &cap1 : &cap0;
    return end_cmp(ln, e, lo) >= 0 && end_cmp(ln, e, hi) <= 0;
}

/* The side crossings as hits: prim 0, ENTER/EXIT (front/back for the open
 * cylinder) or one TOUCH; with clip_to_caps, only those between the caps. */
static int side_hits(cyl_line *ln, int clip_to_caps, const isect_ray *ray,
                     isect_hit out[ISECT_MAX_HITS])
{
    cyl_side side;
    side_solve(ln, &side);
    int count = 0;
    for (int i = 0; !side.parallel && i < side.roots.count; i++) {
        cyl_end e = side_end(&side.roots, i);
        if (clip_to_caps && !in_slab(ln, &e))
            continue;
        int32_t kind = side.roots.touch ? ISECT_TOUCH
                     : side.roots.enter[i] ? ISECT_ENTER : ISECT_EXIT;
        count += end_emit(ln, &e, ray, kind, &out[count]);
    }
    return count;
}

/* ------------------------------------------------------- fast kernels */

/* Crossing i of the solved kernel (lane_pair_hits). */
static int kernel_record(const void *prep, const lane_ray *ray, const void *solved, int i,
                         lane_hit *h)
{
    const cyl_lanes *cl = solved;
    cylinder_lanes_record(prep, ray, &cl->root[i], cl->prim[i], i == 1, h);
    return 1;
}

/* The fast kernel (cylinder_lanes.h) on one ray, as the batch runs it, then
 * the exact path for what it leaves undecided. */
static int kernel_hits(const isect_shape *s, lane_exact_fn exact, const isect_ray *ray,
                       const isect_params *prm, isect_hit out[ISECT_MAX_HITS])
{
    cylinder_prep cp;
    cylinder_prepare(s->data, cylinder_kind(s->type, s->flags), prm->eps, &cp);
    if (cp.degenerate)
        return 0;
    lane_ray lr;
    lane_ray_from(&lr, ray);
    if (!cylinder_lanes_screen(&cp, &lr))
        return 0;
    cyl_lanes cl;
    cylinder_lanes_solve(&cp, &lr, 0, &cl);
    static const int32_t kinds[2] = { ISECT_ENTER, ISECT_EXIT };
    return lane_pair_hits(&cl.pr, kinds, kernel_record, &cp, &lr, &cl, exact, s, ray, prm, out);
}

/* ------------------------------------------------------- finite cylinder */

int cylinder_check(const isect_shape *s)
{
    if (s->flags != 0 && s->flags != ISECT_CAPPED)
        return ISECT_E_ARG;
    if (!all_finite(s->data, 7))
        return ISECT_E_NONFINITE;
    return s->data[6] < 0.0 ? ISECT_E_ARG : ISECT_OK;
}

/* The exact path of the finite cylinders: certified, else exact. */
static int cylinder_exact(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                          isect_hit out[ISECT_MAX_HITS])
{
    cyl_frame fr;
    if (!frame_finite(s->data, ray->org, ray->dir, &fr))
        return 0;
    cyl_line ln;
    line_make(&fr, prm->eps, &ln);
    if (s->flags & ISECT_CAPPED)
        return capped_hits(&ln, ray, out);
    return side_hits(&ln, 1, ray, out);
}

int cylinder_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                  isect_hit out[ISECT_MAX_HITS])
{
    return kernel_hits(s, cylinder_exact, ray, prm, out);
}

/* The point's signs: outside the side (C), below cap 0 (-F0), above cap 1
 * (F1); exact. */
static void point_signs(cyl_frame *fr, int finite, int signs[3])
{
    cyl_line ln;
    line_make(fr, 0.0, &ln);
    signs[0] = sign_of(&ln, Q_C);
    signs[1] = finite ? -sign_of(&ln, Q_F0) : -1;
    signs[2] = finite ? sign_of(&ln, Q_F1) : -1;
}

int cylinder_contains(const isect_shape *s, const double p[3])
{
    cyl_frame fr;
    if (!frame_finite(s->data, p, NULL, &fr))
        return 0;
    int signs[3];
    point_signs(&fr, 1, signs);
    return signs[0] <= 0 && signs[1] <= 0 && signs[2] <= 0;
}

/* The capped cylinder as a solid (outside beyond either cap or the side);
 * the open one as the side surface alone, in front of its radial normal. */
int cylinder_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    cyl_frame fr;
    if (!frame_finite(s->data, p, NULL, &fr))
        return 1; /* degenerate */
    int signs[3];
    point_signs(&fr, 1, signs);
    if (!(s->flags & ISECT_CAPPED))
        return signs[0];
    if (signs[0] > 0 || signs[1] > 0 || signs[2] > 0)
        return 1;
    return signs[0] < 0 && signs[1] < 0 && signs[2] < 0 ? -1 : 0;
}

/* ----------------------------------------------------- infinite cylinder */

int cylinder_inf_check(const isect_shape *s)
{
    if (!all_finite(s->data, 7))
        return ISECT_E_NONFINITE;
    return s->data[6] < 0.0 ? ISECT_E_ARG : ISECT_OK;
}

static int cylinder_inf_exact(const isect_shape *s, const isect_ray *ray,
                              const isect_params *prm, isect_hit out[ISECT_MAX_HITS])
{
    cyl_frame fr;
    if (!frame_infinite(s->data, ray->org, ray->dir, &fr))
        return 0;
    cyl_line ln;
    line_make(&fr, prm->eps, &ln);
    /* parallel: inside or outside along the whole line, no crossing */
    return side_hits(&ln, 0, ray, out);
}

int cylinder_inf_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                      isect_hit out[ISECT_MAX_HITS])
{
    return kernel_hits(s, cylinder_inf_exact, ray, prm, out);
}

int cylinder_inf_contains(const isect_shape *s, const double p[3])
{
    cyl_frame fr;
    if (!frame_infinite(s->data, p, NULL, &fr))
        return 0;
    int signs[3];
    point_signs(&fr, 0, signs);
    return signs[0] <= 0;
}

int cylinder_inf_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    cyl_frame fr;
    if (!frame_infinite(s->data, p, NULL, &fr))
        return 1;
    int signs[3];
    point_signs(&fr, 0, signs);
    return signs[0];
}
