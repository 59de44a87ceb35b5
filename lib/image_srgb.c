/* Linear light to code values (image_srgb.h). */
#include "image_srgb.h"

#include <math.h>

static double clamp01(double v)
{
    /* Written so that NaN fails both comparisons' "keep" branch: a NaN pixel
     * (a shape that broke its contract) becomes black, not an undefined
     * integer conversion. */
    if (!(v > 0.0)) return 0.0;
    if (!(v < 1.0)) return 1.0;
    return v;
}

double hr_srgb_encode(double linear)
{
    double v = clamp01(linear);
    if (v == 1.0) return 1.0; /* exactly, not 1.055 - 0.055 */
    if (v <= 0.0031308) return 12.92 * v;
    return 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

uint32_t hr_code_value(float linear, int srgb, uint32_t max_code)
{
    double v = srgb ? hr_srgb_encode(linear) : clamp01(linear);
    /* v is in [0, 1], so the sum is in [0.5, max_code + 0.5]: no overflow. */
    return (uint32_t)floor(v * (double)max_code + 0.5);
}
