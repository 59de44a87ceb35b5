/* The cylinder module: cylinder (s = 1), cone (s = 0), taperedCylinder and
 * openTaperedCylinder (the wall alone), against hits worked out by hand, rays along the axis, rays through the
 * cone's apex, rays parallel to a generator line, the wall/disk seams swept
 * in 1e-7 steps, create with s = 0, 1 and 1e6, and Hill's taperedTube (its
 * surface 3 the inner wall).
 * Surfaces: 0 wall, 1 base (z = 0, normal -z), 2 cap (z = 1, normal +z).
 * The wall's outward normal at (x, y, z) is (x, y, -(s-1) r(z)), with
 * r(z) = 1 + (s-1) z. */
#include <math.h>
#include <string.h>

#include "hr_test.h"
#include "module_harness.h"

#define WALL 0
#define BASE 1
#define CAP 2
#define TUBE_INNER 3

static harness_shape cylinder, cone;

/* (5, 0, 0.5) + t (-1, 0, 0): (5 - t)^2 = 1 gives t = 4 and 6; dz = 0 with
 * 0 <= z <= 1 keeps the ray in the slab throughout. */
static void test_cylinder_side(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cylinder, harness_ray(5, 0, 0.5, -1, 0, 0), h) == 2);
    harness_expect_hit("side in", &h[0], 4, WALL, 1, harness_vec(1, 0, 0.5), harness_vec(1, 0, 0));
    harness_expect_hit("side out", &h[1], 6, WALL, 0, harness_vec(-1, 0, 0.5),
                       harness_vec(-1, 0, 0));
}

/* Along the axis, (0, 0, 5) + t (0, 0, -1): the wall's quadric is
 * x^2 + y^2 - 1 = -1 < 0 for every t (a = b = 0), so only the slab decides:
 * enter the cap at t = 4, leave the base at t = 5. Parallel to the axis off
 * it, (0.6, 0, -2) + t (0, 0, 3): base at t = 2/3, cap at t = 1. */
static void test_cylinder_axis(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cylinder, harness_ray(0, 0, 5, 0, 0, -1), h) == 2);
    harness_expect_hit("axis cap", &h[0], 4, CAP, 1, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
    harness_expect_hit("axis base", &h[1], 5, BASE, 0, harness_vec(0, 0, 0), harness_vec(0, 0, -1));
    CHECK(harness_hits(&cylinder, harness_ray(0.6, 0, -2, 0, 0, 3), h) == 2);
    harness_expect_hit("parallel base", &h[0], 2.0 / 3, BASE, 1, harness_vec(0.6, 0, 0),
                       harness_vec(0, 0, -1));
    harness_expect_hit("parallel cap", &h[1], 1, CAP, 0, harness_vec(0.6, 0, 1), harness_vec(0, 0, 1));
}

/* A vertical ray exactly in the wall, (1, 0, -2) + t (0, 0, 1): Q is 0 for
 * every t, which counts as inside (the solid is closed), so it enters and
 * leaves through the rims, owned by the disks: base at t = 2, cap at t = 3.
 * One ulp further out: a miss. */
static void test_cylinder_in_wall(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cylinder, harness_ray(1, 0, -2, 0, 0, 1), h) == 2);
    harness_expect_hit("in wall base", &h[0], 2, BASE, 1, harness_vec(1, 0, 0), harness_vec(0, 0, -1));
    harness_expect_hit("in wall cap", &h[1], 3, CAP, 0, harness_vec(1, 0, 1), harness_vec(0, 0, 1));
    CHECK(harness_hits(&cylinder, harness_ray(nextafter(1, 2), 0, -2, 0, 0, 1), h) == 0);
}

/* (2, 0, 0) + t (-2, 0, 1): the wall x = +-1 at t = 0.5 (z = 0.5) and
 * t = 1.5 (z = 1.5, above the cap); the cap z = 1 at t = 1, x = 0. */
static void test_cylinder_wall_then_cap(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cylinder, harness_ray(2, 0, 0, -2, 0, 1), h) == 2);
    harness_expect_hit("wall in", &h[0], 0.5, WALL, 1, harness_vec(1, 0, 0.5), harness_vec(1, 0, 0));
    harness_expect_hit("cap out", &h[1], 1, CAP, 0, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
}

