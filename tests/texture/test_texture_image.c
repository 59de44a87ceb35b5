/* Image textures: the readers (PNG through libpng, BMP and JPEG through
 * stb_image) against images of known pixels, and a pixmap on a sphere
 * sampled at every texel's (u, v): nearest gives that texel exactly,
 * bilinear gives it at the texel's centre and the mean of two texels
 * midway between them. Also the texture on a CSG object (its leaf's
 * (u, v)), on a mesh (its OBJ file's texture coordinates), tiling by the
 * (u, v) range, and the `texture` effect. */
#define _POSIX_C_SOURCE 200809L /* snprintf into paths */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>
#include <stb_image_write.h>

#include "hr_test.h"
#include "texture_support.h"

#define PI 3.14159265358979323846
#define TW 4
#define TH 3

/* Texel (x, y) of the test image, linear, each a multiple of 1/65535 so a
 * 16-bit linear PNG holds it exactly. */
static hr_color texel(int x, int y)
{
    return (hr_color){(double)(1000 * (x + 1)) / 65535.0, (double)(7000 * (y + 1)) / 65535.0,
                      (double)(3000 * (x + y)) / 65535.0};
}

static char *write_test_png(hr_context *ctx, const char *dir)
{
    hr_image *img;
    CHECK_OK(hr_image_create(ctx, TW, TH, 3, &img));
    float *p = hr_image_data(img);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++) {
            hr_color c = texel(x, y);
            float *q = p + (y * TW + x) * 3;
            q[0] = (float)c.r, q[1] = (float)c.g, q[2] = (float)c.b;
        }
    char *path = malloc(strlen(dir) + 32);
    sprintf(path, "%s/texels.png", dir);
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.png_bits = 16;
    o.png_linear = 1;
    CHECK_OK(hr_image_write(ctx, img, path, &o));
    hr_image_destroy(img);
    return path;
}

/* A 16-bit linear PNG reads back exactly (the floats of k / 65535). */
static void test_png_reads_back(hr_context *ctx, const char *png)
{
    hr_image *img = NULL;
    CHECK_MSG(hr_image_read(ctx, png, &img) == HR_OK, "%s", hr_context_last_error(ctx));
    if (!img) return;
    CHECK(hr_image_width(img) == TW && hr_image_height(img) == TH && hr_image_channels(img) == 3);
    const float *p = hr_image_data(img);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++) {
            hr_color c = texel(x, y);
            const float *q = p + (y * TW + x) * 3;
            CHECK(q[0] == (float)c.r && q[1] == (float)c.g && q[2] == (float)c.b);
        }
    hr_image_destroy(img);
}

/* 8-bit files hold sRGB codes: each reads as the sRGB curve's linear value
 * of its code, computed here in double from the standard's formula. BMP
 * is lossless, so exactly (to float); JPEG at quality 100 of one flat
 * colour comes back within 2 codes (its rounding of the colour transform). */
