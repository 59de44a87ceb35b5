/* A camera's ray-making constants, worked out once: its axes and the half
 * sizes of the image plane. hr_camera_ray makes one for every ray it is
 * asked for; a render makes one for the whole image (the axes take two
 * square roots and the plane a tangent, more than the ray itself costs).
 * Both give a ray the same bits, because they run the same code. */
#ifndef HITRAY_CAMERA_FRAME_H
#define HITRAY_CAMERA_FRAME_H

#include <hitray/camera.h>

typedef struct hr_camera_frame {
    hr_vec3 eye, u, v, n;
    double half_width, half_height; /* W and H of the plane at distance 1 */
    double width, height;           /* the image, in pixels */
} hr_camera_frame;

/* 0 (and the frame unset) where hr_camera_ray refuses the camera. */
int hr_camera_frame_init(hr_camera_frame *f, const hr_camera *cam);

/* The ray through image position (px, py), pixels from the top left. */
void hr_camera_frame_ray(const hr_camera_frame *f, double px, double py, hr_ray *out);

#endif
