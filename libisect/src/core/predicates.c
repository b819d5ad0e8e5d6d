/* SPDX-License-Identifier: Apache-2.0 */
/*
 * predicates.c — exact orientation signs with error-free transformations.
 *
 * orient2_sign follows the structure of Shewchuk's adaptive predicates
 * ("Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
 * Predicates", DCG 1997): a floating-point evaluation with a static error
 * bound decides almost every call; the rest are evaluated exactly as a
 * nonoverlapping expansion whose largest component carries the sign.
 * TwoSum is Knuth's, TwoProduct uses one fma (exact product error).
 */
#include "core/predicates.h"

#include <float.h>
#include <math.h>

/* u = 2^-53, the unit roundoff of binary64. */
#define UNIT_ROUNDOFF (DBL_EPSILON / 2.0)

/* det = fl(fl(ax-cx) * fl(by-cy)) - fl(fl(ay-cy) * fl(bx-cx)) carries three
 * roundings on each side, so |det - exact| <= (3u + 16u^2)(|l| + |r|) with
 * l, r the two computed products (Shewchuk's ccwerrboundA). */
#define ORIENT2_FILTER ((3.0 + 16.0 * UNIT_ROUNDOFF) * UNIT_ROUNDOFF)

/* The bound assumes relative rounding errors. With detsum >= 2^-960 the
 * larger product is normal and a subnormal smaller one errs by at most
 * 2^-1075 <= 2^-115 detsum, inside the bound's 16u^2 slack; smaller
 * determinants (possibly underflowed) go to the exact evaluation. */
#define ORIENT2_FILTER_MIN 0x1p-960

/* x + y = *s + *e exactly, |*e| <= ulp(*s)/2 (Knuth's TwoSum; no branch on
 * magnitudes, exact for any finite x, y whose sum does not overflow). */
static void two_sum(double x, double y, double *s, double *e)
{
    double sum = x + y;
    double y_part = sum - x;
    double x_part = sum - y_part;
    *e = (x - x_part) + (y - y_part);
    *s = sum;
}

/* x * y = *p + *e exactly, provided the product error does not underflow
 * (see the exactness range in predicates.h). */
static void two_product(double x, double y, double *p, double *e)
{
    double prod = x * y;
    *e = fma(x, y, -prod);
    *p = prod;
}

/* A nonoverlapping expansion, components in increasing magnitude, zeros
 * removed: its value is the exact sum of everything added, its sign that
 * of its last component. 16 components suffice for orient2 (8 products,
 * two parts each). */
typedef struct expansion {
    double part[16];
    int    count;
} expansion;

/* Shewchuk's GROW-EXPANSION with zero elimination on part[0 .. *count):
 * adding one double lengthens the expansion by at most one component (the
 * caller provides room for one more). */
static void parts_add(double *part, int *count, double b)
{
    if (b == 0.0)
        return;
    double carry = b;
    int kept = 0;
    for (int i = 0; i < *count; i++) {
        double sum, err;
        two_sum(carry, part[i], &sum, &err);
        if (err != 0.0)
            part[kept++] = err;
        carry = sum;
    }
    if (carry != 0.0)
        part[kept++] = carry;
    *count = kept;
}

static void expansion_add(expansion *x, double b)
{
    parts_add(x->part, &x->count, b);
}

/* Adds sign * (x_hi + x_lo) * (y_hi + y_lo) exactly: four products, each
 * split by TwoProduct. */
static void expansion_add_product(expansion *acc, double sign, double x_hi, double x_lo,
                                  double y_hi, double y_lo)
{
    const double xs[2] = { x_hi, x_lo }, ys[2] = { y_hi, y_lo };
    for (int i = 0; i < 2; i++) {
        for (int j = 0; j < 2; j++) {
            if (xs[i] == 0.0 || ys[j] == 0.0)
                continue;
            double p, e;
            two_product(sign * xs[i], ys[j], &p, &e);
            expansion_add(acc, e);
            expansion_add(acc, p);
        }
    }
}

/* The slow path. The sign is invariant under scaling all six coordinates by
 * one power of two, so they are first brought to a largest magnitude in
 * [1, 2) (exact unless the input spans more than ~2^1000): then no product
 * overflows and, for coordinates within 2^480 of the largest, none loses
 * bits to underflow. Each difference is split exactly into head + tail
 * (TwoSum of x and -y) and the determinant expanded into its 8 products. */
