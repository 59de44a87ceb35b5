/* Linear light to code values (image_srgb.h). */
#include "image/image_srgb.h"

#include <hitray/image.h>

#include <math.h>
#include <pthread.h>
#include <string.h>

static double clamp01(double v)
{
    /* Written so that NaN fails both comparisons' "keep" branch: a NaN pixel
     * (a shape that broke its contract) becomes black, not an undefined
     * integer conversion. */
    if (!(v > 0.0)) return 0.0;
    if (!(v < 1.0)) return 1.0;
    return v;
}

double hri_srgb_encode(double linear)
{
    double v = clamp01(linear);
    if (v == 1.0) return 1.0; /* exactly, not 1.055 - 0.055 */
    if (v <= 0.0031308) return 12.92 * v;
    return 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

double hri_srgb_decode(double encoded)
{
    double v = clamp01(encoded);
    if (v == 1.0) return 1.0;
    if (v <= 0.04045) return v / 12.92;
    return pow((v + 0.055) / 1.055, 2.4);
}

/* The code value by the formula: what the table below reproduces. */
static uint32_t code_by_formula(float linear, int srgb, uint32_t max_code)
{
    double v = srgb ? hri_srgb_encode(linear) : clamp01(linear);
    /* v is in [0, 1], so the sum is in [0.5, max_code + 0.5]: no overflow. */
    return (uint32_t)floor(v * (double)max_code + 0.5);
}

/* 8-bit sRGB, the common case (every PNG and PPM by default), without a pow
 * call per channel: the code is a non-decreasing step function of the
 * float input. step[c - 1] is the smallest float whose code is c or more,
 * found once by bisecting over the floats of [0, 1] in bit order with the
 * formula itself, so the steps give the formula's answer for every float.
 * (Non-decreasing: the formula is monotone, and pow's error, under an ulp
 * of a double, is far below the 2^-25 by which the encoded values of
 * neighbouring floats differ.) To find the steps below a value fast, the
 * floats from the first step to 1 are cut into buckets by their top 16 bits
 * (exponent and 7 bits of mantissa), each knowing the code at its start; a
 * bucket is narrower than the gap between two steps, so at most one step
 * lies past its start. */
#define SRGB8_BUCKET_SHIFT 16
static float srgb8_step[256]; /* [255]: +inf, a step never met */
static uint8_t srgb8_buckets[(0x3f800000u >> SRGB8_BUCKET_SHIFT) + 1]; /* by top bits, to 1.0f */
static uint32_t srgb8_first_bucket;
static pthread_once_t srgb8_once = PTHREAD_ONCE_INIT;

static uint32_t float_bits(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

static float bits_float(uint32_t b)
{
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

static void srgb8_build(void)
{
    for (uint32_t c = 1; c <= 255; c++) {
        /* The smallest bit pattern in (0, 1.0f] whose code is >= c. */
        uint32_t lo = 0, hi = float_bits(1.0f);
        while (lo < hi) {
            uint32_t mid = lo + (hi - lo) / 2;
            if (code_by_formula(bits_float(mid), 1, 255) >= c) hi = mid;
            else lo = mid + 1;
        }
        srgb8_step[c - 1] = bits_float(lo);
    }
    srgb8_step[255] = INFINITY;
    srgb8_first_bucket = float_bits(srgb8_step[0]) >> SRGB8_BUCKET_SHIFT;
    uint32_t code = 0;
    for (uint32_t k = srgb8_first_bucket; k <= float_bits(1.0f) >> SRGB8_BUCKET_SHIFT; k++) {
        const float start = bits_float(k << SRGB8_BUCKET_SHIFT);
        while (code < 255 && srgb8_step[code] <= start) code++;
        srgb8_buckets[k] = (uint8_t)code;
    }
}

/* The code of `linear` once the table is built (srgb8_once): callers that
 * encode many values make sure of the table once, not per value. */
static uint32_t srgb8_code(float linear)
{
    /* NaN, zero and below: 0; 1 and above: 255. */
    if (!(linear > 0.0f)) return 0;
    if (linear >= 1.0f) return 255;
    const uint32_t bucket = float_bits(linear) >> SRGB8_BUCKET_SHIFT;
    if (bucket < srgb8_first_bucket) return 0;
    uint32_t code = srgb8_buckets[bucket];
    while (srgb8_step[code] <= linear) code++;
    return code;
}

uint32_t hri_code_value(float linear, int srgb, uint32_t max_code)
{
    if (srgb && max_code == 255) {
        pthread_once(&srgb8_once, srgb8_build);
        return srgb8_code(linear);
    }
    return code_by_formula(linear, srgb, max_code);
}

uint32_t hri_code_value_by_formula(float linear, int srgb, uint32_t max_code)
{
    return code_by_formula(linear, srgb, max_code);
}

HR_API void hr_srgb8_encode(const float *linear, size_t count, uint8_t *codes)
{
    if (!linear || !codes) return;
    pthread_once(&srgb8_once, srgb8_build);
    for (size_t i = 0; i < count; i++) codes[i] = (uint8_t)srgb8_code(linear[i]);
}

void hri_srgb8_encode_rgb(const float *pixels, size_t count, int32_t channels, uint8_t *codes)
{
    pthread_once(&srgb8_once, srgb8_build);
    for (size_t i = 0; i < count; i++, pixels += channels, codes += 3) {
        codes[0] = (uint8_t)srgb8_code(pixels[0]);
        codes[1] = (uint8_t)srgb8_code(pixels[1]);
        codes[2] = (uint8_t)srgb8_code(pixels[2]);
    }
}
