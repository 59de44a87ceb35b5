/* Hill's shade() on scenes whose colours are worked out by hand. The
 * tolerances are a few ulps of the values (1e-12): each colour is a short sum
 * of products of exact inputs. */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

static hr_color shade(hr_scene *s, hr_vec3 o, hr_vec3 d)
{
    hr_ray r = {o, d};
    hr_color c = {-1, -1, -1};
    CHECK_OK(hr_scene_shade(s, &r, -1, &c));
    return c;
}

#define CHECK_RGB(c, R, G, B)                                                  \
    do {                                                                       \
        CHECK_NEAR((c).r, (R), 1e-12);                                         \
        CHECK_NEAR((c).g, (G), 1e-12);                                         \
        CHECK_NEAR((c).b, (B), 1e-12);                                         \
    } while (0)

/* ambient * globalAmbient, and the background on a miss. */
static void ambient_only(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.global_ambient = (hr_color){0.5, 0.5, 0.5};
    g.background = (hr_color){0.25, 0.5, 0.75};
    hr_scene_set_globals(s, &g);
    hr_material m = tb_black();
    m.ambient = (hr_color){0.2, 0.4, 0.6};
    m.diffuse = (hr_color){1, 1, 1}; /* no light: no diffuse term */
    tb_add(s, "sphere", &m, NULL);
    CHECK_OK(hr_scene_commit(s));
    CHECK(hr_scene_effects(s) == HR_EFFECT_AMBIENT);
    CHECK_RGB(shade(s, (hr_vec3){0, 0, 5}, (hr_vec3){0, 0, -1}), 0.1, 0.2, 0.3);
    CHECK_RGB(shade(s, (hr_vec3){0, 5, 5}, (hr_vec3){0, 0, -1}), 0.25, 0.5, 0.75);
    hr_scene_destroy(s);
}

/* One light head-on: s = m = h = (0,0,1), so diffuse and specular count in
 * full: colour = light * (diffuse + specular). Off-axis: Lambert's cosine. */
