/* SPDX-License-Identifier: Apache-2.0 */
/*
 * quadric.c — the general quadric (ISECT_QUADRIC, data = q[10] = A..J)
 *     Q(x) = Ax^2 + By^2 + Cz^2 + Dxy + Exz + Fyz + Gx + Hy + Iz + J = 0,
 * a solid with inside Q < 0 (a closed set for contains: Q <= 0); prim -1.
 *
 * Along the line, Q(org + t dir) = a t^2 + 2b t + c (core/quad_line.h) with
 *     a = Q2(dir) (the quadratic part), b = grad Q(org) . dir / 2, c = Q(org),
 * each formed as a double-double with an error bound (core/ddx.h), and the
 * discriminant b^2 - ac from them; quad_line_certify certifies the
 * crossings, and where it cannot (a touch or near-touch, the linear case, a
 * decision within the bounds) the same coefficients as exact expansions
 * decide exactly (quad_line_exact). Rules:
 *  - Linear case, |a| <= eps S |dir|^2 with S = max(|A|..|F|) (a ray
 *    parallel to a cone's generator or a paraboloid's axis, a plane written
 *    as a quadric, where S = 0 and a = 0): one root t = -c/(2b), ENTER when
 *    b < 0 (Q decreasing); b = 0 too (the line misses, or lies in the
 *    surface): no hit.
 *  - TOUCH when |b^2 - ac| <= eps (b^2 + |ac|), at -b/a.
 *  - Otherwise two crossings: the entry into Q < 0 where Q' < 0 (for a > 0
 *    the first, for a < 0 the second), the exit at the other.
 *  - Normal: unit(grad Q) at the point org + t dir formed from the
 *    double-double t (so far rays keep it on the surface); where the
 *    gradient vanishes (a cone's apex) it faces the ray as the kind says
 *    (normal_or_facing).
 *  - All ten coefficients zero: degenerate (no hits, nothing inside).
 *
 * Scaling. Coordinates are taken in units of 2^e_pos (the power of two of
 * the largest coordinate of org, or of the point), which multiplies the
 * quadratic coefficients by 2^(2 e_pos) and the linear ones by 2^e_pos; all
 * ten are then divided by the power of two that brings the largest into
 * [0.5, 1), and dir gets its own power of two. Every step is exact (barring
 * underflow of terms 2^1022 times below the largest), so signs and roots
 * are those of the coefficients as given.
 */
#include "prim/prim.h"
#include "prim/quadric_lanes.h"
#include "core/ddx.h"
#include "core/expansion.h"
#include "core/quad_line.h"
#include "core/scaling.h"
#include "core/vec3.h"

#include <limits.h>

enum { QA, QB, QC, QD, QE, QF, QG, QH, QI, QJ };

static int all_zero(const double *q)
{
    for (int i = 0; i < 10; i++)
        if (q[i] != 0.0)
            return 0;
    return 1;
}

/* The coefficients for coordinates in units of 2^e_pos, normalised. */
static void scaled_coefficients(const double *q, int e_pos, double out[10])
{
    static const int degree[10] = { 2, 2, 2, 2, 2, 2, 1, 1, 1, 0 };
    int top = INT_MIN;
    for (int i = 0; i < 10; i++) {
        if (q[i] != 0.0 && pow2_exponent(q[i]) + degree[i] * e_pos > top)
            top = pow2_exponent(q[i]) + degree[i] * e_pos;
    }
    for (int i = 0; i < 10; i++)
        out[i] = q[i] != 0.0 ? ldexp(q[i], degree[i] * e_pos - top) : 0.0;
}

/*
 * The power of two to measure positions in. Any choice is exact, but the
 * scaled coefficients span 2^(degree * e_pos): measured in units far below
 * the quadric's own length scale (an origin at 1e-200 near a unit sphere)
 * the degree-2 terms would underflow against J. So the unit is the larger
 * of the origin's magnitude and the scale where the highest- and
 * lowest-degree terms balance, |q_high| L^dh ~ |q_low| L^dl.
 */
