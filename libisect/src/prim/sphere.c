/*
 * sphere.c — the sphere |x - c| = r (ISECT_SPHERE, data = c[3], r) and the
 * axis-aligned ellipsoid sum(((x - c)/radii)^2) = 1 (ISECT_ELLIPSOID, data =
 * c[3], radii[3]). Both are solids; prim -1.
 *
 * Both reduce to line_sphere_roots() (quadratic.c): the sphere directly, the
 * ellipsoid as the unit sphere in the frame y = (x - c)/radii, where the
 * line keeps its parameter t. Tangency is therefore |r^2 - h^2| <= eps r^2
 * for the sphere and |1 - h'^2| <= eps for the ellipsoid (h' the distance
 * from the centre to the line in the scaled frame).
 *
 * Hit points are snapped onto the surface, c + r n (c + radii*n' for the
 * ellipsoid), when that is the more accurate of the two ways to place them:
 * the snapped point carries an error of order u(|c| + r), org + t*dir one of
 * order u(|org| + |t dir|), so the snapped one is used when |c| + r is the
 * smaller (a small sphere near the coordinate origin seen from afar), and
 * org + t*dir otherwise (a huge sphere hit near its surface's closest point
 * to the origin, where c + r n would lose the small coordinates). A TOUCH
 * is never snapped: its point is defined as the foot of the perpendicular,
 * org + t_m dir, which under eps may lie off the surface by up to ~eps r/2.
 *
 * A zero radius (any zero semi-axis) is degenerate: no hits, no points
 * inside. An ellipsoid whose semi-axes differ by more than the double range
 * (ratio above ~2^1022) cannot be scaled to a unit sphere and is treated as
 * degenerate too.
 */
#include "prim/prim.h"
#include "core/quadratic.h"
#include "core/vec3.h"

/* One crossing in the ray's units: t, the world normal, and the point
 * placed on the surface from the centre. */
typedef struct crossing {
    double t;
    double normal[3];
    double snapped[3];
} crossing;

/*
 * The crossings of `ls` as hits. For ENTER / EXIT the snapped point replaces
 * org + t*dir when its error scale `snap_scale` (|c| + r) is below that of
 * org + t*dir (see the top of the file).
 */
static int emit_crossings(const line_sphere *ls, const crossing cr[2], double snap_scale,
                          const isect_ray *ray, isect_hit out[ISECT_MAX_HITS])
{
    int count = 0;
    for (int i = 0; i < ls->count; i++) {
        if (!isfinite(cr[i].t))
            continue; /* beyond the double range: not reported */
        int32_t kind = ls->count == 1 ? ISECT_TOUCH : (i == 0 ? ISECT_ENTER : ISECT_EXIT);
        isect_hit *h = &out[count++];
        hit_set(h, ray, cr[i].t, cr[i].normal, -1, kind);
        double ray_scale = max_abs3(ray->org) + fabs(cr[i].t) * max_abs3(ray->dir);
        if (ls->count == 2 && snap_scale < ray_scale)
            v3_copy(h->point, cr[i].snapped);
    }
    return count;
}

/* ---------------------------------------------------------------- sphere */

int sphere_check(const isect_shape *s)
{
    if (!all_finite(s->data, 4))
        return ISECT_E_NONFINITE;
    return s->data[3] < 0.0 ? ISECT_E_ARG : ISECT_OK;
}

int sphere_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                isect_hit out[ISECT_MAX_HITS])
{
    const double *c = s->data;
    double r = s->data[3];
    if (r == 0.0)
        return 0;
    /* org - c without overflow: both scaled by the power of two of the
     * largest coordinate first (exact), t scaled back at the end. */
    int e = pow2_exponent(fmax_nan(r, fmax_nan(max_abs3(ray->org), max_abs3(c))));
    double f[3];
    for (int k = 0; k < 3; k++) /* the same operations as scale3 + v3_sub */
        f[k] = pow2_scale(ray->org[k], -e) - pow2_scale(c[k], -e);

    line_sphere ls;
    line_sphere_roots(f, ray->dir, pow2_scale(r, -e), prm->eps, &ls);
    crossing cr[2];
    for (int i = 0; i < ls.count; i++) {
        cr[i].t = pow2_scale(ls.t[i], e);
        v3_copy(cr[i].normal, ls.normal[i]);
        v3_madd(cr[i].snapped, c, r, ls.normal[i]);
    }
    return emit_crossings(&ls, cr, max_abs3(c) + r, ray, out);
}

