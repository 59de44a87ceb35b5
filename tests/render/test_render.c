/* The renderer: pixel centres, the same image whatever the thread count,
 * Hill's block size, supersampling, cancelling, and the ray statistics. */
#include <stdint.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

/* Mirror floor, glass ball, diffuse ball, two lights: every effect. */
static hr_scene *busy_scene(int with_mirror_and_glass)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    tb_add_mirror_glass_set(s, with_mirror_and_glass);
    tb_light(s, 5, 8, 6, 1, 1, 1);
    tb_light(s, -6, 4, 3, 0.3, 0.3, 0.4);
    hr_scene_commit(s);
    return s;
}

static hr_camera view(int32_t w, int32_t h)
{
    return tb_mirror_glass_view(w, h);
}

static hr_image *render(hr_scene *s, const hr_camera *c, hr_render_options *o, hr_render_stats *st)
{
    hr_image *img = NULL;
    hr_status status = hr_render(s, c, o, &img, st);
    CHECK_MSG(status == HR_OK, "render: %s", hr_context_last_error(ctx));
    /* A rendered image starts on a cache line too (image.h). */
    CHECK(!img || (uintptr_t)hr_image_data(img) % 64 == 0);
    return img;
}

static void centres_and_threads(void)
{
    hr_scene *s = busy_scene(1);
    hr_camera c = view(61, 37); /* odd sizes: partial tiles */
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    o.tile_size = 16;
    hr_render_stats st = {0};
    st.struct_size = sizeof st;
    hr_image *one = render(s, &c, &o, &st);
    CHECK(st.primary == 61u * 37u);
    CHECK(st.shadow > 0 && st.reflected > 0 && st.refracted > 0);
    CHECK(st.threads == 1);
    /* One sample per pixel: the ray through the pixel's centre, exactly,
     * at every pixel (the renderer works the camera's plane out by rows
     * and columns, hr_camera_ray per ray: the same bits). */
    const float *px = hr_image_data(one);
    int32_t wrong = 0;
    for (int32_t y = 0; y < 37; y++)
        for (int32_t x = 0; x < 61; x++) {
            hr_ray r;
            hr_camera_ray(&c, x + 0.5, y + 0.5, &r);
            hr_color want;
            CHECK_OK(hr_scene_shade(s, &r, -1, &want));
            const float *p = px + 3 * (y * 61 + x);
            wrong += !(p[0] == (float)want.r && p[1] == (float)want.g && p[2] == (float)want.b);
        }
    CHECK_MSG(wrong == 0, "%d pixels are not their centre ray's colour", (int)wrong);
    /* 2 and 3 threads, and supersampling with 2 threads against 1. */
    for (int threads = 2; threads <= 3; threads++) {
        o.threads = threads;
        hr_image *many = render(s, &c, &o, NULL);
        CHECK(many && memcmp(hr_image_data(one), hr_image_data(many), 61 * 37 * 3 * sizeof(float)) == 0);
        hr_image_destroy(many);
    }
    o.samples_per_pixel = 5;
    o.threads = 1;
    hr_image *ss1 = render(s, &c, &o, &st);
    CHECK(st.primary == 61u * 37u * 5u);
    CHECK(st.effects & HR_EFFECT_SUPERSAMPLING);
    o.threads = 2;
    hr_image *ss2 = render(s, &c, &o, NULL);
    CHECK(ss1 && ss2 && memcmp(hr_image_data(ss1), hr_image_data(ss2), 61 * 37 * 3 * sizeof(float)) == 0);
    hr_image_destroy(ss1);
    hr_image_destroy(ss2);
    hr_image_destroy(one);
    hr_scene_destroy(s);
}

