/* The host's prepared ray (hr_hit_args.walk_ray): where the scene walk
 * traces an untransformed mesh, it hands the mesh the accel_ray4 it
 * prepared for its own walk, and the mesh's walk starts from it instead of
 * preparing the ray again (shapes/mesh/mesh_trace.c, host_walk_ray).
 * - Same answers: random rays at the teapot (open) and the buckyball
 *   (closed), first, any and every hit, tmin 0 or later and tmax finite or
 *   not, give bit for bit the hits they give with no prepared ray.
 * - It is read: a prepared ray made for another ray (one that runs away
 *   from the mesh, from outside its box) makes the mesh's walk visit no leaf, so a ray that hits
 *   finds nothing; that is how the test knows the mesh used it.
 * - It is read only where it may be: with another format (the other CPU
 *   path's flip, another layout) or from an older host (struct_size ending
 *   before walk_ray_format), the same wrong ray is ignored and the hit
 *   found. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh4.h"
#include "hr_test.h"
#include "module_harness.h"
#include "random_rays.h"

static hr_intersection list;

/* The shape's answer in `mode` (HR_TRACE_*), its hits copied to out. */
static int32_t trace(const harness_shape *s, const hr_ray *ray, double tmin, double tmax, int32_t mode,
                     const void *walk_ray, uint32_t format, uint32_t struct_size, hr_hit *out, int32_t room)
{
    hr_hit_args args;
    memset(&args, 0, sizeof args);
    args.shape = s->shape;
    args.ray = *ray;
    args.tmin = tmin;
    args.tmax = tmax;
    args.out = &list;
    args.struct_size = struct_size;
    args.walk_ray = walk_ray;
    args.walk_ray_format = format;
    list.count = 0;
    const hr_hit_fn fn = mode == HR_TRACE_ALL ? s->cls->hit : mode == HR_TRACE_FIRST ? s->cls->first_hit
                                                                                     : s->cls->any_hit;
    CHECK_OK(fn(&args));
    const int32_t n = list.count < room ? list.count : room;
    memcpy(out, list.hits, (size_t)n * sizeof *out);
    return list.count;
}

static int same_hits(const hr_hit *a, const hr_hit *b, int32_t n, int32_t mode)
{
    for (int32_t i = 0; i < n; i++) {
        /* An any-hit answer carries only t (HR_TRACE_ANY). */
        if (mode == HR_TRACE_ANY ? a[i].t != b[i].t : memcmp(&a[i], &b[i], sizeof a[i]) != 0) return 0;
    }
    return 1;
}

