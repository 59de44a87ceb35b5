/* CSG through the whole library: booleans nested three deep, read from SDL
 * with the real shape modules, hit-tested through the public queries; each
 * hit names its leaf (for its material) and the subtracted sphere's surface
 * shows with its normal turned to the viewer. Shadows go through the same
 * booleans: light falls through a hole drilled in a sphere and nowhere else
 * under it. Composites nested past HR_MAX_COMPOSITE_DEPTH are refused, and a
 * chain of exactly that depth traces on the render threads. An open surface
 * as an operand is refused where the boolean is written. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_scene *load(hr_context *ctx, const char *text)
{
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    if (hr_sdl_load_string(ctx, text, "csg.sdl", NULL, &r) != HR_OK) {
        CHECK_MSG(0, "load: %s", hr_context_last_error(ctx));
        return NULL;
    }
    CHECK_OK(hr_scene_commit(r.scene));
    return r.scene;
}

/* ((A | B) - bite) & slab: A the unit sphere (red, object 0), B a unit
 * sphere at z = 0.5 (object 1), the bite a sphere of radius 0.5 at z = 1.2
 * (blue, object 3), the slab a cube moved to z in [-1.1, 0.9] (object 5).
 * Along the z axis the solid is z in [-1, 0.7]: it ends at the bite. */
static const char nested[] =
    "diffuse 1 0 0\n"
    "intersection\n"
    "  difference\n"
    "    union\n"
    "      sphere\n"
    "      push translate 0 0 0.5 diffuse 0 1 0 sphere pop\n"
    "    push translate 0 0 1.2 scale .5 .5 .5 diffuse 0 0 1 sphere pop\n"
    "  push translate 0 0 -0.1 cube pop\n";

static void test_nested(hr_context *ctx)
{
    hr_scene *s = load(ctx, nested);
    if (!s) return;
    CHECK(hr_scene_object_count(s) == 7);
    static const char *const shapes[] = {"sphere", "sphere", "union", "sphere",
                                         "difference", "cube", "intersection"};
    for (int64_t i = 0; i < 7; i++) {
        hr_object_info o = tb_object_info(s, i);
        CHECK_MSG(strcmp(o.shape, shapes[i]) == 0, "object %lld is %s", (long long)i, o.shape);
        CHECK(o.top_level == (i == 6));
    }

    hr_intersection list;
    hr_intersection_init(&list);
    /* Up the axis from z = -5. */
    hr_ray up = {{0, 0, -5}, {0, 0, 1}};
    CHECK_OK(hr_scene_all_hits(s, &up, 0, INFINITY, &list));
    CHECK_MSG(list.count == 2, "%d hits going up", (int)list.count);
    if (list.count == 2) {
        /* 0.7 is 1.2 - 0.5 through a rounded transform: a few ulps. */
        CHECK_NEAR(list.hits[0].t, 4.0, 1e-14);
        CHECK(list.hits[0].object == 0 && list.hits[0].entering == 1 && list.hits[0].normal.z < 0);
        CHECK_NEAR(list.hits[1].t, 5.7, 1e-14);
        /* Leaving into the bite: its surface, its normal (-z) turned to +z. */
        CHECK(list.hits[1].object == 3 && list.hits[1].entering == 0);
        CHECK_NEAR(list.hits[1].normal.z, 1.0, 1e-15);
    }
    /* Down the axis from z = 5: the first thing seen is the inside of the
     * bite, blue, facing the eye. */
    hr_ray down = {{0, 0, 5}, {0, 0, -1}};
    CHECK_OK(hr_scene_all_hits(s, &down, 0, INFINITY, &list));
    CHECK_MSG(list.count == 2, "%d hits going down", (int)list.count);
    hr_hit first;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &first, &found));
    CHECK(found == 1);
    if (found && list.count == 2) {
        CHECK(memcmp(&first, &list.hits[0], sizeof first) == 0);
        CHECK_NEAR(first.t, 4.3, 1e-14);
        CHECK(first.object == 3 && first.entering == 1);
        CHECK_NEAR(first.normal.z, 1.0, 1e-15);
        hr_object_info bite = tb_object_info(s, first.object);
        CHECK(bite.material.diffuse.b == 1 && bite.material.diffuse.r == 0);
        CHECK(list.hits[1].object == 0 && list.hits[1].entering == 0);
        CHECK_NEAR(list.hits[1].t, 6.0, 1e-14);
    }
    /* Sideways at z = 0.95: inside A and B, but above the slab: nothing. */
    hr_ray side = {{-5, 0, 0.95}, {1, 0, 0}};
    CHECK_OK(hr_scene_all_hits(s, &side, 0, INFINITY, &list));
    CHECK_MSG(list.count == 0, "%d hits above the slab", (int)list.count);
    /* Sideways at z = -0.5: B's equator; A is left at x = +-sqrt(0.75). */
    hr_ray low = {{-5, 0, -0.5}, {1, 0, 0}};
    CHECK_OK(hr_scene_all_hits(s, &low, 0, INFINITY, &list));
    CHECK_MSG(list.count == 2, "%d hits at z = -0.5", (int)list.count);
    if (list.count == 2) {
        CHECK_NEAR(list.hits[0].t, 5 - sqrt(0.75), 1e-14);
        CHECK_NEAR(list.hits[1].t, 5 + sqrt(0.75), 1e-14);
        CHECK(list.hits[0].object == 0 && list.hits[1].object == 0);
    }
    hr_intersection_release(&list);
    hr_scene_destroy(s);
}

/* A sphere with a vertical hole of radius 0.3 drilled through it, over a
 * floor, lit from straight above. */
