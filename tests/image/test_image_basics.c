/* hr_image itself and the choice of format: argument checks, accessors,
 * default options, options from an older (shorter) struct, extensions in any
 * case, and an explicit format winning over the extension. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "image_fixture.h"

static hr_context *ctx;

static void check_create(void)
{
    static char not_an_image;
    hr_image *image = (hr_image *)(void *)&not_an_image; /* must be reset to NULL on failure */
    CHECK(hr_image_create(ctx, 0, 4, 3, &image) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(image == NULL);
    CHECK(hr_image_create(ctx, 4, -1, 3, &image) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_image_create(ctx, 4, 4, 2, &image) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "channels") != NULL);
    CHECK(hr_image_create(ctx, 4, 4, 5, &image) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_image_create(ctx, 4, 4, 3, NULL) == HR_ERROR_INVALID_ARGUMENT);
    /* Too many bytes to count: refused, not wrapped around. */
    CHECK(hr_image_create(ctx, INT32_MAX, INT32_MAX, 4, &image) == HR_ERROR_OUT_OF_MEMORY);
    CHECK(image == NULL);

    CHECK_OK(hr_image_create(ctx, 5, 3, 4, &image));
    CHECK(hr_image_width(image) == 5);
    CHECK(hr_image_height(image) == 3);
    CHECK(hr_image_channels(image) == 4);
    const float *p = hr_image_data(image);
    CHECK(p != NULL);
    int zero = 1;
    for (int i = 0; i < 5 * 3 * 4; i++) zero &= p[i] == 0.0f;
    CHECK(zero);
    hr_image_destroy(image);

    CHECK(hr_image_width(NULL) == 0 && hr_image_height(NULL) == 0 && hr_image_channels(NULL) == 0);
    CHECK(hr_image_data(NULL) == NULL);
    hr_image_destroy(NULL);
    /* A NULL context is allowed: the status still comes back. */
    CHECK(hr_image_create(NULL, 0, 0, 3, &image) == HR_ERROR_INVALID_ARGUMENT);
}

/* The pixels start on a cache line (image.h), whatever the size, so a
 * render's threads writing neighbouring tiles of rows of whole lines never
 * write one line from two cores. */
static void check_alignment(void)
{
    const int32_t sizes[][2] = {{1, 1}, {5, 3}, {16, 16}, {480, 270}, {1024, 1024}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
        for (int32_t channels = 3; channels <= 4; channels++) {
            hr_image *image = NULL;
            CHECK_OK(hr_image_create(ctx, sizes[i][0], sizes[i][1], channels, &image));
            CHECK((uintptr_t)hr_image_data(image) % 64 == 0);
            hr_image_destroy(image);
        }
}

static void check_default_options(void)
{
    hr_image_write_options o;
    memset(&o, 0xab, sizeof o);
    hr_image_write_options_default(&o);
    CHECK(o.struct_size == sizeof o);
    CHECK(o.format == HR_FORMAT_AUTO);
    CHECK(o.png_bits == 8);
    CHECK(o.png_linear == 0);
    CHECK(o.exr_half == 0);
    CHECK(o.jpeg_quality == 0);
    hr_image_write_options_default(NULL);
}

/* The first bytes of a file, to tell formats apart. */
static int starts_with(const char *path, const char *magic, size_t n)
{
    long size = 0;
    unsigned char *data = fixture_read_file(path, &size);
    int ok = data && size >= (long)n && memcmp(data, magic, n) == 0;
    free(data);
    return ok;
}

static const char png_magic[] = "\x89PNG\r\n\x1a\n";
static const char exr_magic[] = "\x76\x2f\x31\x01";

static void check_format_choice(const char *dir)
{
    hr_image *image = fixture_image(ctx, 4, 3, 3, 0);
    char path[4096];
    struct {
        const char *name;
        const char *magic;
        size_t n;
    } cases[] = {
        {"a.Png", png_magic, 8}, {"b.EXR", exr_magic, 4}, {"c.PpM", "P6\n", 3}, {"d.pFm", "PF\n", 3},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        fixture_format(path, sizeof path, "%s", fixture_path(dir, cases[i].name));
        CHECK_OK(hr_image_write(ctx, image, path, NULL));
        CHECK_MSG(starts_with(path, cases[i].magic, cases[i].n), "%s has the wrong format", cases[i].name);
    }

    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.format = HR_FORMAT_PNG;
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "explicit.dat"));
    CHECK_OK(hr_image_write(ctx, image, path, &o));
    CHECK(starts_with(path, png_magic, 8));
    o.format = HR_FORMAT_PFM;
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "really_pfm.png"));
    CHECK_OK(hr_image_write(ctx, image, path, &o));
    CHECK(starts_with(path, "PF\n", 3));
    o.format = HR_FORMAT_EXR;
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "no_extension"));
    CHECK_OK(hr_image_write(ctx, image, path, &o));
    CHECK(starts_with(path, exr_magic, 4));

    /* An older caller whose struct ends before png_linear: the fields it
     * does not know keep their defaults, so its 16-bit PNG is sRGB. */
    hr_image_write_options old;
    memset(&old, 0xff, sizeof old); /* garbage beyond struct_size */
    old.struct_size = (uint32_t)offsetof(hr_image_write_options, png_linear);
    old.format = HR_FORMAT_AUTO;
    old.png_bits = 16;
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "old_caller.png"));
    CHECK_OK(hr_image_write(ctx, image, path, &old));
    fixture_png png;
    if (fixture_read_png(path, &png) == 0) {
        CHECK(png.bits == 16);
        CHECK(png.has_srgb);
        free(png.samples);
    } else {
        CHECK(0);
    }
    hr_image_destroy(image);
}

