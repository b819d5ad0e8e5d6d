/*
 * cylinder.c — the finite cylinder of radius r around the segment p0-p1
 * (ISECT_CYLINDER, data = p0[3], p1[3], r; flags ISECT_CAPPED or 0) and the
 * infinite cylinder around the line p + s*axis (ISECT_CYLINDER_INF, data =
 * p[3], axis[3], r).
 *
 * The side, as in the seeds: project onto the plane across the axis and
 * intersect the projected line with the circle. With a the axis vector and
 * f = org - p0, the projection is taken by the cross products
 *     m = f x a,   n = dir x a,
 * which are the projected origin and direction turned by 90 degrees about
 * the axis and scaled by |a|, so |(f + t dir) x a| = r |a| is the circle
 * problem, solved by the same cancellation-free line_sphere_roots() as the
 * sphere (quadratic.c). Each component of m and n is a 2x2 determinant
 * evaluated by det2_accurate (Kahan's FMA algorithm), so a ray nearly
 * parallel to the axis keeps an accurate projected direction. The radial
 * normal at a crossing is unit(a x q), q the crossing's m-frame normal.
 *
 * Rules (isect.h):
 *  - Side tangency: |r^2 - h^2| <= eps r^2, h the distance between the line
 *    and the axis: one TOUCH.
 *  - Parallel to the axis, |dir x a| <= eps |dir| |a|: the side is not hit.
 *    The line is then inside the infinite solid iff |m| <= r|a| (closed).
 *  - Capped: a convex solid, the side's interval intersected with the slab
 *    between the cap planes (p - p0).a >= 0, (p - p1).a <= 0. A cap plane
 *    parallel to the ray by the library's epsilon policy, |dir.a| <= eps
 *    |dir| |a|, is not crossed and constrains by the side the origin is on
 *    (on the plane = inside), exactly as a convex-polyhedron face. Entry =
 *    the latest entry, exit = the earliest exit; ties go to the lowest prim
 *    (side 0 before the caps 1, 2: a ray through the rim is reported on the
 *    side); entry == exit is one TOUCH with the entry's prim and normal.
 *  - Open: the side only, a thin surface with the outward radial normal,
 *    each crossing kept when it lies between the cap planes (closed).
 *  - r = 0 or p0 == p1 (axis = 0): degenerate, no hits, nothing inside.
 *
 * Scaling. Positions (org, p0, p1 and r) share the power of two that brings
 * the largest into [0.5, 1); dir and the infinite cylinder's axis get their
 * own. All exact, so the arithmetic is the unscaled one but no product can
 * overflow. Line parameters are compared in the scaled units (a common
 * power-of-two factor, which keeps their order) and converted once.
 */
#include "prim/prim.h"
#include "core/expansion.h"
#include "core/quadratic.h"
#include "core/vec3.h"

/* |m|^2 - r^2 |a|^2, compensated: its sign is that of (distance to the
 * axis) - r for m = (x - p0) x a, without rounding r|a| first. Each r a_k is
 * split exactly by an FMA into ra + ra_err, and (ra + ra_err)^2 is taken to
 * second order, ra^2 + 2 ra ra_err. */
static double radial_excess(const double m[3], double r, const double a[3])
{
    comp_sum s = { 0.0, 0.0 };
    for (int k = 0; k < 3; k++) {
        double ra = r * a[k];
        double ra_err = fma(r, a[k], -ra);
        comp_add_product(&s, m[k], m[k]);
        comp_add_product(&s, -ra, ra);
        s.lo -= 2.0 * ra * ra_err;
    }
    return comp_value(&s);
}

/* The problem in scaled units; t = t' * 2^t_shift. */
typedef struct cyl_frame {
    double f[3];  /* org - p0 (scaled) */
    double g[3];  /* org - p1 (scaled; finite cylinder only) */
    double a[3];  /* axis (scaled) */
    double d[3];  /* dir (scaled) */
    double r;     /* radius (scaled like the positions) */
    int t_shift;
} cyl_frame;

/* dir scaled by its own power of two (zero for a containment frame). */
static void frame_set_dir(cyl_frame *fr, const double dir[3], int e_pos)
{
    static const double none[3] = { 0.0, 0.0, 0.0 };
    int e_dir = dir != NULL ? pow2_exponent(max_abs3(dir)) : 0;
    scale3(fr->d, dir != NULL ? dir : none, e_dir);
    fr->t_shift = e_pos - e_dir;
}

/* Finite cylinder frame (dir may be NULL: containment only). 0 when
 * degenerate. */
