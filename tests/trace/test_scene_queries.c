/* Hill's queries through whole scenes: getFirstHit and the Intersection of
 * every hit, with objects under translation, rotation and non-uniform scale
 * (normals through the inverse transpose), hand-worked. */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *ctx;

static hr_scene *new_scene(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    return s;
}

static void add(hr_scene *s, const char *shape, const hr_transform *t)
{
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = shape;
    d.transform = t ? t->m : NULL;
    d.inverse = t ? t->inv : NULL;
    CHECK_MSG(hr_scene_add_object(s, &d, NULL) == HR_OK, "add %s: %s", shape, hr_context_last_error(ctx));
}

static int first(hr_scene *s, hr_vec3 o, hr_vec3 dir, hr_hit *h)
{
    hr_ray r = {o, dir};
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, h, &found));
    return found;
}

/* Hill's worked example: (4,1,3) + (-3,-5,-3) t meets z = 0 at t = 1,
 * point (1,-4,0). */
static void plane_example(void)
{
    hr_scene *s = new_scene();
    add(s, "plane", NULL);
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    CHECK(first(s, (hr_vec3){4, 1, 3}, (hr_vec3){-3, -5, -3}, &h));
    CHECK_NEAR(h.t, 1.0, 0.0);
    CHECK_NEAR(h.point.x, 1.0, 1e-15);
    CHECK_NEAR(h.point.y, -4.0, 1e-15);
    CHECK_NEAR(h.point.z, 0.0, 1e-15);
    CHECK_NEAR(h.normal.z, 1.0, 0.0);
    CHECK(h.entering == 1 && h.object == 0);
    hr_scene_destroy(s);
}

/* translate 2 4 9 scale 1 4 4 sphere: an ellipsoid centred (2,4,9) with
 * semi-axes (1,4,4). */
static void ellipsoid(void)
{
    hr_scene *s = new_scene();
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, 2, 4, 9);
    hr_transform_scale(&t, 1, 4, 4);
    add(s, "sphere", &t);
    CHECK_OK(hr_scene_commit(s));
    /* Down the z axis through the centre: z = 13 at t = 7, z = 5 at t = 15. */
    hr_ray r = {{2, 4, 20}, {0, 0, -1}};
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &r, 0, INFINITY, &all));
    CHECK(all.count == 2);
    if (all.count == 2) {
        CHECK_NEAR(all.hits[0].t, 7, 1e-14);
        CHECK_NEAR(all.hits[1].t, 15, 1e-14);
        CHECK(all.hits[0].entering == 1 && all.hits[1].entering == 0);
        CHECK_NEAR(all.hits[0].normal.z, 1, 1e-15);
        CHECK_NEAR(all.hits[1].normal.z, -1, 1e-15);
    }
    /* The object point (0, 1, 1)/sqrt2 maps to (2, 4 + 2sqrt2, 9 + 2sqrt2);
     * its object normal (0,1,1) goes through M^-T = diag(1, 1/4, 1/4) to
     * (0, 1/4, 1/4): the unit world normal is (0, 1, 1)/sqrt2 — not the
     * direction from the centre scaled, which a naive M n would give. A ray
     * coming straight down that normal hits it at t = 10. */
    double q = 2.0 * sqrt(2.0), k = 1.0 / sqrt(2.0);
    hr_hit h;
    CHECK(first(s, (hr_vec3){2, 4 + q + 10 * k, 9 + q + 10 * k}, (hr_vec3){0, -k, -k}, &h));
    CHECK_NEAR(h.t, 10, 1e-13);
    CHECK_NEAR(h.normal.x, 0, 1e-15);
    CHECK_NEAR(h.normal.y, k, 1e-14);
    CHECK_NEAR(h.normal.z, k, 1e-14);
    /* tmin and tmax are exclusive bounds on t. */
    r.origin = (hr_vec3){2, 4, 20};
    CHECK_OK(hr_scene_all_hits(s, &r, 7, 15, &all));
    CHECK(all.count == 0);
    CHECK_OK(hr_scene_all_hits(s, &r, 6.5, 15.5, &all));
    CHECK(all.count == 2);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* rotate 90 about z after scale 2 1 1: the long axis ends up along y. */
