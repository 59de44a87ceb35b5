/* Internal: turning linear light into integer code values for 8- and 16-bit
 * files (PNG, PPM). */
#ifndef HITRAY_LIB_IMAGE_SRGB_H
#define HITRAY_LIB_IMAGE_SRGB_H

#include <stddef.h>
#include <stdint.h>

/* The sRGB transfer function (IEC 61966-2-1), the exact piecewise curve,
 * of a linear value clamped to [0, 1]; NaN counts as 0. */
double hri_srgb_encode(double linear);

/* The inverse: the linear value of an sRGB-encoded value in [0, 1]. */
double hri_srgb_decode(double encoded);

/* `linear` as a code value in 0..max_code (255 or 65535), rounded to
 * nearest: sRGB-encoded if `srgb`, else only clamped (NaN gives 0). */
uint32_t hri_code_value(float linear, int srgb, uint32_t max_code);
/* The 8-bit sRGB codes (hri_code_value(v, 1, 255)) of the red, green and
 * blue of `count` pixels of `channels` floats each (3 or 4: alpha is
 * skipped), three bytes a pixel: a row of a PPM. */
void hri_srgb8_encode_rgb(const float *pixels, size_t count, int32_t channels, uint8_t *codes);
/* The same by the formula alone (hri_code_value answers 8-bit sRGB from a
 * table built with it); for the test that the two agree. */
uint32_t hri_code_value_by_formula(float linear, int srgb, uint32_t max_code);

#endif
