/* Internal: cheap tests that let a ray pass what it cannot hit without
 * tracing it (lib/trace.c): an unbounded object (a plane) by its
 * object-space bounds, and the whole BVH by the box around its objects. A
 * header of their own so that tests/core/test_ray_cull.c can check them on
 * many rays. */
#ifndef HITRAY_LIB_UNBOUNDED_CULL_H
#define HITRAY_LIB_UNBOUNDED_CULL_H

#include <float.h>
#include <math.h>

#include "scene_internal.h"
#include "transform_inline.h"
#include "vec.h"

/* Sets o->slab_axes, the axes on which its object-space bounds have a finite
 * end (and no NaN), and o->cull_dir_limit, 2^190 over the largest row sum
 * of |inv|'s linear part (unbounded_misses), from local_bounds and inv. */
static inline void unbounded_cull_prepare(hr_object *o)
{
    const double *lo = &o->local_bounds.lo.x, *hi = &o->local_bounds.hi.x;
    o->slab_axes = 0;
    for (int k = 0; k < 3; k++)
        if (!isnan(lo[k]) && !isnan(hi[k]) && lo[k] <= hi[k] && (isfinite(lo[k]) || isfinite(hi[k])))
            o->slab_axes |= 1u << k;
    const hr_xform_error_terms terms = hr_xform_error_terms_of(o->inv);
    const double gain = fmax(terms.row_abs[0], fmax(terms.row_abs[1], terms.row_abs[2]));
    o->cull_dir_limit = gain > 0.0 ? 0x1p190 / gain : 0.0; /* NaN or 0: never culled */
}

/* Relative and absolute widening of a slab's entry and exit: as the BVH's
 * (accel/bvh4.h), far more than the two roundings of each distance, and
 * enough to cover a shape's own rounding of t as the BVH's slack does. */
#define CULL_SLACK 0x1p-20
#define CULL_TINY 0x1p-1022

/* The slab lo <= o + t d <= hi along one axis: its entry and exit,
 * (lo - o) / d and (hi - o) / d in order, each with two roundings (an
 * infinite end gives an infinite distance), intersected with
 * [*t_near, *t_far]. For d == +-0 the distances are infinities of the right
 * signs (the parallel ray is in the slab everywhere or nowhere), or NaN
 * where o is on a face, which the max and min ignore. */
static inline void cull_slab(double o, double d, double lo, double hi, double *t_near, double *t_far)
{
    double t0 = (lo - o) / d, t1 = (hi - o) / d;
    if (signbit(d)) {
        const double swap = t0;
        t0 = t1, t1 = swap;
    }
    *t_near = t0 > *t_near ? t0 : *t_near;
    *t_far = t1 < *t_far ? t1 : *t_far;
}

/* Whether no t in the open (tmin, tmax) lies in [t_near, t_far] moved
 * outward by CULL_SLACK relative (one more rounding, far below it) and
 * CULL_TINY absolute. Moving a t outward is monotone, so moving the largest
 * entry and the smallest exit is moving every slab's own; it is a product
 * rather than t - CULL_SLACK |t|, so that an infinite end stays infinite
 * (inf - inf would be NaN, and cull nothing). */
static inline int cull_window_missed(double t_near, double t_far, double tmin, double tmax)
{
    t_near = t_near * (1.0 - copysign(CULL_SLACK, t_near)) - CULL_TINY;
    t_far = t_far * (1.0 + copysign(CULL_SLACK, t_far)) + CULL_TINY;
    return t_far <= tmin || t_near >= tmax || t_near > t_far;
}

