/* The viewer's render thread (view/view_render.c) with no window: every
 * frame it hands out is hr_render's image for that pass and camera, bit for
 * bit; a restart drops the old camera's frames and refines the new one; a
 * restart or a stop during a pass that would take minutes cancels it (the
 * ctest timeout makes a hang a failure); a render error is reported once
 * and the next camera renders again. The pixels for the window hold every
 * tile of the final pass once it is handed out, and after a restart no
 * tile of the old camera reaches them, not even one finished before the
 * restart and not yet taken. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "hr_test.h"
#include "view.h"

/* The notify callback's side: a counter and a condition to wait on. */
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t notified = PTHREAD_COND_INITIALIZER;
static int notifications;

static void on_notify(void *user)
{
    (void)user;
    pthread_mutex_lock(&lock);
    notifications++;
    pthread_cond_broadcast(&notified);
    pthread_mutex_unlock(&lock);
}

/* The next frame, waiting up to a minute (a hang, not a speed test). */
static int next_frame(view_renderer *r, view_frame *out)
{
    struct timespec deadline;
    clock_gettime(CLOCK_REALTIME, &deadline);
    deadline.tv_sec += 60;
    for (;;) {
        pthread_mutex_lock(&lock);
        int seen = notifications;
        pthread_mutex_unlock(&lock);
        if (view_renderer_take(r, out)) return 1;
        pthread_mutex_lock(&lock);
        int timed_out = 0;
        while (notifications == seen && !timed_out)
            timed_out = pthread_cond_timedwait(&notified, &lock, &deadline) != 0;
        pthread_mutex_unlock(&lock);
        if (timed_out) return 0;
    }
}

/* The frame's image must be hr_render's with its pass's settings. */
static void check_frame(const cli_scene *s, const hr_render_options *base, const view_frame *f)
{
    hr_render_options o = *base;
    o.block_size = f->settings.block_size;
    o.samples_per_pixel = f->settings.samples_per_pixel;
    hr_image *want = NULL;
    CHECK_OK(hr_render(s->sdl.scene, &f->camera, &o, &want, NULL));
    if (!want) return;
    size_t n = (size_t)hr_image_width(want) * (size_t)hr_image_height(want) * 3;
    CHECK(hr_image_width(f->image) == hr_image_width(want) && hr_image_height(f->image) == hr_image_height(want));
    CHECK_MSG(memcmp(hr_image_data(f->image), hr_image_data(want), n * sizeof(float)) == 0,
              "pass %d (block %d, %d spp) differs from hr_render's image", f->pass, (int)f->settings.block_size,
              (int)f->settings.samples_per_pixel);
    CHECK(f->stats.primary > 0 && f->stats.seconds >= 0.0);
    hr_image_destroy(want);
}

/* hr_render's image for `pass` of the plan at `cam`, as the window's sRGB. */
static uint8_t *pass_srgb(const cli_scene *s, const hr_render_options *base, const view_pass *pass,
                          const hr_camera *cam)
{
    hr_render_options o = *base;
    o.block_size = pass->block_size;
    o.samples_per_pixel = pass->samples_per_pixel;
    hr_image *img = NULL;
    CHECK_OK(hr_render(s->sdl.scene, cam, &o, &img, NULL));
    if (!img) return NULL;
    int32_t w = hr_image_width(img), h = hr_image_height(img);
    uint8_t *out = malloc(3 * (size_t)w * (size_t)h);
    if (out) view_pixels_srgb8(hr_image_data(img), 3 * w, w, h, out, 3 * w);
    hr_image_destroy(img);
    return out;
}

/* The window's pixels must be the final frame's image in sRGB. */
static void check_pixels_are(view_renderer *r, const hr_image *image)
{
    int32_t w = hr_image_width(image), h = hr_image_height(image);
    uint8_t *want = malloc(3 * (size_t)w * (size_t)h);
    if (!want) return;
    view_pixels_srgb8(hr_image_data((hr_image *)image), 3 * w, w, h, want, 3 * w);
    view_rect changed;
    const uint8_t *got = view_renderer_take_pixels(r, &changed);
    CHECK_MSG(memcmp(got, want, 3 * (size_t)w * (size_t)h) == 0,
              "the window's pixels are not the final pass when it is handed out");
    free(want);
}

/* Take frames until the final pass of `generation`; each is checked, none
 * may be of a later generation, passes of one generation come in order. */
static void refine_to_the_end(view_renderer *r, const cli_scene *s, const hr_render_options *base,
                              uint64_t generation, const hr_camera *cam)
{
    int last_pass = -1;
    for (;;) {
        view_frame f;
        if (!next_frame(r, &f)) {
            CHECK_MSG(0, "no frame of generation %llu within a minute", (unsigned long long)generation);
            return;
        }
        CHECK(f.generation <= generation);
        if (f.generation == generation) {
            CHECK(f.pass > last_pass);
            CHECK(memcmp(&f.camera, cam, sizeof *cam) == 0);
            last_pass = f.pass;
        }
        check_frame(s, base, &f);
        int final = f.generation == generation && f.pass == f.passes - 1;
        if (final) check_pixels_are(r, f.image);
        hr_image_destroy(f.image);
        if (final) return;
    }
}

