/* Where a ray spawned at a hit starts: the one rule the renderer uses for
 * shadow, reflected and refracted rays, public so a caller's own integrator
 * (and the self-intersection tests) leave surfaces the same way. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "trace/trace_context.h"
#include "geometry/vec.h"

/* The distance is the hit's own error bound projected on the side vector
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
HR_API hr_vec3 hr_hit_spawn_origin(const hr_hit *hit, hr_vec3 side)
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
