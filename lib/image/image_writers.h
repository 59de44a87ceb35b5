/* Internal: the image file writers behind hr_image_write.
 *
 * hr_image_write (image.c) checks the arguments, picks the format, opens the
 * temporary file and commits or abandons it; a writer only turns pixels into
 * bytes on an open file and reports what went wrong, naming `out->target`. */
#ifndef HITRAY_LIB_IMAGE_WRITERS_H
#define HITRAY_LIB_IMAGE_WRITERS_H

#include <hitray/hitray.h>

#include "image/atomic_file.h"

/* A read-only view of an image's pixels (layout as in image.h). */
typedef struct hr_pixels {
    int32_t width, height, channels;
    const float *data;
} hr_pixels;

/* hr_image_write up to the last step: the image written to `out`'s
 * temporary file and synced; hri_atomic_file_publish puts it in place. On
 * failure `out` is released. */
hr_status hri_image_write_unpublished(const hr_context *ctx, const hr_image *image, const char *path,
                                     const hr_image_write_options *options, hr_atomic_file *out);

hr_status hri_write_png(const hr_context *ctx, const hr_pixels *px,
                       const hr_image_write_options *o, hr_atomic_file *out);
hr_status hri_write_exr(const hr_context *ctx, const hr_pixels *px,
                       const hr_image_write_options *o, hr_atomic_file *out);
hr_status hri_write_ppm(const hr_context *ctx, const hr_pixels *px, hr_atomic_file *out);
hr_status hri_write_pfm(const hr_context *ctx, const hr_pixels *px, hr_atomic_file *out);
/* JPEG, HDR, BMP and TGA (o->format says which) through stb_image_write. */
hr_status hri_write_stb(const hr_context *ctx, const hr_pixels *px, const hr_image_write_options *o,
                       hr_atomic_file *out);

#endif
