/* The torus module (ring radius 1 about z, tube radius `tube`), with every
 * root solver it offers. The default solver must pass every case; the
 * others must pass the cases marked ALL_SOLVERS (the easy ones, and the
 * module contract the harness checks on every call: finite, sorted, inside
 * (tmin, tmax), entering alternating), and their accuracy on the hard ones
 * is printed, not required (that is what they trade for speed; the numbers
 * are the module's parameter help).
 *
 * Cases: the four crossings of the equatorial line, the axis through the
 * hole, unusable rays, tangents on the inner and outer equators and on top
 * (exact for tube 0.25, to within an ulp for 0.2, and moved off by 1e-12 and
 * 1e-9), thin tubes (1e-3), random near, far (1e4, 1e6) and grazing rays
 * for tubes 0.2, 1e-3 and 0.9 (and 1e-6 for the default), rays re-shot from
 * hit points, and the parameters' checks and messages.
 * References: hand-worked values, and roots of the quartic computed in quad
 * precision with Sturm sequences (quad_reference.c, quad_poly.c). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/scene.h>

#include "hr_test.h"
#include "module_harness.h"
#include "quad_reference.h"
#include "random_rays.h"

#define UNIT_ROUNDOFF (DBL_EPSILON / 2)
/* As test_shape_accuracy.c: the computed root is the exact root of inputs
 * perturbed by a few u, which moves it by u * condition (quad_reference.h);
 * 8 allows for the handful of roundings in the frame shift, the compensated
 * G and the final t = shift + u. */
#define T_TOLERANCE_FACTOR 8.0
/* Rays within this distance of a tangency are compared only for parity: there
 * rounding may rightly report a touch or a miss. */
#define SAFE_MARGIN 1e-6

static const char *const solvers[] = {"ferrari", "ferrari-newton", "bracketing", ""};
#define SOLVER_COUNT 4
#define DEFAULT_SOLVER 3 /* "" is the default, which is "bracketing" */

static hr_status create_torus(const hr_shape_class *cls, double tube, const char *solver,
                              void **out, char *error, size_t error_size)
{
    hr_param params[2];
    memset(params, 0, sizeof params);
    params[0].name = "tube", params[0].type = HR_PARAM_NUMBER, params[0].number = tube;
    params[0].string = "", params[0].object = -1;
    params[1].name = "solver", params[1].type = HR_PARAM_STRING, params[1].string = solver;
    params[1].object = -1;
    const void *objects[2] = {NULL, NULL};
    hr_create_args args;
    memset(&args, 0, sizeof args);
    args.struct_size = sizeof args;
    args.param_count = 2;
    args.params = params;
    args.objects = objects;
    args.host = harness_host();
    args.error = error;
    args.error_size = error_size;
    args.base_dir = "";
    if (error_size) error[0] = '\0';
    *out = NULL;
    return cls->create(&args, out);
}

static int open_torus(harness_shape *out, double tube, const char *solver)
{
    memset(out, 0, sizeof *out);
    if (!harness_load("torus", &out->module)) return 0;
    out->cls = harness_find_class(&out->module, "torus");
    CHECK_MSG(out->cls != NULL, "the torus module has no class 'torus'");
    if (!out->cls) return 0;
    char error[256];
    const hr_status st = create_torus(out->cls, tube, solver, &out->shape, error, sizeof error);
    CHECK_MSG(st == HR_OK && out->shape, "create torus tube %g solver '%s': %d %s", tube, solver,
              (int)st, error);
    return st == HR_OK && out->shape != NULL;
}

/* --- Hand-worked cases, every solver -------------------------------------------- */

/* o = (-10, 0, 0), d = (1, 0, 0), tube 0.2: the line runs through the ring's
 * centre along a diameter and crosses the tube four times, at x = -1.2,
 * -0.8, 0.8, 1.2: t = 8.8 (in), 9.2 (out), 10.8 (in), 11.2 (out), normals
 * -x, +x, -x, +x. Over t > 10 only the far part of the ring is hit. */
