/* A far torus through the whole library: a torus placed 1e4 away from the
 * world origin under a rotation and a non-uniform scale, rays from near the
 * origin aimed at random points of its bounding box, hits from
 * hr_scene_all_hits compared with roots computed in quad precision, with
 * every solver (the default must pass; the others' agreement is printed).
 *
 * Reference: the world ray is carried into object space in __float128
 * through the scene's own inverse matrix (whose double entries are taken as
 * exact), then the torus's quartic is solved by Sturm sequences
 * (quad_reference.c). Hill's rule keeps t the same in both spaces.
 *
 * Tolerance on t, in two parts.
 * - The host rounds the object-space ray: each coordinate of M^-1 o is a dot
 *   product of 3 terms plus the translation, within gamma(3) times the sum
 *   of the magnitudes of its terms (Higham 3.1), and likewise the direction.
 *   That moves the point of the line at the root by dp_i <= gamma(3)
 *   (m_i + |t| n_i) (m_i, n_i those magnitude sums), hence the root by
 *   sum_i |df/dp_i| dp_i / |f'(t)|. With the translation at 1e4 this is the
 *   larger part: about 1e-12 / (scale * cos(angle)).
 * - The module's own error on the ray it was given: 8 u * condition, as in
 *   test_shape_torus.c.
 * Rays within 1e-6 of a tangency are left out (test_shape_torus.c covers
 * tangents); the test checks they are few.
 * Points: mapped back to object space in quad, each must lie within 1e-9 of
 * the surface: the host's M p rounds by u |M| |p| + u |translation|, about
 * 2e-12 here in world units, at most 1e-11 in object units (smallest scale
 * 0.5), and the module's own bound is ~1e-15; 1e-9 leaves room for the
 * slip along the surface that the error of t causes on oblique rays. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "quad_reference.h"
#include "random_rays.h"

#define UNIT_ROUNDOFF (DBL_EPSILON / 2)
#define GAMMA3 (3 * UNIT_ROUNDOFF / (1 - 3 * UNIT_ROUNDOFF))
#define RAYS 3000

static quad qabs(quad x)
{
    return x < 0 ? -x : x;
}

static const char *const solvers[] = {"ferrari", "ferrari-newton", "bracketing", ""};

typedef struct world {
    hr_transform t;
    hr_scene *scene;
} world;

static int make_world(hr_context *ctx, const char *solver, world *w)
{
    hr_transform_identity(&w->t);
    hr_transform_translate(&w->t, 6000, -7000, 3500);
    hr_transform_rotate(&w->t, 37, 1, 2, -0.5);
    hr_transform_scale(&w->t, 2, 0.5, 3);
    hr_transform_rotate(&w->t, -20, 0, 1, 1);
    CHECK_OK(hr_scene_create(ctx, &w->scene));
    hr_param params[2];
    memset(params, 0, sizeof params);
    params[0].name = "tube", params[0].type = HR_PARAM_NUMBER, params[0].number = 0.2;
    params[1].name = "solver", params[1].type = HR_PARAM_STRING, params[1].string = solver;
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = "torus";
    d.params = params;
    d.param_count = 2;
    d.transform = w->t.m;
    d.inverse = w->t.inv;
    const hr_status st = hr_scene_add_object(w->scene, &d, NULL);
    CHECK_MSG(st == HR_OK, "torus: %s", hr_context_last_error(ctx));
    if (st != HR_OK) return 0;
    CHECK_OK(hr_scene_commit(w->scene));
    return 1;
}

/* The host's rounding of the object-space ray, propagated to the root. */
static quad host_term(const world *w, const hr_ray *wr, const quad o[3], const quad d[3], quad t)
{
    const double *inv = w->t.inv;
    quad p[3], m[3], n[3];
    for (int i = 0; i < 3; i++) {
        p[i] = o[i] + t * d[i];
        m[i] = qabs(inv[4 * i + 3]) + qabs(inv[4 * i] * (quad)wr->origin.x) +
               qabs(inv[4 * i + 1] * (quad)wr->origin.y) + qabs(inv[4 * i + 2] * (quad)wr->origin.z);
        n[i] = qabs(inv[4 * i] * (quad)wr->dir.x) + qabs(inv[4 * i + 1] * (quad)wr->dir.y) +
               qabs(inv[4 * i + 2] * (quad)wr->dir.z);
    }
    const quad r = 0.2;
    const quad G = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1 - r * r;
    const quad grad[3] = {4 * G * p[0], 4 * G * p[1], 4 * G * p[2] + 8 * p[2]};
    const quad slope = qabs(grad[0] * d[0] + grad[1] * d[1] + grad[2] * d[2]);
    quad moved = 0;
    for (int i = 0; i < 3; i++) moved += qabs(grad[i]) * GAMMA3 * (m[i] + qabs(t) * n[i]);
    return slope > 0 ? moved / slope : (quad)INFINITY;
}

