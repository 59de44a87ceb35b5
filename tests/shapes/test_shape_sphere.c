/* The sphere module against hits worked out by hand, the hard cases (ray
 * starting inside, exact tangent, near tangent, rays pointing away, the open
 * interval (tmin, tmax)) and a far sphere with an exactly known answer.
 * Random rays against quad-precision roots are in test_shape_accuracy.c. */
#include <float.h>
#include <math.h>

#include "hr_test.h"
#include "module_harness.h"

static harness_shape sphere;

/* o = (0, 0, 5), d = (0, 0, -1): |o + t d|^2 = (5 - t)^2 = 1, so t = 4 (at
 * the north pole (0, 0, 1), entering) and t = 6 (south pole, exiting). */
static void test_axis_ray(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&sphere, harness_ray(0, 0, 5, 0, 0, -1), h) == 2);
    harness_expect_hit("axis in", &h[0], 4, 0, 1, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
    harness_expect_hit("axis out", &h[1], 6, 0, 0, harness_vec(0, 0, -1), harness_vec(0, 0, -1));
}

/* o = (-3, 0.6, 0), d = (2, 0, 0) (not unit length: t is in units of d):
 * (-3 + 2t)^2 + 0.36 = 1, so 2t - 3 = -+0.8, t = 1.1 at (-0.8, 0.6, 0)
 * entering and t = 1.9 at (0.8, 0.6, 0) exiting; the normals are the
 * points. */
static void test_scaled_direction(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&sphere, harness_ray(-3, 0.6, 0, 2, 0, 0), h) == 2);
    harness_expect_hit("chord in", &h[0], 1.1, 0, 1, harness_vec(-0.8, 0.6, 0),
                       harness_vec(-0.8, 0.6, 0));
    harness_expect_hit("chord out", &h[1], 1.9, 0, 0, harness_vec(0.8, 0.6, 0),
                       harness_vec(0.8, 0.6, 0));
}

/* From the centre along +y the roots are -1 and 1: only t = 1 is in
 * (0, inf), an exiting hit at (0, 1, 0). From (0.2, 0.1, -0.3) along
 * (0, 0, 2): (0.05 + (-0.3 + 2t)^2 = 1, 2t = 0.3 + sqrt(0.95)) one exiting
 * hit. */
static void test_origin_inside(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&sphere, harness_ray(0, 0, 0, 0, 1, 0), h) == 1);
    harness_expect_hit("from centre", &h[0], 1, 0, 0, harness_vec(0, 1, 0), harness_vec(0, 1, 0));

    CHECK(harness_hits(&sphere, harness_ray(0.2, 0.1, -0.3, 0, 0, 2), h) == 1);
    const double t = (0.3 + sqrt(0.95)) / 2, z = -0.3 + 2 * t;
    harness_expect_hit("from inside", &h[0], t, 0, 0, harness_vec(0.2, 0.1, z),
                       harness_vec(0.2, 0.1, z));
}

/* o = (-2, 1, 0), d = (1, 0, 0) touches the sphere at (0, 1, 0), t = 2:
 * o x d = (0, 0, -1), so the discriminant |d|^2 - |o x d|^2 is exactly 0.
 * The same with o = (-5, 0, 1), d = (0.5, 0, 0): o x d = (0, 0.5, 0),
 * 0.25 - 0.25 = 0, double root -b/a = 2.5 / 0.25 = 10 at (0, 0, 1).
 * A tangent is a double root: reported as two hits at the same t, entering
 * then exiting, never one hit and never NaN. */
static void test_exact_tangent(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&sphere, harness_ray(-2, 1, 0, 1, 0, 0), h) == 2);
    harness_expect_hit("tangent in", &h[0], 2, 0, 1, harness_vec(0, 1, 0), harness_vec(0, 1, 0));
    harness_expect_hit("tangent out", &h[1], 2, 0, 0, harness_vec(0, 1, 0), harness_vec(0, 1, 0));
    CHECK(h[0].t == h[1].t);

    CHECK(harness_hits(&sphere, harness_ray(-5, 0, 1, 0.5, 0, 0), h) == 2);
    harness_expect_hit("tangent 2 in", &h[0], 10, 0, 1, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
    CHECK(h[0].t == h[1].t);

    /* The fast paths see the same single touching point. */
    CHECK(harness_trace(&sphere, harness_ray(-2, 1, 0, 1, 0, 0), 0, INFINITY, HARNESS_FIRST, h) == 1);
    CHECK(h[0].t == 2 && h[0].entering == 1);
    CHECK(harness_trace(&sphere, harness_ray(-2, 1, 0, 1, 0, 0), 0, INFINITY, HARNESS_ANY, h) == 1);
}

