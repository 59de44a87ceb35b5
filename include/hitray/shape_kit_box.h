/* hitray shape kit: the slab test, a ray against an axis-aligned box (part of
 * <hitray/shape_kit.h>; see there). The host's own culling of rays (the box
 * around a scene, an unbounded plane's finite sides) and the CSG module's
 * pruning of its operands use this same test. */
#ifndef HITRAY_SHAPE_KIT_BOX_H
#define HITRAY_SHAPE_KIT_BOX_H

#include <math.h>

#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Relative and absolute widening of a box's entry and exit. pbrt widens the
 * exit by 1 + 2 gamma(3) (about 1 + 7e-16), enough for the rounding of the
 * slab distances alone; this is far more (2^-20 ~ 1e-6), so that it also
 * covers a shape's own rounding of the t it reports for a point on its box
 * (the float boxes of the host's BVH use the same relative slack). */
#define SHAPE_SLAB_SLACK 0x1p-20
#define SHAPE_SLAB_TINY 0x1p-1022

/* The slab lo <= o + t d <= hi along one axis: its entry and exit,
 * (lo - o) / d and (hi - o) / d, the smaller first, each with two roundings
 * (an infinite end gives an infinite distance), intersected with
 * [*t_near, *t_far]. For d == +-0 the distances are infinities of the right
 * signs (the parallel ray is in the slab everywhere or nowhere), or NaN
 * where o is on a face: each compare is written so that a NaN drops out (the
 * entry and exit go NaN together, and the max and min keep what they had),
 * so a ray parallel to a face and on it is kept. */
static inline void shape_slab_window(double o, double d, double lo, double hi, double *t_near,
                                     double *t_far)
{
    const double a = (lo - o) / d, b = (hi - o) / d;
    const double t0 = b < a ? b : a, t1 = b > a ? b : a;
    *t_near = t0 > *t_near ? t0 : *t_near;
    *t_far = t1 < *t_far ? t1 : *t_far;
}

/* Whether no t in the open (tmin, tmax) lies in [t_near, t_far] moved
 * outward by SHAPE_SLAB_SLACK relative (one more rounding, far below it) and
 * SHAPE_SLAB_TINY absolute. Moving a t outward is monotone, so moving the
 * largest entry and the smallest exit is moving every slab's own; it is a
 * product rather than t - slack |t|, so that an infinite end stays infinite
 * (inf - inf would be NaN, and cull nothing). */
static inline int shape_window_missed(double t_near, double t_far, double tmin, double tmax)
{
    t_near = t_near * (1.0 - copysign(SHAPE_SLAB_SLACK, t_near)) - SHAPE_SLAB_TINY;
    t_far = t_far * (1.0 + copysign(SHAPE_SLAB_SLACK, t_far)) + SHAPE_SLAB_TINY;
    return t_far <= tmin || t_near >= tmax || t_near > t_far;
}

/* Whether the ray certainly meets nothing inside the box `b` in the open
 * (tmin, tmax): the slab test on each axis, widened as above. Guarantee: a
 * ray that touches the box at some t in (tmin, tmax) is never reported as
 * missing it (rounding can only keep a ray that misses, never drop one that
 * hits). Rays that are not finite are never culled (NaN compares false). */
static inline int shape_box_misses(const hr_bounds *b, const hr_ray *ray, double tmin, double tmax)
{
    double t_near = -INFINITY, t_far = INFINITY;
    shape_slab_window(ray->origin.x, ray->dir.x, b->lo.x, b->hi.x, &t_near, &t_far);
    shape_slab_window(ray->origin.y, ray->dir.y, b->lo.y, b->hi.y, &t_near, &t_far);
    shape_slab_window(ray->origin.z, ray->dir.z, b->lo.z, b->hi.z, &t_near, &t_far);
    return shape_window_missed(t_near, t_far, tmin, tmax);
}

#ifdef __cplusplus
}
#endif
#endif
