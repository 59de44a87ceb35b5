/* hitray: rendering a committed scene through a camera into an image.
 *
 * Tiles are rendered on a pool of threads. The image depends only on the
 * scene, the camera and the options, never on the thread count or timing:
 * the same inputs give the same image bit for bit. */
#ifndef HITRAY_RENDER_H
#define HITRAY_RENDER_H

#include "camera.h"
#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Called from one thread at a time as tiles finish, and every 65536 rays
 * within a tile (so even a render stuck in one costly pixel can be stopped),
 * with the fraction of tiles done in [0, 1], never less than the one before
 * (the last is 1 for a render that ran to the end). Return non-zero to cancel:
 * hr_render then stops early and returns HR_ERROR_CANCELLED, with no image. */
typedef int32_t (*hr_progress_fn)(void *user, double fraction);

/* Called as each tile of the output image is finished, so a caller can show
 * or send a render's pixels before the whole image is done (a viewer draws
 * each pass as its tiles come, as Hill's raytrace loop paints its blocks).
 *
 * The tile is the rectangle of `width` x `height` pixels whose top-left
 * pixel is (x, y) of the output image, counted from its top left: of the
 * window where one is set (hr_render_options.window_*), so a window's
 * tiles are reported in the window's image, not the full one. `pixels` is
 * that pixel of the output image: 3 linear floats (R, G, B) a pixel, rows
 * `row_stride` floats apart (3 x the output image's width). They are the
 * final values, the same bits the returned image will hold, and no pixel
 * of the tile is written again; they stay readable until hr_render
 * returns (on success they are the returned image's; on failure the image
 * is freed), and must not be written.
 *
 * Each rectangle is at most tile_size pixels on a side; over a render that
 * runs to the end, they cover every pixel of the output image exactly once. Only finished tiles are reported: a tile
 * that a cancel (the progress callback, the `cancel` flag) or a shape's
 * failure may have cut short is not, so a render that ends with an error
 * may have reported some of its tiles (each final, as above) and never
 * reports the rest. The order of tiles is not defined.
 *
 * Threading: called from the render's worker thread that finished the
 * tile, and so from several threads at once (with threads > 1; the calling
 * thread is one of them): the function must be thread-safe, and quick, as
 * that thread renders nothing meanwhile. Every call returns before
 * hr_render does, and each tile's call returns before the progress
 * callback is given a fraction that counts that tile. */
typedef void (*hr_tile_fn)(void *user, int32_t x, int32_t y, int32_t width, int32_t height,
                           const float *pixels, int32_t row_stride);

#define HR_EFFECTS_AUTO 0 /* simulate only what the scene calls for */
#define HR_EFFECTS_ALL 1  /* run every effect's code path: a shadow ray to every
                             light, a reflected and a transmitted ray at every
                             hit down to the depth, each weighted by what the
                             material calls for (0 where nothing): the same
                             image, bit for bit, at the cost of the analysis
                             not done. For measuring what it saves. */

/* The bounds hr_render checks its options against, public so that a caller
 * can refuse a value before any work is done (the command line checks
 * --threads before it loads the scene) with the same limit the library
 * applies. */
#define HR_RENDER_MAX_SIDE 65536    /* width, height */
#define HR_RENDER_MAX_SAMPLES 65536 /* samples_per_pixel */
#define HR_RENDER_MAX_THREADS 256   /* threads */
#define HR_RENDER_MAX_BLOCK 4096    /* block_size */
#define HR_RENDER_MAX_TILE 4096     /* tile_size */

