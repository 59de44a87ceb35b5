/* The work and the error of a deep scene bounded (issue 29, D5): the ray
 * budget per camera sample and the branching-aware default cut-off.
 *
 * The scene behind it: the camera inside a glass ball inside a glass cube,
 * reflectivity and transparency 0.5 each, depth 1000, Hill's thresholds at
 * 0. Every hit branches in two and no weight is lost, so no cut-off of the
 * weights can end it: only the budget does. */
#include <math.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *ctx;

static const char *nested_glass =
    "camera 0 0 0  0 0 -1  0 1 0  60\n"
    "maxRecursionDepth 1000 minReflectivity 0 minTransparency 0\n"
    "light 0 0.5 0 1 1 1\n"
    "reflectivity 0.5 transparency 0.5 speedOfLight 0.7 diffuse 0.3 0.3 0.3\n"
    "push scale 3 3 3 cube pop\n"
    "push scale 1.5 1.5 1.5 sphere pop\n";

/* The same nest, fainter: reflectivity and transparency 0.1 each, so a
 * path of k bounces weighs 0.1^k and, with 2^k of them, its level 0.2^k in
 * all. Depth 12 keeps the exact render small (2^13 rays a sample). */
static const char *faint_glass =
    "camera 0 0 0  0 0 -1  0 1 0  60\n"
    "maxRecursionDepth 12 minReflectivity 0 minTransparency 0\n"
    "light 0 0.5 0 1 1 1\n"
    "reflectivity 0.1 transparency 0.1 speedOfLight 0.7 diffuse 0.3 0.3 0.3 ambient 0.2 0.2 0.2\n"
    "push scale 3 3 3 cube pop\n"
    "push scale 1.5 1.5 1.5 sphere pop\n";

typedef struct seen_warnings {
    int count;
    int32_t code;
    char message[512];
} seen_warnings;

static void on_warning(void *user, const hr_warning *w)
{
    seen_warnings *seen = user;
    seen->count++;
    seen->code = w->code;
    strncpy(seen->message, w->message, sizeof seen->message - 1);
}

static hr_sdl_result load(const char *text)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK_MSG(hr_sdl_load_string(ctx, text, "budget.sdl", NULL, &r) == HR_OK, "%s", hr_context_last_error(ctx));
    if (r.scene) CHECK_OK(hr_scene_commit(r.scene));
    return r;
}

static hr_image *render(hr_sdl_result *r, int32_t w, int32_t h, hr_render_options *o, hr_render_stats *stats,
                        hr_status *status)
{
    o->width = w, o->height = h, o->threads = 2, o->tile_size = 4;
    memset(stats, 0, sizeof *stats);
    stats->struct_size = sizeof *stats;
    hr_image *image = NULL;
    *status = hr_render(r->scene, &r->camera, o, &image, stats);
    return image;
}

static uint64_t all_rays(const hr_render_stats *s)
{
    return s->primary + s->shadow + s->reflected + s->refracted;
}

static int all_finite(hr_image *image, int n)
{
    const float *px = hr_image_data(image);
    for (int i = 0; i < n; i++)
        if (!isfinite(px[i])) return 0;
    return 1;
}

