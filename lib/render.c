/* Rendering: tiles handed out to a pool of threads through an atomic
 * counter. Every pixel is computed from the scene, camera and options alone
 * (a fixed sample pattern, no shared random state), so the image is the same
 * bit for bit whatever the number of threads or the order tiles finish. */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "errors.h"
#include "scene_internal.h"
#include "vec.h"

#define DEFAULT_TILE 32
#define MAX_THREADS 256

HR_API void hr_render_options_default(hr_render_options *o)
{
    if (!o) return;
    memset(o, 0, sizeof *o);
    o->struct_size = sizeof *o;
    o->samples_per_pixel = 1;
    o->block_size = 1;
    o->max_depth = -1;
}

typedef struct render_job {
    const hr_scene *scene;
    hr_camera camera;
    hr_render_options opt;
    float *pixels;
    int32_t width, height;
    /* 65536 x 65536 pixels in tiles of 1 is 2^32 tiles: past int32. */
    int64_t tiles_x, tiles_y, tile_count;
    int32_t max_depth;
    atomic_llong next_tile;
    atomic_llong tiles_done;
    atomic_int cancelled;
    pthread_mutex_t progress_lock;
    hr_status failure; /* first shape failure (guarded by progress_lock) */
} render_job;

typedef struct worker {
    render_job *job;
    pthread_t thread;
    uint64_t primary, shadow, reflected, refracted;
} worker;

/* Radical inverse in base 2: the second coordinate of Hammersley points. */
static double radical_inverse2(uint32_t i)
{
    i = (i << 16) | (i >> 16);
    i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    return (double)i * (1.0 / 4294967296.0);
}

/* Sample k of n inside a unit square: Hammersley points shifted by half a
 * stratum, so n = 1 is the centre and every pixel uses the same pattern. */
static void sample_offset(int32_t k, int32_t n, double *dx, double *dy)
{
    *dx = (k + 0.5) / n;
    double y = radical_inverse2((uint32_t)k) + 0.5 / n;
    *dy = y >= 1.0 ? y - 1.0 : y;
}

/* Called from inside shading every HR_POLL_INTERVAL rays: report progress
 * (and so let the callback cancel) without waiting for the tile to end. A
 * busy lock means another thread is reporting: skip, the next poll comes. */
static void poll_progress(void *user)
{
    render_job *job = user;
    if (!job->opt.progress || pthread_mutex_trylock(&job->progress_lock) != 0) return;
    if (!atomic_load(&job->cancelled) &&
        job->opt.progress(job->opt.progress_user,
                          (double)atomic_load(&job->tiles_done) / (double)job->tile_count))
        atomic_store(&job->cancelled, 1);
    pthread_mutex_unlock(&job->progress_lock);
}

static void render_tile(worker *w, int64_t tile)
{
    render_job *job = w->job;
    hr_trace_ctx tc;
    hr_trace_ctx_init(&tc, job->scene);
    tc.force_all_effects = job->opt.effects == HR_EFFECTS_ALL;
    tc.cancelled = &job->cancelled;
    tc.poll = poll_progress;
    tc.poll_user = job;
    int32_t tsize = job->opt.tile_size;
    int32_t x0 = (int32_t)(tile % job->tiles_x) * tsize, y0 = (int32_t)(tile / job->tiles_x) * tsize;
    int32_t x1 = x0 + tsize < job->width ? x0 + tsize : job->width;
    int32_t y1 = y0 + tsize < job->height ? y0 + tsize : job->height;
    int32_t block = job->opt.block_size, spp = job->opt.samples_per_pixel;
    /* Blocks are aligned to the image, not the tile, so a block that straddles
     * tiles gets the same colour in both. */
    for (int32_t y = y0; y < y1; y++) {
        for (int32_t x = x0; x < x1; x++) {
            int32_t bx = x - x % block, by = y - y % block;
            if (block > 1 && x != bx && x != x0) {
                /* Copy from the pixel to the left, inside this tile and block. */
                memcpy(&job->pixels[3 * ((size_t)y * job->width + x)],
                       &job->pixels[3 * ((size_t)y * job->width + x - 1)], 3 * sizeof(float));
                continue;
            }
            if (block > 1 && y != by && y != y0) {
                memcpy(&job->pixels[3 * ((size_t)y * job->width + x)],
                       &job->pixels[3 * ((size_t)(y - 1) * job->width + x)], 3 * sizeof(float));
                continue;
            }
            /* One pixel, or the one ray of a block over its whole area. */
            double bw = block < job->width - bx ? block : job->width - bx;
            double bh = block < job->height - by ? block : job->height - by;
            hr_color sum = rgb(0, 0, 0);
            for (int32_t k = 0; k < spp; k++) {
                double dx, dy;
                sample_offset(k, spp, &dx, &dy);
                hr_ray ray;
                hr_camera_ray(&job->camera, bx + dx * bw, by + dy * bh, &ray);
                w->primary++;
                sum = rgb_add(sum, hr_shade_ray(&tc, &ray, 0, job->max_depth));
            }
            float *px = &job->pixels[3 * ((size_t)y * job->width + x)];
            px[0] = (float)(sum.r / spp), px[1] = (float)(sum.g / spp), px[2] = (float)(sum.b / spp);
        }
    }
    w->shadow += tc.rays_shadow;
    w->reflected += tc.rays_reflected;
    w->refracted += tc.rays_refracted;
    if (tc.status) {
        pthread_mutex_lock(&job->progress_lock);
        if (!job->failure) job->failure = tc.status;
        pthread_mutex_unlock(&job->progress_lock);
        atomic_store(&job->cancelled, 1);
    }
    hr_trace_ctx_release(&tc);
}

