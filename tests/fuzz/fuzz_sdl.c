/* Fuzz harness: the SDL reader (lib/sdl/sdl_*.c), through the public call
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
#include <hitray/hitray.h>

#include "fuzz_input.h"
#include "fuzz_reader_checks.h"

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

/* Relative mesh names resolve in tests/data/meshes. */
static hr_status read_sdl(hr_context *c, const char *text, const char *name, hr_sdl_result *out)
{
    return hr_sdl_load_string(c, text, name, HR_TEST_SOURCE_DIR "/tests/data/meshes", out);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_reader_input(ctx, "sdl", SCENE_NAME, read_sdl, data, size);
    return 0;
}
