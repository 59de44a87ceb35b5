/* PNG output, read back with libpng: 8 and 16 bits, sRGB and linear, RGB and
 * RGBA, and the clamping of NaN, negative and too-bright samples. Every code
 * value must lie within half a code of the reference curve computed in
 * double, which is what rounding to nearest promises. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "image_fixture.h"

static hr_context *ctx;

/* Write `image` as PNG with the given options and check every sample. */
static void check_png(const char *dir, const char *name, int32_t channels, int bits, int linear)
{
    hr_image *image = fixture_image(ctx, 37, 21, channels, 1);
    CHECK(image != NULL);
    if (!image) return;
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.png_bits = bits;
    o.png_linear = linear;
    char path[4096];
    fixture_format(path, sizeof path, "%s", fixture_path(dir, name));
    CHECK_OK(hr_image_write(ctx, image, path, &o));

    fixture_png png;
    CHECK(fixture_read_png(path, &png) == 0);
    if (!png.samples) {
        hr_image_destroy(image);
        return;
    }
    CHECK(png.width == 37 && png.height == 21);
    CHECK(png.channels == channels);
    CHECK(png.bits == bits);
    /* sRGB-encoded files say so; linear ones carry gAMA 1.0 and no sRGB. */
    CHECK(png.has_srgb == !linear);
    CHECK(png.has_gamma);
    if (linear) CHECK_NEAR(png.gamma, 1.0, 1e-5);

    const float *src = hr_image_data(image);
    double max_code = bits == 16 ? 65535.0 : 255.0;
    size_t n = (size_t)37 * 21 * (size_t)channels;
    int bad = 0;
    for (size_t i = 0; i < n; i++) {
        int is_alpha = channels == 4 && i % 4 == 3;
        double v = src[i];
        double clamped = isnan(v) || v <= 0 ? 0.0 : v >= 1 ? 1.0 : v;
        double want = (linear || is_alpha ? clamped : fixture_srgb(v)) * max_code;
        if (!(fabs((double)png.samples[i] - want) <= 0.5)) {
            if (bad++ < 5)
                hr_test_fail(__FILE__, __LINE__, "%s sample %zu: linear %g gave %u, want %.3f", name, i, v,
                             (unsigned)png.samples[i], want);
        }
    }
    hr_test_checks++;
    /* The special first pixel: NaN and -1 are black, +inf is full. */
    CHECK(png.samples[0] == 0);
    CHECK(png.samples[1] == 0);
    CHECK(png.samples[2] == (uint16_t)max_code);
    free(png.samples);
    hr_image_destroy(image);
}

/* The exact curve at a few hand-computed points (8-bit sRGB). */
static void check_known_codes(const char *dir)
{
    hr_image *image = NULL;
    CHECK_OK(hr_image_create(ctx, 6, 1, 3, &image));
    float *p = hr_image_data(image);
    const float linear[6] = {0.0f, 0.0031308f, 0.18f, 0.5f, 1.0f, 0.05f};
    /* 0.0031308 -> 0.04045 -> 10.31; 0.18 -> 0.4614 -> 117.65; 0.5 ->
     * 0.7354 -> 187.52; 0.05 -> 0.2478 -> 63.19. */
    for (int i = 0; i < 6; i++) p[3 * i] = p[3 * i + 1] = p[3 * i + 2] = linear[i];
    const char *path = fixture_path(dir, "known.png");
    CHECK_OK(hr_image_write(ctx, image, path, NULL));
    fixture_png png;
    if (fixture_read_png(path, &png) == 0) {
        const uint16_t want[6] = {0, 10, 118, 188, 255, 63};
        for (int i = 0; i < 6; i++)
            CHECK_MSG(png.samples[3 * i] == want[i], "linear %g: code %u, want %u", (double)linear[i],
                      (unsigned)png.samples[3 * i], (unsigned)want[i]);
        free(png.samples);
    } else {
        CHECK(0);
    }
    hr_image_destroy(image);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    const char *shared = fixture_dir("png");
    char dir[4096];
    fixture_format(dir, sizeof dir, "%s", shared);
    check_png(dir, "srgb8.png", 3, 8, 0);
    check_png(dir, "srgb8_rgba.png", 4, 8, 0);
    check_png(dir, "srgb16.png", 3, 16, 0);
    check_png(dir, "srgb16_rgba.png", 4, 16, 0);
    check_png(dir, "linear8.png", 3, 8, 1);
    check_png(dir, "linear16.png", 3, 16, 1);
    check_png(dir, "UPPER.PNG", 3, 8, 0);
    check_known_codes(dir);
    hr_context_destroy(ctx);
    return hr_test_end();
}