static int frame_finite(const double *data, const double org[3], const double dir[3],
                        cyl_frame *fr)
{
    const double *p0 = data, *p1 = data + 3;
    double r = data[6];
    int e = pow2_exponent(fmax(fmax(r, max_abs3(org)), fmax(max_abs3(p0), max_abs3(p1))));
    double o_s[3], p0_s[3], p1_s[3];
    scale3(o_s, org, e);
    scale3(p0_s, p0, e);
    scale3(p1_s, p1, e);
    v3_sub(fr->f, o_s, p0_s);
    v3_sub(fr->g, o_s, p1_s);
    v3_sub(fr->a, p1_s, p0_s);
    fr->r = ldexp(r, -e);
    frame_set_dir(fr, dir, e);
    return fr->r > 0.0 && max_abs3(fr->a) > 0.0;
}

/* Infinite cylinder frame; the axis is a direction with its own scale. */
static int frame_infinite(const double *data, const double org[3], const double dir[3],
                          cyl_frame *fr)
{
    const double *p = data, *axis = data + 3;
    double r = data[6];
    int e = pow2_exponent(fmax(r, fmax(max_abs3(org), max_abs3(p))));
    double o_s[3], p_s[3];
    scale3(o_s, org, e);
    scale3(p_s, p, e);
    v3_sub(fr->f, o_s, p_s);
    v3_copy(fr->g, fr->f);
    scale3(fr->a, axis, pow2_exponent(max_abs3(axis)));
    fr->r = ldexp(r, -e);
    frame_set_dir(fr, dir, e);
    return fr->r > 0.0 && max_abs3(fr->a) > 0.0;
}

/* The side of the infinite cylinder along the line. */
typedef struct cyl_side {
    int parallel;    /* the line is parallel to the axis (epsilon policy) */
    int inside;      /* parallel only: the whole line is in the closed solid */
    line_sphere ls;  /* otherwise: crossings, t in scaled units, 3D normals */
} cyl_side;

static void side_solve(const cyl_frame *fr, double eps, cyl_side *side)
{
    double m[3], n[3];
    cross_accurate(m, fr->f, fr->a);
    cross_accurate(n, fr->d, fr->a);
    double a_len = v3_norm(fr->a);
    double radius_m = fr->r * a_len; /* the circle's radius in the m frame */
    side->parallel = v3_norm(n) <= eps * v3_norm(fr->d) * a_len;
    side->inside = 0;
    side->ls.count = 0;
    if (side->parallel) {
        side->inside = radial_excess(m, fr->r, fr->a) <= 0.0;
        return;
    }
    line_sphere_roots(m, n, radius_m, eps, &side->ls);
    for (int i = 0; i < side->ls.count; i++) {
        double radial[3]; /* turned back by 90 degrees; nonzero, as a is normal to q */
        v3_cross(radial, fr->a, side->ls.normal[i]);
        normal_or_facing(side->ls.normal[i], radial, fr->d, ISECT_TOUCH);
    }
}

/* One end of the inside interval. */
typedef struct cyl_end {
    double t; /* scaled units; +-inf: the line does not leave there */
    int32_t prim;
    double normal[3];
} cyl_end;

static void end_set(cyl_end *end, double t, int32_t prim, const double normal[3])
{
    end->t = t;
    end->prim = prim;
    v3_copy(end->normal, normal);
}

/* Emit one end as a hit if its t is in the double range. */
static int end_emit(const cyl_end *end, const cyl_frame *fr, const isect_ray *ray,
                    int32_t kind, isect_hit *out)
{
    double t = ldexp(end->t, fr->t_shift) + 0.0;
    if (!isfinite(t))
        return 0;
    hit_set(out, ray, t, end->normal, end->prim, kind);
    return 1;
}

