/* Accuracy against references in quad precision (quad_reference.c).
 *
 * 1. Random rays near every class, and far rays (origins 1e4 and 1e6 away,
 *    aimed at the shape), traced over all t. Rays that pass within 1e-6 of a
 *    seam, edge, tangency or grazing angle are left out here (there rounding
 *    may rightly decide either way; the hand-made tests pin down what
 *    happens) -- the test checks that such rays are rare. For the rest:
 *    - the same number of hits, surfaces and entering flags as the reference;
 *    - t within the tolerance below;
 *    - the point within its stated error of the surface: Euclidean distance
 *      <= sqrt(3) * error (the error bounds each coordinate), and for flat
 *      surfaces, whose points are not re-projected, each coordinate within
 *      error of the exact intersection point origin + t_ref dir.
 * 2. Far spheres, 1e4 and 1e6 away, rays aimed within 0.5 of the centre:
 *    both roots within 10 ulps (derived at test_far_sphere).
 * 3. Rays from inside each closed solid get one, exiting, hit (as many as
 *    the reference has after t = 0 for the torus, which is not convex).
 *
 * Tolerance on t. A flat face's t = fl(fl(h - o) / d) has two roundings,
 * so |t - t_ref| <= 2u |t| (u = 2^-53, the unit roundoff). A quadric root
 * is computed from coefficients summed with compensation and a
 * discriminant from products good to 1.5 ulp, so the computed root is the
 * exact root of a problem whose inputs are perturbed by a few u; to first
 * order that moves the root by u * condition (quad_reference.h gives the
 * formula: the change of Q over its slope at the root). We allow
 *     |t - t_ref| <= 8 u condition,
 * and the test prints the worst ratio |t - t_ref| / (u condition) seen, so a
 * drift toward the limit shows before it fails. The textbook b^2 - a c
 * fails this by orders of magnitude for the far rays (its error there is
 * about u |o|^2 / sqrt(disc), not u |o|). */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "hr_test.h"
#include "module_harness.h"
#include "quad_reference.h"
#include "random_rays.h"

#define UNIT_ROUNDOFF (DBL_EPSILON / 2)
#define T_TOLERANCE_FACTOR 8.0
#define SAFE_MARGIN 1e-6
#define NEAR_RAYS 20000
#define FAR_RAYS 4000

typedef struct stats {
    int compared, skipped;
    double worst_t_ratio;     /* |t - t_ref| / (u condition) */
    double worst_point_ratio; /* distance to surface / error */
} stats;

static int is_flat(ref_shape shape, int surface)
{
    return shape.kind == REF_PLANE || shape.kind == REF_SQUARE || shape.kind == REF_CUBE ||
           (shape.kind == REF_TAPERED && surface != 0) ||
           (shape.kind == REF_TUBE && (surface == 1 || surface == 2));
}

static void compare_ray(const harness_shape *shape, ref_shape ref, hr_ray ray, stats *st,
                        const char *what)
{
    ref_trace expect;
    ref_trace_ray(ref, ray, &expect);
    hr_hit h[HARNESS_MAX_HITS];
    const int n = harness_trace(shape, ray, -INFINITY, INFINITY, HARNESS_ALL, h);
    if (!(expect.margin > SAFE_MARGIN)) {
        st->skipped++;
        return;
    }
    st->compared++;
#define RAY_FMT "%s %s ray (%.17g, %.17g, %.17g) + t (%.17g, %.17g, %.17g): "
#define RAY_ARGS                                                                              \
    what, shape->cls->name, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, \
        ray.dir.z
    CHECK_MSG(n == expect.count, RAY_FMT "%d hits, reference %d", RAY_ARGS, n, expect.count);
    if (n != expect.count) return;
    for (int i = 0; i < n; i++) {
        const ref_hit *r = &expect.hits[i];
        CHECK_MSG(h[i].surface == r->surface && h[i].entering == r->entering,
                  RAY_FMT "hit %d: surface %d entering %d, reference %d %d", RAY_ARGS, i,
                  (int)h[i].surface, (int)h[i].entering, r->surface, r->entering);
        const double scale = UNIT_ROUNDOFF * ref_to_double(r->condition);
        const double err = fabs(ref_to_double((quad)h[i].t - r->t));
        const double ratio = scale > 0 ? err / scale : (err > 0 ? INFINITY : 0);
        if (ratio > st->worst_t_ratio) st->worst_t_ratio = ratio;
        CHECK_MSG(ratio <= T_TOLERANCE_FACTOR,
                  RAY_FMT "hit %d: t = %.17g, reference %.17g (%.3g u * condition)", RAY_ARGS, i,
                  h[i].t, ref_to_double(r->t), ratio);
        const double distance = ref_surface_distance(ref, h[i].surface, h[i].point);
        const double point_ratio = h[i].error > 0 ? distance / h[i].error : (distance > 0 ? INFINITY : 0);
        if (point_ratio > st->worst_point_ratio) st->worst_point_ratio = point_ratio;
        CHECK_MSG(distance <= sqrt(3.0) * h[i].error,
                  RAY_FMT "hit %d: point %.3g from the surface, error bound %.3g", RAY_ARGS, i,
                  distance, h[i].error);
        if (is_flat(ref, h[i].surface)) {
            const quad px = (quad)ray.origin.x + r->t * ray.dir.x;
            const quad py = (quad)ray.origin.y + r->t * ray.dir.y;
            const quad pz = (quad)ray.origin.z + r->t * ray.dir.z;
            const double dx = fabs(ref_to_double(px - h[i].point.x));
            const double dy = fabs(ref_to_double(py - h[i].point.y));
            const double dz = fabs(ref_to_double(pz - h[i].point.z));
            CHECK_MSG(dx <= h[i].error && dy <= h[i].error && dz <= h[i].error,
                      RAY_FMT "hit %d: point off the exact one by (%.3g, %.3g, %.3g), bound %.3g",
                      RAY_ARGS, i, dx, dy, dz, h[i].error);
        }
    }
#undef RAY_FMT
#undef RAY_ARGS
}