static int orient2_exact(const double a[2], const double b[2], const double c[2])
{
    double m = 0.0;
    for (int k = 0; k < 2; k++)
        m = fmax(m, fmax(fabs(a[k]), fmax(fabs(b[k]), fabs(c[k]))));
    if (m == 0.0)
        return 0;
    int e = -ilogb(m);
    double sa[2], sb[2], sc[2];
    for (int k = 0; k < 2; k++) {
        sa[k] = ldexp(a[k], e);
        sb[k] = ldexp(b[k], e);
        sc[k] = ldexp(c[k], e);
    }
    double acx, acx_t, acy, acy_t, bcx, bcx_t, bcy, bcy_t;
    two_sum(sa[0], -sc[0], &acx, &acx_t);
    two_sum(sa[1], -sc[1], &acy, &acy_t);
    two_sum(sb[0], -sc[0], &bcx, &bcx_t);
    two_sum(sb[1], -sc[1], &bcy, &bcy_t);
    expansion det = { { 0.0 }, 0 };
    expansion_add_product(&det, 1.0, acx, acx_t, bcy, bcy_t);
    expansion_add_product(&det, -1.0, acy, acy_t, bcx, bcx_t);
    if (det.count == 0)
        return 0;
    return det.part[det.count - 1] > 0.0 ? 1 : -1;
}

int orient2_sign(const double a[2], const double b[2], const double c[2])
{
    double acx = a[0] - c[0], acy = a[1] - c[1];
    double bcx = b[0] - c[0], bcy = b[1] - c[1];
    double left = acx * bcy;
    double right = acy * bcx;
    double det = left - right;
    double detsum = fabs(left) + fabs(right);
    if (detsum >= ORIENT2_FILTER_MIN) {
        /* An overflowed detsum makes the bound infinite: both tests fail. */
        double bound = ORIENT2_FILTER * detsum;
        if (det > bound)
            return 1;
        if (-det > bound)
            return -1;
    } else if ((acx == 0.0 || bcy == 0.0) && (acy == 0.0 || bcx == 0.0)) {
        /* Each product has a factor that is exactly zero (fl(x - y) == 0
         * only when x == y, so its tail is zero too): the common case of a
         * vertex on the query point or an axis-parallel edge through it. */
        return 0;
    }
    return orient2_exact(a, b, c);
}

/* orient(p, q, c) is affine in c: d/dc.x = p.y - q.y, d/dc.y = q.x - p.x.
 * Moving c by (-e^2, -e) adds -e (q.x - p.x) - e^2 (p.y - q.y), so the first
 * nonzero of sign(p.x - q.x), sign(q.y - p.y) decides a zero determinant. */
int orient2_sign_perturbed(const double p[2], const double q[2], const double c[2])
{
    int s = orient2_sign(p, q, c);
    if (s != 0)
        return s;
    if (p[0] != q[0])
        return p[0] > q[0] ? 1 : -1;
    if (p[1] != q[1])
        return q[1] > p[1] ? 1 : -1;
    return 0;
}

int winding_edge(const double p[2], const double q[2], const double c[2])
{
    /* A vertex on c's horizontal line is above the perturbed point, so
     * "y >= c.y" is the half-open rule; a horizontal edge on the line has
     * both ends above and never crosses. */
    int p_above = p[1] >= c[1];
    int q_above = q[1] >= c[1];
    if (p_above == q_above)
        return 0;
    int side = orient2_sign_perturbed(p, q, c);
    if (!p_above)
        return side > 0 ? 1 : 0;  /* upward, c on the left */
    return side < 0 ? -1 : 0;     /* downward, c on the right */
}

int collinear3(const double a[3], const double b[3], const double c[3])
{
    /* The components of (b - a) x (c - a) are the orientations of the
     * projections onto the yz, zx and xy planes. */
    static const int axes[3][2] = { { 1, 2 }, { 2, 0 }, { 0, 1 } };
    for (int k = 0; k < 3; k++) {
        int i = axes[k][0], j = axes[k][1];
        const double a2[2] = { a[i], a[j] }, b2[2] = { b[i], b[j] }, c2[2] = { c[i], c[j] };
        if (orient2_sign(a2, b2, c2) != 0)
            return 0;
    }
    return 1;
}