/* Capped: the convex solid's entry and exit (see the top of the file). */
static int capped_hits(const cyl_frame *fr, const isect_ray *ray, double eps,
                       isect_hit out[ISECT_MAX_HITS])
{
    static const double no_normal[3] = { 0.0, 0.0, 0.0 };
    cyl_end enter, leave;
    end_set(&enter, -INFINITY, -1, no_normal);
    end_set(&leave, INFINITY, -1, no_normal);

    cyl_side side;
    side_solve(fr, eps, &side);
    if (side.parallel ? !side.inside : side.ls.count == 0)
        return 0;
    if (!side.parallel) {
        int last = side.ls.count - 1; /* a tangent line enters and leaves at t[0] */
        end_set(&enter, side.ls.t[0], 0, side.ls.normal[0]);
        end_set(&leave, side.ls.t[last], 0, side.ls.normal[last]);
    }

    double a_unit[3];
    unit3(a_unit, fr->a); /* a != 0: checked when the frame was made */
    double a_len = v3_norm(fr->a);
    double d_dot_a = v3_dot(fr->d, fr->a);
    double f_dot_a = v3_dot(fr->f, fr->a), g_dot_a = v3_dot(fr->g, fr->a);
    if (fabs(d_dot_a) <= eps * v3_norm(fr->d) * a_len) {
        if (!(f_dot_a >= 0.0 && g_dot_a <= 0.0))
            return 0; /* origin beyond a parallel cap plane */
    } else {
        double down[3] = { 0.0 - a_unit[0], 0.0 - a_unit[1], 0.0 - a_unit[2] };
        cyl_end cap0, cap1; /* cap at p0: normal -a; cap at p1: +a */
        end_set(&cap0, -f_dot_a / d_dot_a, 1, down);
        end_set(&cap1, -g_dot_a / d_dot_a, 2, a_unit);
        const cyl_end *cap_in = d_dot_a > 0.0 ? &cap0 : &cap1;
        const cyl_end *cap_out = d_dot_a > 0.0 ? &cap1 : &cap0;
        /* Strictly later / earlier only: the side (prim 0) keeps ties. */
        if (cap_in->t > enter.t)
            enter = *cap_in;
        if (cap_out->t < leave.t)
            leave = *cap_out;
    }
    if (enter.t > leave.t)
        return 0;
    if (enter.t == leave.t)
        return end_emit(&enter, fr, ray, ISECT_TOUCH, &out[0]);
    int count = end_emit(&enter, fr, ray, ISECT_ENTER, &out[0]);
    return count + end_emit(&leave, fr, ray, ISECT_EXIT, &out[count]);
}

/* The side crossings as hits: prim 0, ENTER/EXIT (front/back for the open
 * cylinder) or one TOUCH; with clip_to_caps, only those between the cap
 * planes (closed), each plane tested from its own end point. */
static int side_emit(const cyl_frame *fr, const cyl_side *side, int clip_to_caps,
                     const isect_ray *ray, isect_hit out[ISECT_MAX_HITS])
{
    double d_dot_a = v3_dot(fr->d, fr->a);
    double f_dot_a = v3_dot(fr->f, fr->a), g_dot_a = v3_dot(fr->g, fr->a);
    int count = 0;
    for (int i = 0; i < side->ls.count; i++) {
        double t = side->ls.t[i];
        if (clip_to_caps && !(f_dot_a + t * d_dot_a >= 0.0 && g_dot_a + t * d_dot_a <= 0.0))
            continue;
        cyl_end end;
        end_set(&end, t, 0, side->ls.normal[i]);
        int32_t kind = side->ls.count == 1 ? ISECT_TOUCH : (i == 0 ? ISECT_ENTER : ISECT_EXIT);
        count += end_emit(&end, fr, ray, kind, &out[count]);
    }
    return count;
}

/* Closed-solid test on a frame built for point p: between the cap planes
 * (finite only) and |m| <= r|a|, m = (p - p0) x a, compensated. */
static int frame_contains(const cyl_frame *fr, int finite)
{
    if (finite && !(v3_dot(fr->f, fr->a) >= 0.0 && v3_dot(fr->g, fr->a) <= 0.0))
        return 0;
    double m[3];
    cross_accurate(m, fr->f, fr->a);
    return radial_excess(m, fr->r, fr->a) <= 0.0;
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

int cylinder_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                  isect_hit out[ISECT_MAX_HITS])
{
    cyl_frame fr;
    if (!frame_finite(s->data, ray->org, ray->dir, &fr))
        return 0;
    if (s->flags & ISECT_CAPPED)
        return capped_hits(&fr, ray, prm->eps, out);
    cyl_side side;
    side_solve(&fr, prm->eps, &side);
    return side.parallel ? 0 : side_emit(&fr, &side, 1, ray, out);
}

int cylinder_contains(const isect_shape *s, const double p[3])
{
    cyl_frame fr;
    if (!frame_finite(s->data, p, NULL, &fr))
        return 0;
    return frame_contains(&fr, 1);
}

/* ----------------------------------------------------- infinite cylinder */

int cylinder_inf_check(const isect_shape *s)
{
    if (!all_finite(s->data, 7))
        return ISECT_E_NONFINITE;
    return s->data[6] < 0.0 ? ISECT_E_ARG : ISECT_OK;
}