static void *worker_main(void *arg)
{
    worker *w = arg;
    render_job *job = w->job;
    for (;;) {
        if (atomic_load(&job->cancelled)) break;
        int64_t tile = atomic_fetch_add(&job->next_tile, 1);
        if (tile >= job->tile_count) break;
        render_tile(w, tile);
        int64_t done = atomic_fetch_add(&job->tiles_done, 1) + 1;
        if (job->opt.progress) {
            pthread_mutex_lock(&job->progress_lock);
            if (!atomic_load(&job->cancelled) &&
                job->opt.progress(job->opt.progress_user, (double)done / (double)job->tile_count))
                atomic_store(&job->cancelled, 1);
            pthread_mutex_unlock(&job->progress_lock);
        }
    }
    return NULL;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int32_t core_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int32_t)n;
}

static hr_status check_options(hr_context *ctx, hr_render_options *o, const hr_camera *cam)
{
    if (o->width == 0) o->width = cam->width;
    if (o->height == 0) o->height = cam->height;
    if (o->samples_per_pixel == 0) o->samples_per_pixel = 1;
    if (o->block_size == 0) o->block_size = 1;
    if (o->tile_size == 0) o->tile_size = DEFAULT_TILE;
    if (o->width <= 0 || o->height <= 0 || o->width > 65536 || o->height > 65536)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: image size %dx%d must be within 1..65536", (int)o->width, (int)o->height);
    if (o->samples_per_pixel < 1 || o->samples_per_pixel > 65536)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: samples per pixel %d must be within 1..65536",
                        (int)o->samples_per_pixel);
    if (o->threads < 0 || o->threads > MAX_THREADS)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: threads %d must be within 0..%d",
                        (int)o->threads, MAX_THREADS);
    if (o->block_size < 1 || o->block_size > 4096)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: block size %d must be within 1..4096",
                        (int)o->block_size);
    if (o->tile_size < 1 || o->tile_size > 4096)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: tile size %d must be within 1..4096",
                        (int)o->tile_size);
    if (o->max_depth > HR_MAX_RECURSION_DEPTH)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: depth %d must be at most %d",
                        (int)o->max_depth, HR_MAX_RECURSION_DEPTH);
    if (o->effects != HR_EFFECTS_AUTO && o->effects != HR_EFFECTS_ALL)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: effects must be HR_EFFECTS_AUTO or HR_EFFECTS_ALL");
    return HR_OK;
}

