/* Internal: what commit prepares for the cheap culls of tracing
 * (lib/trace/ray_cull.h): an unbounded object's slab axes and direction
 * limit, and the widened box around the BVH's objects, with the widening
 * both sides share. */
#ifndef HITRAY_LIB_SCENE_CULL_PREPARE_H
#define HITRAY_LIB_SCENE_CULL_PREPARE_H

#include <math.h>

#include <hitray/shape_kit_box.h>

#include "scene/scene_internal.h"
#include "geometry/transform_inline.h"
#include "geometry/vec.h"

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
    const hr_xform_error_terms terms = hri_xform_error_terms_of(o->inv);
    const double gain = fmax(terms.row_abs[0], fmax(terms.row_abs[1], terms.row_abs[2]));
    o->cull_dir_limit = gain > 0.0 ? 0x1p190 / gain : 0.0; /* NaN or 0: never culled */
}

/* The widening of a slab's entry and exit is the shape kit's
 * (SHAPE_SLAB_SLACK, SHAPE_SLAB_TINY), the BVH's too (accel/bvh4.h): far
 * more than the two roundings of each distance, and enough to cover a
 * shape's own rounding of t. */

/* The box the BVH walk of a scene may meet (at commit): the union of its
 * objects' world bounds, widened by SHAPE_SLAB_SLACK of its largest coordinate
 * (plus SHAPE_SLAB_TINY), far more than the float walk's own rounding of boxes
 * outward (2^-24), so that a ray this box culls is one the walk could only
 * take to shapes it misses by more than that. An empty union (no bounded
 * object) stays empty: lo > hi. */
static inline hr_bounds cull_box_widened(hr_bounds b)
{
    if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z)) return b;
    const double pad = SHAPE_SLAB_SLACK * fmax(v3_max_abs(b.lo), v3_max_abs(b.hi)) + SHAPE_SLAB_TINY;
    b.lo = v3(b.lo.x - pad, b.lo.y - pad, b.lo.z - pad);
    b.hi = v3(b.hi.x + pad, b.hi.y + pad, b.hi.z + pad);
    return b;
}

#endif