/* Exactly through the rim (1, 0, 1): (2, 0, 2) + t (-1, 0, -1) meets the
 * wall at t = 1 (and t = 3, z = -1) and the slab over [1, 2]. The tie at t = 1
 * goes to the disk: enter the cap at (1, 0, 1); leave the base at (0, 0, 0). */
static void test_cylinder_rim(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cylinder, harness_ray(2, 0, 2, -1, 0, -1), h) == 2);
    harness_expect_hit("rim cap", &h[0], 1, CAP, 1, harness_vec(1, 0, 1), harness_vec(0, 0, 1));
    harness_expect_hit("rim base", &h[1], 2, BASE, 0, harness_vec(0, 0, 0), harness_vec(0, 0, -1));
}

/* Tangent to the wall. Cylinder: (-2, 1, 0.5) + t (1, 0, 0) has
 * u x e = 0 * 0 - 1 * 1 = -1, so disc = |e|^2 - (u x e)^2 = 0 exactly: a
 * double root t = 2 at (0, 1, 0.5). Cone: (-2, 0.5, 0.5) + t (1, 0, 0) at
 * height 0.5 (radius 0.5): w0 = 0.5, omega = 0, disc = 0.25 - 0.5^2 = 0, the
 * touching point (0, 0.5, 0.5) with normal (0, 0.5, 0.5) ~ (0, 1, 1). A
 * tangent is reported as a zero-length visit: enter and leave at the same
 * t, both on the wall. */
static void test_wall_tangent(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cylinder, harness_ray(-2, 1, 0.5, 1, 0, 0), h) == 2);
    harness_expect_hit("tangent in", &h[0], 2, WALL, 1, harness_vec(0, 1, 0.5), harness_vec(0, 1, 0));
    harness_expect_hit("tangent out", &h[1], 2, WALL, 0, harness_vec(0, 1, 0.5),
                       harness_vec(0, 1, 0));
    CHECK(h[0].t == h[1].t);
    CHECK(harness_hits(&cone, harness_ray(-2, 0.5, 0.5, 1, 0, 0), h) == 2);
    harness_expect_hit("cone tangent in", &h[0], 2, WALL, 1, harness_vec(0, 0.5, 0.5),
                       harness_vec(0, 1, 1));
    CHECK(h[0].t == h[1].t && h[1].entering == 0);
    /* One ulp outside the tangent line: a miss or a tiny chord, never one hit. */
    const int n = harness_hits(&cylinder, harness_ray(-2, nextafter(1, 2), 0.5, 1, 0, 0), h);
    CHECK(n == 0 || n == 2);
}

/* Sweeps across a seam in steps of 1e-7. Each ray must enter exactly once and
 * leave exactly once (no hole, no double hit), the entering surface switching
 * from `below` (i < 0) to `above` (i > 0), and the entering point staying
 * within 1e-5 of the rim point `rim`. */
static void sweep_seam(const char *what, const harness_shape *shape, hr_vec3 origin,
                       hr_vec3 step, hr_vec3 dir, int below, int above, hr_vec3 rim)
{
    for (int i = -30; i <= 30; i++) {
        const double delta = i * 1e-7;
        const hr_ray ray = harness_ray(origin.x + delta * step.x, origin.y + delta * step.y,
                                       origin.z + delta * step.z, dir.x, dir.y, dir.z);
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(shape, ray, h);
        CHECK_MSG(n == 2, "%s: delta = %g: %d hits", what, delta, n);
        if (n != 2) continue;
        CHECK_MSG(h[0].entering == 1 && h[1].entering == 0, "%s: delta = %g: flags", what, delta);
        if (i < 0) CHECK_MSG(h[0].surface == below, "%s: delta = %g: surface %d", what, delta,
                             (int)h[0].surface);
        if (i > 0) CHECK_MSG(h[0].surface == above, "%s: delta = %g: surface %d", what, delta,
                             (int)h[0].surface);
        CHECK_MSG(fabs(h[0].point.x - rim.x) <= 1e-5 && fabs(h[0].point.y - rim.y) <= 1e-5 &&
                      fabs(h[0].point.z - rim.z) <= 1e-5,
                  "%s: delta = %g: entered at (%g, %g, %g)", what, delta, h[0].point.x,
                  h[0].point.y, h[0].point.z);
    }
}

