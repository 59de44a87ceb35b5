/* A torus far from the camera (1e4 and 1e6 away), rendered with each root
 * solver: the speckled pixels each one leaves, and what the render costs.
 *
 *   build/bench/accuracy/torus_far [--size=WxH] [--repeats=N] [--images=DIR]
 *
 * The scene: the torus (ring radius 1, tube 0.2, 0.05 or 0.01) tilted 60
 * degrees, centred that far from the eye, framed tightly (at 1e4 a view
 * angle of about 0.019 degrees), one light, a dark background; built
 * through the library because the SDL reader gives the torus no solver
 * parameter. For each distance, tube and solver one JSON line:
 * - hitmiss: pixels whose primary ray (through the pixel centre, what the
 *   renderer casts at 1 spp) hits where the reference misses or misses where
 *   it hits. The reference carries the world ray into object space in
 *   __float128 through the scene's own inverse matrix and solves the quartic
 *   by Sturm sequences (tests/reference/quad_reference.c), as
 *   tests/shapes/test_torus_far.c does; `hitmiss_clear` counts those of them
 *   whose reference margin exceeds 1e-9 object units (the line is not within
 *   rounding of touching the tube), where no solver may disagree;
 * - t_rel: the worst relative error of t over the pixels where both hit;
 * - shade: pixels of the rendered 8-bit sRGB image that differ from the
 *   render with the bracketing solver. Bracketing is the reference image
 *   because it is the one solver that misses no root (torus_quartic.c), its t
 *   is within a few u * condition (bench/programs/torus_solvers.c), and its own hitmiss
 *   count against the quad reference is the first line this program prints
 *   for each view, so a reader can check it;
 * - seconds: the render's wall time at 1 spp, the best of `repeats`.
 * With --images, DIR/torus_far_<distance>_<tube>_<solver>.png are the
 * renders. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "bench_util.h"
#include "quad_reference.h"

#define SOLVER_COUNT 3
static const char *const solver_names[SOLVER_COUNT] = {"bracketing", "ferrari-newton", "ferrari"};
#define CLEAR_MARGIN 1e-9

static void fail(hr_context *ctx, const char *what)
{
    fprintf(stderr, "torus_far: %s: %s\n", what, hr_context_last_error(ctx));
    exit(1);
}

typedef struct world {
    hr_transform t;
    hr_scene *scene;
    hr_camera camera;
} world;

static void make_world(hr_context *ctx, double distance, double tube, const char *solver,
                       int width, int height, world *w)
{
    /* The centre 1e4 from the eye at the origin, off every axis. */
    const hr_vec3 centre = {0.48 * distance, 0.6 * distance, -0.64 * distance};
    hr_transform_identity(&w->t);
    hr_transform_translate(&w->t, centre.x, centre.y, centre.z);
    hr_transform_rotate(&w->t, 60, 1, 0.3, 0);
    if (hr_scene_create(ctx, &w->scene) != HR_OK) fail(ctx, "scene");
    hr_param params[2];
    memset(params, 0, sizeof params);
    params[0].name = "tube", params[0].type = HR_PARAM_NUMBER, params[0].number = tube;
    params[1].name = "solver", params[1].type = HR_PARAM_STRING, params[1].string = solver;
    hr_material mat;
    hr_material_default(&mat);
    mat.ambient = (hr_color){0.15, 0.1, 0.05};
    mat.diffuse = (hr_color){0.8, 0.55, 0.2};
    mat.specular = (hr_color){0.6, 0.6, 0.6};
    mat.specular_exponent = 40;
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = "torus";
    d.params = params;
    d.param_count = 2;
    d.material = &mat;
    d.transform = w->t.m;
    d.inverse = w->t.inv;
    if (hr_scene_add_object(w->scene, &d, NULL) != HR_OK) fail(ctx, "torus");
    hr_light light = {sizeof light, 0, {-0.3 * distance, 0.8 * distance, 0}, {1, 1, 1}};
    if (hr_scene_add_light(w->scene, &light) != HR_OK) fail(ctx, "light");
    hr_scene_globals globals;
    hr_scene_globals_default(&globals);
    globals.background = (hr_color){0.02, 0.03, 0.06};
    if (hr_scene_set_globals(w->scene, &globals) != HR_OK) fail(ctx, "globals");
    if (hr_scene_commit(w->scene) != HR_OK) fail(ctx, "commit");
    hr_camera_default(&w->camera);
    w->camera.width = width;
    w->camera.height = height;
    w->camera.eye = (hr_vec3){0, 0, 0};
    w->camera.look = centre;
    w->camera.up = (hr_vec3){0, 1, 0};
    /* The ring's radius plus the tube, with a margin, fills the height. */
    w->camera.view_angle = 2 * atan(1.35 * (1 + tube) / distance) * 180 / 3.14159265358979323846;
}

/* Whether the reference's line meets the torus at t > 0, and its first t
 * there; the margin of that line. */
static int reference_hit(const world *w, const hr_ray *wr, double tube, double *t,
                         double *margin)
{
    quad o[3], d[3];
    for (int r = 0; r < 3; r++) {
        const double *row = w->t.inv + 4 * r;
        o[r] = row[0] * (quad)wr->origin.x + row[1] * (quad)wr->origin.y +
               row[2] * (quad)wr->origin.z + row[3];
        d[r] = row[0] * (quad)wr->dir.x + row[1] * (quad)wr->dir.y + row[2] * (quad)wr->dir.z;
    }
    ref_trace trace;
    ref_trace_quad_ray(ref_shape_of("torus", tube, NAN), o, d, &trace);
    *margin = trace.margin;
    for (int k = 0; k < trace.count; k++)
        if (trace.hits[k].t > 0) {
            *t = ref_to_double(trace.hits[k].t);
            return 1;
        }
    return 0;
}

