/* Pixmaps' mip-maps and trilinear sampling (lib/texture/pixmap.c, compiled
 * into this test).
 *
 * - Each level of a power-of-two image against the box filter of the
 *   image: texel (x, y) of level k is the mean of the block of the image it
 *   covers (2^k x 2^k, or the whole side once a side is down to 1), summed
 *   in long double. Each level is rounded to float once from a mean of four
 *   floats of the level below (exact sums in double, one rounding), so
 *   level k is within k roundings of the true mean: we allow
 *   k * 2^-24 * max |texel| (plus nothing: the four-term sum and the
 *   quarter are exact in double).
 * - Odd sides: the level sizes (half, rounded up, to 1 x 1) and a texel
 *   that pairs the last column with the first (the texture tiles).
 * - Trilinear sampling: a footprint under a texel is the bilinear sample of
 *   the image bit for bit; one of 2^k texels is level k's bilinear sample;
 *   one wider than the image is the image's mean; in between, the blend of
 *   the two levels by log2 of the width; a constant image stays constant.
 * - The bytes the levels take. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hr_test.h"
#include "texture/texture.h"

static uint32_t state = 12345u;
static float next_value(void)
{
    state = state * 1664525u + 1013904223u;
    return (float)((state >> 8) & 0xffff) / 65535.0f;
}

/* A w x h RGB image of pseudo-random texels (or `constant` everywhere if >= 0). */
static hr_image *make_image(hr_context *ctx, int32_t w, int32_t h, float constant)
{
    hr_image *img = NULL;
    if (hr_image_create(ctx, w, h, 3, &img) != HR_OK) return NULL;
    float *p = hr_image_data(img);
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++) p[i] = constant >= 0 ? constant : next_value();
    return img;
}

static const float *level_texel(const hr_pixmap *pm, int32_t k, int32_t x, int32_t y)
{
    return pm->levels[k] + ((size_t)y * (size_t)pm->level_width[k] + (size_t)x) * 3;
}

static void test_power_of_two(hr_context *ctx)
{
    hr_pixmap_set set = {0};
    hr_image *img = make_image(ctx, 32, 8, -1.0f);
    CHECK_OK(hri_pixmap_add(ctx, &set, 1, img));
    const hr_pixmap *pm = hri_pixmap_find(&set, 1);
    CHECK(pm && pm->level_count == 6); /* 32x8 16x4 8x2 4x1 2x1 1x1 */
    if (!pm || pm->level_count != 6) goto done;
    const float *src = hr_image_data(img);
    double worst = 0.0;
    for (int32_t k = 0; k < pm->level_count; k++) {
        const int32_t lw = pm->level_width[k], lh = pm->level_height[k];
        const int32_t bw = 32 / lw, bh = 8 / lh; /* the block each texel covers */
        CHECK(lw == (32 >> k > 1 ? 32 >> k : 1) && lh == (8 >> k > 1 ? 8 >> k : 1));
        for (int32_t y = 0; y < lh; y++)
            for (int32_t x = 0; x < lw; x++)
                for (int c = 0; c < 3; c++) {
                    long double sum = 0;
                    for (int32_t j = 0; j < bh; j++)
                        for (int32_t i = 0; i < bw; i++)
                            sum += src[((size_t)(y * bh + j) * 32 + (size_t)(x * bw + i)) * 3 + (size_t)c];
                    const double want = (double)(sum / (bw * bh));
                    const double err = fabs(level_texel(pm, k, x, y)[c] - want);
                    if (err > worst) worst = err;
                    CHECK_MSG(err <= k * 0x1p-24 + 1e-300, "level %d texel (%d, %d): %.9g, box mean %.9g",
                              (int)k, (int)x, (int)y, (double)level_texel(pm, k, x, y)[c], want);
                }
    }
    printf("power of two: worst level error %.3g\n", worst);
    /* Sampling: under a texel, the image's bilinear sample bit for bit. */
    const double st[][2] = {{0.1, 0.2}, {0.5, 0.5}, {0.97, 0.03}, {0.333, 0.777}};
    for (int i = 0; i < 4; i++) {
        const double s = st[i][0], t = st[i][1];
        const hr_color plain = hri_pixmap_sample(pm, s, t, 0);
        const double small[4] = {0.5 / 32, 0, 0, 0.5 / 8};
        const hr_color a = hri_pixmap_sample_footprint(pm, s, t, small);
        CHECK(a.r == plain.r && a.g == plain.g && a.b == plain.b);
        /* Exactly 4 texels wide: level 2. */
        const double four[4] = {4.0 / 32, 0, 0, 1.0 / 8};
        const hr_color b = hri_pixmap_sample_footprint(pm, s, t, four);
        const hr_color l2 = hri_pixmap_sample_level(pm, 2, s, t);
        CHECK(b.r == l2.r && b.g == l2.g && b.b == l2.b);
        /* 2^2.5 texels: halfway between levels 2 and 3. */
        const double between[4] = {0, pow(2.0, 2.5) / 8, pow(2.0, 2.5) / 32, 0};
        const hr_color c = hri_pixmap_sample_footprint(pm, s, t, between);
        const hr_color l3 = hri_pixmap_sample_level(pm, 3, s, t);
        CHECK(fabs(c.g - 0.5 * (l2.g + l3.g)) <= 1e-12);
        /* Wider than the image: its mean (the 1 x 1 level, blended with
         * itself by the bilinear weights: within an ulp or two). */
        const double huge[4] = {3.0, 0, 0, 3.0};
        const hr_color d = hri_pixmap_sample_footprint(pm, s, t, huge);
        const float *mean = level_texel(pm, pm->level_count - 1, 0, 0);
        CHECK(fabs(d.r - mean[0]) <= 1e-15 && fabs(d.g - mean[1]) <= 1e-15 && fabs(d.b - mean[2]) <= 1e-15);
    }
    CHECK(hri_pixmap_mip_bytes(32, 8) == (uint64_t)(16 * 4 + 8 * 2 + 4 + 2 + 1) * 12);
done:
    hri_pixmap_set_free(&set);
    hr_image_destroy(img);
}