/* The cap rim: (2, 0, 2 + delta) + t (-1, 0, -1) reaches z = 1 at
 * x = 1 - delta: inside the cap for delta > 0, else it has met the wall just
 * below the rim. The base rim: (2, 0, -1 + delta) + t (-1, 0, 1) reaches
 * x = 1 at z = delta: the wall for delta > 0, else the base at x = 1 + delta.
 * The cone's base rim needs a ray that closes in on the wall (x + z falls):
 * (3, 0, -1 + delta) + t (-2, 0, 1) is inside the cone for t >= 1 + delta
 * and above the base for t >= 1 - delta: the wall owns the entry for
 * delta > 0, the base for delta < 0. (Along (-1, 0, 1), parallel to a
 * generator, it would stay delta outside the cone: a miss, rightly.)
 * A horizontal ray at height 1 - delta enters the wall for delta >= 0 and
 * misses for delta < 0: swept separately, since there the count changes. */
static void test_seam_sweeps(void)
{
    sweep_seam("cylinder cap rim", &cylinder, harness_vec(2, 0, 2), harness_vec(0, 0, 1),
               harness_vec(-1, 0, -1), WALL, CAP, harness_vec(1, 0, 1));
    sweep_seam("cylinder base rim", &cylinder, harness_vec(2, 0, -1), harness_vec(0, 0, 1),
               harness_vec(-1, 0, 1), BASE, WALL, harness_vec(1, 0, 0));
    sweep_seam("cone base rim", &cone, harness_vec(3, 0, -1), harness_vec(0, 0, 1),
               harness_vec(-2, 0, 1), BASE, WALL, harness_vec(1, 0, 0));
    for (int i = -30; i <= 30; i++) {
        const double delta = i * 1e-7;
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&cylinder, harness_ray(2, 0, 1 - delta, -1, 0, 0), h);
        CHECK_MSG(n == (i >= 0 ? 2 : 0), "horizontal at 1 - %g: %d hits", delta, n);
        if (n == 2) CHECK(h[0].surface == WALL && h[1].surface == WALL);
    }
}

/* The tapered cap rim, s = 0.5: (1.5, 0, 2 + delta) + t (-1, 0, -1) reaches
 * z = 1 at x = 0.5 - delta (inside the cap of radius 0.5 for delta > 0). */
static void test_tapered_seam(void)
{
    harness_shape tapered;
    if (!harness_open(&tapered, "cylinder", "taperedCylinder", 0.5)) return;
    sweep_seam("tapered cap rim", &tapered, harness_vec(1.5, 0, 2), harness_vec(0, 0, 1),
               harness_vec(-1, 0, -1), WALL, CAP, harness_vec(0.5, 0, 1));
    harness_close(&tapered);
}

/* Cone along the axis: from above, (0, 0, 2) + t (0, 0, -1), Q(t) =
 * -(t - 1)^2 has a double root at the apex, but the ray goes in there (a < 0
 * picks the half-line where the radius grows): enter the wall at the apex
 * (0, 0, 1), t = 1 (normal +z, the gradient vanishes there), leave the base
 * at t = 2. From below: enter the base at t = 1, leave at the apex, t = 2. */
