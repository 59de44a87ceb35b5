/* SDL state: Hill's transform stack (his worked example), the sticky
 * material, defaultMaterials, push/pop saving the transform only, globals,
 * lights in world coordinates, and the camera extension. */
#include <string.h>

#include "sdl_test_support.h"

static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

static void hill_worked_example(hr_context *ctx)
{
    /* M = T(2,4,9) S(1,4,4): the transform written last acts first. The
     * inverse is S^-1 T^-1 (the lecture slide's "-4" in row 2 is a typo for
     * -1 = -4 * 1/4). Every entry is exact in binary. */
    hr_sdl_result r;
    if (!LOAD_OK(ctx, "translate 2 4 9 scale 1 4 4 sphere", &r)) return;
    CHECK(hr_scene_object_count(r.scene) == 1);
    hr_object_info o = sdl_test_object(r.scene, 0);
    CHECK(strcmp(o.shape, "sphere") == 0);
    const double m[16] = {1, 0, 0, 2, 0, 4, 0, 4, 0, 0, 4, 9, 0, 0, 0, 1};
    const double inv[16] = {1, 0, 0, -2, 0, 0.25, 0, -1, 0, 0, 0.25, -2.25, 0, 0, 0, 1};
    CHECK_MATRIX(o.transform, m, 0, "M");
    CHECK_MATRIX(o.inverse, inv, 0, "M^-1");
    hr_scene_destroy(r.scene);
}

static void transforms(hr_context *ctx)
{
    hr_sdl_result r;
    /* push/pop restore the transform; identityAffine clears the top only;
     * an object keeps the transform of the moment it was read. */
    const char *text = "translate 1 0 0\n"
                       "push translate 0 2 0 sphere pop\n" /* 0: (1,2,0) */
                       "sphere\n"                          /* 1: (1,0,0) */
                       "push identityAffine cube pop\n"    /* 2: identity */
                       "cube\n"                            /* 3: (1,0,0) again */
                       "identityAffine square\n"           /* 4: identity */
                       "push push push translate 5 5 5\n"  /* unbalanced at the end */
                       "rotate 90 0 0 7 cone\n";           /* 5: axis normalised */
    if (!LOAD_OK(ctx, text, &r)) return;
    CHECK(hr_scene_object_count(r.scene) == 6);
    hr_object_info o = sdl_test_object(r.scene, 0);
    CHECK(o.transform[3] == 1 && o.transform[7] == 2 && o.transform[11] == 0);
    o = sdl_test_object(r.scene, 1);
    CHECK(o.transform[3] == 1 && o.transform[7] == 0);
    o = sdl_test_object(r.scene, 2);
    CHECK_MATRIX(o.transform, identity, 0, "identityAffine inside push");
    CHECK_MATRIX(o.inverse, identity, 0, "identityAffine inverse");
    o = sdl_test_object(r.scene, 3);
    CHECK(o.transform[3] == 1);
    o = sdl_test_object(r.scene, 4);
    CHECK_MATRIX(o.transform, identity, 0, "identityAffine at the base");
    /* rotate 90 about (0,0,7) is exactly the quarter turn about z, after
     * the translation: x goes to y. */
    o = sdl_test_object(r.scene, 5);
    hr_vec3 p = hr_transform_point(o.transform, (hr_vec3){1, 0, 0});
    CHECK(p.x == 5 && p.y == 6 && p.z == 5);
    hr_vec3 back = hr_transform_point(o.inverse, p);
    CHECK(back.x == 1 && back.y == 0 && back.z == 0);
    hr_scene_destroy(r.scene);

    /* A huge or tiny axis is normalised without overflow. */
    if (LOAD_OK(ctx, "rotate 90 0 0 1e300 sphere rotate -90 0 0 1e-300 cube", &r)) {
        o = sdl_test_object(r.scene, 1);
        CHECK_MATRIX(o.transform, identity, 0, "rotate there and back");
        hr_scene_destroy(r.scene);
    }
    /* A negative scale mirrors; it is not an error. */
    if (LOAD_OK(ctx, "scale -1 2 -3 sphere", &r)) {
        o = sdl_test_object(r.scene, 0);
        CHECK(o.transform[0] == -1 && o.transform[5] == 2 && o.transform[10] == -3);
        CHECK_NEAR(o.inverse[10], -1.0 / 3.0, 1e-16);
        hr_scene_destroy(r.scene);
    }
}

