/* Failures of hr_image_write: each one returns the right status with a
 * message naming the path and the reason, leaves an existing target exactly
 * as it was, and leaves no temporary file behind. Write errors in the middle
 * of a file are provoked with RLIMIT_FSIZE (the "disk" fills up after a few
 * kilobytes), so every format's own error path runs, not just the final
 * rename. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "image_fixture.h"

static hr_context *ctx;

static const char *const extensions[4] = {"png", "exr", "ppm", "pfm"};

static int contains(const char *text, const char *part) { return strstr(text, part) != NULL; }

/* Noise compresses badly, so every format writes more than the size limit. */
static hr_image *noise_image(int32_t w, int32_t h)
{
    hr_image *image = NULL;
    if (hr_image_create(ctx, w, h, 3, &image) != HR_OK) return NULL;
    float *p = hr_image_data(image);
    uint32_t state = 12345u;
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++) {
        state = state * 1664525u + 1013904223u;
        p[i] = (float)(state >> 8) / 16777216.0f;
    }
    return image;
}

static void write_marker(const char *path)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs("old contents\n", f);
        fclose(f);
    }
}

static int has_marker(const char *path)
{
    long size = 0;
    unsigned char *data = fixture_read_file(path, &size);
    int ok = data && size == 13 && memcmp(data, "old contents\n", 13) == 0;
    free(data);
    return ok;
}

static void check_missing_directory(const char *dir)
{
    hr_image *image = fixture_image(ctx, 4, 4, 3, 0);
    for (int i = 0; i < 4; i++) {
        char path[4096];
        fixture_format(path, sizeof path, "%s/no/such/dir/out.%s", dir, extensions[i]);
        CHECK(hr_image_write(ctx, image, path, NULL) == HR_ERROR_IO);
        const char *msg = hr_context_last_error(ctx);
        CHECK_MSG(contains(msg, path) && contains(msg, strerror(ENOENT)), "unclear message: %s", msg);
    }
    CHECK(fixture_count_entries(dir) == 0);
    hr_image_destroy(image);
}

static void check_refused_arguments(const char *dir)
{
    hr_image *image = fixture_image(ctx, 4, 4, 3, 0);
    char path[4096];
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "picture.tiff"));
    CHECK(hr_image_write(ctx, image, path, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(contains(hr_context_last_error(ctx), path));
    CHECK(contains(hr_context_last_error(ctx), ".png"));
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "no_extension"));
    CHECK(hr_image_write(ctx, image, path, NULL) == HR_ERROR_INVALID_ARGUMENT);

    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.png_bits = 12;
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "bits.png"));
    CHECK(hr_image_write(ctx, image, path, &o) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(contains(hr_context_last_error(ctx), "png_bits"));
    hr_image_write_options_default(&o);
    o.format = 42;
    CHECK(hr_image_write(ctx, image, path, &o) == HR_ERROR_INVALID_ARGUMENT);
    hr_image_write_options_default(&o);
    o.struct_size = 0;
    CHECK(hr_image_write(ctx, image, path, &o) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_image_write(ctx, NULL, path, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_image_write(ctx, image, NULL, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_image_write(ctx, image, "", NULL) == HR_ERROR_INVALID_ARGUMENT);
    fixture_format(path, sizeof path, "%s/", dir);
    o.format = HR_FORMAT_PNG;
    o.struct_size = sizeof o;
    CHECK(hr_image_write(ctx, image, path, &o) == HR_ERROR_IO);
    CHECK(fixture_count_entries(dir) == 0);
    hr_image_destroy(image);
}

/* libpng itself refuses a width over its limit of a million pixels: the
 * error comes through png_error and longjmp, mid-header. */
static void check_libpng_error(const char *dir)
{
    hr_image *image = NULL;
    CHECK_OK(hr_image_create(ctx, 1000001, 1, 3, &image));
    char path[4096];
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "wide.png"));
    write_marker(path);
    CHECK(hr_image_write(ctx, image, path, NULL) == HR_ERROR_IO);
    const char *msg = hr_context_last_error(ctx);
    CHECK_MSG(contains(msg, path) && contains(msg, "libpng"), "unclear message: %s", msg);
    CHECK(has_marker(path));
    CHECK(fixture_count_entries(dir) == 1);
    remove(path);
    hr_image_destroy(image);
}

