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
#include <string.h>

#include "errors.h"
#include "sdl_diag.h"
#include "sdl_reader.h"
#include "solid_textures.h"

static const struct {
    const char *keyword;
    size_t offset;
} color_fields[] = {
    {"ambient", offsetof(hr_material, ambient)},
    {"diffuse", offsetof(hr_material, diffuse)},
    {"specular", offsetof(hr_material, specular)},
    {"emissive", offsetof(hr_material, emissive)},
};

static const struct {
    const char *keyword;
    size_t offset;
} number_fields[] = {
    {"specularExponent", offsetof(hr_material, specular_exponent)},
    {"reflectivity", offsetof(hr_material, reflectivity)},
    {"transparency", offsetof(hr_material, transparency)},
    {"speedOfLight", offsetof(hr_material, speed_of_light)},
    {"specularFraction", offsetof(hr_material, specular_fraction)},
    {"surfaceRoughness", offsetof(hr_material, surface_roughness)},
};

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
    for (size_t i = 0; i < sizeof color_fields / sizeof color_fields[0]; i++)
        if (strcmp(keyword.token->text, color_fields[i].keyword) == 0) {
            hr_color c;
            hr_status st = sdl_read_color(r, keyword, &c);
            if (st) return st;
            memcpy((char *)&r->material + color_fields[i].offset, &c, sizeof c);
            return check_value(r, keyword);
        }
    return hr_error(r->ctx, HR_ERROR_SDL, "internal: '%s' is not a material colour",
                    keyword.token->text);
}

hr_status sdl_cmd_material_number(sdl_reader *r, sdl_located keyword)
{
    for (size_t i = 0; i < sizeof number_fields / sizeof number_fields[0]; i++)
        if (strcmp(keyword.token->text, number_fields[i].keyword) == 0) {
            double v;
            sdl_located at;
            hr_status st = sdl_read_number(r, keyword, &v, &at);
            if (st) return st;
            memcpy((char *)&r->material + number_fields[i].offset, &v, sizeof v);
            sdl_note_coefficient(r, keyword);
            return check_value(r, at);
        }
    return hr_error(r->ctx, HR_ERROR_SDL, "internal: '%s' is not a material number",
                    keyword.token->text);
}

hr_status sdl_cmd_texture(sdl_reader *r, sdl_located keyword)
{
    int64_t texture;
    hr_status st = sdl_read_whole(r, keyword, (double)INT32_MIN, (double)INT32_MAX, &texture);
    if (st) return st;
    if (texture < 0 && !hr_solid_texture_name((int32_t)texture)) {
        char known[256];
        hr_solid_texture_list(known, sizeof known);
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
                return hr_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
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
