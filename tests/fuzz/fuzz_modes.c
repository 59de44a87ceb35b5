#include "fuzz_modes.h"

#include <float.h>
#include <math.h>

#include "fuzz_input.h"

static int within(double v, double lo, double hi, double slack)
{
    return v >= lo - slack && v <= hi + slack;
}

/* Whether first_hit's hit stands for hit's first: the same hit; or
 * another hit of hit's list (with the same entering flag for a closed
 * shape) that lies as close to
 * it as rounding of t can make two crossings: the same place within the
 * two hits' error bounds (|dt| max|d| <= 4 (e1 + e2), the slack of the
 * mesh's and the CSG module's coincidence rules) or within 1e-6 of t
 * relative. A mesh computes t with an error bound (mesh_t_error) that
 * reaches 2e-5 relative for coordinates near 2^32 seen from 1e10 away, and
 * its BVH prunes by boxes, not by the computed t, so its first hit may be
 * a crossing 1e-9 further that hit's sorting put second; where the caller
 * knows a bound on the rounding of every crossing's t (the mesh harness
 * computes the mesh's own), two crossings within twice it may come either
 * way too. */
static int same_first(const hr_ray *ray, const hr_hit *first, const hr_hit *all, int n_all,
                      int closed, double t_error)
{
    const hr_hit *f = &first[0], *a = &all[0];
    if (f->t == a->t && f->surface == a->surface && f->entering == a->entering) return 1;
    const double speed = fmax(fabs(ray->dir.x), fmax(fabs(ray->dir.y), fabs(ray->dir.z)));
    const double gap = f->t - a->t;
    const int same_place = gap * speed <= 4.0 * (f->error + a->error);
    if (!(same_place || gap <= 1e-6 * fabs(a->t) || gap <= 2.0 * t_error)) return 0;
    /* A closed shape's hit list fixes which of two crossings at one place
     * comes first (entering from outside), so first_hit must agree on the
     * flag; an open surface's order there is rounding's. */
    if (closed && f->entering != a->entering) return 0;
    const int shown = n_all < HARNESS_MAX_HITS ? n_all : HARNESS_MAX_HITS;
    for (int k = 1; k < shown; k++)
        if (all[k].t == f->t && all[k].surface == f->surface && all[k].entering == f->entering)
            return 1;
    /* Past the hits copied out (harness_trace copies HARNESS_MAX_HITS of a
     * longer list), it cannot be looked for. */
    return n_all >= HARNESS_MAX_HITS && f->t >= all[shown - 1].t;
}

int fuzz_trace_modes(const harness_shape *shape, hr_ray ray, double tmin, double tmax,
                     int closed, double t_error, hr_hit all[HARNESS_MAX_HITS])
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
    if (n_all > 0 && !same_first(&ray, first, all, n_all, closed, t_error))
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
