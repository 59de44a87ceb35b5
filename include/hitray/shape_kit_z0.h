/* hitray shape kit: the plane z = 0, which the plane, the square and any
 * flat shape in it (the example plugin's disk) share. */
#ifndef HITRAY_SHAPE_KIT_Z0_H
#define HITRAY_SHAPE_KIT_Z0_H

#include "shape_kit_hits.h"
#include "shape_kit_math.h"

/* The crossing of the ray with z = 0: t = -o.z / d.z, one rounding. A ray
 * with d.z == 0 (+0 or -0) is parallel and never crosses: it is refused before
 * dividing, so no infinity or NaN is made. The side the normal +z points to
 * is outside, so moving against the normal (d.z < 0) is entering. */
static inline int shape_z0_crossing(const hr_ray *ray, shape_crossing *out)
{
    if (ray->dir.z == 0.0) return 0;
    out->t = -ray->origin.z / ray->dir.z;
    out->surface = 0;
    out->entering = ray->dir.z < 0.0;
    return 1;
}

/* The point of a z = 0 crossing: x and y from origin + t dir, z exactly 0
 * (the point is projected onto the plane, so it is off the surface only
 * along it). The error bounds x and y against the exact intersection: t has
 * one rounding, see shape_ray_point_error. */
static inline void shape_z0_fill(const hr_ray *ray, hr_hit *hit)
{
    hit->point = shape_vec3(ray->origin.x + hit->t * ray->dir.x,
                            ray->origin.y + hit->t * ray->dir.y, 0.0);
    hit->normal = shape_vec3(0.0, 0.0, 1.0);
    hit->error = shape_ray_point_error(ray, hit->t, 1);
}

/* shape_z0_fill in the form shape_report takes, for a shape whose hits are
 * all crossings of z = 0 (its data does not change the point). */
static inline void shape_z0_report_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    (void)shape;
    shape_z0_fill(ray, hit);
}

#endif
