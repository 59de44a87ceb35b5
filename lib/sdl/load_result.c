/* The result struct of the scene file readers (sdl/load_result.h; the NFF reader uses it too). */
#include "util/sized_copy.h"
#include "sdl/load_result.h"

#include <stddef.h>
#include <string.h>

#include "util/errors.h"

#define RESULT_MIN_SIZE (offsetof(hr_sdl_result, scene) + sizeof(hr_scene *))

void hri_load_result_give(hr_sdl_result *out, const hr_sdl_result *full)
{
    HR_SIZED_COPY_OUT(out, full);
}

void hri_load_result_empty(hr_sdl_result *r)
{
    memset(r, 0, sizeof *r);
    r->struct_size = sizeof *r;
    hr_camera_default(&r->camera);
}

hr_status hri_load_result_begin(hr_context *ctx, hr_sdl_result *out, const char *reader)
{
    if (!ctx) return HR_ERROR_INVALID_ARGUMENT;
    if (!out || out->struct_size < RESULT_MIN_SIZE)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "%s: the result is NULL or its struct_size is not set", reader);
    hr_sdl_result empty;
    hri_load_result_empty(&empty);
    hri_load_result_give(out, &empty);
    return HR_OK;
}