int cylinder_inf_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                      isect_hit out[ISECT_MAX_HITS])
{
    cyl_frame fr;
    if (!frame_infinite(s->data, ray->org, ray->dir, &fr))
        return 0;
    cyl_side side;
    side_solve(&fr, prm->eps, &side);
    /* parallel: inside or outside along the whole line, no crossing */
    return side.parallel ? 0 : side_emit(&fr, &side, 0, ray, out);
}

int cylinder_inf_contains(const isect_shape *s, const double p[3])
{
    cyl_frame fr;
    if (!frame_infinite(s->data, p, NULL, &fr))
        return 0;
    return frame_contains(&fr, 0);
}

/* ------------------------------------------------------------ side tests */

/*
 * Exactly, after one power-of-two scale of every position and the radius
 * (and the infinite cylinder's axis by its own): the radial excess
 * |(p - p0) x a|^2 - r^2 |a|^2 (degree 4) and, for the finite cylinder, the
 * cap values (p - p0).a and (p - p1).a, a the axis (p1 - p0, exact as two
 * parts per component).
 */
typedef struct cyl_signs {
    int radial;      /* sign of the radial excess */
    int below, above; /* (p - p0).a < 0, (p - p1).a > 0 as signs (+1 beyond the cap) */
} cyl_signs;

static void cyl_exact_signs(const double *origin, const xp axis[3], double r, const double p[3],
                            const double *end, int e, cyl_signs *out)
{
    xp f[3], m, sum, aa, tmp;
    for (int k = 0; k < 3; k++)
        xp_diff(&f[k], pow2_scale(p[k], -e), pow2_scale(origin[k], -e));
    xp_set(&sum, 0.0);
    xp_set(&aa, 0.0);
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        xp_mul(&m, &f[i], &axis[j]);
        xp_mul(&tmp, &f[j], &axis[i]);
        xp_sub(&m, &m, &tmp);
        xp_add_mul(&sum, &m, &m);
        xp_add_mul(&aa, &axis[k], &axis[k]);
    }
    double rs = pow2_scale(r, -e);
    xp rr;
    xp_set(&rr, rs);
    xp_scale(&rr, &rr, -rs);
    xp_mul(&tmp, &rr, &aa);
    xp_add(&sum, &sum, &tmp);
    out->radial = xp_sign(&sum);
    out->below = out->above = -1;
    if (end != NULL) {
        xp c0, c1, g;
        xp_set(&c0, 0.0);
        xp_set(&c1, 0.0);
        for (int k = 0; k < 3; k++) {
            xp_add_mul(&c0, &f[k], &axis[k]);
            xp_diff(&g, pow2_scale(p[k], -e), pow2_scale(end[k], -e));
            xp_add_mul(&c1, &g, &axis[k]);
        }
        out->below = -xp_sign(&c0);
        out->above = xp_sign(&c1);
    }
}

/* The capped cylinder as a solid (outside beyond either cap or the side);
 * the open one as the side surface alone, in front of its radial normal. */
int cylinder_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    const double *p0 = s->data, *p1 = s->data + 3;
    double r = s->data[6];
    int e = pow2_exponent(fmax_nan(r, fmax_nan(max_abs3(p), fmax_nan(max_abs3(p0), max_abs3(p1)))));
    xp axis[3];
    int zero_axis = 1;
    for (int k = 0; k < 3; k++) {
        xp_diff(&axis[k], pow2_scale(p1[k], -e), pow2_scale(p0[k], -e));
        zero_axis &= p0[k] == p1[k];
    }
    if (r == 0.0 || zero_axis)
        return 1; /* degenerate */
    cyl_signs cs;
    int capped = (s->flags & ISECT_CAPPED) != 0;
    cyl_exact_signs(p0, axis, r, p, capped ? p1 : NULL, e, &cs);
    if (!capped)
        return cs.radial;
    if (cs.radial > 0 || cs.below > 0 || cs.above > 0)
        return 1;
    return cs.radial < 0 && cs.below < 0 && cs.above < 0 ? -1 : 0;
}

int cylinder_inf_side_test(const isect_shape *s, const double p[3], int32_t prim)
{
    (void)prim;
    const double *point = s->data, *dir = s->data + 3;
    double r = s->data[6];
    if (r == 0.0 || max_abs3(dir) == 0.0)
        return 1;
    int e = pow2_exponent(fmax_nan(r, fmax_nan(max_abs3(p), max_abs3(point))));
    int e_axis = pow2_exponent(max_abs3(dir));
    xp axis[3];
    for (int k = 0; k < 3; k++)
        xp_set(&axis[k], pow2_scale(dir[k], -e_axis));
    cyl_signs cs;
    cyl_exact_signs(point, axis, r, p, NULL, e, &cs);
    return cs.radial;
}
