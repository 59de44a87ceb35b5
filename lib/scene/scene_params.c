#include "scene/scene_params.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/shape_kit_module.h>

#include "util/errors.h"
#include "util/suggest.h"

static const char *type_name(int32_t type)
{
    switch (type) {
    case HR_PARAM_NUMBER: return "a number";
    case HR_PARAM_STRING: return "a string";
    case HR_PARAM_OBJECT: return "an object";
    case HR_PARAM_NUMBERS: return "an array of numbers";
    default: return "an unknown type";
    }
}

/* "a, b, c" or "no parameters", for messages. */
static void list_params(const hr_shape_class *cls, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    if (cls->param_count == 0) {
        snprintf(buf, size, "it takes no parameters");
        return;
    }
    int n = snprintf(buf, size, "it takes: ");
    len = n > 0 ? (size_t)n : 0;
    for (int32_t i = 0; i < cls->param_count && len < size; i++) {
        n = snprintf(buf + len, size - len, "%s%s", i ? ", " : "", cls->params[i].name);
        if (n > 0) len += (size_t)n;
    }
}

static void format_bound(double v, char *buf, size_t size)
{
    if (isinf(v)) snprintf(buf, size, "%sinf", v < 0 ? "-" : "");
    else snprintf(buf, size, "%g", v);
}

/* "[0, 100]", or with an excluded end "(0, 1e+06]: it must be > 0", for
 * the messages of out-of-range numbers. */
static void format_range(const hr_param_spec *spec, char *buf, size_t size)
{
    char lo[32], hi[32];
    format_bound(spec->min, lo, sizeof lo);
    format_bound(spec->max, hi, sizeof hi);
    const int open_lo = (spec->flags & HR_PARAM_MIN_EXCLUSIVE) != 0;
    const int open_hi = (spec->flags & HR_PARAM_MAX_EXCLUSIVE) != 0;
    int n = snprintf(buf, size, "%c%s, %s%c", open_lo ? '(' : '[', lo, hi, open_hi ? ')' : ']');
    size_t len = n > 0 && (size_t)n < size ? (size_t)n : 0;
    if (open_lo && open_hi) snprintf(buf + len, size - len, ": it must be > %s and < %s", lo, hi);
    else if (open_lo) snprintf(buf + len, size - len, ": it must be > %s", lo);
    else if (open_hi) snprintf(buf + len, size - len, ": it must be < %s", hi);
}

/* An array parameter: a sane count, a pointer when there are elements, and
 * every element a number the spec accepts (the message names the first one
 * that is not). */
static hr_status check_numbers(hr_context *ctx, const hr_shape_class *cls, const char *module_path,
                               const hr_param_spec *spec, const hr_param *p)
{
    if (p->count < 0 || (p->count > 0 && !p->numbers))
        return hri_error(ctx, HR_ERROR_PARAMETER,
                        "shape '%s': parameter '%s' has count %lld and %s pointer", cls->name,
                        p->name, (long long)p->count, p->numbers ? "a" : "a NULL");
    for (int64_t i = 0; i < p->count; i++) {
        double v = p->numbers[i];
        if (!isfinite(v))
            return hri_error(ctx, HR_ERROR_PARAMETER,
                            "shape '%s': element %lld of parameter '%s' must be a finite "
                            "number, not %g",
                            cls->name, (long long)i, p->name, v);
        if (!shape_param_accepts(spec, v)) {
            char range[128];
            format_range(spec, range, sizeof range);
            return hri_error(ctx, HR_ERROR_PARAMETER,
                            "shape '%s' (module '%s'): element %lld of parameter '%s' = %g is "
                            "outside %s",
                            cls->name, module_path, (long long)i, p->name, v, range);
        }
    }
    return HR_OK;
}