static void test_odd_sides(hr_context *ctx)
{
    hr_pixmap_set set = {0};
    hr_image *img = make_image(ctx, 5, 3, -1.0f);
    CHECK_OK(hri_pixmap_add(ctx, &set, 2, img));
    const hr_pixmap *pm = hri_pixmap_find(&set, 2);
    CHECK(pm && pm->level_count == 4); /* 5x3 3x2 2x1 1x1 */
    if (pm && pm->level_count == 4) {
        CHECK(pm->level_width[1] == 3 && pm->level_height[1] == 2);
        CHECK(pm->level_width[2] == 2 && pm->level_height[2] == 1);
        CHECK(pm->level_width[3] == 1 && pm->level_height[3] == 1);
        /* Level 1's last texel: columns 4 and 0 (wrapped) of rows 2 and 0. */
        const float *src = hr_image_data(img);
        for (int c = 0; c < 3; c++) {
            const double want = 0.25 * ((double)src[(2 * 5 + 4) * 3 + c] + src[(2 * 5 + 0) * 3 + c] +
                                        src[(0 * 5 + 4) * 3 + c] + src[(0 * 5 + 0) * 3 + c]);
            CHECK(level_texel(pm, 1, 2, 1)[c] == (float)want);
        }
    }
    CHECK(hri_pixmap_mip_bytes(5, 3) == (uint64_t)(3 * 2 + 2 + 1) * 12);
    CHECK(hri_pixmap_mip_bytes(1, 1) == 0);
    hri_pixmap_set_free(&set);
    hr_image_destroy(img);
}

static void test_constant(hr_context *ctx)
{
    hr_pixmap_set set = {0};
    hr_image *img = make_image(ctx, 7, 12, 0.375f);
    CHECK_OK(hri_pixmap_add(ctx, &set, 3, img));
    const hr_pixmap *pm = hri_pixmap_find(&set, 3);
    for (int i = 0; pm && i < 50; i++) {
        const double w = pow(2.0, 0.2 * i - 2.0) / 7.0;
        const double d[4] = {w, 0.3 * w, -0.5 * w, w};
        const hr_color c = hri_pixmap_sample_footprint(pm, 0.01 * i, 0.02 * i, d);
        CHECK(fabs(c.r - 0.375) <= 1e-15 && fabs(c.b - 0.375) <= 1e-15);
    }
    hri_pixmap_set_free(&set);
    hr_image_destroy(img);
}

int main(void)
{
    hr_context *ctx = NULL;
    CHECK(hr_context_create(&ctx) == HR_OK);
    test_power_of_two(ctx);
    test_odd_sides(ctx);
    test_constant(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
