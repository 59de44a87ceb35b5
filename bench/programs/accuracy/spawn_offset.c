/* Where a spawned ray starts: a fixed epsilon along the normal (1e-3, 1e-6
 * world units, the textbook fix, written here as the baseline) against the
 * renderer's rule, hr_hit_spawn_origin (the hit's own error bound), over
 * scene scales 1e-4 .. 1e12. Through the library: the object is a scene
 * object scaled by S, turned, and placed S * (3, -2, 5) from the origin, so
 * every length of the scene grows with S and only the offsets do not.
 *
 *   build/bench/accuracy/spawn_offset [--rays=N] [--shell-rays=N]
 *
 * Self-hits (one JSON line per shape, scale and method; shapes: sphere,
 * cylinder, both convex, so the right answer is known without a reference):
 * N camera rays from 10 S away aimed at random points of the object's
 * bounds; at each hit two rays are spawned, as a reflected and a refracted
 * ray would be:
 * - out: from the offset origin on the normal's side, in a random direction
 *   of that hemisphere. A convex solid cannot be met again: any hit is a
 *   self-hit;
 * - in: from the offset origin on the other side, in a random direction of
 *   the inner hemisphere. It must leave the solid (a first hit that exits);
 *   a first hit that enters is a self-hit (the origin was left outside),
 *   none at all is a ray lost (the offset carried it through the solid).
 * `offset` is the mean distance from the hit point to the spawned origin,
 * relative to S.
 *
 * Thinnest shell (one JSON line per scale and method): two concentric
 * spheres of radius S and S (1 - g), the camera ray meets the outer one and
 * a ray is spawned inward (within 30 degrees of the inward normal, so it
 * must meet the inner sphere); it finds the shell when its first hit enters
 * the inner sphere. g sweeps 10^-1, 10^-1.5, ..., 10^-16; `thinnest_gap` is
 * the smallest g down to which every g of the sweep was found by all of
 * --shell-rays rays (1 when even 10^-1 was missed). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "bench_util.h"
#include "random_rays.h"

#define METHOD_COUNT 3
static const char *const method_names[METHOD_COUNT] = {"epsilon 1e-3", "epsilon 1e-6",
                                                       "error bound"};
static const double method_epsilons[METHOD_COUNT] = {1e-3, 1e-6, 0.0};

static void fail(hr_context *ctx, const char *what)
{
    fprintf(stderr, "spawn_offset: %s: %s\n", what, hr_context_last_error(ctx));
    exit(1);
}

/* The placement of scale S: M = T R S, the translation S (3, -2, 5). */
static void placement(double scale, double radius, hr_transform *t)
{
    hr_transform_identity(t);
    hr_transform_translate(t, 3 * scale, -2 * scale, 5 * scale);
    hr_transform_rotate(t, 37, 1, 2, -0.5);
    hr_transform_scale(t, scale * radius, scale * radius, scale * radius);
}

static void add_object(hr_context *ctx, hr_scene *scene, const char *shape, double scale,
                       double radius)
{
    hr_transform t;
    placement(scale, radius, &t);
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = shape;
    d.transform = t.m;
    d.inverse = t.inv;
    if (hr_scene_add_object(scene, &d, NULL) != HR_OK) fail(ctx, shape);
}

static hr_vec3 vec(double x, double y, double z)
{
    hr_vec3 v = {x, y, z};
    return v;
}