static void check_mesh(const char *name, int rays)
{
    harness_shape s;
    if (!harness_open(&s, "mesh", name, NAN)) {
        CHECK_MSG(0, "%s: cannot open", name);
        return;
    }
    hr_bounds box;
    s.cls->bounds(s.shape, &box);
    const hr_vec3 c = {0.5 * (box.lo.x + box.hi.x), 0.5 * (box.lo.y + box.hi.y), 0.5 * (box.lo.z + box.hi.z)};
    const double size = fmax(box.hi.x - box.lo.x, fmax(box.hi.y - box.lo.y, box.hi.z - box.lo.z));
    ray_rng rng;
    rng_seed(&rng, 2026);
    long compared = 0, prepared = 0, differ = 0, hits = 0, used = 0, ignored = 0;
    enum { ROOM = 64 };
    static hr_hit plain[ROOM], given[ROOM];
    for (int i = 0; i < rays; i++) {
        const hr_vec3 from = harness_vec(c.x + size * rng_uniform(&rng, -1.5, 1.5),
                                         c.y + size * rng_uniform(&rng, -1.5, 1.5),
                                         c.z + size * rng_uniform(&rng, -1.5, 1.5));
        const hr_vec3 to = harness_vec(c.x + size * rng_uniform(&rng, -0.4, 0.4),
                                       c.y + size * rng_uniform(&rng, -0.4, 0.4),
                                       c.z + size * rng_uniform(&rng, -0.4, 0.4));
        const hr_ray ray = harness_ray(from.x, from.y, from.z, to.x - from.x, to.y - from.y, to.z - from.z);
        const double tmin = i % 3 == 0 ? 0.0 : rng_uniform(&rng, 0.0, 0.8);
        const double tmax = i % 2 ? INFINITY : rng_uniform(&rng, 0.9, 2.0);
        accel_ray4 r;
        if (!accel_ray4_prepare(&r, &ray, tmin)) continue;
        prepared++;
        for (int32_t mode = HR_TRACE_ALL; mode <= HR_TRACE_ANY; mode++) {
            const int32_t a = trace(&s, &ray, tmin, tmax, mode, NULL, 0, sizeof(hr_hit_args), plain, ROOM);
            const int32_t b =
                trace(&s, &ray, tmin, tmax, mode, &r, accel_ray4_format(), sizeof(hr_hit_args), given, ROOM);
            compared++;
            if (a != b || !same_hits(plain, given, a < ROOM ? a : ROOM, mode)) {
                if (differ++ < 5)
                    CHECK_MSG(0, "%s ray %d mode %d: %d hits plain, %d from the prepared ray", name, i, mode, a, b);
            }
        }
        /* A prepared ray of another ray, running away from the mesh from
         * an origin outside its box (so that ray meets no box). */
        const int outside = from.x < box.lo.x || from.x > box.hi.x || from.y < box.lo.y || from.y > box.hi.y ||
                            from.z < box.lo.z || from.z > box.hi.z;
        if (!outside) continue;
        if (trace(&s, &ray, tmin, tmax, HR_TRACE_FIRST, NULL, 0, sizeof(hr_hit_args), plain, ROOM) != 1) continue;
        hits++;
        const hr_ray away = {ray.origin, {from.x - to.x, from.y - to.y, from.z - to.z}};
        accel_ray4 wrong;
        if (!accel_ray4_prepare(&wrong, &away, tmin)) continue;
        used += trace(&s, &ray, tmin, tmax, HR_TRACE_FIRST, &wrong, accel_ray4_format(), sizeof(hr_hit_args),
                      given, ROOM) == 0;
        const uint32_t other_flip = accel_ray4_format() ^ ACCEL_RAY4_FLIPPED;
        const uint32_t other_layout = accel_ray4_format() + 1;
        const uint32_t older = (uint32_t)offsetof(hr_hit_args, walk_ray_format);
        ignored += trace(&s, &ray, tmin, tmax, HR_TRACE_FIRST, &wrong, other_flip, sizeof(hr_hit_args), given,
                         ROOM) == 1 &&
                   trace(&s, &ray, tmin, tmax, HR_TRACE_FIRST, &wrong, other_layout, sizeof(hr_hit_args), given,
                         ROOM) == 1 &&
                   trace(&s, &ray, tmin, tmax, HR_TRACE_FIRST, &wrong, accel_ray4_format(), older, given,
                         ROOM) == 1;
    }
    fprintf(stderr, "%s: %ld rays prepared, %ld answers compared, %ld differ; of %ld hit, %ld lost with a wrong "
                    "prepared ray, %ld kept where its format or the host's size says not to read it\n",
            name, prepared, compared, differ, hits, used, ignored);
    CHECK_MSG(differ == 0, "%s: %ld answers differ from the prepared ray", name, differ);
    CHECK(prepared > rays / 2 && hits > rays / 10);
    CHECK_MSG(used == hits, "%s: a wrong prepared ray lost %ld of %ld hits: the mesh did not read it", name, used,
              hits);
    CHECK_MSG(ignored == hits, "%s: %ld of %ld hits kept where the prepared ray must be ignored", name, ignored,
              hits);
    harness_close(&s);
}

int main(void)
{
    CHECK_OK(harness_host()->reserve(NULL, &list, 4 * HR_MIN_HIT_CAPACITY));
    check_mesh("teapot", 4000);
    check_mesh("buckyball", 4000);
    free(list.hits);
    return hr_test_end();
}
