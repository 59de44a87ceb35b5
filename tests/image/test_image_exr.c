/* EXR output, read back through OpenEXRCore: 32-bit float samples must come
 * back bit for bit (NaN and infinity included); half samples within half's
 * rounding (relative 2^-11, absolute 2^-25 for half's subnormals). The
 * picture's height is not a multiple of ZIP's 16-line chunks, so the short
 * last chunk is exercised too. */
#include <math.h>
#include <openexr.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "image_fixture.h"

static hr_context *ctx;

static int same_bits(float a, float b) { return memcmp(&a, &b, sizeof a) == 0; }

static int half_close(float got, float want)
{
    if (isnan(want)) return isnan(got);
    if (isinf(want)) return got == want;
    double tol = fmax(fabs((double)want) * ldexp(1.0, -11), ldexp(1.0, -25));
    return fabs((double)got - (double)want) <= tol;
}

static void check_exr(const char *dir, const char *name, int32_t w, int32_t h, int32_t channels, int half)
{
    hr_image *image = fixture_image(ctx, w, h, channels, 1);
    CHECK(image != NULL);
    if (!image) return;
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.exr_half = half;
    char path[4096];
    fixture_format(path, sizeof path, "%s", fixture_path(dir, name));
    CHECK_OK(hr_image_write(ctx, image, path, &o));

    fixture_exr exr;
    CHECK(fixture_read_exr(path, &exr) == 0);
    if (exr.samples) {
        CHECK(exr.width == w && exr.height == h);
        CHECK(exr.channels == channels);
        CHECK(exr.pixel_type == (half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT));
        CHECK(exr.compression == EXR_COMPRESSION_ZIP);
        const float *src = hr_image_data(image);
        size_t n = (size_t)w * (size_t)h * (size_t)channels;
        int bad = 0;
        for (size_t i = 0; i < n; i++) {
            int ok = half ? half_close(exr.samples[i], src[i]) : same_bits(exr.samples[i], src[i]);
            if (!ok && bad++ < 5)
                hr_test_fail(__FILE__, __LINE__, "%s sample %zu: wrote %.9g, read %.9g", name, i,
                             (double)src[i], (double)exr.samples[i]);
        }
        hr_test_checks++;
        free(exr.samples);
    }
    hr_image_destroy(image);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    char dir[4096];
    fixture_format(dir, sizeof dir, "%s", fixture_dir("exr"));
    check_exr(dir, "float_rgb.exr", 37, 21, 3, 0);
    check_exr(dir, "float_rgba.exr", 37, 21, 4, 0);
    check_exr(dir, "half_rgb.exr", 37, 21, 3, 1);
    check_exr(dir, "half_rgba.exr", 19, 40, 4, 1);
    check_exr(dir, "one_pixel.EXR", 1, 1, 3, 0);
    check_exr(dir, "tall.exr", 3, 100, 3, 0);
    hr_context_destroy(ctx);
    return hr_test_end();
}
