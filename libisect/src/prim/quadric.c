/*
 * quadric.c — the general quadric (ISECT_QUADRIC, data = q[10] = A..J)
 *     Q(x) = Ax^2 + By^2 + Cz^2 + Dxy + Exz + Fyz + Gx + Hy + Iz + J = 0,
 * a solid with inside Q < 0 (a closed set for contains: Q <= 0); prim -1.
 *
 * Along the line, Q(org + t dir) = a t^2 + b t + c with
 *     a = Q2(dir) (the quadratic part), b = grad Q(org) . dir, c = Q(org).
 *  - Linear case, |a| <= eps S |dir|^2 with S = max(|A|..|F|) (a ray
 *    parallel to a cone's generator or a paraboloid's axis, a plane written
 *    as a quadric, where S = 0 and a = 0): one root t = -c/b; b = 0 too
 *    (the line misses, or lies in the surface): no hit.
 *  - Otherwise quadratic_roots() (quadratic.c): disc = b^2 - 4ac by Kahan's
 *    FMA algorithm plus the first-order terms of the coefficients' low
 *    parts (a, b, c are compensated sums, known to about twice the working
 *    precision); TOUCH when |b^2 - 4ac| <= eps (b^2 + 4|ac|), at -b/2a;
 *    roots by q = -(b + sign(b) sqrt(disc))/2, t = q/a, c/q.
 *  - Kinds from the sign pattern of a t^2 + b t + c, exact in real
 *    arithmetic: a > 0 is negative (inside) between the roots, so ENTER then
 *    EXIT; a < 0 the reverse; linear: ENTER when b < 0 (Q decreasing).
 *  - Normal: unit(grad Q) at the hit; where the gradient vanishes (a cone's
 *    apex) it faces the ray as the kind says (normal_or_facing).
 *  - All ten coefficients zero: degenerate (no hits, nothing inside).
 *
 * Scaling. Coordinates are taken in units of 2^e_pos (the power of two of
 * the largest coordinate of org, or of the point), which multiplies the
 * quadratic coefficients by 2^(2 e_pos) and the linear ones by 2^e_pos; all
 * ten are then divided by the power of two that brings the largest into
 * [0.5, 1), and dir gets its own power of two. Every step is exact (barring
 * underflow of terms 2^1022 times below the largest), so signs and roots
 * are those of the coefficients as given, while a, b, c, the discriminant
 * and the gradient are bounded numbers that cannot overflow.
 */
#include "prim/prim.h"
#include "core/expansion.h"
#include "core/quadratic.h"
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

/*
 * Q(p) by a compensated sum of its monomials: accurate as if evaluated in
 * twice the precision. contains() uses it, and so does the root finder for
 * c = Q(org), so contains(org) agrees with the sign the roots come from.
 */
static comp_sum q_sum(const double q[10], const double p[3])
{
    comp_sum s = { 0.0, 0.0 };
    for (int k = 0; k < 6; k++)
        comp_add_product3(&s, q[quad_term[k][0]], p[quad_term[k][1]], p[quad_term[k][2]]);
    for (int i = 0; i < 3; i++)
        comp_add_product(&s, q[QG + i], p[i]);
    comp_add(&s, q[QJ]);
    return s;
}

/*
 * a = Q2(dir), b = grad Q(org).dir, c = Q(org), each a compensated sum of
 * its monomials kept as hi + lo, so the discriminant quadratic_roots forms
 * from them is accurate too (a plainly evaluated c or b would carry an
 * error of u times the largest monomial, which near tangency dominates
 * b^2 - 4ac).
 */
static void line_coefficients(const double q[10], const double org[3], const double dir[3],
                              comp_sum *a, comp_sum *b, comp_sum *c)
{
    comp_sum sa = { 0.0, 0.0 }, sb = { 0.0, 0.0 };
    for (int k = 0; k < 6; k++) {
        double coef = q[quad_term[k][0]];
        int i = quad_term[k][1], j = quad_term[k][2];
        comp_add_product3(&sa, coef, dir[i], dir[j]);
        comp_add_product3(&sb, coef, org[i], dir[j]);
        comp_add_product3(&sb, coef, dir[i], org[j]);
    }
    for (int i = 0; i < 3; i++)
        comp_add_product(&sb, q[QG + i], dir[i]);
    *a = comp_normalized(sa);
    *b = comp_normalized(sb);
    *c = comp_normalized(q_sum(q, org));
}

