/* Image test fixtures (image_fixture.h). The readers use libpng and
 * OpenEXRCore directly, not anything of lib/, so a writer bug cannot hide
 * behind a matching reader bug. */
#define _POSIX_C_SOURCE 200809L
#include "image_fixture.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <openexr.h>
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

hr_image *fixture_image(hr_context *ctx, int32_t width, int32_t height, int32_t channels, int special)
{
    hr_image *image = NULL;
    if (hr_image_create(ctx, width, height, channels, &image) != HR_OK) return NULL;
    float *p = hr_image_data(image);
    size_t n = (size_t)width * (size_t)height * (size_t)channels;
    static const float edges[] = {0.0f, 1.0f, 0.0031308f, 1e-6f, 7.5f, 0.5f, 0.04045f, 0.999f};
    for (size_t i = 0; i < n; i++) {
        /* 0.0137 is not a multiple of 1/255 or 1/65535, so samples land all
         * over the code-value grid, including near rounding midpoints. */
        p[i] = -0.25f + 0.0137f * (float)(i % 128u);
        if (i % 97u < sizeof edges / sizeof edges[0]) p[i] = edges[i % 97u];
    }
    if (special && n >= 3) {
        p[0] = NAN;
        p[1] = -1.0f;
        p[2] = INFINITY;
    }
    return image;
}

double fixture_srgb(double v)
{
    if (isnan(v) || v <= 0.0) return 0.0;
    if (v >= 1.0) return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

void fixture_format(char *buf, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, size, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= size) {
        fprintf(stderr, "fixture: path too long: %s...\n", buf);
        exit(2);
    }
}

/* Remove the files of a scratch directory left by an earlier run. */
static void empty_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        char path[4096];
        fixture_format(path, sizeof path, "%s/%s", dir, e->d_name);
        if (unlink(path) != 0) rmdir(path);
    }
    closedir(d);
}

const char *fixture_dir(const char *name)
{
    static char dir[4096];
    mkdir(HR_TEST_BINARY_DIR "/tests", 0777);
    mkdir(HR_TEST_BINARY_DIR "/tests/scratch", 0777);
    fixture_format(dir, sizeof dir, "%s/tests/scratch/%s", HR_TEST_BINARY_DIR, name);
    mkdir(dir, 0777);
    empty_dir(dir);
    return dir;
}

const char *fixture_path(const char *dir, const char *file)
{
    static char path[4096];
    fixture_format(path, sizeof path, "%s/%s", dir, file);
    return path;
}

int fixture_count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

unsigned char *fixture_read_file(const char *path, long *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *data = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n >= 0 && fseek(f, 0, SEEK_SET) == 0 && (data = malloc((size_t)n + 1)) &&
            fread(data, 1, (size_t)n, f) != (size_t)n) {
            free(data);
            data = NULL;
        }
        *size = n;
    }
    fclose(f);
    return data;
}

/* Everything the PNG reader allocates, kept apart from setjmp's frame. */
typedef struct png_reading {
    FILE *file;
    png_structp png;
    png_infop info;
    png_bytep row;
} png_reading;

static int read_png_rows(png_reading *r, fixture_png *out)
{
    if (setjmp(png_jmpbuf(r->png))) return -1;
    png_init_io(r->png, r->file);
    png_read_info(r->png, r->info);
    out->width = (int32_t)png_get_image_width(r->png, r->info);
    out->height = (int32_t)png_get_image_height(r->png, r->info);
    out->bits = png_get_bit_depth(r->png, r->info);
    out->channels = png_get_channels(r->png, r->info);
    int intent;
    out->has_srgb = png_get_sRGB(r->png, r->info, &intent) != 0;
    out->has_gamma = png_get_gAMA(r->png, r->info, &out->gamma) != 0;
    size_t row_bytes = png_get_rowbytes(r->png, r->info);
    size_t per_row = (size_t)out->width * (size_t)out->channels;
    r->row = malloc(row_bytes);
    out->samples = malloc(per_row * (size_t)out->height * sizeof *out->samples);
    if (!r->row || !out->samples) return -1;
    for (int32_t y = 0; y < out->height; y++) {
        png_read_row(r->png, r->row, NULL);
        uint16_t *dst = out->samples + (size_t)y * per_row;
        for (size_t i = 0; i < per_row; i++)
            dst[i] = out->bits == 16 ? (uint16_t)(r->row[2 * i] << 8 | r->row[2 * i + 1]) : r->row[i];
    }
    png_read_end(r->png, NULL);
    return 0;
}

int fixture_read_png(const char *path, fixture_png *out)
{
    memset(out, 0, sizeof *out);
    png_reading r = {0};
    r.file = fopen(path, "rb");
    if (!r.file) {
        fprintf(stderr, "cannot open %s: %s\n", path, strerror(errno));
        return -1;
    }
    r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    r.info = r.png ? png_create_info_struct(r.png) : NULL;
    int rc = r.info ? read_png_rows(&r, out) : -1;
    png_destroy_read_struct(r.png ? &r.png : NULL, r.info ? &r.info : NULL, NULL);
    free(r.row);
    fclose(r.file);
    if (rc != 0) {
        free(out->samples);
        out->samples = NULL;
        fprintf(stderr, "libpng could not read %s\n", path);
    }
    return rc;
}

