/* hr_scene_first_hit against the slow truth, through the paths tracing takes
 * for speed: the BVH walk (straight down to the nearer child, both children
 * tested at once) must find exactly the nearest of every hit along the ray
 * (hr_scene_all_hits, which visits every object without the BVH, the
 * bounded ones where the ray meets the box around them); planes,
 * tested after the BVH within its best t, must give that answer too, ties
 * included (the object added first wins); and a shape that asks for more room than the
 * query's on-stack list has (through host->reserve) must get it, with no hit
 * lost. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/nff.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

/* xorshift64*: the same scene on every run. */
static double uniform(uint64_t *s)
{
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1p-53;
}

/* 2,000 spheres of random sizes in a box (overlapping, some nested), and
 * rays from random points outside and inside it in random directions: the
 * first hit is the nearest of all hits, the same t and the same object
 * (ties go to the lower object index in both, hit_before's order). */
static void bvh_walk_matches_every_hit(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    uint64_t seed = 99;
    for (int i = 0; i < 2000; i++) {
        hr_transform t = tb_place(20 * uniform(&seed) - 10, 20 * uniform(&seed) - 10,
                                  20 * uniform(&seed) - 10, 0.05 + 0.6 * uniform(&seed));
        CHECK(tb_add(s, i % 3 ? "sphere" : "cube", NULL, &t) >= 0);
    }
    CHECK_OK(hr_scene_commit(s));
    hr_intersection all;
    hr_intersection_init(&all);
    int compared = 0, hits = 0;
    for (int k = 0; k < 3000; k++) {
        double spread = k % 2 ? 30 : 8;
        hr_ray r = {{spread * (2 * uniform(&seed) - 1), spread * (2 * uniform(&seed) - 1),
                     spread * (2 * uniform(&seed) - 1)},
                    {2 * uniform(&seed) - 1, 2 * uniform(&seed) - 1, 2 * uniform(&seed) - 1}};
        if (k % 7 == 0) r.dir.y = 0; /* axis-parallel slabs: 1/d is infinite */
        if (r.dir.x == 0 && r.dir.y == 0 && r.dir.z == 0) continue;
        hr_hit first;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, &first, &found));
        CHECK_OK(hr_scene_all_hits(s, &r, 0, INFINITY, &all));
        compared++;
        CHECK_MSG(found == (all.count > 0), "ray %d: first hit found %d, all hits %d", k,
                  (int)found, (int)all.count);
        if (!found || all.count == 0) continue;
        hits++;
        CHECK_MSG(first.t == all.hits[0].t && first.object == all.hits[0].object,
                  "ray %d: first hit t = %.17g object %lld, nearest of all t = %.17g object %lld",
                  k, first.t, (long long)first.object, all.hits[0].t,
                  (long long)all.hits[0].object);
    }
    /* Enough rays hit something for the comparison to mean much (about 40%). */
    CHECK_MSG(compared > 2900 && hits > compared / 4, "compared %d rays, %d hit", compared, hits);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* Planes (unbounded: not in the BVH) are tested after the BVH's walk, within
 * its best t, but must answer as the brute force does: the nearest hit of
 * all, and on a tie in t the object added first (the tie rule): here a cube
 * before any plane, the earlier plane before a later one. 64 cubes whose
 * top faces lie in z = 0 (objects 0 to 63), then two planes z = 0 (64 and
 * 65) and a tilted one (66). Half the rays have dyadic origins and
 * directions, for which a cube's top face and the planes give the same t,
 * bit for bit (-o_z / d_z both ways): ties decided by the rule, not by
 * rounding; the others are random, and some have a window that ends before
 * the planes. */