static void test_equatorial_line(const harness_shape *s)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(s, harness_ray(-10, 0, 0, 1, 0, 0), h) == 4);
    harness_expect_hit("eq 1", &h[0], 8.8, 0, 1, harness_vec(-1.2, 0, 0), harness_vec(-1, 0, 0));
    harness_expect_hit("eq 2", &h[1], 9.2, 0, 0, harness_vec(-0.8, 0, 0), harness_vec(1, 0, 0));
    harness_expect_hit("eq 3", &h[2], 10.8, 0, 1, harness_vec(0.8, 0, 0), harness_vec(-1, 0, 0));
    harness_expect_hit("eq 4", &h[3], 11.2, 0, 0, harness_vec(1.2, 0, 0), harness_vec(1, 0, 0));
    CHECK(harness_trace(s, harness_ray(-10, 0, 0, 1, 0, 0), 10, INFINITY, HARNESS_ALL, h) == 2);
    harness_expect_hit("far part", &h[0], 10.8, 0, 1, harness_vec(0.8, 0, 0), harness_vec(-1, 0, 0));
    /* The same line from the centre, direction scaled by 4: t = 0.2, 0.3. */
    CHECK(harness_hits(s, harness_ray(0, 0, 0, 4, 0, 0), h) == 2);
    harness_expect_hit("centre in", &h[0], 0.2, 0, 1, harness_vec(0.8, 0, 0), harness_vec(-1, 0, 0));
    harness_expect_hit("centre out", &h[1], 0.3, 0, 0, harness_vec(1.2, 0, 0), harness_vec(1, 0, 0));
    /* From inside the tube at (1, 0, 0) going +y: the tube's centre circle
     * curves away, so the ray leaves at y = sqrt(1.2^2 - 1) = sqrt(0.44). */
    CHECK(harness_hits(s, harness_ray(1, 0, 0, 0, 1, 0), h) == 1);
    harness_expect_hit("inside out", &h[0], sqrt(0.44), 0, 0, harness_vec(1, sqrt(0.44), 0),
                       harness_vec(1, sqrt(0.44), 0));
    /* First and any hit agree with the list. */
    CHECK(harness_trace(s, harness_ray(-10, 0, 0, 1, 0, 0), 9, 11, HARNESS_FIRST, h) == 1);
    harness_expect_hit("first after 9", &h[0], 9.2, 0, 0, harness_vec(-0.8, 0, 0),
                       harness_vec(1, 0, 0));
    CHECK(harness_trace(s, harness_ray(-10, 0, 0, 1, 0, 0), 9.3, 10.7, HARNESS_ANY, h) == 0);
}

/* Along the axis, through the hole: the line stays at distance 1 from the
 * ring, far outside the tube: no hit from near or far, whatever the
 * direction's length. Parallel to the axis inside the hole: none either. */
static void test_axis(const harness_shape *s)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(s, harness_ray(0, 0, -10, 0, 0, 1), h) == 0);
    CHECK(harness_trace(s, harness_ray(0, 0, 1e4, 0, 0, -3), -INFINITY, INFINITY, HARNESS_ALL,
                        h) == 0);
    CHECK(harness_trace(s, harness_ray(0, 0, 0, 0, 0, 1e-9), -INFINITY, INFINITY, HARNESS_ALL,
                        h) == 0);
    CHECK(harness_hits(s, harness_ray(0.5, 0.1, -10, 0, 0, 1), h) == 0);
    /* Parallel to the axis through the tube: (1, 0, -10) + t (0, 0, 1)
     * crosses it at z = -0.2, 0.2. */
    CHECK(harness_hits(s, harness_ray(1, 0, -10, 0, 0, 1), h) == 2);
    harness_expect_hit("vertical in", &h[0], 9.8, 0, 1, harness_vec(1, 0, -0.2), harness_vec(0, 0, -1));
    harness_expect_hit("vertical out", &h[1], 10.2, 0, 0, harness_vec(1, 0, 0.2), harness_vec(0, 0, 1));
}

