/* The render thread (view.h).
 *
 * One thread runs the passes of the current camera, one hr_render call
 * each (hr_render has its own pool of threads for the tiles). The window's
 * thread asks for a new camera by bumping the generation and raising the
 * cancel flag, both under the lock; the render thread reads them under the
 * same lock when it starts a refinement, so a restart is never lost and a
 * frame of an old camera is never handed out as new (its generation no
 * longer matches and it is dropped).
 *
 * The window shows each pass as its tiles finish (hr_render_options.
 * tile_done): hr_render's workers write each finished tile, as the
 * window's 8-bit sRGB, into the canvas, under the same lock and only while
 * its generation is the current one; the window's thread takes what
 * changed into `shown`, the pixels it has been given. The canvas differs
 * from `shown` only inside the changed rectangle, so a restart puts that
 * rectangle back as shown: a tile of the old camera that the window has
 * not taken yet never reaches it, and what it shows stays the old picture
 * until the new camera's tiles replace it. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "view.h"

struct view_renderer {
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    const hr_scene *scene;
    hr_context *ctx;
    hr_render_options options;
    view_pass plan[VIEW_MAX_PASSES];
    int passes;
    view_notify_fn notify;
    void *notify_user;

    /* Under the lock. */
    hr_camera camera;
    uint64_t generation; /* asked for */
    uint64_t done;       /* refined to the end (or failed) */
    int quit;
    view_frame ready;    /* image NULL: none */
    char error[1024];
    int has_error;
    uint8_t *canvas;     /* width x height sRGB: every tile reported */
    view_rect changed;   /* where canvas and shown differ (empty: none) */

    int32_t width, height; /* the image's, set at the start */
    uint8_t *shown;      /* what the window was given: written by its thread
                            alone, under the lock (read there by a restart) */

    /* hr_render reads it from its threads; set with an atomic store. */
    int32_t cancel;
    /* For the status line, read without the lock. */
    atomic_int running_pass;
    atomic_int fraction_ppm; /* millionths */
};

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int32_t on_progress(void *user, double fraction)
{
    view_renderer *r = user;
    atomic_store(&r->fraction_ppm, (int)(fraction * 1e6));
    return 0; /* cancelling is the flag's job */
}

/* The hr_render call's tiles, for the refinement of `generation`. */
typedef struct tile_target {
    view_renderer *r;
    uint64_t generation;
} tile_target;

static int rect_empty(const view_rect *a) { return a->width <= 0 || a->height <= 0; }

/* The smallest rectangle holding both. */
static void rect_add(view_rect *a, int32_t x, int32_t y, int32_t width, int32_t height)
{
    if (rect_empty(a)) {
        *a = (view_rect){x, y, width, height};
        return;
    }
    int32_t x1 = a->x + a->width > x + width ? a->x + a->width : x + width;
    int32_t y1 = a->y + a->height > y + height ? a->y + a->height : y + height;
    a->x = a->x < x ? a->x : x, a->y = a->y < y ? a->y : y;
    a->width = x1 - a->x, a->height = y1 - a->y;
}

/* Copy a rectangle between two width x height sRGB buffers. */
static void copy_rect(const view_renderer *r, uint8_t *to, const uint8_t *from, const view_rect *a)
{
    for (int32_t y = a->y; y < a->y + a->height; y++) {
        size_t at = 3 * ((size_t)y * (size_t)r->width + (size_t)a->x);
        memcpy(to + at, from + at, 3 * (size_t)a->width);
    }
}

/* hr_render's workers, several at once: a finished tile into the canvas,
 * unless the camera changed meanwhile. The window is woken when the canvas
 * starts to differ from what it shows; later tiles join that change. */