static void rotated_scaled(void)
{
    hr_scene *s = new_scene();
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_rotate(&t, 90, 0, 0, 1);
    hr_transform_scale(&t, 2, 1, 1);
    add(s, "sphere", &t);
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    CHECK(first(s, (hr_vec3){0, -10, 0}, (hr_vec3){0, 1, 0}, &h));
    CHECK_NEAR(h.t, 8, 1e-14);
    CHECK_NEAR(h.normal.y, -1, 1e-15);
    CHECK(first(s, (hr_vec3){-10, 0, 0}, (hr_vec3){1, 0, 0}, &h));
    CHECK_NEAR(h.t, 9, 1e-14);
    CHECK_NEAR(h.normal.x, -1, 1e-15);
    hr_scene_destroy(s);
}

/* Several objects: every hit sorted, each naming its object; the cube's
 * faces as surfaces; a ray inside a solid starts with an exit. */
static void several(void)
{
    hr_scene *s = new_scene();
    hr_transform a, b;
    hr_transform_identity(&a);
    hr_transform_translate(&a, 0, 0, -5);
    hr_transform_identity(&b);
    hr_transform_translate(&b, 0, 0, 5);
    add(s, "cube", &a);   /* object 0: z in [-6, -4] */
    add(s, "sphere", &b); /* object 1: z in [4, 6] */
    add(s, "sphere", NULL); /* object 2: z in [-1, 1] */
    CHECK_OK(hr_scene_commit(s));
    hr_ray r = {{0, 0, 10}, {0, 0, -1}};
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &r, 0, INFINITY, &all));
    CHECK(all.count == 6);
    const double t[6] = {4, 6, 9, 11, 14, 16};
    const int64_t obj[6] = {1, 1, 2, 2, 0, 0};
    for (int i = 0; i < all.count && i < 6; i++) {
        CHECK_NEAR(all.hits[i].t, t[i], 1e-14);
        CHECK(all.hits[i].object == obj[i]);
        CHECK(all.hits[i].entering == (i % 2 == 0));
    }
    if (all.count == 6) {
        CHECK(all.hits[4].surface == 4); /* +z face */
        CHECK(all.hits[5].surface == 5); /* -z face */
    }
    hr_hit h;
    CHECK(first(s, (hr_vec3){0, 0, 0}, (hr_vec3){0, 0, -1}, &h));
    CHECK(h.object == 2 && h.entering == 0);
    CHECK_NEAR(h.t, 1, 1e-15);
    hr_intersection_release(&all);

    /* The scene's bounds and the framed camera see every object. */
    hr_bounds bb;
    int32_t found;
    CHECK_OK(hr_scene_bounds(s, &bb, &found));
    CHECK(found && bb.lo.z <= -6 && bb.hi.z >= 6);
    hr_camera cam;
    hr_camera_default(&cam);
    CHECK_OK(hr_scene_frame_camera(s, &cam));
    CHECK_OK(hr_camera_validate(ctx, &cam));
    hr_scene_destroy(s);
}

/* Objects scaled to the ends of the double range: the object-space
 * direction is ~1e300 or ~1e-160 long, so a shape's d.d would overflow or go
 * subnormal. The host rescales it by a power of two; t comes back exact.
 * References: a sphere of radius r at the origin, ray from z = -10 r along
 * +z, meets it at t = 9 r and 11 r (r * 9 is one rounding: 1 ulp). */
static void extreme_scales(void)
{
    const double radii[3] = {1e-300, 1e160, 0x1p-1000};
    for (int i = 0; i < 3; i++) {
        double r = radii[i];
        hr_scene *s = new_scene();
        hr_transform t;
        hr_transform_identity(&t);
        CHECK_OK(hr_transform_scale(&t, r, r, r));
        add(s, "sphere", &t);
        CHECK_OK(hr_scene_commit(s));
        hr_ray ray = {{0, 0, -10 * r}, {0, 0, 1}};
        hr_intersection all;
        hr_intersection_init(&all);
        CHECK_OK(hr_scene_all_hits(s, &ray, 0, INFINITY, &all));
        CHECK_MSG(all.count == 2, "radius %g: %d hits", r, (int)all.count);
        if (all.count == 2) {
            CHECK_MSG(hr_test_ulps(all.hits[0].t, 9 * r) <= 4, "radius %g: t0 %.17g", r, all.hits[0].t);
            CHECK_MSG(hr_test_ulps(all.hits[1].t, 11 * r) <= 4, "radius %g: t1 %.17g", r, all.hits[1].t);
            CHECK_NEAR(all.hits[0].normal.z, -1, 1e-15);
        }
        hr_intersection_release(&all);
        hr_scene_destroy(s);
    }
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    extreme_scales();
    plane_example();
    ellipsoid();
    rotated_scaled();
    several();
    hr_context_destroy(ctx);
    return hr_test_end();
}