static void diffuse_head_on(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    tb_dark_globals(s, 3);
    hr_material m = tb_black();
    m.diffuse = (hr_color){0.5, 0.25, 1};
    m.specular = (hr_color){0.125, 0.125, 0.125};
    m.specular_exponent = 20;
    tb_add(s, "sphere", &m, NULL);
    tb_light(s, 0, 0, 10, 1, 0.5, 1);
    CHECK_OK(hr_scene_commit(s));
    CHECK(hr_scene_effects(s) == (HR_EFFECT_DIFFUSE | HR_EFFECT_SPECULAR | HR_EFFECT_SHADOWS));
    CHECK_RGB(shade(s, (hr_vec3){0, 0, 5}, (hr_vec3){0, 0, -1}), 0.625, 0.1875, 1.125);
    hr_scene_destroy(s);

    /* A plane lit from (0,0,10), seen at the point (5,0,0): s = (-5,0,10)/
     * sqrt(125), s.m = 10/sqrt(125); no specular. */
    hr_scene_create(ctx, &s);
    tb_dark_globals(s, 3);
    m = tb_black();
    m.diffuse = (hr_color){1, 1, 1};
    tb_add(s, "plane", &m, NULL);
    tb_light(s, 0, 0, 10, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    double lambert = 10.0 / sqrt(125.0);
    CHECK_RGB(shade(s, (hr_vec3){5, 0, 3}, (hr_vec3){0, 0, -1}), lambert, lambert, lambert);
    /* Seen from below, the light is on the other side: only ambient (0). */
    CHECK_RGB(shade(s, (hr_vec3){5, 0, -3}, (hr_vec3){0, 0, 1}), 0, 0, 0);
    hr_scene_destroy(s);
}

/* A sphere between the light and the plane's origin shades it. */
static void in_shadow(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.global_ambient = (hr_color){1, 1, 1};
    hr_scene_set_globals(s, &g);
    hr_material m = tb_black();
    m.ambient = (hr_color){0.1, 0.1, 0.1};
    m.diffuse = (hr_color){1, 1, 1};
    tb_add(s, "plane", &m, NULL);
    hr_transform t = tb_place(0, 0, 5, 1);
    tb_add(s, "sphere", &m, &t);
    tb_light(s, 0, 0, 10, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    /* (0,0,0) is behind the sphere: ambient only. */
    CHECK_RGB(shade(s, (hr_vec3){3, 0, 3}, (hr_vec3){-1, 0, -1}), 0.1, 0.1, 0.1);
    /* (5,0,0) sees the light past the sphere. */
    double lambert = 10.0 / sqrt(125.0);
    CHECK_RGB(shade(s, (hr_vec3){5, 0, 3}, (hr_vec3){0, 0, -1}), 0.1 + lambert, 0.1 + lambert,
              0.1 + lambert);
    hr_scene_destroy(s);
}

/* A mirror plane shows an emissive sphere: reflectivity * emissive. A
 * reflectivity below minReflectivity spawns no ray and adds nothing. */
static void mirror(void)
{
    for (int below = 0; below < 2; below++) {
        hr_scene *s;
        hr_scene_create(ctx, &s);
        tb_dark_globals(s, 3);
        hr_material mirror_m = tb_black();
        mirror_m.reflectivity = below ? 0.4 : 0.75;
        tb_add(s, "plane", &mirror_m, NULL);
        hr_material glow = tb_black();
        glow.emissive = (hr_color){0, 1, 0.5};
        hr_transform t = tb_place(5, 0, 5, 1);
        tb_add(s, "sphere", &glow, &t);
        CHECK_OK(hr_scene_commit(s));
        CHECK(!!(hr_scene_effects(s) & HR_EFFECT_REFLECTION) == !below);
        /* (-5,0,5) + t(1,0,-1) meets the plane at (0,0,0) and reflects along
         * (1,0,1), straight at the sphere's centre. */
        hr_color c = shade(s, (hr_vec3){-5, 0, 5}, (hr_vec3){1, 0, -1});
        if (below) CHECK_RGB(c, 0, 0, 0);
        else CHECK_RGB(c, 0, 0.75, 0.375);
        hr_scene_destroy(s);
    }
}

/* A glass slab (a cube scaled to 10 x 10 x 1) in front of an emissive
 * plane: straight through at normal incidence, weighted by transparency
 * once per surface. maxRecursionDepth 1 stops inside the slab. */
static void refraction_slab(void)
{
    for (int depth = 1; depth <= 3; depth += 2) {
        hr_scene *s;
        hr_scene_create(ctx, &s);
        tb_dark_globals(s, depth);
        hr_material glass = tb_black();
        glass.transparency = 0.8;
        glass.speed_of_light = 0.6;
        hr_transform slab;
        hr_transform_identity(&slab);
        hr_transform_scale(&slab, 10, 10, 1);
        tb_add(s, "cube", &glass, &slab);
        hr_material glow = tb_black();
        glow.emissive = (hr_color){1, 0.5, 0.25};
        hr_transform below = tb_place(0, 0, -5, 1);
        tb_add(s, "plane", &glow, &below);
        CHECK_OK(hr_scene_commit(s));
        CHECK(hr_scene_effects(s) == (HR_EFFECT_EMISSION | HR_EFFECT_REFRACTION));
        hr_color c = shade(s, (hr_vec3){0, 0, 5}, (hr_vec3){0, 0, -1});
        if (depth == 1) CHECK_RGB(c, 0, 0, 0);
        else CHECK_RGB(c, 0.64, 0.32, 0.16);
        hr_scene_destroy(s);
    }
    /* Oblique: a ray at 45 degrees bends toward the normal inside (speed
     * 0.5: sin t = sin(45)/2) and leaves parallel to how it came, shifted.
     * The emissive target is a small sphere placed where the shifted ray
     * goes: entry at (0,0,1), inside slope tan t = sin t / cos t. */
    hr_scene *s;
    hr_scene_create(ctx, &s);
    tb_dark_globals(s, 3);
    hr_material glass = tb_black();
    glass.transparency = 1.0;
    glass.speed_of_light = 0.5;
    hr_transform slab;
    hr_transform_identity(&slab);
    hr_transform_scale(&slab, 10, 10, 1);
    tb_add(s, "cube", &glass, &slab);
    double sin_t = sqrt(0.5) / 2.0, cos_t = sqrt(1.0 - sin_t * sin_t);
    double exit_x = 2.0 * sin_t / cos_t; /* after crossing thickness 2 */
    /* After leaving at (exit_x, 0, -1) along (1,0,-1)/sqrt2, it passes
     * (exit_x + 4, 0, -5). A sphere of radius 0.05 there is hit only if the
     * bend is right (an unbent ray would pass 4 - 2 + ... far away). */
    hr_material glow = tb_black();
    glow.emissive = (hr_color){1, 1, 1};
    hr_transform target = tb_place(exit_x + 4, 0, -5, 0.05);
    tb_add(s, "sphere", &glow, &target);
    CHECK_OK(hr_scene_commit(s));
    hr_color c = shade(s, (hr_vec3){-4, 0, 5}, (hr_vec3){1, 0, -1});
    CHECK_RGB(c, 1, 1, 1);
    hr_scene_destroy(s);
}

/* Values that could make a pixel infinite are refused when the object or
 * light is added, naming the field; the extremes allowed stay finite. */
static void refused_materials(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "sphere";
    hr_material m;
    hr_material_default(&m);
    m.specular_exponent = -1;
    d.material = &m;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "specularExponent -1 must be within [0, 1e+06]") != NULL);
    hr_material_default(&m);
    m.reflectivity = 1.5;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "reflectivity 1.5 must be within [0, 1]") != NULL);
    hr_material_default(&m);
    m.transparency = -0.1;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "transparency") != NULL);
    hr_material_default(&m);
    m.emissive.g = 1e7;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "emissive") != NULL);
    hr_material_default(&m);
    m.speed_of_light = 0;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "speedOfLight") != NULL);
    hr_light l = {sizeof l, 0, {0, 0, 10}, {INFINITY, 1, 1}};
    CHECK(hr_scene_add_light(s, &l) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "light: colour") != NULL);
    CHECK(hr_scene_object_count(s) == 0);

    /* The extremes allowed: everything at the bounds, mirrors and glass at
     * weight 1 both, deep recursion. Every shaded value is finite. */
    hr_material_default(&m);
    m.ambient = m.diffuse = m.specular = m.emissive = (hr_color){1e6, -1e6, 1e6};
    m.specular_exponent = 0;
    m.reflectivity = m.transparency = 1;
    m.speed_of_light = 1e-9;
    CHECK_OK(hr_scene_add_object(s, &d, NULL));
    hr_transform t = tb_place(0, 0, -3, 1);
    d.transform = t.m, d.inverse = t.inv;
    CHECK_OK(hr_scene_add_object(s, &d, NULL));
    l.color = (hr_color){1e6, 1e6, -1e6};
    CHECK_OK(hr_scene_add_light(s, &l));
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.max_recursion_depth = 12;
    g.global_ambient = (hr_color){1e6, 1e6, 1e6};
    CHECK_OK(hr_scene_set_globals(s, &g));
    CHECK_OK(hr_scene_commit(s));
    for (int i = 0; i < 8; i++) {
        hr_ray r = {{0.1 * i, 0.05 * i, 5}, {0.01 * i, -0.02 * i, -1}};
        hr_color c;
        CHECK_OK(hr_scene_shade(s, &r, -1, &c));
        CHECK(isfinite(c.r) && isfinite(c.g) && isfinite(c.b));
    }
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    refused_materials();
    ambient_only();
    diffuse_head_on();
    in_shadow();
    mirror();
    refraction_slab();
    hr_context_destroy(ctx);
    return hr_test_end();
}