/* Unusable rays: no hit, no NaN (the harness checks every field). */
static void test_degenerate_rays(const harness_shape *s)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_trace(s, harness_ray(-10, 0, 0, 0, 0, 0), -INFINITY, INFINITY, HARNESS_ALL, h) == 0);
    CHECK(harness_trace(s, harness_ray(-1e300, 0, 0, 1e-300, 0, 0), -INFINITY, INFINITY,
                        HARNESS_ALL, h) <= 4);
    CHECK(harness_trace(s, harness_ray(-1e308, 0, 0, 1, 0, 0), -INFINITY, INFINITY, HARNESS_ALL,
                        h) <= 4);
    CHECK(harness_trace(s, harness_ray(-10, 0, 0, 5e-324, 0, 0), 0, INFINITY, HARNESS_ALL, h) <= 4);
    CHECK(harness_trace(s, harness_ray(-10, 0, 0, 1e308, 1e308, 0), 0, INFINITY, HARNESS_ALL, h) <= 4);
    CHECK(harness_trace(s, harness_ray(NAN, 0, 0, 1, 0, 0), 0, INFINITY, HARNESS_ALL, h) == 0);
    CHECK(harness_trace(s, harness_ray(0, 0, 0, INFINITY, 0, 0), 0, INFINITY, HARNESS_ALL, h) == 0);
}

/* --- Tangents ------------------------------------------------------------------ */

typedef struct tangent_case {
    const char *what;
    hr_ray ray;
    int count;            /* hits of the default solver */
    double t[4];          /* their times */
    int entering[4];
} tangent_case;

/* Tube 0.25, a binary fraction, so the rays below are exactly tangent:
 * - outer equator, y = 1.25: touches (0, 1.25, 0) at t = 10 from outside;
 * - inner equator, y = 0.75: inside the tube for 0 < |x| <= 1, touching
 *   (0, 0.75, 0) from inside at t = 10: in at 9, out and in at 10, out at 11;
 * - on top, z = 0.25 through the axis: touches (-1, 0, 0.25) and
 *   (1, 0, 0.25), t = 9 and 11;
 * - on top along the ring, x = 1, z = 0.25, direction y: touches (1, 0, 0.25)
 *   at t = 10.
 * The default solver recognises each touch as a double root (|f| within its
 * rounding bound at a critical point) and reports two hits at its t. */
static const tangent_case exact_tangents[] = {
    {"outer equator", {{-10, 1.25, 0}, {1, 0, 0}}, 2, {10, 10}, {1, 0}},
    {"inner equator", {{-10, 0.75, 0}, {1, 0, 0}}, 4, {9, 10, 10, 11}, {1, 0, 1, 0}},
    {"top, across", {{-10, 0, 0.25}, {1, 0, 0}}, 4, {9, 9, 11, 11}, {1, 0, 1, 0}},
    {"top, along the ring", {{1, -10, 0.25}, {0, 1, 0}}, 2, {10, 10}, {1, 0}},
};

static void test_exact_tangents(const harness_shape *s, int is_default)
{
    for (size_t i = 0; i < sizeof exact_tangents / sizeof exact_tangents[0]; i++) {
        const tangent_case *c = &exact_tangents[i];
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(s, c->ray, h);
        if (is_default) {
            CHECK_MSG(n == c->count, "%s: %d hits, expected %d", c->what, n, c->count);
            for (int k = 0; k < n && k < c->count; k++) {
                CHECK_MSG(hr_test_ulps(h[k].t, c->t[k]) <= 4 && h[k].entering == c->entering[k],
                          "%s: hit %d at t = %.17g entering %d, expected %g %d", c->what, k,
                          h[k].t, (int)h[k].entering, c->t[k], c->entering[k]);
            }
        } else {
            /* A cheaper solver may drop a touch (a pair) or find a pair of
             * roots at it (along the ring f = y^4: a fourfold root), never
             * half of one. */
            CHECK_MSG(n % 2 == 0 && n <= 4, "%s: %d hits", c->what, n);
        }
    }
}

