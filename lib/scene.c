/* Scenes: building (objects, lights, globals), introspection and commit.
 * Tracing is in trace.c, shading in shade.c, rendering in render.c. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "context_internal.h"
#include "errors.h"
#include "field_table.h"
#include "scene_internal.h"
#include "scene_params.h"
#include "sized_copy.h"
#include "specular.h"
#include "texture.h"
#include "ray_cull.h"
#include "vec.h"

HR_API void hr_material_default(hr_material *m)
{
    if (!m) return;
    memset(m, 0, sizeof *m);
    m->struct_size = sizeof *m;
    hr_fields_default(&hr_material_field_table, m);
}

HR_API void hr_scene_globals_default(hr_scene_globals *g)
{
    if (!g) return;
    memset(g, 0, sizeof *g);
    g->struct_size = sizeof *g;
    hr_fields_default(&hr_globals_field_table, g);
}

HR_API hr_status hr_scene_create(hr_context *ctx, hr_scene **out)
{
    if (!ctx || !out) return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_scene_create: NULL argument");
    *out = NULL;
    hr_scene *s = calloc(1, sizeof *s);
    if (!s) return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    s->ctx = ctx;
    hr_scene_globals_default(&s->globals);
    *out = s;
    return HR_OK;
}

/* A zeroed object on cache lines of its own (HR_OBJECT_ALIGN), so that its
 * fields tracing reads first share the fewest lines (hr_object); free()
 * releases it. */
static hr_object *object_alloc(void)
{
    const size_t size = (sizeof(hr_object) + HR_OBJECT_ALIGN - 1) / HR_OBJECT_ALIGN * HR_OBJECT_ALIGN;
    hr_object *o = aligned_alloc(HR_OBJECT_ALIGN, size);
    if (o) memset(o, 0, size);
    return o;
}

static void object_free(hr_object *o)
{
    if (!o) return;
    if (o->shape) o->cls->destroy(o->shape);
    free(o->texture);
    free(o->params_copy);
    free(o);
}

HR_API void hr_scene_destroy(hr_scene *scene)
{
    if (!scene) return;
    /* Composites before their children: reverse order of creation. */
    for (int64_t i = scene->object_count - 1; i >= 0; i--) object_free(scene->objects[i]);
    free(scene->objects);
    free(scene->lights);
    hr_scene_free_pixmaps(scene);
    free(scene->unbounded);
    accel_bvh4_release(&scene->bvh);
    free(scene->leaf_objects);
    free(scene);
}

HR_API hr_context *hr_scene_context(const hr_scene *scene) { return scene ? scene->ctx : NULL; }

static int color_finite(hr_color c) { return isfinite(c.r) && isfinite(c.g) && isfinite(c.b); }

/* Input bounds that keep every pixel finite. With |colour| <= HR_MAX_COLOR,
 * weights in [0, 1] and an exponent >= 0 (so (h.m)^e <= 1), each ray traced
 * adds at most (2 + lights) * 1e12 to its pixel, weighted by products of
 * coefficients <= 1. A pixel is a sum over the rays it traced, so it stays
 * far below float's 3.4e38 for any render that can finish (it would take
 * ~1e20 rays per pixel to get there). A texture's colour is bounded the same
 * way (its parameters and pixmap pixels), and Cook-Torrance's term by
 * HR_COOK_TORRANCE_MAX: each multiplies a ray's share by at most 1e6 more,
 * which still takes ~1e14 rays per pixel to overflow. */
#define HR_MAX_COLOR 1e6
#define HR_MAX_EXPONENT 1e6

static int color_in_range(hr_color c)
{
    return color_finite(c) && fabs(c.r) <= HR_MAX_COLOR && fabs(c.g) <= HR_MAX_COLOR &&
           fabs(c.b) <= HR_MAX_COLOR;
}

/* The checks on a full-size material; hr_material_validate is the public
 * door, which first reads only the bytes the caller declared. */