static void check_solver(hr_context *ctx, int solver)
{
    world w;
    if (!make_world(ctx, solvers[solver], &w)) return;
    const int strict = solvers[solver][0] == '\0';
    const ref_shape ref = ref_shape_of("torus", 0.2, NAN);
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0xfa770000));
    hr_intersection list;
    hr_intersection_init(&list);
    int compared = 0, skipped = 0, wrong = 0, hits = 0;
    double worst = 0;
    for (int i = 0; i < RAYS; i++) {
        /* Aim at a random point of the object's bounding box, from near the
         * world origin, with a random direction length. */
        const quad target_o[3] = {rng_uniform(&rng, -1.2, 1.2), rng_uniform(&rng, -1.2, 1.2),
                                  rng_uniform(&rng, -0.2, 0.2)};
        quad target_w[3];
        for (int r = 0; r < 3; r++)
            target_w[r] = w.t.m[4 * r] * target_o[0] + w.t.m[4 * r + 1] * target_o[1] +
                          w.t.m[4 * r + 2] * target_o[2] + w.t.m[4 * r + 3];
        hr_ray wr;
        wr.origin.x = rng_uniform(&rng, -1, 1);
        wr.origin.y = rng_uniform(&rng, -1, 1);
        wr.origin.z = rng_uniform(&rng, -1, 1);
        const double length = exp2(rng_uniform(&rng, -16, -10));
        wr.dir.x = (double)((target_w[0] - wr.origin.x) * length);
        wr.dir.y = (double)((target_w[1] - wr.origin.y) * length);
        wr.dir.z = (double)((target_w[2] - wr.origin.z) * length);
        quad o[3], d[3];
        for (int r = 0; r < 3; r++) {
            const double *row = w.t.inv + 4 * r;
            o[r] = row[0] * (quad)wr.origin.x + row[1] * (quad)wr.origin.y +
                   row[2] * (quad)wr.origin.z + row[3];
            d[r] = row[0] * (quad)wr.dir.x + row[1] * (quad)wr.dir.y + row[2] * (quad)wr.dir.z;
        }
        ref_trace expect;
        ref_trace_quad_ray(ref, o, d, &expect);
        CHECK_OK(hr_scene_all_hits(w.scene, &wr, 0, INFINITY, &list));
        if (!(expect.margin > 1e-6)) {
            skipped++;
            continue;
        }
        compared++;
        int ok = list.count == expect.count;
        for (int k = 0; ok && k < list.count; k++) {
            const hr_hit *h = &list.hits[k];
            const ref_hit *r = &expect.hits[k];
            const quad allowed = 8 * UNIT_ROUNDOFF * r->condition + host_term(&w, &wr, o, d, r->t);
            const quad err = qabs((quad)h->t - r->t);
            const double ratio = (double)(err / allowed);
            if (ratio > worst) worst = ratio;
            ok &= h->entering == r->entering && err <= allowed;
            /* The point, back in object space, on the surface. */
            quad po[3];
            for (int row = 0; row < 3; row++) {
                const double *m = w.t.inv + 4 * row;
                po[row] = m[0] * (quad)h->point.x + m[1] * (quad)h->point.y +
                          m[2] * (quad)h->point.z + m[3];
            }
            const hr_vec3 pd = {(double)po[0], (double)po[1], (double)po[2]};
            const double distance = ref_surface_distance(ref, 0, pd);
            CHECK_MSG(distance <= 1e-9, "ray %d hit %d: %.3g off the surface", i, k, distance);
            hits++;
        }
        if (!ok) {
            wrong++;
            if (strict)
                CHECK_MSG(0,
                          "ray %d (%.17g %.17g %.17g) + t (%.17g %.17g %.17g): %d hits, "
                          "reference %d; first t %.17g vs %.17g",
                          i, wr.origin.x, wr.origin.y, wr.origin.z, wr.dir.x, wr.dir.y, wr.dir.z,
                          (int)list.count, expect.count, list.count ? list.hits[0].t : 0.0,
                          expect.count ? ref_to_double(expect.hits[0].t) : 0.0);
        }
    }
    printf("far torus, %-15s: %d rays compared, %d near-tangent skipped, %d hits; %d disagree; "
           "worst t error %.3g of the tolerance\n",
           solvers[solver][0] ? solvers[solver] : "(default)", compared, skipped, hits, wrong,
           worst);
    CHECK_MSG(skipped < RAYS / 20, "%d rays skipped", skipped);
    CHECK_MSG(hits > RAYS, "only %d hits", hits);
    hr_intersection_release(&list);
    hr_scene_destroy(w.scene);
}

/* Through the library, a refused parameter names the shape, the module's
 * path, the parameter and what it may be. */
static void check_refusals(hr_context *ctx)
{
    hr_scene *scene;
    CHECK_OK(hr_scene_create(ctx, &scene));
    hr_param p;
    memset(&p, 0, sizeof p);
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = "torus";
    d.params = &p;
    d.param_count = 1;
    p.name = "solver", p.type = HR_PARAM_STRING, p.string = "newton";
    CHECK(hr_scene_add_object(scene, &d, NULL) == HR_ERROR_PARAMETER);
    const char *message = hr_context_last_error(ctx);
    CHECK_MSG(strstr(message, "torus.so") && strstr(message, "'solver' = 'newton'") &&
                  strstr(message, "'ferrari-newton'") && strstr(message, "'bracketing'"),
              "message: %s", message);
    p.name = "tube", p.type = HR_PARAM_NUMBER, p.number = 1.0, p.string = NULL;
    CHECK(hr_scene_add_object(scene, &d, NULL) == HR_ERROR_PARAMETER);
    message = hr_context_last_error(ctx);
    CHECK_MSG(strstr(message, "'tube'") && strstr(message, "0.999"), "message: %s", message);
    CHECK(hr_scene_object_count(scene) == 0);
    hr_scene_destroy(scene);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    check_refusals(ctx);
    for (int solver = 0; solver < 4; solver++) check_solver(ctx, solver);
    hr_context_destroy(ctx);
    return hr_test_end();
}
