/* JPEG, Radiance HDR, BMP and TGA through stb_image_write (Debian's
 * libstb, which also reads BMP and JPEG pixmaps). JPEG, BMP and TGA hold
 * 8-bit sRGB codes, the same ones the PNG and PPM writers store; HDR holds
 * the linear values in RGBE (an 8-bit mantissa per channel under a shared
 * exponent). All four store RGB: alpha is dropped. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "util/errors.h"
#include "image/image_srgb.h"
#include "image/image_writers.h"

#define JPEG_DEFAULT_QUALITY 90
#define RGBE_MAX 1e38f /* under 2^127 (1.7e38), the largest RGBE exponent */

typedef struct sink {
    FILE *fp;
    int failed; /* a short write: errno says why */
} sink;

static void write_bytes(void *user, void *data, int size)
{
    sink *s = user;
    if (!s->failed && size > 0 && fwrite(data, 1, (size_t)size, s->fp) != (size_t)size) s->failed = 1;
}

/* RGBE holds no sign, no NaN and exponents up to 2^127 (the encoder
 * would wrap its exponent byte past them): negative and NaN give 0, the
 * rest is capped under 2^127. */
static float rgbe_storable(float v)
{
    if (!(v > 0.0f)) return 0.0f;
    return v < RGBE_MAX ? v : RGBE_MAX;
}

/* The image as RGB: 8-bit sRGB codes or, for HDR, linear floats. */
static void *rgb_copy(const hr_pixels *px, int floats)
{
    size_t count = (size_t)px->width * (size_t)px->height;
    if (count > SIZE_MAX / 3 / sizeof(float)) return NULL;
    void *rgb = malloc(count * 3 * (floats ? sizeof(float) : 1));
    if (!rgb) return NULL;
    if (!floats) {
        hri_srgb8_encode_rgb(px->data, count, px->channels, rgb);
        return rgb;
    }
    float *dst = rgb;
    for (size_t i = 0; i < count; i++)
        for (int c = 0; c < 3; c++) dst[i * 3 + c] = rgbe_storable(px->data[i * (size_t)px->channels + (size_t)c]);
    return rgb;
}

hr_status hri_write_stb(const hr_context *ctx, const hr_pixels *px, const hr_image_write_options *o,
                       hr_atomic_file *out)
{
    int quality = o->jpeg_quality ? (int)o->jpeg_quality : JPEG_DEFAULT_QUALITY;
    if (o->format == HR_FORMAT_JPEG && (quality < 1 || quality > 100))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "cannot write '%s': jpeg_quality is %d; only 1..100",
                        out->target, quality);
    /* The formats' own limits: stb_image_write takes int sizes, and JPEG's
     * header has 16 bits for each side. */
    if (o->format == HR_FORMAT_JPEG && (px->width > 65535 || px->height > 65535))
        return hri_error(ctx, HR_ERROR_UNSUPPORTED, "cannot write '%s': JPEG holds at most 65535 pixels a side",
                        out->target);
    void *rgb = rgb_copy(px, o->format == HR_FORMAT_HDR);
    if (!rgb) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "cannot write '%s': out of memory", out->target);
    sink s = {out->fp, 0};
    int w = (int)px->width, h = (int)px->height, ok = 0;
    errno = 0;
    switch (o->format) {
    case HR_FORMAT_JPEG: ok = stbi_write_jpg_to_func(write_bytes, &s, w, h, 3, rgb, quality); break;
    case HR_FORMAT_HDR: ok = stbi_write_hdr_to_func(write_bytes, &s, w, h, 3, rgb); break;
    case HR_FORMAT_BMP: ok = stbi_write_bmp_to_func(write_bytes, &s, w, h, 3, rgb); break;
    default: ok = stbi_write_tga_to_func(write_bytes, &s, w, h, 3, rgb); break;
    }
    int saved = errno;
    free(rgb);
    if (s.failed) return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", out->target, strerror(saved));
    if (!ok) return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': the %s encoder failed", out->target,
                             hr_image_format_name(o->format));
    return HR_OK;
}