/* One ulp either side of the tangent line y = 1: the answer may be a miss or
 * a (tiny) chord, but always 0 or 2 well-formed hits (the harness checks
 * order, alternation and finiteness) whose points lie on the sphere. */
static void test_near_tangent(void)
{
    const double ys[] = {nextafter(1.0, 0.0), nextafter(1.0, 2.0), 1.0 - 1e-12, 1.0 + 1e-12};
    for (int i = 0; i < 4; i++) {
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&sphere, harness_ray(-2, ys[i], 0, 1, 0, 0), h);
        CHECK_MSG(n == 0 || n == 2, "y = %.17g: %d hits", ys[i], n);
        CHECK_MSG(ys[i] < 1 || n == 0 || h[1].t - h[0].t < 1e-5, "y = %.17g: chord too long",
                  ys[i]);
        for (int j = 0; j < n; j++)
            CHECK_NEAR(h[j].point.x * h[j].point.x + h[j].point.y * h[j].point.y +
                           h[j].point.z * h[j].point.z,
                       1.0, 8 * DBL_EPSILON);
    }
}

/* Away from the sphere there is nothing in (0, inf); over all t the two
 * roots are -6 (entering: t increases into the sphere) and -4. */
static void test_pointing_away(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&sphere, harness_ray(0, 0, 5, 0, 0, 1), h) == 0);
    CHECK(harness_trace(&sphere, harness_ray(0, 0, 5, 0, 0, 1), -INFINITY, INFINITY, HARNESS_ALL,
                        h) == 2);
    harness_expect_hit("behind in", &h[0], -6, 0, 1, harness_vec(0, 0, -1), harness_vec(0, 0, -1));
    harness_expect_hit("behind out", &h[1], -4, 0, 0, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
    CHECK(harness_hits(&sphere, harness_ray(0, 2, 5, 0, 0, -1), h) == 0); /* a clean miss */
}

/* The interval is open: with roots 4 and 6, tmin = 4 drops the first,
 * tmax = 6 the second, (4.5, 5.5) holds neither. */
static void test_open_interval(void)
{
    const hr_ray ray = harness_ray(0, 0, 5, 0, 0, -1);
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_trace(&sphere, ray, 4, INFINITY, HARNESS_ALL, h) == 1 && h[0].t == 6);
    CHECK(harness_trace(&sphere, ray, 0, 6, HARNESS_ALL, h) == 1 && h[0].t == 4);
    CHECK(harness_trace(&sphere, ray, 4.5, 5.5, HARNESS_ALL, h) == 0);
    CHECK(harness_trace(&sphere, ray, 4, INFINITY, HARNESS_FIRST, h) == 1 && h[0].t == 6);
    CHECK(harness_trace(&sphere, ray, 4.5, 5.5, HARNESS_ANY, h) == 0);
}

/* From (1e6, 0, 0) toward the centre: b = -1e6, c = 1e12 - 1 (exact in
 * double), disc = 1, so q = 1e6 + 1 and the roots are q = 1000001 and
 * c / q = 999999, both exact. The textbook b^2 - a c = 1e12 - (1e12 - 1)
 * would be right here only by luck; at an angle it loses ~12 digits (see
 * test_shape_accuracy.c). Scaled and offset versions keep exact answers. */
static void test_far_exact(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&sphere, harness_ray(1e6, 0, 0, -1, 0, 0), h) == 2);
    CHECK_MSG(h[0].t == 999999.0 && h[1].t == 1000001.0, "far roots %.17g %.17g", h[0].t, h[1].t);
    CHECK(harness_hits(&sphere, harness_ray(0, 0, -1e6, 0, 0, 0.25), h) == 2);
    CHECK_MSG(h[0].t == 3999996.0 && h[1].t == 4000004.0, "far roots %.17g %.17g", h[0].t, h[1].t);
    harness_expect_hit("far in", &h[0], 3999996.0, 0, 1, harness_vec(0, 0, -1),
                       harness_vec(0, 0, -1));
}

int main(void)
{
    if (!harness_open(&sphere, "sphere", "sphere", NAN)) return hr_test_end() | 1;
    test_axis_ray();
    test_scaled_direction();
    test_origin_inside();
    test_exact_tangent();
    test_near_tangent();
    test_pointing_away();
    test_open_interval();
    test_far_exact();
    harness_close(&sphere);
    return hr_test_end();
}
