/* The torus's hard cases (T01-T11 of CATALOG.md), with the default solver,
 * in object space through the test host, against the Sturm-sequence roots
 * of the quartic in quad precision (quad_reference.c, quad_poly.c): the
 * equatorial line, the axis through the hole, exact and near tangents on
 * the inner and outer equators and on top, thin tubes (1e-3, 1e-6), a far
 * torus (1e4) and grazing rays. Scoring: numerics_family.h. */
#include <math.h>
#include <stdio.h>

#include "hr_test.h"
#include "module_harness.h"
#include "numerics_cases.h"
#include "numerics_family.h"
#include "quad_reference.h"
#include "random_rays.h"

/* Fixed rays, each a family of one (i picks the ray). */
typedef struct fixed_ray {
    hr_ray ray;
    double distance; /* from the nearest tangency; NaN: the reference margin */
} fixed_ray;

static const fixed_ray *fixed_rays;
static double fixed_band;

static void fixed_probe(ray_rng *rng, int i, nf_probe *out)
{
    (void)rng;
    out->ray = fixed_rays[i].ray;
    out->distance = fixed_rays[i].distance;
    out->band = fixed_band;
}

static void run_fixed(const fixed_ray *rays, int count, double tube, double band, nc_result *out)
{
    fixed_rays = rays;
    fixed_band = band;
    nf_run_family("torus", "torus", tube, fixed_probe, count, 0, out);
}

/* T01: the equatorial line o = (-10, 0, 0) + t (1, 0, 0) crosses the tube
 * four times (x = -1.2, -0.8, 0.8, 1.2); also from the centre with the
 * direction scaled by 4 and 1/3, and tilted by 1e-3. */
static void t01(nc_result *out)
{
    static const fixed_ray rays[] = {
        {{{-10, 0, 0}, {1, 0, 0}}, NAN},   {{{0, 0, 0}, {4, 0, 0}}, NAN},
        {{{0, 0, 0}, {-1.0 / 3, 0, 0}}, NAN}, {{{-10, 0, 0.01}, {1, 0, -1e-3}}, NAN},
        {{{0, -1e4, 0}, {0, 1, 0}}, NAN},
    };
    run_fixed(rays, 5, NAN, 0, out);
}

/* T02: along the axis, through the hole: the line stays 1 from the ring,
 * no hit whatever the direction's length or the origin's distance. */
static void t02(nc_result *out)
{
    static const fixed_ray rays[] = {
        {{{0, 0, -10}, {0, 0, 1}}, NAN},     {{{0, 0, 1e4}, {0, 0, -3}}, NAN},
        {{{0, 0, 1e6}, {0, 0, -1e-3}}, NAN}, {{{0, 0, 0}, {0, 0, 1}}, NAN},
        {{{0.5, 0.5, -10}, {0, 0, 1}}, NAN},
    };
    run_fixed(rays, 5, NAN, 0, out);
}

/* T03: exact tangents, tube 0.25 (0.75, 1.25 and 0.25 are binary): the
 * outer equator y = 1.25 (touch at t = 10), the inner equator y = 0.75 (a
 * touch from inside the hole at t = 10, between crossings at t = 9 and
 * 11), the top z = 0.25 across the axis (touches at t = 9 and 11) and along
 * the ring (t = 10), and the outer equator from 1e4. The quad reference
 * cannot be used here: it resolves a double root only to a pair of nearby
 * roots or none (the line lies exactly in the tangent plane), so the
 * answers are worked by hand, each touch a pair of hits at one t (entering
 * then leaving), every t within 4 ulps (the hand values are exact; the
 * solver's t carries a few roundings), scored as ulps / 4. */
