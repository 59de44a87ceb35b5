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

#endif