/* The same rays for tube 0.2 (0.2, 0.8 and 1.2 are not binary, so these
 * rays are tangent only to within an ulp: a miss by 1e-17, a touch, or a
 * chord of ~1e-8), and the rays moved by 1e-12 and 1e-9 either way. Moved
 * toward the solid at the touching point (into the tube for the outer
 * equator and the top, into the hole for the inner equator, where the touch
 * is from inside), the line crosses twice more there: a chord of 2e-6 or
 * more, which every ray must show; moved the other way it misses (or, for
 * the inner equator, stays inside). Every solver gives an even number of
 * extra hits; the default gives exactly the right one, the touch included. */
static void test_near_tangents(const harness_shape *s, int is_default)
{
    static const struct {
        const char *what;
        double oy, oz;     /* origin (-10, oy, oz), direction +x */
        double solid_y, solid_z; /* toward the solid at the touching point */
        int touches;       /* touching points (top: two) */
        int base;          /* crossings away from the touches */
    } cases[] = {
        {"outer equator", 1.2, 0, -1, 0, 1, 0},
        {"inner equator", 0.8, 0, -1, 0, 1, 2},
        {"top", 0, 0.2, 0, -1, 2, 0},
    };
    const double offsets[] = {0, 1e-12, -1e-12, 1e-9, -1e-9};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; k++) {
            const double off = offsets[k]; /* > 0: toward the solid */
            const hr_ray ray = harness_ray(-10, cases[i].oy + off * cases[i].solid_y,
                                           cases[i].oz + off * cases[i].solid_z, 1, 0, 0);
            hr_hit h[HARNESS_MAX_HITS];
            const int n = harness_hits(s, ray, h);
            const int extra = n - cases[i].base;
            CHECK_MSG(extra >= 0 && extra % 2 == 0 && extra <= 2 * cases[i].touches,
                      "%s offset %g: %d hits", cases[i].what, off, n);
            if (!is_default) continue;
            const int expected = cases[i].base + (off >= 0 ? 2 * cases[i].touches : 0);
            /* Unmoved, the inner equator's line is 5e-17 inside the tube,
             * within rounding of the touch: either answer is right. */
            const int either = off == 0 && cases[i].base == 2;
            CHECK_MSG(n == expected || (either && n == cases[i].base),
                      "%s offset %g: %d hits, expected %d", cases[i].what, off, n, expected);
        }
    }
}

/* --- Against the quad reference -------------------------------------------------- */

typedef struct stats {
    int compared, skipped, wrong_count, wrong_flags, wrong_t, wrong_point;
    double worst_ratio, worst_relative;
} stats;

/* Compares one ray over all t; `strict` turns disagreements into failures. */
static void compare_ray(const harness_shape *s, ref_shape ref, hr_ray ray, stats *st, int strict,
                        const char *what)
{
    ref_trace expect;
    ref_trace_ray(ref, ray, &expect);
    hr_hit h[HARNESS_MAX_HITS];
    const int n = harness_trace(s, ray, -INFINITY, INFINITY, HARNESS_ALL, h);
    if (!(expect.margin > SAFE_MARGIN)) {
        st->skipped++;
        CHECK_MSG(n % 2 == 0, "%s: %d hits on a near-tangent ray", what, n);
        return;
    }
    st->compared++;
#define RAY_FMT "%s tube %g ray (%.17g, %.17g, %.17g) + t (%.17g, %.17g, %.17g): "
#define RAY_ARGS what, ref.s, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z
    if (n != expect.count) {
        st->wrong_count++;
        if (strict) CHECK_MSG(0, RAY_FMT "%d hits, reference %d", RAY_ARGS, n, expect.count);
        return;
    }
    for (int i = 0; i < n; i++) {
        const ref_hit *r = &expect.hits[i];
        if (h[i].entering != r->entering) {
            st->wrong_flags++;
            if (strict) CHECK_MSG(0, RAY_FMT "hit %d entering %d", RAY_ARGS, i, (int)h[i].entering);
        }
        const double scale = UNIT_ROUNDOFF * ref_to_double(r->condition);
        const double err = fabs(ref_to_double((quad)h[i].t - r->t));
        const double ratio = err / scale;
        const double relative = err / fmax(fabs(h[i].t), 1e-300);
        if (ratio > st->worst_ratio) st->worst_ratio = ratio;
        if (relative > st->worst_relative) st->worst_relative = relative;
        if (!(ratio <= T_TOLERANCE_FACTOR)) {
            st->wrong_t++;
            if (strict)
                CHECK_MSG(0, RAY_FMT "hit %d: t = %.17g, reference %.17g (%.3g u * condition)",
                          RAY_ARGS, i, h[i].t, ref_to_double(r->t), ratio);
        }
        const double distance = ref_surface_distance(ref, 0, h[i].point);
        if (!(distance <= sqrt(3.0) * h[i].error)) {
            st->wrong_point++;
            CHECK_MSG(0, RAY_FMT "hit %d: point %.3g from the surface, bound %.3g", RAY_ARGS, i,
                      distance, h[i].error);
        }
    }
#undef RAY_FMT
#undef RAY_ARGS
}