static void planes_after_the_walk_keep_the_tie_rule(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    for (int i = 0; i < 64; i++) {
        hr_transform t = tb_place((i % 8) * 3 - 10.5, (i / 8) * 3 - 10.5, -1.0, 1.0);
        CHECK(tb_add(s, "cube", NULL, &t) == i);
    }
    CHECK(tb_add(s, "plane", NULL, NULL) == 64);
    CHECK(tb_add(s, "plane", NULL, NULL) == 65);
    hr_transform tilted;
    hr_transform_identity(&tilted);
    CHECK_OK(hr_transform_rotate(&tilted, 37, 1, 2, 0.5));
    hr_transform_translate(&tilted, 0, 0, -3);
    CHECK(tb_add(s, "plane", NULL, &tilted) == 66);
    CHECK_OK(hr_scene_commit(s));
    hr_intersection all;
    hr_intersection_init(&all);
    uint64_t seed = 7;
    int ties = 0, cubes = 0, planes = 0, misses = 0;
    for (int k = 0; k < 20000; k++) {
        hr_ray r;
        if (k % 2) { /* dyadic: multiples of 1/8 and 1/16 */
            r.origin = (hr_vec3){floor(160 * uniform(&seed) - 80) / 8, floor(160 * uniform(&seed) - 80) / 8,
                                 floor(80 * uniform(&seed) + 1) / 8};
            r.dir = (hr_vec3){floor(32 * uniform(&seed) - 16) / 16, floor(32 * uniform(&seed) - 16) / 16,
                              -floor(16 * uniform(&seed) + 1) / 16};
        } else {
            r.origin = (hr_vec3){30 * uniform(&seed) - 15, 30 * uniform(&seed) - 15, 20 * uniform(&seed) - 5};
            r.dir = (hr_vec3){2 * uniform(&seed) - 1, 2 * uniform(&seed) - 1, 2 * uniform(&seed) - 1};
        }
        if (r.dir.x == 0 && r.dir.y == 0 && r.dir.z == 0) continue;
        const double tmax = k % 5 == 0 ? 2 * uniform(&seed) : INFINITY;
        hr_hit first;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &r, 0, tmax, &first, &found));
        CHECK_OK(hr_scene_all_hits(s, &r, 0, tmax, &all));
        CHECK_MSG(found == (all.count > 0), "ray %d: first hit found %d, all hits %d", k, (int)found,
                  (int)all.count);
        if (!found || all.count == 0) {
            misses++;
            continue;
        }
        /* The nearest t; among its hits the first added (hit_before's
         * order, all hits' first). */
        int32_t want = 0, at_t = 0;
        for (int32_t i = 0; i < all.count && all.hits[i].t == all.hits[0].t; i++) at_t++;
        ties += at_t > 1;
        cubes += all.hits[want].object < 64;
        planes += all.hits[want].object >= 64;
        CHECK_MSG(first.t == all.hits[want].t && first.object == all.hits[want].object,
                  "ray %d: first hit t = %.17g object %lld, want t = %.17g object %lld", k, first.t,
                  (long long)first.object, all.hits[want].t, (long long)all.hits[want].object);
    }
    /* Each case is met often: ties, cubes in front, planes, and no hit. */
    CHECK_MSG(ties > 1000 && cubes > 300 && planes > 1000 && misses > 100,
              "%d ties, %d cubes, %d planes, %d misses", ties, cubes, planes, misses);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* A shape that reports 1,000 crossings of the plane-like slab z = 1000 - i,
 * listed far to near, after asking host->reserve for the room. */
typedef struct many {
    const hr_host *host;
} many;

static hr_status many_create(const hr_create_args *a, void **out)
{
    many *m = a->host->alloc(sizeof *m);
    if (!m) return HR_ERROR_OUT_OF_MEMORY;
    m->host = a->host;
    *out = m;
    return HR_OK;
}

static void many_destroy(void *shape)
{
    many *m = shape;
    m->host->free(m);
}

static void many_bounds(const void *shape, hr_bounds *b)
{
    (void)shape;
    b->lo = (hr_vec3){-1, -1, 0};
    b->hi = (hr_vec3){1, 1, 1001};
}

static hr_status many_hit(const hr_hit_args *a)
{
    const many *m = a->shape;
    hr_status st = m->host->reserve(a->call, a->out, a->out->count + 1000);
    if (st) return st;
    for (int i = 0; i < 1000; i++) {
        double z = 1000 - i;
        if (a->ray.dir.z == 0) break;
        double t = (z - a->ray.origin.z) / a->ray.dir.z;
        if (!(t > a->tmin && t < a->tmax)) continue;
        hr_hit *h = &a->out->hits[a->out->count++];
        memset(h, 0, sizeof *h);
        h->t = t;
        h->point = (hr_vec3){a->ray.origin.x + t * a->ray.dir.x, a->ray.origin.y + t * a->ray.dir.y, z};
        h->normal = (hr_vec3){0, 0, 1};
        h->entering = 1;
    }
    return HR_OK;
}