static void test_nested_glass(void)
{
    hr_sdl_result r = load(nested_glass);
    if (!r.scene) return;
    seen_warnings seen = {0};
    hr_context_set_warning_callback(ctx, on_warning, &seen);
    hr_render_options o;
    hr_render_stats st;
    hr_status status;

    /* By default: it ends, every pixel over the budget and said so, no
     * sample past HR_DEFAULT_RAY_BUDGET rays (16x12, one sample a pixel). */
    hr_render_options_default(&o);
    CHECK(o.ray_budget == 0);
    hr_image *image = render(&r, 16, 12, &o, &st, &status);
    CHECK_OK(status);
    CHECK_MSG(st.pixels_over_budget == 16 * 12, "%llu pixels over budget",
              (unsigned long long)st.pixels_over_budget);
    CHECK(st.rays_over_budget > 0);
    CHECK_MSG(all_rays(&st) <= st.primary * HR_DEFAULT_RAY_BUDGET, "%llu rays for %llu samples",
              (unsigned long long)all_rays(&st), (unsigned long long)st.primary);
    CHECK(image && all_finite(image, 16 * 12 * 3));
    hr_image_destroy(image);
    CHECK(seen.count == 1 && seen.code == HR_WARNING_RAY_BUDGET);
    CHECK_MSG(strstr(seen.message, "192 of 192 pixels reached the ray budget of 65536 rays per camera sample"),
              "%s", seen.message);

    /* A budget of its own, on one pixel: never a ray past it, the warning
     * counts one pixel, and a larger budget casts more. */
    seen.count = 0;
    hr_render_options_default(&o);
    o.ray_budget = 1000;
    image = render(&r, 1, 1, &o, &st, &status);
    CHECK_OK(status);
    uint64_t small = all_rays(&st);
    CHECK_MSG(small <= 1000 && small > 500, "%llu rays under a budget of 1000", (unsigned long long)small);
    CHECK(st.pixels_over_budget == 1 && seen.count == 1);
    CHECK(strstr(seen.message, "1 of 1 pixels reached the ray budget of 1000 rays"));
    hr_image_destroy(image);
    o.ray_budget = 4000;
    image = render(&r, 1, 1, &o, &st, &status);
    CHECK_OK(status);
    CHECK(all_rays(&st) <= 4000 && all_rays(&st) > small);
    hr_image_destroy(image);

    /* Rays and pixels do not depend on the threads or the tiles. */
    o.ray_budget = 0;
    hr_render_stats one, two;
    o.threads = 1;
    image = render(&r, 4, 3, &o, &one, &status);
    hr_image *again = NULL;
    hr_render_options o2 = o;
    o2.tile_size = 1;
    CHECK_OK(status);
    o2.width = 4, o2.height = 3, o2.threads = 2;
    memset(&two, 0, sizeof two);
    two.struct_size = sizeof two;
    CHECK_OK(hr_render(r.scene, &r.camera, &o2, &again, &two));
    CHECK(all_rays(&one) == all_rays(&two) && one.rays_over_budget == two.rays_over_budget);
    if (image && again) CHECK(memcmp(hr_image_data(image), hr_image_data(again), 4 * 3 * 3 * sizeof(float)) == 0);
    hr_image_destroy(image);
    hr_image_destroy(again);

    /* Exact has no budget: at depth 22 one pixel casts more than the
     * default budget, and nothing is cut. */
    seen.count = 0;
    hr_render_options_default(&o);
    o.exact = 1, o.max_depth = 22;
    image = render(&r, 1, 1, &o, &st, &status);
    CHECK_OK(status);
    CHECK_MSG(all_rays(&st) > HR_DEFAULT_RAY_BUDGET, "%llu rays", (unsigned long long)all_rays(&st));
    CHECK(st.rays_over_budget == 0 && st.pixels_over_budget == 0 && st.rays_cut == 0 && seen.count == 0);
    hr_image_destroy(image);

    /* Bad budgets are refused, naming the value. */
    hr_render_options_default(&o);
    o.ray_budget = -1;
    CHECK(render(&r, 1, 1, &o, &st, &status) == NULL && status == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "ray budget -1 must be positive"));
    o.ray_budget = 100, o.exact = 1;
    CHECK(render(&r, 1, 1, &o, &st, &status) == NULL && status == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "exclude each other"));

    /* A caller that predates the field gets the default budget. */
    hr_render_options_default(&o);
    o.struct_size = (uint32_t)offsetof(hr_render_options, ray_budget);
    o.ray_budget = 5; /* past its struct_size: not read */
    image = render(&r, 1, 1, &o, &st, &status);
    CHECK_OK(status);
    CHECK(all_rays(&st) > 1000 && all_rays(&st) <= HR_DEFAULT_RAY_BUDGET);
    hr_image_destroy(image);

    /* hr_scene_shade has the default budget too: it returns. */
    hr_ray ray = {{0, 0, 0}, {0.1, 0.2, -1}};
    hr_color c;
    CHECK_OK(hr_scene_shade(r.scene, &ray, -1, &c));
    CHECK(isfinite(c.r) && isfinite(c.g) && isfinite(c.b));
    hr_context_set_warning_callback(ctx, NULL, NULL);
    hr_scene_destroy(r.scene);
}

/* Concentric spheres of radius 1 to 4 about the camera and the light,
 * glass of speed 1 (so nothing bends or is reflected whole): every ray up
 * to depth 3 hits one, and splits in two. Under HR_EFFECTS_ALL each hit
 * casts its shadow ray too, so a camera sample casts the largest tree
 * depth 3 and one light allow, (1 + 1) * (2^4 - 1) = 30 rays. */
static const char *full_tree =
    "camera 0 0 0  0 0 -1  0 1 0  60\n"
    "maxRecursionDepth 3 minReflectivity 0 minTransparency 0\n"
    "light 0 0 0 1 1 1\n"
    "reflectivity 0.5 transparency 0.5 speedOfLight 1 diffuse 0.3 0.3 0.3\n"
    "sphere\n"
    "push scale 2 2 2 sphere pop\n"
    "push scale 3 3 3 sphere pop\n"
    "push scale 4 4 4 sphere pop\n";