static hr_status check_material(hr_context *ctx, const hr_material *m)
{
    const hr_field_table *t = &hr_material_field_table;
    for (size_t i = 0; i < t->count; i++) {
        if (t->fields[i].kind != HR_FIELD_COLOR) continue;
        hr_color c;
        memcpy(&c, (const char *)m + t->fields[i].offset, sizeof c);
        if (!color_in_range(c))
            return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                            "material: %s (%g %g %g) must be finite, each within +-%g",
                            t->fields[i].word, c.r, c.g, c.b, HR_MAX_COLOR);
    }
    if (!(m->specular_exponent >= 0 && m->specular_exponent <= HR_MAX_EXPONENT))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: specularExponent %g must be within [0, %g]",
                        m->specular_exponent, HR_MAX_EXPONENT);
    if (!(m->reflectivity >= 0 && m->reflectivity <= 1))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: reflectivity %g must be within [0, 1]", m->reflectivity);
    if (!(m->transparency >= 0 && m->transparency <= 1))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: transparency %g must be within [0, 1]", m->transparency);
    if (!isfinite(m->specular_fraction) || !isfinite(m->surface_roughness))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: specularFraction and surfaceRoughness must be finite");
    if (!(m->specular_fraction >= 0 && m->specular_fraction <= 1))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: specularFraction %g must be within [0, 1]", m->specular_fraction);
    /* Beckmann's m: below 1e-3 the highlight is narrower than a pixel of any
     * view, and 1 / m^2 would let one term grow past what keeps a pixel
     * finite; past 100 it is flat. Only Cook-Torrance reads it. */
    if (m->specular_fraction > 0 && !(m->surface_roughness >= 1e-3 && m->surface_roughness <= 100))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: surfaceRoughness %g must be within [0.001, 100] where "
                        "specularFraction is above 0",
                        m->surface_roughness);
    if (!(m->speed_of_light > 0.0) || !isfinite(m->speed_of_light))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "material: speedOfLight must be positive and finite, not %g",
                        m->speed_of_light);
    if (m->parameter_count < 0 || (m->parameter_count > 0 && !m->parameters))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "material: bad texture parameter list");
    return HR_OK;
}

HR_API hr_status hr_material_validate(hr_context *ctx, const hr_material *m)
{
    if (!m || m->struct_size < sizeof(uint32_t))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "material: NULL or struct_size not set");
    hr_material full;
    hr_material_default(&full);
    HR_SIZED_COPY_IN(&full, m);
    return check_material(ctx, &full);
}

static int is_identity(const double m[16])
{
    for (int i = 0; i < 16; i++)
        if (m[i] != ((i % 5 == 0) ? 1.0 : 0.0)) return 0;
    return 1;
}

/* Bounds of the 8 corners of a box under an affine map; infinite input
 * stays unbounded (no inf * 0 = NaN). */
static int transform_bounds(const double m[16], const hr_bounds *in, hr_bounds *out)
{
    if (!v3_is_finite(in->lo) || !v3_is_finite(in->hi)) {
        out->lo = v3(-INFINITY, -INFINITY, -INFINITY);
        out->hi = v3(INFINITY, INFINITY, INFINITY);
        return 0;
    }
    out->lo = v3(DBL_MAX, DBL_MAX, DBL_MAX);
    out->hi = v3(-DBL_MAX, -DBL_MAX, -DBL_MAX);
    for (int c = 0; c < 8; c++) {
        hr_vec3 p = v3(c & 1 ? in->hi.x : in->lo.x, c & 2 ? in->hi.y : in->lo.y,
                       c & 4 ? in->hi.z : in->lo.z);
        hr_vec3 q = hr_transform_point(m, p);
        out->lo = v3(fmin(out->lo.x, q.x), fmin(out->lo.y, q.y), fmin(out->lo.z, q.z));
        out->hi = v3(fmax(out->hi.x, q.x), fmax(out->hi.y, q.y), fmax(out->hi.z, q.z));
    }
    /* Widen by the rounding of the corner transform, so a box never clips
     * its object (a relative 4 ulps of the largest magnitude involved). */
    double mag = fmax(fmax(fabs(out->lo.x), fabs(out->hi.x)),
                      fmax(fmax(fabs(out->lo.y), fabs(out->hi.y)), fmax(fabs(out->lo.z), fabs(out->hi.z))));
    double pad = 4.0 * DBL_EPSILON * mag;
    out->lo = v3(out->lo.x - pad, out->lo.y - pad, out->lo.z - pad);
    out->hi = v3(out->hi.x + pad, out->hi.y + pad, out->hi.z + pad);
    return v3_is_finite(out->lo) && v3_is_finite(out->hi);
}

