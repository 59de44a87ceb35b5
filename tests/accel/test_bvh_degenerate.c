/* The BVH on inputs that break naive builders: every box the same, boxes of
 * zero size, one object, flat boxes all in one plane, boxes spaced
 * geometrically (a deep, lopsided tree) and 100k objects. Whatever the
 * tree, getFirstHit through it must be the nearest of every hit
 * (hr_scene_all_hits, which tests every object without the BVH). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

/* A fixed, portable pseudo-random sequence (xorshift64*). */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double uniform(double lo, double hi)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    uint64_t r = rng_state * 0x2545F4914F6CDD1Dull;
    return lo + (hi - lo) * (double)(r >> 11) * (1.0 / 9007199254740992.0);
}

static void add_at(hr_scene *s, const char *shape, double x, double y, double z, double scale)
{
    hr_transform t = tb_place(x, y, z, scale);
    CHECK(tb_add(s, shape, NULL, &t) >= 0);
}

/* Shoot `n` rays from random points of `box` toward random points of
 * `target`; the first hit must agree with the nearest of all hits. */
static void agree(hr_scene *s, const char *what, int n, hr_bounds from, hr_bounds target)
{
    int mismatches = 0, hits = 0;
    hr_intersection all;
    hr_intersection_init(&all);
    for (int i = 0; i < n; i++) {
        hr_vec3 o = {uniform(from.lo.x, from.hi.x), uniform(from.lo.y, from.hi.y),
                     uniform(from.lo.z, from.hi.z)};
        hr_vec3 p = {uniform(target.lo.x, target.hi.x), uniform(target.lo.y, target.hi.y),
                     uniform(target.lo.z, target.hi.z)};
        hr_ray r = {o, {p.x - o.x, p.y - o.y, p.z - o.z}};
        hr_hit h;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, &h, &found));
        CHECK_OK(hr_scene_all_hits(s, &r, 0, INFINITY, &all));
        if (found != (all.count > 0) || (found && h.t != all.hits[0].t)) {
            if (mismatches++ < 3)
                fprintf(stderr, "%s: ray %d: first hit %d t=%.17g, all hits %d t=%.17g\n", what, i,
                        (int)found, found ? h.t : 0.0, (int)all.count,
                        all.count ? all.hits[0].t : 0.0);
        }
        hits += found;
    }
    hr_intersection_release(&all);
    CHECK_MSG(mismatches == 0, "%s: %d of %d rays disagree", what, mismatches, n);
    CHECK_MSG(hits > 0, "%s: no ray hit anything", what);
}

static hr_bounds box(double x0, double y0, double z0, double x1, double y1, double z1)
{
    hr_bounds b = {{x0, y0, z0}, {x1, y1, z1}};
    return b;
}

static hr_scene *committed(hr_scene *s)
{
    CHECK_OK(hr_scene_commit(s));
    return s;
}

static void identical_boxes(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    for (int i = 0; i < 1000; i++) add_at(s, "sphere", 1, 2, 3, 1);
    committed(s);
    agree(s, "1000 identical spheres", 300, box(-10, -10, 10, 10, 10, 12), box(0, 1, 2, 2, 3, 4));
    hr_scene_destroy(s);
}

static void zero_size_and_single(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    add_at(s, "sphere", 0, 0, 0, 1);
    committed(s);
    agree(s, "one sphere", 200, box(-5, -5, 5, 5, 5, 6), box(-1, -1, -1, 1, 1, 1));
    hr_scene_destroy(s);

    /* Spheres so small their boxes are points next to anything else, all at
     * the origin and in a row. (Not below ~1e-150: the sphere module misses
     * a ray whose object-space direction squared overflows.) */
    hr_scene_create(ctx, &s);
    for (int i = 0; i < 64; i++) add_at(s, "sphere", 0, 0, 0, 1e-100);
    for (int i = 0; i < 64; i++) add_at(s, "sphere", i * 1e-3, 0, 0, 1e-100);
    committed(s);
    /* Rays at a sphere's centre exactly, along the axes. */
    hr_intersection all;
    hr_intersection_init(&all);
    for (int i = 0; i < 64; i++) {
        hr_ray r = {{i * 1e-3, 0, 1}, {0, 0, -1}};
        hr_hit h;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, &h, &found));
        CHECK_OK(hr_scene_all_hits(s, &r, 0, INFINITY, &all));
        CHECK_MSG(found && all.count > 0 && h.t == all.hits[0].t, "tiny sphere %d: found %d, all %d", i,
                  (int)found, (int)all.count);
    }
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* Squares in the plane z = 0 (flat boxes), and squares standing on one
 * line (boxes flat in two ways at once). */