static void q_gradient(const double q[10], const double x[3], double g[3])
{
    g[0] = 2.0 * q[QA] * x[0] + q[QD] * x[1] + q[QE] * x[2] + q[QG];
    g[1] = q[QD] * x[0] + 2.0 * q[QB] * x[1] + q[QF] * x[2] + q[QH];
    g[2] = q[QE] * x[0] + q[QF] * x[1] + 2.0 * q[QC] * x[2] + q[QI];
}

int quadric_check(const isect_shape *s)
{
    return all_finite(s->data, 10) ? ISECT_OK : ISECT_E_NONFINITE;
}

int quadric_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                 isect_hit out[ISECT_MAX_HITS])
{
    if (all_zero(s->data))
        return 0;
    int e_pos = position_exponent(s->data, ray->org);
    int e_dir = pow2_exponent(max_abs3(ray->dir));
    double q[10], org[3], dir[3];
    scaled_coefficients(s->data, e_pos, q);
    scale3(org, ray->org, e_pos);
    scale3(dir, ray->dir, e_dir);

    comp_sum a, b, c; /* normalised: hi is the rounded value */
    line_coefficients(q, org, dir, &a, &b, &c);
    double s_max = 0.0;
    for (int i = QA; i <= QF; i++)
        s_max = fmax(s_max, fabs(q[i]));

    /* Roots in scaled units (t = t' 2^(e_pos - e_dir)) and their kinds. */
    double roots[2];
    int32_t kinds[2];
    int count;
    if (fabs(a.hi) <= prm->eps * s_max * v3_dot(dir, dir)) {
        if (b.hi == 0.0)
            return 0;
        count = 1;
        roots[0] = -c.hi / b.hi;
        kinds[0] = b.hi < 0.0 ? ISECT_ENTER : ISECT_EXIT;
    } else {
        quad_roots qr;
        quadratic_roots(a, b, c, prm->eps, &qr);
        count = qr.count;
        roots[0] = qr.t[0];
        roots[1] = qr.t[1];
        kinds[0] = count == 1 ? ISECT_TOUCH : (a.hi > 0.0 ? ISECT_ENTER : ISECT_EXIT);
        kinds[1] = a.hi > 0.0 ? ISECT_EXIT : ISECT_ENTER;
    }

    int kept = 0;
    for (int i = 0; i < count; i++) {
        double t = ldexp(roots[i], e_pos - e_dir) + 0.0;
        if (!isfinite(t))
            continue; /* beyond the double range: not reported */
        double x[3], g[3], normal[3];
        v3_madd(x, org, roots[i], dir);
        q_gradient(q, x, g);
        normal_or_facing(normal, g, ray->dir, kinds[i]);
        hit_set(&out[kept++], ray, t, normal, -1, kinds[i]);
    }
    return kept;
}

int quadric_contains(const isect_shape *s, const double p[3])
{
    if (all_zero(s->data))
        return 0;
    int e_pos = position_exponent(s->data, p);
    double q[10], x[3];
    scaled_coefficients(s->data, e_pos, q);
    scale3(x, p, e_pos);
    comp_sum value = q_sum(q, x);
    return comp_value(&value) <= 0.0;
}

/* Q(p) exactly, in the scaled coordinates of quadric_contains (the scaling
 * is exact and keeps the sign): each monomial coefficient * x * y as an
 * expansion. */
int quadric_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    if (all_zero(s->data))
        return 1;
    int e_pos = position_exponent(s->data, p);
    double q[10], x[3];
    scaled_coefficients(s->data, e_pos, q);
    scale3(x, p, e_pos);
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