/* Hill's block size: one ray per block, the block filled with it. */
static void blocks(void)
{
    hr_scene *s = busy_scene(0);
    hr_camera c = view(40, 30);
    hr_render_options o;
    hr_render_options_default(&o);
    o.block_size = 8;
    o.tile_size = 12; /* blocks straddle tiles */
    o.threads = 2;
    hr_render_stats st = {0};
    st.struct_size = sizeof st;
    hr_image *img = render(s, &c, &o, &st);
    const float *p = hr_image_data(img);
    int same = 1;
    for (int y = 0; y < 30; y++)
        for (int x = 0; x < 40; x++) {
            const float *q = p + 3 * (y * 40 + x), *b = p + 3 * ((y - y % 8) * 40 + (x - x % 8));
            same &= q[0] == b[0] && q[1] == b[1] && q[2] == b[2];
        }
    CHECK(same);
    /* The block's ray goes through the block's centre (the last row of
     * blocks is 6 pixels tall: its centre is 3 below its top). */
    hr_ray r;
    hr_camera_ray(&c, 16 + 4, 24 + 3, &r);
    hr_color want;
    hr_scene_shade(s, &r, -1, &want);
    const float *b = p + 3 * (24 * 40 + 16);
    CHECK(b[0] == (float)want.r && b[1] == (float)want.g && b[2] == (float)want.b);
    /* No mirror, no glass: no reflected or refracted ray was cast. */
    CHECK(st.reflected == 0 && st.refracted == 0);
    CHECK(!(st.effects & (HR_EFFECT_REFLECTION | HR_EFFECT_REFRACTION)));
    hr_image_destroy(img);
    hr_scene_destroy(s);
}

static int calls;
static int32_t cancel_after_two(void *user, double fraction)
{
    (void)user;
    CHECK(fraction >= 0 && fraction <= 1);
    return ++calls >= 2;
}

static void cancelling(void)
{
    hr_scene *s = busy_scene(1);
    hr_camera c = view(128, 128);
    hr_render_options o;
    hr_render_options_default(&o);
    o.tile_size = 8;
    o.threads = 2;
    o.progress = cancel_after_two;
    hr_image *img = (hr_image *)1;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_CANCELLED);
    CHECK(img == NULL);
    CHECK(strstr(hr_context_last_error(ctx), "cancelled") != NULL);
    /* Bad options name the option. */
    hr_render_options_default(&o);
    o.samples_per_pixel = -3;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "samples per pixel") != NULL);
    hr_scene_destroy(s);
    /* An uncommitted scene is refused. */
    hr_scene_create(ctx, &s);
    CHECK(hr_render(s, &c, NULL, &img, NULL) == HR_ERROR_STATE);
    hr_scene_destroy(s);
}

/* HR_EFFECTS_ALL runs every path (shadow rays to every light, reflected and
 * transmitted rays at every hit) yet gives the same image bit for bit: on a
 * scene without mirrors or glass, AUTO casts no bounce at all. */
static void effects_all(void)
{
    for (int busy = 0; busy < 2; busy++) {
        hr_scene *s = busy_scene(busy);
        hr_camera c = view(40, 30);
        hr_render_options o;
        hr_render_options_default(&o);
        o.threads = 2;
        hr_render_stats auto_st = {0}, all_st = {0};
        auto_st.struct_size = all_st.struct_size = sizeof auto_st;
        hr_image *a = render(s, &c, &o, &auto_st);
        o.effects = HR_EFFECTS_ALL;
        hr_image *b = render(s, &c, &o, &all_st);
        CHECK(a && b && memcmp(hr_image_data(a), hr_image_data(b), 40 * 30 * 3 * sizeof(float)) == 0);
        if (!busy) CHECK(auto_st.reflected == 0 && auto_st.refracted == 0);
        CHECK(all_st.reflected > auto_st.reflected && all_st.refracted > auto_st.refracted);
        CHECK(all_st.shadow > auto_st.shadow);
        CHECK(all_st.primary == auto_st.primary);
        CHECK(all_st.effects & HR_EFFECT_REFLECTION && all_st.effects & HR_EFFECT_REFRACTION);
        CHECK(!(all_st.effects & HR_EFFECT_SUPERSAMPLING));
        hr_image_destroy(a);
        hr_image_destroy(b);
        hr_scene_destroy(s);
    }
}

