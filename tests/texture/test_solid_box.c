/* The box-filtered checkerboard and wood (lib/texture/texture_solid.c,
 * compiled into this test) against numerical integration of the
 * point-sampled ones over the same box, and against themselves
 * point-sampled.
 *
 * Reference: the midpoint rule on an n-per-axis grid over the box, summed
 * in long double, of the point texture with A = white and B = black (so the
 * red channel is the share of A). Its error: along one axis the wave is +-1
 * with a jump at each whole number; a grid cell without a jump is exact, a
 * cell with one is off by at most 2 in a mean of n cells, so that axis's
 * mean is within 2 J / n, J the whole numbers strictly inside the interval.
 * The grid is a product, so the grid mean of the product of the axes' waves
 * is the product of the axes' grid means, and a product of factors within
 * [-1, 1] moves by at most the sum of their moves: the share of A, half the
 * mean plus a half, is within sum_i J_i / n. The closed form adds at most
 * 2^-26 per axis (see square_wave_mean); we allow sum_i J_i / n + 1e-6. */
#include <math.h>
#include <stdio.h>

#include "hr_test.h"
#include "texture/texture.h"
#include "geometry/vec.h"

static double checker[7] = {1.0, 1, 1, 1, 0, 0, 0};
/* Wood: rings 0.1 apart, A white and B black; straight (no wobble) or
 * Hill's default wobble. */
static double straight_wood[10] = {0.1, 0.0, 4, 2.0, 1, 1, 1, 0, 0, 0};
static double wobbly_wood[10] = {0.1, 0.4, 4, 2.0, 1, 1, 1, 0, 0, 0};

static int jumps_inside(double lo, double hi)
{
    if (!(hi > lo)) return 0;
    return (int)(ceil(hi) - floor(lo)) - 1;
}

static double reference(const hr_texture_kind *kind, const double *params, hr_vec3 q, hr_vec3 h,
                        int n[3])
{
    long double sum = 0;
    const double lo[3] = {q.x - h.x, q.y - h.y, q.z - h.z};
    const double step[3] = {2 * h.x / n[0], 2 * h.y / n[1], 2 * h.z / n[2]};
    for (int i = 0; i < n[0]; i++)
        for (int j = 0; j < n[1]; j++)
            for (int k = 0; k < n[2]; k++) {
                const hr_vec3 p = {n[0] > 1 ? lo[0] + (i + 0.5) * step[0] : q.x,
                                   n[1] > 1 ? lo[1] + (j + 0.5) * step[1] : q.y,
                                   n[2] > 1 ? lo[2] + (k + 0.5) * step[2] : q.z};
                sum += kind->solid(params, p).r;
            }
    return (double)(sum / ((long double)n[0] * n[1] * n[2]));
}

static void check_box(const hr_texture_kind *kind, hr_vec3 q, hr_vec3 h, int per_axis)
{
    int n[3];
    const double half[3] = {h.x, h.y, h.z}, at[3] = {q.x, q.y, q.z};
    double tol = 1e-6;
    for (int i = 0; i < 3; i++) {
        n[i] = half[i] > 0 ? per_axis : 1;
        if (half[i] > 0) tol += (double)jumps_inside(at[i] - half[i], at[i] + half[i]) / n[i];
    }
    const double want = reference(kind, checker, q, h, n);
    const double got = kind->solid_box(checker, q, h).r;
    CHECK_MSG(fabs(got - want) <= tol,
              "box (%g, %g, %g) +- (%g, %g, %g): %.9f, integrated %.9f (tolerance %.3g)", q.x, q.y,
              q.z, h.x, h.y, h.z, got, want, tol);
}

/* Wood. Straight rings across a box along x at (x, 0, z), x > 0: the ring
 * number is x / 0.1, linear, so the filter is the exact mean, and the
 * midpoint rule's bound holds with the jumps counted in ring numbers (a
 * rule over n cells in x). A box many rings wide, or on the axis, gives the
 * mean colour: the wave's mean over w rings is at most 1 / (2 w) (its
 * integral, the triangle wave, is within [0, 1]). half = 0 is Hill's wood
 * bit for bit. */
