/* hitray shape kit: from "where does the ray cross my surfaces" to the hits
 * a module reports (part of <hitray/shape_kit.h>; see there).
 *
 * Every built-in shape is convex (or a single flat surface), so what a ray
 * does to it is one span of t: it enters at span.t_in and leaves at
 * span.t_out. A solid bounded by several surfaces is the intersection of
 * simple regions (the cube: three slabs; the tapered cylinder: a slab and the
 * inside of the wall), and the span of the solid is the intersection of their
 * spans. Working with spans rather than with separate surface hits is what
 * keeps edges and seams honest: each end of the span belongs to exactly one
 * region, so a ray through an edge is entered once, never twice and never not
 * at all, whatever rounding does to the two nearly equal times.
 *
 * Ownership of an exact tie (a ray through an edge, a corner or a seam): the
 * region intersected FIRST keeps the end (shape_span_intersect replaces an
 * end only when the new region's time is strictly later on entry or strictly
 * earlier on exit). Each shape says in which order it intersects. */
#ifndef HITRAY_SHAPE_KIT_HITS_H
#define HITRAY_SHAPE_KIT_HITS_H

#include <math.h>

#include "shape_kit_math.h"
#include "shape_module.h"

#ifdef __cplusplus
extern "C" {
#endif

/* No surface: the end of a span that runs to infinity. */
#define SHAPE_NO_SURFACE (-1)

/* One place where the ray crosses a surface of the shape. */
typedef struct shape_crossing {
    double t;
    int32_t surface;
    int32_t entering;
} shape_crossing;

/* The closed interval of t over which the ray is inside a region, and the
 * surface it crosses at each end. Empty when !(t_in <= t_out). */
typedef struct shape_span {
    double t_in, t_out;
    int32_t surface_in, surface_out;
} shape_span;

static inline shape_span shape_span_make(double t_in, int32_t surface_in, double t_out,
                                         int32_t surface_out)
{
    shape_span s = {t_in, t_out, surface_in, surface_out};
    return s;
}

static inline shape_span shape_span_everywhere(void)
{
    return shape_span_make(-INFINITY, SHAPE_NO_SURFACE, INFINITY, SHAPE_NO_SURFACE);
}

static inline shape_span shape_span_nowhere(void)
{
    return shape_span_make(INFINITY, SHAPE_NO_SURFACE, -INFINITY, SHAPE_NO_SURFACE);
}

static inline int shape_span_is_empty(shape_span s)
{
    return !(s.t_in <= s.t_out);
}

/* Where the ray is in both regions; on a tie `kept` keeps its end. */
static inline shape_span shape_span_intersect(shape_span kept, shape_span other)
{
    if (other.t_in > kept.t_in) {
        kept.t_in = other.t_in;
        kept.surface_in = other.surface_in;
    }
    if (other.t_out < kept.t_out) {
        kept.t_out = other.t_out;
        kept.surface_out = other.surface_out;
    }
    return kept;
}

/* The span of lo <= o + t d <= hi along one axis: the ray enters through the
 * face it moves away from. A zero component (+0 or -0) means the ray runs
 * parallel to the slab: inside everywhere or nowhere, decided without
 * dividing. Each finite time is fl(fl(face - o) / d): two roundings (one when
 * the face is 0). A tiny d may give an infinite time, which no report ever
 * passes on (see shape_report). */
static inline shape_span shape_slab_span(double o, double d, double lo, int32_t surface_lo,
                                         double hi, int32_t surface_hi)
{
    if (d == 0.0) return (lo <= o && o <= hi) ? shape_span_everywhere() : shape_span_nowhere();
    const double t_lo = (lo - o) / d, t_hi = (hi - o) / d;
    return d > 0.0 ? shape_span_make(t_lo, surface_lo, t_hi, surface_hi)
                   : shape_span_make(t_hi, surface_hi, t_lo, surface_lo);
}

/* The two crossings of a non-empty span (entering first, also when both ends
 * have the same t: a tangent or a grazed edge is reported as a zero-length
 * visit, so entering/exiting still alternate). */
static inline int shape_span_crossings(shape_span s, shape_crossing out[2])
{
    if (shape_span_is_empty(s)) return 0;
    out[0].t = s.t_in;
    out[0].surface = s.surface_in;
    out[0].entering = 1;
    out[1].t = s.t_out;
    out[1].surface = s.surface_out;
    out[1].entering = 0;
    return 2;
}

/* --- Reporting ---------------------------------------------------------------- */

/* Fills point, normal and error of a hit whose t, surface and entering flag
 * are already set. */
typedef void (*shape_fill_fn)(const void *shape, const hr_ray *ray, hr_hit *hit);

/* One comparison for all eight values: x - x is 0 for a finite x and NaN
 * for an infinite or NaN one, and a sum with a NaN in it is NaN. */
static inline int shape_hit_is_finite(const hr_hit *h)
{
    const hr_vec3 p = h->point, n = h->normal;
    const double zero = (h->t - h->t) + (h->error - h->error) + (p.x - p.x) + (p.y - p.y) +
                        (p.z - p.z) + (n.x - n.x) + (n.y - n.y) + (n.z - n.z);
    return zero == 0.0;
}

/* Appends the crossings (sorted by t) that lie strictly inside (tmin, tmax):
 * all of them for HR_TRACE_ALL, the nearest for HR_TRACE_FIRST and
 * HR_TRACE_ANY. The open-interval test also drops every infinite or NaN time.
 * A hit whose point, normal or error came out non-finite (only for absurdly
 * large rays, whose arithmetic overflows) is dropped rather than passed on:
 * the contract forbids NaN and infinity. */
static inline hr_status shape_report(const hr_hit_args *args, int32_t mode,
                                     const shape_crossing *crossings, int count,
                                     shape_fill_fn fill)
{
    hr_intersection *out = args->out;
    if (out->capacity - out->count < count) return HR_ERROR_INVALID_ARGUMENT;
    for (int i = 0; i < count; i++) {
        const shape_crossing *c = &crossings[i];
        if (!(c->t > args->tmin && c->t < args->tmax)) continue;
        hr_hit *hit = &out->hits[out->count];
        hit->t = c->t;
        hit->surface = c->surface;
        hit->entering = c->entering;
        fill(args->shape, &args->ray, hit);
        if (!shape_hit_is_finite(hit)) continue;
        out->count++;
        if (mode != HR_TRACE_ALL) break;
    }
    return HR_OK;
}

/* The three entry points of the vtable (hit, first_hit, any_hit) differ only
 * in the mode they pass to the shape's one trace function; this defines them
 * as <prefix>_hit, <prefix>_first_hit and <prefix>_any_hit. */
#define SHAPE_DEFINE_HIT_MODES(prefix, trace)                                  \
    static hr_status prefix##_hit(const hr_hit_args *args)                     \
    {                                                                          \
        return trace(args, HR_TRACE_ALL);                                      \
    }                                                                          \
    static hr_status prefix##_first_hit(const hr_hit_args *args)               \
    {                                                                          \
        return trace(args, HR_TRACE_FIRST);                                    \
    }                                                                          \
    static hr_status prefix##_any_hit(const hr_hit_args *args)                 \
    {                                                                          \
        return trace(args, HR_TRACE_ANY);                                      \
    }

#ifdef __cplusplus
}
#endif
#endif
