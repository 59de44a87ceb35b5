/* Hard cases of the quadrics in object space (cases Q01-Q15 of CATALOG.md):
 * the sphere far away and grazed, exact tangents, signed zeros, the
 * cylinder nearly parallel to its axis, the cone along its generators and
 * through its apex. The modules are loaded by the test host
 * (module_harness.c, which checks the module contract on every call) and
 * families of rays are compared with the quad-precision references of
 * quad_reference.c by numerics_family.c (which says how a ray is scored). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"
#include "module_harness.h"
#include "numerics_cases.h"
#include "numerics_family.h"
#include "quad_reference.h"
#include "random_rays.h"

/* From `distance` away in a random direction, aimed within 0.5 of the
 * centre, the direction's length random over 2^-3 .. 2^3. */
static void far_probe(ray_rng *rng, double distance, hr_vec3 centre, nf_probe *out)
{
    const hr_vec3 away = rng_unit_vector(rng);
    const hr_vec3 aim = rng_unit_vector(rng);
    const double r = rng_uniform(rng, 0, 0.5), length = exp2(rng_uniform(rng, -3, 3));
    const hr_vec3 o = {centre.x + distance * away.x, centre.y + distance * away.y,
                       centre.z + distance * away.z};
    const hr_vec3 to = {centre.x + r * aim.x, centre.y + r * aim.y, centre.z + r * aim.z};
    out->ray = harness_ray(o.x, o.y, o.z, (to.x - o.x) * length / distance,
                           (to.y - o.y) * length / distance, (to.z - o.z) * length / distance);
}

/* The distance (and centre) the families below are run at: set by the
 * case before nf_run_family, which takes a plain function. */
static double family_distance;
static hr_vec3 family_centre;
static double family_taper; /* the tapered families' s */

static void far_family(ray_rng *rng, int i, nf_probe *out)
{
    (void)i;
    far_probe(rng, family_distance, family_centre, out);
}

static void run_far(const char *module, const char *cls, double s, double distance,
                    hr_vec3 centre, int rays, uint64_t seed, nc_result *out)
{
    family_distance = distance;
    family_centre = centre;
    nf_run_family(module, cls, s, far_family, rays, seed, out);
}

/* The textbook root pair from b^2 - a c in double, for the printed
 * comparison of the far cases (what the stable form buys). */
static double naive_worst(double distance, uint64_t seed)
{
    ray_rng rng;
    rng_seed(&rng, seed);
    double worst = 0;
    for (int i = 0; i < 2000; i++) {
        nf_probe p;
        far_probe(&rng, distance, harness_vec(0, 0, 0), &p);
        const hr_vec3 o = p.ray.origin, d = p.ray.dir;
        const double a = d.x * d.x + d.y * d.y + d.z * d.z, b = o.x * d.x + o.y * d.y + o.z * d.z;
        const double c = o.x * o.x + o.y * o.y + o.z * o.z - 1, disc = b * b - a * c;
        ref_trace expect;
        ref_trace_ray(ref_shape_of("sphere", NAN, NAN), p.ray, &expect);
        if (expect.count != 2 || !(disc >= 0)) continue;
        const double t = (-b - sqrt(disc)) / a;
        const double err = ref_to_double(nf_qabs((quad)t - expect.hits[0].t));
        const double ratio = err / (NF_T_FACTOR * NC_U * ref_to_double(expect.hits[0].condition));
        if (ratio > worst) worst = ratio;
    }
    return worst;
}

static void run_far_sphere(double distance, uint64_t seed, nc_result *out)
{
    run_far("sphere", "sphere", NAN, distance, harness_vec(0, 0, 0), 4000, seed, out);
    snprintf(out->note, sizeof out->note, "textbook b^2 - ac: worst %.3g of the tolerance",
             naive_worst(distance, seed));
}

static void q01(nc_result *out) { run_far_sphere(1e4, 0x9a01, out); }
static void q02(nc_result *out) { run_far_sphere(1e6, 0x9a02, out); }