static int channel_offset(const char *name)
{
    static const char *const names[4] = {"R", "G", "B", "A"};
    for (int i = 0; i < 4; i++)
        if (!strcmp(name, names[i])) return i;
    return -1;
}

/* IEEE half to float, written out here so the check does not trust the
 * conversion of the library under test's dependency either. */
static float half_to_float(uint16_t h)
{
    int sign = h >> 15, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
    float magnitude;
    if (exponent == 0x1f) magnitude = mantissa ? NAN : INFINITY;
    else if (exponent == 0) magnitude = ldexpf((float)mantissa, -24); /* subnormal */
    else magnitude = ldexpf((float)(mantissa | 0x400), exponent - 25);
    return sign ? -magnitude : magnitude;
}

/* Each chunk is decoded channel by channel into a planar buffer of the
 * file's own sample type, then converted and interleaved here. (OpenEXRCore
 * 3.1.5's fast path for four half channels into interleaved floats puts them
 * in the wrong order; planar, unconverted decoding avoids it.) */
static exr_result_t read_exr_chunks(exr_context_t exr, fixture_exr *out)
{
    int32_t lines = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(exr, 0, &lines);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    int started = 0;
    size_t plane_size = (size_t)out->width * (size_t)(lines > 0 ? lines : 1) * 4;
    unsigned char *planes[4] = {NULL, NULL, NULL, NULL};
    for (int c = 0; c < out->channels && c < 4; c++)
        if (!(planes[c] = malloc(plane_size))) rv = EXR_ERR_OUT_OF_MEMORY;
    for (int32_t y = 0; rv == EXR_ERR_SUCCESS && y < out->height; y += lines) {
        exr_chunk_info_t chunk;
        rv = exr_read_scanline_chunk_info(exr, 0, y, &chunk);
        if (rv != EXR_ERR_SUCCESS) break;
        rv = started ? exr_decoding_update(exr, 0, &chunk, &dec) : exr_decoding_initialize(exr, 0, &chunk, &dec);
        if (rv != EXR_ERR_SUCCESS) break;
        started = 1;
        if (dec.channel_count != out->channels || out->channels > 4) {
            rv = EXR_ERR_INVALID_ATTR;
            break;
        }
        for (int c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            ch->decode_to_ptr = planes[c];
            ch->user_pixel_stride = ch->bytes_per_element;
            ch->user_line_stride = ch->bytes_per_element * chunk.width;
        }
        rv = exr_decoding_choose_default_routines(exr, 0, &dec);
        if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(exr, 0, &dec);
        for (int c = 0; rv == EXR_ERR_SUCCESS && c < dec.channel_count; c++) {
            const exr_coding_channel_info_t *ch = &dec.channels[c];
            int offset = channel_offset(ch->channel_name);
            if (offset < 0 || offset >= out->channels) {
                rv = EXR_ERR_INVALID_ATTR;
                break;
            }
            for (int32_t i = 0; i < chunk.width * chunk.height; i++) {
                float v;
                if (ch->data_type == EXR_PIXEL_HALF) {
                    uint16_t h;
                    memcpy(&h, planes[c] + 2 * (size_t)i, 2);
                    v = half_to_float(h);
                } else {
                    memcpy(&v, planes[c] + 4 * (size_t)i, 4);
                }
                size_t pixel = (size_t)chunk.start_y * (size_t)out->width + (size_t)i;
                out->samples[pixel * (size_t)out->channels + (size_t)offset] = v;
            }
        }
    }
    if (started) exr_decoding_destroy(exr, &dec);
    for (int c = 0; c < 4; c++) free(planes[c]);
    return rv;
}

int fixture_read_exr(const char *path, fixture_exr *out)
{
    memset(out, 0, sizeof *out);
    exr_context_t exr = NULL;
    exr_result_t rv = exr_start_read(&exr, path, NULL);
    const exr_attr_chlist_t *chlist = NULL;
    exr_attr_box2i_t window;
    exr_compression_t compression = EXR_COMPRESSION_LAST_TYPE;
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_channels(exr, 0, &chlist);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_data_window(exr, 0, &window);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_compression(exr, 0, &compression);
    if (rv == EXR_ERR_SUCCESS) {
        out->width = window.max.x - window.min.x + 1;
        out->height = window.max.y - window.min.y + 1;
        out->channels = chlist->num_channels;
        out->pixel_type = (int)chlist->entries[0].pixel_type;
        for (int c = 1; c < chlist->num_channels; c++)
            if ((int)chlist->entries[c].pixel_type != out->pixel_type) out->pixel_type = -1;
        out->compression = (int)compression;
        out->samples = calloc((size_t)out->width * (size_t)out->height * (size_t)out->channels, sizeof(float));
        rv = out->samples ? read_exr_chunks(exr, out) : EXR_ERR_OUT_OF_MEMORY;
    }
    if (exr) exr_finish(&exr);
    if (rv != EXR_ERR_SUCCESS) {
        fprintf(stderr, "OpenEXRCore could not read %s: %s\n", path, exr_get_default_error_message(rv));
        free(out->samples);
        out->samples = NULL;
        return -1;
    }
    return 0;
}