static void test_wood(void)
{
    const hr_texture_kind *wood = hri_solid_texture_find(-2);
    CHECK(wood && wood->solid_box);
    if (!(wood && wood->solid_box)) return;
    const double boxes[][2] = {{0.33, 0.02}, {1.234, 0.07}, {2.5, 0.011}, {0.8, 0.3}};
    for (int i = 0; i < 4; i++) {
        const hr_vec3 q = {boxes[i][0], 0, 0.4}, h = {boxes[i][1], 0, 0};
        int n[3] = {4096, 1, 1};
        const double want = reference(wood, straight_wood, q, h, n);
        const double got = wood->solid_box(straight_wood, q, h).r;
        const double tol = jumps_inside((q.x - h.x) / 0.1, (q.x + h.x) / 0.1) / 4096.0 + 1e-6;
        CHECK_MSG(fabs(got - want) <= tol, "straight wood at %g +- %g: %.9f, integrated %.9f",
                  q.x, h.x, got, want);
    }
    for (int i = 0; i < 10; i++) {
        const hr_vec3 q = {0.3 + 0.41 * i, -0.2 * i, 0.1 * i};
        const double far = wood->solid_box(wobbly_wood, q, (hr_vec3){5, 5, 5}).r;
        CHECK_MSG(fabs(far - 0.5) <= 1.0 / (2 * 50), "wood over 50 rings at %d: %.9f", i, far);
        const double axis = wood->solid_box(wobbly_wood, (hr_vec3){0, 0, q.z}, (hr_vec3){1e-3, 0, 0}).r;
        CHECK_MSG(axis == 0.5, "wood on the axis: %.17g", axis);
        const hr_vec3 p = {q.x - 2, q.y + 0.7, q.z - 0.3};
        const double r = hypot(p.x, p.y), theta = atan2(p.y, p.x);
        const double ring = r / 0.1 + 0.4 * sin(4 * theta + 2.0 * p.z);
        const double hill = fabs(fmod(floor(ring), 2.0)) == 1.0 ? 0.0 : 1.0;
        const double point = wood->solid(wobbly_wood, p).r;
        CHECK_MSG(point == hill && wood->solid_box(wobbly_wood, p, (hr_vec3){0, 0, 0}).r == point,
                  "wood point %d: %g, Hill's %g", i, point, hill);
    }
}

/* Marble: half = 0 is Hill's formula bit for bit; with no turbulence the
 * veins are sqrt|sin(pi f z)|, whose mean over a box one period deep
 * (2 half_z = 1 / f) is the mean colour, which the filtered texture gives
 * there (checked against the midpoint rule in long double: the integrand
 * is continuous, its rule error under 1e-6 at 200000 points); a box a
 * thousandth of a period deep stays within 1% of the point value, and
 * boxes wider than a period give the mean exactly. */
