/* A camera framed on a scene that gives none: looking at its bounded
 * objects from far enough that they fill the view. */
#include <math.h>

#include "util/errors.h"
#include "scene/scene_internal.h"
#include "geometry/vec.h"

/* The bounded top-level object whose bounds reach farthest from the origin
 * (or are largest): the one that made framing overflow. */
static int64_t farthest_object(const hr_scene *s, double *reach)
{
    int64_t best = -1;
    *reach = -1.0;
    for (int64_t i = 0; i < s->object_count; i++) {
        const hr_object *o = s->objects[i];
        if (!o->top_level || !o->bounded) continue;
        const hr_bounds *b = &o->world_bounds;
        double r = fmax(fmax(v3_max_abs(b->lo), v3_max_abs(b->hi)), v3_max_abs(v3_sub(b->hi, b->lo)));
        if (r > *reach || isnan(r)) best = i, *reach = r;
    }
    return best;
}

/* Look from the +z side, a little from above and the right, at the centre
 * of the bounding sphere of the bounded objects, from far enough that the
 * sphere fits the narrower of the two view angles with a 5% margin. */
HR_API hr_status hr_scene_frame_camera(const hr_scene *s, hr_camera *cam)
{
    if (!s || !cam) return HR_ERROR_INVALID_ARGUMENT;
    hr_bounds b;
    int32_t found;
    hr_scene_bounds(s, &b, &found);
    if (cam->width <= 0 || cam->height <= 0) cam->width = 640, cam->height = 480;
    if (!(cam->view_angle > 0 && cam->view_angle < 180)) cam->view_angle = 45.0;
    if (!found) {
        int32_t w = cam->width, h = cam->height;
        double angle = cam->view_angle;
        hr_camera_default(cam);
        cam->width = w, cam->height = h, cam->view_angle = angle;
        return HR_OK;
    }
    hr_vec3 centre = v3_scale(v3_add(b.lo, b.hi), 0.5);
    double radius = 0.5 * v3_length(v3_sub(b.hi, b.lo));
    if (!(radius > 0)) radius = 1.0;
    double half_v = 0.5 * cam->view_angle * (3.14159265358979323846 / 180.0);
    double half_h = atan(tan(half_v) * cam->width / cam->height);
    double half = fmin(half_v, half_h);
    double dist = 1.05 * radius / sin(half);
    hr_vec3 dir = v3_normalize(v3(0.35, 0.45, 1.0));
    hr_vec3 eye = v3_madd(centre, dir, dist);
    if (!v3_is_finite(eye) || !v3_is_finite(centre)) {
        double reach;
        int64_t i = farthest_object(s, &reach);
        return hri_error(s->ctx, HR_ERROR_NUMERIC,
                        "cannot frame a camera: object %lld (a '%s') reaches %g from the origin, so "
                        "far that a view of it overflows; give the scene a camera",
                        (long long)i, i >= 0 ? s->objects[i]->cls->name : "?", reach);
    }
    cam->look = centre;
    cam->eye = eye;
    cam->up = v3(0, 1, 0);
    return HR_OK;
}
