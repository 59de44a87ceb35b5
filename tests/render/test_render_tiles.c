/* The per-tile callback (hr_render_options.tile_done): over a render that
 * runs to the end, the reported rectangles cover every pixel of the output
 * image exactly once, and the pixels read in each call are the returned
 * image's bits (so none is written after its tile is reported), for 1 to 4
 * threads, tiles of 1, 7 and 32 pixels, samples, Hill's blocks, adaptive
 * supersampling and windows (rectangles in the window's image). The
 * callback changes nothing in the image; no progress fraction counts a tile
 * whose call has not returned; a caller whose struct_size ends before
 * tile_done gets no calls; a cancelled render reports only finished tiles,
 * each already final. Calls come from several threads at once, so the
 * collector takes a lock (and the ThreadSanitizer run checks that hr_render
 * needs no more of its caller). */
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

#define W 45
#define H 31

static hr_context *ctx;
static hr_scene *scene;

/* What the calls of one render saw. Written from the render's threads, so
 * under `lock`; read by the test after hr_render has returned. */
typedef struct collector {
    pthread_mutex_t lock;
    int32_t width, height; /* the output image's */
    int32_t tile_size;     /* the rectangles' largest side */
    int32_t *covered;      /* per pixel: how many rectangles held it */
    float *seen;           /* per pixel: the values read in its call */
    int64_t calls;
    int64_t bad_rects;     /* outside the image, empty, or larger than a tile */
    int64_t bad_strides;   /* row_stride not 3 x the width */
    int64_t early_fractions; /* progress counted a tile not yet reported */
    int64_t tile_count;
    int32_t cancel_after;  /* > 0: raise `cancel` at this many calls */
    int32_t *cancel;
} collector;

static void collector_init(collector *c, int32_t width, int32_t height, int32_t tile_size)
{
    memset(c, 0, sizeof *c);
    pthread_mutex_init(&c->lock, NULL);
    c->width = width, c->height = height, c->tile_size = tile_size;
    c->covered = calloc((size_t)width * height, sizeof *c->covered);
    c->seen = calloc((size_t)width * height * 3, sizeof *c->seen);
    c->tile_count = (int64_t)((width + tile_size - 1) / tile_size) * ((height + tile_size - 1) / tile_size);
    CHECK(c->covered && c->seen);
}

static void collector_free(collector *c)
{
    free(c->covered);
    free(c->seen);
    pthread_mutex_destroy(&c->lock);
}

static void on_tile(void *user, int32_t x, int32_t y, int32_t width, int32_t height, const float *pixels,
                    int32_t row_stride)
{
    collector *c = user;
    pthread_mutex_lock(&c->lock);
    c->calls++;
    if (row_stride != 3 * c->width) c->bad_strides++;
    if (x < 0 || y < 0 || width < 1 || height < 1 || width > c->tile_size || height > c->tile_size ||
        x + width > c->width || y + height > c->height) {
        c->bad_rects++;
    } else {
        for (int32_t row = 0; row < height; row++)
            for (int32_t col = 0; col < width; col++) {
                size_t at = (size_t)(y + row) * c->width + (size_t)(x + col);
                c->covered[at]++;
                memcpy(&c->seen[3 * at], &pixels[(size_t)row * row_stride + 3 * (size_t)col], 3 * sizeof(float));
            }
    }
    if (c->cancel_after > 0 && c->calls == c->cancel_after) __atomic_store_n(c->cancel, 1, __ATOMIC_RELAXED);
    pthread_mutex_unlock(&c->lock);
}

/* Every fraction is tiles done / tiles: never more than were reported. */
static int32_t on_progress(void *user, double fraction)
{
    collector *c = user;
    pthread_mutex_lock(&c->lock);
    if (fraction * (double)c->tile_count > (double)c->calls + 1e-9) c->early_fractions++;
    pthread_mutex_unlock(&c->lock);
    return 0;
}

static hr_status render(const hr_render_options *o, hr_image **img)
{
    hr_camera cam = tb_mirror_glass_view(W, H);
    *img = NULL;
    return hr_render(scene, &cam, o, img, NULL);
}

typedef struct option_set {
    const char *name;
    int32_t spp, block;
    double adaptive;
    int32_t win_x, win_y, win_w, win_h; /* all 0: the whole image */
} option_set;

