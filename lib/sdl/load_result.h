/* Internal: the result struct the scene file readers fill (hr_sdl_result,
 * shared by the SDL and NFF readers). The caller's struct may be older,
 * shorter than ours: it must at least reach the scene pointer, and only the
 * bytes it has are written. */
#ifndef HITRAY_LIB_SDL_LOAD_RESULT_H
#define HITRAY_LIB_SDL_LOAD_RESULT_H

#include <hitray/hitray.h>

/* No scene, no camera, the default camera in `camera`. */
void hri_load_result_empty(hr_sdl_result *r);
/* Copy the bytes the caller's struct has, keeping its struct_size. */
void hri_load_result_give(hr_sdl_result *out, const hr_sdl_result *full);
/* Checks ctx and out (`reader` names the reader in the message, "SDL") and
 * empties out, so that every later failure leaves out->scene NULL. */
hr_status hri_load_result_begin(hr_context *ctx, hr_sdl_result *out, const char *reader);

#endif
