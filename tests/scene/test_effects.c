/* The effect analysis, counted in rays: the renderer runs only what a
 * scene, a material and a light call for, the statistics say what ran, and
 * the contribution cut-off skips exactly the bounces below its weight. The
 * HR_EFFECTS_ALL render of each scene is the bit-for-bit check that
 * nothing skipped mattered. */
#include <stddef.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

static hr_camera looking(hr_vec3 eye, hr_vec3 look, double angle, int32_t w, int32_t h)
{
    hr_camera c;
    hr_camera_default(&c);
    c.eye = eye, c.look = look, c.view_angle = angle;
    c.up = (hr_vec3){0, 1, 0};
    c.width = w, c.height = h;
    return c;
}

static hr_image *render(hr_scene *s, const hr_camera *c, const hr_render_options *o, hr_render_stats *st)
{
    hr_image *img = NULL;
    memset(st, 0, sizeof *st);
    st->struct_size = sizeof *st;
    hr_status status = hr_render(s, c, o, &img, st);
    CHECK_MSG(status == HR_OK, "render: %s", hr_context_last_error(ctx));
    return img;
}

static int same_pixels(hr_image *a, hr_image *b)
{
    size_t n = (size_t)hr_image_width(a) * hr_image_height(a) * 3 * sizeof(float);
    return a && b && hr_image_width(a) == hr_image_width(b) && hr_image_height(a) == hr_image_height(b) &&
           memcmp(hr_image_data(a), hr_image_data(b), n) == 0;
}

/* Render with AUTO and with ALL: the images must be the same bit for bit;
 * AUTO's statistics are returned, ALL's through `all`. */
static void render_both(hr_scene *s, const hr_camera *c, hr_render_options o, hr_render_stats *auto_st,
                        hr_render_stats *all_st)
{
    o.effects = HR_EFFECTS_AUTO;
    hr_image *a = render(s, c, &o, auto_st);
    o.effects = HR_EFFECTS_ALL;
    hr_image *b = render(s, c, &o, all_st);
    CHECK_MSG(same_pixels(a, b), "the HR_EFFECTS_ALL image differs");
    hr_image_destroy(a);
    hr_image_destroy(b);
}

static hr_render_options one_thread(void)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    return o;
}

/* A purely emissive object runs no light loop: every pixel sees it, and no
 * shadow ray is cast, although the scene (with a diffuse object out of
 * view) calls for shadows. */