typedef struct hr_render_options {
    uint32_t struct_size;
    int32_t width;             /* 0: the camera's width */
    int32_t height;            /* 0: the camera's height */
    int32_t samples_per_pixel; /* 1 (default, 0 means 1): the pixel centre;
                                  more: a fixed stratified pattern */
    int32_t threads;           /* 0: every core */
    int32_t block_size;        /* Hill's blocksize: one ray per block of
                                  block_size x block_size pixels (1 = every
                                  pixel; 0 means 1) */
    int32_t max_depth;         /* < 0: the scene's maxRecursionDepth */
    int32_t tile_size;         /* 0: 32 pixels */
    int32_t effects;           /* HR_EFFECTS_AUTO or HR_EFFECTS_ALL */
    int32_t reserved;
    hr_progress_fn progress;   /* may be NULL */
    void *progress_user;
    /* Added after the first release: a caller whose struct_size ends before a
     * field gets its default, 0: off. */
    double adaptive_threshold; /* > 0: adaptive supersampling. Every pixel
                                  corner is sampled once; a pixel whose four
                                  corners differ by more than this (largest
                                  channel difference, display space: sRGB
                                  encoded, clamped to [0, 1]) gets the full
                                  samples_per_pixel pattern, the same bits as
                                  a full render; the others get the mean of
                                  their corners. Within [0, 1]; needs
                                  samples_per_pixel >= 2 and block_size 1. */
    double min_weight;         /* Contribution cut-off. A reflected or
                                  transmitted ray whose weight (the product
                                  of the reflectivities and transparencies
                                  along its path) is below this is not
                                  traced. Within [0, 1]; 0 (the default):
                                  the branching-aware cut-off below
                                  (HR_DEFAULT_MIN_WEIGHT_BITS), unless
                                  `exact`. */
    /* Added with the default cut-off (issue 16). */
    int32_t exact;             /* 1: trace every contribution, however small
                                  (min_weight must be 0): a deep scene of
                                  mirrors and glass may then take time
                                  exponential in the depth. 0 (default): the
                                  cut-off above. */
    int32_t reserved2;
    const int32_t *cancel;     /* may be NULL. A flag the caller may set to
                                  non-zero from any thread (an atomic store)
                                  to cancel: read before every ray, so the
                                  render stops within one ray of each thread,
                                  however slow its shapes (the progress
                                  callback is asked only every 65536 rays).
                                  hr_render then returns HR_ERROR_CANCELLED. */
    /* Added with the render window (issue 14). A rectangle of the image of
     * width x height: pixels window_x .. window_x + window_width - 1 of rows
     * window_y .. window_y + window_height - 1, counted from the top left.
     * The output image is the window's size (window_width x window_height),
     * and each of its pixels is bit for bit the same pixel of the full
     * render with the same options (samples, adaptive corners and Hill's
     * blocks are all placed on the full image), so windows that tile the
     * image give the full image exactly, however they cut tiles or blocks.
     * The statistics and the progress fraction count the window's work
     * only. All four 0 (the default): the whole image; a width or height
     * of 0 reaches to the image's right or bottom edge. The window must lie
     * inside the image. */
    int32_t window_x;
    int32_t window_y;
    int32_t window_width;
    int32_t window_height;
    /* Added with the viewer's tile-by-tile passes (issue 18): a caller whose
     * struct_size ends before tile_done gets no calls. */
    hr_tile_fn tile_done; /* may be NULL; see hr_tile_fn */
    void *tile_user;      /* handed to tile_done */
    /* Added with the ray budget (issue 29). */
    int64_t ray_budget; /* The most rays one camera sample may cast: itself,
                           its shadow rays, and every reflected and
                           transmitted ray below it with theirs. A hit that
                           spawns two bounces gives each half of what its
                           path has left, one bounce all of it; a bounce
                           whose share is under one ray is not traced, and
                           the render warns (HR_WARNING_RAY_BUDGET) with
                           the number of pixels that lost one. 0 (the
                           default): HR_DEFAULT_RAY_BUDGET, unless `exact`,
                           which has no budget; > 0: this budget (not with
                           `exact`). */
    /* Added with texture filtering (issue 30). */
    int32_t texture_filter; /* HR_TEXTURE_FILTER_FOOTPRINT (0, the default):
                               in a scene with a texture, camera rays carry
                               ray differentials through every reflection and
                               refraction, and each texture is averaged over
                               the hit's footprint (the solid textures in
                               closed form or band-limited, pixmaps by their
                               mip-maps); a scene without one traces none.
                               HR_TEXTURE_FILTER_NONE: every texture
                               point-sampled at the hit, as before. */
    int32_t reserved3;
} hr_render_options;

