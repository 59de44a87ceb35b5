/* Rendering: tiles handed out to a pool of threads through an atomic
 * counter. Every pixel is computed from the scene, camera and options alone
 * (a fixed sample pattern, no shared random state), so the image is the same
 * bit for bit whatever the number of threads or the order tiles finish.
 *
 * Adaptive supersampling keeps that promise: a pixel's decision uses only
 * the samples at its own four corners, which any tile computes to the same
 * bits (corners on a tile's border are traced by both tiles). Each thread
 * owns its tracing context and corner rows for the whole render, so no ray
 * allocates.
 *
 * A window (hr_render_options.window_*) renders a rectangle of the image:
 * tiles cover the window only, but every sample, corner and block keeps its
 * place on the full image (coordinates are the full image's throughout; only
 * the store into the window's pixels subtracts its origin), so a window's
 * pixels are the full render's bits. */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "util/sized_copy.h"
#include "geometry/camera_frame.h"
#include "util/errors.h"
#include "util/strutil.h"
#include "image/image_internal.h"
#include "image/image_srgb.h"
#include "trace/query_nesting.h"
#include "trace/trace_context.h"
#include "geometry/vec.h"

#define DEFAULT_TILE 32

HR_API void hr_render_options_default(hr_render_options *o)
{
    if (!o) return;
    memset(o, 0, sizeof *o);
    o->struct_size = sizeof *o;
    o->samples_per_pixel = 1;
    o->block_size = 1;
    o->max_depth = -1;
}

/* What threads write and what they only read kept on different cache
 * lines: every thread reads the job (the frame, the options, the pixels and
 * `cancelled`) on every ray, and a write to a line another core holds takes
 * it away from that core. The tile counter is written each time a thread
 * takes a tile, the progress fields each time one finishes, by whichever
 * thread; each has a line of its own, so taking a tile costs the other
 * thread nothing. */
#define HR_CACHE_LINE 64

typedef struct render_job {
    const hr_scene *scene;
    hr_camera camera;
    hr_camera_frame frame; /* the camera's ray constants, once for the image */
    hr_render_options opt;
    float *pixels;          /* the window's pixels */
    int32_t width, height;  /* the full image's size */
    int32_t win_x, win_y, win_width, win_height;
    /* 65536 x 65536 pixels in tiles of 1 is 2^32 tiles: past int32. */
    int64_t tiles_x, tiles_y, tile_count;
    int32_t max_depth;
    int32_t differentials; /* camera rays carry ray differentials (the
                              scene has a texture and filtering is on) */
    int32_t query_level; /* every render thread's query nesting (query_nesting.h) */
    atomic_int cancelled; /* written once, when the render stops early */
    _Alignas(HR_CACHE_LINE) atomic_llong next_tile;
    _Alignas(HR_CACHE_LINE) atomic_llong tiles_done;
    pthread_mutex_t progress_lock;
    hr_status failure; /* first shape failure (guarded by progress_lock) */
} render_job;

/* A sample at a pixel corner: its colour, and that colour as shown
 * (sRGB-encoded, clamped), what the adaptive test compares. */
typedef struct corner_sample {
    hr_color linear;
    double shown[3];
    int over_budget; /* the sample lost a ray to the ray budget */
} corner_sample;

/* Each worker on cache lines of its own, for the same reason: a worker
 * writes its counters and its context (the shadow cache, the ray counts) on
 * every ray. */