#define RAY_SETS 4
static const char *const set_names[RAY_SETS] = {"near", "far 1e4", "grazing", "far 1e6"};

static void test_random_rays(double tube, int solver, uint64_t seed)
{
    harness_shape s;
    if (!open_torus(&s, tube, solvers[solver])) {
        harness_close(&s);
        return;
    }
    const ref_shape ref = ref_shape_of("torus", tube, NAN);
    hr_bounds b;
    s.cls->bounds(s.shape, &b);
    ray_rng rng;
    rng_seed(&rng, seed);
    const int strict = solver == DEFAULT_SOLVER;
    for (int set = 0; set < RAY_SETS; set++) {
        stats st;
        memset(&st, 0, sizeof st);
        const int rays = set == 0 ? 4000 : 1500;
        for (int i = 0; i < rays; i++) {
            const hr_ray ray = set == 0   ? random_ray_near(&rng, &b)
                               : set == 1 ? random_ray_far(&rng, &b, 1e4)
                               : set == 2 ? random_ray_grazing_torus(&rng, tube)
                                          : random_ray_far(&rng, &b, 1e6);
            compare_ray(&s, ref, ray, &st, strict, set_names[set]);
        }
        printf("tube %-6g %-15s %-8s: %5d compared %4d skipped; wrong: %d counts, %d flags, "
               "%d t; worst t %.3g u*cond (%.3g relative)\n",
               tube, solvers[solver][0] ? solvers[solver] : "(default)", set_names[set],
               st.compared, st.skipped, st.wrong_count, st.wrong_flags, st.wrong_t,
               st.worst_ratio, st.worst_relative);
        /* The skipped rays must stay few, or the test says little (grazing
         * rays are near-tangent by design: most of them are skipped). */
        if (set != 2) CHECK_MSG(st.skipped < rays / 10, "%d of %d rays skipped", st.skipped, rays);
    }
    harness_close(&s);
}

/* --- Spawned rays ----------------------------------------------------------------- */

/* Spawned rays leave by the host's own rule, hr_hit_spawn_origin (the hit's
 * error bound projected on the side, rounded away from the surface): it
 * works on any hit record, here one in the torus's object space. */
/* pbrt's test of error bounds: rays re-shot from hit points, outward
 * (reflection) and inward (refraction), in random directions on that side,
 * a quarter of them within 1e-3 of the tangent plane, must never hit the
 * surface they start from. A hit closer than 1e-9 (a true second crossing
 * that near needs a direction within ~1e-9 of the surface) counts as a
 * self-hit. */
