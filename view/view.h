/* hitray-view: Hill's raytrace loop in a window (`hitray view`).
 *
 * Hill's Camera::raytrace(scn, blockSize) runs from the display callback and
 * paints one colour per block, so a coarse picture shows at once and then
 * sharpens. The viewer does the same with the public API alone: a render
 * thread calls hr_render once per pass (blocks of 16, 8, 4, 2, 1 pixels, one
 * ray each, then the full-quality pass), the window shows each finished pass
 * in place of the last, and a camera key (Hill's slide, roll, pitch, yaw)
 * cancels the pass in flight (hr_render_options.cancel) and starts the
 * refinement again.
 *
 * The files: view_main.c (options, the order of the checks, the event
 * loop), view_passes.c (which passes), view_render.c (the render thread),
 * view_keys.c (keys to camera moves), view_save_path.c (the P key's file
 * names), view_status.c (the window title),
 * view_pixels.c (linear light to the window's 8-bit sRGB). Only the window
 * code (view_main.c, view_window.c) knows SDL. */
#ifndef HITRAY_VIEW_H
#define HITRAY_VIEW_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/hitray.h>

/* --- the passes (view_passes.c) --- */

/* Hill's coarsest block, and one more pass for the full quality. */
#define VIEW_FIRST_BLOCK 16
#define VIEW_MAX_PASSES 6

typedef struct view_pass {
    int32_t block_size;        /* one ray per block_size x block_size pixels */
    int32_t samples_per_pixel; /* 1 for the preview passes */
} view_pass;

/* The passes down to `finest_block` with `spp` samples: Hill's blocks 16, 8,
 * 4, 2, 1 coarser than finest_block, one ray each, then finest_block at spp
 * (where spp > 1, also finest_block at one ray first, so the picture has
 * every detail before the slow pass starts). Returns the count (1..6). */
int view_pass_plan(int32_t finest_block, int32_t spp, view_pass out[VIEW_MAX_PASSES]);

/* --- the render thread (view_render.c) --- */

/* One finished pass, handed from the render thread to the window. */
typedef struct view_frame {
    hr_image *image;        /* owned by whoever holds the frame */
    hr_camera camera;       /* what it was rendered with */
    uint64_t generation;    /* which refinement (one per camera) */
    int pass;               /* 0-based index into the plan */
    int passes;             /* the plan's length */
    view_pass settings;
    hr_render_stats stats;
    double since_restart;   /* seconds from the refinement's start to this pass's end */
} view_frame;

typedef struct view_renderer view_renderer;

/* A rectangle of the image: columns x .. x + width - 1 of rows y ..
 * y + height - 1, from the top left; empty where width or height is 0. */
typedef struct view_rect {
    int32_t x, y, width, height;
} view_rect;

/* Called when a frame is ready, the render failed, or finished tiles wait
 * to be taken (view_renderer_take_pixels): from the render thread and
 * hr_render's workers, so it must be thread-safe and quick (the window's
 * wake-up). */
typedef void (*view_notify_fn)(void *user);

/* Starts the thread on the first camera. `options` are the caller's
 * (threads, depth); the plan sets block size and samples per pass. The
 * scene must be committed and outlive the renderer. NULL if out of memory
 * or no thread could start (reported). */
view_renderer *view_renderer_start(const hr_scene *scene, hr_context *ctx, const hr_render_options *options,
                                   const view_pass *plan, int passes, const hr_camera *camera,
                                   view_notify_fn notify, void *notify_user);
/* Cancel what is in flight and refine `camera` from the first pass. The
 * first camera's refinement is generation 1; returns the new one's. */
uint64_t view_renderer_restart(view_renderer *r, const hr_camera *camera);
/* The newest finished frame not taken yet: 1 and *out filled (the caller
 * now owns out->image), or 0. Older frames were dropped unseen. */
int view_renderer_take(view_renderer *r, view_frame *out);
/* What the window is to show: the image's size (the options', else the
 * camera's) in 8-bit sRGB RGB, row by row from the top, 3 x width bytes a
 * row, every tile of the current camera's passes in place as it finished
 * (black before the first). `changed` is set to where it changed since the
 * last call (empty: nowhere). The pixels are the caller's to read until
 * its next call of this or view_renderer_restart; call both from one
 * thread (the window's). Every tile of a frame view_renderer_take has
 * handed out is in place by then. After a restart, no tile of an older
 * camera comes: the picture stays as it was until the new one's tiles
 * replace it. */
