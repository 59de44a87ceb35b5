/* Internal: checking the parameters given for a shape against its class. */
#ifndef HITRAY_LIB_SCENE_PARAMS_H
#define HITRAY_LIB_SCENE_PARAMS_H

#include "scene/scene_internal.h"

/* Fill `full` (cls->param_count entries, in the class's order) from the
 * given parameters and the class's defaults, checking names, types, ranges
 * and required parameters; resolves HR_PARAM_OBJECT indices into `objects`.
 * Errors name the shape, its module and the parameter. */
hr_status hri_params_resolve(hr_scene *scene, const hr_shape_class *cls, const char *module_path,
                            const hr_param *given, int32_t given_count, hr_param *full,
                            const void **objects);

/* A copy of the resolved parameters (cls->param_count of them) that the
 * scene keeps for hr_scene_object_info: one block holding the entries and
 * their strings; names point at the class's spec, an HR_PARAM_NUMBERS
 * keeps its count but not its array. *bytes is the block's size. NULL when
 * out of memory (or when there are none, with *bytes 0). */
hr_param *hri_params_keep(const hr_param *full, int32_t n, uint64_t *bytes);

#endif
