/* The two Netpbm-family writers: PPM (binary P6, 8-bit sRGB) and PFM (32-bit
 * float, the "PF" colour variant). Both store RGB only: alpha is dropped. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "image/image_srgb.h"
#include "image/image_writers.h"

static hr_status write_failed(const hr_context *ctx, const hr_atomic_file *out)
{
    return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", out->target, strerror(errno));
}

static hr_status out_of_memory(const hr_context *ctx, const hr_atomic_file *out)
{
    return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "cannot write '%s': out of memory", out->target);
}

hr_status hri_write_ppm(const hr_context *ctx, const hr_pixels *px, hr_atomic_file *out)
{
    size_t row_bytes = (size_t)px->width * 3;
    unsigned char *row = malloc(row_bytes);
    if (!row) return out_of_memory(ctx, out);
    hr_status st = HR_OK;
    if (fprintf(out->fp, "P6\n%d %d\n255\n", (int)px->width, (int)px->height) < 0) st = write_failed(ctx, out);
    for (int32_t y = 0; y < px->height && st == HR_OK; y++) {
        const float *src = px->data + (size_t)y * (size_t)px->width * (size_t)px->channels;
        hri_srgb8_encode_rgb(src, (size_t)px->width, px->channels, row);
        if (fwrite(row, 1, row_bytes, out->fp) != row_bytes) st = write_failed(ctx, out);
    }
    free(row);
    return st;
}

/* PFM samples are raw IEEE floats in the byte order the scale's sign names;
 * we always write little-endian (scale -1), whatever the host's order. */
static void store_le32(unsigned char *dst, float value)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    dst[0] = (unsigned char)(bits & 0xffu);
    dst[1] = (unsigned char)((bits >> 8) & 0xffu);
    dst[2] = (unsigned char)((bits >> 16) & 0xffu);
    dst[3] = (unsigned char)(bits >> 24);
}

hr_status hri_write_pfm(const hr_context *ctx, const hr_pixels *px, hr_atomic_file *out)
{
    size_t row_bytes = (size_t)px->width * 3 * 4;
    unsigned char *row = malloc(row_bytes);
    if (!row) return out_of_memory(ctx, out);
    hr_status st = HR_OK;
    if (fprintf(out->fp, "PF\n%d %d\n-1.0\n", (int)px->width, (int)px->height) < 0) st = write_failed(ctx, out);
    /* The format stores the bottom row first. */
    for (int32_t y = px->height - 1; y >= 0 && st == HR_OK; y--) {
        const float *src = px->data + (size_t)y * (size_t)px->width * (size_t)px->channels;
        unsigned char *dst = row;
        for (int32_t x = 0; x < px->width; x++, src += px->channels)
            for (int c = 0; c < 3; c++, dst += 4) store_le32(dst, src[c]);
        if (fwrite(row, 1, row_bytes, out->fp) != row_bytes) st = write_failed(ctx, out);
    }
    free(row);
    return st;
}