static void test_cone_axis(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cone, harness_ray(0, 0, 2, 0, 0, -1), h) == 2);
    harness_expect_hit("apex in", &h[0], 1, WALL, 1, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
    harness_expect_hit("base out", &h[1], 2, BASE, 0, harness_vec(0, 0, 0), harness_vec(0, 0, -1));
    CHECK(harness_hits(&cone, harness_ray(0, 0, -1, 0, 0, 1), h) == 2);
    harness_expect_hit("base in", &h[0], 1, BASE, 1, harness_vec(0, 0, 0), harness_vec(0, 0, -1));
    harness_expect_hit("apex out", &h[1], 2, WALL, 0, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
}

/* Through the apex at an angle. Steeper than the wall: (0.25, 0, 2) +
 * t (-0.25, 0, -1) passes (0, 0, 1) at t = 1 (a = 1/16 - 1 < 0) and leaves
 * the base at t = 2, (-0.25, 0, 0): one entry at the apex, no tangent pair.
 * Shallower than the wall: (-2, 0, 2) + t (1, 0, -0.5) touches only the apex
 * at t = 2 (disc = |w0 e - omega u|^2 - (u x e)^2 = 0 exactly, a = 0.75 > 0):
 * a zero-length visit, enter and leave at t = 2, both on the wall. */
static void test_cone_apex(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cone, harness_ray(0.25, 0, 2, -0.25, 0, -1), h) == 2);
    harness_expect_hit("steep apex", &h[0], 1, WALL, 1, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
    harness_expect_hit("steep base", &h[1], 2, BASE, 0, harness_vec(-0.25, 0, 0),
                       harness_vec(0, 0, -1));
    CHECK(harness_hits(&cone, harness_ray(-2, 0, 2, 1, 0, -0.5), h) == 2);
    harness_expect_hit("touch apex in", &h[0], 2, WALL, 1, harness_vec(0, 0, 1), harness_vec(0, 0, 1));
    harness_expect_hit("touch apex out", &h[1], 2, WALL, 0, harness_vec(0, 0, 1),
                       harness_vec(0, 0, 1));
    /* Rays fanned through the apex at many angles: never NaN (the harness
     * checks), always 0 or 2 hits, and an entry there when steep. */
    for (int i = 0; i <= 64; i++) {
        const double angle = i * (3.14159265358979 / 64); /* 0 .. pi from +z */
        const hr_vec3 d = harness_vec(sin(angle), 0.3 * sin(angle), -cos(angle));
        const hr_ray ray = harness_ray(-2 * d.x, -2 * d.y, 1 - 2 * d.z, d.x, d.y, d.z);
        const int n = harness_hits(&cone, ray, h);
        CHECK_MSG(n == 0 || n == 2, "apex fan %d: %d hits", i, n);
    }
}

/* The cone's side at height 0.5 (radius 0.5): (2, 0, 0.5) + t (-1, 0, 0)
 * enters at t = 1.5, (0.5, 0, 0.5), normal (0.5, 0, 0.5) ~ (1, 0, 1), and
 * leaves at t = 2.5. Parallel to a generator (a = 0): (0.5, 0, 0) +
 * t (-1, 0, 1) stays inside while |0.5 - t| <= 1 - t, i.e. t <= 0.75: from
 * the base (t = 0, counted over (-1, inf)) to the wall at (-0.25, 0, 0.75),
 * normal ~ (-1, 0, 1). Shifted out to (2, 0, 0), the same direction stays
 * outside (x - r = 1): no hit. */
static void test_cone_side_and_generator(void)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(&cone, harness_ray(2, 0, 0.5, -1, 0, 0), h) == 2);
    harness_expect_hit("cone in", &h[0], 1.5, WALL, 1, harness_vec(0.5, 0, 0.5), harness_vec(1, 0, 1));
    harness_expect_hit("cone out", &h[1], 2.5, WALL, 0, harness_vec(-0.5, 0, 0.5),
                       harness_vec(-1, 0, 1));
    CHECK(harness_trace(&cone, harness_ray(0.5, 0, 0, -1, 0, 1), -1, INFINITY, HARNESS_ALL, h) == 2);
    harness_expect_hit("generator base", &h[0], 0, BASE, 1, harness_vec(0.5, 0, 0),
                       harness_vec(0, 0, -1));
    harness_expect_hit("generator wall", &h[1], 0.75, WALL, 0, harness_vec(-0.25, 0, 0.75),
                       harness_vec(-1, 0, 1));
    CHECK(harness_hits(&cone, harness_ray(2, 0, 0, -1, 0, 1), h) == 0);
}

/* Tapered, s = 0.5: at z = 0.5 the radius is 0.75; (2, 0, 0.5) + t (-1, 0, 0)
 * enters at t = 1.25, normal (0.75, 0, 0.5 * 0.75) ~ (1, 0, 0.5).
 * s = 3 (widening upward, apex below the base at z = -0.5): the vertical ray
 * (1.5, 0, -1) + t (0, 0, 1) meets the wall where 1 + 2z = 1.5, z = 0.25,
 * t = 1.25, normal (1.5, 0, -2 * 1.5) ~ (1, 0, -2), and leaves the cap at
 * t = 2. s = 1e6: the radius at z = 0.5 is 500000.5, so (1e6, 0, 0.5) +
 * t (-1, 0, 0) enters at t = 499999.5 and leaves at t = 1500000.5. */
