/* Fuzz harness: the NFF reader (lib/nff/nff_*.c), through the public call
 * hr_nff_load_string, with the real shape modules; the twin of fuzz_sdl.c.
 *
 * The input is the scene text (up to its first NUL byte: the call takes a
 * C string). The reader must return HR_OK with a scene, or an error with no
 * scene whose message starts with "fuzz.nff:<line>:<col>: " (every NFF
 * error is located, those a library call raised too; only running out of
 * memory is not) and whose error info names the file and a line and column
 * of the input. A scene read is committed and five rays from its camera go
 * through Hill's queries, with fuzz_sdl.c's checks (fuzz_reader_checks.c). Polygon
 * and vertex counts are bounded by the text, so no input may allocate much
 * more than its own size (-rss_limit_mb), nor hang (-timeout). */
#include <hitray/hitray.h>

#include "fuzz_input.h"
#include "fuzz_reader_checks.h"

#define SCENE_NAME "fuzz.nff"

static hr_context *ctx;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    if (hr_context_create(&ctx) != HR_OK) fuzz_fail("nff: no context");
    /* Load every module now, not during the first input that needs one. */
    hr_context_module_count(ctx);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_reader_input(ctx, "nff", SCENE_NAME, hr_nff_load_string, data, size);
    return 0;
}
