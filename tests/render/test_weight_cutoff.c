/* The default contribution cut-off (2^-HR_DEFAULT_MIN_WEIGHT_BITS, issue 16 defect
 * 5) and ray budget: the camera inside a glass cube whose walls reflect half
 * and transmit half, at depth 1000 with Hill's thresholds at 0, casts rays
 * that multiply by about 1.9 per level; traced exactly it would never end.
 * By default it ends (a hang here is what the timeout turns into a
 * failure), within the bound the budget promises: no pixel casts more than
 * HR_DEFAULT_RAY_BUDGET rays. On a scene whose paths never get that faint,
 * the default and the exact mode give the same image bit for bit, and the
 * exact mode stays reachable. test_ray_budget.c tests both bounds closely. */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *ctx;

static const char *glass_box =
    "camera 0 0 0  0 0 -1  0 1 0  60\n"
    "maxRecursionDepth 1000 minReflectivity 0 minTransparency 0\n"
    "light 0 0.5 0 1 1 1\n"
    "reflectivity 0.5 transparency 0.5 speedOfLight 0.7 diffuse 0.3 0.3 0.3\n"
    "push scale 2 2 2 cube pop\n"
    "push translate 0 0 -1 scale 0.3 0.3 0.3 sphere pop\n";

/* Mirrors at 0.3, glass at 0.6, depth 5: the faintest path weighs 0.6^5. */
static const char *mirrors =
    "camera 0 1 6  0 0 0  0 1 0  50\n"
    "maxRecursionDepth 5 minReflectivity 0 minTransparency 0\n"
    "light 4 6 5 1 1 1\n"
    "push reflectivity 0.3 diffuse 0.2 0.2 0.2 rotate -90 1 0 0 plane pop\n"
    "push translate -1 1 0 transparency 0.6 reflectivity 0.3 speedOfLight 0.8 sphere pop\n"
    "push translate 1.2 1 -1 reflectivity 0.3 diffuse 0.8 0.1 0.1 cube pop\n";

static hr_sdl_result load(const char *text)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK_MSG(hr_sdl_load_string(ctx, text, "cutoff.sdl", NULL, &r) == HR_OK, "%s", hr_context_last_error(ctx));
    if (r.scene) CHECK_OK(hr_scene_commit(r.scene));
    return r;
}

static hr_image *render(hr_sdl_result *r, int32_t w, int32_t h, int32_t exact, double min_weight,
                        hr_render_stats *stats, hr_status *status)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = w, o.height = h, o.threads = 2, o.tile_size = 2;
    o.exact = exact;
    o.min_weight = min_weight;
    memset(stats, 0, sizeof *stats);
    stats->struct_size = sizeof *stats;
    hr_image *image = NULL;
    *status = hr_render(r->scene, &r->camera, &o, &image, stats);
    return image;
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    hr_render_options d;
    hr_render_options_default(&d);
    CHECK(d.min_weight == 0.0 && d.exact == 0);

    hr_sdl_result box = load(glass_box);
    if (box.scene) {
        hr_render_stats st;
        hr_status status;
        hr_image *image = render(&box, 4, 3, 0, 0.0, &st, &status);
        CHECK_OK(status);
        CHECK(st.rays_cut + st.rays_over_budget > 0);
        uint64_t rays = st.primary + st.shadow + st.reflected + st.refracted;
        CHECK_MSG(rays <= st.primary * HR_DEFAULT_RAY_BUDGET, "%llu rays for %llu pixels",
                  (unsigned long long)rays, (unsigned long long)st.primary);
        /* Every pixel finite. */
        const float *px = hr_image_data(image);
        for (int i = 0; image && i < 4 * 3 * 3; i++) CHECK(px[i] == px[i] && px[i] - px[i] == 0.0f);
        hr_image_destroy(image);
        /* exact and a cut-off exclude each other; exact must be 0 or 1. */
        CHECK(render(&box, 4, 3, 1, 0.01, &st, &status) == NULL && status == HR_ERROR_INVALID_ARGUMENT);
        CHECK(strstr(hr_context_last_error(ctx), "exclude each other") != NULL);
        CHECK(render(&box, 4, 3, 2, 0.0, &st, &status) == NULL && status == HR_ERROR_INVALID_ARGUMENT);
        /* hr_scene_shade takes the default cut-off too: it returns. */
        hr_ray ray = {{0, 0, 0}, {0.1, 0.2, -1}};
        hr_color c;
        CHECK_OK(hr_scene_shade(box.scene, &ray, -1, &c));
        CHECK(c.r == c.r && c.r - c.r == 0.0);
        hr_scene_destroy(box.scene);
    }

    hr_sdl_result scene = load(mirrors);
    if (scene.scene) {
        hr_render_stats by_default, exact;
        hr_status s1, s2;
        hr_image *a = render(&scene, 40, 30, 0, 0.0, &by_default, &s1);
        hr_image *b = render(&scene, 40, 30, 1, 0.0, &exact, &s2);
        CHECK_OK(s1);
        CHECK_OK(s2);
        CHECK(by_default.rays_cut == 0 && exact.rays_cut == 0);
        CHECK(by_default.reflected == exact.reflected && by_default.refracted == exact.refracted &&
              by_default.shadow == exact.shadow && by_default.reflected > 0 && by_default.refracted > 0);
        if (a && b) CHECK(memcmp(hr_image_data(a), hr_image_data(b), 40 * 30 * 3 * sizeof(float)) == 0);
        hr_image_destroy(a);
        hr_image_destroy(b);
        hr_scene_destroy(scene.scene);
    }
    hr_context_destroy(ctx);
    return hr_test_end();
}
