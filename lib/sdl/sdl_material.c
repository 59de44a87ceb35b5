/* SDL's material commands (lib/sdl/sdl_reader.h). The material is sticky: every
 * later object gets a copy of it, until it changes or `defaultMaterials`
 * resets it; push/pop do not save it. `texture` names a solid texture
 * (checked here) or an image texture, whose pixmap and parameters the
 * scene checks at each object that takes it (lib/texture/texture.c). The
 * reader is a client of the public API: hr_solid_texture_name says which
 * solid textures there are. */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_reader.h"
#include "util/solid_textures.h"

void sdl_material_reset(sdl_reader *r)
{
    free(r->parameters);
    r->parameters = NULL;
    hr_material_default(&r->material);
    r->material.parameters = NULL;
    r->material.parameter_count = 0;
}

/* A value the scene would refuse is reported here, at the place that set
 * it, not at the next object (nor never, if no object follows). The limits
 * are the library's own: hr_material_validate. */
static hr_status check_value(sdl_reader *r, sdl_located at)
{
    if (hr_material_validate(r->ctx, &r->material) == HR_OK) return HR_OK;
    char why[512];
    snprintf(why, sizeof why, "%s", hr_context_last_error(r->ctx));
    return sdl_error(r->src, HR_ERROR_SDL, at, "%s", why);
}

hr_status sdl_cmd_material_color(sdl_reader *r, sdl_located keyword)
{
    hr_status st = sdl_read_field(r, keyword, &hri_material_field_table, &r->material, NULL);
    return st ? st : check_value(r, keyword);
}

hr_status sdl_cmd_material_number(sdl_reader *r, sdl_located keyword)
{
    sdl_located at;
    hr_status st = sdl_read_field(r, keyword, &hri_material_field_table, &r->material, &at);
    if (st) return st;
    sdl_note_coefficient(r, keyword);
    return check_value(r, at);
}

hr_status sdl_cmd_texture(sdl_reader *r, sdl_located keyword)
{
    int64_t texture;
    hr_status st = sdl_read_whole(r, keyword, (double)INT32_MIN, (double)INT32_MAX, &texture);
    if (st) return st;
    if (texture < 0 && !hr_solid_texture_name((int32_t)texture)) {
        char known[256];
        hri_solid_texture_list(known, sizeof known);
        return sdl_error(r->src, HR_ERROR_SDL, keyword, "there is no solid texture %lld (there are %s)",
                         (long long)texture, known);
    }
    r->material.texture = (int32_t)texture;
    return HR_OK;
}

hr_status sdl_cmd_parameters(sdl_reader *r, sdl_located keyword)
{
    int64_t count;
    hr_status st = sdl_read_whole(r, keyword, 0.0, (double)INT32_MAX, &count);
    if (st) return st;
    /* Grow as the numbers come rather than trusting `count` for one big
     * allocation: a file saying "parameters 2000000000" ends long before. */
    double *values = NULL;
    int64_t capacity = 0;
    for (int64_t i = 0; i < count; i++) {
        if (i == capacity) {
            capacity = capacity ? 2 * capacity : 8;
            if (capacity > count) capacity = count;
            double *grown = realloc(values, (size_t)capacity * sizeof *grown);
            if (!grown) {
                free(values);
                return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
            }
            values = grown;
        }
        if ((st = sdl_read_number(r, keyword, &values[i], NULL))) {
            free(values);
            return st;
        }
    }
    free(r->parameters);
    r->parameters = values;
    r->material.parameters = values;
    r->material.parameter_count = (int32_t)count;
    return HR_OK;
}

hr_status sdl_cmd_default_materials(sdl_reader *r, sdl_located keyword)
{
    (void)keyword;
    sdl_material_reset(r);
    return HR_OK;
}
