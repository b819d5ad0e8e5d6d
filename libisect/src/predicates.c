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
#include "predicates.h"

#include <float.h>
#include <math.h>

/* u = 2^-53, the unit roundoff of binary64. */
#define UNIT_ROUNDOFF (DBL_EPSILON / 2.0)

/* det = fl(fl(ax-cx) * fl(by-cy)) - fl(fl(ay-cy) * fl(bx-cx)) carries three
 * roundings on each side, so |det - exact| <= (3u + 16u^2)(|l| + |r|) with
 * l, r the two computed products (Shewchuk's ccwerrboundA). */
#define ORIENT2_FILTER ((3.0 + 16.0 * UNIT_ROUNDOFF) * UNIT_ROUNDOFF)

/* Below this the bound itself would be a subnormal and lose its relative
 * accuracy; such tiny determinants go to the exact evaluation instead. */
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

/* Shewchuk's GROW-EXPANSION with zero elimination: adding one double
 * lengthens the expansion by at most one component. */
static void expansion_add(expansion *x, double b)
{
    if (b == 0.0)
        return;
    double carry = b;
    int kept = 0;
    for (int i = 0; i < x->count; i++) {
        double sum, err;
        two_sum(carry, x->part[i], &sum, &err);
        if (err != 0.0)
            x->part[kept++] = err;
        carry = sum;
    }
    if (carry != 0.0)
        x->part[kept++] = carry;
    x->count = kept;
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

/* The slow path: each difference split exactly into head + tail (TwoSum of
 * a and -c), the determinant expanded into its 8 products and summed. */
static int orient2_exact(const double a[2], const double b[2], const double c[2])
{
    double acx, acx_t, acy, acy_t, bcx, bcx_t, bcy, bcy_t;
    two_sum(a[0], -c[0], &acx, &acx_t);
    two_sum(a[1], -c[1], &acy, &acy_t);
    two_sum(b[0], -c[0], &bcx, &bcx_t);
    two_sum(b[1], -c[1], &bcy, &bcy_t);
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
        double bound = ORIENT2_FILTER * detsum;
        if (det > bound)
            return 1;
        if (-det > bound)
            return -1;
    } else if (detsum == 0.0) {
        /* In the exactness range a zero product means an exactly zero
         * difference (fl(x - y) == 0 only when x == y), so both exact
         * products vanish. */
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

double det2_accurate(double a, double b, double c, double d)
{
    double bc = b * c;
    double bc_err = fma(-b, c, bc); /* bc - b*c, exact */
    double diff = fma(a, d, -bc);   /* a*d - bc, one rounding */
    return diff + bc_err;
}