static double dot(hr_vec3 a, hr_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static double distance(hr_vec3 a, hr_vec3 b)
{
    const hr_vec3 d = vec(a.x - b.x, a.y - b.y, a.z - b.z);
    return sqrt(dot(d, d));
}

/* A camera ray from 10 S away (a random direction) at a random point of the
 * world box [centre - S, centre + S]. */
static hr_ray camera_ray(ray_rng *rng, double scale)
{
    const hr_vec3 centre = vec(3 * scale, -2 * scale, 5 * scale);
    const hr_vec3 target = vec(centre.x + scale * rng_uniform(rng, -1, 1),
                               centre.y + scale * rng_uniform(rng, -1, 1),
                               centre.z + scale * rng_uniform(rng, -1, 1));
    const hr_vec3 away = rng_unit_vector(rng);
    hr_ray r;
    r.origin = vec(centre.x + 10 * scale * away.x, centre.y + 10 * scale * away.y,
                   centre.z + 10 * scale * away.z);
    r.dir = vec(target.x - r.origin.x, target.y - r.origin.y, target.z - r.origin.z);
    return r;
}

/* The origin of a ray leaving `hit` toward `side` (a unit vector). */
static hr_vec3 spawn(int method, const hr_hit *hit, hr_vec3 side)
{
    if (method_epsilons[method] == 0.0) return hr_hit_spawn_origin(hit, side);
    const double e = method_epsilons[method];
    return vec(hit->point.x + e * side.x, hit->point.y + e * side.y, hit->point.z + e * side.z);
}

/* A random unit direction in the hemisphere around `axis`. */
static hr_vec3 hemisphere(ray_rng *rng, hr_vec3 axis)
{
    hr_vec3 v = rng_unit_vector(rng);
    if (dot(v, axis) < 0) v = vec(-v.x, -v.y, -v.z);
    return v;
}

static void first_hit(hr_context *ctx, const hr_scene *scene, hr_ray ray, hr_hit *hit,
                      int32_t *found)
{
    if (hr_scene_first_hit(scene, &ray, 0.0, INFINITY, hit, found) != HR_OK)
        fail(ctx, "first hit");
}

static void self_hits(hr_context *ctx, const char *shape, double scale, int count)
{
    hr_scene *scene;
    if (hr_scene_create(ctx, &scene) != HR_OK) fail(ctx, "scene");
    add_object(ctx, scene, shape, scale, 1.0);
    if (hr_scene_commit(scene) != HR_OK) fail(ctx, "commit");
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0x5ba3) + (uint64_t)(log10(scale) + 10));
    int hits = 0, out_self[METHOD_COUNT] = {0}, in_self[METHOD_COUNT] = {0};
    int in_lost[METHOD_COUNT] = {0};
    double offset_sum[METHOD_COUNT] = {0};
    for (int i = 0; i < count; i++) {
        hr_hit hit;
        int32_t found;
        first_hit(ctx, scene, camera_ray(&rng, scale), &hit, &found);
        if (!found) continue;
        hits++;
        const hr_vec3 n = hit.normal, inward = vec(-n.x, -n.y, -n.z);
        const hr_vec3 out_dir = hemisphere(&rng, n), in_dir = hemisphere(&rng, inward);
        for (int m = 0; m < METHOD_COUNT; m++) {
            hr_hit again;
            hr_ray r = {spawn(m, &hit, n), out_dir};
            offset_sum[m] += distance(r.origin, hit.point) / scale;
            first_hit(ctx, scene, r, &again, &found);
            out_self[m] += found;
            r.origin = spawn(m, &hit, inward);
            r.dir = in_dir;
            first_hit(ctx, scene, r, &again, &found);
            if (!found) in_lost[m]++;
            else if (again.entering) in_self[m]++;
        }
    }
    for (int m = 0; m < METHOD_COUNT; m++)
        printf("{\"test\": \"self-hit\", \"shape\": \"%s\", \"scale\": %g, \"method\": \"%s\", "
               "\"hits\": %d, \"out_self\": %d, \"in_self\": %d, \"in_lost\": %d, "
               "\"offset\": %.3e}\n",
               shape, scale, method_names[m], hits, out_self[m], in_self[m], in_lost[m],
               hits ? offset_sum[m] / hits : 0.0);
    fflush(stdout);
    hr_scene_destroy(scene);
}

/* 1 when every one of `count` spawned rays finds the inner sphere of the
 * shell of relative gap g with method m. */
static int shell_found(hr_context *ctx, double scale, double gap, int method, int count)
{
    hr_scene *scene;
    if (hr_scene_create(ctx, &scene) != HR_OK) fail(ctx, "scene");
    add_object(ctx, scene, "sphere", scale, 1.0);
    add_object(ctx, scene, "sphere", scale, 1.0 - gap);
    if (hr_scene_commit(scene) != HR_OK) fail(ctx, "commit");
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0x5e11));
    int all = 1;
    for (int i = 0; i < count && all; i++) {
        hr_hit hit;
        int32_t found;
        first_hit(ctx, scene, camera_ray(&rng, scale), &hit, &found);
        if (!found) {
            i--; /* the camera ray missed both: draw another */
            continue;
        }
        if (hit.object != 0) { /* the inner sphere came first: unresolved */
            all = 0;
            break;
        }
        const hr_vec3 n = hit.normal, v = rng_unit_vector(&rng);
        /* |0.5 v| <= 0.5 keeps the direction within 30 degrees of -n, where
         * every line from the outer sphere meets the inner one. */
        const hr_ray r = {spawn(method, &hit, vec(-n.x, -n.y, -n.z)),
                          vec(-n.x + 0.5 * v.x, -n.y + 0.5 * v.y, -n.z + 0.5 * v.z)};
        hr_hit next;
        first_hit(ctx, scene, r, &next, &found);
        all = found && next.object == 1 && next.entering;
    }
    hr_scene_destroy(scene);
    return all;
}

static void thinnest_shell(hr_context *ctx, double scale, int count)
{
    for (int m = 0; m < METHOD_COUNT; m++) {
        double thinnest = 1.0;
        for (int k = 2; k <= 32; k++) {
            const double gap = pow(10.0, -0.5 * k);
            if (!shell_found(ctx, scale, gap, m, count)) break;
            thinnest = gap;
        }
        printf("{\"test\": \"shell\", \"shape\": \"sphere\", \"scale\": %g, \"method\": \"%s\", "
               "\"rays\": %d, \"thinnest_gap\": %.3g}\n",
               scale, method_names[m], count, thinnest);
        fflush(stdout);
    }
}

int main(int argc, char **argv)
{
    int count = 20000, shell_count = 500;
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (bench_option(argv[i], "--rays", &v)) count = atoi(v);
        else if (bench_option(argv[i], "--shell-rays", &v)) shell_count = atoi(v);
        else count = 0;
    }
    if (count <= 0 || shell_count <= 0) {
        fprintf(stderr, "usage: spawn_offset [--rays=N] [--shell-rays=N]\n");
        return 2;
    }
    hr_context *ctx;
    if (hr_context_create(&ctx) != HR_OK) return 1;
    static const char *const shapes[] = {"sphere", "cylinder"};
    for (int e = -4; e <= 12; e++) {
        const double scale = pow(10.0, e);
        for (int s = 0; s < 2; s++) self_hits(ctx, shapes[s], scale, count);
        thinnest_shell(ctx, scale, shell_count);
    }
    hr_context_destroy(ctx);
    return 0;
}