static void materials(hr_context *ctx)
{
    hr_sdl_result r;
    const char *text =
        "diffuse .1 .2 .3 ambient .4 .5 .6 specular .7 .8 .9 emissive 1 .5 .25\n"
        "specularExponent 20 reflectivity .6 transparency .3 speedOfLight .75\n"
        "specularFraction .4 surfaceRoughness .2 texture -2 parameters 3 1 2.5 3\n"
        "sphere\n"                          /* 0: everything above */
        "push diffuse 1 0 0 pop cube\n"     /* 1: push/pop do not save the material */
        "parameters 0 texture -1 square\n"  /* 2: parameters replaced, none now */
        "defaultMaterials plane\n"          /* 3: SDL's defaults */
        "parameters 2 7 8 cylinder\n"       /* 4: parameters after a reset */
        "defaultMaterials cone\n";          /* 5: and reset again */
    if (!LOAD_OK(ctx, text, &r)) return;
    CHECK(hr_scene_object_count(r.scene) == 6);
    hr_object_info o = sdl_test_object(r.scene, 0);
    CHECK_COLOR(o.material.diffuse, .1, .2, .3, 0);
    CHECK_COLOR(o.material.ambient, .4, .5, .6, 0);
    CHECK_COLOR(o.material.specular, .7, .8, .9, 0);
    CHECK_COLOR(o.material.emissive, 1, .5, .25, 0);
    CHECK(o.material.specular_exponent == 20);
    CHECK(o.material.reflectivity == .6);
    CHECK(o.material.transparency == .3);
    CHECK(o.material.speed_of_light == .75);
    CHECK(o.material.specular_fraction == .4);
    CHECK(o.material.surface_roughness == .2);
    CHECK(o.material.texture == -2);
    CHECK(o.material.parameter_count == 3);
    if (o.material.parameter_count == 3 && o.material.parameters)
        CHECK(o.material.parameters[0] == 1 && o.material.parameters[1] == 2.5 &&
              o.material.parameters[2] == 3);

    o = sdl_test_object(r.scene, 1);
    CHECK_COLOR(o.material.diffuse, 1, 0, 0, 0);
    CHECK_COLOR(o.material.ambient, .4, .5, .6, 0);
    CHECK(o.material.parameter_count == 3);

    o = sdl_test_object(r.scene, 2);
    CHECK(o.material.parameter_count == 0);
    CHECK(o.material.texture == -1);
    CHECK_COLOR(o.material.diffuse, 1, 0, 0, 0);

    hr_material d;
    hr_material_default(&d);
    o = sdl_test_object(r.scene, 3);
    CHECK_COLOR(o.material.diffuse, d.diffuse.r, d.diffuse.g, d.diffuse.b, 0);
    CHECK_COLOR(o.material.ambient, 0.1, 0.1, 0.1, 0);
    CHECK_COLOR(o.material.specular, 0, 0, 0, 0);
    CHECK_COLOR(o.material.emissive, 0, 0, 0, 0);
    CHECK(o.material.specular_exponent == 1 && o.material.reflectivity == 0 &&
          o.material.transparency == 0 && o.material.speed_of_light == 1 &&
          o.material.specular_fraction == 0 && o.material.surface_roughness == 1 &&
          o.material.texture == 0 && o.material.parameter_count == 0);

    o = sdl_test_object(r.scene, 4);
    CHECK(o.material.parameter_count == 2);
    if (o.material.parameter_count == 2 && o.material.parameters)
        CHECK(o.material.parameters[0] == 7 && o.material.parameters[1] == 8);
    o = sdl_test_object(r.scene, 5);
    CHECK(o.material.parameter_count == 0);
    hr_scene_destroy(r.scene);
}

