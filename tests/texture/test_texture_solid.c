/* Solid textures (texture < 0): the checkerboard at known points of a
 * floor seen head-on (both colours, the square size, moving and scaling
 * with its object), wood and marble the same bits with 1, 2 and 3 threads
 * and against a stored reference image, the `texture` effect, the
 * noise's own properties, and their names (hr_solid_texture_name). */
#include <stdint.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "texture_support.h"

/* Only the ambient term, with global ambient 1: a pixel is the texture's
 * colour itself. Red squares (A) and blue ones (B), 0.5 on a side. */
#define FLAT "background 0 0 0  globalAmbient 1 1 1\n" \
             "ambient 1 1 1  diffuse 0 0 0\n"          \
             "texture -1  parameters 7  0.5  1 0 0  0 0 1\n"

static int is_color(hr_color c, double r, double g, double b)
{
    return c.r == r && c.g == g && c.b == b;
}

/* The floor is the generic plane z = 0. The texture is looked up just
 * inside it, at z slightly below 0, where floor(z / s) is -1: so the
 * square [0, s) x [0, s) has an odd sum, colour B. */
static void test_checker_head_on(hr_context *ctx)
{
    hr_scene *s = tx_scene(ctx, FLAT "plane\n", NULL);
    if (!s) return;
    const struct {
        double x, y;
        int a; /* 1: colour A (red), 0: B (blue) */
    } at[] = {
        {0.25, 0.25, 0}, {0.75, 0.25, 1}, {0.25, 0.75, 1}, {0.75, 0.75, 0},
        {1.25, 0.25, 0}, {-0.25, 0.25, 1}, {-0.25, -0.25, 0}, {10.1, 3.3, 0}, {10.6, 3.3, 1},
        /* Just either side of a square's edge at x = 0.5. */
        {0.499, 0.1, 0}, {0.501, 0.1, 1},
    };
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        hr_color c = tx_down(s, at[i].x, at[i].y);
        CHECK_MSG(at[i].a ? is_color(c, 1, 0, 0) : is_color(c, 0, 0, 1),
                  "checker at (%g, %g): %g %g %g, expected colour %s", at[i].x, at[i].y, c.r, c.g, c.b,
                  at[i].a ? "A" : "B");
    }
    CHECK(hr_scene_effects(s) & HR_EFFECT_TEXTURE);
    hr_scene_destroy(s);
}

/* The texture is the object's: moved by 0.5 along x the squares move with
 * it; scaled by 2 they double. */
static void test_checker_moves_with_object(hr_context *ctx)
{
    hr_scene *moved = tx_scene(ctx, FLAT "translate 0.5 0 0  plane\n", NULL);
    hr_scene *scaled = tx_scene(ctx, FLAT "scale 2 2 2  plane\n", NULL);
    if (moved) {
        CHECK(is_color(tx_down(moved, 0.25, 0.25), 1, 0, 0));
        CHECK(is_color(tx_down(moved, 0.75, 0.25), 0, 0, 1));
    }
    if (scaled) {
        CHECK(is_color(tx_down(scaled, 0.25, 0.25), 0, 0, 1));
        CHECK(is_color(tx_down(scaled, 0.75, 0.25), 0, 0, 1));
        CHECK(is_color(tx_down(scaled, 1.25, 0.25), 1, 0, 0));
    }
    hr_scene_destroy(moved);
    hr_scene_destroy(scaled);
}

/* Inside a CSG object the leaf's own space counts: a cube scaled inside
 * the union, the union moved. */
static void test_checker_in_csg(hr_context *ctx)
{
    hr_scene *s = tx_scene(ctx,
                           FLAT "translate 0.5 0 0\n"
                                "union  push scale 4 4 1 translate 0 0 -1 cube pop\n"
                                "       push translate 0 0 -20 sphere pop\n",
                           NULL);
    if (!s) return;
    /* The cube's top face is at object z = 1 (world z = 0 after the
     * translate -1): looked up just inside, floor(1 - tiny) / 0.5 = 1. The
     * cube is scaled by 4 in x, y: object x = (world x - 0.5) / 4. */
    /* world x 0.75 -> object 0.0625: floor 0; y 0.25 -> 0.0625: 0; sum 1: B. */
    CHECK(is_color(tx_down(s, 0.75, 0.25), 0, 0, 1));
    /* world x 2.75 -> object 0.5625: floor 1; sum 2: A. */
    CHECK(is_color(tx_down(s, 2.75, 0.25), 1, 0, 0));
    hr_scene_destroy(s);
}