/* The class's own box of the mapped shape, where it is tighter than the
 * mapped corners of its object-space box (both hold the shape, so their
 * intersection does), padded as transform_bounds pads. A box the class gets
 * wrong (NaN, inverted, or empty against the corners' box) is ignored. */
static void tighten_bounds(hr_object *o)
{
    hr_bounds t;
    o->cls->transformed_bounds(o->shape, o->m, &t);
    if (!v3_is_finite(t.lo) || !v3_is_finite(t.hi)) return;
    hr_bounds *w = &o->world_bounds;
    double mag = fmax(fmax(fabs(t.lo.x), fabs(t.hi.x)),
                      fmax(fmax(fabs(t.lo.y), fabs(t.hi.y)), fmax(fabs(t.lo.z), fabs(t.hi.z))));
    double pad = 4.0 * DBL_EPSILON * mag;
    hr_bounds n = {v3(fmax(w->lo.x, t.lo.x - pad), fmax(w->lo.y, t.lo.y - pad), fmax(w->lo.z, t.lo.z - pad)),
                   v3(fmin(w->hi.x, t.hi.x + pad), fmin(w->hi.y, t.hi.y + pad), fmin(w->hi.z, t.hi.z + pad))};
    if (!(n.lo.x <= n.hi.x && n.lo.y <= n.hi.y && n.lo.z <= n.hi.z)) return;
    *w = n;
}

static hr_status grow_objects(hr_scene *s)
{
    if (s->object_count < s->object_cap) return HR_OK;
    int64_t cap = s->object_cap ? s->object_cap * 2 : 16;
    hr_object **grown = realloc(s->objects, (size_t)cap * sizeof *grown);
    if (!grown) return hr_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    s->objects = grown;
    s->object_cap = cap;
    return HR_OK;
}

/* Material and transform of a new object, copied and checked. */
static hr_status set_material_and_transform(hr_scene *s, hr_object *o, const hr_object_desc *d)
{
    hr_context *ctx = s->ctx;
    hr_material_default(&o->material);
    if (d->material) {
        if (d->material->struct_size < sizeof(uint32_t))
            return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "material: struct_size is not set");
        HR_SIZED_COPY_IN(&o->material, d->material);
    }
    hr_status st = check_material(ctx, &o->material);
    if (st) return st;
    if (o->material.parameter_count > 0) {
        o->params_copy = malloc((size_t)o->material.parameter_count * sizeof(double));
        if (!o->params_copy) return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        memcpy(o->params_copy, o->material.parameters,
               (size_t)o->material.parameter_count * sizeof(double));
    }
    o->material.parameters = o->params_copy;

    hr_transform t;
    hr_transform_identity(&t);
    if (d->transform && d->inverse) {
        memcpy(t.m, d->transform, sizeof t.m);
        memcpy(t.inv, d->inverse, sizeof t.inv);
        if (!doubles_are_finite(t.m, 16) || !doubles_are_finite(t.inv, 16))
            return hr_error(ctx, HR_ERROR_NUMERIC, "object transform has a non-finite entry");
        if (t.m[12] != 0 || t.m[13] != 0 || t.m[14] != 0 || t.m[15] != 1)
            return hr_error(ctx, HR_ERROR_NUMERIC, "object transform is not affine (last row must be 0 0 0 1)");
    } else if (d->transform) {
        if (hr_transform_from_matrix(&t, d->transform) != HR_OK)
            return hr_error(ctx, HR_ERROR_NUMERIC,
                            "object transform is singular, not affine or not finite");
    } else if (d->inverse) {
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object has an inverse but no transform");
    }
    memcpy(o->m, t.m, sizeof o->m);
    memcpy(o->inv, t.inv, sizeof o->inv);
    o->identity = is_identity(o->m);
    o->diagonal = !o->identity && hr_xform_is_diagonal(o->m) && hr_xform_is_diagonal(o->inv);
    o->m_error = hr_xform_error_terms_of(o->m);
    return HR_OK;
}

/* A composite's depth is one more than its deepest child's: tracing it
 * recurses that deep (see HR_MAX_COMPOSITE_DEPTH). */
