/* Image files that lie or are cut, and solid textures far from the origin.
 * Each file is made here, byte by byte where no writer would make it: a
 * top-down BMP (negative height) reads right side up; a BMP or JPEG whose
 * header promises more pixels than the file holds, a PNG chunk declaring
 * more bytes than follow it, and a palette index beyond the palette are
 * refused, naming the file and what is wrong, never read as black. A
 * marble, wood or checkerboard texture on a shape at 1e308 gives finite
 * colours. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>
#include <stb_image_write.h>
#include <zlib.h>

#include "hr_test.h"
#include "texture_support.h"

static char dir_path[4096];

static const char *in_dir(const char *name)
{
    static char path[8192];
    snprintf(path, sizeof path, "%s/%s", dir_path, name);
    return path;
}

static void write_bytes(const char *name, const void *bytes, size_t n)
{
    FILE *f = fopen(in_dir(name), "wb");
    CHECK(f != NULL);
    if (!f) return;
    CHECK(fwrite(bytes, 1, n, f) == n);
    fclose(f);
}

static void put16(unsigned char *b, unsigned v) { b[0] = (unsigned char)v, b[1] = (unsigned char)(v >> 8); }
static void put32(unsigned char *b, uint32_t v)
{
    for (int i = 0; i < 4; i++) b[i] = (unsigned char)(v >> (8 * i));
}
static void put32be(unsigned char *b, uint32_t v)
{
    for (int i = 0; i < 4; i++) b[i] = (unsigned char)(v >> (24 - 8 * i));
}

/* A 24-bit BMP header (54 bytes) of w x h pixels whose data starts at 54. */
static void bmp_header(unsigned char *b, int32_t w, int32_t h, uint32_t file_size)
{
    memset(b, 0, 54);
    b[0] = 'B', b[1] = 'M';
    put32(b + 2, file_size);
    put32(b + 10, 54);
    put32(b + 14, 40);
    put32(b + 18, (uint32_t)w);
    put32(b + 22, (uint32_t)h);
    put16(b + 26, 1);
    put16(b + 28, 24);
}

static void expect_refused(hr_context *ctx, const char *name, const char *what)
{
    hr_image *img = NULL;
    hr_status st = hr_image_read(ctx, in_dir(name), &img);
    const char *m = hr_context_last_error(ctx);
    CHECK_MSG(st == HR_ERROR_IO && img == NULL && strstr(m, name) && strstr(m, what),
              "%s: status %d, message '%s' lacks '%s'", name, (int)st, m, what);
    hr_image_destroy(img);
}

static void test_bmp(hr_context *ctx)
{
    /* Top-down, 2 x 2: rows of 6 bytes padded to 8, the first row the top;
     * BMP stores blue, green, red. Top left red, bottom right blue. */
    unsigned char b[54 + 16] = {0};
    bmp_header(b, 2, -2, sizeof b);
    b[54 + 2] = 255;      /* (0, 0) red */
    b[62 + 3 + 0] = 255;  /* (1, 1) blue */
    write_bytes("topdown.bmp", b, sizeof b);
    hr_image *img = NULL;
    CHECK_MSG(hr_image_read(ctx, in_dir("topdown.bmp"), &img) == HR_OK, "%s", hr_context_last_error(ctx));
    if (img) {
        const float *p = hr_image_data(img);
        CHECK(hr_image_width(img) == 2 && hr_image_height(img) == 2);
        CHECK(p[0] == 1.0f && p[1] == 0.0f && p[2] == 0.0f);
        CHECK(p[9] == 0.0f && p[10] == 0.0f && p[11] == 1.0f);
        hr_image_destroy(img);
    }
    /* A header and no pixels; a header promising 4096 x 4096 in 822 bytes. */
    bmp_header(b, 16, 16, 54);
    write_bytes("empty.bmp", b, 54);
    expect_refused(ctx, "empty.bmp", "822 bytes in all, but the file has 54");
    static unsigned char lying[822];
    bmp_header(lying, 4096, 4096, sizeof lying);
    write_bytes("lying.bmp", lying, sizeof lying);
    expect_refused(ctx, "lying.bmp", "promises 4096 x 4096 pixels");
    /* One byte short: the last row's padding. */
    bmp_header(b, 2, 2, sizeof b - 1);
    write_bytes("short.bmp", b, sizeof b - 1);
    expect_refused(ctx, "short.bmp", "70 bytes in all, but the file has 69");
}

static int find_sof(const unsigned char *j, size_t n)
{
    for (size_t i = 2; i + 9 < n; i++)
        if (j[i] == 0xff && j[i + 1] == 0xc0) return (int)i;
    return -1;
}

