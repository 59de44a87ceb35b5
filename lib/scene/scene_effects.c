/* The effects analysis: which effects (HR_EFFECT_*) a scene calls for,
 * and each material's flags (HR_MAT_*), worked out at commit so that shade
 * tests one bit. */
#include <stdint.h>
#include <string.h>

#include "scene/scene_internal.h"
#include "scene/material_analysis.h"
#include "texture/texture.h"
#include "geometry/vec.h"

/* a <- a * b, 4x4 row-major. */
static void multiply(double a[16], const double b[16])
{
    double r[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            r[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j] +
                           a[4 * i + 3] * b[12 + j];
    memcpy(a, r, sizeof r);
}

/* The textured object's world-to-object map and back, for its texture. A
 * child's m maps to its parent's space: the world map is the product of
 * the maps up the chain, the parent's on the left; the inverse the other
 * way round. */
static void place_texture(hr_object *o)
{
    hr_texture *t = o->texture;
    if (!t) return;
    memcpy(t->to_world, o->m, sizeof t->to_world);
    memcpy(t->to_object, o->inv, sizeof t->to_object);
    for (const hr_object *p = o->parent; p; p = p->parent) {
        double m[16];
        memcpy(m, p->m, sizeof m);
        multiply(m, t->to_world);
        memcpy(t->to_world, m, sizeof m);
        multiply(t->to_object, p->inv);
    }
}


/* Which effects each material and the whole scene call for. A coefficient
 * below Hill's threshold spawns no ray and contributes nothing (the ray is
 * not worth tracing), so such a material does not make the scene reflect.
 * The material flags do not depend on maxRecursionDepth: hr_scene_shade and
 * hr_render may ask for more depth than the scene's, and shade stops at the
 * depth it is given. Only the scene's effects say what its own depth does. */
void hri_scene_work_out_effects(hr_scene *s)
{
    const hr_scene_globals *g = &s->globals;
    int lit = 0;
    for (int32_t i = 0; i < s->light_count; i++) lit |= !rgb_is_zero(s->lights[i].color);
    uint32_t effects = 0;
    for (int64_t i = 0; i < s->object_count; i++) {
        hr_object *o = s->objects[i];
        const hr_material *m = o->material;
        uint32_t f = 0;
        if (o->cls->flags & HR_SHAPE_COMPOSITE) {
            o->mat_flags = 0; /* its hits carry the leaves' materials */
            continue;
        }
        if (!rgb_is_zero(m->emissive)) f |= HR_MAT_EMITS;
        if (!rgb_is_zero(rgb_mul(m->ambient, g->global_ambient))) f |= HR_MAT_AMBIENT;
        if (lit && !rgb_is_zero(m->diffuse)) f |= HR_MAT_DIFFUSE;
        if (lit && !rgb_is_zero(m->specular)) f |= HR_MAT_SPECULAR;
        if (m->specular_fraction > 0) f |= HR_MAT_COOK_TORRANCE;
        if (o->texture) f |= HR_MAT_TEXTURED;
        if (m->reflectivity > 0 && m->reflectivity >= g->min_reflectivity) f |= HR_MAT_REFLECTS;
        if (m->transparency > 0 && m->transparency >= g->min_transparency) f |= HR_MAT_REFRACTS;
        if (f & (HR_MAT_DIFFUSE | HR_MAT_SPECULAR))
            for (int32_t k = 0; k < s->light_count; k++)
                if (hri_light_adds_nothing(&s->lights[k], m, f)) f |= HR_MAT_INERT_LIGHT;
        o->mat_flags = f;
        place_texture(o);
        if (o->texture && (f & (HR_MAT_AMBIENT | HR_MAT_DIFFUSE))) effects |= HR_EFFECT_TEXTURE;
        o->specular_cutoff = hri_specular_cutoff(m->specular_exponent);
        if (f & HR_MAT_EMITS) effects |= HR_EFFECT_EMISSION;
        if (f & HR_MAT_AMBIENT) effects |= HR_EFFECT_AMBIENT;
        if (f & HR_MAT_DIFFUSE) effects |= HR_EFFECT_DIFFUSE | HR_EFFECT_SHADOWS;
        if (f & HR_MAT_SPECULAR) effects |= HR_EFFECT_SPECULAR | HR_EFFECT_SHADOWS;
        if (f & HR_MAT_REFLECTS) effects |= HR_EFFECT_REFLECTION;
        if (f & HR_MAT_REFRACTS) effects |= HR_EFFECT_REFRACTION;
    }
    s->bounce_effects = effects & (HR_EFFECT_REFLECTION | HR_EFFECT_REFRACTION);
    if (g->max_recursion_depth == 0) effects &= ~s->bounce_effects;
    s->effects = effects;
}

HR_API uint32_t hr_scene_effects(const hr_scene *s) { return s && s->committed ? s->effects : 0; }

HR_API const char *hr_effect_name(uint32_t effect)
{
    switch (effect) {
    case HR_EFFECT_EMISSION: return "emission";
    case HR_EFFECT_AMBIENT: return "ambient";
    case HR_EFFECT_DIFFUSE: return "diffuse";
    case HR_EFFECT_SPECULAR: return "specular";
    case HR_EFFECT_SHADOWS: return "shadows";
    case HR_EFFECT_REFLECTION: return "reflection";
    case HR_EFFECT_REFRACTION: return "refraction";
    case HR_EFFECT_SUPERSAMPLING: return "supersampling";
    case HR_EFFECT_TEXTURE: return "texture";
    default: return NULL;
    }
}