static void test_random_rays(const harness_class_ref *cref, uint64_t seed)
{
    harness_shape shape;
    if (!harness_open_ref(&shape, cref)) {
        harness_close(&shape);
        return;
    }
    const ref_shape ref = ref_shape_of(cref->name, cref->s, cref->t);
    hr_bounds bounds;
    shape.cls->bounds(shape.shape, &bounds);
    ray_rng rng;
    rng_seed(&rng, seed);
    stats near = {0, 0, 0, 0}, far = {0, 0, 0, 0};
    for (int i = 0; i < NEAR_RAYS; i++)
        compare_ray(&shape, ref, random_ray_near(&rng, &bounds), &near, "near");
    for (int i = 0; i < FAR_RAYS; i++) {
        const double distance = i % 2 ? 1e6 : 1e4;
        compare_ray(&shape, ref, random_ray_far(&rng, &bounds, distance), &far, "far");
    }
    printf("%-16s s=%-6g near: %5d compared %4d skipped, worst t %.3g u*cond, point %.3g error;"
           " far: %4d compared %3d skipped, worst t %.3g, point %.3g\n",
           cref->name, isnan(cref->s) ? 0.0 : cref->s, near.compared, near.skipped,
           near.worst_t_ratio, near.worst_point_ratio, far.compared, far.skipped,
           far.worst_t_ratio, far.worst_point_ratio);
    /* Leaving out near-degenerate rays must not hollow the test out. */
    CHECK_MSG(near.skipped < NEAR_RAYS / 10, "%s: %d near rays skipped", cref->name, near.skipped);
    CHECK_MSG(far.skipped < FAR_RAYS / 10, "%s: %d far rays skipped", cref->name, far.skipped);
    harness_close(&shape);
}

/* Far sphere, 1e4 and 1e6 away, rays aimed within 0.5 of the centre (the
 * line passes at a distance h <= 0.5). Error budget of a root, in units of
 * u, relative: the cross product o x d has components within 1.5 ulp (3u),
 * so |o x d|^2 is within 6u, and the discriminant |d|^2 - |o x d|^2 =
 * |d|^2 (1 - h^2) within u (1 + 6 h^2 / (1 - h^2)) <= 3u; its square root
 * 2u; b is within u (compensated, rounded once), so q = -(b + sign(b) sqrt)
 * (no cancellation) within 3u; c and a within u and one division: each root
 * within about 5u. One u relative is at most 2 ulps (a binade spans a factor
 * of 2), so we allow 10 ulps: 2e-9 at 1e6, where the textbook b^2 - a c is
 * off by about u |o|^2 / sqrt(disc) ~ 1e-4. The worst seen is printed.
 * (Rays closer to grazing are covered by test_random_rays' condition-based
 * tolerance.) */
