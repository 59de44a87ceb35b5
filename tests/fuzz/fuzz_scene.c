/* Fuzz harness: the whole pipeline, as the `hitray render` command runs it.
 *
 * The input is SDL text (up to its first NUL byte): it is read with the
 * real shape modules (hr_sdl_load_string), committed, and rendered at 4x3
 * pixels through the file's camera (or the framed one); every step either
 * succeeds or fails with a message, and a render that succeeds gives an
 * image whose every value is finite (no NaN pixel, no infinity: the
 * contract of shade and of every shape behind it). The depth is the file's,
 * capped at 8 so an input costs at most a few thousand rays a pixel (the
 * default contribution cut-off bounds the rest); the render runs on two
 * threads in tiles of one pixel, so the thread pool and the per-thread
 * trace contexts are in the path (the image must not depend on them: a
 * second render on one thread, in two windows split at a column the input
 * picks, must give the same bits). Relative mesh names
 * resolve in tests/data/meshes. Never a crash, a hang (-timeout) or a leak.
 *
 * The scene memory budget is SCENE_MEMORY (16 MB), not the default (half
 * of what the process may use): the work of a render grows with what the
 * scene holds, and libFuzzer's -timeout wants each input bounded in time,
 * not only in memory. A thousand teapots from nested macros (1.1 MB each,
 * within the default budget) took over 10 s to build under coverage. A
 * scene past the budget is refused with its message, a path the harness
 * checks like any other error. */
#include <math.h>
#include <string.h>

#include <hitray/hitray.h>

#include "fuzz_input.h"
#include "fuzz_sdl_text.h"
#define WIDTH 4
#define HEIGHT 3
#define MAX_DEPTH 8
#define SCENE_MEMORY (16u << 20)

static hr_context *ctx;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    if (hr_context_create(&ctx) != HR_OK) fuzz_fail("scene: no context");
    if (hr_context_set_scene_memory(ctx, SCENE_MEMORY) != HR_OK) fuzz_fail("scene: no scene memory budget");
    hr_context_module_count(ctx); /* every module loaded now: coverage from the start */
    return 0;
}

static void require_message(const char *step, hr_status st)
{
    if (!hr_context_last_error(ctx)[0]) fuzz_fail("scene: %s failed (status %d) without a message", step, (int)st);
}

/* A render of the WIDTH x HEIGHT image, or of the window of its columns
 * x0 .. x0 + columns - 1 (columns 0: the whole image). */
static hr_image *render(const hr_scene *scene, const hr_camera *camera, int32_t threads, int32_t depth,
                        int32_t x0, int32_t columns, hr_status *st)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = WIDTH, o.height = HEIGHT;
    o.window_x = x0, o.window_width = columns;
    o.threads = threads;
    o.tile_size = 1;
    o.max_depth = depth;
    hr_image *image = NULL;
    *st = hr_render(scene, camera, &o, &image, NULL);
    if (*st == HR_OK && !image) fuzz_fail("scene: render succeeded with no image");
    if (*st != HR_OK && image) fuzz_fail("scene: render failed (status %d) with an image", (int)*st);
    return image;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    hr_sdl_result r;
    size_t length;
    hr_status st = fuzz_load_sdl(ctx, data, size, &r, &length);
    if (st == HR_ERROR_OUT_OF_MEMORY && !r.scene) return 0;
    if (st != HR_OK) {
        if (r.scene) fuzz_fail("scene: load failed (status %d) and still a scene", (int)st);
        require_message("load", st);
        return 0;
    }
    if (!r.scene) fuzz_fail("scene: HR_OK and no scene");
    if ((st = hr_scene_commit(r.scene)) != HR_OK) {
        require_message("commit", st);
        hr_scene_destroy(r.scene);
        return 0;
    }
    hr_scene_globals g = {.struct_size = sizeof g};
    int32_t depth = MAX_DEPTH;
    if (hr_scene_get_globals(r.scene, &g) == HR_OK && g.max_recursion_depth < MAX_DEPTH)
        depth = g.max_recursion_depth;
    hr_image *image = render(r.scene, &r.camera, 2, depth, 0, 0, &st);
    if (!image) {
        require_message("render", st);
        hr_scene_destroy(r.scene);
        return 0;
    }
    const float *px = hr_image_data(image);
    for (int i = 0; i < WIDTH * HEIGHT * 3; i++)
        if (!isfinite(px[i]))
            fuzz_fail("scene: pixel %d channel %d is %g", i / 3, i % 3, (double)px[i]);
    const int32_t split = 1 + (int32_t)(size % (WIDTH - 1)); /* 1 .. WIDTH - 1 */
    for (int half = 0; half < 2; half++) {
        const int32_t x0 = half ? split : 0, columns = half ? WIDTH - split : split;
        hr_image *again = render(r.scene, &r.camera, 1, depth, x0, columns, &st);
        if (!again)
            fuzz_fail("scene: the render of a window failed (status %d): %s", (int)st, hr_context_last_error(ctx));
        if (hr_image_width(again) != columns || hr_image_height(again) != HEIGHT)
            fuzz_fail("scene: a window of %d columns gave a %dx%d image", (int)columns, (int)hr_image_width(again),
                      (int)hr_image_height(again));
        const float *w = hr_image_data(again);
        for (int32_t y = 0; y < HEIGHT; y++)
            if (memcmp(&px[3 * (y * WIDTH + x0)], &w[3 * y * columns], sizeof(float) * 3 * (size_t)columns) != 0)
                fuzz_fail("scene: row %d of the window at column %d on one thread differs from the image on two",
                          (int)y, (int)x0);
        hr_image_destroy(again);
    }
    hr_image_destroy(image);
    hr_scene_destroy(r.scene);
    return 0;
}
