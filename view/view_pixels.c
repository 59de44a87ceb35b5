/* Linear light to the window's 8-bit sRGB (view.h).
 *
 * The library's own encoder is internal to it (the writers use it), and the
 * viewer sees only the public API, so it finds the same code values its own
 * way: the code of a value v is the number of code boundaries at or below
 * v, where the boundary between codes c-1 and c is the linear value the
 * sRGB curve (IEC 61966-2-1) takes to (c - 0.5) / 255. The window is for
 * looking; the files the viewer saves come from hr_image_write. */
#include <math.h>
#include <pthread.h>

#include "view.h"

static float boundary[255]; /* boundary[c - 1]: the least linear value of code c */
static pthread_once_t boundary_once = PTHREAD_ONCE_INIT;

/* The inverse of the sRGB curve. */
static double srgb_decode(double encoded)
{
    return encoded <= 0.04045 ? encoded / 12.92 : pow((encoded + 0.055) / 1.055, 2.4);
}

static void build_boundaries(void)
{
    for (int c = 1; c <= 255; c++) boundary[c - 1] = (float)srgb_decode((c - 0.5) / 255.0);
}

static uint8_t code_of(float v)
{
    /* NaN and below zero: black (the comparison fails, as for 0). */
    if (!(v >= boundary[0])) return 0;
    int lo = 1, hi = 255; /* the code is the last c with boundary[c - 1] <= v */
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (boundary[mid - 1] <= v) lo = mid;
        else hi = mid - 1;
    }
    return (uint8_t)lo;
}

void view_pixels_srgb8(const float *pixels, int32_t row_stride, int32_t width, int32_t height, uint8_t *out,
                       int pitch)
{
    pthread_once(&boundary_once, build_boundaries);
    for (int32_t y = 0; y < height; y++) {
        uint8_t *row = out + (size_t)y * (size_t)pitch;
        const float *src = pixels + (size_t)y * (size_t)row_stride;
        for (int32_t i = 0; i < 3 * width; i++) row[i] = code_of(src[i]);
    }
}
