/* hitray shape kit: declaring a module. A one-class module ends in two
 * statements, its class and its module:
 *
 *   SHAPE_CLASS(disk, .name = "disk", .help = "...", SHAPE_PARAMS(disk_params),
 *               .surface_count = 1, .create = disk_create, .destroy = disk_destroy);
 *   SHAPE_MODULE_OF(disk, "a flat disk", SHAPE_METADATA("1.0.0", "me", NULL));
 *
 * SHAPE_CLASS(prefix, ...) defines `prefix_class` with struct_size and the
 * functions named by the kit's conventions filled in: prefix_bounds and
 * prefix_hit, prefix_first_hit, prefix_any_hit (SHAPE_DEFINE_HIT_MODES makes
 * those three); the rest are the designated initializers given.
 * SHAPE_MODULE_OF(prefix, description, metadata) exports a module named
 * "prefix" of that one class; SHAPE_MODULE(name, description, metadata,
 * &a_class, &b_class, ...) one of several classes. The entry point answers
 * every host with its description: the host compares abi_version with its
 * own and explains a mismatch, naming the module's path. */
#ifndef HITRAY_SHAPE_KIT_MODULE_H
#define HITRAY_SHAPE_KIT_MODULE_H

#include <string.h>

#include "shape_module.h"

/* The parameter `name` of a create call, or NULL if the class declares no
 * such parameter. The host passes every declared parameter, checked against
 * its spec (type, range) and with its default filled in, so a class looks
 * its parameters up by name: a parameter added later cannot shift what
 * create reads. */
static inline const hr_param *shape_param(const hr_create_args *args, const char *name)
{
    for (int32_t i = 0; i < args->param_count; i++)
        if (args->params[i].name && strcmp(args->params[i].name, name) == 0) return &args->params[i];
    return NULL;
}

/* Whether the number v lies in spec's range (every number does when
 * min > max), each end inclusive unless its HR_PARAM_*_EXCLUSIVE flag is
 * set; NaN never does, and -0 is not > 0. The host's check before create
 * (and so a module's or a test's that must agree with it). */
static inline int shape_param_accepts(const hr_param_spec *spec, double v)
{
    if (!(spec->min <= spec->max)) return 1;
    const int above = spec->flags & HR_PARAM_MIN_EXCLUSIVE ? v > spec->min : v >= spec->min;
    const int below = spec->flags & HR_PARAM_MAX_EXCLUSIVE ? v < spec->max : v <= spec->max;
    return above && below;
}

/* The designated initializers of a class's parameter list. */
#define SHAPE_PARAMS(specs)                                                    \
    .params = (specs), .param_count = (int32_t)(sizeof(specs) / sizeof((specs)[0]))

/* The designated initializers of a module's metadata (each may be NULL). */
#define SHAPE_METADATA(version_, author_, url_)                                \
    .version = (version_), .author = (author_), .url = (url_)

#define SHAPE_CLASS(prefix, ...)                                               \
    static const hr_shape_class prefix##_class = {                             \
        .struct_size = sizeof(hr_shape_class),                                 \
        .bounds = prefix##_bounds,                                             \
        .hit = prefix##_hit,                                                   \
        .first_hit = prefix##_first_hit,                                       \
        .any_hit = prefix##_any_hit,                                           \
        __VA_ARGS__}

/* The module info of shape_module_classes_ and the entry point that returns
 * it; the variable arguments are the metadata's initializers. */
#define SHAPE_MODULE_INFO_(name_, description_, ...)                           \
    static const hr_module_info shape_module_info_ = {                         \
        .struct_size = sizeof(hr_module_info),                                 \
        .abi_version = HR_SHAPE_ABI_VERSION,                                   \
        .name = (name_),                                                       \
        .description = (description_),                                         \
        .classes = shape_module_classes_,                                      \
        .class_count = (int32_t)(sizeof shape_module_classes_ /                \
                                 sizeof shape_module_classes_[0]),             \
        __VA_ARGS__};                                                          \
    HR_DEFINE_SHAPE_MODULE(shape_host_version_, shape_host_)                   \
    {                                                                          \
        (void)shape_host_version_;                                             \
        (void)shape_host_;                                                     \
        return &shape_module_info_;                                            \
    }                                                                          \
    typedef int shape_module_defined_ /* so the use ends in ';' */

#define SHAPE_MODULE(name_, description_, metadata_, ...)                      \
    static const hr_shape_class *const shape_module_classes_[] = {__VA_ARGS__}; \
    SHAPE_MODULE_INFO_(name_, description_, metadata_)

#define SHAPE_MODULE_OF(prefix, description_, ...)                             \
    static const hr_shape_class *const shape_module_classes_[] = {&prefix##_class}; \
    SHAPE_MODULE_INFO_(#prefix, description_, __VA_ARGS__)

#endif
