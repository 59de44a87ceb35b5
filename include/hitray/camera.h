/* hitray: Hill's camera — eye, look-at point, up vector, vertical view angle.
 *
 * The camera's axes follow Hill: n points from the look-at point back to the
 * eye, u = up x n, v = n x u. Pixel (0,0) is the top-left corner of the image;
 * pixel (i, j) covers [i, i+1) x [j, j+1), so its centre is (i+0.5, j+0.5). */
#ifndef HITRAY_CAMERA_H
#define HITRAY_CAMERA_H

#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hr_camera {
    uint32_t struct_size;
    int32_t width;       /* image width in pixels (aspect = width / height) */
    int32_t height;      /* image height in pixels */
    int32_t reserved;
    hr_vec3 eye;         /* centre of projection */
    hr_vec3 look;        /* a point the camera looks at */
    hr_vec3 up;          /* roughly up; must not be parallel to look - eye */
    double view_angle;   /* vertical field of view in degrees, (0, 180) */
} hr_camera;

/* 640x480, eye (0,0,5) looking at the origin, up +y, 45 degrees. */
HR_API void hr_camera_default(hr_camera *cam);
/* Refuses a camera that cannot make rays (zero size, eye at the look-at
 * point, up parallel to the view direction, angle outside (0, 180)),
 * naming the field. `ctx` may be NULL (then no message is kept). */
HR_API hr_status hr_camera_validate(hr_context *ctx, const hr_camera *cam);
/* The ray through image position (px, py) in pixels from the top-left corner;
 * its direction is unit length. */
HR_API hr_status hr_camera_ray(const hr_camera *cam, double px, double py, hr_ray *out);
/* Hill's camera moves: slide along (u, v, n); roll about n, pitch about u,
 * yaw about v (degrees). They move eye/look/up accordingly. */
HR_API void hr_camera_slide(hr_camera *cam, double du, double dv, double dn);
HR_API void hr_camera_roll(hr_camera *cam, double degrees);
HR_API void hr_camera_pitch(hr_camera *cam, double degrees);
HR_API void hr_camera_yaw(hr_camera *cam, double degrees);

#ifdef __cplusplus
}
#endif
#endif
