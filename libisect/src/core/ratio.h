/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ratio.h — a crossing parameter t = num / den decided exactly, for the
 * exact paths of the planar primitives (a plane, a face, a slab of a box
 * or a convex polyhedron, a cylinder's cap): the primitive forms num and
 * den as exact expansions (expansion.h) in its own scaled units, and this
 * decides whether the crossing exists (den != 0) and lies in [tmin, tmax]
 * (signs of num - tau den), and rounds t to a double-double.
 */
#ifndef ISECT_RATIO_H
#define ISECT_RATIO_H

#include "core/expansion.h"

/* The crossing t = num/den: 0 when den == 0 (no crossing point); else 1,
 * with *in_range set when tmin <= t <= tmax exactly (tmin, tmax in the same
 * units as t, either may be infinite) and t = *t_hi + *t_lo to within
 * 4u^2 |t| (t_hi = t rounded). */
int ratio_decide(const xp *num, const xp *den, double tmin, double tmax, int *in_range,
                 double *t_hi, double *t_lo);

/* sign(num/den - tau), exactly (den != 0; tau may be infinite). */
int ratio_cmp_tau(const xp *num, const xp *den, double tau);

/* sign(n1/d1 - n2/d2), exactly (d1, d2 != 0). */
int ratio_cmp(const xp *n1, const xp *d1, const xp *n2, const xp *d2);

/* num/den as a double-double, within 4u^2 |t| (t_hi = t rounded); den != 0. */
void ratio_value(const xp *num, const xp *den, double *t_hi, double *t_lo);

/* The epsilon policy's parallel test |den| <= eps sqrt(nn dd) (den = n.dir,
 * nn = |n|^2, dd = |dir|^2), exactly: 1 parallel, 0 not. With eps = 0 it is
 * den == 0. The squares are taken after scaling den and eps by one power
 * of two, so that a tiny den does not underflow to a false "parallel". */
int parallel_exact(const xp *den, const xp *nn, const xp *dd, double eps);

#endif /* ISECT_RATIO_H */
