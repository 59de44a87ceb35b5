/* Images of linear float pixels, and hr_image_write: argument checks, the
 * choice of format, and the all-or-nothing file around each writer. */
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "util/sized_copy.h"
#include "image/atomic_file.h"
#include "util/errors.h"
#include "image/image_internal.h"
#include "image/image_writers.h"

#define IMAGE_ALIGN 64 /* a cache line */
#define IMAGE_HUGE_PAGE ((size_t)2 << 20)

struct hr_image {
    int32_t width, height, channels;
    float *pixels;
};

static hr_status image_new(hr_context *ctx, int32_t width, int32_t height, int32_t channels, int zeroed,
                           hr_image **out)
{
    if (!out) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "image: NULL output pointer");
    *out = NULL;
    if (width <= 0 || height <= 0)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "image: size %dx%d must be positive",
                        (int)width, (int)height);
    if (channels != 3 && channels != 4)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "image: %d channels; only 3 (RGB) or 4 (RGBA)",
                        (int)channels);
    size_t count = (size_t)width * (size_t)height;
    if (count > SIZE_MAX / sizeof(float) / (size_t)channels)
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "image: %dx%d is too large", (int)width, (int)height);
    count *= (size_t)channels;
    /* On cache lines of their own: a render's threads write neighbouring
     * tiles at once, and with rows of whole lines (a width that is a
     * multiple of 16 pixels) no line then holds pixels of two tiles, so no
     * write of one thread takes a line from the other. aligned_alloc wants
     * a size that is a multiple of the alignment. */
    size_t bytes = count * sizeof(float);
    /* A large image on huge pages where the system gives them on request
     * (transparent huge pages in "madvise" mode): a 1024 x 1024 render
     * would otherwise take 3,072 page faults, in the render's threads, which
     * contend for the process's page tables; 2 MiB pages take 6. The
     * request may be refused, which changes nothing but the count. */
    size_t align = bytes >= IMAGE_HUGE_PAGE ? IMAGE_HUGE_PAGE : IMAGE_ALIGN;
    if (bytes > SIZE_MAX - (align - 1))
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "image: %dx%d is too large", (int)width, (int)height);
    bytes = (bytes + align - 1) / align * align;

    hr_image *image = malloc(sizeof *image);
    float *pixels = aligned_alloc(align, bytes);
    if (pixels && align == IMAGE_HUGE_PAGE) (void)madvise(pixels, bytes, MADV_HUGEPAGE);
    if (pixels && zeroed) memset(pixels, 0, bytes);
    if (!image || !pixels) {
        free(image);
        free(pixels);
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "image: out of memory for %dx%d", (int)width,
                        (int)height);
    }
    image->width = width;
    image->height = height;
    image->channels = channels;
    image->pixels = pixels;
    *out = image;
    return HR_OK;
}

HR_API hr_status hr_image_create(hr_context *ctx, int32_t width, int32_t height,
                                 int32_t channels, hr_image **out)
{
    return image_new(ctx, width, height, channels, 1, out);
}

hr_status hri_image_create_unset(hr_context *ctx, int32_t width, int32_t height, int32_t channels,
                                hr_image **out)
{
    return image_new(ctx, width, height, channels, 0, out);
}

HR_API void hr_image_destroy(hr_image *image)
{
    if (!image) return;
    free(image->pixels);
    free(image);
}

HR_API int32_t hr_image_width(const hr_image *image) { return image ? image->width : 0; }
HR_API int32_t hr_image_height(const hr_image *image) { return image ? image->height : 0; }
HR_API int32_t hr_image_channels(const hr_image *image) { return image ? image->channels : 0; }
HR_API float *hr_image_data(hr_image *image) { return image ? image->pixels : NULL; }

HR_API void hr_image_write_options_default(hr_image_write_options *o)
{
    if (!o) return;
    memset(o, 0, sizeof *o);
    o->struct_size = sizeof *o;
    o->format = HR_FORMAT_AUTO;
    o->png_bits = 8;
}

/* The caller's options over the defaults, reading only the bytes the caller
 * says its struct has (common.h), then checked. */
static hr_status read_options(const hr_context *ctx, const hr_image_write_options *given,
                              const char *path, hr_image_write_options *o)
{
    hr_image_write_options_default(o);
    if (given) {
        if (given->struct_size < sizeof(uint32_t))
            return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "image write options: struct_size not set");
        HR_SIZED_COPY_IN(o, given);
    }
    if (o->png_bits == 0) o->png_bits = 8;
    if (o->png_bits != 8 && o->png_bits != 16)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "cannot write '%s': png_bits is %d; only 8 or 16",
                        path, (int)o->png_bits);
    if (o->format == HR_FORMAT_AUTO) {
        o->format = hr_image_format_from_path(path);
        if (o->format == HR_FORMAT_AUTO) {
            char known[128];
            hr_image_format_list(known, sizeof known);
            return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "cannot write '%s': unknown image format (use %s)",
                            path, known);
        }
    } else if (!hr_image_format_name(o->format)) {
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "cannot write '%s': unknown format code %d",
                        path, (int)o->format);
    }
    return HR_OK;
}

/* Write `image` to `out`'s temporary file and finish it (image_writers.h):
 * on success only publishing is left; on failure `out` is released. */
hr_status hri_image_write_unpublished(const hr_context *ctx, const hr_image *image, const char *path,
                                     const hr_image_write_options *options, hr_atomic_file *out)
{
    if (!image) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "image write: NULL image");
    if (!path || !*path) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "image write: empty file name");
    hr_image_write_options o;
    hr_status st = read_options(ctx, options, path, &o);
    if (st) return st;

    hr_pixels px = {image->width, image->height, image->channels, image->pixels};
    st = hri_atomic_file_open(ctx, path, out);
    if (st) return st;
    switch (o.format) {
    case HR_FORMAT_PNG: st = hri_write_png(ctx, &px, &o, out); break;
    case HR_FORMAT_EXR: st = hri_write_exr(ctx, &px, &o, out); break;
    case HR_FORMAT_PPM: st = hri_write_ppm(ctx, &px, out); break;
    case HR_FORMAT_PFM: st = hri_write_pfm(ctx, &px, out); break;
    default: st = hri_write_stb(ctx, &px, &o, out); break;
    }
    if (st) {
        hri_atomic_file_abort(out);
        return st;
    }
    return hri_atomic_file_finish(ctx, out);
}

HR_API hr_status hr_image_write(hr_context *ctx, const hr_image *image, const char *path,
                                const hr_image_write_options *options)
{
    hr_atomic_file out;
    hr_status st = hri_image_write_unpublished(ctx, image, path, options, &out);
    return st ? st : hri_atomic_file_publish(ctx, &out);
}