static int position_exponent(const double *q, const double org[3])
{
    static const int degree[10] = { 2, 2, 2, 2, 2, 2, 1, 1, 1, 0 };
    int e_deg[3] = { INT_MIN, INT_MIN, INT_MIN };
    for (int i = 0; i < 10; i++)
        if (q[i] != 0.0 && pow2_exponent(q[i]) > e_deg[degree[i]])
            e_deg[degree[i]] = pow2_exponent(q[i]);
    int hi = 2, lo = 0;
    while (hi > 0 && e_deg[hi] == INT_MIN)
        hi--;
    while (lo < hi && e_deg[lo] == INT_MIN)
        lo++;
    int e_org = max_abs3(org) > 0.0 ? pow2_exponent(max_abs3(org)) : INT_MIN;
    if (lo == hi)
        return e_org == INT_MIN ? 0 : e_org;
    int e_shape = (e_deg[lo] - e_deg[hi]) / (hi - lo);
    return e_org > e_shape ? e_org : e_shape;
}

/* The monomials of the quadratic part: coefficient index and variables. */
static const int quad_term[6][3] = {
    { QA, 0, 0 }, { QB, 1, 1 }, { QC, 2, 2 }, { QD, 0, 1 }, { QE, 0, 2 }, { QF, 1, 2 }
};

/* The line function's coefficients, certified: a = Q2(d), b = (grad Q(o)
 * . d)/2 (each monomial's two halves), c = Q(o). */
static void line_dd(const double q[10], const double o[3], const double d[3], double eps,
                    quad_line_dd *out)
{
    ddx a = ddx_of(0.0), b = ddx_of(0.0), c = ddx_of(q[QJ]);
    double s_max = 0.0;
    for (int k = 0; k < 6; k++) {
        ddx coef = ddx_of(q[quad_term[k][0]]);
        int i = quad_term[k][1], j = quad_term[k][2];
        s_max = fmax(s_max, fabs(coef.hi));
        a = ddx_add(a, ddx_mul_d(ddx_mul_d(coef, d[i]), d[j]));
        ddx half = ddx_mul_d(coef, 0.5);
        b = ddx_add(b, ddx_mul_d(ddx_mul_d(half, o[i]), d[j]));
        b = ddx_add(b, ddx_mul_d(ddx_mul_d(half, d[i]), o[j]));
        c = ddx_add(c, ddx_mul_d(ddx_mul_d(coef, o[i]), o[j]));
    }
    for (int i = 0; i < 3; i++) {
        b = ddx_add(b, ddx_mul_d(ddx_of(0.5 * q[QG + i]), d[i]));
        c = ddx_add(c, ddx_mul_d(ddx_of(q[QG + i]), o[i]));
    }
    ddx bb = ddx_sqr(b), ac = ddx_mul(a, c);
    out->a = a;
    out->b = b;
    out->c = c;
    out->g = ddx_sub(bb, ac);
    double up = 1.0 + 8.0 * DDX_U;
    out->t_thr = eps * (ddx_abs(bb) + bb.err + ddx_abs(ac) + ac.err) * up;
    out->l_thr = eps * s_max * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * up;
}

/* The same, exactly: a, b, c, the tangency threshold eps (b^2 + |ac|) and
 * the linear one eps S |d|^2. Halving is exact (a power of two). */
