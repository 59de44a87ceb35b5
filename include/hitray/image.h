/* hitray: images of linear float RGB(A) and their writers.
 *
 * Pixels are stored row by row from the top, channels interleaved, as 32-bit
 * floats in linear light. Writers: PNG (libpng), EXR (OpenEXRCore), PPM
 * (binary P6, 8-bit sRGB), PFM (float, bottom row first as the format
 * says), and JPEG, Radiance HDR, BMP and TGA (stb_image_write). Every writer writes to a temporary file beside the target and
 * renames it into place, so a failure never leaves a half-written image. */
#ifndef HITRAY_IMAGE_H
#define HITRAY_IMAGE_H

#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* channels: 3 (RGB) or 4 (RGBA). Pixels start at 0. */
HR_API hr_status hr_image_create(hr_context *ctx, int32_t width, int32_t height,
                                 int32_t channels, hr_image **out);
HR_API void hr_image_destroy(hr_image *image);
HR_API int32_t hr_image_width(const hr_image *image);
HR_API int32_t hr_image_height(const hr_image *image);
HR_API int32_t hr_image_channels(const hr_image *image);
/* width * height * channels floats, starting on a 64-byte boundary (a
 * cache line); stays valid until destroy. */
HR_API float *hr_image_data(hr_image *image);

/* Read a PNG (libpng: any bit depth, palette or grey, its gAMA/sRGB
 * honoured), BMP or JPEG (stb_image: 8-bit sRGB) file into a new RGB image
 * of linear floats, the format told by the file's first bytes. Fails with
 * HR_ERROR_IO naming the file and the reason (missing, not a regular file,
 * unreadable, not one of these formats, corrupt) or HR_ERROR_UNSUPPORTED for an image wider or
 * taller than HR_IMAGE_READ_MAX_SIDE or of more than
 * HR_IMAGE_READ_MAX_PIXELS pixels (checked before its pixels are decoded,
 * so a file cannot make the reader allocate without bound). */
#define HR_IMAGE_READ_MAX_SIDE 65536
#define HR_IMAGE_READ_MAX_PIXELS 16777216 /* 2^24, 4096 x 4096: 192 MiB of floats */
HR_API hr_status hr_image_read(hr_context *ctx, const char *path, hr_image **out);

/* `count` linear values as the 8-bit codes an sRGB PNG or a PPM holds for
 * them, the same codes hr_image_write writes: the exact sRGB curve (IEC
 * 61966-2-1) rounded to nearest, NaN and values at or below 0 giving 0, at
 * or above 1 giving 255. For showing pixels on a display (hitray view)
 * without writing a file. Reentrant; `linear` and `codes` must not overlap. */
HR_API void hr_srgb8_encode(const float *linear, size_t count, uint8_t *codes);

#define HR_FORMAT_AUTO 0 /* from the file extension */
#define HR_FORMAT_PNG 1
#define HR_FORMAT_EXR 2
#define HR_FORMAT_PPM 3
#define HR_FORMAT_PFM 4
#define HR_FORMAT_JPEG 5 /* 8-bit sRGB, lossy (jpeg_quality) */
#define HR_FORMAT_HDR 6  /* Radiance RGBE: linear, an 8-bit mantissa a channel */
#define HR_FORMAT_BMP 7  /* 8-bit sRGB */
#define HR_FORMAT_TGA 8  /* 8-bit sRGB, run-length encoded */

/* The formats by name and extension, from one table (the codes above are
 * contiguous from HR_FORMAT_PNG: a code whose name is NULL is past the
 * last). hr_image_format_from_path: the format a file name's extension
 * names (any case), HR_FORMAT_AUTO for none; hr_image_format_from_name:
 * the format a short name ("png", as hitray's --format takes it) names,
 * HR_FORMAT_AUTO for none; hr_image_format_name and _extension: a format's
 * short name and its usual extension (".png"), NULL for no format;
 * hr_image_format_list: every usual extension as one phrase for messages
 * (".png, .exr, .ppm or .pfm"), cut to fit `size` bytes. */
HR_API int32_t hr_image_format_from_path(const char *path);
HR_API int32_t hr_image_format_from_name(const char *name);
HR_API const char *hr_image_format_name(int32_t format);
HR_API const char *hr_image_format_extension(int32_t format);
HR_API void hr_image_format_list(char *buf, size_t size);

typedef struct hr_image_write_options {
    uint32_t struct_size;
    int32_t format;     /* HR_FORMAT_*; AUTO picks by extension */
    int32_t png_bits;   /* 8 (default, 0 means 8) or 16 */
    int32_t png_linear; /* 1: write values as they are (what Hill's OpenGL
                           display showed); 0: sRGB-encode (default) */
    int32_t exr_half;   /* 1: 16-bit half floats; 0: 32-bit floats */
    int32_t jpeg_quality; /* 1..100; 0 (default): 90. Was `reserved`
                             (always 0) before the JPEG writer. */
} hr_image_write_options;
HR_API void hr_image_write_options_default(hr_image_write_options *o);

/* `options` may be NULL for the defaults. */
HR_API hr_status hr_image_write(hr_context *ctx, const hr_image *image, const char *path,
                                const hr_image_write_options *options);

/* Several files written all or nothing, for a program whose one command
 * makes several outputs (an image, its EXR twin, its statistics): each file
 * is written in full, and synced, to a temporary file beside its target as
 * it is added, so a full disk or an unwritable place fails there, with none
 * of the batch's files put in place. Commit then puts every file in place
 * (one rename each, in the order added). Until commit nothing of the batch
 * is visible; destroying an uncommitted batch removes its temporary files.
 * Targets are checked as hr_image_write checks them (not a regular file, or
 * read-only: refused). A rename that fails during commit (the directory
 * removed meanwhile) is reported and the files after it are discarded;
 * those before it stay in place. */
typedef struct hr_file_batch hr_file_batch;
HR_API hr_status hr_file_batch_create(hr_context *ctx, hr_file_batch **out);
/* Write `image` as hr_image_write would write it to `path`. */
HR_API hr_status hr_file_batch_add_image(hr_file_batch *batch, const hr_image *image, const char *path,
                                         const hr_image_write_options *options);
/* Write `size` bytes of `data` to `path`. */
HR_API hr_status hr_file_batch_add_bytes(hr_file_batch *batch, const char *path, const void *data,
                                         size_t size);
/* Put every file in place; the batch is then empty (and may be reused). */
HR_API hr_status hr_file_batch_commit(hr_file_batch *batch);
/* Discard what is not committed and free the batch (NULL: nothing). */
HR_API void hr_file_batch_destroy(hr_file_batch *batch);

#ifdef __cplusplus
}
#endif
#endif
