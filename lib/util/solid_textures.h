/* Internal: the solid textures as a list for messages ("-1 checkerboard,
 * -2 wood, -3 marble"), from the public hr_solid_texture_name, so that the
 * scene's check of a material and the SDL reader's say the same. Inline, so
 * that the call to texture/ is made from the caller's layer (texture itself,
 * or a reader through the public API), not from util, which is below it. */
#ifndef HITRAY_LIB_UTIL_SOLID_TEXTURES_H
#define HITRAY_LIB_UTIL_SOLID_TEXTURES_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <hitray/hitray.h>

static inline void hri_solid_texture_list(char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int32_t id = -1; used < size; id--) {
        const char *name = hr_solid_texture_name(id);
        if (!name) break;
        int n = snprintf(buf + used, size - used, "%s%d %s", id < -1 ? ", " : "", (int)id, name);
        if (n < 0) break;
        used += (size_t)n;
    }
}

#endif
