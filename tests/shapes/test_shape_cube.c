/* The cube module (corners (+-1, +-1, +-1); surfaces +x, -x, +y, -y, +z, -z
 * = 0..5): hits by hand, edges and corners (entered once, owned by the x
 * faces, then y, on exact ties), a ray in a face's plane, zero and
 * negative-zero direction components, an origin inside, and a sweep across
 * an edge. */
#include <math.h>

#include "hr_test.h"
#include "module_harness.h"

static harness_shape cube;

/* (5, 0, 0) + t (-1, 0, 0): the x slab is t in [(1-5)/-1, (-1-5)/-1] =
 * [4, 6], y and z are always inside. Enter +x (0) at (1, 0, 0), leave -x (1)
 * at (-1, 0, 0). */
static void test_axis_ray(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cube, harness_ray(5, 0, 0, -1, 0, 0), h) == 2);
    harness_expect_hit("+x in", &h[0], 4, 0, 1, harness_vec(1, 0, 0), harness_vec(1, 0, 0));
    harness_expect_hit("-x out", &h[1], 6, 1, 0, harness_vec(-1, 0, 0), harness_vec(-1, 0, 0));
}

/* (0.5, -3, 0.25) + t (0, 2, 0.5): y slab [(-1+3)/2, (1+3)/2] = [1, 2]; z
 * slab (z = 0.25 + 0.5 t) [-2.5, 1.5]; x always inside. Span [1, 1.5]:
 * enter -y (3) at (0.5, -1, 0.75), leave +z (4) at (0.5, 0, 1). */
static void test_oblique(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cube, harness_ray(0.5, -3, 0.25, 0, 2, 0.5), h) == 2);
    harness_expect_hit("-y in", &h[0], 1, 3, 1, harness_vec(0.5, -1, 0.75), harness_vec(0, -1, 0));
    harness_expect_hit("+z out", &h[1], 1.5, 4, 0, harness_vec(0.5, 0, 1), harness_vec(0, 0, 1));
}

/* Through the edge x = y = 1: (3, 3, 0) + t (-1, -1, 0) has x and y slabs
 * both [2, 4]; the exact tie goes to x: enter +x at (1, 1, 0), leave -x at
 * (-1, -1, 0). Through the corner (1, 1, 1) along (-1, -1, -1): the same
 * with three slabs tied. Exactly two hits each: no miss, no double count. */
static void test_edge_and_corner(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cube, harness_ray(3, 3, 0, -1, -1, 0), h) == 2);
    harness_expect_hit("edge in", &h[0], 2, 0, 1, harness_vec(1, 1, 0), harness_vec(1, 0, 0));
    harness_expect_hit("edge out", &h[1], 4, 1, 0, harness_vec(-1, -1, 0), harness_vec(-1, 0, 0));
    CHECK(harness_hits(&cube, harness_ray(3, 3, 3, -1, -1, -1), h) == 2);
    harness_expect_hit("corner in", &h[0], 2, 0, 1, harness_vec(1, 1, 1), harness_vec(1, 0, 0));
    harness_expect_hit("corner out", &h[1], 4, 1, 0, harness_vec(-1, -1, -1),
                       harness_vec(-1, 0, 0));
}

/* Touching only an edge: (2, 0, 0) + t (-1, 0, 1) has x slab [1, 3] and z
 * slab [-1, 1]: the span [1, 1] is a zero-length visit at (1, 0, 1), entered
 * through +x (0) and left through +z (4) at the same t. */
static void test_grazing_edge(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cube, harness_ray(2, 0, 0, -1, 0, 1), h) == 2);
    harness_expect_hit("graze in", &h[0], 1, 0, 1, harness_vec(1, 0, 1), harness_vec(1, 0, 0));
    harness_expect_hit("graze out", &h[1], 1, 4, 0, harness_vec(1, 0, 1), harness_vec(0, 0, 1));
}

/* In the plane of the +x face, (1, -5, 0) + t (+-0, 1, 0): the closed x slab
 * holds the ray everywhere; y gives [4, 6]: enter -y at (1, -1, 0), leave +y
 * at (1, 1, 0). One ulp outside the face plane: no hit. Both signs of zero
 * behave the same, and nothing divides by them. */
static void test_in_face_plane(void)
{
    const double zeros[] = {0.0, -0.0};
    for (int i = 0; i < 2; i++) {
        hr_hit h[HARNESS_MAX_HITS];
        CHECK(harness_hits(&cube, harness_ray(1, -5, 0, zeros[i], 1, zeros[i]), h) == 2);
        harness_expect_hit("face plane in", &h[0], 4, 3, 1, harness_vec(1, -1, 0),
                           harness_vec(0, -1, 0));
        harness_expect_hit("face plane out", &h[1], 6, 2, 0, harness_vec(1, 1, 0),
                           harness_vec(0, 1, 0));
        CHECK(harness_hits(&cube, harness_ray(nextafter(1, 2), -5, 0, zeros[i], 1, 0), h) == 0);
        CHECK(harness_hits(&cube, harness_ray(0, -5, 2, 0, 1, zeros[i]), h) == 0);
    }
}

/* From the centre down: one exiting hit, -z (5) at (0, 0, -1), t = 1. */
static void test_origin_inside(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cube, harness_ray(0, 0, 0, 0, 0, -1), h) == 1);
    harness_expect_hit("inside", &h[0], 1, 5, 0, harness_vec(0, 0, -1), harness_vec(0, 0, -1));
}

/* (3, 3 + delta, 0.5) + t (-1, -1, 0) passes the edge x = y = 1 at a
 * distance of about delta: x slab [2, 4], y slab [2 + delta, 4 + delta].
 * Swept over delta = -2e-6 .. 2e-6 in 1e-7 steps it always enters once and
 * leaves once: +x (0) then -y (3) below the edge, +y (2) then -x (1) above
 * it, and at delta = 0 (the tie) the x faces. */
static void test_edge_sweep(void)
{
    for (int i = -20; i <= 20; i++) {
        const double delta = i * 1e-7;
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&cube, harness_ray(3, 3 + delta, 0.5, -1, -1, 0), h);
        CHECK_MSG(n == 2, "delta = %g: %d hits", delta, n);
        if (n != 2) continue;
        CHECK_MSG(h[0].surface == (i > 0 ? 2 : 0) && h[1].surface == (i < 0 ? 3 : 1),
                  "delta = %g: surfaces %d, %d", delta, (int)h[0].surface, (int)h[1].surface);
        CHECK(fabs(h[0].t - 2) <= 3e-6 && fabs(h[1].t - 4) <= 3e-6);
    }
}

int main(void)
{
    if (!harness_open(&cube, "cube", "cube", NAN)) return hr_test_end() | 1;
    test_axis_ray();
    test_oblique();
    test_edge_and_corner();
    test_grazing_edge();
    test_in_face_plane();
    test_origin_inside();
    test_edge_sweep();
    harness_close(&cube);
    return hr_test_end();
}
