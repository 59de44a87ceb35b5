/* The fast paths against the full hit list, for every class on thousands of
 * random rays (fixed seed) with random intervals (tmin, tmax):
 * - first_hit returns exactly the first element of hit (every field), or
 *   nothing when hit has nothing;
 * - any_hit returns one hit when hit has any (and its t is one of them),
 *   none otherwise.
 * Every call also goes through the harness's contract checks (open interval,
 * sorted, finite, alternating for solids, ...), and every hit point must lie
 * within the class's bounds (grown by the hit's error bound). */
#include <math.h>
#include <string.h>

#include "hr_test.h"
#include "module_harness.h"
#include "random_rays.h"

#define RAYS_PER_CLASS 20000

static int same_hit(const hr_hit *a, const hr_hit *b)
{
    return a->t == b->t && a->point.x == b->point.x && a->point.y == b->point.y &&
           a->point.z == b->point.z && a->normal.x == b->normal.x &&
           a->normal.y == b->normal.y && a->normal.z == b->normal.z && a->error == b->error &&
           a->surface == b->surface && a->entering == b->entering;
}

static int within_bounds(const hr_bounds *b, const hr_hit *h)
{
    const double e = h->error;
    return h->point.x >= b->lo.x - e && h->point.x <= b->hi.x + e && h->point.y >= b->lo.y - e &&
           h->point.y <= b->hi.y + e && h->point.z >= b->lo.z - e && h->point.z <= b->hi.z + e;
}

static void test_class(const harness_class_ref *ref, uint64_t seed)
{
    harness_shape shape;
    if (!harness_open_ref(&shape, ref)) {
        harness_close(&shape);
        return;
    }
    hr_bounds bounds;
    shape.cls->bounds(shape.shape, &bounds);
    ray_rng rng;
    rng_seed(&rng, seed);
    int rays_with_hits = 0, first_mismatch = 0, any_mismatch = 0, outside_bounds = 0;
    for (int i = 0; i < RAYS_PER_CLASS; i++) {
        const hr_ray ray = random_ray_near(&rng, &bounds);
        double tmin, tmax;
        random_interval(&rng, &tmin, &tmax);
        hr_hit all[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
        const int n_all = harness_trace(&shape, ray, tmin, tmax, HARNESS_ALL, all);
        const int n_first = harness_trace(&shape, ray, tmin, tmax, HARNESS_FIRST, first);
        const int n_any = harness_trace(&shape, ray, tmin, tmax, HARNESS_ANY, any);
        rays_with_hits += n_all > 0;
        if (n_first != (n_all > 0) || (n_first && !same_hit(&first[0], &all[0]))) first_mismatch++;
        int any_ok = n_any == (n_all > 0);
        if (any_ok && n_any) {
            any_ok = 0;
            for (int j = 0; j < n_all; j++) any_ok |= any[0].t == all[j].t;
        }
        any_mismatch += !any_ok;
        for (int j = 0; j < n_all; j++) outside_bounds += !within_bounds(&bounds, &all[j]);
    }
    CHECK_MSG(first_mismatch == 0, "%s (s = %g): first_hit disagrees on %d rays", ref->name,
              ref->s, first_mismatch);
    CHECK_MSG(any_mismatch == 0, "%s (s = %g): any_hit disagrees on %d rays", ref->name, ref->s,
              any_mismatch);
    CHECK_MSG(outside_bounds == 0, "%s (s = %g): %d points outside the bounds", ref->name, ref->s,
              outside_bounds);
    /* The rays are aimed to hit often; a class that never reports a hit
     * would pass the agreement checks vacuously. */
    CHECK_MSG(rays_with_hits > RAYS_PER_CLASS / 5, "%s: only %d of %d rays hit", ref->name,
              rays_with_hits, RAYS_PER_CLASS);
    harness_close(&shape);
}

int main(void)
{
    for (int i = 0; i < harness_catalog_count; i++)
        test_class(&harness_catalog[i], UINT64_C(0x5eed0000) + (uint64_t)i);
    return hr_test_end();
}
