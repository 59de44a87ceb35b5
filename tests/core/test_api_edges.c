/* Edges of the public calls: a depth given to a query or a render overrides
 * the scene's maxRecursionDepth both ways, transforms whose inverse (or
 * product) is not representable are refused, hr_camera_ray refuses what
 * cannot make a ray, and a shape directory with no module in it is fine. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

/* A mirror sphere seen head on reflects the background straight back. */
static hr_scene *mirror_scene(int32_t scene_depth)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material mirror = tb_black();
    mirror.reflectivity = 1;
    CHECK(tb_add(s, "sphere", &mirror, NULL) >= 0);
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.global_ambient = (hr_color){0, 0, 0};
    g.background = (hr_color){0.25, 0.5, 0.75};
    g.max_recursion_depth = scene_depth;
    CHECK_OK(hr_scene_set_globals(s, &g));
    CHECK_OK(hr_scene_commit(s));
    return s;
}

/* hr_scene_shade's max_depth and hr_render_options.max_depth override the
 * scene's depth: a scene saved with depth 0 still reflects when asked for
 * depth 2, and the render statistics say which effects actually ran. */
static void depth_override(void)
{
    hr_scene *s = mirror_scene(0);
    hr_ray r = {{0, 0, 5}, {0, 0, -1}};
    hr_color c;
    CHECK_OK(hr_scene_shade(s, &r, -1, &c));
    CHECK(c.r == 0 && c.g == 0 && c.b == 0); /* the scene's depth 0: no bounce */
    CHECK_OK(hr_scene_shade(s, &r, 2, &c));
    CHECK_MSG(fabs(c.b - 0.75) < 1e-12, "depth 2 on a depth-0 scene: (%g %g %g), expected the "
              "background (0.25 0.5 0.75)", c.r, c.g, c.b);

    hr_camera cam;
    hr_camera_default(&cam);
    cam.width = cam.height = 8;
    cam.view_angle = 1; /* every pixel sees the sphere's front */
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    o.max_depth = 2;
    hr_image *img = NULL;
    hr_render_stats st;
    memset(&st, 0, sizeof st);
    st.struct_size = sizeof st;
    CHECK_OK(hr_render(s, &cam, &o, &img, &st));
    if (img) {
        const float *px = hr_image_data(img);
        CHECK_MSG(fabs(px[2] - 0.75) < 1e-6, "render at depth 2: blue %g, expected 0.75", px[2]);
        hr_image_destroy(img);
    }
    CHECK(st.reflected > 0);
    CHECK((st.effects & HR_EFFECT_REFLECTION) != 0);
    hr_scene_destroy(s);

    /* The other way: depth 0 asked of a depth-3 scene casts no reflected ray,
     * and the statistics do not claim reflection ran. */
    s = mirror_scene(3);
    o.max_depth = 0;
    img = NULL;
    CHECK_OK(hr_render(s, &cam, &o, &img, &st));
    hr_image_destroy(img);
    CHECK(st.reflected == 0);
    CHECK_MSG((st.effects & HR_EFFECT_REFLECTION) == 0, "effects 0x%x claim reflection at depth 0",
              (unsigned)st.effects);
    hr_scene_destroy(s);
}

/* hr_scene_shade: "the ray's direction need not be unit length" -- any
 * finite non-zero length gives the colour the unit direction gives. */
static void shade_any_direction_length(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material m;
    hr_material_default(&m);
    m.specular = (hr_color){0.5, 0.5, 0.5};
    m.specular_exponent = 10;
    m.reflectivity = 0.5;
    CHECK(tb_add(s, "sphere", &m, NULL) >= 0);
    tb_light(s, 3, 4, 10, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    hr_ray r = {{0.3, 0.2, 5}, {-0.05, -0.03, -1}};
    hr_color want, got;
    CHECK_OK(hr_scene_shade(s, &r, -1, &want));
    CHECK(want.r > 0.2); /* lit, not the background */
    const double lengths[] = {1e-200, 1e-160, 1e160, 1e200};
    for (int i = 0; i < 4; i++) {
        hr_ray q = {r.origin, {r.dir.x * lengths[i], r.dir.y * lengths[i], r.dir.z * lengths[i]}};
        CHECK_OK(hr_scene_shade(s, &q, -1, &got));
        CHECK_MSG(fabs(got.r - want.r) < 1e-12 && fabs(got.g - want.g) < 1e-12 &&
                      fabs(got.b - want.b) < 1e-12,
                  "direction length %g: (%g %g %g), unit length gives (%g %g %g)", lengths[i],
                  got.r, got.g, got.b, want.r, want.g, want.b);
    }
    hr_scene_destroy(s);
}

static int all_finite(const double m[16])
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(m[i])) return 0;
    return 1;
}

/* A factor whose reciprocal overflows has no representable inverse: it is
 * refused, as a zero factor is, and leaves the transform as it was. */
