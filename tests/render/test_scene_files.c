/* Every SDL scene the project ships or must read (the demo, the CSG scene,
 * the three real Hill files, and a scene per shape Hill names but the real
 * files do not use: tests/data/scenes/shapes/) renders end to end: finite pixels, something besides the
 * background, and the same bits with 1, 2 and 4 threads and with
 * supersampling (the demo and tapered_tube.sdl with their textures filtered,
 * the default: ray differentials too give the same bits for any thread
 * count). */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static const char *const scenes[] = {
    HR_TEST_SOURCE_DIR "/scenes/demo.sdl",
    HR_TEST_SOURCE_DIR "/scenes/csg.sdl",
    HR_TEST_SOURCE_DIR "/tests/data/scenes/hill/chair.dat",
    HR_TEST_SOURCE_DIR "/tests/data/scenes/hill/village.dat",
    HR_TEST_SOURCE_DIR "/tests/data/scenes/hill/room.dat",
    HR_TEST_SOURCE_DIR "/tests/data/scenes/shapes/torus.sdl",
    HR_TEST_SOURCE_DIR "/tests/data/scenes/shapes/teapot.sdl",
    HR_TEST_SOURCE_DIR "/tests/data/scenes/shapes/buckyball.sdl",
    HR_TEST_SOURCE_DIR "/tests/data/scenes/shapes/tapered_tube.sdl",
};

#define W 96
#define H 72

static hr_image *render(hr_context *ctx, hr_scene *s, const hr_camera *cam, int32_t threads,
                        int32_t spp)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = W, o.height = H, o.threads = threads, o.samples_per_pixel = spp;
    o.tile_size = 16;
    hr_image *img = NULL;
    CHECK_MSG(hr_render(s, cam, &o, &img, NULL) == HR_OK, "render: %s", hr_context_last_error(ctx));
    return img;
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        hr_sdl_result r = {0};
        r.struct_size = sizeof r;
        if (hr_sdl_load_file(ctx, scenes[i], &r) != HR_OK) {
            CHECK_MSG(0, "%s: %s", scenes[i], hr_context_last_error(ctx));
            continue;
        }
        CHECK_OK(hr_scene_commit(r.scene));
        hr_scene_globals g = {0};
        g.struct_size = sizeof g;
        hr_scene_get_globals(r.scene, &g);
        hr_image *one = render(ctx, r.scene, &r.camera, 1, 1);
        if (one) {
            const float *p = hr_image_data(one);
            int finite = 1, lit = 0;
            for (int k = 0; k < W * H * 3; k += 3) {
                finite &= isfinite(p[k]) && isfinite(p[k + 1]) && isfinite(p[k + 2]);
                lit += p[k] != (float)g.background.r || p[k + 1] != (float)g.background.g ||
                       p[k + 2] != (float)g.background.b;
            }
            CHECK_MSG(finite, "%s: a pixel is not finite", scenes[i]);
            /* Framed or with its own camera, the objects fill part of the view. */
            CHECK_MSG(lit > W * H / 20, "%s: only %d of %d pixels show an object", scenes[i], lit, W * H);
            for (int32_t threads = 2; threads <= 4; threads *= 2) {
                hr_image *many = render(ctx, r.scene, &r.camera, threads, 1);
                CHECK_MSG(many && memcmp(p, hr_image_data(many), sizeof(float) * W * H * 3) == 0,
                          "%s: %d threads differ from 1", scenes[i], (int)threads);
                hr_image_destroy(many);
            }
            hr_image *a = render(ctx, r.scene, &r.camera, 1, 4);
            hr_image *b = render(ctx, r.scene, &r.camera, 3, 4);
            CHECK_MSG(a && b && memcmp(hr_image_data(a), hr_image_data(b), sizeof(float) * W * H * 3) == 0,
                      "%s: 4 spp differs between 1 and 3 threads", scenes[i]);
            hr_image_destroy(a);
            hr_image_destroy(b);
        }
        hr_image_destroy(one);
        hr_scene_destroy(r.scene);
    }
    hr_context_destroy(ctx);
    return hr_test_end();
}