static double srgb(float linear)
{
    const double v = linear < 0 ? 0 : linear > 1 ? 1 : linear;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static int shade_differs(const float *a, const float *b)
{
    for (int c = 0; c < 3; c++)
        if (lround(255 * srgb(a[c])) != lround(255 * srgb(b[c]))) return 1;
    return 0;
}

static hr_image *render(hr_context *ctx, const world *w, int repeats, double *seconds)
{
    hr_render_options opt;
    hr_render_options_default(&opt);
    hr_image *image = NULL;
    *seconds = INFINITY;
    for (int rep = 0; rep < repeats; rep++) {
        if (image) hr_image_destroy(image);
        hr_render_stats stats = {.struct_size = sizeof stats};
        if (hr_render(w->scene, &w->camera, &opt, &image, &stats) != HR_OK) fail(ctx, "render");
        *seconds = fmin(*seconds, stats.seconds);
    }
    return image;
}

static void run_tube(hr_context *ctx, double distance, double tube, int width, int height,
                     int repeats, const char *images)
{
    const int pixels = width * height;
    signed char *ref_found = bench_checked(malloc((size_t)pixels));
    signed char *ref_clear = bench_checked(malloc((size_t)pixels));
    double *ref_t = bench_checked(malloc((size_t)pixels * sizeof *ref_t));
    float *bracketing_image = bench_checked(malloc((size_t)pixels * 3 * sizeof(float)));
    for (int s = 0; s < SOLVER_COUNT; s++) {
        world w;
        make_world(ctx, distance, tube, solver_names[s], width, height, &w);
        int hitmiss = 0, hitmiss_clear = 0, hits = 0;
        double worst_t = 0;
        for (int j = 0; j < height; j++)
            for (int i = 0; i < width; i++) {
                const int p = j * width + i;
                hr_ray ray;
                hr_camera_ray(&w.camera, i + 0.5, j + 0.5, &ray);
                if (s == 0) {
                    double margin;
                    ref_found[p] = (signed char)reference_hit(&w, &ray, tube, &ref_t[p], &margin);
                    ref_clear[p] = margin > CLEAR_MARGIN;
                }
                hr_hit hit;
                int32_t found;
                if (hr_scene_first_hit(w.scene, &ray, 0, INFINITY, &hit, &found) != HR_OK)
                    fail(ctx, "first hit");
                if (found != ref_found[p]) {
                    hitmiss++;
                    hitmiss_clear += ref_clear[p];
                } else if (found) {
                    hits++;
                    worst_t = fmax(worst_t, fabs(hit.t - ref_t[p]) / ref_t[p]);
                }
            }
        double seconds;
        hr_image *image = render(ctx, &w, repeats, &seconds);
        float *data = hr_image_data(image);
        if (s == 0) memcpy(bracketing_image, data, (size_t)pixels * 3 * sizeof(float));
        int shade = 0;
        for (int p = 0; p < pixels; p++)
            shade += shade_differs(data + 3 * p, bracketing_image + 3 * p);
        if (images) {
            char path[1024];
            snprintf(path, sizeof path, "%s/torus_far_%g_%g_%s.png", images, distance, tube,
                     solver_names[s]);
            if (hr_image_write(ctx, image, path, NULL) != HR_OK) fail(ctx, path);
        }
        printf("{\"tube\": %g, \"solver\": \"%s\", \"distance\": %g, \"width\": %d, "
               "\"height\": %d, \"hits\": %d, \"hitmiss\": %d, \"hitmiss_clear\": %d, "
               "\"t_rel\": %.3e, \"shade\": %d, \"repeats\": %d, \"seconds\": %.4f}\n",
               tube, solver_names[s], distance, width, height, hits, hitmiss, hitmiss_clear,
               worst_t, shade, repeats, seconds);
        fflush(stdout);
        hr_image_destroy(image);
        hr_scene_destroy(w.scene);
    }
    free(ref_found);
    free(ref_clear);
    free(ref_t);
    free(bracketing_image);
}

int main(int argc, char **argv)
{
    int width = 320, height = 240, repeats = 3, ok = 1;
    const char *images = NULL;
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (bench_option(argv[i], "--size", &v)) ok &= sscanf(v, "%dx%d", &width, &height) == 2;
        else if (bench_option(argv[i], "--repeats", &v)) repeats = atoi(v);
        else if (bench_option(argv[i], "--images", &v)) images = v;
        else ok = 0;
    }
    if (!ok || width <= 0 || height <= 0 || repeats <= 0) {
        fprintf(stderr, "usage: torus_far [--size=WxH] [--repeats=N] [--images=DIR]\n");
        return 2;
    }
    hr_context *ctx;
    if (hr_context_create(&ctx) != HR_OK) return 1;
    static const double distances[] = {1e4, 1e6}, tubes[] = {0.2, 0.05, 0.01};
    for (int d = 0; d < 2; d++)
        for (int t = 0; t < 3; t++)
            run_tube(ctx, distances[d], tubes[t], width, height, repeats, images);
    hr_context_destroy(ctx);
    return 0;
}
