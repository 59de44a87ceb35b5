/* A camera's ray-making constants, worked out once: its axes and the half
 * sizes of the image plane. hr_camera_ray makes one for every ray it is
 * asked for; a render makes one for the whole image (the axes take two
 * square roots and the plane a tangent, more than the ray itself costs).
 * Both give a ray the same bits, because they run the same code. */
#ifndef HITRAY_LIB_GEOMETRY_CAMERA_FRAME_H
#define HITRAY_LIB_GEOMETRY_CAMERA_FRAME_H

#include <hitray/camera.h>

#include "geometry/vec.h"

typedef struct hr_camera_frame {
    hr_vec3 eye, u, v, n;
    double half_width, half_height; /* W and H of the plane at distance 1 */
    double width, height;           /* the image, in pixels */
} hr_camera_frame;

/* 0 (and the frame unset) where hr_camera_ray refuses the camera. */
int hri_camera_frame_init(hr_camera_frame *f, const hr_camera *cam);

/* The ray's two coordinates on the image plane, each of one image
 * coordinate alone, so a caller that makes a row of rays works each column's
 * and the row's out once: x of px, y of py (pixels from the top left). */
static inline double hri_camera_frame_x(const hr_camera_frame *f, double px)
{
    return f->half_width * (2.0 * px / f->width - 1.0);
}

static inline double hri_camera_frame_y(const hr_camera_frame *f, double py)
{
    return f->half_height * (1.0 - 2.0 * py / f->height);
}

/* The ray through the image plane's point (x, y). */
static inline void hri_camera_frame_ray_xy(const hr_camera_frame *f, double x, double y, hr_ray *out)
{
    hr_vec3 dir = v3_add(v3_add(v3_scale(f->u, x), v3_scale(f->v, y)), v3_neg(f->n));
    out->origin = f->eye;
    out->dir = v3_normalize(dir);
}

/* The ray through image position (px, py), pixels from the top left. */
static inline void hri_camera_frame_ray(const hr_camera_frame *f, double px, double py, hr_ray *out)
{
    hri_camera_frame_ray_xy(f, hri_camera_frame_x(f, px), hri_camera_frame_y(f, py), out);
}

#endif