static void test_tapered(void)
{
    harness_shape t05, t3, big;
    hr_hit h[HARNESS_MAX_HITS];
    if (harness_open(&t05, "cylinder", "taperedCylinder", 0.5)) {
        CHECK(harness_hits(&t05, harness_ray(2, 0, 0.5, -1, 0, 0), h) == 2);
        harness_expect_hit("s=0.5 in", &h[0], 1.25, WALL, 1, harness_vec(0.75, 0, 0.5),
                           harness_vec(1, 0, 0.5));
        harness_close(&t05);
    }
    if (harness_open(&t3, "cylinder", "taperedCylinder", 3)) {
        CHECK(harness_hits(&t3, harness_ray(1.5, 0, -1, 0, 0, 1), h) == 2);
        harness_expect_hit("s=3 in", &h[0], 1.25, WALL, 1, harness_vec(1.5, 0, 0.25),
                           harness_vec(1, 0, -2));
        harness_expect_hit("s=3 out", &h[1], 2, CAP, 0, harness_vec(1.5, 0, 1), harness_vec(0, 0, 1));
        harness_close(&t3);
    }
    if (harness_open(&big, "cylinder", "taperedCylinder", 1e6)) {
        CHECK(harness_hits(&big, harness_ray(1e6, 0, 0.5, -1, 0, 0), h) == 2);
        CHECK_MSG(h[0].t == 499999.5 && h[1].t == 1500000.5, "s=1e6: %.17g %.17g", h[0].t, h[1].t);
        CHECK(h[0].surface == WALL && h[0].entering == 1);
        CHECK(harness_hits(&big, harness_ray(0, 0, 5, 0, 0, -1), h) == 2);
        CHECK(h[0].surface == CAP && h[1].surface == BASE);
        harness_close(&big);
    }
}

/* openTaperedCylinder: the same wall with no disks. Across it, the two
 * wall crossings of the closed cylinder; along the axis (where the closed
 * one is entered at the cap and left at the base) nothing; from inside
 * the tube, out through the wall once; a ray whose quadric crossings lie
 * above and below the slab, nothing. s = 0.5: the wall crossing at
 * z = 0.5, radius 0.75, as taperedCylinder's; s = 0, the open cone: along
 * the axis only the apex, one point of the wall. */
static void test_open(void)
{
    harness_shape open1, open05, open0;
    hr_hit h[HARNESS_MAX_HITS];
    if (harness_open(&open1, "cylinder", "openTaperedCylinder", 1.0)) {
        CHECK(harness_hits(&open1, harness_ray(5, 0, 0.5, -1, 0, 0), h) == 2);
        harness_expect_hit("open side in", &h[0], 4, WALL, 1, harness_vec(1, 0, 0.5),
                           harness_vec(1, 0, 0));
        harness_expect_hit("open side out", &h[1], 6, WALL, 0, harness_vec(-1, 0, 0.5),
                           harness_vec(-1, 0, 0));
        CHECK(harness_hits(&open1, harness_ray(0, 0, 5, 0, 0, -1), h) == 0);
        CHECK(harness_hits(&open1, harness_ray(0.3, 0.2, -3, 0, 0, 1), h) == 0);
        CHECK(harness_hits(&open1, harness_ray(0, 0, 0.5, 1, 0, 0), h) == 1);
        harness_expect_hit("open from inside", &h[0], 1, WALL, 0, harness_vec(1, 0, 0.5),
                           harness_vec(1, 0, 0));
        /* (0, 0, 2) toward (3, 0, -4): crosses x = 1 at z = 0, x = -1 never. */
        CHECK(harness_hits(&open1, harness_ray(0, 0, 2, 1, 0, -2), h) == 1);
        harness_expect_hit("open through the base ring", &h[0], 1, WALL, 0, harness_vec(1, 0, 0),
                           harness_vec(1, 0, 0));
        CHECK(harness_hits(&open1, harness_ray(0, 0, 3, 2, 0, -0.1), h) == 0);
        harness_close(&open1);
    }
    if (harness_open(&open05, "cylinder", "openTaperedCylinder", 0.5)) {
        CHECK(harness_hits(&open05, harness_ray(2, 0, 0.5, -1, 0, 0), h) == 2);
        harness_expect_hit("open s=0.5 in", &h[0], 1.25, WALL, 1, harness_vec(0.75, 0, 0.5),
                           harness_vec(1, 0, 0.5));
        CHECK(harness_hits(&open05, harness_ray(0, 0, 5, 0, 0, -1), h) == 0);
        harness_close(&open05);
    }
    if (harness_open(&open0, "cylinder", "openTaperedCylinder", 0.0)) {
        CHECK(harness_hits(&open0, harness_ray(2, 0, 0.5, -1, 0, 0), h) == 2);
        harness_expect_hit("open cone in", &h[0], 1.5, WALL, 1, harness_vec(0.5, 0, 0.5),
                           harness_vec(1, 0, 1));
        CHECK(harness_hits(&open0, harness_ray(0, 0, -5, 0, 0, 1), h) <= 1);
        harness_close(&open0);
    }
}

