/* The scene budget: a scene of more objects, shape data (a tessellated
 * teapot's triangles) or texels than its memory budget allows is refused
 * at the line that passes it, naming what and how much, before that is
 * allocated; the budget comes from hr_context_set_scene_memory, else
 * HITRAY_MAX_SCENE_MEMORY, else half the process's memory. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_status load(hr_context *ctx, const char *text, const char *dir)
{
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    hr_status st = hr_sdl_load_string(ctx, text, "test.sdl", dir, &r);
    hr_scene_destroy(r.scene);
    return st;
}

static void expect_refused(hr_context *ctx, const char *text, const char *dir, const char *where,
                           const char *what)
{
    hr_status st = load(ctx, text, dir);
    const char *m = hr_context_last_error(ctx);
    CHECK_MSG(st == HR_ERROR_OUT_OF_MEMORY && strncmp(m, where, strlen(where)) == 0 && strstr(m, what),
              "status %d, message '%s' lacks '%s' ... '%s'", (int)st, m, where, what);
}

/* Objects: 1000 spheres fit 1 MB; at 20 KB the budget ends some way in,
 * at the line of the sphere that would pass it. */
static void test_objects(hr_context *ctx)
{
    size_t n = 1000 * 8 + 1;
    char *text = malloc(n);
    for (size_t i = 0; i < 1000; i++) memcpy(text + 7 * i, "sphere\n", 7);
    text[7000] = '\0';
    CHECK_OK(hr_context_set_scene_memory(ctx, 1000000));
    CHECK_MSG(load(ctx, text, NULL) == HR_OK, "%s", hr_context_last_error(ctx));
    CHECK_OK(hr_context_set_scene_memory(ctx, 20000));
    hr_status st = load(ctx, text, NULL);
    const char *m = hr_context_last_error(ctx);
    int line = 0;
    CHECK_MSG(st == HR_ERROR_OUT_OF_MEMORY && sscanf(m, "test.sdl:%d:", &line) == 1 && line > 1 &&
                  line < 1000 && strstr(m, "(a 'sphere') needs") &&
                  strstr(m, "than the scene's memory budget of 20000 bytes leaves") &&
                  strstr(m, "HITRAY_MAX_SCENE_MEMORY"),
              "%s", m);
    free(text);
}

/* Shape data: teapot 64 keeps some 65k triangles, megabytes: past a
 * budget of 2 MB, refused at its line as shape data. */
static void test_shape_data(hr_context *ctx)
{
    CHECK_OK(hr_context_set_scene_memory(ctx, 2000000));
    expect_refused(ctx, "sphere\nteapot 64\n", NULL, "test.sdl:2:",
                   "object 1 (a 'teapot') needs");
    expect_refused(ctx, "sphere\nteapot 64\n", NULL, "test.sdl:2:", "of shape data");
    CHECK_MSG(load(ctx, "sphere\nteapot 8\n", NULL) == HR_OK, "%s", hr_context_last_error(ctx));
    CHECK_OK(hr_context_set_scene_memory(ctx, 0));
}

/* Texels: a 64 x 64 pixmap keeps 64 * 64 * 3 floats, 49152 bytes, and its
 * mip-map's levels (32^2 + 16^2 + ... + 1^2 texels, 1365 of them), 16380
 * more: 65532. */
static void test_texels(hr_context *ctx, const char *dir)
{
    hr_image *img;
    CHECK_OK(hr_image_create(ctx, 64, 64, 3, &img));
    char path[4096];
    snprintf(path, sizeof path, "%s/t.png", dir);
    CHECK_OK(hr_image_write(ctx, img, path, NULL));
    hr_image_destroy(img);
    CHECK_OK(hr_context_set_scene_memory(ctx, 140000));
    CHECK_MSG(load(ctx, "makePixmap 1 t.png\nmakePixmap 2 t.png\n", dir) == HR_OK, "%s",
              hr_context_last_error(ctx));
    expect_refused(ctx, "makePixmap 1 t.png\nmakePixmap 2 t.png\nmakePixmap 3 t.png\n", dir, "test.sdl:3:",
                   "pixmap 3 (64 x 64 texels and its mip-map) needs 65532 bytes more than the scene's memory "
                   "budget of 140000 bytes leaves (it holds 0 bytes of objects, 0 of shape data, 131064 of "
                   "texels)");
    CHECK_OK(hr_context_set_scene_memory(ctx, 0));
}

/* The environment's budget, and a bad one named. */
static void test_environment(hr_context *ctx)
{
    CHECK_OK(hr_context_set_scene_memory(ctx, 0));
    setenv("HITRAY_MAX_SCENE_MEMORY", "100", 1);
    expect_refused(ctx, "sphere\n", NULL, "test.sdl:1:", "budget of 100 bytes");
    static const char *bad[] = {"0", "-5", "12k", " 7"};
    for (int i = 0; i < 4; i++) {
        setenv("HITRAY_MAX_SCENE_MEMORY", bad[i], 1);
        hr_scene *s = NULL;
        CHECK(hr_scene_create(ctx, &s) == HR_ERROR_INVALID_ARGUMENT && s == NULL);
        CHECK(strstr(hr_context_last_error(ctx), "HITRAY_MAX_SCENE_MEMORY") != NULL);
    }
    unsetenv("HITRAY_MAX_SCENE_MEMORY");
    CHECK(load(ctx, "sphere\n", NULL) == HR_OK);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    char dir[] = "/tmp/hitray-budget-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    unsetenv("HITRAY_MAX_SCENE_MEMORY");
    test_objects(ctx);
    test_shape_data(ctx);
    test_texels(ctx, dir);
    test_environment(ctx);
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    hr_context_destroy(ctx);
    return hr_test_end();
}