static void test_no_self_hits(double tube, uint64_t seed)
{
    harness_shape s;
    if (!open_torus(&s, tube, "")) {
        harness_close(&s);
        return;
    }
    hr_bounds b;
    s.cls->bounds(s.shape, &b);
    ray_rng rng;
    rng_seed(&rng, seed);
    int spawned = 0, self_hits = 0;
    for (int i = 0; i < 4000; i++) {
        /* Half the rays near the bounds, half aimed at a random point of the
         * surface from outside it (a thin tube is rarely hit otherwise). */
        hr_ray ray = random_ray_near(&rng, &b);
        if (i % 2) {
            const double phi = rng_uniform(&rng, 0, 6.283185307179586);
            const double theta = rng_uniform(&rng, 0, 6.283185307179586);
            const hr_vec3 n = {cos(theta) * cos(phi), cos(theta) * sin(phi), sin(theta)};
            const hr_vec3 p = {(1 + tube * cos(theta)) * cos(phi),
                               (1 + tube * cos(theta)) * sin(phi), tube * sin(theta)};
            hr_vec3 w = rng_unit_vector(&rng);
            const double wn = w.x * n.x + w.y * n.y + w.z * n.z;
            if (wn < 0) w.x -= 2 * wn * n.x, w.y -= 2 * wn * n.y, w.z -= 2 * wn * n.z;
            ray = harness_ray(p.x + 3 * w.x, p.y + 3 * w.y, p.z + 3 * w.z, -w.x, -w.y, -w.z);
        }
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&s, ray, h);
        for (int k = 0; k < n; k++) {
            const hr_vec3 nrm = h[k].normal;
            for (int side = -1; side <= 1; side += 2) {
                const hr_vec3 out = harness_vec(side * nrm.x, side * nrm.y, side * nrm.z);
                hr_vec3 v = rng_unit_vector(&rng);
                double along = v.x * out.x + v.y * out.y + v.z * out.z;
                if (along < 0) v.x -= 2 * along * out.x, v.y -= 2 * along * out.y,
                               v.z -= 2 * along * out.z, along = -along;
                if (rng_chance(&rng, 0.25)) { /* graze: keep 1e-3 of the normal part */
                    const double keep = 1e-3 - 1;
                    v.x += keep * along * out.x, v.y += keep * along * out.y,
                        v.z += keep * along * out.z;
                }
                const hr_ray spawn = {hr_hit_spawn_origin(&h[k], out), v};
                hr_hit again[HARNESS_MAX_HITS];
                const int m = harness_trace(&s, spawn, 0.0, INFINITY, HARNESS_FIRST, again);
                const double length = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
                spawned++;
                if (m && again[0].t * length < 1e-9) {
                    self_hits++;
                    CHECK_MSG(0, "tube %g: a ray spawned %s from (%.17g, %.17g, %.17g) hits "
                                 "itself at t = %.3g",
                              tube, side > 0 ? "outward" : "inward", h[k].point.x, h[k].point.y,
                              h[k].point.z, again[0].t);
                }
            }
        }
    }
    printf("tube %-6g spawned rays: %d, self-hits %d\n", tube, spawned, self_hits);
    CHECK(spawned > 4000);
    harness_close(&s);
}

/* --- Parameters ------------------------------------------------------------------ */