static double srgb_linear(int code)
{
    double v = code / 255.0;
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static void test_bmp_and_jpeg(hr_context *ctx, const char *dir)
{
    enum { W = 8, H = 8 };
    unsigned char rgb[W * H * 3];
    for (int i = 0; i < W * H; i++) rgb[3 * i] = (unsigned char)(i * 4), rgb[3 * i + 1] = 200, rgb[3 * i + 2] = 17;
    char bmp[4096], jpg[4096];
    snprintf(bmp, sizeof bmp, "%s/t.bmp", dir);
    snprintf(jpg, sizeof jpg, "%s/t.jpg", dir);
    CHECK(stbi_write_bmp(bmp, W, H, 3, rgb) != 0);
    hr_image *img = NULL;
    CHECK_MSG(hr_image_read(ctx, bmp, &img) == HR_OK, "%s", hr_context_last_error(ctx));
    if (img) {
        const float *p = hr_image_data(img);
        int exact = 1;
        for (int i = 0; i < W * H * 3; i++) exact &= p[i] == (float)srgb_linear(rgb[i]);
        CHECK_MSG(exact, "BMP pixels differ from their sRGB codes");
        hr_image_destroy(img);
    }
    unsigned char flat[W * H * 3];
    for (int i = 0; i < W * H; i++) flat[3 * i] = 180, flat[3 * i + 1] = 90, flat[3 * i + 2] = 30;
    CHECK(stbi_write_jpg(jpg, W, H, 3, flat, 100) != 0);
    img = NULL;
    CHECK_MSG(hr_image_read(ctx, jpg, &img) == HR_OK, "%s", hr_context_last_error(ctx));
    if (img) {
        const float *p = hr_image_data(img);
        for (int c = 0; c < 3; c++) {
            CHECK(p[c] >= srgb_linear(flat[c] - 2) && p[c] <= srgb_linear(flat[c] + 2));
        }
        hr_image_destroy(img);
    }
}

/* The unit sphere's point at (u, v) (sphere.c: longitude about z from +x,
 * latitude from the south pole). */
static hr_vec3 sphere_point(double u, double v)
{
    double lon = 2 * PI * u, lat = PI * (v - 0.5);
    return (hr_vec3){cos(lat) * cos(lon), cos(lat) * sin(lon), sin(lat)};
}

static hr_color at_uv(const hr_scene *s, double u, double v)
{
    hr_vec3 p = sphere_point(u, v);
    return tx_shade(s, (hr_vec3){3 * p.x, 3 * p.y, 3 * p.z}, (hr_vec3){-p.x, -p.y, -p.z});
}

#define FLAT "background 0 0 0  globalAmbient 1 1 1  ambient 1 1 1  diffuse 0 0 0\n"

static void test_sphere_texels(hr_context *ctx, const char *dir)
{
    hr_scene *nearest = tx_scene(ctx, FLAT "makePixmap 1 texels.png\n"
                                           "texture 1 parameters 5 0 1 0 1 1  sphere\n", dir);
    hr_scene *bilinear = tx_scene(ctx, FLAT "makePixmap 1 texels.png  texture 1  sphere\n", dir);
    if (!nearest || !bilinear) return;
    CHECK(hr_scene_effects(nearest) & HR_EFFECT_TEXTURE);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++) {
            /* The texel's centre; row 0 is the top of the image, v = 1. */
            double u = (x + 0.5) / TW, v = 1.0 - (y + 0.5) / TH;
            hr_color want = texel(x, y);
            hr_color n = at_uv(nearest, u, v), b = at_uv(bilinear, u, v);
            hr_color wf = {(float)want.r, (float)want.g, (float)want.b};
            CHECK_MSG(n.r == wf.r && n.g == wf.g && n.b == wf.b,
                      "nearest at texel (%d, %d): %.9g %.9g %.9g", x, y, n.r, n.g, n.b);
            /* Off the centre by the rounding of the point and of atan2:
             * some 1e-15 of a texel, times a texel-to-texel step under 1. */
            CHECK_NEAR(b.r, wf.r, 1e-9);
            CHECK_NEAR(b.g, wf.g, 1e-9);
            CHECK_NEAR(b.b, wf.b, 1e-9);
        }
    /* Midway between texels (1, 1) and (2, 1): their mean; and between
     * texel (3, 1) and, across the seam at u = 0, texel (0, 1). */
    hr_color mid = at_uv(bilinear, 2.0 / TW, 1.0 - 1.5 / TH);
    CHECK_NEAR(mid.r, 0.5 * ((double)(float)texel(1, 1).r + (double)(float)texel(2, 1).r), 1e-9);
    hr_color seam = at_uv(bilinear, 1e-12, 1.0 - 1.5 / TH);
    CHECK_NEAR(seam.r, 0.5 * ((double)(float)texel(3, 1).r + (double)(float)texel(0, 1).r), 1e-9);
    hr_scene_destroy(nearest);
    hr_scene_destroy(bilinear);
}