static void flat_boxes(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    for (int i = 0; i < 40; i++)
        for (int j = 0; j < 40; j++) add_at(s, "square", 2.5 * i, 2.5 * j, 0, 1);
    committed(s);
    agree(s, "1600 coplanar squares", 500, box(-5, -5, 3, 105, 105, 10), box(-2, -2, 0, 100, 100, 0));
    hr_scene_destroy(s);

    hr_scene_create(ctx, &s);
    for (int i = 0; i < 200; i++) {
        hr_transform t;
        hr_transform_identity(&t);
        hr_transform_translate(&t, 0, 0, i * 0.5);
        hr_transform_rotate(&t, 90, 1, 0, 0);
        hr_transform_scale(&t, 1e-9, 1, 1); /* a sliver: box nearly a segment */
        CHECK(tb_add(s, "square", NULL, &t) >= 0);
    }
    committed(s);
    agree(s, "200 slivers on a line", 300, box(-3, -5, -2, 3, -4, 102), box(-1e-9, 0, 0, 1e-9, 0, 100));
    hr_scene_destroy(s);
}

/* Boxes spaced geometrically: binned SAH peels a few off per level, so the
 * tree is far deeper than a balanced one (the traversal stack's limit).
 * 1.5^800 ~ 1e140 keeps the object-space directions (~1/scale) in the
 * range where the sphere module's a = d.d neither under- nor overflows. */
static void geometric_spacing(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    double x = 1;
    for (int i = 0; i < 800; i++, x *= 1.5) add_at(s, "sphere", x, 0, 0, 0.3 * x);
    committed(s);
    /* Along the row from below its start, and across it at many scales. */
    agree(s, "geometric row, along", 100, box(-10, -0.1, -0.1, -5, 0.1, 0.1), box(1e3, -0.1, -0.1, 1e6, 0.1, 0.1));
    int bad = 0;
    x = 1;
    for (int i = 0; i < 800; i += 7) {
        double xi = x;
        for (int k = 0; k < 7 && i + k < 800; k++) x *= 1.5;
        hr_ray r = {{xi, 0, 10 * xi}, {0, 0, -1}};
        hr_hit h;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, &h, &found));
        if (!found || fabs(h.t - 9.7 * xi) > 1e-9 * xi) {
            if (bad < 3) fprintf(stderr, "across %d: found %d t %.17g want %.17g\n", i, (int)found, found ? h.t : 0.0, 9.7 * xi);
            bad++;
        }
    }
    CHECK_MSG(bad == 0, "geometric row, across: %d rays missed their sphere", bad);
    hr_scene_destroy(s);
}

static void many_objects(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    for (int i = 0; i < 100000; i++)
        add_at(s, "sphere", uniform(-100, 100), uniform(-100, 100), uniform(-100, 100),
               uniform(0.05, 0.5));
    committed(s);
    CHECK(hr_scene_object_count(s) == 100000);
    agree(s, "100k spheres", 300, box(-150, -150, -150, 150, 150, 150), box(-100, -100, -100, 100, 100, 100));
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    identical_boxes();
    zero_size_and_single();
    flat_boxes();
    geometric_spacing();
    many_objects();
    hr_context_destroy(ctx);
    return hr_test_end();
}
