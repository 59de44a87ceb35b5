/* What the SDL reader says to help: "did you mean" for a misspelt keyword
 * (the book's `exponent` too), a keyword whose module was found but refused,
 * a camera with Hill's 9 numbers, the optional tube radius of `torus`, and
 * the warnings it gives through the context's warning callback: a
 * coefficient below its threshold (naming the command's line, inside macros
 * too, at most eight per kind and then a count) and an empty scene (from
 * commit). Also hr_suggest itself. */
#include <stdio.h>
#include <string.h>

#include "sdl_test_support.h"

typedef struct warning_log {
    int count;
    int32_t code[32];
    int32_t line[32];
    char message[32][512];
} warning_log;

static void log_warning(void *user, const hr_warning *w)
{
    warning_log *log = user;
    if (log->count < 32) {
        log->code[log->count] = w->code;
        log->line[log->count] = w->line;
        snprintf(log->message[log->count], sizeof log->message[0], "%s", w->message);
        CHECK(w->struct_size == sizeof *w && (strcmp(w->file, SDL_TEST_NAME) == 0 || w->file[0] == 0));
    }
    log->count++;
}

/* Load `text`, commit it, and return its warnings in *log. */
static void load_and_commit(hr_context *ctx, const char *text, warning_log *log)
{
    memset(log, 0, sizeof *log);
    hr_context_set_warning_callback(ctx, log_warning, log);
    hr_sdl_result r;
    if (LOAD_OK(ctx, text, &r)) {
        CHECK_OK(hr_scene_commit(r.scene));
        hr_scene_destroy(r.scene);
    }
    hr_context_set_warning_callback(ctx, NULL, NULL);
}

static void suggestions(hr_context *ctx)
{
    static const char *const words[] = {"specularExponent", "specular", "sphere", "--spp", "--size"};
    CHECK(hr_suggest("specularExponet", words, 5) == words[0]);  /* a letter left out */
    CHECK(hr_suggest("specualr", words, 5) == words[1]);         /* two letters swapped */
    CHECK(hr_suggest("SPHERE", words, 5) == words[2]);           /* case is no step */
    CHECK(hr_suggest("--sp", words, 5) == words[3]);
    CHECK(hr_suggest("cube", words, 5) == NULL);                 /* nothing near */
    CHECK(hr_suggest("sphere", words, 5) == NULL);               /* itself is no suggestion */
    CHECK(hr_suggest("", words, 5) == NULL && hr_suggest(NULL, words, 5) == NULL);
    char huge[200];
    memset(huge, 'a', sizeof huge - 1);
    huge[sizeof huge - 1] = '\0';
    CHECK(hr_suggest(huge, words, 5) == NULL);

    EXPECT_ERROR(ctx, "specularExponet 20 sphere", HR_ERROR_SDL, 1, 1,
                 "unknown keyword 'specularExponet' (did you mean 'specularExponent'?)");
    EXPECT_ERROR(ctx, "sphere\nexponent 20", HR_ERROR_SDL, 2, 1,
                 "unknown keyword 'exponent' (did you mean 'specularExponent'?");
    EXPECT_ERROR(ctx, "sphre", HR_ERROR_SDL, 1, 1, "unknown keyword 'sphre' (did you mean 'sphere'?)");
    EXPECT_ERROR(ctx, "translate 1 2 3 rotat 90 0 1 0", HR_ERROR_SDL, 1, 17,
                 "(did you mean 'rotate'?)");
    /* Case keeps its own, more exact message. */
    EXPECT_ERROR(ctx, "Sphere", HR_ERROR_SDL, 1, 1, "keywords are case-sensitive: 'sphere'");
    /* Nothing near: no guess. */
    EXPECT_ERROR(ctx, "frobnicate", HR_ERROR_SDL, 1, 1, "unknown keyword 'frobnicate'");
    hr_sdl_result r = {.struct_size = sizeof r};
    CHECK(hr_sdl_load_string(ctx, "frobnicate", SDL_TEST_NAME, NULL, &r) == HR_ERROR_SDL);
    CHECK(strstr(hr_context_last_error(ctx), "did you mean") == NULL);

    /* A parameter name of a class, given through the C API. */
    hr_sdl_result scene_only = {.struct_size = sizeof scene_only};
    if (LOAD_OK(ctx, "", &scene_only)) {
        hr_param p = {.name = "tub", .type = HR_PARAM_NUMBER, .number = 0.5};
        hr_object_desc d = {.struct_size = sizeof d, .shape = "taperedCylinder", .param_count = 1,
                            .params = &p};
        CHECK(hr_scene_add_object(scene_only.scene, &d, NULL) == HR_ERROR_PARAMETER);
        CHECK_MSG(strstr(hr_context_last_error(ctx), "no parameter 'tub'") != NULL &&
                      strstr(hr_context_last_error(ctx), "did you mean") == NULL,
                  "%s", hr_context_last_error(ctx));
        p.name = "ss";
        CHECK(hr_scene_add_object(scene_only.scene, &d, NULL) == HR_ERROR_PARAMETER);
        CHECK_MSG(strstr(hr_context_last_error(ctx), "no parameter 'ss' (did you mean 's'?)") != NULL,
                  "%s", hr_context_last_error(ctx));
        hr_scene_destroy(scene_only.scene);
    }

    /* A class name asked of the context by name (C, Python's Shape(...)). */
    const hr_shape_class *cls;
    CHECK(hr_context_find_shape_class(ctx, "cylindre", &cls, NULL) == HR_ERROR_MODULE);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "no shape module provides 'cylindre' (did you mean "
                                                 "'cylinder'?)") != NULL,
              "%s", hr_context_last_error(ctx));
}

