/* An input read as SDL text (fuzz_sdl_text.h). */
#include "fuzz_sdl_text.h"

#include <stdlib.h>
#include <string.h>

hr_status fuzz_load_sdl(hr_context *ctx, const uint8_t *data, size_t size, hr_sdl_result *out,
                        size_t *length)
{
    memset(out, 0, sizeof *out);
    out->struct_size = sizeof *out;
    *length = 0;
    char *text = malloc(size + 1);
    if (!text) return HR_ERROR_OUT_OF_MEMORY;
    memcpy(text, data, size);
    text[size] = '\0';
    *length = strlen(text);
    hr_status st =
        hr_sdl_load_string(ctx, text, FUZZ_SCENE_NAME, HR_TEST_SOURCE_DIR "/tests/data/meshes", out);
    free(text);
    return st;
}
