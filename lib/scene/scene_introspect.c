/* What a scene holds, read back: its context, counts, globals, objects,
 * lights and bounds. */
#include <math.h>
#include <string.h>

#include "util/errors.h"
#include "scene/scene_internal.h"
#include "util/sized_copy.h"
#include "geometry/vec.h"

HR_API hr_context *hr_scene_context(const hr_scene *scene) { return scene ? scene->ctx : NULL; }
HR_API int32_t hr_scene_is_committed(const hr_scene *s) { return s ? s->committed : 0; }
HR_API int64_t hr_scene_object_count(const hr_scene *s) { return s ? s->object_count : 0; }
HR_API int32_t hr_scene_light_count(const hr_scene *s) { return s ? s->light_count : 0; }

HR_API hr_status hr_scene_get_globals(const hr_scene *s, hr_scene_globals *out)
{
    if (!s || !out || out->struct_size < sizeof(uint32_t)) return HR_ERROR_INVALID_ARGUMENT;
    HR_SIZED_COPY_OUT(out, &s->globals);
    return HR_OK;
}

HR_API hr_status hr_scene_object_info(const hr_scene *s, int64_t index, hr_object_info *out)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!out || out->struct_size < sizeof(uint32_t))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "object info: NULL or struct_size not set");
    if (index < 0 || index >= s->object_count)
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "object index %lld out of range [0, %lld)",
                        (long long)index, (long long)s->object_count);
    const hr_object *o = s->objects[index];
    hr_object_info info = {0};
    info.top_level = o->top_level;
    info.shape = o->cls->name;
    info.module_path = o->module_path;
    info.material = *o->material;
    memcpy(info.transform, o->m, sizeof info.transform);
    memcpy(info.inverse, o->inv, sizeof info.inverse);
    info.world_bounds = o->world_bounds;
    info.params = o->params;
    info.param_count = o->params ? o->cls->param_count : 0;
    HR_SIZED_COPY_OUT(out, &info);
    return HR_OK;
}

HR_API hr_status hr_scene_light(const hr_scene *s, int32_t index, hr_light *out)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!out || out->struct_size < sizeof(uint32_t) || index < 0 || index >= s->light_count)
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "light index %d out of range", (int)index);
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
