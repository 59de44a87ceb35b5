/* Adding an object to a scene: its shape created by its class from the
 * resolved parameters, its material and transform copied and checked, and
 * its bounds in its parent's space worked out. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/context_internal.h"
#include "util/errors.h"
#include "scene/cull_prepare.h"
#include "scene/scene_internal.h"
#include "scene/scene_params.h"
#include "util/sized_copy.h"
#include "texture/texture.h"
#include "geometry/transform_inline.h"
#include "geometry/vec.h"

/* Objects a slab holds: the first slab 16, each next one twice the last,
 * up to this many. */
#define SLAB_MOST_OBJECTS 4096u
#define OBJECT_SIZE ((sizeof(hr_object) + HR_OBJECT_ALIGN - 1) / HR_OBJECT_ALIGN * HR_OBJECT_ALIGN)
#define SLAB_HEADER ((sizeof(hri_object_slab) + HR_OBJECT_ALIGN - 1) / HR_OBJECT_ALIGN * HR_OBJECT_ALIGN)

/* A zeroed object on cache lines of its own (HR_OBJECT_ALIGN), so that its
 * fields tracing reads first share the fewest lines (hr_object), from the
 * scene's newest slab, or a new one when that is full. */
static hr_object *object_alloc(hr_scene *s)
{
    hri_object_slab *slab = s->slabs;
    if (!slab || slab->used == slab->cap) {
        size_t cap = slab ? 2 * slab->cap : 16;
        if (cap > SLAB_MOST_OBJECTS) cap = SLAB_MOST_OBJECTS;
        hri_object_slab *fresh = aligned_alloc(HR_OBJECT_ALIGN, SLAB_HEADER + cap * OBJECT_SIZE);
        if (!fresh) return NULL;
        fresh->next = slab;
        fresh->used = 0;
        fresh->cap = cap;
        s->slabs = slab = fresh;
    }
    hr_object *o = (hr_object *)(void *)((char *)slab + SLAB_HEADER + slab->used++ * OBJECT_SIZE);
    memset(o, 0, OBJECT_SIZE);
    return o;
}

/* Gives back the object object_alloc gave last (an add that failed); were
 * it not the last, its slot would stay unused until the scene is freed. */
static void object_unalloc(hr_scene *s, hr_object *o)
{
    hri_object_free(o);
    hri_object_slab *slab = s->slabs;
    if ((char *)o == (char *)slab + SLAB_HEADER + (slab->used - 1) * OBJECT_SIZE) slab->used--;
}

void hri_object_free(hr_object *o)
{
    if (!o) return;
    if (o->shape) o->cls->destroy(o->shape);
    free(o->texture);
    free(o->params);
}

void hri_object_slabs_free(hri_object_slab *slab)
{
    while (slab) {
        hri_object_slab *next = slab->next;
        free(slab);
        slab = next;
    }
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
        out->lo = v3(v_fmin(out->lo.x, q.x), v_fmin(out->lo.y, q.y), v_fmin(out->lo.z, q.z));
        out->hi = v3(v_fmax(out->hi.x, q.x), v_fmax(out->hi.y, q.y), v_fmax(out->hi.z, q.z));
    }
    /* Widen by the rounding of the corner transform, so a box never clips
     * its object (a relative 4 ulps of the largest magnitude involved). */
    double mag = v_fmax(v_fmax(fabs(out->lo.x), fabs(out->hi.x)),
                      v_fmax(v_fmax(fabs(out->lo.y), fabs(out->hi.y)), v_fmax(fabs(out->lo.z), fabs(out->hi.z))));
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
    double mag = v_fmax(v_fmax(fabs(t.lo.x), fabs(t.hi.x)),
                      v_fmax(v_fmax(fabs(t.lo.y), fabs(t.hi.y)), v_fmax(fabs(t.lo.z), fabs(t.hi.z))));
    double pad = 4.0 * DBL_EPSILON * mag;
    hr_bounds n = {v3(v_fmax(w->lo.x, t.lo.x - pad), v_fmax(w->lo.y, t.lo.y - pad), v_fmax(w->lo.z, t.lo.z - pad)),
                   v3(v_fmin(w->hi.x, t.hi.x + pad), v_fmin(w->hi.y, t.hi.y + pad), v_fmin(w->hi.z, t.hi.z + pad))};
    if (!(n.lo.x <= n.hi.x && n.lo.y <= n.hi.y && n.lo.z <= n.hi.z)) return;
    *w = n;
}

static hr_status grow_objects(hr_scene *s)
{
    if (s->object_count < s->object_cap) return HR_OK;
    int64_t cap = s->object_cap ? s->object_cap * 2 : 16;
    hr_object **grown = realloc(s->objects, (size_t)cap * sizeof *grown);
    if (!grown) return hri_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    s->objects = grown;
    s->object_cap = cap;
    return HR_OK;
}