#define WOOD_MARBLE HR_TEST_SOURCE_DIR "/tests/data/textures/wood_marble.sdl"
#define REFERENCE HR_TEST_SOURCE_DIR "/tests/data/textures/wood_marble_ref.png"
#define RW 64
#define RH 48

/* The reference was written by the CLI as a 16-bit linear PNG
 * (hitray render wood_marble.sdl -o ref.png --size 64x48 --png16
 * --linear-png), so each channel is the float pixel clamped to [0, 1] and
 * rounded to 1/65535. A pixel may differ by that rounding (half a step)
 * plus float's (2^-24 relative), under one step in all. Beyond that only a
 * pixel on the edge of a ring or a vein may differ, where a last-place
 * change in sin or atan2 of another libm flips it: at most 1% of them. */
static void test_wood_marble_reference(hr_context *ctx)
{
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    if (hr_sdl_load_file(ctx, WOOD_MARBLE, &r) != HR_OK) {
        CHECK_MSG(0, "%s", hr_context_last_error(ctx));
        return;
    }
    CHECK_OK(hr_scene_commit(r.scene));
    hr_image *img[3] = {NULL, NULL, NULL};
    for (int t = 0; t < 3; t++) img[t] = tx_render(ctx, r.scene, &r.camera, RW, RH, t + 1);
    hr_image *ref = NULL;
    CHECK_MSG(hr_image_read(ctx, REFERENCE, &ref) == HR_OK, "%s", hr_context_last_error(ctx));
    if (img[0] && img[1] && img[2] && ref) {
        const size_t n = (size_t)RW * RH * 3;
        CHECK(memcmp(hr_image_data(img[0]), hr_image_data(img[1]), n * sizeof(float)) == 0);
        CHECK(memcmp(hr_image_data(img[0]), hr_image_data(img[2]), n * sizeof(float)) == 0);
        CHECK(hr_image_width(ref) == RW && hr_image_height(ref) == RH);
        const float *p = hr_image_data(img[0]), *q = hr_image_data(ref);
        size_t off = 0;
        int textured = 0;
        for (size_t i = 0; i < n && hr_image_width(ref) == RW && hr_image_height(ref) == RH; i++) {
            double v = p[i] < 0 ? 0 : p[i] > 1 ? 1 : p[i];
            off += !(fabs(v - q[i]) <= 1.0 / 65535.0);
            textured |= q[i] != q[0];
        }
        CHECK_MSG(off * 100 <= n, "%zu of %zu channels differ from the reference", off, n);
        CHECK(textured);
    }
    /* Filtered by the footprint (the default): the same bits for any
     * number of threads, and a different picture from the point samples
     * (the rings and veins fade where they are finer than a pixel). */
    hr_image *filtered[3] = {NULL, NULL, NULL};
    for (int t = 0; t < 3; t++)
        filtered[t] = tx_render_filtered(ctx, r.scene, &r.camera, RW, RH, t + 1, HR_TEXTURE_FILTER_FOOTPRINT);
    if (filtered[0] && filtered[1] && filtered[2] && img[0]) {
        const size_t bytes = (size_t)RW * RH * 3 * sizeof(float);
        CHECK(memcmp(hr_image_data(filtered[0]), hr_image_data(filtered[1]), bytes) == 0);
        CHECK(memcmp(hr_image_data(filtered[0]), hr_image_data(filtered[2]), bytes) == 0);
        CHECK(memcmp(hr_image_data(filtered[0]), hr_image_data(img[0]), bytes) != 0);
    }
    for (int t = 0; t < 3; t++) hr_image_destroy(filtered[t]);
    CHECK(tx_effects_ran(r.scene, &r.camera) & HR_EFFECT_TEXTURE);
    /* Running every effect's code changes no bit of a textured scene. */
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = RW, o.height = RH, o.effects = HR_EFFECTS_ALL, o.texture_filter = HR_TEXTURE_FILTER_NONE;
    hr_image *all = NULL;
    CHECK_OK(hr_render(r.scene, &r.camera, &o, &all, NULL));
    if (all && img[0])
        CHECK(memcmp(hr_image_data(all), hr_image_data(img[0]), (size_t)RW * RH * 3 * sizeof(float)) == 0);
    hr_image_destroy(all);
    for (int t = 0; t < 3; t++) hr_image_destroy(img[t]);
    hr_image_destroy(ref);
    hr_scene_destroy(r.scene);
}