/* taperedTube s = 1, t = 0.25: the wall 0.75 <= rho <= 1 (surface 0 outside,
 * 3 inside, whose outward normal points at the axis), annuli at z = 0 and 1.
 * Across at z = 0.5: the outer wall at t = 4 and 6, the inner at 4.25 and
 * 5.75. Down the axis: through the hole, no hit. Vertically through the
 * wall at rho = 0.9: the base annulus at t = 2, the cap's at t = 3; at
 * rho = 0.7, in the hole: nothing. From inside the hole outward: the inner
 * wall entered at t = 0.75, the outer left at 1. s = 0.5, t = 0.25 (hole
 * radius 0.75 - 0.5 z): at z = 0.5 the outer radius is 0.75, the inner 0.5,
 * so (2, 0, 0.5) + t (-1, 0, 0) enters at 1.25 and reaches the hole at 1.5,
 * the inner normal (-0.5, 0, -0.5 * 0.5) reversed from the gradient. */
static void test_tube(void)
{
    harness_module module;
    if (!harness_load("cylinder", &module)) return;
    const hr_shape_class *cls = harness_find_class(&module, "taperedTube");
    CHECK(cls != NULL);
    if (!cls) {
        harness_unload(&module);
        return;
    }
    const char *names[] = {"s", "t"};
    const double straight[] = {1.0, 0.25}, narrowing[] = {0.5, 0.25};
    harness_shape tube = {module, cls, NULL}, cone_tube = {module, cls, NULL};
    char error[256];
    CHECK_OK(harness_create(cls, names, straight, 2, &tube.shape, error, sizeof error));
    CHECK_OK(harness_create(cls, names, narrowing, 2, &cone_tube.shape, error, sizeof error));
    hr_hit h[HARNESS_MAX_HITS];
    if (tube.shape) {
        CHECK(harness_hits(&tube, harness_ray(5, 0, 0.5, -1, 0, 0), h) == 4);
        harness_expect_hit("tube outer in", &h[0], 4, WALL, 1, harness_vec(1, 0, 0.5),
                           harness_vec(1, 0, 0));
        harness_expect_hit("tube inner out", &h[1], 4.25, TUBE_INNER, 0,
                           harness_vec(0.75, 0, 0.5), harness_vec(-1, 0, 0));
        harness_expect_hit("tube inner in", &h[2], 5.75, TUBE_INNER, 1,
                           harness_vec(-0.75, 0, 0.5), harness_vec(1, 0, 0));
        harness_expect_hit("tube outer out", &h[3], 6, WALL, 0, harness_vec(-1, 0, 0.5),
                           harness_vec(-1, 0, 0));
        CHECK(harness_hits(&tube, harness_ray(0, 0, 5, 0, 0, -1), h) == 0);
        CHECK(harness_hits(&tube, harness_ray(0.9, 0, -2, 0, 0, 1), h) == 2);
        harness_expect_hit("tube base annulus", &h[0], 2, BASE, 1, harness_vec(0.9, 0, 0),
                           harness_vec(0, 0, -1));
        harness_expect_hit("tube cap annulus", &h[1], 3, CAP, 0, harness_vec(0.9, 0, 1),
                           harness_vec(0, 0, 1));
        CHECK(harness_hits(&tube, harness_ray(0.7, 0, -2, 0, 0, 1), h) == 0);
        CHECK(harness_hits(&tube, harness_ray(0, 0, 0.5, 1, 0, 0), h) == 2);
        harness_expect_hit("tube from the hole", &h[0], 0.75, TUBE_INNER, 1,
                           harness_vec(0.75, 0, 0.5), harness_vec(-1, 0, 0));
        tube.cls->destroy(tube.shape);
    }
    if (cone_tube.shape) {
        CHECK(harness_hits(&cone_tube, harness_ray(2, 0, 0.5, -1, 0, 0), h) == 4);
        harness_expect_hit("narrowing tube in", &h[0], 1.25, WALL, 1, harness_vec(0.75, 0, 0.5),
                           harness_vec(1, 0, 0.5));
        harness_expect_hit("narrowing tube hole", &h[1], 1.5, TUBE_INNER, 0,
                           harness_vec(0.5, 0, 0.5), harness_vec(-1, 0, -0.5));
        cone_tube.cls->destroy(cone_tube.shape);
    }
    /* t must leave a hole (t < 1) of radius s - t >= 0 at the cap, and be
     * a wall (t > 0); each refusal names t. */
    const double bad[][2] = {{1.0, 0.0}, {2.0, 1.0}, {0.5, 0.75}, {1.0, NAN}, {NAN, 0.1}};
    for (int i = 0; i < 5; i++) {
        void *shape = NULL;
        CHECK(harness_create(cls, names, bad[i], 2, &shape, error, sizeof error) ==
              HR_ERROR_PARAMETER);
        CHECK_MSG(strstr(error, isnan(bad[i][0]) ? "'s'" : "'t'") != NULL, "message: %s", error);
        CHECK(shape == NULL);
    }
    harness_unload(&module);
}