/* A budget that covers the largest tree a scene's depth and lights allow
 * is never reached, and shade skips its accounts (tc.budget_free_levels);
 * one ray less and it is reached, so the accounts are kept exactly where
 * they can matter. */
static void test_full_tree_boundary(void)
{
    hr_sdl_result r = load(full_tree);
    if (!r.scene) return;
    hr_render_options o;
    hr_render_stats st;
    hr_status status;
    hr_render_options_default(&o);
    o.effects = HR_EFFECTS_ALL;
    o.exact = 1;
    hr_image *exact = render(&r, 1, 1, &o, &st, &status);
    CHECK_OK(status);
    CHECK_MSG(all_rays(&st) == 30, "%llu rays in the full tree", (unsigned long long)all_rays(&st));
    o.exact = 0;
    o.ray_budget = 30;
    hr_image *covered = render(&r, 1, 1, &o, &st, &status);
    CHECK_OK(status);
    CHECK_MSG(all_rays(&st) == 30 && st.rays_over_budget == 0 && st.pixels_over_budget == 0,
              "%llu rays, %llu over a budget of 30", (unsigned long long)all_rays(&st),
              (unsigned long long)st.rays_over_budget);
    if (exact && covered) CHECK(memcmp(hr_image_data(exact), hr_image_data(covered), 3 * sizeof(float)) == 0);
    o.ray_budget = 29;
    hr_image *short_one = render(&r, 1, 1, &o, &st, &status);
    CHECK_OK(status);
    CHECK_MSG(all_rays(&st) <= 29 && st.rays_over_budget > 0 && st.pixels_over_budget == 1,
              "%llu rays, %llu over a budget of 29", (unsigned long long)all_rays(&st),
              (unsigned long long)st.rays_over_budget);
    hr_image_destroy(exact);
    hr_image_destroy(covered);
    hr_image_destroy(short_one);
    hr_scene_destroy(r.scene);
}

static double largest_difference(hr_image *a, hr_image *b, int n)
{
    const float *pa = hr_image_data(a), *pb = hr_image_data(b);
    double d = 0;
    for (int i = 0; i < n; i++) d = fmax(d, fabs((double)pa[i] - (double)pb[i]));
    return d;
}

/* The default cut-off counts the branches: everything it drops from a
 * sample weighs under 2^-24 in all. Each dropped ray would have brought back
 * at most its weight times the brightest a ray sees here, the local terms
 * of a hit (ambient 0.2 under a global ambient of at most 1, diffuse 0.3
 * under one white light: at most 0.5) summed over a subtree that fades by
 * 0.2 a level, so under 0.625: the pixel moves by under 0.625 * 2^-24 from
 * the exact one, plus the float's rounding of each (half a unit in the last
 * place of values under 1, 2^-25). A cut-off of 2^-24 per ray, the same
 * number not shared out, drops the 2^8 rays of weight 0.1^8 at depth 8,
 * 0.2^8 = 2.6e-6 of what they see in all: past the bound. */
static void test_faint_glass(void)
{
    hr_sdl_result r = load(faint_glass);
    if (!r.scene) return;
    hr_render_options o;
    hr_render_stats by_default, exact, per_ray;
    hr_status status;
    hr_render_options_default(&o);
    hr_image *a = render(&r, 8, 6, &o, &by_default, &status);
    CHECK_OK(status);
    o.exact = 1;
    hr_image *b = render(&r, 8, 6, &o, &exact, &status);
    CHECK_OK(status);
    o.exact = 0, o.min_weight = 1.0 / (1 << 24);
    hr_image *c = render(&r, 8, 6, &o, &per_ray, &status);
    CHECK_OK(status);
    CHECK(by_default.rays_cut > 0 && by_default.rays_over_budget == 0 && exact.rays_cut == 0);
    CHECK(all_rays(&by_default) < all_rays(&exact));
    if (a && b && c) {
        double bound = 0.625 * ldexp(1.0, -24) + 2 * ldexp(1.0, -25);
        double d = largest_difference(a, b, 8 * 6 * 3);
        CHECK_MSG(d <= bound, "default differs from exact by %g, bound %g", d, bound);
        double per = largest_difference(c, b, 8 * 6 * 3);
        CHECK_MSG(per > bound, "a per-ray cut-off differs by %g only", per);
    }
    hr_image_destroy(a);
    hr_image_destroy(b);
    hr_image_destroy(c);
    hr_scene_destroy(r.scene);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    test_nested_glass();
    test_faint_glass();
    test_full_tree_boundary();
    hr_context_destroy(ctx);
    return hr_test_end();
}
