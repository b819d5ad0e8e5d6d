/* SPDX-License-Identifier: Apache-2.0 */
/*
 * frame_signs.h — the signs that decide whether a ray crosses a triangle or
 * polygon, evaluated exactly on the given doubles: the sheared-frame test of
 * isect.h ("Tie-breaking") on the EXACT projected coordinates, which the
 * fast kernels (prim/face_lanes.h) certify in plain double and defer to
 * these where they cannot.
 *
 * The exact projection. For a vertex v and a ray o + t d, with A = v - o
 * (real, not rounded) and (kx, ky, kz) the frame's axes,
 *     x = A[kx] - (d[kx]/d[kz]) A[kz],   y = A[ky] - (d[ky]/d[kz]) A[kz].
 * Multiplied by |d[kz]| (which keeps every sign below) these are components
 * of the cross product A x d:
 *     |d[kz]| x = -(A x d)[ky],   |d[kz]| y = (A x d)[kx]
 * (the frame is right-handed with the ray along +z, so the swap of kx and ky
 * for d[kz] < 0 absorbs the sign of d[kz]). The orientation of an edge
 * p -> q about the frame origin is then
 *     x_p y_q - y_p x_q = d . ((p - o) x (q - o)) / |d[kz]|,
 * a triple product that does not depend on the frame at all; only the
 * ties (a zero orientation, a vertex on the test line y = 0) use the axes.
 *
 * Exactness. Every quantity is a polynomial of degree 2 or 3 in the input
 * doubles, expanded into its products and summed exactly by
 * core/dyadic_sum.c whatever the exponents involved: the signs are exact
 * for every finite input (subnormal coordinates and direction components
 * included).
 */
#ifndef ISECT_FRAME_SIGNS_H
#define ISECT_FRAME_SIGNS_H

#include "core/ray_frame.h"

/* 1 when the exact projection of v lies on or above the test line
 * (y >= 0: the perturbed query point is below it), else 0. */
int frame_above_exact(const ray_frame *f, const double v[3]);

/* The exact orientation of the edge p -> q about the perturbed frame
 * origin (orient2_sign_perturbed on the exact projections): the sign of
 * d . ((p - o) x (q - o)); where that is zero, the sign of x_p - x_q, then
 * of y_q - y_p. +1 or -1; 0 only when p and q project to the same point
 * (p - q parallel to d). Antisymmetric in p, q. */
int frame_orient_exact(const ray_frame *f, const double p[3], const double q[3]);

/* The triangle's three orientations d . (B x C), d . (C x A), d . (A x B)
 * (A = a - o, ...: the unnormalised barycentric weights of a, b, c) as
 * doubles, each the exact value times one common power of two, rounded
 * once: for the weights of a triangle whose fast test was not certain. */
void frame_triangle_weights_exact(const ray_frame *f, const double a[3], const double b[3],
                                  const double c[3], double w[3]);

#endif /* ISECT_FRAME_SIGNS_H */