static void test_parameters(void)
{
    harness_module m;
    if (!harness_load("torus", &m)) return;
    const hr_shape_class *cls = harness_find_class(&m, "torus");
    CHECK(cls && cls->param_count == 2);
    if (!cls || cls->param_count != 2) {
        harness_unload(&m);
        return;
    }
    CHECK(strcmp(cls->params[0].name, "tube") == 0 && cls->params[0].type == HR_PARAM_NUMBER);
    CHECK(cls->params[0].default_number == 0.2 && cls->params[0].required == 0);
    CHECK(cls->params[0].min == 1e-6 && cls->params[0].max == 0.999);
    CHECK(strcmp(cls->params[1].name, "solver") == 0 && cls->params[1].type == HR_PARAM_STRING);
    for (int i = 0; i < 3; i++)
        CHECK_MSG(strstr(cls->params[1].help, solvers[i]) != NULL, "solver help lacks %s", solvers[i]);
    char error[256];
    void *shape;
    const double bad_tubes[] = {0, -0.1, 1, 2.5, 1e-7, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad_tubes / sizeof bad_tubes[0]; i++) {
        CHECK(create_torus(cls, bad_tubes[i], "", &shape, error, sizeof error) == HR_ERROR_PARAMETER);
        CHECK_MSG(strstr(error, "'tube'") && strstr(error, "0.999"), "message: %s", error);
        CHECK(shape == NULL);
    }
    CHECK(create_torus(cls, 0.2, "newton", &shape, error, sizeof error) == HR_ERROR_PARAMETER);
    CHECK_MSG(strstr(error, "'solver'") && strstr(error, "'newton'") && strstr(error, "ferrari-newton") &&
                  strstr(error, "bracketing"),
              "message: %s", error);
    CHECK(shape == NULL);
    /* The extremes of the range are accepted; bounds follow the tube. */
    const double good[] = {1e-6, 0.999};
    for (int i = 0; i < 2; i++) {
        CHECK(create_torus(cls, good[i], "ferrari", &shape, error, sizeof error) == HR_OK);
        if (!shape) continue;
        hr_bounds bounds;
        cls->bounds(shape, &bounds);
        CHECK(bounds.hi.x == 1 + good[i] && bounds.lo.y == -1 - good[i] && bounds.hi.z == good[i]);
        cls->destroy(shape);
    }
    harness_unload(&m);
}

/* Thin tube, 1e-3, default solver: the equatorial line's roots
 * 10 -+ 1 -+ 0.001, and a ray along the ring's tangent on the outer
 * equator (a touch, as above: 0 or 2 hits, 2 for the default). */
static void test_thin_tube(const harness_shape *s, int is_default)
{
    hr_hit h[HARNESS_MAX_HITS];
    CHECK(harness_hits(s, harness_ray(-10, 0, 0, 1, 0, 0), h) == 4);
    const double t[4] = {10 - 1.001, 10 - 0.999, 10 + 0.999, 10 + 1.001};
    for (int i = 0; i < 4; i++)
        CHECK_MSG(fabs(h[i].t - t[i]) <= 1e-14 && h[i].entering == (i % 2 == 0),
                  "thin hit %d: t = %.17g, expected %.17g", i, h[i].t, t[i]);
    /* Through the tube's centre circle, vertically: z = -+0.001. */
    CHECK(harness_hits(s, harness_ray(1, 0, -1, 0, 0, 1), h) == 2);
    CHECK(fabs(h[0].t - 0.999) <= 1e-15 && fabs(h[1].t - 1.001) <= 1e-15);
    const int n = harness_hits(s, harness_ray(-10, 1.001, 0, 1, 0, 0), h);
    CHECK_MSG(n == 2 || (!is_default && n == 0), "thin outer equator: %d hits", n);
}

int main(void)
{
    test_parameters();
    for (int solver = 0; solver < SOLVER_COUNT; solver++) {
        const int is_default = solver == DEFAULT_SOLVER;
        harness_shape s;
        if (open_torus(&s, 0.2, solvers[solver])) {
            test_equatorial_line(&s);
            test_axis(&s);
            test_degenerate_rays(&s);
            test_near_tangents(&s, is_default);
        }
        harness_close(&s);
        if (open_torus(&s, 0.25, solvers[solver])) test_exact_tangents(&s, is_default);
        harness_close(&s);
        if (open_torus(&s, 1e-3, solvers[solver])) test_thin_tube(&s, is_default);
        harness_close(&s);
        test_random_rays(0.2, solver, UINT64_C(0x70705) + (uint64_t)solver);
        test_random_rays(1e-3, solver, UINT64_C(0x7070e) + (uint64_t)solver);
        test_random_rays(0.9, solver, UINT64_C(0x70717) + (uint64_t)solver);
    }
    /* The thinnest tube the module accepts, with the default solver. */
    test_random_rays(1e-6, DEFAULT_SOLVER, UINT64_C(0x70720));
    test_no_self_hits(0.2, UINT64_C(0x5e1f));
    test_no_self_hits(1e-3, UINT64_C(0x5e20));
    test_no_self_hits(0.9, UINT64_C(0x5e21));
    return hr_test_end();
}
