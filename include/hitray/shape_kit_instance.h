/* hitray shape kit: the instance of a shape class that has no
 * parameters (sphere, plane, square, cube). Nothing is kept per instance:
 * the generic shape is the same for every object, and the host's transform
 * does the rest. So every object of such a class shares one instance, an
 * object of the module that is never written, and creating one allocates
 * nothing (a scene of a million spheres paid an allocation, its bytes and
 * its free for each). The host only hands `shape` back to the class. */
#ifndef HITRAY_SHAPE_KIT_INSTANCE_H
#define HITRAY_SHAPE_KIT_INSTANCE_H

#include "shape_module.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct shape_plain {
    char unused;
} shape_plain;

static inline hr_status shape_plain_create(const hr_create_args *args, void **out_shape)
{
    static shape_plain instance;
    (void)args;
    *out_shape = &instance;
    return HR_OK;
}

static inline void shape_plain_destroy(void *shape)
{
    (void)shape;
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