static void refused_module(void)
{
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);
    CHECK_OK(hr_context_add_shape_dir(ctx, HR_TEST_MODULE_DIR));
    EXPECT_ERROR(ctx, "wrong_abi 1", HR_ERROR_MODULE, 1, 1,
                 "unknown keyword 'wrong_abi': a module for it was found but refused",
                 "wrong_abi.so", "ABI version");
    hr_context_destroy(ctx);
}

static void camera_with_nine_numbers(hr_context *ctx)
{
    EXPECT_ERROR(ctx, "camera 0 0 5 0 0 0 0 1 0\nsphere", HR_ERROR_SDL, 2, 1,
                 "'camera' takes 10 numbers", "view angle", "found 9 before 'sphere'");
    /* A bad first number keeps the plain message. */
    EXPECT_ERROR(ctx, "camera x", HR_ERROR_SDL, 1, 8, "expected a number after 'camera', found 'x'");
}

static void torus_tube(hr_context *ctx)
{
    if (!sdl_test_has_class(ctx, "torus")) {
        printf("torus module not built: its tube radius is not checked\n");
        return;
    }
    hr_sdl_result r;
    if (!LOAD_OK(ctx, "torus 0.1 translate 3 0 0 torus\n sphere", &r)) return;
    CHECK(hr_scene_object_count(r.scene) == 3);
    CHECK_OK(hr_scene_commit(r.scene));
    /* Down the z axis through (1, 0): the tube's top at z = 0.1 (the
     * default tube, 0.2, would be hit at 0.2). The solver's roots are
     * within a few units of roundoff times the condition for a ray this
     * well conditioned (shapes/torus/torus.c); 1e-12 is thousands of ulps
     * of 4.9 yet far below the 0.1 that tells the radii apart. */
    hr_ray ray = {{1, 0, 5}, {0, 0, -1}};
    hr_hit hit;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(r.scene, &ray, 0, 1e30, &hit, &found));
    CHECK(found && hit.object == 0);
    CHECK_NEAR(hit.t, 4.9, 1e-12);
    /* The second torus took the default. */
    hr_ray ray2 = {{4, 0, 5}, {0, 0, -1}};
    CHECK_OK(hr_scene_first_hit(r.scene, &ray2, 0, 1e30, &hit, &found));
    CHECK(found && hit.object == 1);
    CHECK_NEAR(hit.t, 4.8, 1e-12);
    hr_scene_destroy(r.scene);
    /* A tube out of range is the module's refusal, at the keyword. */
    EXPECT_ERROR(ctx, "torus 1.5", HR_ERROR_PARAMETER, 1, 1, "tube");
}

