/* hitray: a ray tracer after F.S. Hill's Computer Graphics Using OpenGL,
 * chapter 12. Include this one header for the whole public C API. */
#ifndef HITRAY_H
#define HITRAY_H

#include "common.h"
#include "context.h"
#include "shape_module.h"
#include "transform.h"
#include "camera.h"
#include "scene.h"
#include "render.h"
#include "image.h"
#include "sdl.h"
#include "nff.h"

#endif