static hr_status set_composite_depth(hr_scene *s, hr_object *o, const void *const *children)
{
    const hr_shape_class *cls = o->cls;
    int32_t deepest = -1;
    for (int32_t i = 0; i < cls->param_count; i++)
        if (children[i] && (deepest < 0 || ((const hr_object *)children[i])->composite_depth >
                                               ((const hr_object *)children[deepest])->composite_depth))
            deepest = i;
    if (deepest < 0) return HR_OK;
    const int32_t depth = ((const hr_object *)children[deepest])->composite_depth + 1;
    if (depth > HR_MAX_COMPOSITE_DEPTH)
        return hr_error(s->ctx, HR_ERROR_PARAMETER,
                        "shape '%s': parameter '%s' would nest composites %d deep, beyond the "
                        "limit of %d; nest long chains as balanced trees ((a b) (c d))",
                        cls->name, cls->params[deepest].name, (int)depth, HR_MAX_COMPOSITE_DEPTH);
    o->composite_depth = depth;
    return HR_OK;
}

HR_API hr_status hr_scene_add_object(hr_scene *s, const hr_object_desc *d, int64_t *out_index)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    hr_context *ctx = s->ctx;
    if (!d || d->struct_size < offsetof(hr_object_desc, shape) + sizeof(d->shape))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object: NULL description or struct_size not set");
    hr_object_desc desc = {0};
    HR_SIZED_COPY_IN(&desc, d);
    if (s->committed)
        return hr_error(ctx, HR_ERROR_STATE, "cannot add an object to a committed scene");
    if (!desc.shape || !*desc.shape)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object: no shape name");
    if (desc.param_count < 0 || (desc.param_count > 0 && !desc.params))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object '%s': bad parameter list", desc.shape);
    hr_status st = grow_objects(s);
    if (st) return st;

    const hr_shape_class *cls;
    const char *module_path = "";
    if ((st = hr_context_find_shape_class(ctx, desc.shape, &cls, &module_path))) return st;

    hr_object *o = object_alloc();
    if (!o) return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    o->cls = cls;
    o->module_path = module_path;
    o->index = s->object_count;
    o->top_level = 1;
    if ((st = set_material_and_transform(s, o, &desc))) {
        object_free(o);
        return st;
    }

    /* The resolved parameters live only through create: on the stack for
     * the usual few, so a scene of many objects pays no allocation for them.
     * hr_params_resolve sets all n entries of both before anything reads them. */
    enum { FEW_PARAMS = 16 };
    hr_param few_params[FEW_PARAMS];
    const void *few_children[FEW_PARAMS];
    int32_t n = cls->param_count;
    hr_param *full = few_params;
    const void **children = few_children;
    if (n > FEW_PARAMS) {
        full = calloc((size_t)n, sizeof *full);
        children = calloc((size_t)n, sizeof *children);
        if (!full || !children) {
            free(full);
            free(children);
            object_free(o);
            return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        }
    }
    st = hr_params_resolve(s, cls, module_path, desc.params, desc.param_count, full, children);
    if (st == HR_OK) st = set_composite_depth(s, o, children);
    if (st == HR_OK) {
        char message[512];
        message[0] = '\0';
        hr_create_args args = {0};
        args.struct_size = sizeof args;
        args.param_count = n;
        args.params = full;
        args.objects = children;
        args.host = &ctx->host;
        args.error = message;
        args.error_size = sizeof message;
        args.base_dir = desc.base_dir ? desc.base_dir : "";
        st = cls->create(&args, &o->shape);
        if (st != HR_OK || !o->shape) {
            o->shape = NULL;
            if (st == HR_OK) st = HR_ERROR_MODULE;
            st = hr_error(ctx, st, "shape '%s' (module '%s'): %s", cls->name, module_path,
                          message[0] ? message : "create failed without a message");
        }
    }
    if (st == HR_OK) st = hr_texture_bind(s, o);
    if (st == HR_OK) {
        for (int32_t i = 0; i < n; i++)
            if (children[i]) {
                ((hr_object *)children[i])->top_level = 0;
                ((hr_object *)children[i])->parent = o;
            }
    }
    if (full != few_params) {
        free(full);
        free(children);
    }
    if (st) {
        object_free(o);
        return st;
    }
    cls->bounds(o->shape, &o->local_bounds);
    unbounded_cull_prepare(o);
    o->bounded = transform_bounds(o->m, &o->local_bounds, &o->world_bounds);
    if (o->bounded && cls->transformed_bounds) tighten_bounds(o);
    s->objects[s->object_count++] = o;
    if (out_index) *out_index = o->index;
    return HR_OK;
}

