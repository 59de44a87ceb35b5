/* JPEG, Radiance HDR, BMP and TGA, read back by stb_image (an independent
 * decoder of the same library family; the writers are stb_image_write's):
 * BMP and TGA hold the 8-bit sRGB codes the PNG writer stores (within half
 * a code of the curve); JPEG is within a few codes on a smooth picture at
 * quality 100, and a lower quality gives a smaller file; HDR's RGBE keeps
 * each channel to its 8-bit mantissa under the pixel's largest channel. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>
#include <stb_image.h>

#include "hr_test.h"
#include "image_fixture.h"

static hr_context *ctx;

static void write_as(const hr_image *image, const char *path, int32_t format, int32_t quality)
{
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.format = format;
    o.jpeg_quality = quality;
    CHECK_MSG(hr_image_write(ctx, image, path, &o) == HR_OK, "%s: %s", path, hr_context_last_error(ctx));
}

/* The largest distance, in codes, from the sRGB curve of `image` to the
 * 8-bit RGB file stb_image decodes at `path` (-1 if it cannot be read). */
static double code_error(hr_image *image, const char *path)
{
    int w = 0, h = 0, n = 0;
    unsigned char *codes = stbi_load(path, &w, &h, &n, 3);
    if (!codes || w != hr_image_width(image) || h != hr_image_height(image)) {
        stbi_image_free(codes);
        return -1.0;
    }
    const float *p = hr_image_data(image);
    int32_t channels = hr_image_channels(image);
    double worst = 0.0;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        for (int c = 0; c < 3; c++) {
            double d = fabs(codes[i * 3 + (size_t)c] - 255.0 * fixture_srgb(p[i * (size_t)channels + (size_t)c]));
            if (d > worst) worst = d;
        }
    stbi_image_free(codes);
    return worst;
}

static void check_lossless_8bit(const char *dir)
{
    hr_image *image = fixture_image(ctx, 37, 23, 4, 1); /* alpha dropped, NaN/-1/inf clamped */
    const char *names[] = {"a.bmp", "a.TGA"};
    int32_t formats[] = {HR_FORMAT_BMP, HR_FORMAT_TGA};
    for (int i = 0; i < 2; i++) {
        char path[4096];
        fixture_format(path, sizeof path, "%s", fixture_path(dir, names[i]));
        write_as(image, path, HR_FORMAT_AUTO, 0);
        double err = code_error(image, path);
        /* Rounded to nearest: half a code, and a hair for the float input. */
        CHECK_MSG(err >= 0.0 && err <= 0.5 + 1e-4, "%s: %g codes off", names[i], err);
        CHECK(hr_image_format_from_path(path) == formats[i]);
    }
    hr_image_destroy(image);
}

static void check_jpeg(const char *dir)
{
    hr_image *image = NULL;
    CHECK_OK(hr_image_create(ctx, 64, 48, 3, &image));
    float *p = hr_image_data(image);
    for (int y = 0; y < 48; y++)
        for (int x = 0; x < 64; x++)
            for (int c = 0; c < 3; c++) p[(y * 64 + x) * 3 + c] = (float)(x + y * (c + 1)) / 200.0f;
    char best[4096], worst[4096], plain[4096];
    fixture_format(best, sizeof best, "%s", fixture_path(dir, "q100.jpg"));
    fixture_format(worst, sizeof worst, "%s", fixture_path(dir, "q10.jpeg"));
    fixture_format(plain, sizeof plain, "%s", fixture_path(dir, "default.jpg"));
    write_as(image, best, HR_FORMAT_AUTO, 100);
    write_as(image, worst, HR_FORMAT_AUTO, 10);
    write_as(image, plain, HR_FORMAT_AUTO, 0);
    double err = code_error(image, best);
    /* A smooth ramp at quality 100 (no chroma subsampling): the DCT's
     * quantisation and the YCbCr round trip move a code by a few at most. */
    CHECK_MSG(err >= 0.0 && err <= 4.0, "quality 100: %g codes off", err);
    long size_best = 0, size_worst = 0, size_plain = 0;
    free(fixture_read_file(best, &size_best));
    free(fixture_read_file(worst, &size_worst));
    free(fixture_read_file(plain, &size_plain));
    CHECK_MSG(size_worst < size_plain && size_plain < size_best, "sizes %ld %ld %ld", size_worst, size_plain,
              size_best);
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.jpeg_quality = 101;
    CHECK(hr_image_write(ctx, image, best, &o) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "jpeg_quality") != NULL);
    hr_image_destroy(image);
}

static void check_hdr(const char *dir)
{
    hr_image *image = fixture_image(ctx, 37, 23, 3, 1);
    float *p = hr_image_data(image);
    p[3] = 3e38f;  /* over RGBE's range: capped */
    p[4] = 1e-30f; /* far under the pixel's largest channel: 0 */
    char path[4096];
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "a.hdr"));
    write_as(image, path, HR_FORMAT_AUTO, 0);
    int w = 0, h = 0, n = 0;
    float *back = stbi_loadf(path, &w, &h, &n, 3);
    CHECK(back != NULL && w == 37 && h == 23 && stbi_is_hdr(path));
    for (size_t i = 0; back && i < (size_t)w * (size_t)h; i++) {
        double ref[3], largest = 0.0;
        for (int c = 0; c < 3; c++) {
            double v = p[i * 3 + (size_t)c];
            ref[c] = v > 0.0 ? (v < 1e38 ? v : 1e38) : 0.0; /* NaN, -1, +inf, 3e38 as the writer stores them */
            if (ref[c] > largest) largest = ref[c];
        }
        for (int c = 0; c < 3; c++) {
            /* RGBE truncates each channel to a multiple of 2^(e-8), where
             * 2^(e-1) <= largest < 2^e: under largest/128 low, never high. */
            double got = back[i * 3 + (size_t)c], lost = ref[c] - got;
            CHECK_MSG(lost >= -1e-6 * largest && lost <= largest / 128.0, "pixel %zu channel %d: %g for %g", i, c,
                      got, ref[c]);
        }
    }
    stbi_image_free(back);
    hr_image_destroy(image);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    char dir[4096];
    fixture_format(dir, sizeof dir, "%s", fixture_dir("stb"));
    check_lossless_8bit(dir);
    check_jpeg(dir);
    check_hdr(dir);
    CHECK(fixture_count_entries(dir) == 6); /* one file each, no temporary left */
    hr_context_destroy(ctx);
    return hr_test_end();
}