static const hr_shape_class many_class = {
    sizeof(hr_shape_class), 0, "manyHits", "1000 hits, far to near, after host->reserve",
    NULL, 0, 1, many_create, many_destroy, many_bounds, many_hit, many_hit, many_hit, NULL, NULL, NULL, 0,
};

static void growing_list_keeps_every_hit(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    CHECK(tb_add(s, "manyHits", NULL, NULL) >= 0);
    CHECK_OK(hr_scene_commit(s));
    const hr_ray down = {{0, 0, 2000}, {0, 0, -1}};
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    /* The nearest of the 1000 is z = 1000, at t = 1000, listed first; the
     * farthest (z = 1) is listed last: all of them must have been kept. */
    CHECK_MSG(found && h.t == 1000.0, "found %d at t = %g, expected t = 1000", (int)found, h.t);
    const hr_ray up = {{0, 0, -5}, {0, 0, 1}};
    CHECK_OK(hr_scene_first_hit(s, &up, 0, INFINITY, &h, &found));
    CHECK_MSG(found && h.t == 6.0, "found %d at t = %g, expected t = 6 (z = 1, listed last)",
              (int)found, h.t);
    hr_scene_destroy(s);
}

/* A ray from 2e103 away (the nff fuzz input far_eye_cone_every_hit_box_culled.nff):
 * the NFF cone's own copy of the ray, rounded by 1e87 in the transform,
 * met the cone at t = 1.25, where the exact line is 5e32 from it. The
 * first hit, whose walk begins by testing the box around the BVH's objects
 * on the world ray, found nothing; the every-hit query, which traced each
 * object with no box, listed that hit. Both must give the same answer:
 * here none, the exact line's. */
static void far_ray_every_hit_culls_as_the_walk(void)
{
    const char *text = "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\n"
                       "resolution 8 8\nf 1 0.5 0.25 0.8 0.3 20 0.4 1.5\n"
                       "c 1 0 -1 2 3 0 1 0\n";
    hr_sdl_result r = {.struct_size = sizeof r};
    CHECK_OK(hr_nff_load_string(ctx, text, "far_eye_cone.nff", &r));
    CHECK_OK(hr_scene_commit(r.scene));
    const hr_ray ray = {{0x1.3d7f1a771dd02p+343, 0x1.b6418d0c06e3cp+110, 1.0},
                        {-0x1.fbfe90be9619dp+342, -0x1.b6418d0c06e3cp+110, -1.0}};
    hr_hit first;
    int32_t found = 1;
    CHECK_OK(hr_scene_first_hit(r.scene, &ray, 0, INFINITY, &first, &found));
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(r.scene, &ray, 0, INFINITY, &all));
    CHECK_MSG(found == 0 && all.count == 0, "first hit found %d, all hits %d (expected none)",
              (int)found, (int)all.count);
    /* A ray into the cone from nearby is still seen by both. */
    const hr_ray near = {{2, 0, 10}, {0, 0, -1}};
    CHECK_OK(hr_scene_first_hit(r.scene, &near, 0, INFINITY, &first, &found));
    CHECK_OK(hr_scene_all_hits(r.scene, &near, 0, INFINITY, &all));
    CHECK_MSG(found == 1 && all.count == 1 && first.t == all.hits[0].t,
              "near ray: first hit found %d, all hits %d", (int)found, (int)all.count);
    hr_intersection_release(&all);
    hr_scene_destroy(r.scene);
}

/* Eyes 1e12 to 2^64 away from the objects: the first hit must still be the
 * first of all hits, the same t and the same entering flag (and object).
 * Far away, the world ray's origin carries rounding of 1e-4 to 2e3 into
 * every object's copy of it, and the first-hit walk prunes by boxes the
 * every-hit query does not use in the same way: both must still agree on
 * what that rounded line meets. One object of each solid kind, rotated,
 * scaled unevenly and placed apart; rays from points at the distance in
 * random directions, aimed at random points in and near an object (so that
 * most hit and some graze). */
