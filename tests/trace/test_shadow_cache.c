/* Shadow rays ask first the object that blocked the last shadow ray towards
 * the same light (lib/trace/trace.c, hri_scene_trace_shadow). That may change how
 * fast a pixel is answered, never its colour: a render (one thread, so the
 * cache stays warm from pixel to pixel) must give, for every pixel, the
 * colour hr_scene_shade gives its centre ray, which starts with an empty
 * cache. The scene is made for the cache to matter: 400 spheres and boxes
 * over a floor under three lights, a mirror and glass, so most shadow rays
 * are blocked, often by the object that blocked the pixel before, and
 * sometimes not. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

int main(void)
{
    hr_context *ctx;
    CHECK(hr_context_create(&ctx) == HR_OK);
    char *sdl = malloc(1 << 18);
    size_t n = (size_t)snprintf(sdl, 1 << 18,
                                "camera 0 9 14  0 0 0  0 1 0  50\n"
                                "light 6 12 5 .6 .6 .6\nlight -7 10 3 .5 .4 .3\nlight 0 15 -8 .3 .3 .5\n"
                                "globalAmbient .1 .1 .1\nmaxRecursionDepth 3\n"
                                "minReflectivity .1 minTransparency .1\n"
                                "push rotate -90 1 0 0 diffuse .6 .6 .6 specular .3 .3 .3 plane pop\n");
    for (int i = 0; i < 400; i++) {
        double x = (i % 20) - 9.5, z = (i / 20) - 9.5, r = 0.2 + 0.25 * ((i * 7919) % 13) / 13.0;
        n += (size_t)snprintf(sdl + n, (1 << 18) - n,
                              "push translate %g %g %g scale %g %g %g diffuse .7 .3 .2 specular .4 .4 .4 "
                              "specularExponent 30 reflectivity %g transparency %g speedOfLight .7 %s pop\n",
                              x, 0.6 + 0.4 * (i % 3), z, r, r, r, i % 7 == 0 ? 0.5 : 0.0, i % 11 == 0 ? 0.6 : 0.0,
                              i % 2 ? "sphere" : "cube");
    }
    hr_sdl_result res = {.struct_size = sizeof res};
    if (hr_sdl_load_string(ctx, sdl, "shadow_cache.sdl", NULL, &res) != HR_OK) {
        CHECK_MSG(0, "%s", hr_context_last_error(ctx));
        return hr_test_end();
    }
    free(sdl);
    CHECK(hr_scene_commit(res.scene) == HR_OK);
    hr_camera cam = res.camera;
    cam.width = 96, cam.height = 72;
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    hr_render_stats st = {0};
    st.struct_size = sizeof st;
    hr_image *img = NULL;
    CHECK(hr_render(res.scene, &cam, &o, &img, &st) == HR_OK);
    long differ = 0, dark = 0;
    const float *px = img ? hr_image_data(img) : NULL;
    for (int y = 0; px && y < cam.height; y++)
        for (int x = 0; x < cam.width; x++) {
            hr_ray r;
            hr_color want;
            hr_camera_ray(&cam, x + 0.5, y + 0.5, &r);
            CHECK(hr_scene_shade(res.scene, &r, -1, &want) == HR_OK);
            const float *p = px + 3 * ((size_t)y * cam.width + x);
            differ += p[0] != (float)want.r || p[1] != (float)want.g || p[2] != (float)want.b;
            dark += p[0] + p[1] + p[2] < 0.35f;
        }
    fprintf(stderr, "%ld of %d pixels differ; %ld dark; %llu shadow rays\n", differ,
            cam.width * cam.height, dark, (unsigned long long)st.shadow);
    CHECK_MSG(differ == 0, "%ld pixels differ from hr_scene_shade", differ);
    CHECK(st.shadow > 10000 && dark > 500);
    hr_image_destroy(img);
    hr_scene_destroy(res.scene);
    hr_context_destroy(ctx);
    return hr_test_end();
}