HR_API hr_status hr_scene_add_light(hr_scene *s, const hr_light *light)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!light || light->struct_size < sizeof(uint32_t))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "light: NULL or struct_size not set");
    if (s->committed) return hr_error(s->ctx, HR_ERROR_STATE, "cannot add a light to a committed scene");
    hr_light l = {0};
    HR_SIZED_COPY_IN(&l, light);
    if (!v3_is_finite(l.position))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "light: position must be finite");
    if (!color_in_range(l.color))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "light: colour (%g %g %g) must be finite, each within +-%g", l.color.r,
                        l.color.g, l.color.b, HR_MAX_COLOR);
    if (s->light_count == s->light_cap) {
        int32_t cap = s->light_cap ? s->light_cap * 2 : 8;
        hr_light *grown = realloc(s->lights, (size_t)cap * sizeof *grown);
        if (!grown) return hr_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        s->lights = grown;
        s->light_cap = cap;
    }
    s->lights[s->light_count++] = l;
    return HR_OK;
}

HR_API hr_status hr_scene_set_globals(hr_scene *s, const hr_scene_globals *g)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!g || g->struct_size < sizeof(uint32_t))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "globals: NULL or struct_size not set");
    if (s->committed) return hr_error(s->ctx, HR_ERROR_STATE, "cannot change a committed scene");
    hr_scene_globals v;
    hr_scene_globals_default(&v);
    HR_SIZED_COPY_IN(&v, g);
    if (v.max_recursion_depth < 0 || v.max_recursion_depth > HR_MAX_RECURSION_DEPTH)
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "globals: maxRecursionDepth must be within 0..%d, not %d",
                        HR_MAX_RECURSION_DEPTH, (int)v.max_recursion_depth);
    if (!color_in_range(v.background) || !color_in_range(v.global_ambient))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "globals: background and globalAmbient must be finite, each within +-%g",
                        HR_MAX_COLOR);
    if (!isfinite(v.min_reflectivity) || !isfinite(v.min_transparency))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "globals: minReflectivity and minTransparency must be finite");
    s->globals = v;
    return HR_OK;
}

HR_API hr_status hr_scene_get_globals(const hr_scene *s, hr_scene_globals *out)
{
    if (!s || !out || out->struct_size < sizeof(uint32_t)) return HR_ERROR_INVALID_ARGUMENT;
    HR_SIZED_COPY_OUT(out, &s->globals);
    return HR_OK;
}

/* Which effects each material and the whole scene call for. A coefficient
 * below Hill's threshold spawns no ray and contributes nothing (the ray is
 * not worth tracing), so such a material does not make the scene reflect.
 * The material flags do not depend on maxRecursionDepth: hr_scene_shade and
 * hr_render may ask for more depth than the scene's, and shade stops at the
 * depth it is given. Only the scene's effects say what its own depth does. */