static void line_exact(const double q[10], const double o[3], const double d[3], double eps,
                       double tmin, double tmax, quad_line_roots *out)
{
    xp a, b, c, term, thr, lin, tmp;
    xp_set(&a, 0.0);
    xp_set(&b, 0.0);
    xp_set(&c, q[QJ]);
    double s_max = 0.0;
    for (int k = 0; k < 6; k++) {
        double coef = q[quad_term[k][0]];
        int i = quad_term[k][1], j = quad_term[k][2];
        s_max = fmax(s_max, fabs(coef));
        xp_set(&term, coef);
        xp_scale(&term, &term, d[i]);
        xp_scale(&term, &term, d[j]);
        xp_add(&a, &a, &term);
        xp_set(&term, 0.5 * coef);
        xp_scale(&term, &term, o[i]);
        xp_scale(&term, &term, d[j]);
        xp_add(&b, &b, &term);
        xp_set(&term, 0.5 * coef);
        xp_scale(&term, &term, d[i]);
        xp_scale(&term, &term, o[j]);
        xp_add(&b, &b, &term);
        xp_set(&term, coef);
        xp_scale(&term, &term, o[i]);
        xp_scale(&term, &term, o[j]);
        xp_add(&c, &c, &term);
    }
    for (int i = 0; i < 3; i++) {
        xp_set(&term, 0.5 * q[QG + i]);
        xp_scale(&term, &term, d[i]);
        xp_add(&b, &b, &term);
        xp_set(&term, q[QG + i]);
        xp_scale(&term, &term, o[i]);
        xp_add(&c, &c, &term);
    }
    xp_mul(&thr, &b, &b);
    xp_mul(&tmp, &a, &c);
    if (xp_sign(&tmp) < 0)
        xp_scale(&tmp, &tmp, -1.0);
    xp_add(&thr, &thr, &tmp);
    xp_scale(&thr, &thr, eps);
    xp_set(&lin, 0.0);
    for (int k = 0; k < 3; k++) {
        xp_set(&tmp, d[k]);
        xp_scale(&tmp, &tmp, d[k]);
        xp_add(&lin, &lin, &tmp);
    }
    xp_scale(&lin, &lin, s_max);
    xp_scale(&lin, &lin, eps);
    quad_line_exact(&a, &b, &c, &thr, &lin, tmin, tmax, out);
}

/* grad Q at the point o + t d, t a double-double (scaled units). */
static void gradient_at(const double q[10], const double o[3], const double d[3], double t_hi,
                        double t_lo, double g[3])
{
    ddx t = { t_hi, t_lo, 0.0 }, x[3];
    for (int k = 0; k < 3; k++)
        x[k] = ddx_add(ddx_of(o[k]), ddx_mul_d(t, d[k]));
    static const int mixed[3][3] = { { QA, QD, QE }, { QD, QB, QF }, { QE, QF, QC } };
    for (int k = 0; k < 3; k++) {
        ddx sum = ddx_of(q[QG + k]);
        for (int j = 0; j < 3; j++) {
            double coef = q[mixed[k][j]] * (j == k ? 2.0 : 1.0);
            sum = ddx_add(sum, ddx_mul_d(x[j], coef));
        }
        g[k] = sum.hi;
    }
}

int quadric_check(const isect_shape *s)
{
    return all_finite(s->data, 10) ? ISECT_OK : ISECT_E_NONFINITE;
}

/* The exact path: certified from double-doubles, else exact. */
static int quadric_exact(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                         isect_hit out[ISECT_MAX_HITS])
{
    int e_pos = position_exponent(s->data, ray->org);
    int e_dir = pow2_exponent(max_abs3(ray->dir));
    int t_shift = e_pos - e_dir;
    double q[10], org[3], dir[3];
    scaled_coefficients(s->data, e_pos, q);
    scale3(org, ray->org, e_pos);
    scale3(dir, ray->dir, e_dir);
    double tmin = pow2_scale(ray->tmin, -t_shift), tmax = pow2_scale(ray->tmax, -t_shift);

    quad_line_dd line;
    line_dd(q, org, dir, prm->eps, &line);
    quad_line_roots roots;
    if (!quad_line_certify(&line, tmin, tmax, &roots))
        line_exact(q, org, dir, prm->eps, tmin, tmax, &roots);

    int kept = 0;
    for (int i = 0; i < roots.count; i++) {
        if (!roots.in[i])
            continue;
        double t_hi = pow2_scale(roots.t_hi[i], t_shift) + 0.0;
        double t_lo = pow2_scale(roots.t_lo[i], t_shift);
        if (!isfinite(t_hi))
            continue; /* beyond the double range: not reported */
        int32_t kind = roots.touch ? ISECT_TOUCH : roots.enter[i] ? ISECT_ENTER : ISECT_EXIT;
        double g[3], normal[3];
        gradient_at(q, org, dir, roots.t_hi[i], roots.t_lo[i], g);
        if (!unit3_accurate(normal, g))
            normal_or_facing(normal, g, ray->dir, kind);
        hit_set_dd(&out[kept++], ray, t_hi, t_lo, normal, -1, kind);
    }
    return kept;
}