/* Writes that fail part way through, for every format. */
static void check_disk_full(const char *dir)
{
    hr_image *image = noise_image(160, 120);
    struct rlimit saved;
    CHECK(getrlimit(RLIMIT_FSIZE, &saved) == 0);
    /* Past the limit write() fails with EFBIG instead of killing us. */
    signal(SIGXFSZ, SIG_IGN);
    for (int i = 0; i < 4; i++) {
        char path[4096];
        fixture_format(path, sizeof path, "%s/full.%s", dir, extensions[i]);
        write_marker(path);
        struct rlimit small = saved;
        small.rlim_cur = 4096;
        CHECK(setrlimit(RLIMIT_FSIZE, &small) == 0);
        hr_status st = hr_image_write(ctx, image, path, NULL);
        CHECK(setrlimit(RLIMIT_FSIZE, &saved) == 0);
        CHECK_MSG(st == HR_ERROR_IO, "%s: status %d", extensions[i], (int)st);
        const char *msg = hr_context_last_error(ctx);
        CHECK_MSG(contains(msg, path), "%s: message does not name the file: %s", extensions[i], msg);
        CHECK_MSG(contains(msg, strerror(EFBIG)) || contains(msg, "rite"), "%s: no reason given: %s",
                  extensions[i], msg);
        CHECK_MSG(has_marker(path), "%s: the old file was touched", extensions[i]);
        CHECK_MSG(fixture_count_entries(dir) == 1, "%s: %d files left", extensions[i], fixture_count_entries(dir));
        remove(path);
    }
    signal(SIGXFSZ, SIG_DFL);
    /* With the limit lifted the same writes succeed. */
    for (int i = 0; i < 4; i++) {
        char path[4096];
        fixture_format(path, sizeof path, "%s/full.%s", dir, extensions[i]);
        CHECK_OK(hr_image_write(ctx, image, path, NULL));
    }
    CHECK(fixture_count_entries(dir) == 4);
    for (int i = 0; i < 4; i++) {
        char path[4096];
        fixture_format(path, sizeof path, "%s/full.%s", dir, extensions[i]);
        remove(path);
    }
    hr_image_destroy(image);
}

/* The rename itself fails when the target is a directory. */
static void check_target_is_directory(const char *dir)
{
    hr_image *image = fixture_image(ctx, 4, 4, 3, 0);
    char sub[4096];
    fixture_format(sub, sizeof sub, "%s", fixture_path(dir, "subdir.png"));
    CHECK(mkdir(sub, 0777) == 0);
    CHECK(hr_image_write(ctx, image, sub, NULL) == HR_ERROR_IO);
    CHECK(contains(hr_context_last_error(ctx), sub));
    struct stat st;
    CHECK(stat(sub, &st) == 0 && S_ISDIR(st.st_mode));
    CHECK(fixture_count_entries(dir) == 1);
    rmdir(sub);
    hr_image_destroy(image);
}

/* A replaced file keeps its permissions; a new one gets 0666 less umask,
 * as fopen would have made it (not mkstemp's 0600). */
static void check_permissions(const char *dir)
{
    hr_image *image = fixture_image(ctx, 4, 4, 3, 0);
    char path[4096];
    fixture_format(path, sizeof path, "%s", fixture_path(dir, "mode.ppm"));
    mode_t old_mask = umask(022);
    CHECK_OK(hr_image_write(ctx, image, path, NULL));
    struct stat st;
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0644);
    CHECK(chmod(path, 0640) == 0);
    CHECK_OK(hr_image_write(ctx, image, path, NULL));
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0640);
    umask(old_mask);
    remove(path);
    hr_image_destroy(image);
}

/* A name the filesystem accepts (up to 255 bytes) must be writable: the
 * temporary file beside it may not need a longer name than the target. */
static void check_longest_name(const char *dir)
{
    hr_image *image = fixture_image(ctx, 4, 4, 3, 0);
    char name[256];
    memset(name, 'n', 251);
    memcpy(name + 251, ".png", 5); /* 255 bytes, NAME_MAX on Linux */
    char path[4096];
    fixture_format(path, sizeof path, "%s", fixture_path(dir, name));
    hr_status st = hr_image_write(ctx, image, path, NULL);
    CHECK_MSG(st == HR_OK, "a 255-byte name: %s", hr_context_last_error(ctx));
    fixture_png png;
    if (st == HR_OK && fixture_read_png(path, &png) == 0) {
        CHECK(png.width == 4 && png.height == 4);
        free(png.samples);
    }
    CHECK(fixture_count_entries(dir) == (st == HR_OK ? 1 : 0));
    remove(path);
    hr_image_destroy(image);
}

/* A target that is a symbolic link is written through: the file it points
 * to gets the image, the link stays a link. */
static void check_symlink_target(const char *dir)
{
    hr_image *image = fixture_image(ctx, 4, 4, 3, 0);
    char real[4096], link_path[4096];
    fixture_format(real, sizeof real, "%s", fixture_path(dir, "real.png"));
    fixture_format(link_path, sizeof link_path, "%s", fixture_path(dir, "link.png"));
    FILE *f = fopen(real, "wb");
    CHECK(f != NULL);
    if (f) fclose(f);
    CHECK(symlink("real.png", link_path) == 0);
    CHECK_OK(hr_image_write(ctx, image, link_path, NULL));
    struct stat st;
    CHECK(lstat(link_path, &st) == 0 && S_ISLNK(st.st_mode));
    CHECK(stat(real, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0);
    fixture_png png;
    if (fixture_read_png(real, &png) == 0) {
        CHECK(png.width == 4 && png.height == 4);
        free(png.samples);
    } else {
        CHECK_MSG(0, "the linked-to file is not the PNG");
    }
    CHECK(fixture_count_entries(dir) == 2); /* the link and its file, no temporary */
    remove(link_path);
    remove(real);
    hr_image_destroy(image);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    char dir[4096];
    fixture_format(dir, sizeof dir, "%s", fixture_dir("failures"));
    check_missing_directory(dir);
    check_refused_arguments(dir);
    check_libpng_error(dir);
    check_disk_full(dir);
    check_target_is_directory(dir);
    check_permissions(dir);
    check_longest_name(dir);
    check_symlink_target(dir);
    CHECK(fixture_count_entries(dir) == 0);
    hr_context_destroy(ctx);
    return hr_test_end();
}
