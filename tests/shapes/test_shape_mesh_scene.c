/* The mesh module through the library: tests/data/scenes/mesh_solids.sdl (the
 * regular solids, a .3vn and an OBJ file named relative to the scene, a
 * glass dodecahedron and a mirror) loads, renders with finite pixels that
 * show its objects, and gives the same bits with 1 and 3 threads. SDL
 * errors about meshes name the scene's file:line:col and the mesh file's
 * own line; `diamond` is refused as not supported, and `buckyball` and
 * `teapot` load. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

#define W 96
#define H 72

static hr_image *render(hr_context *ctx, const hr_sdl_result *r, int32_t threads)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = W, o.height = H, o.threads = threads;
    hr_image *img = NULL;
    CHECK_MSG(hr_render(r->scene, &r->camera, &o, &img, NULL) == HR_OK, "render: %s",
              hr_context_last_error(ctx));
    return img;
}

static void test_scene(hr_context *ctx)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    if (hr_sdl_load_file(ctx, HR_TEST_SOURCE_DIR "/tests/data/scenes/mesh_solids.sdl", &r) != HR_OK) {
        CHECK_MSG(0, "load: %s", hr_context_last_error(ctx));
        return;
    }
    CHECK(hr_scene_object_count(r.scene) == 8);
    CHECK_OK(hr_scene_commit(r.scene));
    hr_image *one = render(ctx, &r, 1), *three = render(ctx, &r, 3);
    if (one && three) {
        const float *p = hr_image_data(one);
        int finite = 1, lit = 0;
        for (int k = 0; k < W * H * 3; k += 3) {
            finite &= isfinite(p[k]) && isfinite(p[k + 1]) && isfinite(p[k + 2]);
            /* Anything but the background (0.1, 0.1, 0.25). */
            lit += fabsf(p[k] - 0.1f) > 1e-3f || fabsf(p[k + 2] - 0.25f) > 1e-3f;
        }
        CHECK_MSG(finite, "a pixel is not finite");
        CHECK_MSG(lit > W * H / 4, "only %d of %d pixels show an object", lit, W * H);
        CHECK_MSG(memcmp(p, hr_image_data(three), sizeof(float) * W * H * 3) == 0,
                  "3 threads differ from 1");
    }
    hr_image_destroy(one);
    hr_image_destroy(three);
    hr_scene_destroy(r.scene);
}

/* Loads `text` as "s.sdl" in tests/data/meshes and expects status `st` and
 * every fragment in the message. */
static void expect_error(hr_context *ctx, const char *text, hr_status st, const char *a,
                         const char *b)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    hr_status got = hr_sdl_load_string(ctx, text, "s.sdl", HR_TEST_SOURCE_DIR "/tests/data/meshes", &r);
    CHECK_MSG(got == st && r.scene == NULL, "'%s': status %d, expected %d", text, (int)got, (int)st);
    const char *m = hr_context_last_error(ctx);
    CHECK_MSG(strstr(m, a) && (!b || strstr(m, b)), "'%s': message '%s' lacks '%s' / '%s'", text,
              m, a, b ? b : "");
    if (r.scene) hr_scene_destroy(r.scene);
}

static void test_errors(hr_context *ctx)
{
    expect_error(ctx, "sphere\n  mesh missing.3vn", HR_ERROR_IO, "s.sdl:2:3",
                 "tests/data/meshes/missing.3vn': no such file");
    expect_error(ctx, "mesh bad/nan.3vn", HR_ERROR_PARAMETER, "s.sdl:1:1",
                 "tests/data/meshes/bad/nan.3vn:3: vertex 1: expected a number (found 'nan')");
    expect_error(ctx, "sphere diamond", HR_ERROR_UNSUPPORTED, "s.sdl:1:8",
                 "'diamond' is not supported: Hill's reader loaded it from the mesh file diamond.3vn");
    /* And the same names load when they are right. */
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK_MSG(hr_sdl_load_string(ctx,
                                 "mesh cube.obj tetrahedron octahedron dodecahedron icosahedron "
                                 "buckyball teapot",
                                 "s.sdl", HR_TEST_SOURCE_DIR "/tests/data/meshes", &r) == HR_OK,
              "%s", hr_context_last_error(ctx));
    if (r.scene) hr_scene_destroy(r.scene);
}

int main(void)
{
    hr_context *ctx = NULL;
    CHECK_OK(hr_context_create(&ctx));
    if (!ctx) return hr_test_end() | 1;
    test_scene(ctx);
    test_errors(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
