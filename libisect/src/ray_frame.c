/*
 * ray_frame.c — building the sheared frame of a ray (see ray_frame.h).
 */
#include "ray_frame.h"

#include "vec3.h"

void ray_frame_shear(const isect_ray *ray, ray_frame *f)
{
    const double *d = ray->dir;
    /* The dominant axis keeps |sx|, |sy| <= 1; ties go to the lowest index
     * so the frame is a function of dir alone. */
    int kz = 0;
    if (fabs(d[1]) > fabs(d[kz]))
        kz = 1;
    if (fabs(d[2]) > fabs(d[kz]))
        kz = 2;
    int kx = (kz + 1) % 3, ky = (kz + 2) % 3;
    /* (kx, ky, kz) is a cyclic, right-handed permutation; when z runs
     * against dir[kz] swapping x and y keeps the frame right-handed, so a
     * face counter-clockwise in the frame has its normal along the ray. */
    if (d[kz] < 0.0) {
        int swap = kx;
        kx = ky;
        ky = swap;
    }
    f->kx = kx;
    f->ky = ky;
    f->kz = kz;
    f->sx = d[kx] / d[kz];
    f->sy = d[ky] / d[kz];
    f->sz = 1.0 / d[kz];
    v3_copy(f->org, ray->org);
    f->dir_len = v3_norm(d);
}
