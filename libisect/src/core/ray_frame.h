/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ray_frame.h — the ray's sheared frame (Woop, Benthin & Wald, "Watertight
 * Ray/Triangle Intersection", JCGT 2013), exactly as isect.h documents it.
 *
 * In the frame the ray is the +z axis through the 2D origin and a point on
 * the ray at parameter t has z = t. Faces are tested at the origin on the
 * EXACT projection of their vertices (core/frame_signs.h; the fast
 * kernels certify its signs, prim/face_lanes.h), so no two call sites can
 * disagree about a vertex's image; the frame fixes only which axes are x,
 * y and z (and the shear, for the mesh's conservative pre-filter).
 */
#ifndef ISECT_RAY_FRAME_H
#define ISECT_RAY_FRAME_H

#include "isect.h"

#include <math.h>

typedef struct ray_frame {
    int    kx, ky, kz; /* permutation: kz = dominant axis of dir */
    double sx, sy, sz; /* shear dir[kx]/dir[kz], dir[ky]/dir[kz]; scale 1/dir[kz] */
    double org[3], dir[3]; /* the ray's, for the exact signs (frame_signs.h) */
} ray_frame;

/* The frame of a valid ray (finite, dir != 0). */
void ray_frame_shear(const isect_ray *ray, ray_frame *f);

#endif /* ISECT_RAY_FRAME_H */
