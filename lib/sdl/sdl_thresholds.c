/* Warnings for coefficients the renderer will ignore (lib/sdl/sdl_reader.h).
 *
 * A reflectivity above 0 but below minReflectivity (a transparency below
 * minTransparency) spawns no ray and adds nothing: Hill's thresholds, with
 * defaults of 0.5 that make a glass sphere's `reflectivity 0.08` vanish
 * without a word. Which coefficients fall below is known only at the end of
 * the file (the thresholds may be set anywhere), so the reader notes each
 * coefficient command that some object used, and warns at the end, naming
 * the command's line. One note per command used (not per object), and at
 * most SDL_SHOWN_THRESHOLD_WARNINGS warnings per kind, then one saying how
 * many more. */
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_reader.h"

#define SDL_SHOWN_THRESHOLD_WARNINGS 8

static const struct {
    const char *keyword, *threshold;
    size_t field;
} kinds[SDL_COEFFICIENT_KINDS] = {
    {"reflectivity", "minReflectivity", offsetof(hr_material, reflectivity)},
    {"transparency", "minTransparency", offsetof(hr_material, transparency)},
};

static double coefficient(const hr_material *m, int kind)
{
    double v;
    memcpy(&v, (const char *)m + kinds[kind].field, sizeof v);
    return v;
}

static double threshold(const hr_scene_globals *g, int kind)
{
    return kind == 0 ? g->min_reflectivity : g->min_transparency;
}

void sdl_note_coefficient(sdl_reader *r, sdl_located keyword)
{
    for (int k = 0; k < SDL_COEFFICIENT_KINDS; k++)
        if (strcmp(keyword.token->text, kinds[k].keyword) == 0) r->coefficient_at[k] = keyword;
}

hr_status sdl_note_material_use(sdl_reader *r)
{
    for (int k = 0; k < SDL_COEFFICIENT_KINDS; k++) {
        const sdl_located at = r->coefficient_at[k];
        double v = coefficient(&r->material, k);
        /* Only a value some threshold within [0, 1] can hide, set by a
         * command not noted yet. */
        if (!at.token || !(v > 0.0 && v < 1.0)) continue;
        if (r->last_noted[k].token == at.token && r->last_noted[k].expansion == at.expansion)
            continue;
        if (r->coefficient_use_count == r->coefficient_use_capacity) {
            size_t capacity = r->coefficient_use_capacity ? 2 * r->coefficient_use_capacity : 16;
            sdl_coefficient_use *grown = realloc(r->coefficient_uses, capacity * sizeof *grown);
            if (!grown) return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
            r->coefficient_uses = grown;
            r->coefficient_use_capacity = capacity;
        }
        r->coefficient_uses[r->coefficient_use_count++] = (sdl_coefficient_use){k, at, v};
        r->last_noted[k] = at;
    }
    return HR_OK;
}

void sdl_warn_thresholds(sdl_reader *r)
{
    size_t below[SDL_COEFFICIENT_KINDS] = {0};
    for (size_t i = 0; i < r->coefficient_use_count; i++) {
        const sdl_coefficient_use *u = &r->coefficient_uses[i];
        const double limit = threshold(&r->globals, u->kind);
        if (!(u->value < limit)) continue;
        if (below[u->kind]++ < SDL_SHOWN_THRESHOLD_WARNINGS)
            sdl_warning(r->src, HR_WARNING_BELOW_THRESHOLD, u->at,
                        "%s %g is below %s %g: it spawns no ray and adds nothing to the image "
                        "(set %s to at most %g to see it)",
                        kinds[u->kind].keyword, u->value, kinds[u->kind].threshold, limit,
                        kinds[u->kind].threshold, u->value);
    }
    for (int k = 0; k < SDL_COEFFICIENT_KINDS; k++)
        if (below[k] > SDL_SHOWN_THRESHOLD_WARNINGS)
            hri_warn(r->ctx, HR_WARNING_BELOW_THRESHOLD, r->src->file, 0, 0,
                    "%s: %zu more %s commands below %s %g", r->src->file,
                    below[k] - SDL_SHOWN_THRESHOLD_WARNINGS, kinds[k].keyword, kinds[k].threshold,
                    threshold(&r->globals, k));
}