static void t03(nc_result *out)
{
    static const struct {
        hr_ray ray;
        int count;
        double t[4];
    } rays[] = {
        {{{-10, 1.25, 0}, {1, 0, 0}}, 2, {10, 10}},
        {{{-10, 0.75, 0}, {1, 0, 0}}, 4, {9, 10, 10, 11}},
        {{{-10, 0, 0.25}, {1, 0, 0}}, 4, {9, 9, 11, 11}},
        {{{1, -10, 0.25}, {0, 1, 0}}, 2, {10, 10}},
        {{{-1e4, 1.25, 0}, {1, 0, 0}}, 2, {1e4, 1e4}},
    };
    harness_shape s;
    if (!harness_open(&s, "torus", "torus", 0.25)) {
        harness_close(&s);
        return;
    }
    for (size_t k = 0; k < sizeof rays / sizeof rays[0]; k++) {
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&s, rays[k].ray, h);
        CHECK_MSG(n == rays[k].count, "tangent %zu: %d hits, expected %d", k, n, rays[k].count);
        if (n != rays[k].count) {
            nc_note(out, INFINITY);
            continue;
        }
        for (int i = 0; i < n; i++) nc_note(out, hr_test_ulps(h[i].t, rays[k].t[i]) / 4);
    }
    harness_close(&s);
}

/* T04: near tangents, tube 0.2, moved by +-1e-12 and +-1e-9 off the outer
 * equator, the inner equator and the top. The band: at a touching point
 * f ~ 8 r delta, and f is evaluated to within about 8 u (1 + r)^4 (its
 * terms are at most 4 (1 + r)^4 there, summed with compensation), so the
 * sign of f at the critical point is right for delta > u (1 + r)^4 / r,
 * 1.1e-15 for r = 0.2; we allow 8 times that. */
static void t04(nc_result *out)
{
    static const struct {
        double oy, oz, sy, sz; /* origin (-10, oy, oz) + offset (sy, sz), direction +x */
    } at[] = {{1.2, 0, 1, 0}, {0.8, 0, 1, 0}, {0, 0.2, 0, 1}};
    static const double offsets[] = {1e-12, -1e-12, 1e-9, -1e-9};
    fixed_ray rays[12];
    int n = 0;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 4; k++) {
            rays[n].ray = harness_ray(-10, at[i].oy + offsets[k] * at[i].sy,
                                      at[i].oz + offsets[k] * at[i].sz, 1, 0, 0);
            rays[n].distance = offsets[k];
            n++;
        }
    const double r = 0.2, band = 8 * NC_U * pow(1 + r, 4) / r;
    run_fixed(rays, n, r, band, out);
}

/* Rays through a random point inside the tube of radius `tube`, from
 * `distance` away (random direction), direction length 2^-3 .. 2^3. */
static double probe_tube, probe_distance;

static void tube_probe(ray_rng *rng, int i, nf_probe *out)
{
    (void)i;
    const double phi = rng_uniform(rng, 0, 6.283185307179586);
    const double theta = rng_uniform(rng, 0, 6.283185307179586);
    const double rho = probe_tube * sqrt(rng_uniform(rng, 0, 1));
    const hr_vec3 c = {(1 + rho * cos(theta)) * cos(phi), (1 + rho * cos(theta)) * sin(phi),
                       rho * sin(theta)};
    const hr_vec3 away = rng_unit_vector(rng);
    const double length = exp2(rng_uniform(rng, -3, 3));
    const hr_vec3 o = {c.x + probe_distance * away.x, c.y + probe_distance * away.y,
                       c.z + probe_distance * away.z};
    out->ray = harness_ray(o.x, o.y, o.z, -away.x * length, -away.y * length, -away.z * length);
}

static void run_tube(double tube, double distance, int rays, uint64_t seed, nc_result *out)
{
    probe_tube = tube;
    probe_distance = distance;
    nf_run_family("torus", "torus", tube, tube_probe, rays, seed, out);
}

static void t05(nc_result *out) { run_tube(1e-3, 3, 3000, 0x7005, out); }
static void t06(nc_result *out) { run_tube(1e-6, 3, 3000, 0x7006, out); }
static void t07(nc_result *out) { run_tube(0.2, 1e4, 3000, 0x7007, out); }
static void t10(nc_result *out) { run_tube(0.2, 1e6, 2000, 0x7010, out); }

/* T08, T09: grazing rays (random_ray_grazing_torus: along a tangent,
 * moved off the surface by 1e-4 .. 1e-12), tube 0.2 and the thin 1e-3. */
static void grazing_probe(ray_rng *rng, int i, nf_probe *out)
{
    (void)i;
    out->ray = random_ray_grazing_torus(rng, probe_tube);
}