static void emissive_runs_no_light_loop(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material glow = tb_black();
    glow.emissive = (hr_color){1, 0.5, 0.25};
    tb_add(s, "sphere", &glow, NULL);
    hr_material matte;
    hr_material_default(&matte);
    hr_transform away = tb_place(50, 0, 0, 1);
    tb_add(s, "sphere", &matte, &away);
    tb_light(s, 0, 5, 5, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    CHECK(hr_scene_effects(s) & HR_EFFECT_SHADOWS);
    hr_camera c = looking((hr_vec3){0, 0, 3}, (hr_vec3){0, 0, 0}, 10, 8, 8);
    hr_render_stats a, all;
    render_both(s, &c, one_thread(), &a, &all);
    CHECK(a.primary == 64);
    CHECK_MSG(a.shadow == 0, "%llu shadow rays from an emissive object", (unsigned long long)a.shadow);
    CHECK(a.effects == HR_EFFECT_EMISSION);
    /* ALL runs the light loop at every hit: a shadow ray per pixel at least
     * (its bounces hit more). */
    CHECK(all.shadow >= 64);
    CHECK(all.effects & HR_EFFECT_SHADOWS && all.effects & HR_EFFECT_DIFFUSE);
    hr_scene_destroy(s);
}

/* A matte floor seen from above: a light below it (behind every point's
 * front side) casts no shadow ray; one above casts one per pixel. A light
 * whose colour the material reflects in no channel casts none either. */
static void lights_that_cannot_reach(void)
{
    struct {
        double y, r, g, b;
        uint64_t shadow_per_pixel;
        uint32_t ran;
    } cases[] = {
        {-4, 1, 1, 1, 0, HR_EFFECT_AMBIENT},                                    /* below the floor */
        {4, 1, 1, 1, 1, HR_EFFECT_AMBIENT | HR_EFFECT_DIFFUSE | HR_EFFECT_SHADOWS}, /* above */
        {4, 0, 1, 1, 0, HR_EFFECT_AMBIENT},   /* cyan light on a red floor */
        {4, 0.5, 1, 1, 1, HR_EFFECT_AMBIENT | HR_EFFECT_DIFFUSE | HR_EFFECT_SHADOWS},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        hr_scene *s;
        CHECK_OK(hr_scene_create(ctx, &s));
        hr_material red;
        hr_material_default(&red);
        red.diffuse = (hr_color){0.9, 0, 0};
        hr_transform up;
        hr_transform_identity(&up);
        hr_transform_rotate(&up, -90, 1, 0, 0); /* the plane z = 0 turned to y = 0 */
        tb_add(s, "plane", &red, &up);
        tb_light(s, 1, cases[i].y, 1, cases[i].r, cases[i].g, cases[i].b);
        CHECK_OK(hr_scene_commit(s));
        hr_camera c = looking((hr_vec3){0, 5, 0.01}, (hr_vec3){0, 0, 0}, 30, 6, 5);
        hr_render_stats a, all;
        render_both(s, &c, one_thread(), &a, &all);
        CHECK_MSG(a.shadow == cases[i].shadow_per_pixel * 30, "case %zu: %llu shadow rays", i,
                  (unsigned long long)a.shadow);
        CHECK_MSG(a.effects == cases[i].ran, "case %zu: effects 0x%x", i, (unsigned)a.effects);
        CHECK(all.shadow == 30);
        hr_scene_destroy(s);
    }
}

/* The statistics list what ran, not what the scene holds: a mirror behind
 * the camera reflects nothing. A scene without mirrors or glass casts no
 * bounce, and its image is the HR_EFFECTS_ALL image. */
static void effects_that_ran(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material matte;
    hr_material_default(&matte);
    tb_add(s, "sphere", &matte, NULL);
    hr_material mirror = tb_black();
    mirror.reflectivity = 0.9;
    mirror.transparency = 0.9;
    hr_transform behind = tb_place(0, 0, 20, 1);
    tb_add(s, "sphere", &mirror, &behind);
    tb_light(s, 0, 5, 5, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    CHECK(hr_scene_effects(s) & HR_EFFECT_REFLECTION && hr_scene_effects(s) & HR_EFFECT_REFRACTION);
    hr_camera c = looking((hr_vec3){0, 0, 4}, (hr_vec3){0, 0, 0}, 40, 9, 7);
    hr_render_stats a, all;
    render_both(s, &c, one_thread(), &a, &all);
    CHECK(a.reflected == 0 && a.refracted == 0);
    CHECK(!(a.effects & (HR_EFFECT_REFLECTION | HR_EFFECT_REFRACTION)));
    CHECK(a.effects & HR_EFFECT_DIFFUSE);
    CHECK(all.reflected > 0 && all.refracted > 0);
    hr_scene_destroy(s);
}

/* Two mirrors facing each other, the camera between them looking straight
 * at one: the pixel sees emissive e through k reflections with weight
 * 0.6^k. With a cut-off of 0.3, bounces of weight 0.6 and 0.36 are traced,
 * the one of weight 0.216 is not. */
static void cut_off(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    tb_dark_globals(s, 10);
    hr_material m = tb_black();
    m.emissive = (hr_color){0.1, 0.2, 0.3};
    m.reflectivity = 0.6;
    hr_transform front = tb_place(0, 0, -5, 1), back = tb_place(0, 0, 5, 1);
    tb_add(s, "plane", &m, &front);
    tb_add(s, "plane", &m, &back);
    CHECK_OK(hr_scene_commit(s));
    hr_camera c = looking((hr_vec3){0, 0, 0}, (hr_vec3){0, 0, -1}, 30, 1, 1);
    hr_render_options o = one_thread();
    hr_render_stats full, cut, cut_all, ignored;
    hr_image *f = render(s, &c, &o, &full);
    CHECK(full.reflected == 10 && full.rays_cut == 0);
    o.min_weight = 0.3;
    hr_image *g = render(s, &c, &o, &cut);
    CHECK_MSG(cut.reflected == 2 && cut.rays_cut == 1, "reflected %llu, cut %llu",
              (unsigned long long)cut.reflected, (unsigned long long)cut.rays_cut);
    /* The colour is the sum over the bounces traced: e (1 + 0.6 + 0.36)
     * without the cut-off's tail, e (1 + ... + 0.6^10) with all of it. Sums
     * of a few doubles, rounded to float: within one float ulp of the long
     * double sum. */
    const double e[3] = {0.1, 0.2, 0.3};
    for (int ch = 0; ch < 3; ch++) {
        long double tail = 0, all_terms = 0, w = 1;
        for (int k = 0; k <= 10; k++, w *= 0.6L) {
            all_terms += e[ch] * w;
            if (k <= 2) tail += e[ch] * w;
        }
        float got_cut = hr_image_data(g)[ch], got_full = hr_image_data(f)[ch];
        CHECK_NEAR(got_cut, (double)tail, 2e-7 * (double)tail);
        CHECK_NEAR(got_full, (double)all_terms, 2e-7 * (double)all_terms);
    }
    /* ALL with the same cut-off: the same image, the same rays cut (the
     * bounces only ALL traces carry weight 0 and are never cut). */
    o.effects = HR_EFFECTS_ALL;
    hr_image *h = render(s, &c, &o, &cut_all);
    CHECK(same_pixels(g, h));
    CHECK(cut_all.rays_cut == cut.rays_cut && cut_all.refracted > 0);
    /* Cut-off 1: only a bounce of weight 1 would be traced. */
    o.effects = HR_EFFECTS_AUTO;
    o.min_weight = 1;
    hr_image *i = render(s, &c, &o, &ignored);
    CHECK(ignored.reflected == 0 && ignored.rays_cut == 1);
    CHECK(hr_image_data(i)[0] == (float)0.1);
    hr_image_destroy(f);
    hr_image_destroy(g);
    hr_image_destroy(h);
    hr_image_destroy(i);
    hr_scene_destroy(s);
}

/* A caller built before the new fields passes a smaller struct_size: what
 * lies beyond it is neither read (options) nor written (statistics). */
static void older_callers(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material matte;
    hr_material_default(&matte);
    tb_add(s, "sphere", &matte, NULL);
    tb_light(s, 0, 5, 5, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    hr_camera c = looking((hr_vec3){0, 0, 4}, (hr_vec3){0, 0, 0}, 40, 5, 4);
    hr_render_options o;
    hr_render_options_default(&o);
    o.samples_per_pixel = 2;
    o.adaptive_threshold = NAN; /* invalid, and beyond the old size */
    o.min_weight = 7;
    o.struct_size = offsetof(hr_render_options, adaptive_threshold);
    struct {
        hr_render_stats stats;
        unsigned char guard[16];
    } old;
    memset(&old, 0xAB, sizeof old);
    old.stats.struct_size = offsetof(hr_render_stats, pixels_refined);
    hr_image *img = NULL;
    CHECK_OK(hr_render(s, &c, &o, &img, &old.stats));
    CHECK(old.stats.primary == 5 * 4 * 2);
    CHECK(old.stats.struct_size == offsetof(hr_render_stats, pixels_refined));
    const unsigned char *tail = (const unsigned char *)&old.stats + offsetof(hr_render_stats, pixels_refined);
    int untouched = 1;
    for (size_t k = 0; k < sizeof old - offsetof(hr_render_stats, pixels_refined); k++) untouched &= tail[k] == 0xAB;
    CHECK_MSG(untouched, "statistics written beyond the caller's struct_size");
    hr_image_destroy(img);
    /* The same options with the full size are refused, naming the field. */
    o.struct_size = sizeof o;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "adaptive threshold") != NULL);
    o.adaptive_threshold = 0;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "minimum weight") != NULL);
    o.min_weight = -0.5;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
    /* The value in the fewest digits that read back: %g made 1.0000001
     * "1", beside its limit 1. */
    o.min_weight = 1.0000001;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "minimum weight 1.0000001 must be within 0..1") != NULL, "%s",
              hr_context_last_error(ctx));
    o.min_weight = NAN;
    CHECK(hr_render(s, &c, &o, &img, NULL) == HR_ERROR_INVALID_ARGUMENT);
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    emissive_runs_no_light_loop();
    lights_that_cannot_reach();
    effects_that_ran();
    cut_off();
    older_callers();
    hr_context_destroy(ctx);
    return hr_test_end();
}
