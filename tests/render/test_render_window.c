/* The render window: a rectangle of the image rendered alone is, pixel for
 * pixel, the same bits as that rectangle of the full render, for every
 * option that places samples (samples per pixel, adaptive corners, Hill's
 * blocks, depth, tile size). Each option set's frame is tiled several ways
 * (tiles of 1 pixel, of 17, of sizes prime to the block size, windows cut
 * at random) and every window compared with memcmp, so one changed bit
 * fails. The window's statistics count its own rays; bad windows are
 * refused naming what is wrong; an older caller's options (struct_size
 * ending before the window) render the whole image. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "random_rays.h"
#include "scene_builder.h"

#define W 45
#define H 31

static hr_context *ctx;
static hr_scene *scene;

static hr_image *render(const hr_render_options *o, hr_render_stats *st)
{
    hr_camera c = tb_mirror_glass_view(W, H);
    hr_image *img = NULL;
    hr_render_stats local;
    if (!st) st = &local;
    memset(st, 0, sizeof *st);
    st->struct_size = sizeof *st;
    hr_status status = hr_render(scene, &c, o, &img, st);
    CHECK_MSG(status == HR_OK, "render: %s", hr_context_last_error(ctx));
    return img;
}

/* Does `win`, rendered at (x, y), hold the same bits as that part of `full`? */
static int same_as_full(hr_image *full, hr_image *win, int32_t x, int32_t y)
{
    int32_t ww = hr_image_width(win), wh = hr_image_height(win);
    const float *f = hr_image_data(full), *p = hr_image_data(win);
    for (int32_t row = 0; row < wh; row++)
        if (memcmp(&f[3 * ((size_t)(y + row) * W + x)], &p[3 * (size_t)row * ww], 3 * sizeof(float) * ww))
            return 0;
    return 1;
}

/* Render `o` through the window (x, y, w, h) and compare it with `full`. */
static int window_matches(hr_render_options o, hr_image *full, int32_t x, int32_t y, int32_t w, int32_t h,
                          hr_render_stats *st)
{
    o.window_x = x, o.window_y = y, o.window_width = w, o.window_height = h;
    hr_image *win = render(&o, st);
    if (!win) return 0;
    int ok = hr_image_width(win) == w && hr_image_height(win) == h && same_as_full(full, win, x, y);
    hr_image_destroy(win);
    return ok;
}

/* Tile the frame into windows of tw x th (the last row and column cut by
 * the image's edge) and compare each. */
static void check_tiling(const char *what, const hr_render_options *o, hr_image *full, int32_t tw, int32_t th)
{
    int bad = 0;
    for (int32_t y = 0; y < H; y += th)
        for (int32_t x = 0; x < W; x += tw) {
            int32_t w = tw < W - x ? tw : W - x, h = th < H - y ? th : H - y;
            if (!window_matches(*o, full, x, y, w, h, NULL)) bad++;
        }
    CHECK_MSG(bad == 0, "%s: %d windows of %dx%d differ from the full render", what, bad, (int)tw, (int)th);
}

/* Windows with random corners (a fixed seed, so a failure repeats). */
static void check_random_windows(const char *what, const hr_render_options *o, hr_image *full, int count)
{
    ray_rng rng;
    rng_seed(&rng, 14);
    for (int i = 0; i < count; i++) {
        int32_t x = (int32_t)(rng_next(&rng) % W), y = (int32_t)(rng_next(&rng) % H);
        int32_t w = 1 + (int32_t)(rng_next(&rng) % (uint64_t)(W - x));
        int32_t h = 1 + (int32_t)(rng_next(&rng) % (uint64_t)(H - y));
        CHECK_MSG(window_matches(*o, full, x, y, w, h, NULL), "%s: window %dx%d at (%d, %d) differs", what,
                  (int)w, (int)h, (int)x, (int)y);
    }
}

typedef struct option_set {
    const char *name;
    int32_t spp, block, depth, tile, threads;
    double adaptive;
    int one_pixel_tiles; /* also tile by single pixels (costly: one render each) */
} option_set;

static void test_tilings(void)
{
    static const option_set sets[] = {
        {"spp 1", 1, 1, -1, 0, 2, 0.0, 1},
        {"spp 16", 16, 1, -1, 0, 2, 0.0, 0},
        {"adaptive", 4, 1, -1, 0, 2, 0.02, 1},
        {"adaptive, tiles of 5", 16, 1, -1, 5, 1, 0.05, 0},
        {"block 3", 1, 3, -1, 0, 2, 0.0, 1},
        {"block 4, spp 2, tiles of 6", 2, 4, -1, 6, 2, 0.0, 0},
        {"depth 0", 2, 1, 0, 0, 1, 0.0, 0},
        {"depth 2, tiles of 1", 1, 1, 2, 1, 2, 0.0, 0},
    };
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        const option_set *s = &sets[i];
        hr_render_options o;
        hr_render_options_default(&o);
        o.samples_per_pixel = s->spp, o.block_size = s->block, o.max_depth = s->depth;
        o.tile_size = s->tile, o.threads = s->threads, o.adaptive_threshold = s->adaptive;
        hr_image *full = render(&o, NULL);
        if (!full) continue;
        /* A window of the whole image is the whole image. */
        CHECK_MSG(window_matches(o, full, 0, 0, W, H, NULL), "%s: the full window differs", s->name);
        check_tiling(s->name, &o, full, 17, 17);
        check_tiling(s->name, &o, full, 7, 5); /* prime to every block size above */
        check_tiling(s->name, &o, full, W, 1); /* rows */
        check_tiling(s->name, &o, full, 1, H); /* columns */
        check_tiling(s->name, &o, full, 64, 64);
        if (s->one_pixel_tiles) check_tiling(s->name, &o, full, 1, 1);
        check_random_windows(s->name, &o, full, 12);
        hr_image_destroy(full);
    }
}