static void far_eyes_first_hit_is_first_of_all(void)
{
    static const char *const kinds[] = {"sphere",      "cube",       "cylinder",     "cone",
                                        "torus",       "octahedron", "taperedCylinder",
                                        "icosahedron", "tetrahedron", "buckyball"};
    const int n_kinds = (int)(sizeof kinds / sizeof kinds[0]);
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    uint64_t seed = 2024;
    hr_vec3 centre[sizeof kinds / sizeof kinds[0]];
    for (int i = 0; i < n_kinds; i++) {
        centre[i] = (hr_vec3){3.0 * (i % 4) - 4.5, 3.0 * (i / 4) - 3, 0.5 * (i % 3)};
        hr_transform t;
        hr_transform_identity(&t);
        hr_transform_translate(&t, centre[i].x, centre[i].y, centre[i].z);
        const double ax = uniform(&seed) - 0.5, ay = uniform(&seed) - 0.5;
        CHECK_OK(hr_transform_rotate(&t, 360 * uniform(&seed), ax, ay, 1));
        CHECK_OK(hr_transform_scale(&t, 0.5 + uniform(&seed), 0.5 + uniform(&seed),
                                    0.5 + uniform(&seed)));
        CHECK(tb_add(s, kinds[i], NULL, &t) >= 0);
    }
    CHECK_OK(hr_scene_commit(s));
    hr_intersection all;
    hr_intersection_init(&all);
    int rays = 0, hits = 0;
    for (int k = 0; k < 40000; k++) {
        /* log-uniform distance in [1e12, 2^64] */
        const double distance = 1e12 * pow(0x1p64 / 1e12, uniform(&seed));
        hr_vec3 u = {2 * uniform(&seed) - 1, 2 * uniform(&seed) - 1, 2 * uniform(&seed) - 1};
        const double len = sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
        if (len < 0.1 || len > 1) continue;
        const hr_vec3 c = centre[k % n_kinds];
        const hr_vec3 aim = {c.x + 3 * uniform(&seed) - 1.5, c.y + 3 * uniform(&seed) - 1.5,
                             c.z + 3 * uniform(&seed) - 1.5};
        hr_ray r;
        r.origin = (hr_vec3){c.x + distance * u.x / len, c.y + distance * u.y / len,
                             c.z + distance * u.z / len};
        r.dir = (hr_vec3){aim.x - r.origin.x, aim.y - r.origin.y, aim.z - r.origin.z};
        if (k % 3 == 1) { /* unit directions too, so t is the distance */
            const double d = sqrt(r.dir.x * r.dir.x + r.dir.y * r.dir.y + r.dir.z * r.dir.z);
            r.dir = (hr_vec3){r.dir.x / d, r.dir.y / d, r.dir.z / d};
        }
        hr_hit first;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, &first, &found));
        CHECK_OK(hr_scene_all_hits(s, &r, 0, INFINITY, &all));
        rays++;
        CHECK_MSG(found == (all.count > 0),
                  "ray (%a, %a, %a) + t (%a, %a, %a): first hit found %d, all hits %d",
                  r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, (int)found,
                  (int)all.count);
        if (!found || all.count == 0) continue;
        hits++;
        const hr_hit *h = &all.hits[0];
        CHECK_MSG(first.t == h->t && first.entering == h->entering && first.object == h->object,
                  "ray (%a, %a, %a) + t (%a, %a, %a): first hit t = %a entering %d object %lld, "
                  "first of all t = %a entering %d object %lld (%d hits)",
                  r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, first.t,
                  (int)first.entering, (long long)first.object, h->t, (int)h->entering,
                  (long long)h->object, (int)all.count);
    }
    CHECK_MSG(rays > 20000 && hits > rays / 4, "%d rays, %d hit", rays, hits);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_register_shape_class(ctx, &many_class, "test_first_hit_paths.c"));
    bvh_walk_matches_every_hit();
    planes_after_the_walk_keep_the_tie_rule();
    growing_list_keeps_every_hit();
    far_ray_every_hit_culls_as_the_walk();
    far_eyes_first_hit_is_first_of_all();
    hr_context_destroy(ctx);
    return hr_test_end();
}
