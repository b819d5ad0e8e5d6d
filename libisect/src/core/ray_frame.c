/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ray_frame.c — building the sheared frame of a ray (see ray_frame.h).
 */
#include "core/ray_frame.h"

#include "core/vec3.h"

void ray_frame_shear(const isect_ray *ray, ray_frame *f)
{
    const double *d = ray->dir;
    /* The dominant axis keeps |sx|, |sy| <= 1; ties go to the lowest index
     * so the frame is a function of dir alone. */
    /* Written as selects, not branches (the same choices: random rays
     * would mispredict the branches): kz = 1 iff |d1| > |d0|, then 2 iff
     * |d2| > |d[kz]|. */
    double a0 = fabs(d[0]), a1 = fabs(d[1]), a2 = fabs(d[2]);
    int kz = a1 > a0;
    double a01 = kz ? a1 : a0;
    kz = a2 > a01 ? 2 : kz;
    static const int next[3] = { 1, 2, 0 }, prev[3] = { 2, 0, 1 };
    /* (kx, ky, kz) is a cyclic, right-handed permutation; when z runs
     * against dir[kz] swapping x and y keeps the frame right-handed, so a
     * face counter-clockwise in the frame has its normal along the ray. */
    int neg = d[kz] < 0.0;
    int kx = neg ? prev[kz] : next[kz];
    int ky = neg ? next[kz] : prev[kz];
    f->kx = kx;
    f->ky = ky;
    f->kz = kz;
    f->sx = d[kx] / d[kz];
    f->sy = d[ky] / d[kz];
    f->sz = 1.0 / d[kz];
    v3_copy(f->org, ray->org);
    v3_copy(f->dir, ray->dir);
}