static void t08(nc_result *out)
{
    probe_tube = 0.2;
    nf_run_family("torus", "torus", 0.2, grazing_probe, 3000, 0x7008, out);
}

static void t09(nc_result *out)
{
    probe_tube = 1e-3;
    nf_run_family("torus", "torus", 1e-3, grazing_probe, 3000, 0x7009, out);
}

/* T11: grazing so close that the chord is 1e-7 long or less: through a
 * random surface point along a random tangent, moved off the surface along
 * the normal by +-10^-(13 .. 16) (at and below the rounding of f), the
 * origin within 1 of the touching point (as a ray spawned there would be).
 * The pair of roots is then a near-double root next to a critical point of
 * f where f' is ~0 too: a Newton step from a value within rounding jumps
 * anywhere. */
static void close_graze_probe(ray_rng *rng, int i, nf_probe *out)
{
    (void)i;
    const double r = probe_tube;
    const double phi = rng_uniform(rng, 0, 6.283185307179586);
    const double theta = rng_uniform(rng, 0, 6.283185307179586);
    const hr_vec3 n = {cos(theta) * cos(phi), cos(theta) * sin(phi), sin(theta)};
    const hr_vec3 p = {(1 + r * cos(theta)) * cos(phi), (1 + r * cos(theta)) * sin(phi),
                       r * sin(theta)};
    hr_vec3 v = rng_unit_vector(rng);
    const double vn = v.x * n.x + v.y * n.y + v.z * n.z;
    v = harness_vec(v.x - vn * n.x, v.y - vn * n.y, v.z - vn * n.z);
    const double off = (rng_chance(rng, 0.5) ? 1 : -1) * pow(10, -rng_uniform(rng, 13, 16));
    const double back = rng_uniform(rng, -1, 1);
    out->ray = harness_ray(p.x + off * n.x - back * v.x, p.y + off * n.y - back * v.y,
                           p.z + off * n.z - back * v.z, v.x, v.y, v.z);
    out->band = 8 * NC_U * pow(1 + r, 4) / r; /* T04's: where f's sign at the touch is noise */
}

static void t11(nc_result *out)
{
    probe_tube = 0.2;
    nf_run_family("torus", "torus", 0.2, close_graze_probe, 3000, 0x7011, out);
}

#define BY_CONDITION "|t - t_ref| <= 8 u cond; count exact outside the rounding band"

static const nc_case cases[] = {
    {"T01", "torus", "equatorial line, 4 crossings", "4 real roots, 2 close pairs", BY_CONDITION,
     t01},
    {"T02", "torus", "axis through the hole, near and from 1e6", "no real root, f > 0 by 1",
     "no hit", t02},
    {"T03", "torus", "exact tangents, tube 0.25: equators, top", "double roots of a quartic",
     "hand-worked touch pairs, t within 4 ulps", t03},
    {"T04", "torus", "near tangents +-1e-12, +-1e-9, tube 0.2", "a root pair 2e-6 apart or none",
     "count exact for |delta| > 8u(1+r)^4/r", t04},
    {"T05", "torus", "thin tube 1e-3, rays through it", "quartic with tiny r^2 terms",
     BY_CONDITION, t05},
    {"T06", "torus", "thin tube 1e-6, rays through it", "roots 1e-6 apart", BY_CONDITION, t06},
    {"T07", "torus", "far torus: rays from 1e4 through the tube", "coefficients ~1e16",
     BY_CONDITION, t07},
    {"T08", "torus", "grazing 1e-4 .. 1e-12 off the surface, tube 0.2", "near-double roots",
     BY_CONDITION, t08},
    {"T09", "torus", "grazing the thin tube 1e-3", "near-double roots of a thin tube",
     BY_CONDITION, t09},
    {"T10", "torus", "far torus: rays from 1e6 through the tube", "coefficients ~1e24",
     BY_CONDITION, t10},
    {"T11", "torus", "grazing 1e-13 .. 1e-16 off, the touch within 1 of the origin",
     "near-double root at a critical point", BY_CONDITION, t11},
};

int main(void)
{
    return nc_run_table("torus", cases, (int)(sizeof cases / sizeof cases[0]));
}