static void work_out_effects(hr_scene *s)
{
    const hr_scene_globals *g = &s->globals;
    int lit = 0;
    for (int32_t i = 0; i < s->light_count; i++) lit |= !rgb_is_zero(s->lights[i].color);
    uint32_t effects = 0;
    for (int64_t i = 0; i < s->object_count; i++) {
        hr_object *o = s->objects[i];
        const hr_material *m = &o->material;
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
                if (hr_light_adds_nothing(&s->lights[k], m, f)) f |= HR_MAT_INERT_LIGHT;
        o->mat_flags = f;
        hr_texture_place(o);
        if (o->texture && (f & (HR_MAT_AMBIENT | HR_MAT_DIFFUSE))) effects |= HR_EFFECT_TEXTURE;
        o->specular_cutoff = hr_specular_cutoff(m->specular_exponent);
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

HR_API hr_status hr_scene_commit(hr_scene *s)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (s->committed) return HR_OK;
    int64_t bounded = 0, unbounded = 0;
    for (int64_t i = 0; i < s->object_count; i++) {
        const hr_object *o = s->objects[i];
        if (!o->top_level) continue;
        if (o->bounded) bounded++;
        else unbounded++;
    }
    if (bounded > INT32_MAX / 2)
        return hr_error(s->ctx, HR_ERROR_UNSUPPORTED, "too many objects (%lld)", (long long)bounded);
    hr_bounds *boxes = malloc((size_t)(bounded ? bounded : 1) * sizeof *boxes);
    int32_t *owner = malloc((size_t)(bounded ? bounded : 1) * sizeof *owner);
    s->unbounded = malloc((size_t)(unbounded ? unbounded : 1) * sizeof *s->unbounded);
    if (!boxes || !owner || !s->unbounded) {
        free(boxes);
        free(owner);
        free(s->unbounded);
        s->unbounded = NULL;
        return hr_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    int32_t nb = 0;
    s->unbounded_count = 0;
    for (int64_t i = 0; i < s->object_count; i++) {
        const hr_object *o = s->objects[i];
        if (!o->top_level) continue;
        if (o->bounded) {
            boxes[nb] = o->world_bounds;
            owner[nb++] = (int32_t)i;
        } else {
            s->unbounded[s->unbounded_count++] = o;
        }
    }
    /* Leaves of up to 4 objects: a node visit costs about half an object
     * test (a transform and a shape call). */
    const accel_bvh4_options bvh_options = {.max_leaf = 4, .traversal_cost = 0.5};
    hr_bounds around = {v3(INFINITY, INFINITY, INFINITY), v3(-INFINITY, -INFINITY, -INFINITY)};
    for (int32_t i = 0; i < nb; i++) {
        around.lo = v3(fmin(around.lo.x, boxes[i].lo.x), fmin(around.lo.y, boxes[i].lo.y),
                       fmin(around.lo.z, boxes[i].lo.z));
        around.hi = v3(fmax(around.hi.x, boxes[i].hi.x), fmax(around.hi.y, boxes[i].hi.y),
                       fmax(around.hi.z, boxes[i].hi.z));
    }
    s->bvh_box = cull_box_widened(around);
    int built = accel_bvh4_build(&s->bvh, boxes, (uint32_t)nb, &bvh_options);
    free(boxes);
    s->leaf_objects = built == 0 ? malloc((size_t)(nb ? nb : 1) * sizeof *s->leaf_objects) : NULL;
    if (!s->leaf_objects) {
        free(owner);
        accel_bvh4_release(&s->bvh);
        /* The scene stays uncommitted and commit may be tried again, which
         * allocates this anew. */
        free(s->unbounded);
        s->unbounded = NULL;
        s->unbounded_count = 0;
        return hr_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory building the BVH");
    }
    /* Items name BVH inputs; the walk wants the objects themselves. */
    for (uint32_t i = 0; i < s->bvh.item_count; i++) s->leaf_objects[i] = s->objects[owner[s->bvh.items[i]]];
    free(owner);
    work_out_effects(s);
    s->committed = 1;
    if (s->object_count == 0)
        hr_warn(s->ctx, HR_WARNING_EMPTY_SCENE, NULL, 0, 0,
                "the scene has no objects: every pixel is the background colour");
    return HR_OK;
}

HR_API int32_t hr_scene_is_committed(const hr_scene *s) { return s ? s->committed : 0; }
HR_API uint32_t hr_scene_effects(const hr_scene *s) { return s && s->committed ? s->effects : 0; }
HR_API int64_t hr_scene_object_count(const hr_scene *s) { return s ? s->object_count : 0; }
HR_API int32_t hr_scene_light_count(const hr_scene *s) { return s ? s->light_count : 0; }

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

HR_API hr_status hr_scene_object_info(const hr_scene *s, int64_t index, hr_object_info *out)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!out || out->struct_size < sizeof(uint32_t))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "object info: NULL or struct_size not set");
    if (index < 0 || index >= s->object_count)
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "object index %lld out of range [0, %lld)",
                        (long long)index, (long long)s->object_count);
    const hr_object *o = s->objects[index];
    hr_object_info info = {0};
    info.top_level = o->top_level;
    info.shape = o->cls->name;
    info.module_path = o->module_path;
    info.material = o->material;
    memcpy(info.transform, o->m, sizeof info.transform);
    memcpy(info.inverse, o->inv, sizeof info.inverse);
    info.world_bounds = o->world_bounds;
    HR_SIZED_COPY_OUT(out, &info);
    return HR_OK;
}

