/* What a pixmap's mip-map costs: its memory and the time to build it.
 *
 *   build/bench/mipmap_cost [IMAGE ...]   (default: scenes/textures/planet.png
 *                                          and made-up 1024^2 and 4096^2 images)
 *
 * For each image: the bytes of its texels (RGB floats) and of its mip
 * levels, and the time making the pixmap takes (checking and copying the
 * texels, then building the levels), against copying the texels alone; the
 * best of 5 runs. Made through the public API, as a scene's pixmap 1
 * (hr_scene_set_pixmap), so what is timed is what a scene pays. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <hitray/hitray.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The levels' bytes, by docs/textures.md's rule (each level halves both
 * sides, an odd side rounding up, down to 1 x 1; RGB floats), which the
 * library charges to the scene's memory budget; tests/texture/test_mipmap.c
 * checks the levels themselves. */
static unsigned long long mip_bytes(int32_t w, int32_t h)
{
    unsigned long long bytes = 0;
    while (w > 1 || h > 1) {
        w = w / 2 + (w & 1), h = h / 2 + (h & 1);
        bytes += (unsigned long long)w * (unsigned long long)h * 3 * sizeof(float);
    }
    return bytes;
}

static void measure(hr_context *ctx, const char *name, const hr_image *img)
{
    const int32_t w = hr_image_width(img), h = hr_image_height(img);
    double best_add = 1e300, best_copy = 1e300;
    const size_t floats = (size_t)w * (size_t)h * 3;
    float *copy = malloc(floats * sizeof *copy);
    if (!copy) return;
    for (int run = 0; run < 5; run++) {
        hr_scene *scene = NULL;
        if (hr_scene_create(ctx, &scene) != HR_OK) break;
        double t0 = now();
        if (hr_scene_set_pixmap(scene, 1, img) != HR_OK) {
            fprintf(stderr, "mipmap_cost: %s: %s\n", name, hr_context_last_error(ctx));
            hr_scene_destroy(scene);
            break;
        }
        double t1 = now();
        hr_scene_destroy(scene);
        const float *src = hr_image_data((hr_image *)img);
        const int32_t ch = hr_image_channels(img);
        double t2 = now();
        for (size_t p = 0; p < (size_t)w * (size_t)h; p++) memcpy(copy + 3 * p, src + (size_t)ch * p, 3 * sizeof *copy);
        double t3 = now();
        if (t1 - t0 < best_add) best_add = t1 - t0;
        if (t3 - t2 < best_copy) best_copy = t3 - t2;
    }
    free(copy);
    const unsigned long long texels = (unsigned long long)floats * sizeof(float);
    const unsigned long long mip = mip_bytes(w, h);
    printf("{\"image\": \"%s\", \"width\": %d, \"height\": %d, \"texel_bytes\": %llu, \"mip_bytes\": %llu, "
           "\"mip_share\": %.4f, \"add_ms\": %.3f, \"copy_ms\": %.3f}\n",
           name, (int)w, (int)h, texels, mip, (double)mip / (double)texels, 1e3 * best_add, 1e3 * best_copy);
}

int main(int argc, char **argv)
{
    hr_context *ctx = NULL;
    if (hr_context_create(&ctx) != HR_OK) return 1;
    if (argc > 1) {
        for (int i = 1; i < argc; i++) {
            hr_image *img = NULL;
            if (hr_image_read(ctx, argv[i], &img) != HR_OK) {
                fprintf(stderr, "mipmap_cost: %s\n", hr_context_last_error(ctx));
                return 1;
            }
            measure(ctx, argv[i], img);
            hr_image_destroy(img);
        }
    } else {
        hr_image *img = NULL;
        if (hr_image_read(ctx, "scenes/textures/planet.png", &img) == HR_OK) {
            measure(ctx, "scenes/textures/planet.png", img);
            hr_image_destroy(img);
        }
        const int32_t sides[] = {1024, 4096};
        for (int i = 0; i < 2; i++) {
            if (hr_image_create(ctx, sides[i], sides[i], 3, &img) != HR_OK) return 1;
            float *p = hr_image_data(img);
            for (size_t k = 0; k < (size_t)sides[i] * (size_t)sides[i] * 3; k++) p[k] = (float)(k % 251) / 251.0f;
            char name[64];
            snprintf(name, sizeof name, "made-up %dx%d", (int)sides[i], (int)sides[i]);
            measure(ctx, name, img);
            hr_image_destroy(img);
        }
    }
    hr_context_destroy(ctx);
    return 0;
}
