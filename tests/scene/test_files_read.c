/* The files a scene was built from (hr_scene_file): exactly those a reader
 * or a shape read, each once, in the order first read; a file the scene's
 * text only names (in a comment, a macro never used) is not among them. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, chdir */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static void write_text(const char *dir, const char *name, const char *text)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

/* The scene's files are `want` (n of them, "DIR/" standing for dir). */
static void expect_files(const hr_scene *s, const char *dir, const char *const *want, int n, const char *what)
{
    CHECK_MSG(hr_scene_file_count(s) == n, "%s: %lld files listed, expected %d", what,
              (long long)hr_scene_file_count(s), n);
    for (int64_t i = 0; i < hr_scene_file_count(s); i++) {
        char expected[4200] = "";
        if (i < n) snprintf(expected, sizeof expected, "%s/%s", dir, want[i]);
        CHECK_MSG(strcmp(hr_scene_file(s, i), expected) == 0, "%s: file %lld is '%s', expected '%s'", what,
                  (long long)i, hr_scene_file(s, i), expected);
    }
    CHECK(hr_scene_file(s, -1) == NULL && hr_scene_file(s, hr_scene_file_count(s)) == NULL);
}

static const char scene_text[] =
    "! a comment naming secret.txt and SECRET_ABS\n"
    "def unused { mesh secret.txt }\n"
    "def also_unused { mesh SECRET_ABS makePixmap 9 secret.txt }\n"
    "makePixmap 1 t.png\n"
    "mesh meshes/cube.obj\n"
    "push translate 3 0 0 mesh meshes/cube.obj pop\n" /* the same file again: listed once */
    "texture 1 sphere\n";

static void sdl_scene_lists_what_it_read(hr_context *ctx, const char *dir)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/t.png", dir);
    hr_image *img = NULL;
    if (hr_image_create(ctx, 4, 4, 3, &img) == HR_OK) CHECK_OK(hr_image_write(ctx, img, path, NULL));
    hr_image_destroy(img);
    write_text(dir, "secret.txt", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    snprintf(path, sizeof path, "%s/meshes", dir);
    CHECK(mkdir(path, 0700) == 0);
    write_text(dir, "meshes/cube.obj",
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
               "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
    /* SECRET_ABS: the secret's absolute name, which exists too. */
    char text[16384], secret[4200];
    snprintf(secret, sizeof secret, "%s/secret.txt", dir);
    const char *at = strstr(scene_text, "SECRET_ABS");
    const char *at2 = strstr(at + 1, "SECRET_ABS");
    snprintf(text, sizeof text, "%.*s%s%.*s%s%s", (int)(at - scene_text), scene_text, secret,
             (int)(at2 - at - 10), at + 10, secret, at2 + 10);
    write_text(dir, "scene.sdl", text);
    snprintf(path, sizeof path, "%s/scene.sdl", dir);
    hr_sdl_result r = {.struct_size = sizeof r};
    CHECK_MSG(hr_sdl_load_file(ctx, path, &r) == HR_OK, "%s", hr_context_last_error(ctx));
    if (r.scene) {
        static const char *const want[] = {"scene.sdl", "t.png", "meshes/cube.obj"};
        expect_files(r.scene, dir, want, 3, "SDL file");
        hr_scene_destroy(r.scene);
    }
    /* From a string with the scene's directory: the pixmap and the mesh. */
    r.scene = NULL;
    CHECK_MSG(hr_sdl_load_string(ctx, text, "scene.sdl", dir, &r) == HR_OK, "%s", hr_context_last_error(ctx));
    if (r.scene) {
        static const char *const want[] = {"t.png", "meshes/cube.obj"};
        expect_files(r.scene, dir, want, 2, "SDL string");
        hr_scene_destroy(r.scene);
    }
    /* Nothing read, nothing listed. */
    r.scene = NULL;
    CHECK_OK(hr_sdl_load_string(ctx, "sphere\n", "s.sdl", dir, &r));
    if (r.scene) {
        expect_files(r.scene, dir, NULL, 0, "no file");
        hr_scene_destroy(r.scene);
    }
}

static void nff_scene_lists_its_file(hr_context *ctx, const char *dir)
{
    write_text(dir, "ball.nff", "s 0 0 0 1\n# secret.txt\n");
    char path[4200];
    snprintf(path, sizeof path, "%s/ball.nff", dir);
    hr_sdl_result r = {.struct_size = sizeof r};
    CHECK_MSG(hr_nff_load_file(ctx, path, &r) == HR_OK, "%s", hr_context_last_error(ctx));
    if (r.scene) {
        static const char *const want[] = {"ball.nff"};
        expect_files(r.scene, dir, want, 1, "NFF file");
        hr_scene_destroy(r.scene);
    }
}

/* A scene built in code: a mesh object's file, given relative to the
 * working directory (base_dir empty), listed absolute; hr_scene_note_file
 * by hand, once per path. */
static void built_scene_lists_its_mesh(hr_context *ctx, const char *dir)
{
    char old[4096];
    CHECK(getcwd(old, sizeof old) != NULL);
    CHECK(chdir(dir) == 0);
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_param p = {0};
    p.name = "file";
    p.type = HR_PARAM_STRING;
    p.string = "meshes/cube.obj";
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "mesh";
    d.params = &p;
    d.param_count = 1;
    CHECK_MSG(hr_scene_add_object(s, &d, NULL) == HR_OK, "%s", hr_context_last_error(ctx));
    CHECK_OK(hr_scene_note_file(s, "t.png"));
    CHECK_OK(hr_scene_note_file(s, "meshes/cube.obj"));
    CHECK(hr_scene_note_file(s, "") == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_scene_note_file(s, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(chdir(old) == 0);
    static const char *const want[] = {"meshes/cube.obj", "t.png"};
    expect_files(s, dir, want, 2, "built scene");
    hr_scene_destroy(s);
    CHECK(hr_scene_file_count(NULL) == 0 && hr_scene_file(NULL, 0) == NULL);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    char dir[] = "/tmp/hitray-files-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    sdl_scene_lists_what_it_read(ctx, dir);
    nff_scene_lists_its_file(ctx, dir);
    built_scene_lists_its_mesh(ctx, dir);
    hr_context_destroy(ctx);
    static const char *const made[] = {"t.png", "secret.txt", "meshes/cube.obj", "meshes", "scene.sdl",
                                       "ball.nff", ""};
    for (int i = 0; i < (int)(sizeof made / sizeof made[0]); i++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", dir, made[i]);
        CHECK_MSG(remove(path) == 0, "cannot remove %s", path);
    }
    return hr_test_end();
}