hr_status hri_params_resolve(hr_scene *scene, const hr_shape_class *cls, const char *module_path,
                            const hr_param *given, int32_t given_count, hr_param *full,
                            const void **objects)
{
    hr_context *ctx = scene->ctx;
    hr_status st;
    int32_t seen[256] = {0};
    if (cls->param_count > 256)
        return hri_error(ctx, HR_ERROR_MODULE, "shape '%s' (module '%s') declares too many parameters",
                        cls->name, module_path);
    for (int32_t i = 0; i < cls->param_count; i++) {
        const hr_param_spec *spec = &cls->params[i];
        memset(&full[i], 0, sizeof full[i]);
        full[i].name = spec->name;
        full[i].type = spec->type;
        full[i].number = spec->default_number;
        /* string/numbers and object/count share their places: the type says
         * which one the default fills. */
        if (spec->type == HR_PARAM_NUMBERS) {
            full[i].numbers = NULL;
            full[i].count = 0;
        } else {
            full[i].string = "";
            full[i].object = -1;
        }
        objects[i] = NULL;
    }
    for (int32_t g = 0; g < given_count; g++) {
        const hr_param *p = &given[g];
        if (!p->name)
            return hri_error(ctx, HR_ERROR_PARAMETER, "shape '%s': parameter %d has no name",
                            cls->name, (int)g);
        int32_t k = -1;
        for (int32_t i = 0; i < cls->param_count; i++)
            if (strcmp(cls->params[i].name, p->name) == 0) k = i;
        if (k < 0) {
            char names[512], hint[128] = "";
            list_params(cls, names, sizeof names);
            hr_suggester near;
            hri_suggester_init(&near, p->name);
            for (int32_t i = 0; i < cls->param_count; i++) hri_suggester_offer(&near, cls->params[i].name);
            if (near.best) snprintf(hint, sizeof hint, " (did you mean '%.96s'?)", near.best);
            return hri_error(ctx, HR_ERROR_PARAMETER,
                            "shape '%s' (module '%s') has no parameter '%s'%s; %s", cls->name,
                            module_path, p->name, hint, names);
        }
        const hr_param_spec *spec = &cls->params[k];
        if (seen[k]++)
            return hri_error(ctx, HR_ERROR_PARAMETER, "shape '%s': parameter '%s' given twice",
                            cls->name, p->name);
        if (p->type != spec->type)
            return hri_error(ctx, HR_ERROR_PARAMETER, "shape '%s': parameter '%s' must be %s, not %s",
                            cls->name, p->name, type_name(spec->type), type_name(p->type));
        if (spec->type == HR_PARAM_NUMBER) {
            if (!isfinite(p->number))
                return hri_error(ctx, HR_ERROR_PARAMETER,
                                "shape '%s': parameter '%s' must be a finite number, not %g",
                                cls->name, p->name, p->number);
            if (!shape_param_accepts(spec, p->number)) {
                char range[128];
                format_range(spec, range, sizeof range);
                return hri_error(ctx, HR_ERROR_PARAMETER,
                                "shape '%s' (module '%s'): parameter '%s' = %g is outside %s",
                                cls->name, module_path, p->name, p->number, range);
            }
            full[k].number = p->number;
        } else if (spec->type == HR_PARAM_STRING) {
            if (!p->string)
                return hri_error(ctx, HR_ERROR_PARAMETER, "shape '%s': parameter '%s' is NULL",
                                cls->name, p->name);
            full[k].string = p->string;
        } else if (spec->type == HR_PARAM_NUMBERS) {
            if ((st = check_numbers(ctx, cls, module_path, spec, p))) return st;
            full[k].numbers = p->count ? p->numbers : NULL;
            full[k].count = p->count;
        } else {
            if (!(cls->flags & HR_SHAPE_COMPOSITE))
                return hri_error(ctx, HR_ERROR_MODULE,
                                "shape '%s' (module '%s') takes an object parameter but is not "
                                "marked composite",
                                cls->name, module_path);
            if (p->object < 0 || p->object >= scene->object_count)
                return hri_error(ctx, HR_ERROR_PARAMETER,
                                "shape '%s': parameter '%s' names object %lld, but the scene has "
                                "objects 0..%lld",
                                cls->name, p->name, (long long)p->object,
                                (long long)scene->object_count - 1);
            const hr_object *child = scene->objects[p->object];
            if (!child->top_level)
                return hri_error(ctx, HR_ERROR_PARAMETER,
                                "shape '%s': parameter '%s' names object %lld, which another "
                                "composite already uses",
                                cls->name, p->name, (long long)p->object);
            for (int32_t i = 0; i < cls->param_count; i++)
                if (objects[i] == child)
                    return hri_error(ctx, HR_ERROR_PARAMETER,
                                    "shape '%s': object %lld given twice", cls->name,
                                    (long long)p->object);
            full[k].object = p->object;
            objects[k] = child;
        }
    }
    for (int32_t i = 0; i < cls->param_count; i++)
        if (cls->params[i].required && !seen[i])
            return hri_error(ctx, HR_ERROR_PARAMETER,
                            "shape '%s' (module '%s'): parameter '%s' is required", cls->name,
                            module_path, cls->params[i].name);
    return HR_OK;
}

hr_param *hri_params_keep(const hr_param *full, int32_t n, uint64_t *bytes)
{
    *bytes = 0;
    if (n <= 0) return NULL;
    size_t size = (size_t)n * sizeof(hr_param);
    for (int32_t i = 0; i < n; i++)
        if (full[i].type != HR_PARAM_NUMBERS && full[i].string) size += strlen(full[i].string) + 1;
    hr_param *kept = malloc(size);
    if (!kept) return NULL;
    char *text = (char *)(kept + n);
    for (int32_t i = 0; i < n; i++) {
        kept[i] = full[i];
        if (full[i].type == HR_PARAM_NUMBERS) {
            kept[i].numbers = NULL;
        } else if (full[i].string) {
            const size_t length = strlen(full[i].string) + 1;
            memcpy(text, full[i].string, length);
            kept[i].string = text;
            text += length;
        }
    }
    *bytes = size;
    return kept;
}
