/* Materials: the defaults (Hill's) and the checks that keep every pixel
 * finite (HR_MAX_COLOR, util/color_bounds.h). */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "util/errors.h"
#include "util/strutil.h"
#include "util/field_table.h"
#include "scene/scene_internal.h"
#include "util/sized_copy.h"

HR_API void hr_material_default(hr_material *m)
{
    if (!m) return;
    memset(m, 0, sizeof *m);
    m->struct_size = sizeof *m;
    hri_fields_default(&hri_material_field_table, m);
}

hr_status hri_material_check(hr_context *ctx, const hr_material *m)
{
    char shown[HR_SHORTEST_BYTES]; /* a value in a message (hri_shortest) */
    const hr_field_table *t = &hri_material_field_table;
    for (size_t i = 0; i < t->count; i++) {
        if (t->fields[i].kind != HR_FIELD_COLOR) continue;
        hr_color c;
        memcpy(&c, (const char *)m + t->fields[i].offset, sizeof c);
        if (!hri_color_in_range(c))
            return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                            "material: %s (%g %g %g) must be finite, each within +-%g",
                            t->fields[i].word, c.r, c.g, c.b, HR_MAX_COLOR);
    }
    if (!(m->specular_exponent >= 0 && m->specular_exponent <= HR_MAX_EXPONENT))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: specularExponent %s must be within [0, %g]",
                        hri_shortest(m->specular_exponent, shown), HR_MAX_EXPONENT);
    if (!(m->reflectivity >= 0 && m->reflectivity <= 1))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: reflectivity %s must be within [0, 1]", hri_shortest(m->reflectivity, shown));
    if (!(m->transparency >= 0 && m->transparency <= 1))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: transparency %s must be within [0, 1]", hri_shortest(m->transparency, shown));
    if (!isfinite(m->specular_fraction) || !isfinite(m->surface_roughness))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: specularFraction and surfaceRoughness must be finite");
    if (!(m->specular_fraction >= 0 && m->specular_fraction <= 1))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: specularFraction %s must be within [0, 1]", hri_shortest(m->specular_fraction, shown));
    /* Beckmann's m: below 1e-3 the highlight is narrower than a pixel of any
     * view, and 1 / m^2 would let one term grow past what keeps a pixel
     * finite; past 100 it is flat. Only Cook-Torrance reads it. */
    if (m->specular_fraction > 0 && !(m->surface_roughness >= 1e-3 && m->surface_roughness <= 100))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: surfaceRoughness %s must be within [0.001, 100] where "
                        "specularFraction is above 0",
                        hri_shortest(m->surface_roughness, shown));
    if (!(m->speed_of_light > 0.0) || !isfinite(m->speed_of_light))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: speedOfLight must be positive and finite, not %g",
                        m->speed_of_light);
    if (m->parameter_count < 0 || (m->parameter_count > 0 && !m->parameters))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "material: bad texture parameter list");
    return HR_OK;
}

HR_API hr_status hr_material_validate(hr_context *ctx, const hr_material *m)
{
    if (!m || m->struct_size < sizeof(uint32_t))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "material: NULL or struct_size not set");
    hr_material full;
    hr_material_default(&full);
    HR_SIZED_COPY_IN(&full, m);
    return hri_material_check(ctx, &full);
}
