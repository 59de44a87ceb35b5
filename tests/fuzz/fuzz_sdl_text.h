/* What the SDL-reading harnesses (sdl, scene) share: an input read as the
 * text of a scene file named "fuzz.sdl", up to its first NUL byte (the call
 * takes a C string), with relative mesh names resolved in
 * tests/data/meshes. */
#ifndef HR_FUZZ_SDL_TEXT_H
#define HR_FUZZ_SDL_TEXT_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/hitray.h>

#define FUZZ_SCENE_NAME "fuzz.sdl"

/* hr_sdl_load_string of the input into *out (struct_size set here);
 * *length receives the text's length. Out of memory for the copy reads as
 * HR_ERROR_OUT_OF_MEMORY with no scene. */
hr_status fuzz_load_sdl(hr_context *ctx, const uint8_t *data, size_t size, hr_sdl_result *out,
                        size_t *length);

#endif