/* Crossing i of the solved kernel (lane_pair_hits): deferred where its
 * normal is not certified. */
static int quadric_record(const void *prep, const lane_ray *ray, const void *solved, int i,
                          lane_hit *h)
{
    return quadric_lanes_record(prep, ray, &((const quadric_lanes *)solved)->root[i], h);
}

/* The fast kernel (quadric_lanes.h) on one ray, as the batch runs it, then
 * the exact path for what it leaves undecided. */
int quadric_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                 isect_hit out[ISECT_MAX_HITS])
{
    if (all_zero(s->data))
        return 0;
    quadric_prep qp;
    quadric_prepare(s->data, prm->eps, &qp);
    lane_ray lr;
    lane_ray_from(&lr, ray);
    quadric_lanes ql;
    quadric_lanes_solve(&qp, &lr, 0, &ql);
    int32_t kind[2] = { ql.lo_enter ? ISECT_ENTER : ISECT_EXIT, ql.lo_enter ? ISECT_EXIT : ISECT_ENTER };
    return lane_pair_hits(&ql.pr, kind, quadric_record, &qp, &lr, &ql, quadric_exact, s, ray, prm,
                          out);
}

/* Q(x) (scaled coordinates) certified as a double-double, exactly where
 * its bound straddles 0 (below). */
static int side_sign(const double q[10], const double x[3]);

int quadric_contains(const isect_shape *s, const double p[3])
{
    if (all_zero(s->data))
        return 0;
    int e_pos = position_exponent(s->data, p);
    double q[10], x[3];
    scaled_coefficients(s->data, e_pos, q);
    scale3(x, p, e_pos);
    return side_sign(q, x) <= 0;
}

/* Q(x) exactly (scaled coordinates; the scaling is exact and keeps the
 * sign): each monomial coefficient * x * y as an expansion. */
static int side_exact(const double q[10], const double x[3])
{
    xp sum, term;
    xp_set(&sum, q[QJ]);
    for (int k = 0; k < 6; k++) {
        xp_set(&term, q[quad_term[k][0]]);
        xp_scale(&term, &term, x[quad_term[k][1]]);
        xp_scale(&term, &term, x[quad_term[k][2]]);
        xp_add(&sum, &sum, &term);
    }
    for (int i = 0; i < 3; i++) {
        xp_set(&term, q[QG + i]);
        xp_scale(&term, &term, x[i]);
        xp_add(&sum, &sum, &term);
    }
    return xp_sign(&sum);
}

static int side_sign(const double q[10], const double x[3])
{
    static const double none[3] = { 0.0, 0.0, 0.0 };
    quad_line_dd line;
    line_dd(q, x, none, 0.0, &line); /* c = Q(x) */
    if (fabs(line.c.hi) * (1.0 - 2.0 * DDX_U) > line.c.err)
        return line.c.hi > 0.0 ? 1 : -1;
    return side_exact(q, x);
}

int quadric_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    if (all_zero(s->data))
        return 1;
    int e_pos = position_exponent(s->data, p);
    double q[10], x[3];
    scaled_coefficients(s->data, e_pos, q);
    scale3(x, p, e_pos);
    return side_exact(q, x);
}
