/* SPDX-License-Identifier: Apache-2.0 */
/*
 * predicates.h — exact sign predicates in the plane, and the tie-breaking
 * rule every point-in-polygon and ray/face decision of the library uses.
 *
 * Exactness range. The signs below are exact for every finite input whose
 * nonzero coordinates lie within a factor 2^480 of the largest one, at any
 * absolute scale: the slow path first scales all coordinates by one power
 * of two (exact) to a largest magnitude in [1, 2), so no product overflows,
 * every coordinate is a multiple of 2^-532 and every product a multiple of
 * 2^-1064, which no TwoProduct error term loses to underflow. Outside that
 * range the result is still a deterministic function of the input and
 * still antisymmetric (orient2_sign(b, a, c) == -orient2_sign(a, b, c)), so
 * shared edges stay consistent, but a nearly zero determinant may get the
 * wrong sign.
 */
#ifndef ISECT_PREDICATES_H
#define ISECT_PREDICATES_H

#include <math.h>

#include "isect.h"

/* Sign of (a - c) x (b - c): +1 when a, b, c turn counter-clockwise, -1
 * clockwise, 0 collinear. Shewchuk-style floating-point filter, then an
 * exact expansion sum where the filter cannot decide. */
int orient2_sign(const double a[2], const double b[2], const double c[2]);

/* The sign after moving the query point c by (-e^2, -e), e > 0
 * infinitesimal (the "move the ray up epsilon" rule made exact): a vertex
 * with y == c.y counts as above c, a horizontal edge on c's line crosses
 * nothing. Nonzero unless p == q. Antisymmetric in p, q. */
int orient2_sign_perturbed(const double p[2], const double q[2], const double c[2]);

/* Winding-number contribution (+1, -1 or 0) of the edge p -> q around c
 * under the same perturbation: +1 for an upward crossing with c on its
 * left, -1 for a downward crossing with c on its right (Sunday 2001;
 * Hormann & Agathos 2001). Summed over a closed polygon it is the winding
 * number of the perturbed point, which is never on an edge. */
int winding_edge(const double p[2], const double q[2], const double c[2]);

/* A polygon fill rule of isect.h, and whether a winding number is inside
 * under it (even-odd: the crossing number's parity, which equals the
 * winding number's). */
static inline int fill_rule_valid(int rule)
{
    return rule == ISECT_EVEN_ODD || rule == ISECT_NONZERO;
}
static inline int fill_rule_inside(int32_t winding, int rule)
{
    return rule == ISECT_NONZERO ? winding != 0 : winding % 2 != 0;
}

/* 1 when a, b, c lie exactly on one line in 3D (coincident points
 * included): each coordinate-plane projection has a zero orientation. */
int collinear3(const double a[3], const double b[3], const double c[3]);

/* Sign of det[a - d; b - d; c - d] = (a - d) . ((b - a) x (c - a)): +1 when
 * d lies below the plane through a, b, c (the side opposite to their
 * right-hand normal), -1 above, 0 when the four points are coplanar
 * (Shewchuk's orient3d: a floating-point filter with his error bound, then
 * an exact expansion where the filter cannot decide). Exact for finite
 * input whose nonzero coordinates lie within a factor 2^260 of the largest
 * (the exact path scales by a power of two as orient2's does, and its
 * triple products must not underflow); outside that range deterministic. */
int orient3_sign(const double a[3], const double b[3], const double c[3], const double d[3]);

/*
 * fma(x, y, -p) for p = fl(x*y) != 0, i.e. the exact product error, by
 * Dekker's TwoProduct (Veltkamp split) where that is exact: |x|, |y| <=
 * 2^995 (no overflow in the split) and 2^-860 <= |p| <= 2^1000 (e_x + e_y
 * >= -861, far above the -970 below which partial products could lose bits
 * to underflow). The error is then representable, so fma returns it
 * unrounded and both agree bit for bit (an exact zero is +0 in both: the
 * Dekker sum starts with xh*yh - p, nonzero factors). Elsewhere fma itself.
 * Without -mfma, fma() is a libm call that spills every live register.
 */
static inline double product_error(double x, double y, double p)
{
    double ap = fabs(p);
    if (fabs(x) <= 0x1p995 && fabs(y) <= 0x1p995 && ap >= 0x1p-860 && ap <= 0x1p1000) {
        const double split = 134217729.0; /* 2^27 + 1 */
        double cx = split * x, cy = split * y;
        double xh = cx - (cx - x), yh = cy - (cy - y);
        double xl = x - xh, yl = y - yh;
        return ((xh * yh - p) + xh * yl + xl * yh) + xl * yl;
    }
    return fma(x, y, -p);
}

/* a*d - b*c with relative error <= 2u by Kahan's FMA algorithm
 * (Jeannerod, Louvet & Muller, Math. Comp. 2013); away from underflow the
 * result is zero exactly when a*d == b*c and otherwise has the right sign.
 * Inline: the quadric family calls it on every ray. */
static inline double det2_accurate(double a, double b, double c, double d)
{
    double bc = b * c;
    /* fma(-b, c, bc) = (-b) c - fl((-b) c): fl((-b) c) = -bc exactly (sign
     * symmetry of rounding), so this is product_error(-b, c, -bc). */
    double bc_err = product_error(-b, c, -bc); /* bc - b*c, exact */
    double diff = fma(a, d, -bc);   /* a*d - bc, one rounding */
    return diff + bc_err;
}

#endif /* ISECT_PREDICATES_H */