/* Take frames up to the one of pass `last` (the slow pass after it would
 * take minutes, so none comes later); every one must be of `generation`
 * and, if `cam` is given, of that camera. Frames may have been dropped
 * unseen, so the first one taken may already be `last`. 0 on a timeout. */
static int take_up_to(view_renderer *r, int last, uint64_t generation, const hr_camera *cam)
{
    view_frame f;
    do {
        if (!next_frame(r, &f)) return 0;
        CHECK(f.generation == generation);
        if (cam) CHECK(memcmp(&f.camera, cam, sizeof *cam) == 0);
        hr_image_destroy(f.image);
    } while (f.pass != last);
    return 1;
}

int main(void)
{
    cli_scene s;
    if (cli_scene_load(&s, HR_TEST_SOURCE_DIR "/scenes/demo.sdl") || cli_scene_commit(&s)) return 1;
    hr_camera cam = cli_scene_camera(&s, 48, 36);
    hr_render_options base;
    hr_render_options_default(&base);
    base.threads = 2;
    view_pass plan[VIEW_MAX_PASSES];
    int passes = view_pass_plan(1, 2, plan);

    /* The whole refinement of one camera. */
    view_renderer *r = view_renderer_start(s.sdl.scene, s.ctx, &base, plan, passes, &cam, on_notify, NULL);
    CHECK(r != NULL);
    if (!r) return hr_test_end();
    refine_to_the_end(r, &s, &base, 1, &cam);
    int pass;
    double fraction;
    view_renderer_progress(r, &pass, &fraction);
    CHECK(pass == passes);

    /* Two moves at once: the last one's refinement ends the story. */
    view_steps steps = view_steps_for(&cam);
    view_apply(VIEW_FORWARD, &cam, &steps);
    CHECK(view_renderer_restart(r, &cam) == 2);
    view_apply(VIEW_YAW_LEFT, &cam, &steps);
    CHECK(view_renderer_restart(r, &cam) == 3);
    refine_to_the_end(r, &s, &base, 3, &cam);
    view_renderer_stop(r);

    /* A final pass that would take minutes (65536 samples a pixel on one
     * thread, no tile of it done within seconds): a move gets the new
     * camera's first pass at once, and a stop does not wait for the slow
     * pass. */
    view_pass slow[VIEW_MAX_PASSES];
    int slow_passes = view_pass_plan(1, 65536, slow);
    base.threads = 1;
    r = view_renderer_start(s.sdl.scene, s.ctx, &base, slow, slow_passes, &cam, on_notify, NULL);
    CHECK(r != NULL);
    if (!r) return hr_test_end();
    view_frame f;
    /* The old camera's passes are in the pixels, none taken yet. */
    CHECK(take_up_to(r, slow_passes - 2, 1, NULL));
    view_apply(VIEW_PITCH_UP, &cam, &steps);
    uint64_t g = view_renderer_restart(r, &cam);
    /* The window never took anything: each pixel is still black, or a tile
     * of the new camera's passes (the first may be in already). */
    view_rect changed;
    const uint8_t *px = view_renderer_take_pixels(r, &changed);
    uint8_t *refs[VIEW_MAX_PASSES] = {NULL};
    for (int p = 0; p < slow_passes - 1; p++) refs[p] = pass_srgb(&s, &base, &slow[p], &cam);
    size_t n = (size_t)cam.width * (size_t)cam.height;
    size_t stale = 0;
    for (size_t i = 0; i < n; i++) {
        static const uint8_t black[3] = {0, 0, 0};
        int fits = memcmp(px + 3 * i, black, 3) == 0;
        for (int p = 0; !fits && p < slow_passes - 1; p++)
            fits = refs[p] && memcmp(px + 3 * i, refs[p] + 3 * i, 3) == 0;
        stale += !fits;
    }
    CHECK_MSG(stale == 0, "after a restart, %zu pixels of the window's are the old camera's", stale);
    CHECK(take_up_to(r, slow_passes - 2, g, &cam));
    /* Its last quick pass is all there (the slow pass has no tile yet). */
    px = view_renderer_take_pixels(r, &changed);
    CHECK_MSG(refs[slow_passes - 2] && memcmp(px, refs[slow_passes - 2], 3 * n) == 0,
              "the window's pixels are not the last pass handed out");
    for (int p = 0; p < slow_passes - 1; p++) free(refs[p]);
    view_renderer_stop(r); /* in the slow pass */

    /* A camera the renderer refuses: the error is kept, no frame comes;
     * the next camera renders. */
    base.threads = 2;
    hr_camera bad = cam;
    bad.look = bad.eye;
    r = view_renderer_start(s.sdl.scene, s.ctx, &base, plan, passes, &bad, on_notify, NULL);
    CHECK(r != NULL);
    if (!r) return hr_test_end();
    char message[512] = "";
    for (int tries = 0; tries < 6000 && !view_renderer_error(r, message, sizeof message); tries++) {
        struct timespec ms10 = {0, 10000000};
        nanosleep(&ms10, NULL);
    }
    CHECK_MSG(strstr(message, "camera") != NULL, "the render error: '%s'", message);
    CHECK(!view_renderer_take(r, &f));
    g = view_renderer_restart(r, &cam);
    CHECK(!view_renderer_error(r, message, sizeof message));
    refine_to_the_end(r, &s, &base, g, &cam);
    view_renderer_stop(r);
    view_renderer_stop(NULL);

    cli_scene_free(&s);
    return hr_test_end();
}
