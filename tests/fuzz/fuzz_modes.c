#include "fuzz_modes.h"

#include <float.h>
#include <math.h>

#include "fuzz_input.h"

static int within(double v, double lo, double hi, double slack)
{
    return v >= lo - slack && v <= hi + slack;
}

int fuzz_trace_modes(const harness_shape *shape, hr_ray ray, double tmin, double tmax,
                     hr_hit all[HARNESS_MAX_HITS])
{
    const char *name = shape->cls->name;
    hr_hit first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
    const int n_all = harness_trace(shape, ray, tmin, tmax, HARNESS_ALL, all);
    const int n_first = harness_trace(shape, ray, tmin, tmax, HARNESS_FIRST, first);
    const int n_any = harness_trace(shape, ray, tmin, tmax, HARNESS_ANY, any);
    fuzz_require_no_failures(name);
    if (n_first != (n_all > 0) || n_any != (n_all > 0))
        fuzz_fail(FUZZ_RAY_FMT "hit found %d, first_hit %d, any_hit %d",
                  FUZZ_RAY_ARGS(name, ray, tmin, tmax), n_all, n_first, n_any);
    if (n_all > 0 && (first[0].t != all[0].t || first[0].surface != all[0].surface ||
                      first[0].entering != all[0].entering))
        fuzz_fail(FUZZ_RAY_FMT "first_hit t %a surface %d entering %d, hit's first t %a "
                               "surface %d entering %d",
                  FUZZ_RAY_ARGS(name, ray, tmin, tmax), first[0].t, (int)first[0].surface,
                  (int)first[0].entering, all[0].t, (int)all[0].surface, (int)all[0].entering);
    hr_bounds b;
    shape->cls->bounds(shape->shape, &b);
    const int shown = n_all < HARNESS_MAX_HITS ? n_all : HARNESS_MAX_HITS;
    for (int i = 0; i < shown; i++) {
        const hr_hit *h = &all[i];
        /* The slack adds the rounding of the bound's own sum. */
        const double slack =
            h->error * (1 + DBL_EPSILON) +
            DBL_EPSILON * fmax(fabs(h->point.x), fmax(fabs(h->point.y), fabs(h->point.z)));
        if (!within(h->point.x, b.lo.x, b.hi.x, slack) ||
            !within(h->point.y, b.lo.y, b.hi.y, slack) ||
            !within(h->point.z, b.lo.z, b.hi.z, slack))
            fuzz_fail(FUZZ_RAY_FMT "hit %d at (%a, %a, %a), error %g, is outside the bounds "
                                   "(%g, %g, %g)..(%g, %g, %g)",
                      FUZZ_RAY_ARGS(name, ray, tmin, tmax), i, h->point.x, h->point.y,
                      h->point.z, h->error, b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
    }
    return n_all;
}
