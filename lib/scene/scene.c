/* Scenes: creating one, its lights and globals, commit (the BVH over its
 * objects and the effects analysis) and destroying it. Objects are added in
 * scene_objects.c, read back in scene_introspect.c; tracing is in trace.c,
 * shading in shade.c, rendering in render.c. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "util/env_cpu.h"
#include "util/errors.h"
#include "util/field_table.h"
#include "scene/cull_prepare.h"
#include "scene/material_analysis.h"
#include "scene/scene_internal.h"
#include "util/sized_copy.h"
#include "texture/texture.h"
#include "geometry/vec.h"

HR_API void hr_scene_globals_default(hr_scene_globals *g)
{
    if (!g) return;
    memset(g, 0, sizeof *g);
    g->struct_size = sizeof *g;
    hri_fields_default(&hri_globals_field_table, g);
}

HR_API hr_status hr_scene_create(hr_context *ctx, hr_scene **out)
{
    if (!ctx || !out) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_scene_create: NULL argument");
    *out = NULL;
    /* A CPU path forced by HITRAY_CPU that this CPU cannot run, or a value
     * that names none, is refused before any scene exists. */
    hr_status st = hri_env_cpu_check(ctx);
    if (st) return st;
    hr_scene *s = calloc(1, sizeof *s);
    if (!s) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    s->ctx = ctx;
    st = hri_scene_budget_init(ctx, &s->budget);
    if (st) {
        free(s);
        return st;
    }
    hr_scene_globals_default(&s->globals);
    hr_material_default(&s->default_material);
    *out = s;
    return HR_OK;
}

HR_API void hr_scene_destroy(hr_scene *scene)
{
    if (!scene) return;
    /* Composites before their children: reverse order of creation. */
    for (int64_t i = scene->object_count - 1; i >= 0; i--) hri_object_free(scene->objects[i]);
    hri_object_slabs_free(scene->slabs);
    hri_material_store_free(&scene->materials);
    free(scene->objects);
    free(scene->lights);
    hri_pixmap_set_free(&scene->pixmaps);
    free(scene->unbounded);
    accel_bvh4_release(&scene->bvh);
    accel_bvh8_release(&scene->bvh8);
    free(scene->leaf_objects);
    hri_scene_files_free(scene);
    free(scene);
}

HR_API hr_status hr_scene_add_light(hr_scene *s, const hr_light *light)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!light || light->struct_size < sizeof(uint32_t))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "light: NULL or struct_size not set");
    if (s->committed) return hri_error(s->ctx, HR_ERROR_STATE, "cannot add a light to a committed scene");
    hr_light l = {0};
    HR_SIZED_COPY_IN(&l, light);
    if (!v3_is_finite(l.position))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "light: position must be finite");
    if (!hri_color_in_range(l.color))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "light: colour (%g %g %g) must be finite, each within +-%g", l.color.r,
                        l.color.g, l.color.b, HR_MAX_COLOR);
    if (s->light_count == s->light_cap) {
        int32_t cap = s->light_cap ? s->light_cap * 2 : 8;
        hr_light *grown = realloc(s->lights, (size_t)cap * sizeof *grown);
        if (!grown) return hri_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
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
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "globals: NULL or struct_size not set");
    if (s->committed) return hri_error(s->ctx, HR_ERROR_STATE, "cannot change a committed scene");
    hr_scene_globals v;
    hr_scene_globals_default(&v);
    HR_SIZED_COPY_IN(&v, g);
    if (v.max_recursion_depth < 0 || v.max_recursion_depth > HR_MAX_RECURSION_DEPTH)
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "globals: maxRecursionDepth must be within 0..%d, not %d",
                        HR_MAX_RECURSION_DEPTH, (int)v.max_recursion_depth);
    if (!hri_color_in_range(v.background) || !hri_color_in_range(v.global_ambient))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "globals: background and globalAmbient must be finite, each within +-%g",
                        HR_MAX_COLOR);
    if (!isfinite(v.min_reflectivity) || !isfinite(v.min_transparency))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                        "globals: minReflectivity and minTransparency must be finite");
    s->globals = v;
    return HR_OK;
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
        return hri_error(s->ctx, HR_ERROR_UNSUPPORTED, "too many objects (%lld)", (long long)bounded);
    hr_bounds *boxes = malloc((size_t)(bounded ? bounded : 1) * sizeof *boxes);
    int32_t *owner = malloc((size_t)(bounded ? bounded : 1) * sizeof *owner);
    s->unbounded = malloc((size_t)(unbounded ? unbounded : 1) * sizeof *s->unbounded);
    if (!boxes || !owner || !s->unbounded) {
        free(boxes);
        free(owner);
        free(s->unbounded);
        s->unbounded = NULL;
        return hri_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
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
     * test (a transform and a shape call). Large subtrees are built on a
     * thread for each CPU (the same tree as on one). */
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    const accel_bvh4_options bvh_options = {.max_leaf = 4, .traversal_cost = 0.5,
                                            .threads = cpus < 1 ? 1u : cpus > 64 ? 64u : (uint32_t)cpus};
    hr_bounds around = {v3(INFINITY, INFINITY, INFINITY), v3(-INFINITY, -INFINITY, -INFINITY)};
    for (int32_t i = 0; i < nb; i++) {
        around.lo = v3(v_fmin(around.lo.x, boxes[i].lo.x), v_fmin(around.lo.y, boxes[i].lo.y),
                       v_fmin(around.lo.z, boxes[i].lo.z));
        around.hi = v3(v_fmax(around.hi.x, boxes[i].hi.x), v_fmax(around.hi.y, boxes[i].hi.y),
                       v_fmax(around.hi.z, boxes[i].hi.z));
    }
    s->bvh_box = cull_box_widened(around);
    int built = accel_bvh4_build(&s->bvh, boxes, (uint32_t)nb, &bvh_options);
    free(boxes);
    /* On AVX2 CPUs the first-hit walk takes the tree 8 wide (accel/bvh8.h):
     * fewer nodes a ray, for about as many instructions. */
    if (built == 0 && accel_bvh8_usable() && accel_bvh8_build(&s->bvh8, &s->bvh) != 0) built = -1;
    s->leaf_objects = built == 0 ? malloc((size_t)(nb ? nb : 1) * sizeof *s->leaf_objects) : NULL;
    if (!s->leaf_objects) {
        free(owner);
        accel_bvh4_release(&s->bvh);
        accel_bvh8_release(&s->bvh8);
        /* The scene stays uncommitted and commit may be tried again, which
         * allocates this anew. */
        free(s->unbounded);
        s->unbounded = NULL;
        s->unbounded_count = 0;
        return hri_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory building the BVH");
    }
    /* Items name BVH inputs; the walk wants the objects themselves. */
    for (uint32_t i = 0; i < s->bvh.item_count; i++) s->leaf_objects[i] = s->objects[owner[s->bvh.items[i]]];
    free(owner);
    hri_scene_work_out_effects(s);
    s->committed = 1;
    if (s->object_count == 0)
        hri_warn(s->ctx, HR_WARNING_EMPTY_SCENE, NULL, 0, 0,
                "the scene has no objects: every pixel is the background colour");
    return HR_OK;
}
