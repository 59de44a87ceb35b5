/* One ray through a shape's three hit functions, for the harnesses that
 * drive shapes through the module harness (fuzz_shapes.c, fuzz_mesh.c). */
#ifndef HR_FUZZ_MODES_H
#define HR_FUZZ_MODES_H

#include "module_harness.h"

/* Traces the ray with hit, first_hit and any_hit (harness_trace checks the
 * contract of each call) and checks that they agree: first_hit and any_hit
 * find a hit exactly when hit does, and first_hit's is hit's first (same
 * t, surface and entering flag; or another of hit's hits as close to it
 * as rounding of t can put two crossings, with the same entering flag when
 * `closed`, the shape is a closed solid: see same_first; `t_error`, when
 * the caller knows one, bounds the rounding of any crossing's t). Then checks that every hit point lies in
 * the shape's bounds grown by the hit's error bound (the exact surface
 * point is inside the bounds, and the bound is per coordinate). Aborts on
 * a broken check; returns hit's count as harness_trace does (at most
 * HARNESS_MAX_HITS, which a longer list gives too), the hits copied to
 * `all`. */
int fuzz_trace_modes(const harness_shape *shape, hr_ray ray, double tmin, double tmax,
                     int closed, double t_error, hr_hit all[HARNESS_MAX_HITS]);

#define FUZZ_RAY_FMT "%s: ray (%a, %a, %a) + t (%a, %a, %a), t in (%a, %a): "
#define FUZZ_RAY_ARGS(name, r, tmin, tmax)                                                     \
    (name), (r).origin.x, (r).origin.y, (r).origin.z, (r).dir.x, (r).dir.y, (r).dir.z, (tmin), \
        (tmax)

#endif
