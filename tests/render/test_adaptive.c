/* Adaptive supersampling: every pixel corner sampled once, a pixel whose
 * corners differ by more than the threshold (display space) given the full
 * pattern. The test recomputes every decision from corner samples it shades
 * itself and demands each pixel be exactly the full render's value or
 * exactly the mean of its corners, as decided; the image must not depend on
 * the thread count or the tile size. */
#include <math.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

#define W 45
#define H 31
#define SPP 4

static hr_context *ctx;

/* A mirror floor, a glass ball, a matte ball, one light: edges, shadows and
 * reflections for the threshold to find. */
static hr_scene *scene(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    tb_add_mirror_glass_set(s, 1);
    tb_light(s, 5, 8, 6, 1, 1, 1);
    hr_scene_commit(s);
    return s;
}

static hr_camera view(void)
{
    return tb_mirror_glass_view(W, H);
}

static hr_image *render(hr_scene *s, const hr_render_options *o, hr_render_stats *st)
{
    hr_camera c = view();
    hr_image *img = NULL;
    memset(st, 0, sizeof *st);
    st->struct_size = sizeof *st;
    hr_status status = hr_render(s, &c, o, &img, st);
    CHECK_MSG(status == HR_OK, "render: %s", hr_context_last_error(ctx));
    return img;
}

/* The documented measure, written out independently: sRGB (IEC 61966-2-1)
 * of the value clamped to [0, 1]. */
static double shown(double v)
{
    v = v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0;
    if (v == 1.0) return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

static hr_color corner(hr_scene *s, int32_t x, int32_t y)
{
    hr_camera c = view();
    hr_ray r;
    hr_camera_ray(&c, x, y, &r);
    hr_color col;
    CHECK_OK(hr_scene_shade(s, &r, -1, &col));
    return col;
}

static int differ(const hr_color q[4], double threshold)
{
    for (int ch = 0; ch < 3; ch++) {
        double lo = 2, hi = -1;
        for (int k = 0; k < 4; k++) {
            const double v = shown(ch == 0 ? q[k].r : ch == 1 ? q[k].g : q[k].b);
            lo = fmin(lo, v), hi = fmax(hi, v);
        }
        if (hi - lo > threshold) return 1;
    }
    return 0;
}

static void decisions(double threshold)
{
    hr_scene *s = scene();
    hr_render_options o;
    hr_render_options_default(&o);
    o.samples_per_pixel = SPP;
    o.threads = 2;
    hr_render_stats full_st, st;
    hr_image *full = render(s, &o, &full_st);
    o.adaptive_threshold = threshold;
    o.tile_size = 8;
    hr_image *img = render(s, &o, &st);
    const float *f = hr_image_data(full), *p = hr_image_data(img);
    /* The corner lattice, (W + 1) x (H + 1). */
    static hr_color corners[(W + 1) * (H + 1)];
    for (int32_t y = 0; y <= H; y++)
        for (int32_t x = 0; x <= W; x++) corners[y * (W + 1) + x] = corner(s, x, y);
    uint64_t refined = 0;
    int wrong = 0;
    for (int32_t y = 0; y < H; y++)
        for (int32_t x = 0; x < W; x++) {
            const hr_color q[4] = {corners[y * (W + 1) + x], corners[y * (W + 1) + x + 1],
                                   corners[(y + 1) * (W + 1) + x], corners[(y + 1) * (W + 1) + x + 1]};
            const float *got = p + 3 * (y * W + x);
            float want[3];
            if (differ(q, threshold)) {
                refined++;
                memcpy(want, f + 3 * (y * W + x), sizeof want);
            } else {
                /* The renderer's order: (a + b) + (c + d), then / 4. */
                want[0] = (float)(((q[0].r + q[1].r) + (q[2].r + q[3].r)) / 4);
                want[1] = (float)(((q[0].g + q[1].g) + (q[2].g + q[3].g)) / 4);
                want[2] = (float)(((q[0].b + q[1].b) + (q[2].b + q[3].b)) / 4);
            }
            wrong += memcmp(got, want, sizeof want) != 0;
        }
    CHECK_MSG(wrong == 0, "threshold %g: %d pixels are neither their decision's value", threshold, wrong);
    CHECK_MSG(st.pixels_refined == refined, "threshold %g: %llu refined, expected %llu", threshold,
              (unsigned long long)st.pixels_refined, (unsigned long long)refined);
    /* Camera rays: each 8x8 tile samples its (w + 1) x (h + 1) corners
     * (those on a border twice over the image), plus SPP per refined pixel. */
    uint64_t corner_rays = 0;
    for (int32_t ty = 0; ty < H; ty += 8)
        for (int32_t tx = 0; tx < W; tx += 8) {
            int32_t tw = W - tx < 8 ? W - tx : 8, th = H - ty < 8 ? H - ty : 8;
            corner_rays += (uint64_t)(tw + 1) * (uint64_t)(th + 1);
        }
    CHECK(st.primary == corner_rays + SPP * refined);
    CHECK(st.samples_saved == (int64_t)W * H * SPP - (int64_t)st.primary);
    CHECK(full_st.samples_saved == 0 && full_st.pixels_refined == 0);
    CHECK(st.effects & HR_EFFECT_SUPERSAMPLING);
    if (threshold >= 1) CHECK(refined == 0);
    if (threshold > 0 && threshold < 0.1) CHECK(refined > 0 && refined < (uint64_t)W * H);
    hr_image_destroy(full);
    hr_image_destroy(img);
    hr_scene_destroy(s);
}

/* Threads and tiles change who samples a border corner, never its value. */
static void independent_of_threads_and_tiles(void)
{
    hr_scene *s = scene();
    hr_render_options o;
    hr_render_options_default(&o);
    o.samples_per_pixel = SPP;
    o.adaptive_threshold = 0.03;
    const int32_t threads[] = {1, 2, 3, 2};
    const int32_t tiles[] = {32, 7, 1, 13};
    hr_image *first = NULL;
    uint64_t refined = 0;
    for (int i = 0; i < 4; i++) {
        o.threads = threads[i];
        o.tile_size = tiles[i];
        hr_render_stats st;
        hr_image *img = render(s, &o, &st);
        if (i == 0) {
            first = img;
            refined = st.pixels_refined;
            continue;
        }
        CHECK_MSG(memcmp(hr_image_data(first), hr_image_data(img), W * H * 3 * sizeof(float)) == 0,
                  "%d threads, tiles of %d: a different image", (int)threads[i], (int)tiles[i]);
        CHECK(st.pixels_refined == refined);
        hr_image_destroy(img);
    }
    hr_image_destroy(first);
    hr_scene_destroy(s);
}

static void refusals(void)
{
    hr_scene *s = scene();
    hr_camera c = view();
    hr_render_options o;
    hr_render_options_default(&o);
    o.adaptive_threshold = 0.1;
    hr_image *img = NULL;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT); /* 1 sample per pixel */
    CHECK(strstr(hr_context_last_error(ctx), "samples per pixel >= 2") != NULL);
    o.samples_per_pixel = 4;
    o.block_size = 2;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "block size") != NULL);
    o.block_size = 1;
    const double bad[] = {-0.01, 1.5, NAN, INFINITY};
    for (int i = 0; i < 4; i++) {
        o.adaptive_threshold = bad[i];
        CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
        CHECK(strstr(hr_context_last_error(ctx), "adaptive threshold") != NULL);
    }
    CHECK(img == NULL);
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    decisions(0.02);
    decisions(0.2);
    decisions(1.0);
    independent_of_threads_and_tiles();
    refusals();
    hr_context_destroy(ctx);
    return hr_test_end();
}
