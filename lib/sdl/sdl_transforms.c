/* SDL's transform commands (lib/sdl/sdl_reader.h): Hill's stack of matrix pairs,
 * changed only through the public hr_transform_* calls, which post-multiply
 * (M <- M T, M^-1 <- T^-1 M^-1), so the command written last acts on the
 * object first. */
#include <math.h>
#include <stdlib.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_reader.h"

hr_status sdl_cmd_translate(sdl_reader *r, sdl_located keyword)
{
    double d[3];
    hr_status st = sdl_read_numbers(r, keyword, 3, d);
    if (st) return st;
    hr_transform_translate(sdl_current_transform(r), d[0], d[1], d[2]);
    return HR_OK;
}

hr_status sdl_cmd_scale(sdl_reader *r, sdl_located keyword)
{
    double s[3];
    for (int i = 0; i < 3; i++) {
        sdl_located at;
        hr_status st = sdl_read_number(r, keyword, &s[i], &at);
        if (st) return st;
        /* M^-1 would not exist, and every object after it would be flat. */
        if (s[i] == 0.0)
            return sdl_error(r->src, HR_ERROR_SDL, at,
                             "'scale' factors must be non-zero (the object would be "
                             "degenerate), found '%s'",
                             at.token->text);
    }
    if (hr_transform_scale(sdl_current_transform(r), s[0], s[1], s[2]) != HR_OK)
        return sdl_error(r->src, HR_ERROR_NUMERIC, keyword,
                         "'scale' %g %g %g was refused: the transform or its inverse would "
                         "leave the range of a double",
                         s[0], s[1], s[2]);
    return HR_OK;
}

hr_status sdl_cmd_rotate(sdl_reader *r, sdl_located keyword)
{
    double v[4];
    hr_status st = sdl_read_numbers(r, keyword, 4, v);
    if (st) return st;
    double biggest = fmax(fabs(v[1]), fmax(fabs(v[2]), fabs(v[3])));
    if (biggest == 0.0)
        return sdl_error(r->src, HR_ERROR_SDL, keyword,
                         "'rotate' needs a non-zero axis, found %g %g %g", v[1], v[2], v[3]);
    /* Divide by the largest component first: the axis is normalised anyway,
     * and this keeps its length from overflowing (1e200) or vanishing
     * (1e-200) on the way. */
    if (hr_transform_rotate(sdl_current_transform(r), v[0], v[1] / biggest, v[2] / biggest,
                            v[3] / biggest) != HR_OK)
        return sdl_error(r->src, HR_ERROR_NUMERIC, keyword, "'rotate' %g %g %g %g was refused",
                         v[0], v[1], v[2], v[3]);
    return HR_OK;
}

hr_status sdl_cmd_push(sdl_reader *r, sdl_located keyword)
{
    if (r->stack_count >= SDL_MAX_TRANSFORM_DEPTH)
        return sdl_error(r->src, HR_ERROR_SDL, keyword,
                         "more than %d 'push' without 'pop': the transform stack is full",
                         SDL_MAX_TRANSFORM_DEPTH);
    if (r->stack_count == r->stack_capacity) {
        int32_t capacity = 2 * r->stack_capacity;
        hr_transform *grown = realloc(r->stack, (size_t)capacity * sizeof *grown);
        if (!grown) return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        r->stack = grown;
        r->stack_capacity = capacity;
    }
    r->stack[r->stack_count] = r->stack[r->stack_count - 1];
    r->stack_count++;
    return HR_OK;
}

hr_status sdl_cmd_pop(sdl_reader *r, sdl_located keyword)
{
    if (r->stack_count == 1)
        return sdl_error(r->src, HR_ERROR_SDL, keyword,
                         "'pop' without a matching 'push': only the base entry of the transform "
                         "stack is left");
    r->stack_count--;
    return HR_OK;
}

hr_status sdl_cmd_identity_affine(sdl_reader *r, sdl_located keyword)
{
    (void)keyword;
    hr_transform_identity(sdl_current_transform(r));
    return HR_OK;
}
