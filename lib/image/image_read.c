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

#include <limits.h>

#include "util/errors.h"
#include "image/image_srgb.h"

static hr_status check_size(hr_context *ctx, const char *path, long long w, long long h)
{
    if (w < 1 || h < 1 || w > HR_IMAGE_READ_MAX_SIDE || h > HR_IMAGE_READ_MAX_SIDE ||
        w * h > HR_IMAGE_READ_MAX_PIXELS)
        return hri_error(ctx, HR_ERROR_UNSUPPORTED,
                        "image '%s' is %lld x %lld pixels; the most read is %d on a side and %ld "
                        "pixels in all",
                        path, w, h, HR_IMAGE_READ_MAX_SIDE, (long)HR_IMAGE_READ_MAX_PIXELS);
    return HR_OK;
}

static uint32_t be32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

/* Every chunk's declared length against the bytes left in the file, up to
 * IEND, and what IHDR and PLTE say of the pixels: libpng allocates a chunk's length before reading it, so a 45-byte
 * file declaring 2^31-1 bytes would cost 2 GB before its read fails. */
typedef struct png_layout {
    png_uint_32 width, height;
    int color_type;
    int palette_entries; /* -1 without a PLTE chunk */
} png_layout;

static hr_status check_png_chunks(hr_context *ctx, const char *path, FILE *f, long long size,
                                  png_layout *layout)
{
    long long at = 8;
    for (;;) {
        unsigned char head[8];
        if (fseek(f, (long)at, SEEK_SET) != 0 || fread(head, 1, 8, f) != 8)
            return hri_error(ctx, HR_ERROR_IO, "cannot read PNG '%s': cut at byte %lld, before its IEND chunk",
                            path, size < at ? size : at);
        const long long length = be32(head);
        if (length > size - at - 12)
            return hri_error(ctx, HR_ERROR_IO,
                            "cannot read PNG '%s': the chunk at byte %lld declares %lld bytes, but only "
                            "%lld follow it",
                            path, at, length, size - at - 12 > 0 ? size - at - 12 : 0);
        if (memcmp(head + 4, "IEND", 4) == 0) break;
        if (memcmp(head + 4, "PLTE", 4) == 0) layout->palette_entries = (int)(length / 3);
        unsigned char ihdr[10];
        if (memcmp(head + 4, "IHDR", 4) == 0 && length >= 10 && fread(ihdr, 1, 10, f) == 10) {
            layout->width = be32(ihdr), layout->height = be32(ihdr + 4);
            layout->color_type = ihdr[9];
        }
        at += 12 + length;
    }
    if (fseek(f, 0, SEEK_SET) == 0) return HR_OK;
    return hri_error(ctx, HR_ERROR_IO, "cannot read image '%s': %s", path, strerror(errno));
}

static void on_palette_error(png_structp png, png_const_charp message)
{
    (void)message; /* the simplified read after this pass reports it */
    png_longjmp(png, 1);
}

static void on_palette_warning(png_structp png, png_const_charp message)
{
    (void)png, (void)message;
}

/* A palette PNG's indices into rows, one byte each; 0 where the file
 * cannot be read (the simplified read then says why). libpng's simplified
 * read turns an index beyond the palette into black without an error, so
 * a palette file's indices are read raw first. Everything freed after the
 * longjmp is set before setjmp. */
static int read_palette_indices(FILE *f, png_uint_32 w, png_uint_32 h, png_bytep rows)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, on_palette_error, on_palette_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    png_bytepp row = rows ? malloc(h * sizeof *row) : NULL;
    volatile int done = 0;
    if (png && info && row && !setjmp(png_jmpbuf(png))) {
        for (png_uint_32 y = 0; y < h; y++) row[y] = rows + (size_t)y * w;
        png_init_io(png, f);
        png_read_info(png, info);
        png_set_packing(png);
        png_set_interlace_handling(png);
        png_read_update_info(png, info);
        if (png_get_rowbytes(png, info) == w) {
            png_read_image(png, row);
            done = 1;
        }
    }
    png_destroy_read_struct(png ? &png : NULL, info ? &info : NULL, NULL);
    free(row);
    return done;
}