static void globals_and_lights(hr_context *ctx)
{
    hr_sdl_result r;
    hr_scene_globals g;
    memset(&g, 0, sizeof g);
    g.struct_size = sizeof g;

    /* Defaults when the file sets nothing. */
    if (LOAD_OK(ctx, "sphere", &r)) {
        CHECK_OK(hr_scene_get_globals(r.scene, &g));
        CHECK_COLOR(g.background, 0, 0, 0.6, 0);
        CHECK_COLOR(g.global_ambient, 0.1, 0.1, 0.1, 0);
        CHECK(g.min_reflectivity == 0.5 && g.min_transparency == 0.5);
        CHECK(g.max_recursion_depth == 3);
        CHECK(hr_scene_light_count(r.scene) == 0);
        hr_scene_destroy(r.scene);
    }

    /* Lights are in world coordinates: the transform stack does not move
     * them, and a transform after them changes nothing. */
    const char *text = "background .1 .2 .3 globalAmbient .4 .5 .6\n"
                       "minReflectivity .25 minTransparency .75 maxRecursionDepth 7\n"
                       "translate 5 5 5 scale 2 2 2 rotate 30 1 1 0\n"
                       "light 1 2 3 .5 .6 .7\n"
                       "push translate 9 9 9 light -1 -2 -3 1 1 1 pop\n"
                       "maxRecursionDepth 0\n";
    if (LOAD_OK(ctx, text, &r)) {
        CHECK_OK(hr_scene_get_globals(r.scene, &g));
        CHECK_COLOR(g.background, .1, .2, .3, 0);
        CHECK_COLOR(g.global_ambient, .4, .5, .6, 0);
        CHECK(g.min_reflectivity == .25 && g.min_transparency == .75);
        CHECK(g.max_recursion_depth == 0); /* the last one wins */
        CHECK(hr_scene_light_count(r.scene) == 2);
        hr_light l;
        memset(&l, 0, sizeof l);
        l.struct_size = sizeof l;
        CHECK_OK(hr_scene_light(r.scene, 0, &l));
        CHECK(l.position.x == 1 && l.position.y == 2 && l.position.z == 3);
        CHECK_COLOR(l.color, .5, .6, .7, 0);
        CHECK_OK(hr_scene_light(r.scene, 1, &l));
        CHECK(l.position.x == -1 && l.position.y == -2 && l.position.z == -3);
        hr_scene_destroy(r.scene);
    }
}

static void camera(hr_context *ctx)
{
    hr_sdl_result r;
    /* The extension keyword: eye, look-at, up, vertical angle; not moved by
     * the transform stack; the last one wins; size 640x480. */
    if (LOAD_OK(ctx, "translate 100 0 0 camera 9 9 9 0 0 0 0 0 1 10\n"
                     "camera 1 2 3  4 5 6  0 1 0  30 sphere",
                &r)) {
        CHECK(r.has_camera == 1);
        CHECK(r.camera.eye.x == 1 && r.camera.eye.y == 2 && r.camera.eye.z == 3);
        CHECK(r.camera.look.x == 4 && r.camera.look.y == 5 && r.camera.look.z == 6);
        CHECK(r.camera.up.x == 0 && r.camera.up.y == 1 && r.camera.up.z == 0);
        CHECK(r.camera.view_angle == 30);
        CHECK(r.camera.width == 640 && r.camera.height == 480);
        hr_scene_destroy(r.scene);
    }
    /* No camera: has_camera 0 and a camera that frames the scene, looking
     * at the centre of its bounds. */
    if (LOAD_OK(ctx, "translate 10 20 30 sphere", &r)) {
        CHECK(r.has_camera == 0);
        CHECK_OK(hr_camera_validate(ctx, &r.camera));
        CHECK(r.camera.width == 640 && r.camera.height == 480);
        CHECK_NEAR(r.camera.look.x, 10, 1e-12);
        CHECK_NEAR(r.camera.look.y, 20, 1e-12);
        CHECK_NEAR(r.camera.look.z, 30, 1e-12);
        CHECK(r.camera.eye.z > 30);
        CHECK(!hr_scene_is_committed(r.scene)); /* the caller commits */
        hr_scene_destroy(r.scene);
    }
    /* An empty scene still gets a usable camera. */
    if (LOAD_OK(ctx, "", &r)) {
        CHECK(r.has_camera == 0);
        CHECK_OK(hr_camera_validate(ctx, &r.camera));
        hr_scene_destroy(r.scene);
    }
    EXPECT_ERROR(ctx, "sphere\n camera 0 0 5 0 0 5 0 1 0 45", HR_ERROR_SDL, 2, 2,
                 "'camera' cannot make rays", "same point");
    EXPECT_ERROR(ctx, "camera 0 0 5 0 0 0 0 1 0 180", HR_ERROR_SDL, 1, 1,
                 "'camera' cannot make rays", "view angle");
    EXPECT_ERROR(ctx, "camera 0 0 5 0 0 0 0 1 0", HR_ERROR_SDL, 1, 25,
                 "'camera' takes 10 numbers", "found 9 before end of file");
}

int main(void)
{
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);
    hill_worked_example(ctx);
    transforms(ctx);
    materials(ctx);
    globals_and_lights(ctx);
    camera(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