/* --------------------------------------------------------------- orient3 */

/* Shewchuk's o3derrboundA: the filter's evaluation below carries at most
 * (7u + 56u^2) times the permanent of rounding error. */
#define ORIENT3_FILTER ((7.0 + 56.0 * UNIT_ROUNDOFF) * UNIT_ROUNDOFF)

/* As ORIENT2_FILTER_MIN: below this the bound is no longer relative. */
#define ORIENT3_FILTER_MIN 0x1p-900

/* Components of the exact orient3 expansion: 6 terms of 8 triple products
 * of two-part factors, each split into 4 doubles, and GROW-EXPANSION adds
 * at most one component per double added. */
#define ORIENT3_PARTS 192

/* The slow path: scaled as in orient2_exact (a power of two, exact), each
 * difference split into head + tail by TwoSum, and the determinant
 * (a-d) . ((b-d) x (c-d)) expanded into its 48 triple products of parts,
 * each exact as four doubles (TwoProduct of the first two factors, then of
 * both halves by the third). */
static int orient3_exact(const double a[3], const double b[3], const double c[3],
                         const double d[3])
{
    double m = 0.0;
    for (int k = 0; k < 3; k++)
        m = fmax(m, fmax(fmax(fabs(a[k]), fabs(b[k])), fmax(fabs(c[k]), fabs(d[k]))));
    if (m == 0.0)
        return 0;
    int e = -ilogb(m);
    double diff[3][3][2]; /* [point a, b, c][axis][head, tail] of point - d */
    const double *pts[3] = { a, b, c };
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            two_sum(ldexp(pts[i][k], e), -ldexp(d[k], e), &diff[i][k][0], &diff[i][k][1]);
    /* det = sum over permutations (i, j, l) of the axes of sign * a_i b_j c_l. */
    static const int perm[6][3] = { { 0, 1, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
                                    { 0, 2, 1 }, { 1, 0, 2 }, { 2, 1, 0 } };
    double part[ORIENT3_PARTS];
    int count = 0;
    for (int t = 0; t < 6; t++) {
        double sign = t < 3 ? 1.0 : -1.0;
        for (int x = 0; x < 2; x++) {
            double fa = sign * diff[0][perm[t][0]][x];
            if (fa == 0.0)
                continue;
            for (int y = 0; y < 2; y++) {
                double fb = diff[1][perm[t][1]][y];
                if (fb == 0.0)
                    continue;
                double p, pe;
                two_product(fa, fb, &p, &pe);
                for (int z = 0; z < 2; z++) {
                    double fc = diff[2][perm[t][2]][z];
                    if (fc == 0.0)
                        continue;
                    double q[4];
                    two_product(p, fc, &q[1], &q[0]);
                    two_product(pe, fc, &q[3], &q[2]);
                    for (int i = 0; i < 4; i++)
                        parts_add(part, &count, q[i]);
                }
            }
        }
    }
    if (count == 0)
        return 0;
    return part[count - 1] > 0.0 ? 1 : -1;
}

int orient3_sign(const double a[3], const double b[3], const double c[3], const double d[3])
{
    double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
    double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
    double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
    double bc_x = bdx * cdy, cb_x = bdy * cdx;
    double ca_x = cdx * ady, ac_x = cdy * adx;
    double ab_x = adx * bdy, ba_x = ady * bdx;
    double det = adz * (bc_x - cb_x) + bdz * (ca_x - ac_x) + cdz * (ab_x - ba_x);
    double permanent = (fabs(bc_x) + fabs(cb_x)) * fabs(adz)
                     + (fabs(ca_x) + fabs(ac_x)) * fabs(bdz)
                     + (fabs(ab_x) + fabs(ba_x)) * fabs(cdz);
    if (permanent >= ORIENT3_FILTER_MIN) {
        /* An overflowed permanent makes the bound infinite: both tests fail. */
        double bound = ORIENT3_FILTER * permanent;
        if (det > bound)
            return 1;
        if (-det > bound)
            return -1;
    }
    return orient3_exact(a, b, c, d);
}