/* The format table: names, extensions and the phrase for messages agree,
 * and every code from HR_FORMAT_PNG up to the last is one format. */
static void check_format_table(void)
{
    int32_t count = 0;
    for (int32_t code = HR_FORMAT_PNG; hr_image_format_name(code); code++, count++) {
        const char *name = hr_image_format_name(code), *ext = hr_image_format_extension(code);
        CHECK(hr_image_format_from_name(name) == code);
        char upper[32];
        fixture_format(upper, sizeof upper, "x%s", ext);
        for (char *c = upper; *c; c++) *c = (char)(*c >= 'a' && *c <= 'z' ? *c - 32 : *c);
        CHECK_MSG(hr_image_format_from_path(upper) == code, "%s", upper);
    }
    CHECK(count >= 4);
    CHECK(hr_image_format_name(HR_FORMAT_AUTO) == NULL);
    CHECK(hr_image_format_extension(HR_FORMAT_PNG + count) == NULL);
    CHECK(hr_image_format_from_name("PNG") == HR_FORMAT_AUTO); /* names are lower case, as --format takes them */
    CHECK(hr_image_format_from_name(NULL) == HR_FORMAT_AUTO);
    CHECK(hr_image_format_from_path("image.tiff") == HR_FORMAT_AUTO);
    CHECK(hr_image_format_from_path("png") == HR_FORMAT_AUTO);
    CHECK(hr_image_format_from_path(NULL) == HR_FORMAT_AUTO);
    char list[128];
    hr_image_format_list(list, sizeof list);
    CHECK_MSG(strncmp(list, ".png, .exr, ", 12) == 0 && strstr(list, " or ") != NULL, "%s", list);
    hr_image_format_list(list, 5); /* cut to fit, still a string */
    CHECK(strcmp(list, ".png") == 0);
    /* The writer's message lists them too. */
    hr_image *image = fixture_image(ctx, 2, 2, 3, 0);
    CHECK(hr_image_write(ctx, image, "x.tiff", NULL) == HR_ERROR_INVALID_ARGUMENT);
    hr_image_format_list(list, sizeof list);
    CHECK(strstr(hr_context_last_error(ctx), list) != NULL);
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.format = HR_FORMAT_PNG + count;
    CHECK(hr_image_write(ctx, image, "x.png", &o) == HR_ERROR_INVALID_ARGUMENT);
    hr_image_destroy(image);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    char dir[4096];
    fixture_format(dir, sizeof dir, "%s", fixture_dir("basics"));
    check_create();
    check_alignment();
    check_default_options();
    check_format_choice(dir);
    check_format_table();
    hr_context_destroy(ctx);
    return hr_test_end();
}