static const char drilled[] =
    "globalAmbient 0.1 0.1 0.1\n"
    "light 0 10 0  1 1 1\n"
    "difference\n"
    "  sphere\n"
    "  push rotate -90 1 0 0 translate 0 0 -2 scale .3 .3 4 cylinder pop\n"
    "push translate 0 -2 0 scale 5 .1 5 ambient .1 .1 .1 diffuse .8 .8 .8 cube pop\n";

static double floor_brightness(hr_context *ctx, const hr_scene *s, double x, double z)
{
    /* Straight down onto the floor's top (y = -1.9), from just above it. */
    hr_ray ray = {{x, -1.85, z}, {0, -1, 0}};
    hr_color c = {0, 0, 0};
    hr_status st = hr_scene_shade(s, &ray, 0, &c);
    CHECK_MSG(st == HR_OK, "shade: %s", hr_context_last_error(ctx));
    return c.r;
}

static void test_shadows(hr_context *ctx)
{
    hr_scene *s = load(ctx, drilled);
    if (!s) return;
    CHECK(hr_scene_effects(s) & HR_EFFECT_SHADOWS);
    /* Lit: ambient 0.1 * 0.1 + diffuse 0.8 * (cos 0 = 1); shadowed: 0.01. */
    const double lit = 0.81, dark = 0.01;
    /* Under the hole the light comes through. */
    CHECK_NEAR(floor_brightness(ctx, s, 0, 0), lit, 1e-9);
    CHECK_NEAR(floor_brightness(ctx, s, 0.1, -0.1), lit, 1e-3);
    /* Under the ring around it, the sphere casts its shadow. */
    CHECK_NEAR(floor_brightness(ctx, s, 0.6, 0), dark, 1e-9);
    CHECK_NEAR(floor_brightness(ctx, s, 0, -0.7), dark, 1e-9);
    /* Outside the sphere's shadow, lit again (almost straight on). */
    CHECK_NEAR(floor_brightness(ctx, s, 1.5, 0), lit, 0.02);
    hr_scene_destroy(s);
}

/* HR_MAX_COMPOSITE_DEPTH unions in a chain, spheres 3 apart along z: it
 * builds, renders on two threads and gives every hit; one more is refused,
 * naming the parameter. */
static void test_depth_limit(hr_context *ctx)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_object_desc leaf = {0};
    leaf.struct_size = sizeof leaf;
    leaf.shape = "sphere";
    int64_t chain = -1;
    CHECK_OK(hr_scene_add_object(s, &leaf, &chain));
    for (int i = 1; i <= HR_MAX_COMPOSITE_DEPTH + 1; i++) {
        double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 3.0 * i, 0, 0, 0, 1};
        hr_object_desc d = leaf;
        d.transform = m;
        int64_t sphere;
        CHECK_OK(hr_scene_add_object(s, &d, &sphere));
        hr_param p[2] = {{.name = "a", .type = HR_PARAM_OBJECT, .number = 0, .string = NULL, .object = chain},
                         {.name = "b", .type = HR_PARAM_OBJECT, .number = 0, .string = NULL, .object = sphere}};
        hr_object_desc u = {0};
        u.struct_size = sizeof u;
        u.shape = "union";
        u.params = p;
        u.param_count = 2;
        hr_status st = hr_scene_add_object(s, &u, &chain);
        if (i <= HR_MAX_COMPOSITE_DEPTH) {
            CHECK_MSG(st == HR_OK, "depth %d: %s", i, hr_context_last_error(ctx));
        } else {
            CHECK(st == HR_ERROR_PARAMETER);
            CHECK_MSG(strstr(hr_context_last_error(ctx), "parameter 'a'") &&
                          strstr(hr_context_last_error(ctx), "deep"),
                      "message: %s", hr_context_last_error(ctx));
        }
    }
    CHECK_OK(hr_scene_commit(s));
    hr_intersection list;
    hr_intersection_init(&list);
    hr_ray ray = {{0, 0, -5}, {0, 0, 1}};
    CHECK_OK(hr_scene_all_hits(s, &ray, 0, INFINITY, &list));
    /* The chain's spheres, and the last sphere on its own (the union that
     * would have taken it was refused). */
    CHECK_MSG(list.count == 2 * (HR_MAX_COMPOSITE_DEPTH + 2), "%d hits", (int)list.count);
    hr_intersection_release(&list);
    /* Looking down the chain from its end: every pixel traces it on a
     * render thread. */
    hr_camera cam;
    hr_camera_default(&cam);
    cam.eye = (hr_vec3){0, 0, -10};
    cam.look = (hr_vec3){0, 0, 0};
    cam.up = (hr_vec3){0, 1, 0};
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = 16, o.height = 12, o.threads = 2;
    hr_image *img = NULL;
    CHECK_MSG(hr_render(s, &cam, &o, &img, NULL) == HR_OK, "render: %s", hr_context_last_error(ctx));
    hr_image_destroy(img);
    hr_scene_destroy(s);
}

/* An open surface as an operand is refused at the boolean's keyword. */
static void test_open_operand(hr_context *ctx)
{
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    hr_status st = hr_sdl_load_string(ctx, "sphere\n  difference sphere plane", "open.sdl", NULL, &r);
    CHECK(st == HR_ERROR_PARAMETER && r.scene == NULL);
    const char *m = hr_context_last_error(ctx);
    CHECK_MSG(strstr(m, "open.sdl:2:3") && strstr(m, "parameter 'b'") && strstr(m, "'plane'"),
              "message: %s", m);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    test_nested(ctx);
    test_shadows(ctx);
    test_depth_limit(ctx);
    test_open_operand(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
