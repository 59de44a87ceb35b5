/* hitray shape kit: the instance of a shape class that has no
 * parameters (sphere, plane, square, cube). It remembers only the host, so
 * destroy can give the memory back the way create got it. Nothing else is
 * kept per instance: the generic shape is the same for every object, and the
 * host's transform does the rest. */
#ifndef HITRAY_SHAPE_KIT_INSTANCE_H
#define HITRAY_SHAPE_KIT_INSTANCE_H

#include "shape_module.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct shape_plain {
    const hr_host *host;
} shape_plain;

static inline hr_status shape_plain_create(const hr_create_args *args, void **out_shape)
{
    shape_plain *shape = args->host->alloc(sizeof *shape);
    if (!shape) return HR_ERROR_OUT_OF_MEMORY;
    shape->host = args->host;
    *out_shape = shape;
    return HR_OK;
}

static inline void shape_plain_destroy(void *shape)
{
    if (!shape) return;
    const hr_host *host = ((shape_plain *)shape)->host;
    host->free(shape);
}

static inline void shape_set_bounds(hr_bounds *out, double lo_x, double lo_y, double lo_z,
                                    double hi_x, double hi_y, double hi_z)
{
    out->lo.x = lo_x;
    out->lo.y = lo_y;
    out->lo.z = lo_z;
    out->hi.x = hi_x;
    out->hi.y = hi_y;
    out->hi.z = hi_z;
}

#ifdef __cplusplus
}
#endif
#endif
