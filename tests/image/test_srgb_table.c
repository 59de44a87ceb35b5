/* 8-bit sRGB code values come from a table of steps (lib/image/image_srgb.c)
 * instead of a pow call per channel; they must be the formula's, for every
 * float. The table is a step function, so the floats that can disagree are
 * those next to a step: checked are the 512 floats around each of the 255
 * steps, 4 million random floats of [0, 1], the extremes (NaN, infinities,
 * zeros of both signs, subnormals, negatives, 1 and above), and for the
 * other paths (16-bit, linear) the same random floats. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <hitray/image.h>

#include "hr_test.h"
#include "image/image_srgb.h"

static float bits_float(uint32_t b)
{
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

int main(void)
{
    long checked = 0, wrong = 0;
#define SAME(v, srgb, max)                                                           \
    do {                                                                             \
        checked++;                                                                   \
        if (hri_code_value((v), (srgb), (max)) != hri_code_value_by_formula((v), (srgb), (max))) \
            wrong++;                                                                 \
    } while (0)
    /* Around each step: walk the floats where the code changes. */
    uint32_t prev = 0;
    for (uint32_t b = 0; b <= 0x3f800000u; b += 0x400u) {
        uint32_t code = hri_code_value_by_formula(bits_float(b), 1, 255);
        if (code != prev) {
            uint32_t from = b > 0x800u ? b - 0x800u : 0;
            for (uint32_t k = from; k < b + 0x400u; k++) SAME(bits_float(k), 1, 255);
            prev = code;
        }
    }
    uint64_t s = 2024;
    for (int i = 0; i < 4000000; i++) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        float v = (float)((double)(s >> 11) * 0x1p-53);
        SAME(v, 1, 255);
        if (i % 4 == 0) {
            SAME(v, 1, 65535);
            SAME(v, 0, 255);
            SAME(v, 0, 65535);
        }
    }
    const float extremes[] = {NAN, -NAN, INFINITY, -INFINITY, 0.0f, -0.0f, 1e-45f, 1e-38f, -1e-30f,
                              -1.0f, 1.0f, 1.0000001f, 2.0f, 0.0031308f, 0.00313081f, 1e30f};
    for (size_t i = 0; i < sizeof extremes / sizeof *extremes; i++) SAME(extremes[i], 1, 255);
    CHECK_MSG(wrong == 0, "%ld of %ld code values differ from the formula", wrong, checked);
    CHECK(checked > 4000000);
    CHECK(hri_code_value(1.0f, 1, 255) == 255 && hri_code_value(NAN, 1, 255) == 0);
    /* The public encoder (hr_srgb8_encode, what hitray view shows) is the
     * same table: the extremes, and a sweep of [0, 1] a step a code. */
    float sweep[256 + sizeof extremes / sizeof *extremes];
    for (int i = 0; i < 256; i++) sweep[i] = (float)i / 255.0f;
    memcpy(sweep + 256, extremes, sizeof extremes);
    uint8_t codes[sizeof sweep / sizeof *sweep];
    hr_srgb8_encode(sweep, sizeof sweep / sizeof *sweep, codes);
    int differ = 0;
    for (size_t i = 0; i < sizeof sweep / sizeof *sweep; i++)
        differ += codes[i] != hri_code_value_by_formula(sweep[i], 1, 255);
    CHECK_MSG(differ == 0, "%d codes of hr_srgb8_encode differ from the formula", differ);
    /* The writers' row encoder (hri_srgb8_encode_rgb): the same codes, three
     * a pixel, of RGB and of RGBA pixels whose alpha it must skip. */
    enum { PIXELS = sizeof sweep / sizeof *sweep / 3 };
    for (int32_t channels = 3; channels <= 4; channels++) {
        float pixels[PIXELS * 4];
        for (int i = 0; i < PIXELS; i++)
            for (int c = 0; c < channels; c++) pixels[i * channels + c] = c < 3 ? sweep[i * 3 + c] : 0.5f;
        uint8_t rgb[PIXELS * 3 + 1];
        rgb[PIXELS * 3] = 0xa5; /* must stay: three bytes a pixel, no more */
        hri_srgb8_encode_rgb(pixels, PIXELS, channels, rgb);
        int off = 0;
        for (int i = 0; i < PIXELS * 3; i++) off += rgb[i] != hri_code_value_by_formula(sweep[i], 1, 255);
        CHECK_MSG(off == 0, "%d codes of hri_srgb8_encode_rgb (%d channels) differ from the formula", off,
                  (int)channels);
        CHECK(rgb[PIXELS * 3] == 0xa5);
    }
    return hr_test_end();
}