int sphere_contains(const isect_shape *s, const double p[3])
{
    const double *c = s->data;
    double r = s->data[3];
    if (r == 0.0)
        return 0;
    int e = pow2_exponent(fmax_nan(r, fmax_nan(max_abs3(p), max_abs3(c))));
    double p_s[3], c_s[3], f[3];
    scale3(p_s, p, e);
    scale3(c_s, c, e);
    v3_sub(f, p_s, c_s);
    return sumsq_minus_sq(f, pow2_scale(r, -e)) <= 0.0;
}

/* ------------------------------------------------------------- ellipsoid */

/*
 * The ellipsoid's frame. Positions and semi-axes share one power-of-two
 * scale 2^-e (so org - c cannot overflow), y0 = (org - c)/radii is then
 * scale-free; the direction gets its own scale 2^-e_dir, so the line is
 * y0 + t' dy with dy = dir 2^-e_dir / radii_s and t = t' 2^(e - e_dir).
 * Returns 0 when the frame does not exist (a zero or hopelessly small
 * semi-axis).
 */
typedef struct ellipsoid_frame {
    double radii_s[3]; /* radii 2^-e, the largest in [0.5, 1) */
    double y0[3];
    double dy[3];
    int    t_shift;    /* e - e_dir */
} ellipsoid_frame;

static int ellipsoid_frame_make(const double *data, const double org[3], const double dir[3],
                                ellipsoid_frame *fr)
{
    const double *c = data, *radii = data + 3;
    if (radii[0] == 0.0 || radii[1] == 0.0 || radii[2] == 0.0)
        return 0;
    int e = pow2_exponent(fmax_nan(max_abs3(radii), fmax_nan(max_abs3(org), max_abs3(c))));
    int e_dir = dir != NULL ? pow2_exponent(max_abs3(dir)) : 0;
    for (int k = 0; k < 3; k++) {
        fr->radii_s[k] = pow2_scale(radii[k], -e);
        fr->y0[k] = (pow2_scale(org[k], -e) - pow2_scale(c[k], -e)) / fr->radii_s[k];
        fr->dy[k] = dir != NULL ? pow2_scale(dir[k], -e_dir) / fr->radii_s[k] : 0.0;
    }
    fr->t_shift = e - e_dir;
    return all_finite(fr->y0, 3) && all_finite(fr->dy, 3);
}

int ellipsoid_check(const isect_shape *s)
{
    if (!all_finite(s->data, 6))
        return ISECT_E_NONFINITE;
    const double *radii = s->data + 3;
    return radii[0] < 0.0 || radii[1] < 0.0 || radii[2] < 0.0 ? ISECT_E_ARG : ISECT_OK;
}

int ellipsoid_hits(const isect_shape *s, const isect_ray *ray, const isect_params *prm,
                   isect_hit out[ISECT_MAX_HITS])
{
    ellipsoid_frame fr;
    if (!ellipsoid_frame_make(s->data, ray->org, ray->dir, &fr))
        return 0;
    line_sphere ls;
    line_sphere_roots(fr.y0, fr.dy, 1.0, prm->eps, &ls);

    /* World normal: grad of sum(y^2) = 2 y / radii, y = n' on the unit
     * sphere; divided by radii_s / min(radii_s) instead (same direction,
     * factors <= 1, so no overflow whatever the semi-axis ratio). */
    const double *c = s->data, *radii = s->data + 3;
    double r_min = fmin(fr.radii_s[0], fmin(fr.radii_s[1], fr.radii_s[2]));
    crossing cr[2];
    for (int i = 0; i < ls.count; i++) {
        cr[i].t = pow2_scale(ls.t[i], fr.t_shift);
        double g[3];
        for (int k = 0; k < 3; k++) {
            g[k] = ls.normal[i][k] * (r_min / fr.radii_s[k]);
            cr[i].snapped[k] = c[k] + radii[k] * ls.normal[i][k];
        }
        normal_or_facing(cr[i].normal, g, ray->dir, ISECT_TOUCH); /* g != 0 */
    }
    return emit_crossings(&ls, cr, max_abs3(c) + max_abs3(radii), ray, out);
}

int ellipsoid_contains(const isect_shape *s, const double p[3])
{
    ellipsoid_frame fr;
    if (!ellipsoid_frame_make(s->data, p, NULL, &fr))
        return 0; /* degenerate, or p so far out that y overflows */
    return sumsq_minus_sq(fr.y0, 1.0) <= 0.0;
}