typedef struct worker {
    _Alignas(HR_CACHE_LINE) render_job *job;
    pthread_t thread;
    hr_trace_ctx tc;         /* for every tile this thread renders */
    corner_sample *corners;  /* adaptive: two rows of tile_size + 1 */
    double *columns;         /* centres: the plane's x of each column of a tile */
    uint64_t primary, pixels_refined, pixels_over_budget;
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

/* Tell the progress callback how many tiles are done; progress_lock held.
 * The count is read here, under the lock, never before it: a thread that
 * counted its tile and then waited for the lock would otherwise report an
 * older count after a thread that counted later (47% after 48%). Reads of a
 * counter that only grows, serialised by the lock, never go backwards. */
static void report_progress(render_job *job)
{
    if (!atomic_load(&job->cancelled) &&
        job->opt.progress(job->opt.progress_user,
                          (double)atomic_load(&job->tiles_done) / (double)job->tile_count))
        atomic_store(&job->cancelled, 1);
}

/* Called from inside shading every HR_POLL_INTERVAL rays: report progress
 * (and so let the callback cancel) without waiting for the tile to end. A
 * busy lock means another thread is reporting: skip, the next poll comes. */
static void poll_progress(void *user)
{
    render_job *job = user;
    if (!job->opt.progress || pthread_mutex_trylock(&job->progress_lock) != 0) return;
    report_progress(job);
    pthread_mutex_unlock(&job->progress_lock);
}

/* The stored pixel (x, y) of the full image, inside the window. */
static float *pixel_at(const render_job *job, int32_t x, int32_t y)
{
    return &job->pixels[3 * ((size_t)(y - job->win_y) * job->win_width + (size_t)(x - job->win_x))];
}

/* A camera ray with its differentials (lib/trace/ray_diff.h), scaled by
 * the share of a pixel its sample stands for (sx, sy pixels). The image
 * plane's point moves by d(plane x)/d(px) = 2 half_width / width along u
 * per pixel, and by -2 half_height / height along v. */
static __attribute__((noinline)) hr_color trace_camera_ray_diff(worker *w, const hr_ray *ray, double px,
                                                               double py, double sx, double sy)
{
    const hr_camera_frame *f = &w->job->frame;
    const double x = hri_camera_frame_x(f, px), y = hri_camera_frame_y(f, py);
    const hr_vec3 dir = v3_add(v3_add(v3_scale(f->u, x), v3_scale(f->v, y)), v3_neg(f->n));
    hr_ray_diff rd = hri_ray_diff_camera(dir, v3_scale(f->u, 2.0 * f->half_width / f->width),
                                         v3_scale(f->v, -2.0 * f->half_height / f->height));
    rd = hri_ray_diff_scale(rd, sx, sy);
    return hri_shade_ray_diff(&w->tc, ray, &rd, 0, w->job->max_depth);
}

/* The ray of a sample at (px, py) standing for sx x sy pixels. */
static hr_color trace_camera_ray(worker *w, double px, double py, double sx, double sy)
{
    render_job *job = w->job;
    hr_ray ray;
    hri_camera_frame_ray(&job->frame, px, py, &ray);
    w->primary++;
    if (job->differentials) return trace_camera_ray_diff(w, &ray, px, py, sx, sy);
    return hri_shade_ray(&w->tc, &ray, 0, job->max_depth);
}

/* The caller's own flag (hr_render_options.cancel). */
static int caller_cancelled(const render_job *job)
{
    return job->opt.cancel && __atomic_load_n(job->opt.cancel, __ATOMIC_RELAXED);
}

/* The full pattern over a pixel (or Hill's block) at (bx, by) of size
 * bw x bh: the value a full render gives it. Once the render is cancelled
 * the rest of the pattern is skipped: each of its rays would return at once,
 * but a pixel of 65536 samples would still cost 65536 turns of the loop, and
 * a tile of them seconds. */
static void full_pixel(worker *w, int32_t bx, int32_t by, double bw, double bh, float *px)
{
    int32_t spp = w->job->opt.samples_per_pixel;
    uint64_t over_before = w->tc.rays_over_budget;
    hr_color sum = rgb(0, 0, 0);
    /* Each of n samples stands for 1 / sqrt(n) of the block's side. */
    const double share = spp > 1 ? 1.0 / sqrt((double)spp) : 1.0;
    for (int32_t k = 0; k < spp; k++) {
        if (atomic_load_explicit(&w->job->cancelled, memory_order_relaxed) || caller_cancelled(w->job)) break;
        double dx, dy;
        sample_offset(k, spp, &dx, &dy);
        sum = rgb_add(sum, trace_camera_ray(w, bx + dx * bw, by + dy * bh, bw * share, bh * share));
    }
    px[0] = (float)(sum.r / spp), px[1] = (float)(sum.g / spp), px[2] = (float)(sum.b / spp);
    w->pixels_over_budget += w->tc.rays_over_budget != over_before;
}

/* One row of render_tile_centres: n pixels from px on, the plane's x of
 * each in w->columns. Only a `budgeted` row (one whose rays can reach the
 * ray budget: tc.budget_free_levels) asks after each ray whether it did. */
static inline __attribute__((always_inline)) void
centres_row(worker *w, const hr_camera_frame *f, double plane_y, float *px, int32_t n, const int budgeted)
{
    const int32_t max_depth = w->job->max_depth;
    for (int32_t i = 0; i < n; i++, px += 3) {
        hr_ray ray;
        hri_camera_frame_ray_xy(f, w->columns[i], plane_y, &ray);
        uint64_t over_before = budgeted ? w->tc.rays_over_budget : 0;
        hr_color c = budgeted ? hri_shade_ray(&w->tc, &ray, 0, max_depth)
                              : hri_shade_ray_unbudgeted(&w->tc, &ray, 0, max_depth);
        if (budgeted) w->pixels_over_budget += w->tc.rays_over_budget != over_before;
        px[0] = (float)(0.0 + c.r), px[1] = (float)(0.0 + c.g), px[2] = (float)(0.0 + c.b);
    }
}

/* One ray through each pixel's centre (one sample a pixel, no blocks), the
 * common render: the bits full_pixel gives such a pixel (its one sample is
 * the centre, x + 0.5 * 1.0, and its sum +0 plus the colour, divided by 1),
 * with the plane's x worked out once for each column of the tile and its y
 * once for each row, not both for every ray. No cancel test per pixel:
 * shade makes one per ray. */
static void render_tile_centres(worker *w, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    render_job *job = w->job;
    const hr_camera_frame *f = &job->frame;
    const int budgeted = job->max_depth > w->tc.budget_free_levels;
    for (int32_t x = x0; x < x1; x++) w->columns[x - x0] = hri_camera_frame_x(f, x + 0.5);
    for (int32_t y = y0; y < y1; y++) {
        const double plane_y = hri_camera_frame_y(f, y + 0.5);
        float *px = pixel_at(job, x0, y);
        if (budgeted)
            centres_row(w, f, plane_y, px, x1 - x0, 1);
        else
            centres_row(w, f, plane_y, px, x1 - x0, 0);
        w->primary += (uint64_t)(x1 - x0);
    }
}

static void render_tile_full(worker *w, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    render_job *job = w->job;
    int32_t block = job->opt.block_size;
    /* Blocks are aligned to the full image, not the tile or the window, so a
     * block that straddles tiles or windows gets the same colour in each:
     * copying from a neighbour inside the tile gives the bits tracing the
     * block's ray again would. */
    for (int32_t y = y0; y < y1; y++) {
        for (int32_t x = x0; x < x1; x++) {
            int32_t bx = x - x % block, by = y - y % block;
            if (block > 1 && x != bx && x != x0) {
                /* Copy from the pixel to the left, inside this tile and block. */
                memcpy(pixel_at(job, x, y), pixel_at(job, x - 1, y), 3 * sizeof(float));
                continue;
            }
            if (block > 1 && y != by && y != y0) {
                memcpy(pixel_at(job, x, y), pixel_at(job, x, y - 1), 3 * sizeof(float));
                continue;
            }
            /* One pixel, or the one ray of a block over its whole area. */
            double bw = block < job->width - bx ? block : job->width - bx;
            double bh = block < job->height - by ? block : job->height - by;
            full_pixel(w, bx, by, bw, bh, pixel_at(job, x, y));
        }
    }
}

static corner_sample sample_corner(worker *w, int32_t x, int32_t y)
{
    corner_sample c;
    uint64_t over_before = w->tc.rays_over_budget;
    c.linear = trace_camera_ray(w, x, y, 1.0, 1.0);
    c.over_budget = w->tc.rays_over_budget != over_before;
    c.shown[0] = hri_srgb_encode(c.linear.r);
    c.shown[1] = hri_srgb_encode(c.linear.g);
    c.shown[2] = hri_srgb_encode(c.linear.b);
    return c;
}

/* The adaptive test: do the four corners of a pixel differ, in some
 * channel as shown, by more than the threshold? */
static int corners_differ(const corner_sample *a, const corner_sample *b, const corner_sample *c,
                          const corner_sample *d, double threshold)
{
    for (int i = 0; i < 3; i++) {
        double lo = fmin(fmin(a->shown[i], b->shown[i]), fmin(c->shown[i], d->shown[i]));
        double hi = fmax(fmax(a->shown[i], b->shown[i]), fmax(c->shown[i], d->shown[i]));
        if (hi - lo > threshold) return 1;
    }
    return 0;
}

/* Adaptive supersampling, one row of pixels at a time: the corner row above
 * and the one below, then each pixel either refined (the full pattern) or
 * given the mean of its corners. */
static void render_tile_adaptive(worker *w, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    render_job *job = w->job;
    int32_t n = x1 - x0 + 1;
    corner_sample *above = w->corners, *below = w->corners + job->opt.tile_size + 1;
    for (int32_t i = 0; i < n; i++) above[i] = sample_corner(w, x0 + i, y0);
    for (int32_t y = y0; y < y1; y++) {
        for (int32_t i = 0; i < n; i++) below[i] = sample_corner(w, x0 + i, y + 1);
        for (int32_t x = x0; x < x1; x++) {
            int32_t i = x - x0;
            float *px = pixel_at(job, x, y);
            if (corners_differ(&above[i], &above[i + 1], &below[i], &below[i + 1],
                               job->opt.adaptive_threshold)) {
                full_pixel(w, x, y, 1.0, 1.0, px);
                w->pixels_refined++;
                continue;
            }
            hr_color sum = rgb_add(rgb_add(above[i].linear, above[i + 1].linear),
                                   rgb_add(below[i].linear, below[i + 1].linear));
            w->pixels_over_budget += above[i].over_budget || above[i + 1].over_budget ||
                                     below[i].over_budget || below[i + 1].over_budget;
            px[0] = (float)(sum.r / 4), px[1] = (float)(sum.g / 4), px[2] = (float)(sum.b / 4);
        }
        corner_sample *t = above;
        above = below, below = t;
    }
}

/* Render one tile: pixels x0 .. x1 - 1 of rows y0 .. y1 - 1 of the full
 * image, a tile_size square of the window's grid cut at its edges. Returns
 * 1 when every ray of it was traced to the end: neither the render's flag
 * nor the caller's was seen raised. Each flag is one memory location that
 * only ever goes from 0 to 1, so a load of 0 here, after the tile, means
 * every load of it during the tile read 0 too (read-read coherence): no ray
 * or sample loop was cut short, and the pixels are final. */
static int render_tile(worker *w, int64_t tile, int32_t *x0, int32_t *y0, int32_t *x1, int32_t *y1)
{
    render_job *job = w->job;
    int32_t tsize = job->opt.tile_size;
    *x0 = job->win_x + (int32_t)(tile % job->tiles_x) * tsize;
    *y0 = job->win_y + (int32_t)(tile / job->tiles_x) * tsize;
    int32_t xend = job->win_x + job->win_width, yend = job->win_y + job->win_height;
    *x1 = tsize < xend - *x0 ? *x0 + tsize : xend;
    *y1 = tsize < yend - *y0 ? *y0 + tsize : yend;
    if (job->opt.adaptive_threshold > 0) render_tile_adaptive(w, *x0, *y0, *x1, *y1);
    else if (w->columns) render_tile_centres(w, *x0, *y0, *x1, *y1);
    else render_tile_full(w, *x0, *y0, *x1, *y1);
    if (w->tc.status) {
        pthread_mutex_lock(&job->progress_lock);
        if (!job->failure) job->failure = w->tc.status;
        pthread_mutex_unlock(&job->progress_lock);
        atomic_store(&job->cancelled, 1);
    }
    return !atomic_load(&job->cancelled) && !caller_cancelled(job);
}

/* Hand a finished tile to the caller (hr_render_options.tile_done), in the
 * output image's coordinates: the window's, whose origin is (win_x, win_y)
 * of the full image. */
static void report_tile(const render_job *job, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    job->opt.tile_done(job->opt.tile_user, x0 - job->win_x, y0 - job->win_y, x1 - x0, y1 - y0,
                       pixel_at(job, x0, y0), 3 * job->win_width);
}

static void *worker_main(void *arg)
{
    worker *w = arg;
    render_job *job = w->job;
    int32_t outer_level = hr_query_nesting();
    hr_query_set_nesting(job->query_level);
    for (;;) {
        if (atomic_load(&job->cancelled) || caller_cancelled(job)) break;
        int64_t tile = atomic_fetch_add(&job->next_tile, 1);
        if (tile >= job->tile_count) break;
        int32_t x0, y0, x1, y1;
        int final = render_tile(w, tile, &x0, &y0, &x1, &y1);
        /* Before the tile is counted, so no progress fraction counts a tile
         * whose tile_done has not returned. */
        if (final && job->opt.tile_done) report_tile(job, x0, y0, x1, y1);
        atomic_fetch_add(&job->tiles_done, 1);
        if (job->opt.progress) {
            pthread_mutex_lock(&job->progress_lock);
            report_progress(job);
            pthread_mutex_unlock(&job->progress_lock);
        }
    }
    hr_query_set_nesting(outer_level);
    return NULL;
}

/* A worker's own buffer, on whole cache lines: read or written on every
 * ray, it must not share a line with what another thread writes as often
 * (its neighbour on the heap may be the other worker's). */
static void *worker_alloc(size_t bytes)
{
    return aligned_alloc(HR_CACHE_LINE, (bytes + HR_CACHE_LINE - 1) / HR_CACHE_LINE * HR_CACHE_LINE);
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
    return n < 1 ? 1 : n > HR_RENDER_MAX_THREADS ? HR_RENDER_MAX_THREADS : (int32_t)n;
}

/* The window, once the image size is known: a width or height of 0 reaches
 * to the image's edge; what is left must lie inside the image. Sums are
 * taken in 64 bits, so no window overflows on its way to the check. */
static hr_status check_window(hr_context *ctx, hr_render_options *o)
{
    if (o->window_x < 0 || o->window_y < 0 || o->window_width < 0 || o->window_height < 0)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: window x %d, y %d, width %d, height %d must not be negative",
                        (int)o->window_x, (int)o->window_y, (int)o->window_width, (int)o->window_height);
    if (o->window_x >= o->width || o->window_y >= o->height)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: window origin (%d, %d) lies outside the %dx%d image", (int)o->window_x,
                        (int)o->window_y, (int)o->width, (int)o->height);
    if (o->window_width == 0) o->window_width = o->width - o->window_x;
    if (o->window_height == 0) o->window_height = o->height - o->window_y;
    if ((int64_t)o->window_x + o->window_width > o->width ||
        (int64_t)o->window_y + o->window_height > o->height)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: window %dx%d at (%d, %d) reaches past the %dx%d image", (int)o->window_width,
                        (int)o->window_height, (int)o->window_x, (int)o->window_y, (int)o->width,
                        (int)o->height);
    return HR_OK;
}

