/* The solid textures as a list for messages (lib/util/solid_textures.h). */
#include "util/solid_textures.h"

#include <stdint.h>
#include <stdio.h>

#include <hitray/hitray.h>

void hr_solid_texture_list(char *buf, size_t size)
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
