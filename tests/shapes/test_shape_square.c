/* The square module (z = 0, |x|, |y| <= 1, normal +z): hits by hand, the
 * closed edges and corners, a sweep across an edge, parallel rays. */
#include <math.h>

#include "hr_test.h"
#include "module_harness.h"

static harness_shape square;

/* (0.5, 0.25, 2) + t (0, 0, -1): t = 2 at (0.5, 0.25, 0), entering (against
 * the normal). From below, (-0.5, 0.75, -1) + t (0.25, 0, 2): t = 0.5 at
 * (-0.375, 0.75, 0), exiting. Hill's plane example meets z = 0 at
 * (1, -4, 0): outside the square, no hit. */
static void test_by_hand(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&square, harness_ray(0.5, 0.25, 2, 0, 0, -1), h) == 1);
    harness_expect_hit("down", &h[0], 2, 0, 1, harness_vec(0.5, 0.25, 0), harness_vec(0, 0, 1));
    CHECK(harness_hits(&square, harness_ray(-0.5, 0.75, -1, 0.25, 0, 2), h) == 1);
    harness_expect_hit("up", &h[0], 0.5, 0, 0, harness_vec(-0.375, 0.75, 0), harness_vec(0, 0, 1));
    CHECK(harness_hits(&square, harness_ray(4, 1, 3, -3, -5, -3), h) == 0);
}

/* The edges and corners belong to the square; one ulp outside does not. */
static void test_edges_and_corners(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    const double out = nextafter(1.0, 2.0);
    CHECK(harness_hits(&square, harness_ray(1, 0.3, 1, 0, 0, -1), h) == 1);
    CHECK(harness_hits(&square, harness_ray(-1, -0.3, 1, 0, 0, -1), h) == 1);
    CHECK(harness_hits(&square, harness_ray(1, 1, 1, 0, 0, -1), h) == 1);
    CHECK(harness_hits(&square, harness_ray(-1, -1, -1, 0, 0, 1), h) == 1);
    CHECK(harness_hits(&square, harness_ray(out, 0.3, 1, 0, 0, -1), h) == 0);
    CHECK(harness_hits(&square, harness_ray(0.3, -out, 1, 0, 0, -1), h) == 0);
    CHECK(harness_hits(&square, harness_ray(out, out, 1, 0, 0, -1), h) == 0);
}

/* Slanted rays (x0, 0.5, 1) + t (0.5, 0, -1) land at x = x0 + 0.5, swept
 * across the edge x = 1 in steps of 1e-7: a hit exactly when the reported
 * point is inside, so the decision and the reported point never disagree. */
static void test_edge_sweep(void)
{
    for (int i = -20; i <= 20; i++) {
        const double x0 = 0.5 + i * 1e-7;
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&square, harness_ray(x0, 0.5, 1, 0.5, 0, -1), h);
        const double x = x0 + 1.0 * 0.5;
        CHECK_MSG(n == (x <= 1.0 ? 1 : 0), "x0 = %.17g: %d hits", x0, n);
        if (n) CHECK(h[0].point.x == x && fabs(h[0].point.x) <= 1.0);
    }
}

/* Parallel rays (+0 and -0 d.z), also in the square's plane: no hit. */
static void test_parallel(void)
{
    const double dzs[] = {0.0, -0.0};
    const double zs[] = {0.5, 0.0, -0.0};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 2; j++) {
            hr_hit h[HARNESS_MAX_HITS];
            CHECK(harness_trace(&square, harness_ray(-3, 0, zs[i], 1, 0, dzs[j]), -INFINITY,
                                INFINITY, HARNESS_ALL, h) == 0);
        }
}

int main(void)
{
    if (!harness_open(&square, "square", "square", NAN)) return hr_test_end() | 1;
    test_by_hand();
    test_edges_and_corners();
    test_edge_sweep();
    test_parallel();
    harness_close(&square);
    return hr_test_end();
}