/* A (u, v) range a quarter as wide tiles the image four times across. */
static void test_tiling(hr_context *ctx, const char *dir)
{
    hr_scene *s = tx_scene(ctx, FLAT "makePixmap 1 texels.png\n"
                                     "texture 1 parameters 5 0 0.25 0 1 1  sphere\n", dir);
    if (!s) return;
    for (int tile = 0; tile < 4; tile++) {
        hr_color c = at_uv(s, 0.25 * tile + 0.25 * 2.5 / TW, 1.0 - 0.5 / TH);
        CHECK(c.r == (float)texel(2, 0).r && c.g == (float)texel(2, 0).g);
    }
    hr_scene_destroy(s);
}

/* On a CSG object each hit takes its leaf's (u, v): the front sphere of a
 * union shows the texel at its own (u, v). */
static void test_csg_leaf(hr_context *ctx, const char *dir)
{
    hr_scene *s = tx_scene(ctx, FLAT "makePixmap 1 texels.png  texture 1 parameters 5 0 1 0 1 1\n"
                                     "union  push translate 0 0 -3 sphere pop  sphere\n", dir);
    if (!s) return;
    double u = 0.5 / TW, v = 1.0 - 1.5 / TH;
    hr_color c = at_uv(s, u, v);
    CHECK(c.r == (float)texel(0, 1).r && c.g == (float)texel(0, 1).g && c.b == (float)texel(0, 1).b);
    hr_scene_destroy(s);
}

/* On a mesh, the (u, v) of its OBJ file's vt: textured_square.obj has
 * u = x + 1 (the image twice across), v = (y + 1) / 2. */
static void test_mesh_texcoords(hr_context *ctx, const char *dir)
{
    char text[8192];
    snprintf(text, sizeof text,
             FLAT "makePixmap 1 texels.png  texture 1 parameters 5 0 1 0 1 1\n"
                  "mesh %s/tests/data/meshes/textured_square.obj\n",
             HR_TEST_SOURCE_DIR);
    hr_scene *s = tx_scene(ctx, text, dir);
    if (!s) return;
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++) {
            double u = (x + 0.5) / TW, v = 1.0 - (y + 0.5) / TH;
            hr_color want = texel(x, y);
            for (int tile = 0; tile < 2; tile++) {
                hr_color c = tx_down(s, u + tile - 1.0, 2.0 * v - 1.0);
                CHECK_MSG(c.r == (float)want.r && c.g == (float)want.g && c.b == (float)want.b,
                          "mesh texel (%d, %d), tile %d: %g %g %g", x, y, tile, c.r, c.g, c.b);
            }
        }
    hr_scene_destroy(s);
}

/* Pixmaps through the C API. */
static void test_api(hr_context *ctx, const char *png)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_image *img = NULL;
    CHECK_OK(hr_image_read(ctx, png, &img));
    CHECK(hr_scene_has_pixmap(s, 3) == 0);
    CHECK_OK(hr_scene_set_pixmap(s, 3, img));
    CHECK(hr_scene_has_pixmap(s, 3) == 1);
    CHECK(hr_scene_set_pixmap(s, 3, img) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "pixmap 3 is made already") != NULL);
    CHECK(hr_scene_set_pixmap(s, 0, img) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "numbered from 1") != NULL);
    hr_image_data(img)[4] = NAN;
    CHECK(hr_scene_set_pixmap(s, 4, img) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "pixmap 4: pixel (1, 0) has green nan") != NULL);
    CHECK(hr_scene_has_pixmap(s, 4) == 0);
    CHECK_OK(hr_scene_commit(s));
    CHECK(hr_scene_set_pixmap(s, 5, img) == HR_ERROR_STATE);
    hr_image_destroy(img);
    hr_scene_destroy(s);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    char *dir = tx_temp_dir();
    if (!dir) return hr_test_end();
    char *png = write_test_png(ctx, dir);
    test_png_reads_back(ctx, png);
    test_bmp_and_jpeg(ctx, dir);
    test_sphere_texels(ctx, dir);
    test_tiling(ctx, dir);
    test_csg_leaf(ctx, dir);
    test_mesh_texcoords(ctx, dir);
    test_api(ctx, png);
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    free(png);
    free(dir);
    hr_context_destroy(ctx);
    return hr_test_end();
}
