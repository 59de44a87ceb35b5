/* Linear light to the window's 8-bit sRGB (view.h): the codes the library's
 * writers give the same pixels (hr_srgb8_encode), so what the window shows
 * is what `hitray render` writes to a PNG or PPM. */
#include <stddef.h>

#include <hitray/image.h>

#include "view.h"

void view_pixels_srgb8(const float *pixels, int32_t row_stride, int32_t width, int32_t height, uint8_t *out,
                       int pitch)
{
    for (int32_t y = 0; y < height; y++)
        hr_srgb8_encode(pixels + (size_t)y * (size_t)row_stride, 3 * (size_t)width,
                        out + (size_t)y * (size_t)pitch);
}