HR_API hr_status hr_scene_light(const hr_scene *s, int32_t index, hr_light *out)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!out || out->struct_size < sizeof(uint32_t) || index < 0 || index >= s->light_count)
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "light index %d out of range", (int)index);
    HR_SIZED_COPY_OUT(out, &s->lights[index]);
    return HR_OK;
}

HR_API hr_status hr_scene_bounds(const hr_scene *s, hr_bounds *out, int32_t *found)
{
    if (!s || !out || !found) return HR_ERROR_INVALID_ARGUMENT;
    *found = 0;
    for (int64_t i = 0; i < s->object_count; i++) {
        const hr_object *o = s->objects[i];
        if (!o->top_level || !o->bounded) continue;
        if (!*found) {
            *out = o->world_bounds;
            *found = 1;
        } else {
            out->lo = v3(fmin(out->lo.x, o->world_bounds.lo.x), fmin(out->lo.y, o->world_bounds.lo.y),
                         fmin(out->lo.z, o->world_bounds.lo.z));
            out->hi = v3(fmax(out->hi.x, o->world_bounds.hi.x), fmax(out->hi.y, o->world_bounds.hi.y),
                         fmax(out->hi.z, o->world_bounds.hi.z));
        }
    }
    return HR_OK;
}

/* The bounded top-level object whose bounds reach farthest from the origin
 * (or are largest): the one that made framing overflow. */
static int64_t farthest_object(const hr_scene *s, double *reach)
{
    int64_t best = -1;
    *reach = -1.0;
    for (int64_t i = 0; i < s->object_count; i++) {
        const hr_object *o = s->objects[i];
        if (!o->top_level || !o->bounded) continue;
        const hr_bounds *b = &o->world_bounds;
        double r = fmax(fmax(v3_max_abs(b->lo), v3_max_abs(b->hi)), v3_max_abs(v3_sub(b->hi, b->lo)));
        if (r > *reach || isnan(r)) best = i, *reach = r;
    }
    return best;
}

/* Look from the +z side, a little from above and the right, at the centre
 * of the bounding sphere of the bounded objects, from far enough that the
 * sphere fits the narrower of the two view angles with a 5% margin. */
HR_API hr_status hr_scene_frame_camera(const hr_scene *s, hr_camera *cam)
{
    if (!s || !cam) return HR_ERROR_INVALID_ARGUMENT;
    hr_bounds b;
    int32_t found;
    hr_scene_bounds(s, &b, &found);
    if (cam->width <= 0 || cam->height <= 0) cam->width = 640, cam->height = 480;
    if (!(cam->view_angle > 0 && cam->view_angle < 180)) cam->view_angle = 45.0;
    if (!found) {
        int32_t w = cam->width, h = cam->height;
        double angle = cam->view_angle;
        hr_camera_default(cam);
        cam->width = w, cam->height = h, cam->view_angle = angle;
        return HR_OK;
    }
    hr_vec3 centre = v3_scale(v3_add(b.lo, b.hi), 0.5);
    double radius = 0.5 * v3_length(v3_sub(b.hi, b.lo));
    if (!(radius > 0)) radius = 1.0;
    double half_v = 0.5 * cam->view_angle * (3.14159265358979323846 / 180.0);
    double half_h = atan(tan(half_v) * cam->width / cam->height);
    double half = fmin(half_v, half_h);
    double dist = 1.05 * radius / sin(half);
    hr_vec3 dir = v3_normalize(v3(0.35, 0.45, 1.0));
    hr_vec3 eye = v3_madd(centre, dir, dist);
    if (!v3_is_finite(eye) || !v3_is_finite(centre)) {
        double reach;
        int64_t i = farthest_object(s, &reach);
        return hr_error(s->ctx, HR_ERROR_NUMERIC,
                        "cannot frame a camera: object %lld (a '%s') reaches %g from the origin, so "
                        "far that a view of it overflows; give the scene a camera",
                        (long long)i, i >= 0 ? s->objects[i]->cls->name : "?", reach);
    }
    cam->look = centre;
    cam->eye = eye;
    cam->up = v3(0, 1, 0);
    return HR_OK;
}