static int32_t cancel_at_once(void *user, double fraction)
{
    (void)fraction;
    ++*(int *)user;
    return 1;
}

/* One pixel that would cost 2^60 rays: a mirror-and-glass ball inside a
 * mirror box, both bounces at every hit, depth 60. The progress callback is
 * called from inside the pixel and cancels; hr_render returns. (Before, the
 * callback ran only between tiles: this never returned; ctest's timeout is
 * the guard.) */
static void cancel_inside_a_pixel(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.max_recursion_depth = 60;
    hr_scene_set_globals(s, &g);
    hr_material m = tb_black();
    m.reflectivity = 1;
    m.transparency = 1;
    m.speed_of_light = 0.7;
    tb_add(s, "sphere", &m, NULL);
    hr_transform box = tb_place(0, 0, 0, 4);
    tb_add(s, "cube", &m, &box);
    hr_scene_commit(s);
    hr_camera c = view(1, 1);
    c.eye = (hr_vec3){0, 0, 3};
    c.look = (hr_vec3){0, 0, 0};
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    int polls = 0;
    o.progress = cancel_at_once;
    o.progress_user = &polls;
    hr_image *img = (hr_image *)1;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_CANCELLED);
    CHECK(img == NULL && polls == 1);
    hr_scene_destroy(s);
}

/* The fractions a render reports never go backwards, however the threads
 * finishing tiles race for the callback, and the last one is 1. Many tiny
 * tiles on more threads than cores make the race likely (a thread counts its
 * tile, is preempted, and reports after one that counted later). */
typedef struct progress_log {
    double last;
    int calls, backwards;
} progress_log;

static int32_t log_progress(void *user, double fraction)
{
    progress_log *log = user;
    if (fraction < log->last) log->backwards++;
    log->last = fraction;
    log->calls++;
    return 0;
}

static void progress_never_goes_backwards(void)
{
    hr_scene *s = busy_scene(1);
    hr_camera c = view(96, 96);
    hr_render_options o;
    hr_render_options_default(&o);
    o.tile_size = 1;
    o.threads = 8;
    o.progress = log_progress;
    for (int round = 0; round < 8; round++) {
        progress_log log = {0.0, 0, 0};
        o.progress_user = &log;
        hr_image *img = render(s, &c, &o, NULL);
        CHECK_MSG(log.backwards == 0, "round %d: %d of %d reports went backwards", round,
                  log.backwards, log.calls);
        CHECK(log.calls >= 96 * 96 && log.last == 1.0);
        hr_image_destroy(img);
    }
    hr_scene_destroy(s);
}

static int32_t raise_flag(void *user, double fraction)
{
    (void)fraction;
    __atomic_store_n((int32_t *)user, 1, __ATOMIC_RELAXED);
    return 0;
}

/* One tile of 256 x 256 pixels of 65536 samples each, cancelled through
 * hr_render_options.cancel at the first poll: the rest of every pixel's
 * pattern is skipped, not run through ray by ray (that took 2^32 turns of
 * the sample loop, many minutes: ctest's timeout is the guard). */
static void cancel_inside_the_samples(void)
{
    hr_scene *s = busy_scene(0);
    hr_camera c = view(256, 256);
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    o.tile_size = 256;
    o.samples_per_pixel = 65536;
    int32_t flag = 0;
    o.cancel = &flag;
    o.progress = raise_flag;
    o.progress_user = &flag;
    hr_image *img = (hr_image *)1;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_CANCELLED);
    CHECK(img == NULL && flag == 1);
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    cancel_inside_a_pixel();
    cancel_inside_the_samples();
    effects_all();
    centres_and_threads();
    blocks();
    cancelling();
    progress_never_goes_backwards();
    hr_context_destroy(ctx);
    return hr_test_end();
}