/* Whether the unbounded object `o` (a plane) certainly has no hit in the
 * open (tmin, tmax), from the finite ends of its object-space bounds (the
 * axes in o->slab_axes): what the BVH's boxes do for bounded objects, for
 * an object every ray would otherwise take through object_trace (about 200
 * instructions for a shadow ray that never comes near the plane).
 *
 * It reads the ray as the shape would see it. Coordinate k of the origin
 * and of the direction in object space are hr_xform_point_row and
 * hr_xform_vector_row, the very operations object_trace's transform does
 * for that row, so they have its bits. object_trace then scales the
 * direction by a power of two (and the window with it) only when its
 * largest component is beyond 2^-200 or 2^200 (v3_rescale_exponent); every
 * component is at most gain * max |world d| times (1 + u)^3, where gain is
 * the largest row sum of |inv|'s linear part, so with max |world d| at most
 * cull_dir_limit = 2^190 / gain (rounded) none is too large, and |d_k| >= 2^-200 says the
 * largest is not too small. Outside those limits (and for a ray that is not
 * finite) nothing is culled.
 *
 * The shape lies inside its bounds, so along the exact line o + t d its
 * hits lie where lo <= x_k <= hi: for d_k != 0 between (lo - o_k) / d_k and
 * (hi - o_k) / d_k (t is the same in object and world space). Each is
 * computed with two roundings (an infinite end gives an infinite distance,
 * no NaN) and moved outward (cull_slab; the plane's t is -o_z / d_z,
 * exactly the distance computed here). A ray parallel to the slab (d_k == 0, which the shape sees too)
 * stays at o_k: culled only when o_k is outside [lo, hi] by that margin. */
static inline __attribute__((always_inline)) int unbounded_misses(const hr_object *o, const hr_ray *ray,
                                                                   double tmin, double tmax)
{
    if (!(v3_max_abs(ray->dir) <= o->cull_dir_limit)) return 0;
    const double *lo = &o->local_bounds.lo.x, *hi = &o->local_bounds.hi.x;
    double t_near = -INFINITY, t_far = INFINITY;
    uint32_t axes = o->slab_axes;
    do {
        const int k = __builtin_ctz(axes);
        const double ok = o->identity ? (&ray->origin.x)[k] : hr_xform_point_row(o->inv, ray->origin, k);
        const double dk = o->identity ? (&ray->dir.x)[k] : hr_xform_vector_row(o->inv, ray->dir, k);
        if (!(fabs(ok) <= DBL_MAX)) return 0;
        if (!(fabs(dk) >= 0x1p-200)) {
            if (dk != 0.0) return 0; /* too small to say (or NaN) */
            const double margin = CULL_SLACK * fabs(ok) + CULL_TINY;
            if (ok + margin < lo[k] || ok - margin > hi[k]) return 1;
            continue;
        }
        cull_slab(ok, dk, lo[k], hi[k], &t_near, &t_far);
    } while (axes &= axes - 1);
    return cull_window_missed(t_near, t_far, tmin, tmax);
}

/* The box the BVH walk of a scene may meet (at commit): the union of its
 * objects' world bounds, widened by CULL_SLACK of its largest coordinate
 * (plus CULL_TINY), far more than the float walk's own rounding of boxes
 * outward (2^-24), so that a ray this box culls is one the walk could only
 * take to shapes it misses by more than that. An empty union (no bounded
 * object) stays empty: lo > hi. */
static inline hr_bounds cull_box_widened(hr_bounds b)
{
    if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z)) return b;
    const double pad = CULL_SLACK * fmax(v3_max_abs(b.lo), v3_max_abs(b.hi)) + CULL_TINY;
    b.lo = v3(b.lo.x - pad, b.lo.y - pad, b.lo.z - pad);
    b.hi = v3(b.hi.x + pad, b.hi.y + pad, b.hi.z + pad);
    return b;
}

/* Whether the ray certainly meets nothing inside the finite box `b` in the
 * open (tmin, tmax): the slab test of cull_slab on each axis (a ray
 * parallel to a slab stays in it or out of it). A shadow ray from the floor away from every object, or a
 * camera ray into the floor beside them, then skips the walk's setup (about
 * 230 instructions) and its node tests. Rays that are not finite are never
 * culled (NaN compares false). */
static inline int box_misses(const hr_bounds *b, const hr_ray *ray, double tmin, double tmax)
{
    double t_near = -INFINITY, t_far = INFINITY;
    cull_slab(ray->origin.x, ray->dir.x, b->lo.x, b->hi.x, &t_near, &t_far);
    cull_slab(ray->origin.y, ray->dir.y, b->lo.y, b->hi.y, &t_near, &t_far);
    cull_slab(ray->origin.z, ray->dir.z, b->lo.z, b->hi.z, &t_near, &t_far);
    return cull_window_missed(t_near, t_far, tmin, tmax);
}

#endif
