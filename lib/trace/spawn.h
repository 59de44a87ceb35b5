/* Where a ray spawned at a hit starts (hr_hit_spawn_origin, spawn.c), inline
 * for shade, which asks it for every hit that casts a shadow, reflected or
 * refracted ray: the public function is this same code behind a call.
 *
 * The distance is the hit's own error bound projected on the side vector
 * (pbrt's offset: the point is within `error` of the true surface in each
 * coordinate, so moving it by error * (|sx| + |sy| + |sz|) along a unit side
 * clears the surface whatever the rounding was). Only a hit that reports no
 * bound at all (error 0: a shape that claims exactness, such as a Python
 * shape that leaves the field alone) gets a stand-in of a few ulps of the
 * point's magnitude. It is not a floor under every bound: a transformed
 * hit's bound already carries the transform's rounding (object_trace.h), and
 * flooring it at 8 ulps made the offset about 5x the bound far from the
 * origin, hiding surfaces closer than that (tests/numerics, P-cases).
 * Each coordinate is then rounded one ulp further away from the surface, so
 * the offset survives the addition's own rounding. */
#ifndef HITRAY_LIB_TRACE_SPAWN_H
#define HITRAY_LIB_TRACE_SPAWN_H

#include <float.h>
#include <math.h>

#include <hitray/scene.h>
#include "geometry/vec.h"

static inline __attribute__((always_inline)) hr_vec3 hri_hit_spawn_origin(const hr_hit *hit, hr_vec3 side)
{
    hr_vec3 p = hit->point;
    double err = hit->error > 0.0 ? hit->error : 8.0 * DBL_EPSILON * v3_max_abs(p);
    double d = err * (fabs(side.x) + fabs(side.y) + fabs(side.z));
    hr_vec3 o = v3_madd(p, side, d);
    o.x = step_towards(o.x, side.x);
    o.y = step_towards(o.y, side.y);
    o.z = step_towards(o.z, side.z);
    return o;
}

#endif
