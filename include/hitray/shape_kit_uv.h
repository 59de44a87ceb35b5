/* hitray shape kit: (u, v) on a surface (hr_shape_class.surface_uv), the
 * pieces several shapes share. */
#ifndef HITRAY_SHAPE_KIT_UV_H
#define HITRAY_SHAPE_KIT_UV_H

#include <math.h>

#include "shape_module.h"

/* The angle of (x, y) about the origin as a fraction of a turn, in [0, 1):
 * 0 along +x, 1/4 along +y. (0, 0) gives 0. */
static inline double shape_turn(double y, double x)
{
    const double two_pi = 6.28318530717958647692;
    double a = atan2(y, x) / two_pi;
    if (a < 0.0) a += 1.0;
    return a < 1.0 ? a : 0.0; /* -tiny + 1 rounds to 1 */
}

/* The answer to the host's question "does this shape give (u, v)?" (hit
 * NULL) for a shape that always does. */
#define SHAPE_UV_PROBE(hit, uv)                                                \
    do {                                                                       \
        if (!(hit) || !(uv)) return 1;                                         \
    } while (0)

#endif