const uint8_t *view_renderer_take_pixels(view_renderer *r, view_rect *changed);
/* Where the refinement stands: the pass running (or `passes` when all are
 * done) and its fraction done. */
void view_renderer_progress(view_renderer *r, int *pass, double *fraction);
/* The render error of the current refinement, if any: 1 and the message
 * copied (one refinement fails at most once; the next camera tries again). */
int view_renderer_error(view_renderer *r, char *message, size_t size);
/* Cancel, join the thread, free everything. NULL: nothing. */
void view_renderer_stop(view_renderer *r);

/* --- camera keys (view_keys.c) --- */

/* What a key does; the window maps SDL's key codes to these. */
typedef enum view_action {
    VIEW_NONE,
    VIEW_FORWARD, VIEW_BACK, VIEW_LEFT, VIEW_RIGHT, VIEW_UP, VIEW_DOWN, /* slide */
    VIEW_YAW_LEFT, VIEW_YAW_RIGHT, VIEW_PITCH_UP, VIEW_PITCH_DOWN, VIEW_ROLL_LEFT, VIEW_ROLL_RIGHT,
    VIEW_FINER, VIEW_COARSER, /* halve / double the steps */
    VIEW_PRINT_CAMERA, VIEW_SAVE, VIEW_HELP, VIEW_QUIT,
} view_action;

typedef struct view_steps {
    double slide;   /* scene units per slide */
    double degrees; /* per roll, pitch or yaw */
} view_steps;

/* The first steps for a camera: a twentieth of the eye's distance to the
 * look-at point (so a key does as much in any scene's units), 5 degrees. */
view_steps view_steps_for(const hr_camera *cam);
/* Apply a move (or a step change) to the camera; 1 if the camera moved. */
int view_apply(view_action action, hr_camera *cam, view_steps *steps);
/* Keys in the words of --help and the H key. */
extern const char view_keys_help[];
/* "camera ex ey ez lx ly lz ux uy uz angle": the SDL line, every number
 * written so that it reads back to the same double. */
void view_camera_line(const hr_camera *cam, char *buf, size_t size);
/* "--camera ex,ey,ez,lx,ly,lz,ux,uy,uz,angle": the same camera as the
 * option of 'hitray render' and 'hitray view', numbers as above. */
void view_camera_option(const hr_camera *cam, char *buf, size_t size);

/* --- where P saves (view_save_path.c) --- */

/* `path` if no file has that name (`exists` says, given `user`), else the
 * first of path-2, path-3, ... (the number before the extension:
 * shot-2.png) that none has. 1 and the name in `out`, or 0 if it does not
 * fit in `size` or 100000 names are taken. */
int view_save_path(const char *path, int (*exists)(const char *path, void *user), void *user, char *out,
                   size_t size);

/* --- the status line (view_status.c) --- */

typedef struct view_status {
    const char *scene_name;
    int has_frame;          /* a pass of the current refinement finished */
    view_frame last;        /* that pass (image not used) */
    int running_pass;       /* the pass in flight, or passes when done */
    int passes;
    double running_fraction;
    const view_pass *plan;
    int32_t width, height;
    view_steps steps;
    const char *error;      /* the render's error, or NULL */
} view_status;

/* The window title: pass, rays/s, effects that ran, time to the final pass
 * (estimated while it runs, measured once it is done). */
void view_status_text(const view_status *s, char *buf, size_t size);

/* --- pixels (view_pixels.c) --- */

/* A rectangle of width x height linear RGB pixels (3 floats each, rows
 * `row_stride` floats apart: a tile as hr_tile_fn hands it over) as 8-bit
 * sRGB triples for the window, row by row from the top, `pitch` bytes a
 * row. The same curve as the PNG writer's (IEC 61966-2-1); the saved files
 * come from hr_image_write, not from this. */
void view_pixels_srgb8(const float *pixels, int32_t row_stride, int32_t width, int32_t height, uint8_t *out,
                       int pitch);

#endif