/* Grazing band: from `distance` away, the line passes the centre at
 * impact parameter 1 + delta, delta = +-m 10^-k (k = 6 .. 17), in a random
 * orientation. The distance from the tangency is delta measured on the
 * double ray in quad; the band 8u: the discriminant |d|^2 (1 - h^2) is
 * computed to within about 7u |d|^2 (test_shape_accuracy.c's budget), so
 * its sign is right when |1 - h^2| = 2 |delta| exceeds that. */
/* +-m 10^-k, m in [1, 10), k = 6 .. 17: from 1e-5 down to below u. */
static double grazing_delta(ray_rng *rng)
{
    return (rng_chance(rng, 0.5) ? 1 : -1) * rng_uniform(rng, 1, 10) *
           pow(10, -(double)(6 + (int)rng_uniform(rng, 0, 12)));
}

static void grazing_probe(ray_rng *rng, double distance, nf_probe *out)
{
    const hr_vec3 d = rng_unit_vector(rng);
    hr_vec3 w = rng_unit_vector(rng);
    const double wd = w.x * d.x + w.y * d.y + w.z * d.z;
    w = harness_vec(w.x - wd * d.x, w.y - wd * d.y, w.z - wd * d.z);
    const double wl = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
    const double h = (1 + grazing_delta(rng)) / wl, length = exp2(rng_uniform(rng, -3, 3));
    out->ray = harness_ray(h * w.x - distance * d.x, h * w.y - distance * d.y,
                           h * w.z - distance * d.z, d.x * length, d.y * length, d.z * length);
    const quad o[3] = {out->ray.origin.x, out->ray.origin.y, out->ray.origin.z};
    const quad v[3] = {out->ray.dir.x, out->ray.dir.y, out->ray.dir.z};
    const quad cx = o[1] * v[2] - o[2] * v[1], cy = o[2] * v[0] - o[0] * v[2],
               cz = o[0] * v[1] - o[1] * v[0];
    const quad h2 = (cx * cx + cy * cy + cz * cz) / (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    out->distance = (double)((h2 - 1) / 2);
    out->band = 8 * NC_U;
}

static void grazing_family(ray_rng *rng, int i, nf_probe *out)
{
    (void)i;
    grazing_probe(rng, family_distance, out);
}

/* The cylinder's wall grazed: lines at distance 1 + delta from the axis
 * (delta as in Q03) in a plane of constant z in (0.1, 0.9), from `distance`
 * away. The wall's discriminant |w0 e - omega u|^2 - (u x e)^2 is |e|^2
 * (1 - h^2) here (omega = 0, w0 = 1), computed to within about 7u |e|^2
 * as the sphere's, so the band is again 8u in delta. */
static void wall_grazing_probe(ray_rng *rng, double distance, nf_probe *out)
{
    const double phi = rng_uniform(rng, 0, 6.283185307179586);
    const double dx = cos(phi), dy = sin(phi);
    const double h = 1 + grazing_delta(rng), z = rng_uniform(rng, 0.1, 0.9);
    const double length = exp2(rng_uniform(rng, -3, 3));
    out->ray = harness_ray(-h * dy - distance * dx, h * dx - distance * dy, z, dx * length,
                           dy * length, 0);
    const quad ox = out->ray.origin.x, oy = out->ray.origin.y;
    const quad ex = out->ray.dir.x, ey = out->ray.dir.y;
    const quad cross = ox * ey - oy * ex;
    out->distance = (double)((cross * cross / (ex * ex + ey * ey) - 1) / 2);
    out->band = 8 * NC_U;
}

static void wall_grazing_family(ray_rng *rng, int i, nf_probe *out)
{
    (void)i;
    wall_grazing_probe(rng, family_distance, out);
}

static void run_grazing(const char *module, const char *cls, nf_probe_fn make, double distance,
                        int rays, uint64_t seed, nc_result *out)
{
    family_distance = distance;
    nf_run_family(module, cls, NAN, make, rays, seed, out);
}

/* The tapered wall grazed (the cone's and taperedCylinder 0.5's): lines
 * through a random point of the wall (heights 0.05 .. 0.95) along a random
 * tangent, moved off the wall along its normal by +-10^-(6 .. 17), from
 * `family_distance` away. Hit or miss by the reference's margin and the
 * rounding band (compare_ray); t by condition. */
static void tapered_grazing_family(ray_rng *rng, int i, nf_probe *out)
{
    (void)i;
    const double s = family_taper, k = s - 1;
    const double phi = rng_uniform(rng, 0, 6.283185307179586), z = rng_uniform(rng, 0.05, 0.95);
    const double w = 1 + k * z;
    const hr_vec3 p = {w * cos(phi), w * sin(phi), z};
    hr_vec3 n = {cos(phi), sin(phi), -k};
    const double nl = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n = harness_vec(n.x / nl, n.y / nl, n.z / nl);
    hr_vec3 v = rng_unit_vector(rng);
    const double vn = v.x * n.x + v.y * n.y + v.z * n.z;
    v = harness_vec(v.x - vn * n.x, v.y - vn * n.y, v.z - vn * n.z);
    const double vl = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    const double off = grazing_delta(rng), back = family_distance / vl;
    out->ray = harness_ray(p.x + off * n.x - back * v.x, p.y + off * n.y - back * v.y,
                           p.z + off * n.z - back * v.z, v.x, v.y, v.z);
    out->band = 8 * NC_U; /* as Q03: the Lagrange discriminant is within ~7u |e|^2 */
}

static void q15(nc_result *out)
{
    family_taper = 0;
    run_grazing("cylinder", "cone", tapered_grazing_family, 10, 3000, 0x9a17, out);
    run_grazing("cylinder", "cone", tapered_grazing_family, 1e4, 3000, 0x9a18, out);
    family_taper = 0.5;
    family_distance = 1e4;
    nf_run_family("cylinder", "taperedCylinder", 0.5, tapered_grazing_family, 3000, 0x9a19, out);
}

static void q13(nc_result *out)
{
    run_grazing("sphere", "sphere", grazing_family, 1e6, 6000, 0x9a14, out);
}

static void q14(nc_result *out)
{
    run_grazing("cylinder", "cylinder", wall_grazing_family, 10, 4000, 0x9a15, out);
    run_grazing("cylinder", "cylinder", wall_grazing_family, 1e4, 4000, 0x9a16, out);
}

static void q03(nc_result *out)
{
    run_grazing("sphere", "sphere", grazing_family, 10, 6000, 0x9a03, out);
}

static void q04(nc_result *out)
{
    run_grazing("sphere", "sphere", grazing_family, 1e4, 6000, 0x9a04, out);
}

/* Exact tangents: rays whose discriminant is exactly 0 in real arithmetic
 * and whose inputs are all exact in double, from near and far, with
 * direction lengths that are and are not powers of two. Each must give a
 * double root (two hits, entering then leaving, at the same t) within 4 ulps
 * of the exact t, or a miss: never NaN, never one hit. */
typedef struct tangent {
    const char *cls;
    hr_ray ray;
    double t;
} tangent;

static const tangent tangents[] = {
    {"sphere", {{-5, 1, 0}, {1, 0, 0}}, 5},
    {"sphere", {{0, -1, -1e4}, {0, 0, 3}}, 1e4 / 3},
    {"sphere", {{1e6, 0, 1}, {-0.5, 0, 0}}, 2e6},
    {"sphere", {{0, 1, 0}, {1, 0, 0}}, 0}, /* at the origin of the ray */
    {"sphere", {{3, -1e4, 0.6}, {0, 2.5, 0}}, 4000},
    {"cylinder", {{-2, 1, 0.5}, {1, 0, 0}}, 2},
    {"cylinder", {{1, 0, 0.25}, {0, 3, 0}}, 0},
    {"cylinder", {{-1e4, -1, 0.75}, {7, 0, 0}}, 1e4 / 7},
    {"cone", {{-2, 0.5, 0.5}, {1, 0, 0}}, 2},
    {"cone", {{0.25, -1e4, 0.75}, {0, 3, 0}}, 1e4 / 3},
};

static void q05(nc_result *out)
{
    for (size_t k = 0; k < sizeof tangents / sizeof tangents[0]; k++) {
        const tangent *c = &tangents[k];
        harness_shape s;
        if (!harness_open(&s, strcmp(c->cls, "sphere") == 0 ? "sphere" : "cylinder", c->cls,
                          NAN)) {
            harness_close(&s);
            continue;
        }
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_trace(&s, c->ray, -INFINITY, INFINITY, HARNESS_ALL, h);
        if (n == 2 && h[0].entering && !h[1].entering && h[0].t == h[1].t)
            nc_note(out, hr_test_ulps(h[0].t, c->t) / 4);
        else if (n == 0)
            nc_note(out, 0);
        else
            nc_note(out, INFINITY);
        CHECK_MSG(n == 0 || n == 2, "tangent %zu (%s): %d hits", k, c->cls, n);
        harness_close(&s);
    }
}

/* Signed zeros: a ray and its copies with every zero component of origin
 * and direction flipped to -0 must give bit-identical hits. */
static void q06(nc_result *out)
{
    static const struct {
        const char *module, *cls;
        hr_ray ray;
    } rays[] = {
        {"sphere", "sphere", {{0, 0, 5}, {0, 0, -1}}},
        {"sphere", "sphere", {{0.5, 0, 5}, {0, 0, -2}}},
        {"cylinder", "cylinder", {{0, 0, -3}, {0, 0, 1}}},
        {"cylinder", "cylinder", {{0.5, 0, 3}, {0, 0, -1}}},
        {"cylinder", "cylinder", {{5, 0, 0.5}, {-1, 0, 0}}},
        {"cylinder", "cone", {{0, 0, 2}, {0, 0, -1}}},
        {"cylinder", "cone", {{0, 0.25, -1}, {0, 0, 1}}},
    };
    for (size_t k = 0; k < sizeof rays / sizeof rays[0]; k++) {
        harness_shape s;
        if (!harness_open(&s, rays[k].module, rays[k].cls, NAN)) {
            harness_close(&s);
            continue;
        }
        nf_signed_zeros(&s, rays[k].ray, out);
        harness_close(&s);
    }
}

/* Nearly parallel to the cylinder's axis: d = (1e-7 cos phi, 1e-7 sin phi,
 * +-1), origins below, above and inside; the wall, if reached, is crossed
 * at an angle of 1e-7, and a = |e|^2 = 1e-14 makes the textbook roots
 * lose half their digits. Compared with the reference (band: the rounding
 * of t, see compare_ray). */
static void axis_1e7(ray_rng *rng, int i, nf_probe *out)
{
    const double phi = rng_uniform(rng, 0, 6.283185307179586);
    const double rho = i % 4 == 0 ? 1 - rng_uniform(rng, 0, 1e-6) : rng_uniform(rng, 0, 1.2);
    const double psi = rng_uniform(rng, 0, 6.283185307179586);
    const double z = rng_uniform(rng, -2, 3), up = rng_chance(rng, 0.5) ? 1 : -1;
    out->ray = harness_ray(rho * cos(psi), rho * sin(psi), z, 1e-7 * cos(phi), 1e-7 * sin(phi), up);
}

static void q07(nc_result *out)
{
    nf_run_family("cylinder", "cylinder", NAN, axis_1e7, 6000, 0x9a07, out);
}

/* Exactly parallel to the axis, d = (+-0, +-0, +-1): the wall is never
 * crossed (a = b = 0: decided without dividing), so the hits are the base
 * and the cap, t = fl(fl(h - o.z) / d.z), exact here, when rho <= 1 -- on
 * the wall itself (rho = 1 exactly) too, as the solid is closed. */
static void q08(nc_result *out)
{
    static const double xy[][2] = {{0, 0}, {1, 0}, {0, -1}, {-0.0, 1}, {0.5, -0.5}, {1, 1e-300},
                                   {nextafter(1, 2), 0}, {2, 0}};
    harness_shape s;
    if (!harness_open(&s, "cylinder", "cylinder", NAN)) {
        harness_close(&s);
        return;
    }
    for (size_t k = 0; k < sizeof xy / sizeof xy[0]; k++)
        for (int sign = 0; sign < 8; sign++) {
            const double dz = sign & 1 ? -1 : 1, oz = dz > 0 ? -2 : 3;
            const hr_ray r = harness_ray(xy[k][0], xy[k][1], oz, sign & 2 ? -0.0 : 0.0,
                                         sign & 4 ? -0.0 : 0.0, dz);
            hr_hit h[HARNESS_MAX_HITS];
            const int n = harness_hits(&s, r, h);
            const double rho2 = xy[k][0] * xy[k][0] + xy[k][1] * xy[k][1];
            const int inside = rho2 <= 1;
            int ok = n == (inside ? 2 : 0);
            if (ok && n == 2)
                ok = h[0].t == 2 && h[1].t == 3 && h[0].entering && !h[1].entering &&
                     h[0].surface == (dz > 0 ? 1 : 2) && h[1].surface == (dz > 0 ? 2 : 1);
            nc_note(out, ok ? 0 : INFINITY);
            CHECK_MSG(ok, "axis-parallel (%g, %g) dz %g: %d hits", xy[k][0], xy[k][1], dz, n);
        }
    harness_close(&s);
}

/* Along the cone's generators: d = L (-cos phi, -sin phi, 1) for phi a
 * multiple of 90 degrees (so that a = |e|^2 - omega^2 is exactly 0: the
 * quadratic degenerates to a line), L = 2^k, from random origins; and
 * nearly along them, d.z = 1 + j 1e-9. */
static void generator(ray_rng *rng, int i, nf_probe *out)
{
    static const double c[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    const double *e = c[i % 4];
    const double length = exp2((double)((int)rng_uniform(rng, -3, 4)));
    const double dz = i % 8 < 4 ? 1 : 1 + (double)((int)rng_uniform(rng, -5, 6)) * 1e-9;
    out->ray = harness_ray(rng_uniform(rng, -1.5, 1.5), rng_uniform(rng, -1.5, 1.5),
                           rng_uniform(rng, -1, 0.5), -e[0] * length, -e[1] * length, dz * length);
}

static void q09(nc_result *out)
{
    nf_run_family("cylinder", "cone", NAN, generator, 6000, 0x9a09, out);
}

/* Through the apex (0, 0, 1): o = apex - 3 d (rounded), d random. The apex
 * is a double root of the wall's quadratic: its computed discriminant is
 * off by up to gamma(8) S^2 (S = |w0 e| + |omega u| + |u x e|, the terms of
 * the Lagrange form), which moves a double root by sqrt(gamma(8)) S / |a|;
 * the origin's rounding puts the line up to 4u off the apex. Steep rays
 * (a < 0, inside the cone's nappe) must enter (or leave) at the apex within
 * that bound and cross the base: exactly 2 hits. Shallow ones touch the
 * apex, miss it, or cut a chord as short as the line's offset from it:
 * 0 hits, or 2 within the bound of t = 3. Never NaN. */
static void q10(nc_result *out)
{
    harness_shape s;
    if (!harness_open(&s, "cylinder", "cone", NAN)) {
        harness_close(&s);
        return;
    }
    ray_rng rng;
    rng_seed(&rng, 0x9a10);
    for (int i = 0; i < 4000; i++) {
        const hr_vec3 d = rng_unit_vector(&rng);
        const hr_ray r = harness_ray(-3 * d.x, -3 * d.y, 1 - 3 * d.z, d.x, d.y, d.z);
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&s, r, h);
        const double a = d.x * d.x + d.y * d.y - d.z * d.z;
        const double w0 = 1 - r.origin.z, omega = -d.z;
        const double S = fabs(w0) * sqrt(d.x * d.x + d.y * d.y) +
                         fabs(omega) * sqrt(r.origin.x * r.origin.x + r.origin.y * r.origin.y) +
                         fabs(r.origin.x * d.y - r.origin.y * d.x);
        const double bound = sqrt(nc_gamma(8)) * S / fabs(a) + 4 * NC_U * 4;
        if (fabs(a) < 1e-3) { /* within 1e-3 of a generator: either answer */
            CHECK_MSG(n % 2 == 0, "apex ray %d: %d hits", i, n);
            nc_note(out, n % 2 ? INFINITY : 0);
            continue;
        }
        if (a < 0) {
            const int ok = n == 2 && h[0].entering && !h[1].entering;
            /* the apex hit: the one at t near 3 */
            const double t_apex = fabs(h[0].t - 3) < fabs(h[n > 1].t - 3) ? h[0].t : h[n > 1].t;
            nc_note(out, ok ? fabs(t_apex - 3) / bound : INFINITY);
            CHECK_MSG(ok, "steep apex ray %d (%g %g %g): %d hits", i, d.x, d.y, d.z, n);
        } else {
            /* The rounded line passes up to 4u off the apex, below it or
             * above: a touch, a miss or a chord that short, near t = 3. */
            const int ok = n == 0 || (n == 2 && h[0].entering && !h[1].entering);
            nc_note(out, ok ? (n ? fmax(fabs(h[0].t - 3), fabs(h[1].t - 3)) / bound : 0)
                            : INFINITY);
            CHECK_MSG(ok, "shallow apex ray %d (%g %g %g): %d hits", i, d.x, d.y, d.z, n);
        }
    }
    harness_close(&s);
}

static void q11(nc_result *out)
{
    run_far("cylinder", "cylinder", NAN, 1e6, harness_vec(0, 0, 0.5), 4000, 0x9a11, out);
}

static void q12(nc_result *out)
{
    run_far("cylinder", "taperedCylinder", 0.5, 1e4, harness_vec(0, 0, 0.5), 2000, 0x9a12, out);
    run_far("cylinder", "cone", NAN, 1e4, harness_vec(0, 0, 0.5), 2000, 0x9a13, out);
}

#define BY_CONDITION "|t - t_ref| <= 8 u cond; count exact outside the rounding band"

static const nc_case cases[] = {
    {"Q01", "sphere", "unit sphere from 1e4, aimed within 0.5", "b^2 - ac cancels 8 digits",
     BY_CONDITION, q01},
    {"Q02", "sphere", "unit sphere from 1e6, aimed within 0.5", "b^2 - ac cancels 12 digits",
     BY_CONDITION, q02},
    {"Q03", "sphere", "grazing band r(1 +- 1e-6..1e-17) from 10", "disc ~ delta, tangency",
     "hit/miss right outside |delta| <= 8u; t by condition", q03},
    {"Q04", "sphere", "grazing band from 1e4", "far and grazing at once",
     "hit/miss right outside |delta| <= 8u; t by condition", q04},
    {"Q05", "sphere/cyl/cone", "exact tangents, exact inputs", "disc exactly 0: double root",
     "2 hits at one t within 4 ulps, or 0; never NaN or 1", q05},
    {"Q06", "sphere/cyl/cone", "signed zeros in origin and direction", "-0 picks other branches",
     "bit-identical hits", q06},
    {"Q07", "cylinder", "nearly parallel to the axis, |dx, dy| = 1e-7", "a = 1e-14",
     BY_CONDITION, q07},
    {"Q08", "cylinder", "exactly parallel to the axis, +-0 components, on the wall",
     "a = b = 0: no quadratic", "base and cap at exact t; rho <= 1 inside", q08},
    {"Q09", "cone", "along and nearly along generators", "a = 0: the equation is linear",
     BY_CONDITION, q09},
    {"Q10", "cone", "through the apex, random directions", "double root at a point of the wall",
     "2 hits (steep) or a touch/miss; apex t within sqrt(gamma8) S/|a|", q10},
    {"Q11", "cylinder", "from 1e6, aimed within 0.5 of the middle", "Lagrange form vs b^2 - ac",
     BY_CONDITION, q11},
    {"Q12", "taperedCylinder", "s = 0.5 and the cone from 1e4", "tapered Lagrange form",
     BY_CONDITION, q12},
    {"Q13", "sphere", "grazing band from 1e6", "12 digits cancel in o x d",
     "hit/miss right outside |delta| <= 8u; t by condition", q13},
    {"Q14", "cylinder", "wall grazed at 1 +- 1e-6..1e-17 from 10 and 1e4", "wall tangency",
     "hit/miss right outside |delta| <= 8u; t by condition", q14},
    {"Q15", "cone", "cone and tapered walls grazed, 1e-6..1e-17 off", "slanted wall tangency",
     BY_CONDITION, q15},
};

int main(void)
{
    return nc_run_table("quadrics", cases, (int)(sizeof cases / sizeof cases[0]));
}
