/* Internal: the bounds on input colours and exponents that keep every pixel
 * finite, one definition for the scene's checks of materials, lights and
 * globals, the textures' parameters and pixmaps, and the readers. */
#ifndef HITRAY_LIB_UTIL_COLOR_BOUNDS_H
#define HITRAY_LIB_UTIL_COLOR_BOUNDS_H

#include <math.h>

#include <hitray/hitray.h>

/* Input bounds that keep every pixel finite. With |colour| <= HR_MAX_COLOR,
 * weights in [0, 1] and an exponent >= 0 (so (h.m)^e <= 1), each ray traced
 * adds at most (2 + lights) * 1e12 to its pixel, weighted by products of
 * coefficients <= 1. A pixel is a sum over the rays it traced, so it stays
 * far below float's 3.4e38 for any render that can finish (it would take
 * ~1e20 rays per pixel to get there). A texture's colour is bounded the same
 * way (its parameters and pixmap pixels), and Cook-Torrance's term by
 * HR_COOK_TORRANCE_MAX (lib/trace/cook_torrance.c clamps to it): each multiplies a ray's share by
 * at most HR_INPUT_BOUND more, which still takes ~1e14 rays per pixel to overflow. The argument
 * needs one magnitude, HR_INPUT_BOUND, for all three. */
#define HR_INPUT_BOUND 1e6
#define HR_MAX_COLOR HR_INPUT_BOUND
#define HR_MAX_EXPONENT HR_INPUT_BOUND
#define HR_COOK_TORRANCE_MAX HR_INPUT_BOUND

/* A colour of a material, light or the globals within those bounds. */
static inline int hri_color_in_range(hr_color c)
{
    return isfinite(c.r) && isfinite(c.g) && isfinite(c.b) && fabs(c.r) <= HR_MAX_COLOR &&
           fabs(c.g) <= HR_MAX_COLOR && fabs(c.b) <= HR_MAX_COLOR;
}

#endif