/* A window's statistics are its own rays: without adaptive or blocks every
 * pixel casts spp camera rays, so the windows of a tiling cast exactly what
 * the full render casts; adaptive's samples saved are counted on the
 * window's pixels. */
static void test_stats(void)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.samples_per_pixel = 4;
    hr_render_stats st;
    hr_image *full = render(&o, &st);
    if (!full) return;
    uint64_t full_primary = st.primary, sum = 0;
    for (int32_t y = 0; y < H; y += 17)
        for (int32_t x = 0; x < W; x += 17) {
            int32_t w = 17 < W - x ? 17 : W - x, h = 17 < H - y ? 17 : H - y;
            CHECK(window_matches(o, full, x, y, w, h, &st));
            CHECK_MSG(st.primary == (uint64_t)w * h * 4, "window at (%d, %d): %llu camera rays", (int)x, (int)y,
                      (unsigned long long)st.primary);
            sum += st.primary;
        }
    CHECK_MSG(sum == full_primary, "the windows cast %llu camera rays, the full render %llu",
              (unsigned long long)sum, (unsigned long long)full_primary);
    hr_image_destroy(full);

    o.adaptive_threshold = 0.05;
    o.window_x = 10, o.window_y = 4, o.window_width = 20, o.window_height = 9;
    hr_image *win = render(&o, &st);
    if (win) {
        /* 21 x 10 corners, then spp for each refined pixel. */
        CHECK(st.primary == 21u * 10u + 4u * st.pixels_refined);
        CHECK(st.samples_saved == (int64_t)20 * 9 * 4 - (int64_t)st.primary);
        CHECK(st.pixels_refined <= 20u * 9u);
        hr_image_destroy(win);
    }
}

/* Width or height 0: to the image's edge. */
static void test_to_the_edge(void)
{
    hr_render_options o;
    hr_render_options_default(&o);
    hr_image *full = render(&o, NULL);
    if (!full) return;
    o.window_x = 30, o.window_y = 20;
    hr_image *win = render(&o, NULL);
    if (win) {
        CHECK(hr_image_width(win) == W - 30 && hr_image_height(win) == H - 20);
        CHECK(same_as_full(full, win, 30, 20));
        hr_image_destroy(win);
    }
    o.window_x = 0, o.window_y = 0, o.window_height = 3;
    win = render(&o, NULL);
    if (win) {
        CHECK(hr_image_width(win) == W && hr_image_height(win) == 3);
        CHECK(same_as_full(full, win, 0, 0));
        hr_image_destroy(win);
    }
    /* A caller built before the window: its struct ends at `cancel`, and
     * whatever lies past it is not read. */
    hr_render_options old;
    hr_render_options_default(&old);
    old.struct_size = (uint32_t)offsetof(hr_render_options, window_x);
    old.window_x = 5, old.window_width = -3;
    win = render(&old, NULL);
    if (win) {
        CHECK(hr_image_width(win) == W && hr_image_height(win) == H);
        CHECK(same_as_full(full, win, 0, 0));
        hr_image_destroy(win);
    }
    hr_image_destroy(full);
}

static void refused(int32_t x, int32_t y, int32_t w, int32_t h, const char *words)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.window_x = x, o.window_y = y, o.window_width = w, o.window_height = h;
    hr_camera c = tb_mirror_glass_view(W, H);
    hr_image *img = (hr_image *)&o; /* must be set to NULL */
    hr_status st = hr_render(scene, &c, &o, &img, NULL);
    const char *msg = hr_context_last_error(ctx);
    CHECK_MSG(st == HR_ERROR_INVALID_ARGUMENT && img == NULL && strstr(msg, words),
              "window %d,%d %dx%d: status %d, '%s' (expected '%s')", (int)x, (int)y, (int)w, (int)h, (int)st, msg,
              words);
}

static void test_bad_windows(void)
{
    refused(-1, 0, 4, 4, "window x -1, y 0, width 4, height 4 must not be negative");
    refused(0, 0, -4, 4, "must not be negative");
    refused(W, 0, 1, 1, "window origin (45, 0) lies outside the 45x31 image");
    refused(0, H, 0, 0, "lies outside");
    refused(40, 0, 6, 1, "window 6x1 at (40, 0) reaches past the 45x31 image");
    refused(0, 30, 1, 2, "reaches past");
    refused(1, 1, INT32_MAX, INT32_MAX, "reaches past"); /* no overflow on the way */
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    scene = tb_mirror_glass_scene(ctx);
    if (!scene) return hr_test_end();
    test_tilings();
    test_stats();
    test_to_the_edge();
    test_bad_windows();
    hr_scene_destroy(scene);
    hr_context_destroy(ctx);
    return hr_test_end();
}
