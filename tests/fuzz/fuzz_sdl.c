/* Fuzz harness: the SDL reader (lib/sdl_*.c), through the public call
 * hr_sdl_load_string, with the real shape modules.
 *
 * The input is the scene text (up to its first NUL byte: the call takes a
 * C string). The reader must return HR_OK with a scene, or an error with no
 * scene whose message starts with "fuzz.sdl:<line>:<col>: " (every SDL
 * error is located, also those inside macros and those a library call
 * raised; only running out of memory is not) and whose error info names the
 * file and a line and column of the input. A scene read is committed and a
 * few rays are cast through Hill's queries: from the camera's eye through
 * the look point and around it, each with hr_scene_first_hit,
 * hr_scene_all_hits and hr_scene_shade, checking that the hits are finite,
 * sorted, inside (tmin, tmax), that the first hit is the first of all hits
 * (or one of them within rounding of its t, see first_among), and that the
 * colour is finite. Relative mesh names resolve in
 * tests/data/meshes, so `mesh cube.obj` works. Never a crash, a hang
 * (-timeout) or a leak (the leak checker). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "fuzz_input.h"
#include "fuzz_scene.h"

#define SCENE_NAME "fuzz.sdl"

static hr_context *ctx;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    if (hr_context_create(&ctx) != HR_OK) fuzz_fail("sdl: no context");
    /* Load every module now, not during the first input that names one:
     * libFuzzer then sees their coverage from the start. */
    hr_context_module_count(ctx);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    hr_sdl_result r = {.struct_size = sizeof r};
    const hr_status st = hr_sdl_load_string(ctx, text, SCENE_NAME,
                                            HR_TEST_SOURCE_DIR "/tests/data/meshes", &r);
    if (st != HR_OK) {
        fuzz_scene_check_error(ctx, "sdl", SCENE_NAME, st, &r, strlen(text));
        free(text);
        return 0;
    }
    free(text);
    if (!r.scene) fuzz_fail("sdl: HR_OK and no scene");
    fuzz_scene_check_rays(ctx, "sdl", &r);
    hr_scene_destroy(r.scene);
    return 0;
}
