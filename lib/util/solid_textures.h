/* Internal: the solid textures as a list for messages ("-1 checkerboard,
 * -2 wood, -3 marble"), from the public hr_solid_texture_name, so that the
 * scene's check of a material and the SDL reader's say the same. */
#ifndef HITRAY_LIB_SOLID_TEXTURES_H
#define HITRAY_LIB_SOLID_TEXTURES_H

#include <stddef.h>

void hr_solid_texture_list(char *buf, size_t size);

#endif
