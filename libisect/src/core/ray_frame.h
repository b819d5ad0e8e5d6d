/*
 * ray_frame.h — the ray's sheared frame (Woop, Benthin & Wald, "Watertight
 * Ray/Triangle Intersection", JCGT 2013), exactly as isect.h documents it.
 *
 * In the frame the ray is the +z axis through the 2D origin and a point on
 * the ray at parameter t has z = t. Faces are tested by exact 2D predicates
 * at the origin, so two faces sharing a vertex must see bit-identical 2D
 * coordinates for it: ray_frame_project is the one place the projection is
 * written, and it uses fma so that no compiler contraction choice can make
 * two call sites round differently.
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

/* q = (x, y) of p in the frame and q[2] = (p - org)[kz] / dir[kz]. */
static inline void ray_frame_project(const ray_frame *f, const double p[3], double q[3])
{
    double px = p[f->kx] - f->org[f->kx];
    double py = p[f->ky] - f->org[f->ky];
    double pz = p[f->kz] - f->org[f->kz];
    q[0] = fma(-f->sx, pz, px);
    q[1] = fma(-f->sy, pz, py);
    q[2] = pz * f->sz;
}

#endif /* ISECT_RAY_FRAME_H */
