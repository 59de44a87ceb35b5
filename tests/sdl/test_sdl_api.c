/* The SDL entry points as a caller sees them: files and their I/O errors,
 * names and places in messages, hr_context_last_error_info, argument
 * checks, and older (shorter) result structs. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdl_test_support.h"

static void write_file(const char *path, const char *bytes, size_t n)
{
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    fwrite(bytes, 1, n, f);
    fclose(f);
}

static void files(hr_context *ctx)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;

    /* A missing file: HR_ERROR_IO naming the path. */
    const char *missing = HR_TEST_BINARY_DIR "/tests/no-such-scene.dat";
    r.scene = (hr_scene *)&r; /* must be cleared */
    CHECK(hr_sdl_load_file(ctx, missing, &r) == HR_ERROR_IO);
    CHECK(r.scene == NULL);
    CHECK_MSG(strstr(hr_context_last_error(ctx), missing) != NULL, "message: %s",
              hr_context_last_error(ctx));
    hr_error_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    CHECK_OK(hr_context_last_error_info(ctx, &info));
    CHECK(info.status == HR_ERROR_IO && strcmp(info.file, missing) == 0);

    /* A directory is not a scene file. */
    CHECK(hr_sdl_load_file(ctx, HR_TEST_BINARY_DIR "/tests", &r) == HR_ERROR_IO);
    CHECK(r.scene == NULL);

    /* A file: messages use the path as given; the info has the parts. */
    char path[1024];
    snprintf(path, sizeof path, "%s/tests/sdl_api_test.dat", HR_TEST_BINARY_DIR);
    const char bad[] = "sphere\n\n   scale 1 2 x\n";
    write_file(path, bad, sizeof bad - 1);
    CHECK(hr_sdl_load_file(ctx, path, &r) == HR_ERROR_SDL);
    char want[1200];
    snprintf(want, sizeof want, "%s:3:14: expected a number after 'scale', found 'x'", path);
    CHECK_MSG(strcmp(hr_context_last_error(ctx), want) == 0, "message: %s",
              hr_context_last_error(ctx));
    CHECK_OK(hr_context_last_error_info(ctx, &info));
    CHECK(info.status == HR_ERROR_SDL && strcmp(info.file, path) == 0 && info.line == 3 &&
          info.column == 14);
    CHECK(strcmp(info.message, want) == 0);

    /* A NUL byte is an error at its place: reading stops at the first, even
     * in a comment (a text file has none; /dev/zero is all NULs). */
    const char nul[] = "sphere\ncu\0be\n";
    write_file(path, nul, sizeof nul - 1);
    CHECK(hr_sdl_load_file(ctx, path, &r) == HR_ERROR_SDL);
    CHECK_OK(hr_context_last_error_info(ctx, &info));
    CHECK(info.line == 2 && info.column == 3);
    CHECK_MSG(strstr(info.message, "NUL byte") != NULL, "message: %s", info.message);
    const char nul_in_comment[] = "sphere ! a\0b\ncube";
    write_file(path, nul_in_comment, sizeof nul_in_comment - 1);
    CHECK(hr_sdl_load_file(ctx, path, &r) == HR_ERROR_SDL && r.scene == NULL);
    CHECK_OK(hr_context_last_error_info(ctx, &info));
    CHECK(info.line == 1 && info.column == 11);

    /* A good file, no final newline. */
    write_file(path, "camera 0 0 9 0 0 0 0 1 0 40 sphere", 34);
    CHECK_OK(hr_sdl_load_file(ctx, path, &r));
    CHECK(r.has_camera == 1 && r.camera.eye.z == 9);
    hr_scene_destroy(r.scene);
    remove(path);
}

static void names(hr_context *ctx)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    /* NULL name: "<string>". */
    CHECK(hr_sdl_load_string(ctx, "frob", NULL, NULL, &r) == HR_ERROR_SDL);
    /* A word no module provides either: the message goes on to say where
     * modules were looked for. */
    static const char frob[] = "<string>:1:1: unknown keyword 'frob': no SDL command, and no shape module "
                               "provides 'frob' (searched: ";
    CHECK_MSG(strncmp(hr_context_last_error(ctx), frob, sizeof frob - 1) == 0, "message: %s",
              hr_context_last_error(ctx));
    CHECK(strstr(hr_context_last_error(ctx), "HITRAY_SHAPE_PATH") != NULL);
    /* Success leaves a usable, uncommitted scene that commits. */
    CHECK_OK(hr_sdl_load_string(ctx, "light 0 5 5 1 1 1 sphere", "ok.dat", NULL, &r));
    CHECK(r.scene && !hr_scene_is_committed(r.scene));
    if (r.scene) {
        CHECK_OK(hr_scene_commit(r.scene));
        hr_scene_destroy(r.scene);
    }
}

static void arguments(hr_context *ctx)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_sdl_load_string(NULL, "sphere", NULL, NULL, &r) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_sdl_load_string(ctx, NULL, NULL, NULL, &r) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(r.scene == NULL);
    CHECK(hr_sdl_load_string(ctx, "sphere", NULL, NULL, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_sdl_load_file(ctx, NULL, &r) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_sdl_load_file(NULL, "x", &r) == HR_ERROR_INVALID_ARGUMENT);
    r.struct_size = 0;
    CHECK(hr_sdl_load_string(ctx, "sphere", NULL, NULL, &r) == HR_ERROR_INVALID_ARGUMENT);

    /* An older caller whose struct ends before `camera`: only its bytes
     * are written. */
    unsigned char buffer[sizeof(hr_sdl_result) + 64];
    memset(buffer, 0xAB, sizeof buffer);
    hr_sdl_result *old = (hr_sdl_result *)(void *)buffer;
    size_t old_size = offsetof(hr_sdl_result, camera);
    old->struct_size = (uint32_t)old_size;
    CHECK_OK(hr_sdl_load_string(ctx, "camera 0 0 9 0 0 0 0 1 0 40 sphere", NULL, NULL, old));
    CHECK(old->struct_size == old_size && old->has_camera == 1 && old->scene != NULL);
    int untouched = 1;
    for (size_t i = old_size; i < sizeof buffer; i++) untouched &= buffer[i] == 0xAB;
    CHECK_MSG(untouched, "bytes past struct_size were written");
    hr_scene_destroy(old->scene);
}

int main(void)
{
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);
    files(ctx);
    names(ctx);
    arguments(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