static hr_status check_options(hr_context *ctx, hr_render_options *o, const hr_camera *cam)
{
    char shown[HR_SHORTEST_BYTES]; /* a value in a message (hri_shortest) */
    if (o->width == 0) o->width = cam->width;
    if (o->height == 0) o->height = cam->height;
    if (o->samples_per_pixel == 0) o->samples_per_pixel = 1;
    if (o->block_size == 0) o->block_size = 1;
    if (o->tile_size == 0) o->tile_size = DEFAULT_TILE;
    if (o->width <= 0 || o->height <= 0 || o->width > HR_RENDER_MAX_SIDE || o->height > HR_RENDER_MAX_SIDE)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: image size %dx%d must be within 1..%d",
                        (int)o->width, (int)o->height, HR_RENDER_MAX_SIDE);
    if (o->samples_per_pixel < 1 || o->samples_per_pixel > HR_RENDER_MAX_SAMPLES)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: samples per pixel %d must be within 1..%d",
                        (int)o->samples_per_pixel, HR_RENDER_MAX_SAMPLES);
    if (o->threads < 0 || o->threads > HR_RENDER_MAX_THREADS)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: threads %d must be within 0..%d",
                        (int)o->threads, HR_RENDER_MAX_THREADS);
    if (o->block_size < 1 || o->block_size > HR_RENDER_MAX_BLOCK)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: block size %d must be within 1..%d",
                        (int)o->block_size, HR_RENDER_MAX_BLOCK);
    if (o->tile_size < 1 || o->tile_size > HR_RENDER_MAX_TILE)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: tile size %d must be within 1..%d",
                        (int)o->tile_size, HR_RENDER_MAX_TILE);
    if (o->max_depth > HR_MAX_RECURSION_DEPTH)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: depth %d must be at most %d",
                        (int)o->max_depth, HR_MAX_RECURSION_DEPTH);
    if (o->effects != HR_EFFECTS_AUTO && o->effects != HR_EFFECTS_ALL)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: effects must be HR_EFFECTS_AUTO or HR_EFFECTS_ALL");
    if (!(o->adaptive_threshold >= 0.0 && o->adaptive_threshold <= 1.0))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: adaptive threshold %s must be within 0..1 (0: off)", hri_shortest(o->adaptive_threshold, shown));
    if (o->adaptive_threshold > 0.0 && o->samples_per_pixel < 2)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: adaptive supersampling needs samples per pixel >= 2 (the most a pixel gets)");
    if (o->adaptive_threshold > 0.0 && o->block_size > 1)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: adaptive supersampling works on single pixels: block size must be 1");
    if (!(o->min_weight >= 0.0 && o->min_weight <= 1.0))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: minimum weight %s must be within 0..1 (0: the default, 2^-24)", hri_shortest(o->min_weight, shown));
    if (o->exact != 0 && o->exact != 1)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: exact must be 0 or 1, not %d", (int)o->exact);
    if (o->exact && o->min_weight > 0.0)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: exact (trace every contribution) and a minimum weight %s exclude each other",
                        hri_shortest(o->min_weight, shown));
    if (o->ray_budget < 0)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: ray budget %lld must be positive (0: the default, %d rays per camera sample)",
                        (long long)o->ray_budget, HR_DEFAULT_RAY_BUDGET);
    if (o->texture_filter != HR_TEXTURE_FILTER_FOOTPRINT && o->texture_filter != HR_TEXTURE_FILTER_NONE)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: texture filter %d must be HR_TEXTURE_FILTER_FOOTPRINT (0) or "
                        "HR_TEXTURE_FILTER_NONE (1)",
                        (int)o->texture_filter);
    if (o->exact && o->ray_budget > 0)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "render: exact (trace every contribution) and a ray budget %lld exclude each other",
                        (long long)o->ray_budget);
    return check_window(ctx, o);
}