/* create with s = 0, 1 and 1e6 (the ends of the range and the cylinder),
 * with the bounds that follow; s outside the range is the host's to refuse,
 * but the module refuses it too, naming the parameter. The cylinder and
 * cone classes take no parameters. */
static void test_create(void)
{
    harness_module module;
    if (!harness_load("cylinder", &module)) return;
    const hr_shape_class *tapered = harness_find_class(&module, "taperedCylinder");
    CHECK(tapered != NULL);
    if (!tapered) {
        harness_unload(&module);
        return;
    }
    const double good[] = {0.0, 1.0, 1e6, 0.25, 7.5};
    for (int i = 0; i < 5; i++) {
        const char *names[] = {"s"};
        void *shape = NULL;
        char error[256];
        CHECK_OK(harness_create(tapered, names, &good[i], 1, &shape, error, sizeof error));
        CHECK(shape != NULL);
        if (!shape) continue;
        hr_bounds b;
        tapered->bounds(shape, &b);
        const double r = good[i] > 1 ? good[i] : 1;
        CHECK(b.lo.x == -r && b.lo.y == -r && b.lo.z == 0 && b.hi.x == r && b.hi.y == r &&
              b.hi.z == 1);
        tapered->destroy(shape);
    }
    const double bad[] = {-1.0, 2e6, NAN, INFINITY};
    for (int i = 0; i < 4; i++) {
        const char *names[] = {"s"};
        void *shape = NULL;
        char error[256];
        CHECK(harness_create(tapered, names, &bad[i], 1, &shape, error, sizeof error) ==
              HR_ERROR_PARAMETER);
        CHECK_MSG(strstr(error, "'s'") != NULL, "message: %s", error);
        CHECK(shape == NULL);
    }
    harness_unload(&module);
}

int main(void)
{
    const int ok = harness_open(&cylinder, "cylinder", "cylinder", NAN) &&
                   harness_open(&cone, "cylinder", "cone", NAN);
    if (!ok) return hr_test_end() | 1;
    test_cylinder_side();
    test_cylinder_axis();
    test_cylinder_in_wall();
    test_cylinder_wall_then_cap();
    test_cylinder_rim();
    test_wall_tangent();
    test_seam_sweeps();
    test_tapered_seam();
    test_cone_axis();
    test_cone_apex();
    test_cone_side_and_generator();
    test_tapered();
    test_open();
    test_tube();
    test_create();
    harness_close(&cone);
    harness_close(&cylinder);
    return hr_test_end();
}