static const option_set sets[] = {
    {"one ray a pixel", 1, 1, 0.0, 0, 0, 0, 0},
    {"spp 4", 4, 1, 0.0, 0, 0, 0, 0},
    {"blocks of 3", 1, 3, 0.0, 0, 0, 0, 0},
    {"blocks of 8, spp 2", 2, 8, 0.0, 0, 0, 0, 0},
    {"adaptive", 4, 1, 0.05, 0, 0, 0, 0},
    {"window", 1, 1, 0.0, 10, 4, 20, 9},
    {"window, blocks of 4", 1, 4, 0.0, 3, 5, 33, 26},
    {"window, adaptive", 4, 1, 0.02, 7, 0, 38, 17},
};

/* One render with the callback against the same render without it. */
static void check_coverage(const option_set *s, int32_t threads, int32_t tile)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.samples_per_pixel = s->spp, o.block_size = s->block, o.adaptive_threshold = s->adaptive;
    o.window_x = s->win_x, o.window_y = s->win_y, o.window_width = s->win_w, o.window_height = s->win_h;
    o.threads = threads, o.tile_size = tile;
    hr_image *plain;
    CHECK_OK(render(&o, &plain));
    if (!plain) return;
    int32_t ow = hr_image_width(plain), oh = hr_image_height(plain);
    collector c;
    collector_init(&c, ow, oh, tile);
    o.tile_done = on_tile, o.tile_user = &c;
    o.progress = on_progress, o.progress_user = &c;
    hr_image *img;
    CHECK_OK(render(&o, &img));
    if (img && c.covered && c.seen) {
        size_t n = (size_t)ow * oh;
        int64_t uncovered = 0, twice = 0, differ = 0;
        for (size_t i = 0; i < n; i++) uncovered += c.covered[i] == 0, twice += c.covered[i] > 1;
        const float *final = hr_image_data(img);
        for (size_t i = 0; i < n; i++) differ += memcmp(&c.seen[3 * i], &final[3 * i], 3 * sizeof(float)) != 0;
        CHECK_MSG(uncovered == 0 && twice == 0 && c.bad_rects == 0 && c.bad_strides == 0,
                  "%s, %d threads, tiles of %d: %lld pixels never reported, %lld more than once, %lld bad "
                  "rectangles, %lld bad strides",
                  s->name, (int)threads, (int)tile, (long long)uncovered, (long long)twice, (long long)c.bad_rects,
                  (long long)c.bad_strides);
        CHECK_MSG(c.calls == c.tile_count, "%s, %d threads, tiles of %d: %lld calls for %lld tiles", s->name,
                  (int)threads, (int)tile, (long long)c.calls, (long long)c.tile_count);
        CHECK_MSG(differ == 0, "%s, %d threads, tiles of %d: %lld pixels seen in the callback differ from the image",
                  s->name, (int)threads, (int)tile, (long long)differ);
        CHECK_MSG(memcmp(final, hr_image_data(plain), 3 * n * sizeof(float)) == 0,
                  "%s, %d threads, tiles of %d: the callback changed the image", s->name, (int)threads, (int)tile);
        CHECK_MSG(c.early_fractions == 0, "%s, %d threads, tiles of %d: %lld progress fractions ran ahead of the "
                  "tiles reported", s->name, (int)threads, (int)tile, (long long)c.early_fractions);
    }
    hr_image_destroy(img);
    hr_image_destroy(plain);
    collector_free(&c);
}

static void test_coverage(void)
{
    static const int32_t tiles[] = {1, 7, 32};
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++)
        for (int32_t threads = 1; threads <= 4; threads++)
            for (size_t t = 0; t < sizeof tiles / sizeof tiles[0]; t++) check_coverage(&sets[i], threads, tiles[t]);
}

/* A caller built before the callback: its struct ends at the window, and
 * whatever lies past it is not read. */
static void test_old_struct_size(void)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.struct_size = (uint32_t)offsetof(hr_render_options, tile_done);
    collector c;
    collector_init(&c, W, H, 32);
    o.tile_done = on_tile, o.tile_user = &c;
    hr_image *img;
    CHECK_OK(render(&o, &img));
    CHECK(img != NULL);
    CHECK_MSG(c.calls == 0, "an old caller's render made %lld tile calls", (long long)c.calls);
    hr_image_destroy(img);
    collector_free(&c);
}

