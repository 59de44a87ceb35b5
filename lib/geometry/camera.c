/* Hill's camera (include/hitray/camera.h): axes u, v, n from eye, look and
 * up; a ray through the image plane at distance 1 in front of the eye. */
#include <math.h>

#include "geometry/camera_frame.h"
#include "util/errors.h"
#include "geometry/vec.h"

#define DEG2RAD (3.14159265358979323846 / 180.0)

HR_API void hr_camera_default(hr_camera *cam)
{
    if (!cam) return;
    hr_camera c = {0};
    c.struct_size = sizeof c;
    c.width = 640;
    c.height = 480;
    c.eye = v3(0, 0, 5);
    c.look = v3(0, 0, 0);
    c.up = v3(0, 1, 0);
    c.view_angle = 45.0;
    *cam = c;
}

/* a, or where its length overflows or underflows, a divided by its
 * largest component's magnitude: the length of (0, 0, 1e308) is not a
 * double, its direction is. Cameras of ordinary sizes keep their axes to
 * the bit. 0 for a zero or non-finite vector. */
static int scaled_to_one(hr_vec3 a, hr_vec3 *out)
{
    const double big = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
    if (!(big > 0.0) || !isfinite(big)) return 0;
    const double length = v3_length(a);
    if (isfinite(length) && length > 1e-150) *out = a;
    else *out = (hr_vec3){a.x / big, a.y / big, a.z / big};
    return 1;
}

/* n = unit(eye - look), u = unit(up x n), v = n x u; 0 if degenerate. */
static int camera_axes(const hr_camera *cam, hr_vec3 *u, hr_vec3 *v, hr_vec3 *n)
{
    hr_vec3 up;
    if (!scaled_to_one(v3_sub(cam->eye, cam->look), n) || !scaled_to_one(cam->up, &up)) return 0;
    double nlen = v3_length(*n);
    if (!(nlen > 0.0) || !isfinite(nlen)) return 0;
    *n = v3_scale(*n, 1.0 / nlen);
    *u = v3_cross(up, *n);
    double ulen = v3_length(*u);
    /* Up within ~1e-6 rad of the view direction gives a meaningless roll. */
    if (!(ulen > 1e-6 * v3_length(up)) || !isfinite(ulen)) return 0;
    *u = v3_scale(*u, 1.0 / ulen);
    *v = v3_cross(*n, *u);
    return 1;
}

HR_API hr_status hr_camera_validate(hr_context *ctx, const hr_camera *cam)
{
    if (!cam) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "camera: NULL");
    if (cam->width <= 0 || cam->height <= 0)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "camera: image size %dx%d must be positive", (int)cam->width,
                        (int)cam->height);
    if (!v3_is_finite(cam->eye) || !v3_is_finite(cam->look) || !v3_is_finite(cam->up))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "camera: eye, look and up must be finite numbers");
    if (!(cam->view_angle > 0.0 && cam->view_angle < 180.0))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "camera: view angle %g must be in (0, 180) degrees", cam->view_angle);
    hr_vec3 u, v, n;
    const hr_vec3 view = v3_sub(cam->eye, cam->look);
    if (view.x == 0.0 && view.y == 0.0 && view.z == 0.0)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "camera: eye and look are the same point");
    if (!v3_is_finite(view))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "camera: eye and look are too far apart (their difference is not a "
                        "finite double)");
    if (!(cam->up.x != 0.0 || cam->up.y != 0.0 || cam->up.z != 0.0))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "camera: up vector is zero");
    if (!camera_axes(cam, &u, &v, &n))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "camera: up vector is zero or parallel to the view direction");
    return HR_OK;
}

int hri_camera_frame_init(hr_camera_frame *f, const hr_camera *cam)
{
    hr_vec3 u, v, n;
    if (cam->width <= 0 || cam->height <= 0 ||
        !(cam->view_angle > 0.0 && cam->view_angle < 180.0) || !camera_axes(cam, &u, &v, &n))
        return 0;
    f->eye = cam->eye;
    f->u = u, f->v = v, f->n = n;
    f->half_height = tan(0.5 * cam->view_angle * DEG2RAD);
    f->half_width = f->half_height * (double)cam->width / (double)cam->height;
    f->width = (double)cam->width;
    f->height = (double)cam->height;
    return 1;
}

HR_API hr_status hr_camera_ray(const hr_camera *cam, double px, double py, hr_ray *out)
{
    hr_camera_frame f;
    /* The same refusals as hr_camera_validate, and a finite position: the
     * direction promised is unit length, never NaN. */
    if (!cam || !out || !isfinite(px) || !isfinite(py) || !hri_camera_frame_init(&f, cam))
        return HR_ERROR_INVALID_ARGUMENT;
    hri_camera_frame_ray(&f, px, py, out);
    return HR_OK;
}

HR_API void hr_camera_slide(hr_camera *cam, double du, double dv, double dn)
{
    hr_vec3 u, v, n;
    if (!cam || !camera_axes(cam, &u, &v, &n)) return;
    hr_vec3 d = v3_add(v3_add(v3_scale(u, du), v3_scale(v, dv)), v3_scale(n, dn));
    cam->eye = v3_add(cam->eye, d);
    cam->look = v3_add(cam->look, d);
}

/* Rotate a and b (orthonormal) by `degrees` in their plane: a' = c a + s b,
 * b' = -s a + c b, as Hill's roll/pitch/yaw do. */
static void turn(hr_vec3 *a, hr_vec3 *b, double degrees)
{
    double c = cos(degrees * DEG2RAD), s = sin(degrees * DEG2RAD);
    hr_vec3 na = v3_add(v3_scale(*a, c), v3_scale(*b, s));
    hr_vec3 nb = v3_add(v3_scale(*a, -s), v3_scale(*b, c));
    *a = na, *b = nb;
}

/* Store axes back as eye/look/up, keeping the eye-look distance. */
static void set_axes(hr_camera *cam, hr_vec3 v, hr_vec3 n)
{
    double dist = v3_length(v3_sub(cam->eye, cam->look));
    cam->look = v3_sub(cam->eye, v3_scale(n, dist));
    cam->up = v;
}

HR_API void hr_camera_roll(hr_camera *cam, double degrees)
{
    hr_vec3 u, v, n;
    if (!cam || !camera_axes(cam, &u, &v, &n)) return;
    turn(&u, &v, degrees);
    set_axes(cam, v, n);
}

HR_API void hr_camera_pitch(hr_camera *cam, double degrees)
{
    hr_vec3 u, v, n;
    if (!cam || !camera_axes(cam, &u, &v, &n)) return;
    turn(&v, &n, degrees);
    set_axes(cam, v, n);
}

HR_API void hr_camera_yaw(hr_camera *cam, double degrees)
{
    hr_vec3 u, v, n;
    if (!cam || !camera_axes(cam, &u, &v, &n)) return;
    turn(&n, &u, degrees);
    set_axes(cam, v, n);
}