static void on_tile(void *user, int32_t x, int32_t y, int32_t width, int32_t height, const float *pixels,
                    int32_t row_stride)
{
    const tile_target *t = user;
    view_renderer *r = t->r;
    pthread_mutex_lock(&r->lock);
    int current = t->generation == r->generation && !r->quit;
    int wake = current && rect_empty(&r->changed);
    if (current) {
        view_pixels_srgb8(pixels, row_stride, width, height,
                          r->canvas + 3 * ((size_t)y * (size_t)r->width + (size_t)x), 3 * (int)r->width);
        rect_add(&r->changed, x, y, width, height);
    }
    pthread_mutex_unlock(&r->lock);
    if (wake) r->notify(r->notify_user);
}

/* Hand a finished pass over, unless the camera changed meanwhile. */
static int publish(view_renderer *r, const view_frame *frame)
{
    pthread_mutex_lock(&r->lock);
    int current = frame->generation == r->generation && !r->quit;
    if (current) {
        hr_image_destroy(r->ready.image); /* a pass never shown: the newer one replaces it */
        r->ready = *frame;
    }
    pthread_mutex_unlock(&r->lock);
    if (!current) hr_image_destroy(frame->image);
    return current;
}

static void fail(view_renderer *r, uint64_t generation, hr_status st)
{
    /* The message is kept per thread: this one rendered, so it reads it. */
    const char *message = hr_context_last_error(r->ctx);
    pthread_mutex_lock(&r->lock);
    if (generation == r->generation) {
        snprintf(r->error, sizeof r->error, "%s", message && *message ? message : hr_status_name(st));
        r->has_error = 1;
    }
    pthread_mutex_unlock(&r->lock);
}

/* Every pass of one camera; returns when done, failed or cancelled. */
static void refine(view_renderer *r, const hr_camera *camera, uint64_t generation)
{
    double started = now_seconds();
    for (int pass = 0; pass < r->passes; pass++) {
        atomic_store(&r->running_pass, pass);
        atomic_store(&r->fraction_ppm, 0);
        hr_render_options o = r->options;
        o.block_size = r->plan[pass].block_size;
        o.samples_per_pixel = r->plan[pass].samples_per_pixel;
        o.progress = on_progress;
        o.progress_user = r;
        o.cancel = &r->cancel;
        tile_target target = {r, generation};
        o.tile_done = on_tile;
        o.tile_user = &target;
        view_frame frame;
        memset(&frame, 0, sizeof frame);
        frame.stats.struct_size = sizeof frame.stats;
        hr_status st = hr_render(r->scene, camera, &o, &frame.image, &frame.stats);
        if (st == HR_ERROR_CANCELLED) return;
        if (st != HR_OK) {
            fail(r, generation, st);
            break;
        }
        frame.camera = *camera;
        frame.generation = generation;
        frame.pass = pass;
        frame.passes = r->passes;
        frame.settings = r->plan[pass];
        frame.since_restart = now_seconds() - started;
        /* Done before the window hears of the last frame, so the status
         * line it draws for that frame says so. */
        if (pass == r->passes - 1) atomic_store(&r->running_pass, r->passes);
        if (!publish(r, &frame)) return;
        r->notify(r->notify_user);
    }
    atomic_store(&r->running_pass, r->passes);
    pthread_mutex_lock(&r->lock);
    if (generation == r->generation) r->done = generation;
    pthread_mutex_unlock(&r->lock);
    r->notify(r->notify_user); /* a failure, or the title's "done" */
}

