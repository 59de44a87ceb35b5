/* Reading images for pixmaps (hr_image_read): PNG through libpng's
 * simplified API, which decodes any bit depth, palette or grey and applies
 * the file's gAMA or sRGB chunk on its way to linear 16-bit values; BMP
 * and JPEG through stb_image (Debian's libstb), 8-bit sRGB decoded here.
 * The format is told by the first bytes, not the name. Each reader learns
 * the size from the header first and refuses one beyond the limits in
 * image.h before decoding a pixel. */
#include <errno.h>
#include <fcntl.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image.h>

#include "util/errors.h"
#include "image/image_srgb.h"

static hr_status check_size(hr_context *ctx, const char *path, long long w, long long h)
{
    if (w < 1 || h < 1 || w > HR_IMAGE_READ_MAX_SIDE || h > HR_IMAGE_READ_MAX_SIDE ||
        w * h > HR_IMAGE_READ_MAX_PIXELS)
        return hr_error(ctx, HR_ERROR_UNSUPPORTED,
                        "image '%s' is %lld x %lld pixels; the most read is %d on a side and %ld "
                        "pixels in all",
                        path, w, h, HR_IMAGE_READ_MAX_SIDE, (long)HR_IMAGE_READ_MAX_PIXELS);
    return HR_OK;
}

static hr_status read_png(hr_context *ctx, const char *path, FILE *f, hr_image **out)
{
    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_stdio(&png, f))
        return hr_error(ctx, HR_ERROR_IO, "cannot read PNG '%s': %s", path, png.message);
    hr_status st = check_size(ctx, path, png.width, png.height);
    if (st) {
        png_image_free(&png);
        return st;
    }
    png.format = PNG_FORMAT_LINEAR_RGB;
    png_uint_16 *pixels = malloc(PNG_IMAGE_SIZE(png));
    if (!pixels) {
        png_image_free(&png);
        return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
    }
    if (!png_image_finish_read(&png, NULL, pixels, 0, NULL)) {
        free(pixels);
        png_image_free(&png);
        return hr_error(ctx, HR_ERROR_IO, "cannot read PNG '%s': %s", path, png.message);
    }
    hr_image *img;
    if ((st = hr_image_create(ctx, (int32_t)png.width, (int32_t)png.height, 3, &img))) {
        free(pixels);
        return st;
    }
    float *dst = hr_image_data(img);
    for (size_t i = 0; i < (size_t)png.width * png.height * 3; i++) dst[i] = (float)(pixels[i] / 65535.0);
    free(pixels);
    *out = img;
    return HR_OK;
}

static hr_status read_stb(hr_context *ctx, const char *path, FILE *f, const char *format,
                          hr_image **out)
{
    int w, h, n;
    if (!stbi_info_from_file(f, &w, &h, &n))
        return hr_error(ctx, HR_ERROR_IO, "cannot read %s '%s': %s", format, path, stbi_failure_reason());
    hr_status st = check_size(ctx, path, w, h);
    if (st) return st;
    unsigned char *pixels = stbi_load_from_file(f, &w, &h, &n, 3);
    if (!pixels)
        return hr_error(ctx, HR_ERROR_IO, "cannot read %s '%s': %s", format, path, stbi_failure_reason());
    hr_image *img;
    if ((st = hr_image_create(ctx, w, h, 3, &img))) {
        stbi_image_free(pixels);
        return st;
    }
    float decoded[256];
    for (int c = 0; c < 256; c++) decoded[c] = (float)hr_srgb_decode(c / 255.0);
    float *dst = hr_image_data(img);
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++) dst[i] = decoded[pixels[i]];
    stbi_image_free(pixels);
    *out = img;
    return HR_OK;
}

HR_API hr_status hr_image_read(hr_context *ctx, const char *path, hr_image **out)
{
    if (!path || !out) return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_image_read: NULL argument");
    *out = NULL;
    /* A regular file only: a FIFO or a device could block the read, or never
     * end (O_NONBLOCK: opening a FIFO with no writer would wait for one). */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return hr_error(ctx, HR_ERROR_IO, "cannot open image '%s': %s", path, strerror(errno));
    struct stat info;
    const int stat_failed = fstat(fd, &info) != 0;
    if (stat_failed || !S_ISREG(info.st_mode)) {
        const char *why = stat_failed ? strerror(errno) : S_ISDIR(info.st_mode) ? "a directory"
                                                                                 : "not a regular file";
        close(fd);
        return hr_error(ctx, HR_ERROR_IO, "cannot read image '%s': %s", path, why);
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory opening '%s'", path);
    }
    unsigned char magic[8] = {0};
    size_t got = fread(magic, 1, sizeof magic, f);
    hr_status st;
    if (fseek(f, 0, SEEK_SET) != 0)
        st = hr_error(ctx, HR_ERROR_IO, "cannot read image '%s': %s", path, strerror(errno));
    else if (got == 8 && png_sig_cmp(magic, 0, 8) == 0)
        st = read_png(ctx, path, f, out);
    else if (got >= 2 && magic[0] == 'B' && magic[1] == 'M')
        st = read_stb(ctx, path, f, "BMP", out);
    else if (got >= 3 && magic[0] == 0xff && magic[1] == 0xd8 && magic[2] == 0xff)
        st = read_stb(ctx, path, f, "JPEG", out);
    else
        st = hr_error(ctx, HR_ERROR_IO, "image '%s' is not a PNG, BMP or JPEG file", path);
    fclose(f);
    return st;
}