HR_API hr_status hr_render(const hr_scene *scene, const hr_camera *camera,
                           const hr_render_options *options, hr_image **out_image,
                           hr_render_stats *stats)
{
    if (!scene) return HR_ERROR_INVALID_ARGUMENT;
    hr_context *ctx = scene->ctx;
    if (!out_image) return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: NULL output image");
    *out_image = NULL;
    if (!scene->committed)
        return hr_error(ctx, HR_ERROR_STATE, "render: the scene is not committed (call hr_scene_commit)");
    if (!camera || camera->struct_size < sizeof(uint32_t))
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: NULL camera or struct_size not set");
    render_job *job = calloc(1, sizeof *job);
    if (!job) return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    job->scene = scene;
    hr_camera_default(&job->camera);
    memcpy(&job->camera, camera,
           camera->struct_size < sizeof job->camera ? camera->struct_size : sizeof job->camera);
    hr_render_options_default(&job->opt);
    if (options) {
        if (options->struct_size < sizeof(uint32_t)) {
            free(job);
            return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render options: struct_size not set");
        }
        memcpy(&job->opt, options,
               options->struct_size < sizeof job->opt ? options->struct_size : sizeof job->opt);
    }
    hr_status st = check_options(ctx, &job->opt, &job->camera);
    if (st == HR_OK) {
        job->camera.width = job->opt.width, job->camera.height = job->opt.height;
        st = hr_camera_validate(ctx, &job->camera);
    }
    hr_image *image = NULL;
    if (st == HR_OK) st = hr_image_create(ctx, job->opt.width, job->opt.height, 3, &image);
    if (st) {
        free(job);
        return st;
    }
    job->pixels = hr_image_data(image);
    job->width = job->opt.width, job->height = job->opt.height;
    job->max_depth = job->opt.max_depth >= 0 ? job->opt.max_depth : scene->globals.max_recursion_depth;
    job->tiles_x = (job->width + job->opt.tile_size - 1) / job->opt.tile_size;
    job->tiles_y = (job->height + job->opt.tile_size - 1) / job->opt.tile_size;
    job->tile_count = job->tiles_x * job->tiles_y;
    pthread_mutex_init(&job->progress_lock, NULL);

    int32_t nthreads = job->opt.threads > 0 ? job->opt.threads : core_count();
    if (nthreads > job->tile_count) nthreads = (int32_t)job->tile_count;
    worker *workers = calloc((size_t)nthreads, sizeof *workers);
    double t0 = now_seconds();
    int32_t started = 0;
    if (workers) {
        for (int32_t i = 0; i < nthreads; i++) workers[i].job = job;
        /* The calling thread is worker 0; the others are started here. */
        for (started = 1; started < nthreads; started++)
            if (pthread_create(&workers[started].thread, NULL, worker_main, &workers[started]) != 0) break;
        worker_main(&workers[0]);
        for (int32_t i = 1; i < started; i++) pthread_join(workers[i].thread, NULL);
    }
    double seconds = now_seconds() - t0;
    if (!workers) st = hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    else if (job->failure) st = hr_error(ctx, job->failure, "render: a shape failed while tracing: %s",
                                         hr_status_name(job->failure));
    else if (atomic_load(&job->cancelled)) st = hr_error(ctx, HR_ERROR_CANCELLED, "render cancelled");
    if (st == HR_OK && stats && stats->struct_size >= sizeof(uint32_t)) {
        hr_render_stats s = {0};
        s.struct_size = stats->struct_size < sizeof s ? stats->struct_size : (uint32_t)sizeof s;
        s.threads = started;
        for (int32_t i = 0; i < started; i++) {
            s.primary += workers[i].primary;
            s.shadow += workers[i].shadow;
            s.reflected += workers[i].reflected;
            s.refracted += workers[i].refracted;
        }
        s.seconds = seconds;
        /* Bounces run at the depth this render used, which may differ from
         * the scene's own. */
        uint32_t bounces = HR_EFFECT_REFLECTION | HR_EFFECT_REFRACTION;
        s.effects = (scene->effects & ~bounces) | (job->max_depth > 0 ? scene->bounce_effects : 0u) |
                    (job->opt.samples_per_pixel > 1 ? HR_EFFECT_SUPERSAMPLING : 0u);
        /* Forced: every shading path ran (bounces only if the depth allows
         * one); supersampling is a matter of the sample count either way. */
        if (job->opt.effects == HR_EFFECTS_ALL)
            s.effects = (HR_EFFECT_EMISSION | HR_EFFECT_AMBIENT | HR_EFFECT_DIFFUSE |
                         HR_EFFECT_SPECULAR | HR_EFFECT_SHADOWS) |
                        (job->max_depth > 0 ? bounces : 0u) |
                        (s.effects & HR_EFFECT_SUPERSAMPLING);
        memcpy(stats, &s, s.struct_size);
    }
    free(workers);
    pthread_mutex_destroy(&job->progress_lock);
    free(job);
    if (st) {
        hr_image_destroy(image);
        return st;
    }
    *out_image = image;
    return HR_OK;
}