static void unrepresentable_transforms(void)
{
    hr_transform t;
    hr_transform_identity(&t);
    CHECK(hr_transform_scale(&t, 1e-310, 1, 1) == HR_ERROR_NUMERIC);
    CHECK(all_finite(t.m) && all_finite(t.inv));
    CHECK(t.m[0] == 1 && t.inv[0] == 1);

    /* Uniformly tiny: well conditioned, but the inverse (1e310) overflows. */
    double m[16] = {1e-310, 0, 0, 0, 0, 1e-310, 0, 0, 0, 0, 1e-310, 0, 0, 0, 0, 1};
    hr_transform_identity(&t);
    hr_status st = hr_transform_from_matrix(&t, m);
    CHECK_MSG(st == HR_ERROR_NUMERIC, "from_matrix returned %d, inverse[0] = %g", (int)st, t.inv[0]);

    /* The same matrix given to a scene without its inverse. */
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "sphere";
    d.transform = m;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_NUMERIC);
    CHECK(hr_scene_object_count(s) == 0);
    hr_scene_destroy(s);
}

/* hr_camera_ray promises a unit direction: it refuses what cannot give one. */
static void camera_ray_arguments(void)
{
    hr_camera cam;
    hr_camera_default(&cam);
    hr_ray r;
    CHECK_OK(hr_camera_ray(&cam, 320, 240, &r));
    CHECK(hr_camera_ray(&cam, NAN, 240, &r) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_camera_ray(&cam, 320, INFINITY, &r) == HR_ERROR_INVALID_ARGUMENT);
    cam.view_angle = NAN;
    CHECK(hr_camera_ray(&cam, 320, 240, &r) == HR_ERROR_INVALID_ARGUMENT);
    cam.view_angle = 200;
    CHECK(hr_camera_ray(&cam, 320, 240, &r) == HR_ERROR_INVALID_ARGUMENT);
    hr_camera_default(&cam);
    cam.eye.x = INFINITY;
    CHECK(hr_camera_ray(&cam, 320, 240, &r) == HR_ERROR_INVALID_ARGUMENT);
}

/* A search directory that holds no module is searched without complaint. */
static void empty_shape_dir(void)
{
    char dir[] = "/tmp/hitray-empty-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    hr_context *c;
    CHECK_OK(hr_context_create(&c));
    CHECK_OK(hr_context_add_shape_dir(c, dir));
    const hr_shape_class *cls;
    CHECK(hr_context_find_shape_class(c, "noSuchShape", &cls, NULL) == HR_ERROR_MODULE);
    CHECK_OK(hr_context_find_shape_class(c, "sphere", &cls, NULL));
    hr_context_destroy(c);
    rmdir(dir);
}

/* A look-up answers as a fresh search would after every change to the
 * classes (the context remembers its last answer): a class registered
 * under a loaded class's name is found in its place, on the next look-up. */
static void class_lookup_after_registration(void)
{
    hr_context *c;
    CHECK_OK(hr_context_create(&c));
    const hr_shape_class *sphere, *found, *cube;
    const char *origin = NULL;
    CHECK_OK(hr_context_find_shape_class(c, "sphere", &sphere, &origin));
    CHECK_OK(hr_context_find_shape_class(c, "sphere", &found, NULL));
    CHECK(found == sphere);
    CHECK_OK(hr_context_find_shape_class(c, "cube", &cube, NULL));
    CHECK(cube != sphere && strcmp(cube->name, "cube") == 0);
    hr_shape_class mine = *sphere;
    CHECK_OK(hr_context_register_shape_class(c, &mine, "test_api_edges.c"));
    CHECK_OK(hr_context_find_shape_class(c, "sphere", &found, &origin));
    CHECK(found != sphere && strcmp(found->name, "sphere") == 0);
    CHECK(origin && strcmp(origin, "test_api_edges.c") == 0);
    CHECK_OK(hr_context_find_shape_class(c, "cube", &found, NULL));
    CHECK(found == cube);
    hr_context_destroy(c);
}

/* An error callback may call back into its context (list the modules, say)
 * for every error, including those raised while the context looks up,
 * loads or registers shape classes. (A deadlock ends the test by alarm.) */
static int32_t modules_seen = -1;
static void listing_callback(void *user, hr_status status, const char *message)
{
    (void)status, (void)message;
    modules_seen = hr_context_module_count(user);
}

static void reentrant_error_callback(void)
{
    hr_context *c;
    CHECK_OK(hr_context_create(&c));
    hr_context_set_error_callback(c, listing_callback, c);
    alarm(20);
    const hr_shape_class *cls;
    CHECK(hr_context_find_shape_class(c, "noSuchShape", &cls, NULL) == HR_ERROR_MODULE);
    CHECK(modules_seen > 0);
    modules_seen = -1;
    CHECK(hr_context_load_module(c, "/nonexistent/dir/none.so") == HR_ERROR_MODULE);
    CHECK(modules_seen > 0);
    hr_shape_class broken = {0};
    broken.struct_size = sizeof broken;
    modules_seen = -1;
    CHECK(hr_context_register_shape_class(c, &broken, "test_api_edges.c") == HR_ERROR_MODULE);
    CHECK(modules_seen > 0);
    alarm(0);
    hr_context_destroy(c);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    depth_override();
    shade_any_direction_length();
    unrepresentable_transforms();
    camera_ray_arguments();
    empty_shape_dir();
    class_lookup_after_registration();
    reentrant_error_callback();
    hr_context_destroy(ctx);
    return hr_test_end();
}
