/* The plane module (z = 0, normal +z) against hits worked out by hand and its
 * hard cases: parallel rays with +0 and -0 direction components, origins on
 * the plane, and rays whose time or point would overflow. */
#include <math.h>

#include "hr_test.h"
#include "module_harness.h"

static harness_shape plane;

/* Hill's worked example: (4, 1, 3) + t (-3, -5, -3) meets z = 0 where
 * 3 - 3t = 0, t = 1, at (4 - 3, 1 - 5, 0) = (1, -4, 0). The ray moves
 * against the normal (d.z < 0): entering. */
static void test_hill_example(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&plane, harness_ray(4, 1, 3, -3, -5, -3), h) == 1);
    harness_expect_hit("Hill", &h[0], 1, 0, 1, harness_vec(1, -4, 0), harness_vec(0, 0, 1));
    CHECK(h[0].point.z == 0.0);
}

/* From below, (0.5, 0.5, -2) + t (0, 0, 4): t = 2/4 = 0.5, leaving (the
 * normal side is outside). A far, slanted ray (0, 0, 1e6) + t (1e-3, 0, -1):
 * t = 1e6 at (1000, 0, 0). */
static void test_other_rays(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&plane, harness_ray(0.5, 0.5, -2, 0, 0, 4), h) == 1);
    harness_expect_hit("from below", &h[0], 0.5, 0, 0, harness_vec(0.5, 0.5, 0),
                       harness_vec(0, 0, 1));
    CHECK(harness_hits(&plane, harness_ray(0, 0, 1e6, 1e-3, 0, -1), h) == 1);
    harness_expect_hit("far", &h[0], 1e6, 0, 1, harness_vec(1000, 0, 0), harness_vec(0, 0, 1));
}

/* d.z = +0 or -0: parallel, no hit, whether the origin is above, below or on
 * the plane (o.z = +0 and -0), and whatever the interval: nothing divides by
 * zero, so no NaN or infinity can appear. */
static void test_parallel(void)
{
    const double zs[] = {1.0, -1.0, 0.0, -0.0};
    const double dzs[] = {0.0, -0.0};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 2; j++)
            for (int mode = HARNESS_ALL; mode <= HARNESS_ANY; mode++) {
                hr_hit h[HARNESS_MAX_HITS];
                const int n = harness_trace(&plane, harness_ray(0.3, -2, zs[i], 1, 1, dzs[j]),
                                            -INFINITY, INFINITY, mode, h);
                CHECK_MSG(n == 0, "o.z = %g, d.z = %g, mode %d: %d hits", zs[i], dzs[j], mode, n);
            }
}

/* An origin on the plane gives t = 0 (or -0), outside (0, inf) but inside
 * (-1, inf): the interval is what decides, not an epsilon. */
static void test_origin_on_plane(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&plane, harness_ray(1, 2, 0, 0, 1, -1), h) == 0);
    CHECK(harness_hits(&plane, harness_ray(1, 2, -0.0, 0, 1, 1), h) == 0);
    CHECK(harness_trace(&plane, harness_ray(1, 2, 0, 0, 1, -1), -1, INFINITY, HARNESS_ALL, h) == 1);
    CHECK(h[0].t == 0.0 && h[0].point.x == 1.0 && h[0].point.y == 2.0 && h[0].point.z == 0.0);
}

/* Overflow: 1e300 / 1e-300 is infinite (never in an open interval), and a
 * finite t = 1e10 with d.x = 1e300 puts x at infinity: both are no hit
 * rather than an infinite field. */
static void test_overflow(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_trace(&plane, harness_ray(0, 0, 1e300, 0, 0, -1e-300), -INFINITY, INFINITY,
                        HARNESS_ALL, h) == 0);
    CHECK(harness_hits(&plane, harness_ray(1e300, 0, 1, 1e300, 0, -1e-10), h) == 0);
}

int main(void)
{
    if (!harness_open(&plane, "plane", "plane", NAN)) return hr_test_end() | 1;
    test_hill_example();
    test_other_rays();
    test_parallel();
    test_origin_on_plane();
    test_overflow();
    harness_close(&plane);
    return hr_test_end();
}