static void *render_thread(void *arg)
{
    view_renderer *r = arg;
    pthread_mutex_lock(&r->lock);
    while (!r->quit) {
        if (r->done == r->generation) {
            pthread_cond_wait(&r->wake, &r->lock);
            continue;
        }
        uint64_t generation = r->generation;
        hr_camera camera = r->camera;
        __atomic_store_n(&r->cancel, 0, __ATOMIC_RELAXED);
        r->has_error = 0;
        pthread_mutex_unlock(&r->lock);
        refine(r, &camera, generation);
        pthread_mutex_lock(&r->lock);
    }
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

view_renderer *view_renderer_start(const hr_scene *scene, hr_context *ctx, const hr_render_options *options,
                                   const view_pass *plan, int passes, const hr_camera *camera,
                                   view_notify_fn notify, void *notify_user)
{
    view_renderer *r = calloc(1, sizeof *r);
    if (!r) return NULL;
    r->scene = scene;
    r->ctx = ctx;
    r->options = *options;
    memcpy(r->plan, plan, (size_t)passes * sizeof *plan);
    r->passes = passes;
    r->notify = notify;
    r->notify_user = notify_user;
    r->camera = *camera;
    r->generation = 1;
    /* hr_render's image size: the options', else the camera's. */
    r->width = options->width > 0 ? options->width : camera->width;
    r->height = options->height > 0 ? options->height : camera->height;
    size_t bytes = 3 * (size_t)r->width * (size_t)r->height;
    r->canvas = calloc(bytes, 1);
    r->shown = calloc(bytes, 1);
    if (!r->canvas || !r->shown) {
        free(r->canvas);
        free(r->shown);
        free(r);
        return NULL;
    }
    atomic_init(&r->running_pass, 0);
    atomic_init(&r->fraction_ppm, 0);
    int locks = 0;
    if (pthread_mutex_init(&r->lock, NULL) == 0) locks = 1;
    if (locks == 1 && pthread_cond_init(&r->wake, NULL) == 0) locks = 2;
    if (locks == 2 && pthread_create(&r->thread, NULL, render_thread, r) == 0) return r;
    if (locks == 2) pthread_cond_destroy(&r->wake);
    if (locks >= 1) pthread_mutex_destroy(&r->lock);
    free(r->canvas);
    free(r->shown);
    free(r);
    return NULL;
}

uint64_t view_renderer_restart(view_renderer *r, const hr_camera *camera)
{
    pthread_mutex_lock(&r->lock);
    r->camera = *camera;
    uint64_t generation = ++r->generation;
    r->has_error = 0;
    /* The old camera's tiles the window has not taken: back to what it shows. */
    copy_rect(r, r->canvas, r->shown, &r->changed);
    r->changed = (view_rect){0, 0, 0, 0};
    atomic_store(&r->running_pass, 0);
    atomic_store(&r->fraction_ppm, 0);
    __atomic_store_n(&r->cancel, 1, __ATOMIC_RELAXED);
    pthread_cond_signal(&r->wake);
    pthread_mutex_unlock(&r->lock);
    return generation;
}

int view_renderer_take(view_renderer *r, view_frame *out)
{
    pthread_mutex_lock(&r->lock);
    int have = r->ready.image != NULL;
    if (have) {
        *out = r->ready;
        r->ready.image = NULL;
    }
    pthread_mutex_unlock(&r->lock);
    return have;
}

const uint8_t *view_renderer_take_pixels(view_renderer *r, view_rect *changed)
{
    pthread_mutex_lock(&r->lock);
    *changed = r->changed;
    copy_rect(r, r->shown, r->canvas, &r->changed);
    r->changed = (view_rect){0, 0, 0, 0};
    pthread_mutex_unlock(&r->lock);
    return r->shown;
}

void view_renderer_progress(view_renderer *r, int *pass, double *fraction)
{
    *pass = atomic_load(&r->running_pass);
    *fraction = atomic_load(&r->fraction_ppm) * 1e-6;
}

int view_renderer_error(view_renderer *r, char *message, size_t size)
{
    pthread_mutex_lock(&r->lock);
    int has = r->has_error;
    if (has) snprintf(message, size, "%s", r->error);
    pthread_mutex_unlock(&r->lock);
    return has;
}

void view_renderer_stop(view_renderer *r)
{
    if (!r) return;
    pthread_mutex_lock(&r->lock);
    r->quit = 1;
    __atomic_store_n(&r->cancel, 1, __ATOMIC_RELAXED);
    pthread_cond_signal(&r->wake);
    pthread_mutex_unlock(&r->lock);
    pthread_join(r->thread, NULL);
    hr_image_destroy(r->ready.image);
    pthread_cond_destroy(&r->wake);
    pthread_mutex_destroy(&r->lock);
    free(r->canvas);
    free(r->shown);
    free(r);
}