static void test_far_sphere(void)
{
    harness_shape sphere;
    if (!harness_open(&sphere, "sphere", "sphere", NAN)) {
        harness_close(&sphere);
        return;
    }
    const ref_shape ref = ref_shape_of("sphere", NAN, NAN);
    ray_rng rng;
    rng_seed(&rng, 1234567);
    const double distances[] = {1e4, 1e6};
    for (int k = 0; k < 2; k++) {
        double worst_ulps = 0;
        for (int i = 0; i < 5000; i++) {
            hr_vec3 target;
            do {
                target.x = rng_uniform(&rng, -0.5, 0.5);
                target.y = rng_uniform(&rng, -0.5, 0.5);
                target.z = rng_uniform(&rng, -0.5, 0.5);
            } while (target.x * target.x + target.y * target.y + target.z * target.z > 0.25);
            const hr_vec3 away = rng_unit_vector(&rng);
            const double length = i % 3 == 0 ? 1.0 : exp2(rng_uniform(&rng, -3, 3));
            const hr_ray ray = harness_ray(
                distances[k] * away.x, distances[k] * away.y, distances[k] * away.z,
                (target.x - distances[k] * away.x) * (i % 3 == 2 ? 1.0 : length / distances[k]),
                (target.y - distances[k] * away.y) * (i % 3 == 2 ? 1.0 : length / distances[k]),
                (target.z - distances[k] * away.z) * (i % 3 == 2 ? 1.0 : length / distances[k]));
            ref_trace expect;
            ref_trace_ray(ref, ray, &expect);
            hr_hit h[HARNESS_MAX_HITS];
            const int n = harness_hits(&sphere, ray, h);
            CHECK_MSG(n == 2 && expect.count == 2, "far %g: %d hits, reference %d", distances[k],
                      n, expect.count);
            if (n != 2 || expect.count != 2) continue;
            for (int j = 0; j < 2; j++) {
                const double ulps = hr_test_ulps(h[j].t, ref_to_double(expect.hits[j].t));
                if (ulps > worst_ulps) worst_ulps = ulps;
                CHECK_MSG(ulps <= 10, "far %g: root %d = %.17g, reference %.17g (%g ulps)",
                          distances[k], j, h[j].t, ref_to_double(expect.hits[j].t), ulps);
            }
        }
        printf("far sphere at %g: worst root error %g ulps\n", distances[k], worst_ulps);
    }
    harness_close(&sphere);
}

/* Origins inside each closed solid (rejection-sampled against the exact
 * shape, at least 1e-6 inside), random directions: over (0, inf) the first
 * hit leaves, and there are as many as the reference has (one for a convex
 * solid). */
static void test_from_inside(const harness_class_ref *cref, uint64_t seed)
{
    harness_shape shape;
    if (!harness_open_ref(&shape, cref)) {
        harness_close(&shape);
        return;
    }
    if (!(shape.cls->flags & HR_SHAPE_CLOSED)) {
        harness_close(&shape);
        return;
    }
    const ref_shape ref = ref_shape_of(cref->name, cref->s, cref->t);
    hr_bounds b;
    shape.cls->bounds(shape.shape, &b);
    ray_rng rng;
    rng_seed(&rng, seed);
    int tested = 0;
    for (int i = 0; i < 20000 && tested < 2000; i++) {
        const hr_vec3 dir = rng_unit_vector(&rng);
        const hr_ray ray = harness_ray(rng_uniform(&rng, b.lo.x, b.hi.x),
                                       rng_uniform(&rng, b.lo.y, b.hi.y),
                                       rng_uniform(&rng, b.lo.z, b.hi.z), dir.x, dir.y, dir.z);
        ref_trace expect;
        ref_trace_ray(ref, ray, &expect);
        /* Inside: the reference's crossings straddle t = 0 with the one after
         * 0 leaving, and t = 0 is clear of them. */
        int after = 0;
        while (after < expect.count && expect.hits[after].t <= 0) after++;
        if (after == expect.count || expect.hits[after].entering) continue;
        if (!(expect.margin > SAFE_MARGIN)) continue;
        if (!(ref_to_double(expect.hits[after].t) > 1e-6 &&
              (after == 0 || ref_to_double(expect.hits[after - 1].t) < -1e-6)))
            continue;
        tested++;
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&shape, ray, h);
        /* Convex solids: one hit. The torus may leave and come back. */
        CHECK_MSG(n == expect.count - after && h[0].entering == 0,
                  "%s from inside (%.17g, %.17g, %.17g) along (%.17g, %.17g, %.17g): %d hits",
                  cref->name, ray.origin.x, ray.origin.y, ray.origin.z, dir.x, dir.y, dir.z, n);
    }
    CHECK_MSG(tested >= 1000, "%s: only %d rays from inside", cref->name, tested);
    harness_close(&shape);
}

int main(void)
{
    for (int i = 0; i < harness_catalog_count; i++) {
        test_random_rays(&harness_catalog[i], UINT64_C(0xacc0000) + (uint64_t)i);
        test_from_inside(&harness_catalog[i], UINT64_C(0x1551de) + (uint64_t)i);
    }
    test_far_sphere();
    return hr_test_end();
}