/* hr_render_options.texture_filter */
#define HR_TEXTURE_FILTER_FOOTPRINT 0
#define HR_TEXTURE_FILTER_NONE 1

/* The cut-off a render applies by default, 2^-24 of a camera sample in all:
 * POV-Ray's adc_bailout made small enough to be invisible, and made to
 * account for branching. A ray of weight w brings back at most w of its
 * colour; a cut-off of 2^-24 per ray would let 2^24 cut rays, each under
 * it, add up to the whole pixel where every hit branches in two. So the
 * allowance is shared out as the rays are: a camera ray starts with 2^-24,
 * a hit that spawns two bounces gives each half of its own, and a bounce
 * whose weight is below its allowance is not traced. The allowances of
 * everything cut add up to at most 2^-24, so what the cut-off drops from a
 * sample weighs under 2^-24 in all: under half a unit in the last place of
 * a float pixel of the same brightness. It bounds the error; the work is
 * bounded by the ray budget (HR_DEFAULT_RAY_BUDGET). The shipped and
 * benchmark scenes never come near either: no ray of theirs is cut
 * (docs/limits.md). An explicit min_weight is a cut-off per ray, not
 * shared out. */
#define HR_DEFAULT_MIN_WEIGHT_BITS 24 /* the cut-off is 2^-24 (an integer, so
                                        every binding can read it) */
/* The rays one camera sample may cast by default (hr_render_options
 * .ray_budget): far above what a scene of the book needs (depth 5 with two
 * bounces at every hit and eight lights is under 600), and low enough that
 * a camera inside nested glass at depth 1000 renders 16x12 pixels in
 * seconds rather than days. */
#define HR_DEFAULT_RAY_BUDGET 65536
HR_API void hr_render_options_default(hr_render_options *o);

typedef struct hr_render_stats {
    uint32_t struct_size;
    int32_t threads;    /* threads that ran */
    uint64_t primary;   /* rays from the camera */
    uint64_t shadow;    /* rays toward lights */
    uint64_t reflected;
    uint64_t refracted; /* transmitted rays (total internal reflection counts
                           as reflected) */
    double seconds;     /* wall time of the render */
    uint32_t effects;   /* HR_EFFECT_* bits whose code ran at least once
                           (so a mirror out of view adds no "reflection") */
    int32_t reserved;
    /* Added after the first release: written only as far as struct_size reaches. */
    uint64_t pixels_refined; /* adaptive: pixels given every sample */
    int64_t samples_saved;   /* adaptive: camera rays a full render would cast
                                (pixels x samples_per_pixel) minus `primary`;
                                negative where corner samples cost more than
                                they saved; 0 without adaptive */
    uint64_t rays_cut;       /* cut-off: reflected and transmitted rays not
                                traced (each also saves the rays it would
                                have spawned) */
    /* Added with the ray budget (issue 29). */
    uint64_t rays_over_budget;   /* reflected and transmitted rays not traced
                                    because their sample's budget was spent */
    uint64_t pixels_over_budget; /* pixels (Hill's blocks: each block once)
                                    with a sample that lost a ray so */
} hr_render_stats;

/* Render into a new image of width x height x 3 linear floats (the
 * window's size where a window is set). `stats` may be NULL. The scene must
 * be committed. */
HR_API hr_status hr_render(const hr_scene *scene, const hr_camera *camera,
                           const hr_render_options *options, hr_image **out_image,
                           hr_render_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
