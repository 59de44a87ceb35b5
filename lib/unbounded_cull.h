/* Internal: the cheap test that lets a shadow ray pass an unbounded object
 * (a plane) without tracing it (lib/trace.c); a header of its own so that
 * tests/core/test_unbounded_cull.c can check it against the plane's own
 * answer on many rays. */
#ifndef HITRAY_LIB_UNBOUNDED_CULL_H
#define HITRAY_LIB_UNBOUNDED_CULL_H

#include <float.h>
#include <math.h>

#include "scene_internal.h"
#include "transform_inline.h"
#include "vec.h"

/* Sets o->slab_axes, the axes on which its object-space bounds have a finite
 * end (and no NaN), and o->inv_gain, the largest row sum of |inv|'s linear
 * part, from local_bounds and inv. */
static inline void unbounded_cull_prepare(hr_object *o)
{
    const double *lo = &o->local_bounds.lo.x, *hi = &o->local_bounds.hi.x;
    o->slab_axes = 0;
    for (int k = 0; k < 3; k++)
        if (!isnan(lo[k]) && !isnan(hi[k]) && lo[k] <= hi[k] && (isfinite(lo[k]) || isfinite(hi[k])))
            o->slab_axes |= 1u << k;
    const hr_xform_error_terms terms = hr_xform_error_terms_of(o->inv);
    o->inv_gain = fmax(terms.row_abs[0], fmax(terms.row_abs[1], terms.row_abs[2]));
}

/* Relative and absolute widening of an object-space slab's entry and exit
 * in unbounded_misses: as the BVH's (accel/bvh4.h), far more than the two
 * roundings of each distance. */
#define UNBOUNDED_SLACK 0x1p-20
#define UNBOUNDED_TINY 0x1p-1022

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
 * component is at most inv_gain * max |world d| times (1 + u)^3, so below
 * 2^190 for that product none is too large, and |d_k| >= 2^-200 says the
 * largest is not too small. Outside those limits (and for a ray that is not
 * finite) nothing is culled.
 *
 * The shape lies inside its bounds, so along the exact line o + t d its
 * hits lie where lo <= x_k <= hi: for d_k != 0 between (lo - o_k) / d_k and
 * (hi - o_k) / d_k (t is the same in object and world space). Each is
 * computed with two roundings (an infinite end gives an infinite distance,
 * no NaN) and moved outward by UNBOUNDED_SLACK relative and UNBOUNDED_TINY
 * absolute, which also covers a shape's own rounding of t, as the BVH's
 * slack does (the plane's t is -o_z / d_z, exactly the distance computed
 * here). A ray parallel to the slab (d_k == 0, which the shape sees too)
 * stays at o_k: culled only when o_k is outside [lo, hi] by that margin. */
static inline int unbounded_misses(const hr_object *o, const hr_ray *ray, double tmin, double tmax)
{
    if (!(o->inv_gain * v3_max_abs(ray->dir) <= 0x1p190)) return 0;
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
            const double margin = UNBOUNDED_SLACK * fabs(ok) + UNBOUNDED_TINY;
            if (ok + margin < lo[k] || ok - margin > hi[k]) return 1;
            continue;
        }
        double t0 = (lo[k] - ok) / dk, t1 = (hi[k] - ok) / dk;
        if (dk < 0.0) {
            const double swap = t0;
            t0 = t1, t1 = swap;
        }
        t0 -= UNBOUNDED_SLACK * fabs(t0) + UNBOUNDED_TINY;
        t1 += UNBOUNDED_SLACK * fabs(t1) + UNBOUNDED_TINY;
        t_near = t0 > t_near ? t0 : t_near;
        t_far = t1 < t_far ? t1 : t_far;
    } while (axes &= axes - 1);
    /* A hit needs tmin < t < tmax and t_near <= t <= t_far. */
    return t_far <= tmin || t_near >= tmax || t_near > t_far;
}

#endif
