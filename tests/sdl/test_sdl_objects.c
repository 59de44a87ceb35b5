/* SDL objects: class names and parameters as the reader passes them
 * (stub shapes show what they got), mesh file names with base_dir, and CSG:
 * operands first, each with its own material and transform, then the node. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdl_test_support.h"

static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

static void shapes(hr_context *ctx)
{
    hr_sdl_result r;
    const char *text = "sphere cube square plane cylinder cone\n"
                       "taperedCylinder .5 taperedCylinder 3";
    if (!LOAD_OK(ctx, text, &r)) return;
    static const char *names[] = {"sphere",   "cube", "square",          "plane",
                                  "cylinder", "cone", "taperedCylinder", "taperedCylinder"};
    CHECK(hr_scene_object_count(r.scene) == 8);
    for (int i = 0; i < 8; i++) {
        hr_object_info o = sdl_test_object(r.scene, i);
        CHECK_MSG(strcmp(o.shape, names[i]) == 0, "object %d is '%s', expected '%s'", i,
                  o.shape, names[i]);
        CHECK(o.top_level == 1);
    }
    /* The stub's bounds show s: radius max(1, s). (The scene pads world
     * bounds by a few ulps.) */
    hr_object_info o = sdl_test_object(r.scene, 6);
    CHECK_NEAR(o.world_bounds.hi.x, 1, 1e-14);
    o = sdl_test_object(r.scene, 7);
    CHECK_NEAR(o.world_bounds.hi.x, 3, 1e-14);
    CHECK_NEAR(o.world_bounds.hi.z, 1, 1e-14);
    CHECK_NEAR(o.world_bounds.lo.z, 0, 1e-14);
    hr_scene_destroy(r.scene);
}

static void meshes(hr_context *ctx)
{
    /* The stub mesh refuses with what it got: the file name as written and
     * the base directory (none for a string without one). */
    EXPECT_ERROR(ctx, "mesh pillar.3vn", HR_ERROR_PARAMETER, 1, 1,
                 "stub mesh: file 'pillar.3vn' in ''");
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_sdl_load_string(ctx, "sphere\nmesh models/dome1.3vn", "x.dat", "/some/dir", &r) ==
          HR_ERROR_PARAMETER);
    CHECK(r.scene == NULL);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "x.dat:2:1: ") &&
                  strstr(hr_context_last_error(ctx), "file 'models/dome1.3vn' in '/some/dir'"),
              "message: %s", hr_context_last_error(ctx));

    /* From a file: base_dir is the file's directory. */
    char path[1024];
    snprintf(path, sizeof path, "%s/tests/sdl_mesh_test.dat", HR_TEST_BINARY_DIR);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    fputs("sphere mesh pillar.3vn\n", f);
    fclose(f);
    CHECK(hr_sdl_load_file(ctx, path, &r) == HR_ERROR_PARAMETER);
    char want[1200];
    snprintf(want, sizeof want, "%s:1:8: ", path);
    CHECK_MSG(strncmp(hr_context_last_error(ctx), want, strlen(want)) == 0, "message: %s",
              hr_context_last_error(ctx));
    snprintf(want, sizeof want, "file 'pillar.3vn' in '%s/tests'", HR_TEST_BINARY_DIR);
    CHECK_MSG(strstr(hr_context_last_error(ctx), want) != NULL, "message: %s",
              hr_context_last_error(ctx));
    remove(path);
}