static void test_marble(void)
{
    const hr_texture_kind *kind = hri_solid_texture_find(-3);
    CHECK(kind && kind->solid_box);
    if (!kind || !kind->solid_box) return;
    double plain[10] = {1.5, 2.0, 0.0, 5, 1, 1, 1, 0, 0, 0};
    double hill[10] = {1.5, 2.0, 5.0, 5, 1, 1, 1, 0, 0, 0};
    const hr_vec3 pts[] = {{0.1, 0.2, 0.3}, {-1.5, 2.25, 0.7}, {3, -4, -5.125}, {0, 0, 0}};
    for (int i = 0; i < 4; i++) {
        const hr_color a = kind->solid(hill, pts[i]);
        const hr_color b = kind->solid_box(hill, pts[i], (hr_vec3){0, 0, 0});
        const double turb = hri_turbulence(v3_scale(pts[i], 2.0), 5);
        const double want = sqrt(fabs(sin(3.14159265358979323846 * 1.5 * pts[i].z + 5.0 * turb)));
        CHECK_MSG(a.r == b.r && a.r == want, "marble at point %d: %.17g, box %.17g, formula %.17g", i, a.r, b.r,
                  want);
        const int n = 200000;
        const double h = 1.0 / 3.0; /* one period of |sin(1.5 pi z)| */
        long double sum = 0;
        for (int k = 0; k < n; k++) {
            const double z = pts[i].z - h + (k + 0.5) * (2 * h / n);
            sum += kind->solid(plain, (hr_vec3){pts[i].x, pts[i].y, z}).r;
        }
        const hr_color box = kind->solid_box(plain, pts[i], (hr_vec3){0, 0, h});
        CHECK_MSG(fabs(box.r - (double)(sum / n)) < 1e-6, "marble box at %d: %.9g, integral %.9Lg", i, box.r,
                  sum / n);
        const hr_color fine = kind->solid_box(plain, pts[i], (hr_vec3){0, 0, 1e-3 * h});
        const hr_color point = kind->solid(plain, pts[i]);
        CHECK_MSG(fabs(fine.r - point.r) <= 0.01, "marble fine box at %d: %g, point %g", i, fine.r, point.r);
        const hr_color wide = kind->solid_box(hill, pts[i], (hr_vec3){10, 10, 10});
        CHECK_MSG(fabs(wide.r - box.r) < 1e-12, "marble wide box at %d: %.17g", i, wide.r);
    }
}

int main(void)
{
    const hr_texture_kind *kind = hri_solid_texture_find(-1);
    CHECK(kind && kind->solid && kind->solid_box);
    if (!(kind && kind->solid && kind->solid_box)) return hr_test_end();

    /* A floor's footprints (no depth), from a fraction of a square to several. */
    const double floors[][4] = {{0.3, 0.4, 0.1, 0.05}, {0.9, 0.2, 0.3, 0.3},  {-2.7, 5.1, 1.6, 0.2},
                                {10.5, -3.25, 2.5, 4}, {0.0, 0.0, 0.5, 0.5},  {123.4, 56.7, 0.02, 3.3},
                                {-0.01, 0.99, 0.75, 0.01}};
    for (int i = 0; i < 7; i++)
        check_box(kind, (hr_vec3){floors[i][0], floors[i][1], 0.5},
                  (hr_vec3){floors[i][2], floors[i][3], 0}, 2048);
    /* Boxes in all three axes. */
    check_box(kind, (hr_vec3){0.2, 0.7, -0.4}, (hr_vec3){0.6, 0.3, 0.9}, 160);
    check_box(kind, (hr_vec3){3.3, -1.1, 2.2}, (hr_vec3){1.7, 0.05, 0.4}, 160);

    /* A box a whole period wide on one axis averages that axis to 0: the
     * mean colour, (A + B) / 2, wherever it sits. */
    for (int i = 0; i < 20; i++) {
        const double x = -5 + 0.537 * i;
        const double r = kind->solid_box(checker, (hr_vec3){x, 0.3, 0.3}, (hr_vec3){1, 0, 0}).r;
        CHECK_MSG(fabs(r - 0.5) <= 1e-12, "whole period at x = %g: %.17g", x, r);
    }

    /* half = 0 is the point sample bit for bit, at ordinary and huge
     * coordinates and on the squares' edges. */
    const double xs[] = {0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.999, 1e17, -3e300, 7.25, -1e-300};
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            const hr_vec3 p = {xs[i], xs[j], xs[(i + j) % 11]};
            const hr_color a = kind->solid(checker, p);
            const hr_color b = kind->solid_box(checker, p, (hr_vec3){0, 0, 0});
            const int odd = ((int)fabs(fmod(floor(p.x), 2.0)) ^ (int)fabs(fmod(floor(p.y), 2.0)) ^
                             (int)fabs(fmod(floor(p.z), 2.0)));
            CHECK_MSG(a.r == b.r && a.g == b.g && a.b == b.b && a.r == (odd ? 0.0 : 1.0),
                      "point (%g, %g, %g): %g, box %g, parity %d", p.x, p.y, p.z, a.r, b.r, odd);
        }
    test_wood();
    test_marble();
    return hr_test_end();
}
