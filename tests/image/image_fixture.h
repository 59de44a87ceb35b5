/* Shared by the image tests: test pictures, scratch files, the reference sRGB
 * curve, and independent readers that load what the writers wrote. */
#ifndef HR_TEST_IMAGE_FIXTURE_H
#define HR_TEST_IMAGE_FIXTURE_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/hitray.h>

/* A width x height picture whose samples sweep [-0.25, 1.5] in steps that
 * are not multiples of a code value, plus a few edge samples: 0, 1, the
 * sRGB curve's knee 0.0031308, a tiny value and a large one. With `special`
 * the first pixel is NaN, -1, +inf (clamping cases). */
hr_image *fixture_image(hr_context *ctx, int32_t width, int32_t height, int32_t channels, int special);

/* The sRGB transfer function of a value clamped to [0, 1] (NaN: 0), in
 * double, written independently of lib/ as the reference. */
double fixture_srgb(double linear);

/* A fresh empty directory for one test: <build>/tests/scratch/<name>. */
const char *fixture_dir(const char *name);
/* printf into buf; a path too long for it fails the test run loudly
 * instead of being cut short. */
void fixture_format(char *buf, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* dir/file, in a static buffer that the next call overwrites. */
const char *fixture_path(const char *dir, const char *file);
/* Number of entries in dir (not . or ..); -1 if it cannot be read. */
int fixture_count_entries(const char *dir);
/* The whole file, malloc'd (NULL if missing); *size receives its length. */
unsigned char *fixture_read_file(const char *path, long *size);

/* A PNG as it is stored: samples (8 or 16 bit values, top row first). */
typedef struct fixture_png {
    int32_t width, height, channels, bits;
    int has_srgb;       /* an sRGB chunk */
    int has_gamma;      /* a gAMA chunk ... */
    double gamma;       /* ... and its value */
    uint16_t *samples;  /* width * height * channels */
} fixture_png;
/* 0 on success; the error goes to stderr. free(png->samples) when done. */
int fixture_read_png(const char *path, fixture_png *png);

/* An EXR read back through OpenEXRCore, every channel converted to float. */
typedef struct fixture_exr {
    int32_t width, height, channels; /* channels: R, G, B (, A) */
    int pixel_type;                  /* EXR_PIXEL_* of the channels */
    int compression;                 /* EXR_COMPRESSION_* */
    float *samples;                  /* interleaved RGB(A), top row first */
} fixture_exr;
int fixture_read_exr(const char *path, fixture_exr *exr);

#endif
