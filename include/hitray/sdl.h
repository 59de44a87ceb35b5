/* hitray: reading Hill's SDL scene files.
 *
 * The reader builds the scene with the same public calls any program makes.
 * On error it returns HR_ERROR_SDL (HR_ERROR_IO for a file it cannot read,
 * HR_ERROR_UNSUPPORTED for `diamond`, or the error of the library call that
 * failed, such as HR_ERROR_MODULE), makes no scene, and the context's last error
 * names file:line:col and what was expected; hr_context_last_error_info gives
 * the parts. Errors inside an expanded macro name the line of the `use` and
 * of the definition. */
#ifndef HITRAY_SDL_H
#define HITRAY_SDL_H

#include "camera.h"
#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hr_sdl_result {
    uint32_t struct_size;
    int32_t has_camera; /* 1 if the file set `camera` (then `camera` holds it) */
    hr_scene *scene;    /* new, not committed; the caller destroys it */
    hr_camera camera;   /* size 640x480 unless the caller changes it */
} hr_sdl_result;

HR_API hr_status hr_sdl_load_file(hr_context *ctx, const char *path, hr_sdl_result *out);
/* `name` is used in messages (NULL: "<string>"); `base_dir` resolves relative
 * file names such as meshes (NULL: the current directory). */
HR_API hr_status hr_sdl_load_string(hr_context *ctx, const char *text, const char *name,
                                    const char *base_dir, hr_sdl_result *out);

#ifdef __cplusplus
}
#endif
#endif