/* The ray budget's warning: how many pixels lost rays to it, so that a
 * faint error in them is never silent. */
static void warn_over_budget(const render_job *job, const worker *workers, int32_t started)
{
    uint64_t pixels = 0;
    for (int32_t i = 0; i < started; i++) pixels += workers[i].pixels_over_budget;
    if (pixels == 0) return;
    int64_t budget = job->opt.ray_budget > 0 ? job->opt.ray_budget : HR_DEFAULT_RAY_BUDGET;
    hri_warn(job->scene->ctx, HR_WARNING_RAY_BUDGET, NULL, 0, 0,
            "render: %llu of %llu pixels reached the ray budget of %lld rays per camera sample, so their "
            "faintest reflections and refractions were not traced (raise it with a larger ray budget, or "
            "trace everything with exact)",
            (unsigned long long)pixels, (unsigned long long)job->win_width * (unsigned long long)job->win_height,
            (long long)budget);
}

HR_API hr_status hr_render(const hr_scene *scene, const hr_camera *camera,
                           const hr_render_options *options, hr_image **out_image,
                           hr_render_stats *stats)
{
    if (!scene) return HR_ERROR_INVALID_ARGUMENT;
    hr_context *ctx = scene->ctx;
    if (!out_image) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: NULL output image");
    *out_image = NULL;
    if (!scene->committed)
        return hri_error(ctx, HR_ERROR_STATE, "render: the scene is not committed (call hr_scene_commit)");
    if (!camera || camera->struct_size < sizeof(uint32_t))
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render: NULL camera or struct_size not set");
    /* The render's threads trace one level deeper than the caller: a shape
     * that renders its own scene from its hit is stopped like one that
     * queries it. */
    int32_t *level;
    hr_status nesting = hri_query_enter(ctx, "render", &level);
    if (nesting) return nesting;
    int32_t query_level = *level;
    hri_query_leave(level);
    /* Aligned, or the job's lines would be split differently from its
     * fields (sizeof is a multiple of the alignment, as aligned_alloc needs). */
    render_job *job = aligned_alloc(HR_CACHE_LINE, sizeof *job);
    if (!job) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    memset(job, 0, sizeof *job);
    job->scene = scene;
    job->query_level = query_level;
    hr_camera_default(&job->camera);
    HR_SIZED_COPY_IN(&job->camera, camera);
    hr_render_options_default(&job->opt);
    if (options) {
        if (options->struct_size < sizeof(uint32_t)) {
            free(job);
            return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "render options: struct_size not set");
        }
        HR_SIZED_COPY_IN(&job->opt, options);
    }
    hr_status st = check_options(ctx, &job->opt, &job->camera);
    if (st == HR_OK) {
        job->camera.width = job->opt.width, job->camera.height = job->opt.height;
        st = hr_camera_validate(ctx, &job->camera);
        /* A camera hr_camera_validate accepts always has a frame. */
        if (st == HR_OK && !hri_camera_frame_init(&job->frame, &job->camera))
            st = hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "camera: no view through it");
    }
    hr_image *image = NULL;
    if (st == HR_OK) st = hri_image_create_unset(ctx, job->opt.window_width, job->opt.window_height, 3, &image);
    if (st) {
        free(job);
        return st;
    }
    job->pixels = hr_image_data(image);
    job->width = job->opt.width, job->height = job->opt.height;
    job->win_x = job->opt.window_x, job->win_y = job->opt.window_y;
    job->win_width = job->opt.window_width, job->win_height = job->opt.window_height;
    job->max_depth = job->opt.max_depth >= 0 ? job->opt.max_depth : scene->globals.max_recursion_depth;
    job->tiles_x = (job->win_width + job->opt.tile_size - 1) / job->opt.tile_size;
    job->tiles_y = (job->win_height + job->opt.tile_size - 1) / job->opt.tile_size;
    job->tile_count = job->tiles_x * job->tiles_y;
    pthread_mutex_init(&job->progress_lock, NULL);

    int32_t nthreads = job->opt.threads > 0 ? job->opt.threads : core_count();
    if (nthreads > job->tile_count) nthreads = (int32_t)job->tile_count;
    /* sizeof(worker) is a multiple of its alignment, as aligned_alloc needs. */
    worker *workers = aligned_alloc(HR_CACHE_LINE, (size_t)nthreads * sizeof *workers);
    if (workers) memset(workers, 0, (size_t)nthreads * sizeof *workers);
    int adaptive = job->opt.adaptive_threshold > 0.0;
    /* Differentials only where a texture is shaded: any other scene runs
     * the shading it ran without them. */
    job->differentials = (scene->effects & HR_EFFECT_TEXTURE) && job->opt.texture_filter == HR_TEXTURE_FILTER_FOOTPRINT;
    int centres = !adaptive && job->opt.samples_per_pixel == 1 && job->opt.block_size == 1 && !job->differentials;
    int ready = workers != NULL;
    for (int32_t i = 0; ready && i < nthreads; i++) {
        worker *w = &workers[i];
        w->job = job;
        hri_trace_ctx_init(&w->tc, scene);
        w->tc.force_all_effects = job->opt.effects == HR_EFFECTS_ALL;
        hri_trace_ctx_set_bounds(&w->tc, job->opt.exact, job->opt.min_weight, job->opt.ray_budget);
        w->tc.cancelled = &job->cancelled;
        w->tc.cancel_flag = job->opt.cancel;
        w->tc.poll = poll_progress;
        w->tc.poll_user = job;
        if (adaptive) {
            w->corners = worker_alloc(2 * ((size_t)job->opt.tile_size + 1) * sizeof *w->corners);
            ready = w->corners != NULL;
        } else if (centres) {
            w->columns = worker_alloc((size_t)job->opt.tile_size * sizeof *w->columns);
            ready = w->columns != NULL;
        }
    }
    double t0 = now_seconds();
    int32_t started = 0;
    if (ready) {
        /* The calling thread is worker 0; the others are started here. */
        for (started = 1; started < nthreads; started++)
            if (pthread_create(&workers[started].thread, NULL, worker_main, &workers[started]) != 0) break;
        worker_main(&workers[0]);
        for (int32_t i = 1; i < started; i++) pthread_join(workers[i].thread, NULL);
    }
    double seconds = now_seconds() - t0;
    if (!ready) st = hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    else if (job->failure) st = hri_error(ctx, job->failure, "render: a shape failed while tracing: %s",
                                         hr_status_name(job->failure));
    else if (atomic_load(&job->cancelled) || caller_cancelled(job))
        st = hri_error(ctx, HR_ERROR_CANCELLED, "render cancelled");
    if (st == HR_OK) warn_over_budget(job, workers, started);
    if (st == HR_OK && stats && stats->struct_size >= sizeof(uint32_t)) {
        hr_render_stats s = {0};
        s.threads = started;
        for (int32_t i = 0; i < started; i++) {
            s.primary += workers[i].primary;
            s.shadow += workers[i].tc.rays_shadow;
            s.reflected += workers[i].tc.rays_reflected;
            s.refracted += workers[i].tc.rays_refracted;
            s.rays_cut += workers[i].tc.rays_cut;
            s.rays_over_budget += workers[i].tc.rays_over_budget;
            s.pixels_over_budget += workers[i].pixels_over_budget;
            s.pixels_refined += workers[i].pixels_refined;
            s.effects |= workers[i].tc.effects_ran;
        }
        s.seconds = seconds;
        if (job->opt.samples_per_pixel > 1) s.effects |= HR_EFFECT_SUPERSAMPLING;
        if (adaptive)
            s.samples_saved =
                (int64_t)job->win_width * job->win_height * job->opt.samples_per_pixel - (int64_t)s.primary;
        HR_SIZED_COPY_OUT(stats, &s);
    }
    for (int32_t i = 0; workers && i < nthreads; i++) {
        hri_trace_ctx_release(&workers[i].tc);
        free(workers[i].corners);
        free(workers[i].columns);
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