static void test_jpeg(hr_context *ctx)
{
    enum { W = 64, H = 64 };
    static unsigned char rgb[W * H * 3];
    uint32_t x = 12345;
    for (size_t i = 0; i < sizeof rgb; i++) x = x * 1103515245u + 12345u, rgb[i] = (unsigned char)(x >> 24);
    CHECK(stbi_write_jpg(in_dir("noise.jpg"), W, H, 3, rgb, 90) != 0);
    FILE *f = fopen(in_dir("noise.jpg"), "rb");
    static unsigned char j[1 << 16];
    size_t n = f ? fread(j, 1, sizeof j, f) : 0;
    if (f) fclose(f);
    CHECK(n > 2000 && n < sizeof j);
    hr_image *img = NULL;
    CHECK_MSG(hr_image_read(ctx, in_dir("noise.jpg"), &img) == HR_OK, "%s", hr_context_last_error(ctx));
    hr_image_destroy(img);
    /* Cut in the middle of its coded data. */
    write_bytes("cut.jpg", j, n / 2);
    expect_refused(ctx, "cut.jpg", "cannot read JPEG");
    /* The first 633 bytes, their frame header saying 4096 x 4096. */
    int sof = find_sof(j, n);
    CHECK(sof > 0);
    if (sof < 0) return;
    j[sof + 5] = 0x10, j[sof + 6] = 0, j[sof + 7] = 0x10, j[sof + 8] = 0;
    write_bytes("lying.jpg", j, 633);
    expect_refused(ctx, "lying.jpg", "4096 x 4096 pixels need at least 32768 bytes");
}

static void put_chunk(unsigned char *b, size_t *at, const char *type, const unsigned char *data, uint32_t n)
{
    put32be(b + *at, n);
    memcpy(b + *at + 4, type, 4);
    if (n) memcpy(b + *at + 8, data, n);
    put32be(b + *at + 8 + n, (uint32_t)crc32(0, b + *at + 4, 4 + n));
    *at += 12 + n;
}

/* A 4 x 1 palette PNG of 8-bit indices, its palette of two entries. */
static size_t palette_png(unsigned char *b, const unsigned char index[4])
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    memcpy(b, sig, 8);
    size_t at = 8;
    unsigned char ihdr[13] = {0, 0, 0, 4, 0, 0, 0, 1, 8, 3, 0, 0, 0};
    put_chunk(b, &at, "IHDR", ihdr, 13);
    static const unsigned char plte[6] = {255, 0, 0, 0, 255, 0};
    put_chunk(b, &at, "PLTE", plte, 6);
    unsigned char raw[5] = {0, index[0], index[1], index[2], index[3]}, z[64];
    uLongf zn = sizeof z;
    CHECK(compress(z, &zn, raw, sizeof raw) == Z_OK);
    put_chunk(b, &at, "IDAT", z, (uint32_t)zn);
    put_chunk(b, &at, "IEND", NULL, 0);
    return at;
}

static void test_png(hr_context *ctx)
{
    unsigned char b[256];
    static const unsigned char good[4] = {0, 1, 1, 0}, bad[4] = {0, 1, 5, 0};
    write_bytes("palette.png", b, palette_png(b, good));
    hr_image *img = NULL;
    CHECK_MSG(hr_image_read(ctx, in_dir("palette.png"), &img) == HR_OK, "%s", hr_context_last_error(ctx));
    if (img) {
        const float *p = hr_image_data(img);
        CHECK(p[0] == 1.0f && p[1] == 0.0f && p[3] == 0.0f && p[4] == 1.0f);
        hr_image_destroy(img);
    }
    write_bytes("index.png", b, palette_png(b, bad));
    expect_refused(ctx, "index.png", "a pixel is palette index 5, but the palette has 2 entries");
    /* IHDR, then a chunk declaring 2^31 - 1 bytes with 4 after it: refused
     * before libpng allocates 2 GB. */
    size_t n = palette_png(b, good);
    size_t at = 8 + 25;
    put32be(b + at, 0x7fffffffu);
    memcpy(b + at + 4, "tEXt", 4);
    write_bytes("huge_chunk.png", b, at + 12);
    expect_refused(ctx, "huge_chunk.png", "the chunk at byte 33 declares 2147483647 bytes, but only 0 follow");
    (void)n;
}

/* Every shape with a texture at 1e308: the colour seen is finite. */
static void test_far_textures(hr_context *ctx)
{
    static const char *shapes[] = {"sphere", "cube", "cylinder", "torus", "square"};
    static const int textures[] = {-1, -2, -3};
    for (size_t t = 0; t < 3; t++)
        for (size_t k = 0; k < sizeof shapes / sizeof *shapes; k++) {
            char text[512];
            snprintf(text, sizeof text,
                     "camera 0 0 10 0 0 0 0 1 0 40 ambient 1 1 1 globalAmbient 1 1 1\n"
                     "texture %d translate 1e308 0 0 %s\n", textures[t],
                     shapes[k]);
            hr_scene *s = tx_scene(ctx, text, NULL);
            if (!s) continue;
            hr_color c = tx_shade(s, (hr_vec3){1e308, 0.25, 10}, (hr_vec3){0, 0, -1});
            CHECK_MSG(isfinite(c.r) && isfinite(c.g) && isfinite(c.b), "texture %d on %s at 1e308: %g %g %g",
                      textures[t], shapes[k], c.r, c.g, c.b);
            hr_scene_destroy(s);
        }
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    char *dir = tx_temp_dir();
    if (!dir) return hr_test_end();
    snprintf(dir_path, sizeof dir_path, "%s", dir);
    test_bmp(ctx);
    test_jpeg(ctx);
    test_png(ctx);
    test_far_textures(ctx);
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    free(dir);
    hr_context_destroy(ctx);
    return hr_test_end();
}
