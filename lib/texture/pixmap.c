/* A scene's pixmaps (Hill's makePixmap; lib/scene/scene_pixmaps.c is the
 * public door) and how an image texture reads one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "util/color_bounds.h"
#include "texture/texture.h"
#include "geometry/vec.h"

const hr_pixmap *hri_pixmap_find(const hr_pixmap_set *set, int32_t index)
{
    for (int32_t i = 0; i < set->count; i++)
        if (set->pixmaps[i]->index == index) return set->pixmaps[i];
    return NULL;
}

void hri_pixmap_set_free(hr_pixmap_set *set)
{
    for (int32_t i = 0; i < set->count; i++) {
        free(set->pixmaps[i]->rgb);
        free(set->pixmaps[i]);
    }
    free(set->pixmaps);
    set->pixmaps = NULL;
    set->count = set->cap = 0;
}

/* The image's pixels as RGB, checked. */
static hr_status copy_pixels(hr_context *ctx, int32_t index, const hr_image *image, float **out)
{
    const int32_t w = hr_image_width(image), h = hr_image_height(image);
    const int32_t ch = hr_image_channels(image);
    const float *src = hr_image_data((hr_image *)image);
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof *rgb);
    if (!rgb)
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory for pixmap %d (%d x %d)",
                        (int)index, (int)w, (int)h);
    for (size_t p = 0; p < (size_t)w * (size_t)h; p++)
        for (int c = 0; c < 3; c++) {
            const float v = src[p * (size_t)ch + (size_t)c];
            if (!(fabsf(v) <= HR_MAX_COLOR)) {
                free(rgb);
                return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                         "pixmap %d: pixel (%d, %d) has %s %g; pixels must be finite, each within "
                         "+-%g",
                         (int)index, (int)(p % (size_t)w), (int)(p / (size_t)w),
                         c == 0 ? "red" : c == 1 ? "green" : "blue", (double)v, HR_MAX_COLOR);
            }
            rgb[p * 3 + (size_t)c] = v;
        }
    *out = rgb;
    return HR_OK;
}

uint64_t hri_pixmap_bytes(const hr_image *image, int32_t index, char *what, size_t what_size)
{
    const int32_t w = hr_image_width(image), h = hr_image_height(image);
    snprintf(what, what_size, "pixmap %d (%d x %d texels)", (int)index, (int)w, (int)h);
    return (uint64_t)w * (uint64_t)h * 3 * sizeof(float);
}

hr_status hri_pixmap_add(hr_context *ctx, hr_pixmap_set *set, int32_t index, const hr_image *image)
{
    if (!image) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "pixmap %d: NULL image", (int)index);
    if (index < 1)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "pixmap number %d: pixmaps are numbered from 1",
                        (int)index);
    if (hri_pixmap_find(set, index))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "pixmap %d is made already", (int)index);
    const int32_t ch = hr_image_channels(image);
    if (hr_image_width(image) < 1 || hr_image_height(image) < 1 || (ch != 3 && ch != 4))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "pixmap %d: the image must be RGB or RGBA",
                        (int)index);
    if (set->count == set->cap) {
        int32_t cap = set->cap ? 2 * set->cap : 4;
        hr_pixmap **grown = realloc(set->pixmaps, (size_t)cap * sizeof *grown);
        if (!grown) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        set->pixmaps = grown;
        set->cap = cap;
    }
    hr_pixmap *pm = calloc(1, sizeof *pm);
    if (!pm) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    hr_status st = copy_pixels(ctx, index, image, &pm->rgb);
    if (st) {
        free(pm);
        return st;
    }
    pm->index = index;
    pm->width = hr_image_width(image);
    pm->height = hr_image_height(image);
    set->pixmaps[set->count++] = pm;
    return HR_OK;
}

static hr_color texel(const hr_pixmap *pm, int32_t x, int32_t y)
{
    const float *p = pm->rgb + ((size_t)y * (size_t)pm->width + (size_t)x) * 3;
    return rgb(p[0], p[1], p[2]);
}

/* x in [0, n) from a coordinate that may be one step outside. */
static int32_t wrap(int32_t x, int32_t n) { return x < 0 ? x + n : x >= n ? x - n : x; }

hr_color hri_pixmap_sample(const hr_pixmap *pm, double s, double t, int nearest)
{
    /* Texel centres sit at (x + 1/2) / width across and, since rows run
     * from the top, at 1 - (y + 1/2) / height up. */
    const double fx = s * pm->width, fy = (1.0 - t) * pm->height;
    if (nearest) {
        int32_t x = (int32_t)fx, y = (int32_t)fy;
        return texel(pm, x < pm->width ? x : pm->width - 1, y < pm->height ? y : pm->height - 1);
    }
    const double gx = fx - 0.5, gy = fy - 0.5;
    const double x0 = floor(gx), y0 = floor(gy);
    const double ax = gx - x0, ay = gy - y0;
    const int32_t xa = wrap((int32_t)x0, pm->width), xb = wrap((int32_t)x0 + 1, pm->width);
    const int32_t ya = wrap((int32_t)y0, pm->height), yb = wrap((int32_t)y0 + 1, pm->height);
    hr_color top = rgb_add(rgb_scale(texel(pm, xa, ya), 1.0 - ax), rgb_scale(texel(pm, xb, ya), ax));
    hr_color bottom = rgb_add(rgb_scale(texel(pm, xa, yb), 1.0 - ax), rgb_scale(texel(pm, xb, yb), ax));
    return rgb_add(rgb_scale(top, 1.0 - ay), rgb_scale(bottom, ay));
}
