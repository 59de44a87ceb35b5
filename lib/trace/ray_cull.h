/* Internal: cheap tests that let a ray pass what it cannot hit without
 * tracing it (lib/trace/trace.c): an unbounded object (a plane) by its
 * object-space bounds, and the whole BVH by the box around its objects,
 * from what commit prepared (lib/scene/cull_prepare.h). A header of their
 * own so that tests/trace/test_ray_cull.c can check them on many rays. */
#ifndef HITRAY_LIB_TRACE_RAY_CULL_H
#define HITRAY_LIB_TRACE_RAY_CULL_H

#include <float.h>
#include <math.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <hitray/shape_kit_box.h>

#include "scene/cull_prepare.h"
#include "scene/scene_internal.h"
#include "geometry/transform_inline.h"
#include "geometry/vec.h"

/* Whether the unbounded object `o` (a plane) certainly has no hit in the
 * open (tmin, tmax), from the finite ends of its object-space bounds (the
 * axes in o->slab_axes): what the BVH's boxes do for bounded objects, for
 * an object every ray would otherwise take through object_trace (about 200
 * instructions for a shadow ray that never comes near the plane).
 *
 * It reads the ray as the shape would see it. Coordinate k of the origin
 * and of the direction in object space are hri_xform_point_row and
 * hri_xform_vector_row, the very operations object_trace's transform does
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
 * no NaN) and moved outward (shape_slab_window; the plane's t is -o_z / d_z,
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
        const double ok = o->identity ? (&ray->origin.x)[k] : hri_xform_point_row(o->inv, ray->origin, k);
        const double dk = o->identity ? (&ray->dir.x)[k] : hri_xform_vector_row(o->inv, ray->dir, k);
        if (!(fabs(ok) <= DBL_MAX)) return 0;
        if (!(fabs(dk) >= 0x1p-200)) {
            if (dk != 0.0) return 0; /* too small to say (or NaN) */
            const double margin = SHAPE_SLAB_SLACK * fabs(ok) + SHAPE_SLAB_TINY;
            if (ok + margin < lo[k] || ok - margin > hi[k]) return 1;
            continue;
        }
        shape_slab_window(ok, dk, lo[k], hi[k], &t_near, &t_far);
    } while (axes &= axes - 1);
    return shape_window_missed(t_near, t_far, tmin, tmax);
}

/* Whether the ray certainly meets nothing inside the finite box `b` in the
 * open (tmin, tmax): the kit's slab test (shape_box_misses) (a ray
 * parallel to a slab stays in it or out of it). A shadow ray from the floor
 * away from every object, or a camera ray into the floor beside them, then
 * skips the walk's setup (about 230 instructions) and its node tests. Rays
 * that are not finite are never culled (NaN compares false).
 * box_misses_sse2: shape_box_misses, the reference, in SSE2 where there is
 * SSE2: about half the instructions, for a test every camera and shadow ray
 * takes. */
static inline __attribute__((always_inline)) int box_misses_sse2(const hr_bounds *b, const hr_ray *ray,
                                                                   double tmin, double tmax)
{
#if defined(__SSE2__)
    /* x and y in one vector, z in another whose upper lane is a slab
     * everywhere (-inf to inf, o 0, d 1), so it gives -inf and inf. Each
     * lane does shape_slab_window's operations in its order: the subtractions and
     * divisions, then _mm_min_pd(b, a) and _mm_max_pd(b, a), which are
     * "b < a ? b : a" and "b > a ? b : a", then the running max and min
     * with the new value first, so a NaN drops out as it does there. The
     * lanes are folded last; max and min of the same values do not depend
     * on the order but for the sign of a zero, which the widening erases
     * (shape_window_missed turns either zero into the same -SHAPE_SLAB_TINY or
     * SHAPE_SLAB_TINY). So both give the same answer (test_ray_cull). */
    const __m128d inf = _mm_set1_pd(INFINITY), neg_inf = _mm_set1_pd(-INFINITY);
    const __m128d o_xy = _mm_loadu_pd(&ray->origin.x), d_xy = _mm_loadu_pd(&ray->dir.x);
    const __m128d o_z = _mm_load_sd(&ray->origin.z);
    const __m128d d_z = _mm_loadl_pd(_mm_set1_pd(1.0), &ray->dir.z);
    const __m128d lo_xy = _mm_loadu_pd(&b->lo.x), hi_xy = _mm_loadu_pd(&b->hi.x);
    const __m128d lo_z = _mm_loadl_pd(neg_inf, &b->lo.z), hi_z = _mm_loadl_pd(inf, &b->hi.z);
    const __m128d a_xy = _mm_div_pd(_mm_sub_pd(lo_xy, o_xy), d_xy);
    const __m128d b_xy = _mm_div_pd(_mm_sub_pd(hi_xy, o_xy), d_xy);
    const __m128d a_z = _mm_div_pd(_mm_sub_pd(lo_z, o_z), d_z);
    const __m128d b_z = _mm_div_pd(_mm_sub_pd(hi_z, o_z), d_z);
    __m128d t_near = _mm_max_pd(_mm_min_pd(b_xy, a_xy), neg_inf);
    __m128d t_far = _mm_min_pd(_mm_max_pd(b_xy, a_xy), inf);
    t_near = _mm_max_pd(_mm_min_pd(b_z, a_z), t_near);
    t_far = _mm_min_pd(_mm_max_pd(b_z, a_z), t_far);
    t_near = _mm_max_sd(t_near, _mm_unpackhi_pd(t_near, t_near));
    t_far = _mm_min_sd(t_far, _mm_unpackhi_pd(t_far, t_far));
    return shape_window_missed(_mm_cvtsd_f64(t_near), _mm_cvtsd_f64(t_far), tmin, tmax);
#else
    return shape_box_misses(b, ray, tmin, tmax);
#endif
}

/* box_misses_sse2, after a shortcut for the rays it can never cull. */
static inline __attribute__((always_inline)) int box_misses(const hr_bounds *b, const hr_ray *ray,
                                                             double tmin, double tmax)
{
    /* A ray from inside the box (a shadow or reflected ray from an object,
     * a camera among the objects) is in it at t = 0, so a window that
     * starts at 0, as every renderer's ray does, is never culled: six
     * compares say so (and not culling is always safe). */
    const hr_vec3 o = ray->origin;
    if (o.x >= b->lo.x && o.x <= b->hi.x && o.y >= b->lo.y && o.y <= b->hi.y && o.z >= b->lo.z &&
        o.z <= b->hi.z)
        return 0;
    return box_misses_sse2(b, ray, tmin, tmax);
}

#endif
