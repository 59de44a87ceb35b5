/* The seven SPD scenes (../shared/scenes/spd beside the repository, gzip
 * NFF as the SPD's generators wrote them at size factor 1): each loads and
 * renders at a small size with finite pixels and something besides the
 * background; at 512x512 the render statistics' reflected, refracted and
 * shadow rays, and the eye rays that hit something, are within 10% of the
 * counts the SPD's Readme publishes (its README.md here has the table).
 *
 * The SPD counts come from 513x513 eye rays through the pixel corners of a
 * 512x512 image; hitray casts 512x512 through the pixel centres. Both
 * sample the same field of view evenly, so every count scales with the
 * number of eye rays: the published ones are scaled by (512/513)^2 (0.4%)
 * before comparing. gears' glass has Ks = 0, and the SPD rule traces a
 * reflected ray at every transmitting hit all the same, weight 0; hitray
 * traces only what a coefficient calls for, so its gears counts may be lower
 * and are only held to at most 10% above (docs/nff.md measures both ways).
 * Without the folder the test is skipped, saying so. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include <hitray/hitray.h>

#include "hr_test.h"

#define SPD_DIR HR_TEST_SOURCE_DIR "/../shared/scenes/spd"
#define SKIP 77
#define SIZE 512
#define SMALL 48

typedef struct spd_scene {
    const char *name;
    double eye_hits, reflected, refracted, shadow; /* the Readme's counts */
    int at_most;                                    /* 1: only an upper bound */
} spd_scene;

static const spd_scene scenes[] = {
    {"balls", 263169, 175095, 0, 954368, 0},       {"gears", 245086, 304643, 207564, 2246955, 1},
    {"mount", 173125, 354769, 354769, 412922, 0},  {"rings", 263169, 315236, 0, 1085002, 0},
    {"teapot", 161120, 225248, 0, 407656, 0},      {"tetra", 49788, 0, 0, 46112, 0},
    {"tree", 169836, 0, 0, 1097419, 0},
};

static hr_context *ctx;

#ifndef HR_NFF_SMALL_ONLY /* the sanitizer builds render the small size alone */
/* Ours against the published count scaled to 512x512 eye rays. */
static void compare(const char *scene, const char *kind, double ours, double published,
                    int at_most)
{
    const double scaled = published * ((double)SIZE * SIZE) / (513.0 * 513.0);
    printf("%-7s %-9s %9.0f  published %9.0f (scaled %9.0f)  %+6.2f%%\n", scene, kind, ours,
           published, scaled, scaled > 0 ? 100.0 * (ours - scaled) / scaled : 0.0);
    if (published == 0) {
        CHECK_MSG(ours == 0, "%s: %s rays %.0f where the SPD has none", scene, kind, ours);
        return;
    }
    CHECK_MSG(ours <= 1.1 * scaled, "%s: %s rays %.0f, more than 10%% above %.0f", scene, kind,
              ours, scaled);
    if (!at_most)
        CHECK_MSG(ours >= 0.9 * scaled, "%s: %s rays %.0f, more than 10%% below %.0f", scene,
                  kind, ours, scaled);
}

/* Eye rays through the pixel centres that hit something. */
static double eye_hits(const hr_scene *s, hr_camera cam)
{
    cam.width = cam.height = SIZE;
    double hits = 0;
    for (int j = 0; j < SIZE; j++)
        for (int i = 0; i < SIZE; i++) {
            hr_ray ray;
            hr_hit h;
            int32_t found = 0;
            if (hr_camera_ray(&cam, i + 0.5, j + 0.5, &ray) != HR_OK ||
                hr_scene_first_hit(s, &ray, 0.0, INFINITY, &h, &found) != HR_OK)
                return -1;
            hits += found;
        }
    return hits;
}
#endif

static hr_render_stats render(const hr_scene *s, const hr_camera *cam, int32_t size)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = o.height = size;
    hr_render_stats st;
    memset(&st, 0, sizeof st);
    st.struct_size = sizeof st;
    hr_image *img = NULL;
    CHECK_MSG(hr_render(s, cam, &o, &img, &st) == HR_OK, "render: %s", hr_context_last_error(ctx));
    if (img && size == SMALL) {
        hr_scene_globals g = {0};
        g.struct_size = sizeof g;
        hr_scene_get_globals(s, &g);
        const float *p = hr_image_data(img);
        int finite = 1, lit = 0;
        for (int k = 0; k < size * size * 3; k += 3) {
            finite &= isfinite(p[k]) && isfinite(p[k + 1]) && isfinite(p[k + 2]);
            lit += p[k] != (float)g.background.r || p[k + 1] != (float)g.background.g ||
                   p[k + 2] != (float)g.background.b;
        }
        CHECK(finite);
        CHECK(lit > 0);
    }
    hr_image_destroy(img);
    return st;
}

static void test_scene(const spd_scene *sc)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.nff.gz", SPD_DIR, sc->name);
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    if (hr_nff_load_file(ctx, path, &r) != HR_OK) {
        CHECK_MSG(0, "%s", hr_context_last_error(ctx));
        return;
    }
    CHECK(r.has_camera && r.camera.width == SIZE && r.camera.height == SIZE);
    CHECK_OK(hr_scene_commit(r.scene));
    render(r.scene, &r.camera, SMALL);
#ifndef HR_NFF_SMALL_ONLY
    hr_render_stats st = render(r.scene, &r.camera, SIZE);
    compare(sc->name, "eye hits", eye_hits(r.scene, r.camera), sc->eye_hits, 0);
    compare(sc->name, "reflected", (double)st.reflected, sc->reflected, sc->at_most);
    compare(sc->name, "refracted", (double)st.refracted, sc->refracted, sc->at_most);
    compare(sc->name, "shadow", (double)st.shadow, sc->shadow, sc->at_most);
#endif
    hr_scene_destroy(r.scene);
}

int main(void)
{
    struct stat info;
    if (stat(SPD_DIR "/balls.nff.gz", &info) != 0) {
        printf("skipped: the SPD scenes are not at %s (the project's shared/scenes/spd beside "
               "the repository)\n",
               SPD_DIR);
        return SKIP;
    }
    CHECK_OK(hr_context_create(&ctx));
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) test_scene(&scenes[i]);
    hr_context_destroy(ctx);
    return hr_test_end();
}