static hr_status check_palette_indices(hr_context *ctx, const char *path, FILE *f, const png_layout *png)
{
    const int entries = png->palette_entries;
    png_bytep rows = malloc((size_t)png->width * png->height);
    if (!rows) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
    int max = -1;
    if (read_palette_indices(f, png->width, png->height, rows))
        for (size_t i = 0; i < (size_t)png->width * png->height; i++) max = rows[i] > max ? rows[i] : max;
    free(rows);
    if (fseek(f, 0, SEEK_SET) != 0)
        return hri_error(ctx, HR_ERROR_IO, "cannot read image '%s': %s", path, strerror(errno));
    if (max >= entries)
        return hri_error(ctx, HR_ERROR_IO,
                        "cannot read PNG '%s': a pixel is palette index %d, but the palette has %d %s",
                        path, max, entries, entries == 1 ? "entry" : "entries");
    return HR_OK;
}

static hr_status read_png(hr_context *ctx, const char *path, FILE *f, long long size, hr_image **out)
{
    png_layout layout = {0, 0, -1, -1};
    hr_status st = check_png_chunks(ctx, path, f, size, &layout);
    if (st) return st;
    if (layout.color_type == PNG_COLOR_TYPE_PALETTE && layout.palette_entries >= 0 &&
        check_size(ctx, path, layout.width, layout.height) == HR_OK &&
        (st = check_palette_indices(ctx, path, f, &layout)))
        return st;
    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_stdio(&png, f))
        return hri_error(ctx, HR_ERROR_IO, "cannot read PNG '%s': %s", path, png.message);
    st = check_size(ctx, path, png.width, png.height);
    if (st) {
        png_image_free(&png);
        return st;
    }
    png.format = PNG_FORMAT_LINEAR_RGB;
    png_uint_16 *pixels = malloc(PNG_IMAGE_SIZE(png));
    if (!pixels) {
        png_image_free(&png);
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
    }
    if (!png_image_finish_read(&png, NULL, pixels, 0, NULL)) {
        free(pixels);
        png_image_free(&png);
        return hri_error(ctx, HR_ERROR_IO, "cannot read PNG '%s': %s", path, png.message);
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

/* stb_image reads through these, so the reader learns when stb asks for
 * bytes past the end: stb fills what is missing with zeros and reports
 * success, so a cut file would read as a black image. */
typedef struct stb_source {
    FILE *f;
    long long size;
    int past_end;
} stb_source;

static int stb_read(void *user, char *data, int n)
{
    stb_source *src = user;
    size_t got = n > 0 ? fread(data, 1, (size_t)n, src->f) : 0;
    if (n > 0 && got == 0) src->past_end = 1;
    return (int)got;
}

static void stb_skip(void *user, int n)
{
    stb_source *src = user;
    long at = ftell(src->f);
    if (at < 0 || (long long)at + n > src->size) src->past_end = 1;
    if (fseek(src->f, n, SEEK_CUR) != 0) src->past_end = 1;
}

static int stb_eof(void *user)
{
    stb_source *src = user;
    return feof(src->f) || ftell(src->f) >= src->size;
}

static const stbi_io_callbacks stb_io = {stb_read, stb_skip, stb_eof};

static uint32_t le32(const unsigned char *b)
{
    return (uint32_t)b[3] << 24 | (uint32_t)b[2] << 16 | (uint32_t)b[1] << 8 | b[0];
}

/* The bytes an uncompressed BMP's header promises, against the file's
 * size: its pixel offset plus |height| rows of width x bits, each padded
 * to 4 bytes. (stb reads no RLE BMP; it refuses those itself.) */
static hr_status check_bmp_size(hr_context *ctx, const char *path, FILE *f, long long size)
{
    unsigned char h[32] = {0};
    if (fread(h, 1, sizeof h, f) != sizeof h || fseek(f, 0, SEEK_SET) != 0)
        return hri_error(ctx, HR_ERROR_IO, "cannot read BMP '%s': its header is cut (%lld bytes)", path, size);
    const long long offset = le32(h + 10), header = le32(h + 14);
    long long w, rows, bits;
    if (header == 12) {
        w = h[18] | h[19] << 8, rows = h[20] | h[21] << 8, bits = h[24] | h[25] << 8;
    } else {
        w = (int32_t)le32(h + 18), rows = llabs((long long)(int32_t)le32(h + 22)), bits = h[28] | h[29] << 8;
    }
    if (w < 1 || rows < 1 || bits < 1) return HR_OK; /* stb or check_size names these */
    const long long need = offset + (w * bits + 31) / 32 * 4 * rows;
    if (need > size)
        return hri_error(ctx, HR_ERROR_IO,
                        "cannot read BMP '%s': its header promises %lld x %lld pixels of %lld bits at "
                        "byte %lld, %lld bytes in all, but the file has %lld",
                        path, w, rows, bits, offset, need, size);
    return HR_OK;
}

/* A Huffman-coded JPEG (all stb reads) codes every 8x8 block of its
 * full-resolution component in at least one bit: its DC difference's code
 * is a bit at the least, in a baseline scan or a progressive file's first
 * DC scan. A file smaller than that cannot hold the size it declares. */
static hr_status check_jpeg_size(hr_context *ctx, const char *path, long long w, long long h, long long size)
{
    const long long need = ((w + 7) / 8) * ((h + 7) / 8) / 8;
    if (need > size)
        return hri_error(ctx, HR_ERROR_IO,
                        "cannot read JPEG '%s': %lld x %lld pixels need at least %lld bytes of coded data, "
                        "but the file has %lld",
                        path, w, h, need, size);
    return HR_OK;
}

static hr_status read_stb(hr_context *ctx, const char *path, FILE *f, long long size, const char *format,
                          hr_image **out)
{
    const int is_bmp = format[0] == 'B';
    hr_status st = is_bmp ? check_bmp_size(ctx, path, f, size) : HR_OK;
    if (st) return st;
    stb_source src = {f, size, 0};
    int w, h, n;
    if (!stbi_info_from_callbacks(&stb_io, &src, &w, &h, &n))
        return hri_error(ctx, HR_ERROR_IO, "cannot read %s '%s': %s", format, path, stbi_failure_reason());
    /* A top-down BMP gives its height negative here (stb's load flips it). */
    if ((st = check_size(ctx, path, w, h == INT_MIN ? 0 : abs(h)))) return st;
    if (!is_bmp && (st = check_jpeg_size(ctx, path, w, abs(h), size))) return st;
    if (fseek(f, 0, SEEK_SET) != 0)
        return hri_error(ctx, HR_ERROR_IO, "cannot read image '%s': %s", path, strerror(errno));
    clearerr(f);
    src.past_end = 0;
    unsigned char *pixels = stbi_load_from_callbacks(&stb_io, &src, &w, &h, &n, 3);
    if (!pixels)
        return hri_error(ctx, HR_ERROR_IO, "cannot read %s '%s': %s", format, path, stbi_failure_reason());
    if (src.past_end) {
        stbi_image_free(pixels);
        return hri_error(ctx, HR_ERROR_IO, "cannot read %s '%s': the file ends before its pixel data does "
                        "(%lld bytes)", format, path, size);
    }
    hr_image *img;
    if ((st = hr_image_create(ctx, w, h, 3, &img))) {
        stbi_image_free(pixels);
        return st;
    }
    float decoded[256];
    for (int c = 0; c < 256; c++) decoded[c] = (float)hri_srgb_decode(c / 255.0);
    float *dst = hr_image_data(img);
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++) dst[i] = decoded[pixels[i]];
    stbi_image_free(pixels);
    *out = img;
    return HR_OK;
}