static void threshold_warnings(hr_context *ctx)
{
    warning_log log;
    /* Hill's glass sphere: reflectivity 0.08 under the default 0.5. */
    load_and_commit(ctx, "transparency 0.9 speedOfLight 0.7\nreflectivity 0.08\nsphere", &log);
    CHECK(log.count == 1);
    CHECK(log.code[0] == HR_WARNING_BELOW_THRESHOLD && log.line[0] == 2);
    CHECK_MSG(strstr(log.message[0], "t.dat:2:1: reflectivity 0.08 is below minReflectivity 0.5") != NULL,
              "%s", log.message[0]);

    /* The threshold counts as it stands at the end of the file. */
    load_and_commit(ctx, "reflectivity 0.08 sphere minReflectivity 0.05", &log);
    CHECK(log.count == 0);
    load_and_commit(ctx, "minReflectivity 0 reflectivity 0.08 sphere minReflectivity 0.1\n", &log);
    CHECK(log.count == 1 && log.line[0] == 1);
    /* A coefficient no object used, or 0, or 1: nothing to say. */
    load_and_commit(ctx, "sphere reflectivity 0.2\n", &log);
    CHECK(log.count == 0);
    load_and_commit(ctx, "reflectivity 0 transparency 1 sphere\n", &log);
    CHECK(log.count == 0);
    /* Transparency too, each command once however many objects use it. */
    load_and_commit(ctx, "transparency 0.3 sphere cube sphere\nminTransparency 0.4", &log);
    CHECK(log.count == 1 && log.line[0] == 1);
    CHECK(strstr(log.message[0], "transparency 0.3 is below minTransparency 0.4") != NULL);

    /* Inside a macro: the place names the use and the definition. */
    load_and_commit(ctx, "def glass { reflectivity 0.1 sphere }\nuse glass", &log);
    CHECK(log.count == 1);
    CHECK_MSG(strstr(log.message[0], "in macro 'glass'") != NULL, "%s", log.message[0]);

    /* Many: eight, then one line counting the rest. */
    char text[4096] = "";
    for (int i = 0; i < 20; i++) {
        char line[64];
        snprintf(line, sizeof line, "reflectivity 0.%02d sphere\n", i + 1);
        strcat(text, line);
    }
    load_and_commit(ctx, text, &log);
    CHECK(log.count == 9);
    CHECK_MSG(strstr(log.message[8], "12 more reflectivity commands below minReflectivity 0.5") != NULL,
              "%s", log.message[8]);
}

static void empty_scene_warning(hr_context *ctx)
{
    warning_log log;
    load_and_commit(ctx, "light 1 2 3 1 1 1 background 0.2 0.2 0.2", &log);
    CHECK(log.count == 1 && log.code[0] == HR_WARNING_EMPTY_SCENE);
    CHECK(strstr(log.message[0], "no objects") != NULL);
    load_and_commit(ctx, "sphere", &log);
    CHECK(log.count == 0);
    /* No callback: nothing is printed, and nothing fails. */
    hr_sdl_result r;
    if (LOAD_OK(ctx, "", &r)) {
        CHECK_OK(hr_scene_commit(r.scene));
        hr_scene_destroy(r.scene);
    }
}

/* A mesh file read as SDL names the 'mesh FILE' that reads it. */
static void mesh_file_as_sdl(hr_context *ctx)
{
    const char *names[] = {"bunny.obj", "tet.3VN"};
    const char *texts[] = {"v 0 0 0\nv 1 0 0\n", "4 4 4\n0 0 0\n"};
    for (int i = 0; i < 2; i++) {
        hr_sdl_result r;
        memset(&r, 0, sizeof r);
        r.struct_size = sizeof r;
        CHECK(hr_sdl_load_string(ctx, texts[i], names[i], NULL, &r) == HR_ERROR_SDL);
        char want[64];
        snprintf(want, sizeof want, "'mesh %s'", names[i]);
        CHECK_MSG(strstr(hr_context_last_error(ctx), want) != NULL, "%s", hr_context_last_error(ctx));
        CHECK(strstr(hr_context_last_error(ctx), "is a mesh file, not SDL") != NULL);
    }
    /* By another name, an OBJ file's first word says what it is. */
    const char *obj_texts[] = {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "! a comment\nmtllib m.mtl\nv 0 0 0\n"};
    for (int i = 0; i < 2; i++) {
        hr_sdl_result r;
        memset(&r, 0, sizeof r);
        r.struct_size = sizeof r;
        CHECK(hr_sdl_load_string(ctx, obj_texts[i], "scene.sdl", NULL, &r) == HR_ERROR_SDL);
        const char *msg = hr_context_last_error(ctx);
        CHECK_MSG(strstr(msg, "reads like an OBJ mesh file, not SDL") != NULL && strstr(msg, "'mesh FILE.obj'"),
                  "%s", msg);
        CHECK_MSG(strstr(msg, "HITRAY_SHAPE_PATH") == NULL, "%s", msg);
    }
}

int main(void)
{
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);
    suggestions(ctx);
    camera_with_nine_numbers(ctx);
    torus_tube(ctx);
    threshold_warnings(ctx);
    empty_scene_warning(ctx);
    mesh_file_as_sdl(ctx);
    hr_context_destroy(ctx);
    refused_module();
    return hr_test_end();
}