static void csg(hr_context *ctx)
{
    hr_sdl_result r;
    /* Operands keep what was current when each was read; state commands
     * between them run; the node has the identity and the default material. */
    const char *text = "diffuse 1 0 0\n"
                       "union sphere\n"
                       "      diffuse 0 1 0 translate 1 0 0 cube\n"
                       "cone\n";
    if (LOAD_OK(ctx, text, &r)) {
        CHECK(hr_scene_object_count(r.scene) == 4);
        hr_object_info a = sdl_test_object(r.scene, 0), b = sdl_test_object(r.scene, 1),
                       u = sdl_test_object(r.scene, 2), c = sdl_test_object(r.scene, 3);
        CHECK(strcmp(a.shape, "sphere") == 0 && strcmp(b.shape, "cube") == 0 &&
              strcmp(u.shape, "union") == 0 && strcmp(c.shape, "cone") == 0);
        CHECK(a.top_level == 0 && b.top_level == 0 && u.top_level == 1 && c.top_level == 1);
        CHECK_COLOR(a.material.diffuse, 1, 0, 0, 0);
        CHECK_MATRIX(a.transform, identity, 0, "operand A");
        CHECK_COLOR(b.material.diffuse, 0, 1, 0, 0);
        CHECK(b.transform[3] == 1);
        CHECK_COLOR(u.material.diffuse, 0.8, 0.8, 0.8, 0);
        CHECK_MATRIX(u.transform, identity, 0, "boolean node");
        CHECK_MATRIX(u.inverse, identity, 0, "boolean node inverse");
        /* The state after the boolean is what its operands left. */
        CHECK_COLOR(c.material.diffuse, 0, 1, 0, 0);
        CHECK(c.transform[3] == 1);
        hr_scene_destroy(r.scene);
    }

    /* Booleans nest in prefix form: operands come first in file order. */
    text = "difference union sphere cube intersection cone push cylinder pop";
    if (LOAD_OK(ctx, text, &r)) {
        static const char *names[] = {"sphere", "cube",     "union",       "cone",
                                      "cylinder", "intersection", "difference"};
        CHECK(hr_scene_object_count(r.scene) == 7);
        for (int i = 0; i < 7; i++) {
            hr_object_info o = sdl_test_object(r.scene, i);
            CHECK_MSG(strcmp(o.shape, names[i]) == 0, "object %d is '%s', expected '%s'", i,
                      o.shape, names[i]);
            CHECK(o.top_level == (i == 6));
        }
        hr_scene_destroy(r.scene);
    }

    /* Operands from macros, and a boolean inside a macro. */
    text = "def ball { push scale 2 2 2 sphere pop }\n"
           "def pair { union use ball cube }\n"
           "use pair intersection use pair use ball";
    if (LOAD_OK(ctx, text, &r)) {
        CHECK(hr_scene_object_count(r.scene) == 8);
        hr_object_info o = sdl_test_object(r.scene, 0);
        CHECK(o.transform[0] == 2);
        o = sdl_test_object(r.scene, 7);
        CHECK(strcmp(o.shape, "intersection") == 0);
        hr_scene_destroy(r.scene);
    }

    /* Deep nesting is read without recursion: HR_MAX_COMPOSITE_DEPTH unions
     * in a row, the deepest chain a scene may hold. */
    int depth = HR_MAX_COMPOSITE_DEPTH;
    char *deep = malloc((size_t)5000 * 14 + 16);
    size_t len = 0;
    for (int i = 0; i < depth; i++) len += (size_t)sprintf(deep + len, "union ");
    for (int i = 0; i <= depth; i++) len += (size_t)sprintf(deep + len, "sphere ");
    if (LOAD_OK(ctx, deep, &r)) {
        CHECK(hr_scene_object_count(r.scene) == 2 * depth + 1);
        hr_object_info o = sdl_test_object(r.scene, 2 * depth);
        CHECK(strcmp(o.shape, "union") == 0 && o.top_level == 1);
        hr_scene_destroy(r.scene);
    }
    /* 5000 in a row: read without recursion up to the limit, then refused
     * with the place and the reason, not a crash. */
    depth = 5000;
    len = 0;
    for (int i = 0; i < depth; i++) len += (size_t)sprintf(deep + len, "union ");
    for (int i = 0; i <= depth; i++) len += (size_t)sprintf(deep + len, "sphere ");
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_sdl_load_string(ctx, deep, SDL_TEST_NAME, NULL, &r) == HR_ERROR_PARAMETER);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "t.dat:1:") &&
                  strstr(hr_context_last_error(ctx), "1001 deep"),
              "message: %s", hr_context_last_error(ctx));
    free(deep);
}

int main(void)
{
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES | SDL_STUB_CSG | SDL_STUB_MESH);
    shapes(ctx);
    meshes(ctx);
    csg(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