/* An untextured scene does not call for the effect, and its renders do not
 * run it. */
static void test_untextured_has_no_effect(hr_context *ctx)
{
    hr_scene *s = tx_scene(ctx, "light 0 0 10 1 1 1  sphere\n", NULL);
    if (!s) return;
    CHECK(!(hr_scene_effects(s) & HR_EFFECT_TEXTURE));
    hr_camera cam;
    hr_camera_default(&cam);
    cam.eye = (hr_vec3){0, 0, 5};
    CHECK(!(tx_effects_ran(s, &cam) & HR_EFFECT_TEXTURE));
    CHECK(strcmp(hr_effect_name(HR_EFFECT_TEXTURE), "texture") == 0);
    hr_scene_destroy(s);
}

/* Marble between its two colours everywhere; wood exactly one of its two.
 * Sampled along a line through the unit sphere's surface points. */
static void test_wood_marble_colours(hr_context *ctx)
{
    hr_scene *s = tx_scene(ctx,
                           "background 0 0 0  globalAmbient 1 1 1  ambient 1 1 1  diffuse 0 0 0\n"
                           "push texture -2 parameters 10 0.1 0.4 4 2  1 1 1  0 0 0  "
                           "  translate -1.5 0 0 sphere pop\n"
                           "push texture -3 parameters 10 1 3 6 5  1 1 1  0 0 0  "
                           "  translate 1.5 0 0 sphere pop\n",
                           NULL);
    if (!s) return;
    int light = 0, dark = 0, mixed = 0;
    for (int i = 0; i < 200; i++) {
        double y = -0.95 + 1.9 * i / 199.0;
        hr_color w = tx_down(s, -1.5, y), m = tx_down(s, 1.5, y);
        CHECK_MSG((w.r == 1 && w.g == 1 && w.b == 1) || (w.r == 0 && w.g == 0 && w.b == 0),
                  "wood at y %g: %g %g %g", y, w.r, w.g, w.b);
        light += w.r == 1, dark += w.r == 0;
        CHECK(m.r >= 0 && m.r <= 1 && m.r == m.g && m.g == m.b);
        mixed += m.r > 0.01 && m.r < 0.99;
    }
    CHECK_MSG(light > 20 && dark > 20, "wood: %d light, %d dark samples", light, dark);
    CHECK_MSG(mixed > 50, "marble: %d samples between its colours", mixed);
    hr_scene_destroy(s);
}

/* Numbered from -1 down without gaps, as scene.h promises: the first
 * NULL ends the list. 0 and the image textures are none. */
static void test_names(void)
{
    CHECK(strcmp(hr_solid_texture_name(-1), "checkerboard") == 0);
    CHECK(strcmp(hr_solid_texture_name(-2), "wood") == 0);
    CHECK(strcmp(hr_solid_texture_name(-3), "marble") == 0);
    CHECK(hr_solid_texture_name(-4) == NULL);
    CHECK(hr_solid_texture_name(0) == NULL);
    CHECK(hr_solid_texture_name(1) == NULL);
    CHECK(hr_solid_texture_name(INT32_MIN) == NULL);
    CHECK(hr_solid_texture_name(INT32_MAX) == NULL);
}

int main(void)
{
    test_names();
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    test_checker_head_on(ctx);
    test_checker_moves_with_object(ctx);
    test_checker_in_csg(ctx);
    test_wood_marble_reference(ctx);
    test_untextured_has_no_effect(ctx);
    test_wood_marble_colours(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