/* Material and transform of a new object, copied and checked. */
static hr_status set_material_and_transform(hr_scene *s, hr_object *o, const hr_object_desc *d)
{
    hr_context *ctx = s->ctx;
    /* The default material is valid as made (it passes hri_material_check,
     * test_object_materials): only a given one is checked. */
    hr_material m = s->default_material;
    if (d->material) {
        if (d->material->struct_size < sizeof(uint32_t))
            return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "material: struct_size is not set");
        HR_SIZED_COPY_IN(&m, d->material);
        hr_status st = hri_material_check(ctx, &m);
        if (st) return st;
    }
    /* Kept once a scene (its parameters with it): objects of the same
     * material share the copy. */
    if (!(o->material = hri_material_store_add(&s->materials, &m)))
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");

    hr_transform t;
    hr_transform_identity(&t);
    if (d->transform && d->inverse) {
        memcpy(t.m, d->transform, sizeof t.m);
        memcpy(t.inv, d->inverse, sizeof t.inv);
        if (!doubles_are_finite(t.m, 16) || !doubles_are_finite(t.inv, 16))
            return hri_error(ctx, HR_ERROR_NUMERIC, "object transform has a non-finite entry");
        if (t.m[12] != 0 || t.m[13] != 0 || t.m[14] != 0 || t.m[15] != 1)
            return hri_error(ctx, HR_ERROR_NUMERIC, "object transform is not affine (last row must be 0 0 0 1)");
    } else if (d->transform) {
        if (hr_transform_from_matrix(&t, d->transform) != HR_OK)
            return hri_error(ctx, HR_ERROR_NUMERIC,
                            "object transform is singular, not affine or not finite");
    } else if (d->inverse) {
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object has an inverse but no transform");
    }
    memcpy(o->m, t.m, sizeof o->m);
    memcpy(o->inv, t.inv, sizeof o->inv);
    o->identity = is_identity(o->m);
    o->diagonal = !o->identity && hri_xform_is_diagonal(o->m) && hri_xform_is_diagonal(o->inv);
    o->m_error = hri_xform_error_terms_of(o->m);
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
        return hri_error(s->ctx, HR_ERROR_PARAMETER,
                        "shape '%s': parameter '%s' would nest composites %d deep, beyond the "
                        "limit of %d; nest long chains as balanced trees ((a b) (c d))",
                        cls->name, cls->params[deepest].name, (int)depth, HR_MAX_COMPOSITE_DEPTH);
    o->composite_depth = depth;
    return HR_OK;
}

/* An object as the scene budget's refusal names it, its index and class:
 * formatted only when the budget refuses it, not for every object. */
#define OBJECT_WHAT "object %lld (a '%s')"

HR_API hr_status hr_scene_add_object(hr_scene *s, const hr_object_desc *d, int64_t *out_index)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    hr_context *ctx = s->ctx;
    if (!d || d->struct_size < offsetof(hr_object_desc, shape) + sizeof(d->shape))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object: NULL description or struct_size not set");
    hr_object_desc desc = {0};
    HR_SIZED_COPY_IN(&desc, d);
    if (s->committed)
        return hri_error(ctx, HR_ERROR_STATE, "cannot add an object to a committed scene");
    if (!desc.shape || !*desc.shape)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object: no shape name");
    if (desc.param_count < 0 || (desc.param_count > 0 && !desc.params))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "object '%s': bad parameter list", desc.shape);
    hr_status st = grow_objects(s);
    if (st) return st;

    const hr_shape_class *cls;
    const char *module_path = "";
    if ((st = hr_context_find_shape_class(ctx, desc.shape, &cls, &module_path))) return st;

    /* The object itself, its slot in the scene's lists and its share of the
     * scene's BVH; its shape data is charged as the shape allocates it. */
    const long long index = (long long)s->object_count; /* for OBJECT_WHAT */
    const uint64_t object_bytes = sizeof(hr_object) + 64;
    st = hri_scene_budget_charge(ctx, &s->budget, &s->budget.objects, object_bytes, OBJECT_WHAT, index, cls->name);
    if (st) return st;
    hr_object *o = object_alloc(s);
    if (!o) {
        s->budget.objects -= object_bytes;
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    o->cls = cls;
    o->module_path = module_path;
    o->index = s->object_count;
    o->top_level = 1;
    if ((st = set_material_and_transform(s, o, &desc))) {
        object_unalloc(s, o);
        s->budget.objects -= object_bytes;
        return st;
    }

    /* The resolved parameters live only through create: on the stack for
     * the usual few, so a scene of many objects pays no allocation for them.
     * hri_params_resolve sets all n entries of both before anything reads them. */
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
            object_unalloc(s, o);
            s->budget.objects -= object_bytes;
            return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        }
    }
    st = hri_params_resolve(s, cls, module_path, desc.params, desc.param_count, full, children);
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
        s->budget.refused = 0;
        hri_scene_budget_begin(&s->budget);
        hri_scene_create_begin(s, &args);
        st = cls->create(&args, &o->shape);
        hri_scene_create_end();
        hri_scene_budget_end();
        if (st != HR_OK || !o->shape) {
            o->shape = NULL;
            if (st == HR_OK) st = HR_ERROR_MODULE;
            if (s->budget.refused) /* the shape's own message says only "out of memory" */
                st = hri_scene_budget_refused(ctx, &s->budget, OBJECT_WHAT, index, cls->name);
            else
                st = hri_error(ctx, st, "shape '%s' (module '%s'): %s", cls->name, module_path,
                              message[0] ? message : "create failed without a message");
        }
    }
    if (st == HR_OK)
        st = hri_texture_bind(s->ctx, o->material, o->cls, o->shape, o->module_path, &s->pixmaps, &o->texture);
    uint64_t kept_bytes = 0;
    if (st == HR_OK && n > 0) {
        o->params = hri_params_keep(full, n, &kept_bytes);
        if (!o->params) st = hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        else
            st = hri_scene_budget_charge(ctx, &s->budget, &s->budget.objects, kept_bytes, OBJECT_WHAT, index,
                                        cls->name);
        if (st) kept_bytes = 0;
    }
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
        object_unalloc(s, o);
        s->budget.objects -= object_bytes + kept_bytes;
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