/* Cancelled from the first tile's call while the other threads are inside
 * theirs (64 samples a pixel): the render is cancelled, and what was
 * reported is final, the full render's bits. A tile cut short has pixels
 * that lack samples (dark), so reporting one fails the comparison. */
static void test_cancelled(void)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.samples_per_pixel = 64, o.tile_size = 7, o.threads = 4;
    hr_image *full;
    CHECK_OK(render(&o, &full));
    if (!full) return;
    for (int32_t after = 1; after <= 3; after++) {
        int32_t cancel = 0;
        collector c;
        collector_init(&c, W, H, 7);
        c.cancel_after = after, c.cancel = &cancel;
        o.tile_done = on_tile, o.tile_user = &c, o.cancel = &cancel;
        hr_image *img;
        hr_status st = render(&o, &img);
        CHECK_MSG(st == HR_ERROR_CANCELLED && img == NULL, "cancelled at call %d: status %d", (int)after, (int)st);
        hr_image_destroy(img);
        const float *want = hr_image_data(full);
        int64_t reported = 0, wrong = 0, twice = 0;
        for (size_t i = 0; i < (size_t)W * H; i++) {
            if (!c.covered[i]) continue;
            reported++;
            twice += c.covered[i] > 1;
            wrong += memcmp(&c.seen[3 * i], &want[3 * i], 3 * sizeof(float)) != 0;
        }
        CHECK_MSG(c.calls >= after && reported < (int64_t)W * H,
                  "cancelled at call %d: %lld calls, %lld pixels reported", (int)after, (long long)c.calls,
                  (long long)reported);
        CHECK_MSG(wrong == 0 && twice == 0 && c.bad_rects == 0,
                  "cancelled at call %d: %lld reported pixels are not final, %lld reported twice", (int)after,
                  (long long)wrong, (long long)twice);
        collector_free(&c);
    }
    hr_image_destroy(full);
}

/* The progress callback, asked every 65536 rays inside a tile, cancels at
 * its first call: by the flag it returns, or by raising the caller's
 * `cancel` flag. */
typedef struct cancelling {
    int32_t *flag; /* NULL: cancel by returning 1 */
} cancelling;

static int32_t cancel_now(void *user, double fraction)
{
    (void)fraction;
    cancelling *k = user;
    if (!k->flag) return 1;
    __atomic_store_n(k->flag, 1, __ATOMIC_RELAXED);
    return 0;
}

/* Tiles of 32 at 256 samples: every tile needs more than 65536 camera
 * rays, so the first thread to be asked for progress is inside its first
 * tile, and so is every other thread (none can have finished one without
 * being asked first). Every tile is cut short, and none may be reported. */
static void test_cancelled_inside_every_tile(void)
{
    for (int by_flag = 0; by_flag <= 1; by_flag++)
        for (int32_t threads = 1; threads <= 2; threads++) {
            int32_t flag = 0;
            cancelling k = {by_flag ? &flag : NULL};
            hr_render_options o;
            hr_render_options_default(&o);
            o.samples_per_pixel = 256, o.tile_size = 32, o.threads = threads;
            o.progress = cancel_now, o.progress_user = &k, o.cancel = &flag;
            collector c;
            collector_init(&c, W, H, 32);
            o.tile_done = on_tile, o.tile_user = &c;
            hr_image *img;
            hr_status st = render(&o, &img);
            CHECK_MSG(st == HR_ERROR_CANCELLED && img == NULL, "cancelled by %s, %d threads: status %d",
                      by_flag ? "the flag" : "progress", (int)threads, (int)st);
            hr_image_destroy(img);
            CHECK_MSG(c.calls == 0, "cancelled by %s inside every tile, %d threads: %lld tiles reported",
                      by_flag ? "the flag" : "progress", (int)threads, (long long)c.calls);
            collector_free(&c);
        }
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    scene = tb_mirror_glass_scene(ctx);
    if (!scene) return hr_test_end();
    test_coverage();
    test_old_struct_size();
    test_cancelled();
    test_cancelled_inside_every_tile();
    hr_scene_destroy(scene);
    hr_context_destroy(ctx);
    return hr_test_end();
}