HR_API hr_status hr_image_read(hr_context *ctx, const char *path, hr_image **out)
{
    if (!path || !out) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_image_read: NULL argument");
    *out = NULL;
    /* A regular file only: a FIFO or a device could block the read, or never
     * end (O_NONBLOCK: opening a FIFO with no writer would wait for one). */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return hri_error(ctx, HR_ERROR_IO, "cannot open image '%s': %s", path, strerror(errno));
    struct stat info;
    const int stat_failed = fstat(fd, &info) != 0;
    if (stat_failed || !S_ISREG(info.st_mode)) {
        const char *why = stat_failed ? strerror(errno) : S_ISDIR(info.st_mode) ? "a directory"
                                                                                 : "not a regular file";
        close(fd);
        return hri_error(ctx, HR_ERROR_IO, "cannot read image '%s': %s", path, why);
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory opening '%s'", path);
    }
    unsigned char magic[8] = {0};
    size_t got = fread(magic, 1, sizeof magic, f);
    hr_status st;
    if (fseek(f, 0, SEEK_SET) != 0)
        st = hri_error(ctx, HR_ERROR_IO, "cannot read image '%s': %s", path, strerror(errno));
    else if (got == 8 && png_sig_cmp(magic, 0, 8) == 0)
        st = read_png(ctx, path, f, (long long)info.st_size, out);
    else if (got >= 2 && magic[0] == 'B' && magic[1] == 'M')
        st = read_stb(ctx, path, f, (long long)info.st_size, "BMP", out);
    else if (got >= 3 && magic[0] == 0xff && magic[1] == 0xd8 && magic[2] == 0xff)
        st = read_stb(ctx, path, f, (long long)info.st_size, "JPEG", out);
    else
        st = hri_error(ctx, HR_ERROR_IO, "image '%s' is not a PNG, BMP or JPEG file", path);
    fclose(f);
    return st;
}
