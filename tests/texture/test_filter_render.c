/* Texture filtering end to end, through a curved mirror and a glass ball:
 * hr_render's footprint filtering (ray differentials carried through the
 * bounce, the normal's turn found by the renderer) against the converged
 * image.
 *
 * A checkerboard floor of small squares (0.2 units), seen only in a mirror
 * sphere (then in a glass ball) that fills the middle of a 48 x 48 image:
 * in the sphere the floor shrinks, so a pixel spans several squares there.
 * Reference: 256 point samples a pixel (HR_TEXTURE_FILTER_NONE). Within the
 * sphere's pixels, the filtered 1-spp render must be much closer to it than
 * the point-sampled 1-spp render: its RMSE under 0.2 of it for the mirror
 * (measured 0.06), under 0.3 for the glass (measured 0.19). The mirror's
 * bound is what catches a bounce that misses how the sphere's normal turns,
 * which widens a convex mirror's footprint several times: with the normal's
 * derivative set to 0 the mirror's ratio is 0.44 (the glass ball's 0.24,
 * which its bound does not catch: through two refractions the filtering
 * is checked, not that term). And the filtered render is the same bits at
 * 1 and 3 threads. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"
#include "texture_support.h"

#define W 48
#define H 48

static const char *const scenes[2] = {
    /* the mirror */
    "camera 0 1 5  0 1 0  0 1 0  26\n"
    "background 0 0 0 globalAmbient 1 1 1 maxRecursionDepth 2 minReflectivity 0.1\n"
    "push rotate -90 1 0 0 ambient 1 1 1 diffuse 0 0 0 texture -1 parameters 7 0.2 1 1 1 0 0 0 plane pop\n"
    "defaultMaterials\n"
    "push translate 0 1 0 ambient 0 0 0 diffuse 0 0 0 specular 0 0 0 reflectivity 1 sphere pop\n",
    /* the glass ball */
    "camera 0 1 5  0 1 0  0 1 0  26\n"
    "background 0 0 0 globalAmbient 1 1 1 maxRecursionDepth 3 minTransparency 0.1\n"
    "push rotate -90 1 0 0 ambient 1 1 1 diffuse 0 0 0 texture -1 parameters 7 0.2 1 1 1 0 0 0 plane pop\n"
    "defaultMaterials\n"
    "push translate 0 1 0 ambient 0 0 0 diffuse 0 0 0 specular 0 0 0 transparency 1 speedOfLight 0.67 "
    "sphere pop\n",
};

static hr_image *render(hr_context *ctx, const hr_scene *s, const hr_camera *cam, int32_t spp, int32_t threads,
                        int32_t filter)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = W, o.height = H, o.samples_per_pixel = spp, o.threads = threads, o.texture_filter = filter;
    hr_image *img = NULL;
    CHECK_MSG(hr_render(s, cam, &o, &img, NULL) == HR_OK, "render: %s", hr_context_last_error(ctx));
    return img;
}

int main(void)
{
    hr_context *ctx = NULL;
    CHECK_OK(hr_context_create(&ctx));
    for (int k = 0; k < 2; k++) {
        hr_sdl_result r = {0};
        r.struct_size = sizeof r;
        if (hr_sdl_load_string(ctx, scenes[k], "filter.sdl", NULL, &r) != HR_OK) {
            CHECK_MSG(0, "%s", hr_context_last_error(ctx));
            continue;
        }
        CHECK_OK(hr_scene_commit(r.scene));
        hr_image *ref = render(ctx, r.scene, &r.camera, 256, 0, HR_TEXTURE_FILTER_NONE);
        hr_image *point = render(ctx, r.scene, &r.camera, 1, 1, HR_TEXTURE_FILTER_NONE);
        hr_image *filtered = render(ctx, r.scene, &r.camera, 1, 1, HR_TEXTURE_FILTER_FOOTPRINT);
        hr_image *threaded = render(ctx, r.scene, &r.camera, 1, 3, HR_TEXTURE_FILTER_FOOTPRINT);
        if (ref && point && filtered && threaded) {
            const float *R = hr_image_data(ref), *P = hr_image_data(point), *F = hr_image_data(filtered);
            CHECK(memcmp(F, hr_image_data(threaded), sizeof(float) * W * H * 3) == 0);
            /* The sphere's pixels: those within 0.8 of its image's radius
             * of the centre (it spans about 0.86 of the image's height). */
            double ep = 0.0, ef = 0.0;
            int n = 0;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    const double dx = x + 0.5 - W / 2.0, dy = y + 0.5 - H / 2.0;
                    if (hypot(dx, dy) > 0.8 * 0.43 * H) continue;
                    const size_t i = ((size_t)y * W + (size_t)x) * 3;
                    ep += (P[i] - R[i]) * (P[i] - R[i]);
                    ef += (F[i] - R[i]) * (F[i] - R[i]);
                    n++;
                }
            const double rp = sqrt(ep / n), rf = sqrt(ef / n);
            printf("%s: %d pixels, RMSE point-sampled %.4f, filtered %.4f (ratio %.2f)\n",
                   k ? "glass" : "mirror", n, rp, rf, rf / rp);
            CHECK(n > 600);
            CHECK_MSG(rf < (k ? 0.3 : 0.2) * rp, "%s: filtered RMSE %.4f, point-sampled %.4f", k ? "glass" : "mirror",
                      rf, rp);
        }
        hr_image_destroy(ref);
        hr_image_destroy(point);
        hr_image_destroy(filtered);
        hr_image_destroy(threaded);
        hr_scene_destroy(r.scene);
    }
    hr_context_destroy(ctx);
    return hr_test_end();
}
