/* PPM and PFM output, parsed by hand: the header each format requires, PPM's
 * 8-bit sRGB samples (within half a code of the reference, NaN and negative
 * clamped to 0), and PFM's little-endian floats, bit for bit, bottom row
 * first. Alpha is dropped by both. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "image_fixture.h"

static hr_context *ctx;

/* Parse "<magic>\n<w> <h>\n<third>\n" and return the offset of the data. */
static long parse_header(const unsigned char *data, long size, const char *magic, int *w, int *h, char *third,
                         size_t third_size)
{
    char header[128];
    long n = size < (long)sizeof header - 1 ? size : (long)sizeof header - 1;
    memcpy(header, data, (size_t)n);
    header[n] = '\0';
    char m[3] = {0};
    char t[32] = {0};
    int used = 0;
    if (sscanf(header, "%2s %d %d %31s%n", m, w, h, t, &used) != 4 || strcmp(m, magic) != 0) return -1;
    if (header[used] != '\n') return -1; /* exactly one whitespace byte before the data */
    snprintf(third, third_size, "%s", t);
    return used + 1;
}

static void check_ppm(const char *dir, int32_t channels)
{
    const int32_t w = 23, h = 9;
    hr_image *image = fixture_image(ctx, w, h, channels, 1);
    const char *path = fixture_path(dir, channels == 4 ? "rgba.ppm" : "rgb.ppm");
    CHECK_OK(hr_image_write(ctx, image, path, NULL));
    long size = 0;
    unsigned char *data = fixture_read_file(path, &size);
    CHECK(data != NULL);
    if (data) {
        int fw, fh;
        char maxval[32];
        long at = parse_header(data, size, "P6", &fw, &fh, maxval, sizeof maxval);
        CHECK(at > 0);
        CHECK(fw == w && fh == h);
        CHECK(strcmp(maxval, "255") == 0);
        CHECK(size == at + (long)w * h * 3);
        const float *src = hr_image_data(image);
        int bad = 0;
        for (long i = 0; at > 0 && i < (long)w * h * 3 && at + i < size; i++) {
            long pixel = i / 3, c = i % 3;
            double want = fixture_srgb(src[pixel * channels + c]) * 255.0;
            if (!(fabs(data[at + i] - want) <= 0.5) && bad++ < 5)
                hr_test_fail(__FILE__, __LINE__, "ppm sample %ld: %u, want %.3f", i, data[at + i], want);
        }
        hr_test_checks++;
        CHECK(data[at] == 0 && data[at + 1] == 0 && data[at + 2] == 255); /* NaN, -1, +inf */
        /* hr_srgb8_encode gives the file's own bytes, pixel by pixel. */
        int differ = 0;
        for (long p = 0; at > 0 && p < (long)w * h && at + 3 * p + 2 < size; p++) {
            uint8_t codes[3];
            hr_srgb8_encode(src + p * channels, 3, codes);
            differ += memcmp(codes, data + at + 3 * p, 3) != 0;
        }
        CHECK_MSG(differ == 0, "%d of %d pixels: hr_srgb8_encode differs from the PPM", differ, w * h);
        free(data);
    }
    hr_image_destroy(image);
}

static float load_le32(const unsigned char *p)
{
    uint32_t bits = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static void check_pfm(const char *dir, int32_t channels)
{
    const int32_t w = 17, h = 6;
    hr_image *image = fixture_image(ctx, w, h, channels, 1);
    const char *path = fixture_path(dir, channels == 4 ? "rgba.pfm" : "rgb.pfm");
    CHECK_OK(hr_image_write(ctx, image, path, NULL));
    long size = 0;
    unsigned char *data = fixture_read_file(path, &size);
    CHECK(data != NULL);
    if (data) {
        int fw, fh;
        char scale[32];
        long at = parse_header(data, size, "PF", &fw, &fh, scale, sizeof scale);
        CHECK(at > 0);
        CHECK(fw == w && fh == h);
        CHECK(strtod(scale, NULL) == -1.0); /* negative: little-endian */
        CHECK(size == at + (long)w * h * 3 * 4);
        const float *src = hr_image_data(image);
        int bad = 0;
        for (int32_t row = 0; at > 0 && size == at + (long)w * h * 12 && row < h; row++) {
            /* File row `row` counts from the bottom of the picture. */
            int32_t y = h - 1 - row;
            for (int32_t x = 0; x < w; x++)
                for (int c = 0; c < 3; c++) {
                    float got = load_le32(data + at + ((long)row * w + x) * 12 + c * 4);
                    float want = src[((size_t)y * (size_t)w + (size_t)x) * (size_t)channels + (size_t)c];
                    if (memcmp(&got, &want, sizeof got) != 0 && bad++ < 5)
                        hr_test_fail(__FILE__, __LINE__, "pfm (%d,%d,%d): %.9g, want %.9g", (int)x, (int)y, c,
                                     (double)got, (double)want);
                }
        }
        hr_test_checks++;
        free(data);
    }
    hr_image_destroy(image);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    char dir[4096];
    fixture_format(dir, sizeof dir, "%s", fixture_dir("pnm"));
    check_ppm(dir, 3);
    check_ppm(dir, 4);
    check_pfm(dir, 3);
    check_pfm(dir, 4);
    hr_context_destroy(ctx);
    return hr_test_end();
}
