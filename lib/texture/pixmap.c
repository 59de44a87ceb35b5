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
        for (int32_t k = 0; k < set->pixmaps[i]->level_count; k++) free(set->pixmaps[i]->levels[k]);
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

/* The next mip level's side: half, rounded up. */
static int32_t half_side(int32_t n) { return n / 2 + (n & 1); }

uint64_t hri_pixmap_mip_bytes(int32_t w, int32_t h)
{
    uint64_t bytes = 0;
    while (w > 1 || h > 1) {
        w = half_side(w), h = half_side(h);
        bytes += (uint64_t)w * (uint64_t)h * 3 * sizeof(float);
    }
    return bytes;
}

uint64_t hri_pixmap_bytes(const hr_image *image, int32_t index, char *what, size_t what_size)
{
    const int32_t w = hr_image_width(image), h = hr_image_height(image);
    snprintf(what, what_size, "pixmap %d (%d x %d texels and its mip-map)", (int)index, (int)w, (int)h);
    return (uint64_t)w * (uint64_t)h * 3 * sizeof(float) + hri_pixmap_mip_bytes(w, h);
}

/* Mip level k + 1 of pm from level k: each texel the mean of the 2 x 2 it
 * covers, an odd side's last one wrapping to the first (the texture tiles). */
static float *next_level(const float *src, int32_t w, int32_t h, int32_t nw, int32_t nh)
{
    float *dst = malloc((size_t)nw * (size_t)nh * 3 * sizeof *dst);
    if (!dst) return NULL;
    for (int32_t y = 0; y < nh; y++) {
        const int32_t y0 = 2 * y < h ? 2 * y : 0, y1 = 2 * y + 1 < h ? 2 * y + 1 : 0;
        for (int32_t x = 0; x < nw; x++) {
            const int32_t x0 = 2 * x < w ? 2 * x : 0, x1 = 2 * x + 1 < w ? 2 * x + 1 : 0;
            for (int c = 0; c < 3; c++) {
                const double sum = (double)src[((size_t)y0 * (size_t)w + (size_t)x0) * 3 + (size_t)c] +
                                   (double)src[((size_t)y0 * (size_t)w + (size_t)x1) * 3 + (size_t)c] +
                                   (double)src[((size_t)y1 * (size_t)w + (size_t)x0) * 3 + (size_t)c] +
                                   (double)src[((size_t)y1 * (size_t)w + (size_t)x1) * 3 + (size_t)c];
                dst[((size_t)y * (size_t)nw + (size_t)x) * 3 + (size_t)c] = (float)(0.25 * sum);
            }
        }
    }
    return dst;
}

/* Every level above the image, down to 1 x 1. */
static hr_status build_mip_map(hr_context *ctx, hr_pixmap *pm)
{
    pm->levels[0] = pm->rgb;
    pm->level_width[0] = pm->width, pm->level_height[0] = pm->height;
    pm->level_count = 1;
    while (pm->level_width[pm->level_count - 1] > 1 || pm->level_height[pm->level_count - 1] > 1) {
        const int32_t k = pm->level_count;
        const int32_t w = pm->level_width[k - 1], h = pm->level_height[k - 1];
        pm->level_width[k] = half_side(w), pm->level_height[k] = half_side(h);
        if (!(pm->levels[k] = next_level(pm->levels[k - 1], w, h, pm->level_width[k], pm->level_height[k])))
            return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory for pixmap %d's mip-map",
                            (int)pm->index);
        pm->level_count++;
    }
    return HR_OK;
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
    if ((st = build_mip_map(ctx, pm))) {
        for (int32_t k = 0; k < pm->level_count; k++) free(pm->levels[k]);
        free(pm);
        return st;
    }
    set->pixmaps[set->count++] = pm;
    return HR_OK;
}

static hr_color texel(const float *data, int32_t width, int32_t x, int32_t y)
{
    const float *p = data + ((size_t)y * (size_t)width + (size_t)x) * 3;
    return rgb(p[0], p[1], p[2]);
}

/* x in [0, n) from a coordinate that may be one step outside. */
static int32_t wrap(int32_t x, int32_t n) { return x < 0 ? x + n : x >= n ? x - n : x; }

/* Bilinear between the four nearest texel centres of a w x h level. */
static hr_color bilinear(const float *data, int32_t w, int32_t h, double s, double t)
{
    /* Texel centres sit at (x + 1/2) / width across and, since rows run
     * from the top, at 1 - (y + 1/2) / height up. */
    const double gx = s * w - 0.5, gy = (1.0 - t) * h - 0.5;
    const double x0 = floor(gx), y0 = floor(gy);
    const double ax = gx - x0, ay = gy - y0;
    const int32_t xa = wrap((int32_t)x0, w), xb = wrap((int32_t)x0 + 1, w);
    const int32_t ya = wrap((int32_t)y0, h), yb = wrap((int32_t)y0 + 1, h);
    hr_color top = rgb_add(rgb_scale(texel(data, w, xa, ya), 1.0 - ax), rgb_scale(texel(data, w, xb, ya), ax));
    hr_color bottom =
        rgb_add(rgb_scale(texel(data, w, xa, yb), 1.0 - ax), rgb_scale(texel(data, w, xb, yb), ax));
    return rgb_add(rgb_scale(top, 1.0 - ay), rgb_scale(bottom, ay));
}

hr_color hri_pixmap_sample(const hr_pixmap *pm, double s, double t, int nearest)
{
    if (nearest) {
        const double fx = s * pm->width, fy = (1.0 - t) * pm->height;
        int32_t x = (int32_t)fx, y = (int32_t)fy;
        return texel(pm->rgb, pm->width, x < pm->width ? x : pm->width - 1, y < pm->height ? y : pm->height - 1);
    }
    return bilinear(pm->rgb, pm->width, pm->height, s, t);
}

hr_color hri_pixmap_sample_level(const hr_pixmap *pm, int32_t level, double s, double t)
{
    if (level < 0) level = 0;
    if (level >= pm->level_count) level = pm->level_count - 1;
    return bilinear(pm->levels[level], pm->level_width[level], pm->level_height[level], s, t);
}

hr_color hri_pixmap_sample_footprint(const hr_pixmap *pm, double s, double t, const double d[4])
{
    /* The footprint's longer side in texels of the image: level log2 of it
     * has texels that wide. */
    const double along_x = hypot(d[0] * pm->width, d[1] * pm->height);
    const double along_y = hypot(d[2] * pm->width, d[3] * pm->height);
    const double texels = fmax(along_x, along_y);
    if (!(texels > 1.0)) return bilinear(pm->rgb, pm->width, pm->height, s, t);
    const double lod = log2(texels);
    if (!(lod < pm->level_count - 1)) return hri_pixmap_sample_level(pm, pm->level_count - 1, s, t);
    const int32_t k = (int32_t)lod;
    const double f = lod - k;
    return rgb_add(rgb_scale(hri_pixmap_sample_level(pm, k, s, t), 1.0 - f),
                   rgb_scale(hri_pixmap_sample_level(pm, k + 1, s, t), f));
}
