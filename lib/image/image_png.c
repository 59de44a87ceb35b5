/* The PNG writer, through libpng: 8 or 16 bits per sample, RGB or RGBA,
 * sRGB-encoded (with an sRGB chunk) or linear (with gAMA 1.0).
 *
 * libpng reports errors by calling our error function, which must not
 * return: it longjmps back to the setjmp in write_image. Everything that
 * needs freeing on that path is allocated before setjmp and not changed
 * after it, so its value after the longjmp is well defined without
 * `volatile` (C11 7.13.2.1); the one variable written after setjmp that the
 * error path reads is `volatile`. */
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "image/image_srgb.h"
#include "image/image_writers.h"

typedef struct png_failure {
    char message[256];
    char warning[256]; /* the last warning: libpng often explains an error in
                          a warning just before it (a width over its limit) */
} png_failure;

static void on_png_error(png_structp png, png_const_charp message)
{
    png_failure *failure = png_get_error_ptr(png);
    if (failure) snprintf(failure->message, sizeof failure->message, "%s", message);
    png_longjmp(png, 1);
}

/* The library never prints: warnings are kept for the error message. */
static void on_png_warning(png_structp png, png_const_charp message)
{
    png_failure *failure = png_get_error_ptr(png);
    if (failure) snprintf(failure->warning, sizeof failure->warning, "%s", message);
}

/* Our own output functions instead of libpng's stdio ones, so a failed
 * write reports why (disk full, ...), not just "Write Error". */
static void write_bytes(png_structp png, png_bytep data, size_t length)
{
    FILE *fp = png_get_io_ptr(png);
    if (fwrite(data, 1, length, fp) != length) png_error(png, strerror(errno));
}

static void flush_bytes(png_structp png)
{
    FILE *fp = png_get_io_ptr(png);
    if (fflush(fp) != 0) png_error(png, strerror(errno));
}

/* One row of code values, laid out as PNG stores them: 8-bit samples, or
 * 16-bit samples most significant byte first. Alpha is coverage, not light,
 * so it is never sRGB-encoded. */
static void encode_row(const float *src, int32_t width, int32_t channels, int srgb, int bits,
                       png_bytep dst)
{
    if (srgb && bits == 8 && channels == 3) {
        /* The common case, by the table all at once. */
        hri_srgb8_encode_rgb(src, (size_t)width, channels, dst);
        return;
    }
    uint32_t max_code = bits == 16 ? 65535u : 255u;
    for (int32_t x = 0; x < width; x++) {
        for (int32_t c = 0; c < channels; c++) {
            uint32_t code = hri_code_value(*src++, srgb && c < 3, max_code);
            if (bits == 16) {
                *dst++ = (png_byte)(code >> 8);
                *dst++ = (png_byte)(code & 0xffu);
            } else {
                *dst++ = (png_byte)code;
            }
        }
    }
}

static hr_status write_image(const hr_context *ctx, const hr_pixels *px,
                             const hr_image_write_options *o, hr_atomic_file *out,
                             png_structp png, png_infop info, png_bytep row, png_failure *failure)
{
    const int srgb = !o->png_linear;
    const int bits = o->png_bits;
    volatile int32_t rows_done = 0;
    if (setjmp(png_jmpbuf(png))) {
        /* png, info and row belong to the caller, which frees them. */
        char rows[64] = "";
        if (rows_done > 0) snprintf(rows, sizeof rows, " (after %d of %d rows)", (int)rows_done, (int)px->height);
        return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': libpng: %s%s%s%s%s", out->target,
                        failure->message, failure->warning[0] ? " (" : "", failure->warning,
                        failure->warning[0] ? ")" : "", rows);
    }
    png_set_write_fn(png, out->fp, write_bytes, flush_bytes);
    png_set_IHDR(png, info, (png_uint_32)px->width, (png_uint_32)px->height, bits,
                 px->channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (srgb)
        /* sRGB plus the matching gAMA and cHRM for readers that predate sRGB. */
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    else
        png_set_gAMA_fixed(png, info, PNG_FP_1);
    png_write_info(png, info);
    size_t stride = (size_t)px->width * (size_t)px->channels;
    for (int32_t y = 0; y < px->height; y++) {
        encode_row(px->data + (size_t)y * stride, px->width, px->channels, srgb, bits, row);
        png_write_row(png, row);
        rows_done = y + 1;
    }
    png_write_end(png, info);
    return HR_OK;
}

hr_status hri_write_png(const hr_context *ctx, const hr_pixels *px,
                       const hr_image_write_options *o, hr_atomic_file *out)
{
    png_failure failure;
    memset(&failure, 0, sizeof failure);
    size_t row_bytes = (size_t)px->width * (size_t)px->channels * (o->png_bits == 16 ? 2u : 1u);
    png_bytep row = malloc(row_bytes);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &failure, on_png_error,
                                              on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    hr_status st;
    if (!row || !png || !info)
        st = hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "cannot write '%s': out of memory", out->target);
    else
        st = write_image(ctx, px, o, out, png, info, row, &failure);
    png_destroy_write_struct(png ? &png : NULL, info ? &info : NULL);
    free(row);
    return st;
}
