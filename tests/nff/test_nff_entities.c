/* Each NFF entity by hand (tests/data/scenes/nff/entities.nff): the camera, the
 * background, lights with and without a colour, the material's mapping, a
 * sphere, a cone and cylinders in both layouts of `c` (open: a ray along
 * the axis passes through), a truncated cone with its smaller end first,
 * a many-vertex convex polygon and a concave one (its notches stay empty),
 * a patch whose normals are interpolated; the same scene from a string and
 * from a gzip file; a file without `v` gets a framing camera. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include <hitray/hitray.h>

#include "hr_test.h"

#define ENTITIES HR_TEST_SOURCE_DIR "/tests/data/scenes/nff/entities.nff"

static hr_context *ctx;

static const double PI = 3.14159265358979323846;

static hr_scene *load(const char *path, hr_sdl_result *r)
{
    memset(r, 0, sizeof *r);
    r->struct_size = sizeof *r;
    hr_status st = hr_nff_load_file(ctx, path, r);
    CHECK_MSG(st == HR_OK, "%s: %s", path, hr_context_last_error(ctx));
    if (st) return NULL;
    CHECK_OK(hr_scene_commit(r->scene));
    return r->scene;
}

/* The nearest hit of origin + t dir; *found says whether there is one. */
static hr_hit first_hit(hr_scene *s, hr_vec3 o, hr_vec3 d, int32_t *found)
{
    hr_ray ray = {o, d};
    hr_hit h;
    memset(&h, 0, sizeof h);
    CHECK_OK(hr_scene_first_hit(s, &ray, 0.0, INFINITY, &h, found));
    return h;
}

static void expect_hit(hr_scene *s, hr_vec3 o, hr_vec3 d, int64_t object, double t,
                       const char *what)
{
    int32_t found = 0;
    hr_hit h = first_hit(s, o, d, &found);
    CHECK_MSG(found && h.object == object && fabs(h.t - t) < 1e-9,
              "%s: found %d, object %lld, t %.17g (expected object %lld at t %.17g)", what,
              (int)found, (long long)h.object, h.t, (long long)object, t);
}

static void expect_miss(hr_scene *s, hr_vec3 o, hr_vec3 d, const char *what)
{
    int32_t found = 0;
    hr_hit h = first_hit(s, o, d, &found);
    CHECK_MSG(!found, "%s: hit object %lld at t %g", what, (long long)h.object, h.t);
}

static void check_camera_and_settings(const hr_sdl_result *r)
{
    CHECK(r->has_camera == 1);
    const hr_camera *c = &r->camera;
    CHECK(c->eye.x == 0 && c->eye.y == -10 && c->eye.z == 0);
    CHECK(c->look.x == 0 && c->look.y == 0 && c->look.z == 0);
    CHECK(c->up.x == 0 && c->up.y == 0 && c->up.z == 1);
    CHECK(c->view_angle == 40);
    CHECK(c->width == 64 && c->height == 48);
    hr_scene_globals g;
    memset(&g, 0, sizeof g);
    g.struct_size = sizeof g;
    CHECK_OK(hr_scene_get_globals(r->scene, &g));
    /* The SPD's rules: the eye ray and four bounces, every non-zero
     * coefficient spawning its ray, no ambient term. */
    CHECK(g.max_recursion_depth == 4);
    CHECK(g.min_reflectivity == 0.0 && g.min_transparency == 0.0);
    CHECK(g.background.r == 0.1 && g.background.g == 0.2 && g.background.b == 0.3);
    CHECK(g.global_ambient.r == 0 && g.global_ambient.g == 0 && g.global_ambient.b == 0);
}

/* Three lights, one with a colour: the other two get 1/sqrt(3) each. */
static void check_lights(hr_scene *s)
{
    CHECK(hr_scene_light_count(s) == 3);
    const double share = 1.0 / sqrt(3.0);
    for (int32_t i = 0; i < 3 && i < hr_scene_light_count(s); i++) {
        hr_light L;
        memset(&L, 0, sizeof L);
        L.struct_size = sizeof L;
        CHECK_OK(hr_scene_light(s, i, &L));
        if (i == 1) {
            CHECK(L.position.x == -10 && L.position.y == -10 && L.position.z == 10);
            CHECK(L.color.r == 0.5 && L.color.g == 0.25 && L.color.b == 1);
        } else {
            CHECK_MSG(L.color.r == share && L.color.g == share && L.color.b == share,
                      "light %d: %g %g %g", (int)i, L.color.r, L.color.g, L.color.b);
        }
    }
}

static hr_object_info object(hr_scene *s, int64_t i)
{
    hr_object_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    CHECK_OK(hr_scene_object_info(s, i, &info));
    return info;
}

/* f 1 0.5 0.25 0.8 0.3 20 0.4 1.5: Kd times the colour is diffuse, Ks both
 * the (white) specular and the reflectivity, T the transparency, 1 / ior
 * Hill's relative speed of light; no ambient. */
static void check_material(hr_scene *s)
{
    hr_object_info o = object(s, 0);
    const hr_material *m = &o.material;
    CHECK(m->diffuse.r == 0.8 && m->diffuse.g == 0.4 && m->diffuse.b == 0.8 * 0.25);
    CHECK(m->specular.r == 0.3 && m->specular.g == 0.3 && m->specular.b == 0.3);
    CHECK(m->specular_exponent == 20);
    CHECK(m->reflectivity == 0.3 && m->transparency == 0.4);
    CHECK(m->speed_of_light == 1.0 / 1.5);
    CHECK(m->ambient.r == 0 && m->ambient.g == 0 && m->ambient.b == 0);
    /* A material without T keeps the speed of light of empty space. */
    hr_object_info flat = object(s, 3);
    CHECK(flat.material.transparency == 0 && flat.material.speed_of_light == 1.0);
    CHECK(flat.material.reflectivity == 0);
}

static void check_objects(hr_scene *s)
{
    CHECK_MSG(hr_scene_object_count(s) == 6, "%lld objects", (long long)hr_scene_object_count(s));
    static const char *const shapes[6] = {"sphere",
                                          "openTaperedCylinder",
                                          "openTaperedCylinder",
                                          "openTaperedCylinder",
                                          "triangleMesh",
                                          "triangleMesh"};
    for (int64_t i = 0; i < 6 && i < hr_scene_object_count(s); i++) {
        hr_object_info o = object(s, i);
        CHECK_MSG(strcmp(o.shape, shapes[i]) == 0, "object %lld is a %s", (long long)i, o.shape);
    }
    const hr_vec3 y = {0, 1, 0}, x = {1, 0, 0};
    /* The sphere of radius 1 at the origin. */
    expect_hit(s, (hr_vec3){0, -5, 0}, y, 0, 4.0, "sphere");
    /* The cone, radius 1 at z = -1 to a point at z = 1: radius 0.5 at z = 0. */
    expect_hit(s, (hr_vec3){3, -5, 0}, y, 1, 4.5, "cone at mid height");
    expect_miss(s, (hr_vec3){3, -5, 1.2}, y, "above the cone's apex");
    /* The open cylinder along x from -6 to -2, radius 0.5: a ray across it
     * meets its wall twice, one along its axis passes through both open
     * ends and goes on to the sphere. */
    expect_hit(s, (hr_vec3){-4, -5, 0}, y, 2, 4.5, "cylinder's wall");
    hr_intersection all;
    hr_intersection_init(&all);
    hr_ray across = {{-4, -5, 0}, y};
    CHECK_OK(hr_scene_all_hits(s, &across, 0.0, INFINITY, &all));
    CHECK_MSG(all.count == 2 && all.hits[0].object == 2 && all.hits[1].object == 2 &&
                  fabs(all.hits[1].t - 5.5) < 1e-9,
              "across the cylinder: %d hits", (int)all.count);
    hr_intersection_release(&all);
    expect_hit(s, (hr_vec3){-10, 0, 0}, x, 0, 9.0, "along the open cylinder's axis");
    /* The truncated cone: radius 0.25 at z = 3 to 0.75 at z = 5, written
     * small end first. */
    expect_hit(s, (hr_vec3){0, -5, 4}, y, 3, 4.5, "truncated cone at z = 4");
    expect_hit(s, (hr_vec3){0, -5, 4.9}, y, 3, 5.0 - 0.725, "truncated cone at z = 4.9");
    expect_miss(s, (hr_vec3){0, -5, 5.1}, y, "above the truncated cone");
    /* The 12-gon round (9, 3, 0), radius 1, and the comb, both one mesh. */
    expect_hit(s, (hr_vec3){9, -5, 0}, y, 4, 8.0, "12-gon's centre");
    expect_hit(s, (hr_vec3){9.95, -5, 0}, y, 4, 8.0, "12-gon near a corner");
    expect_hit(s, (hr_vec3){9, -5, 0.95}, y, 4, 8.0, "12-gon near an edge's middle");
    expect_miss(s, (hr_vec3){9.7, -5, 0.8}, y, "outside the 12-gon, inside its box");
    const double teeth[] = {11.5, 9.0, 6.5}, gaps[] = {10.5, 7.5};
    for (int i = 0; i < 3; i++)
        expect_hit(s, (hr_vec3){teeth[i], -5, -2.5}, y, 4, 8.0, "a tooth of the comb");
    for (int i = 0; i < 2; i++) expect_miss(s, (hr_vec3){gaps[i], -5, -2.5}, y, "a comb's notch");
    expect_hit(s, (hr_vec3){7.5, -5, -3.5}, y, 4, 8.0, "the comb's bar");
    /* The patch: normals (0, -1, 0) at x = -12 and (1, -1, 0) at x = -10,
     * so (0.5, -1, 0) half way, where the flat normal is (0, -1, 0). */
    int32_t found = 0;
    hr_hit h = first_hit(s, (hr_vec3){-11, -5, 0}, y, &found);
    CHECK(found && h.object == 5 && fabs(h.t - 8.0) < 1e-9);
    const double len = sqrt(1.25);
    CHECK_MSG(fabs(h.normal.x - 0.5 / len) < 1e-12 && fabs(h.normal.y + 1.0 / len) < 1e-12 &&
                  fabs(h.normal.z) < 1e-12,
              "patch normal %.17g %.17g %.17g", h.normal.x, h.normal.y, h.normal.z);
}

static void check_scene(const hr_sdl_result *r)
{
    check_camera_and_settings(r);
    check_lights(r->scene);
    check_material(r->scene);
    check_objects(r->scene);
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    CHECK(f != NULL);
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = calloc((size_t)n + 1, 1);
    CHECK(text && fread(text, 1, (size_t)n, f) == (size_t)n);
    fclose(f);
    return text;
}

/* The same scene from a string, and from a gzip file (zlib tells it by its
 * bytes: the name says nothing). */
static void test_string_and_gzip(void)
{
    char *text = read_text(ENTITIES);
    if (!text) return;
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    CHECK_OK(hr_nff_load_string(ctx, text, "entities", &r));
    if (r.scene) {
        CHECK_OK(hr_scene_commit(r.scene));
        check_scene(&r);
        hr_scene_destroy(r.scene);
    }
    const char *gz = HR_TEST_BINARY_DIR "/tests/entities_nff.gz";
    gzFile f = gzopen(gz, "wb");
    CHECK(f != NULL);
    if (f) {
        CHECK(gzwrite(f, text, (unsigned)strlen(text)) == (int)strlen(text));
        CHECK(gzclose(f) == Z_OK);
        hr_sdl_result z;
        if (load(gz, &z)) {
            check_scene(&z);
            hr_scene_destroy(z.scene);
        }
        remove(gz);
    }
    free(text);
}

/* No `v`: the camera frames the scene, at 640x480, as for SDL. */
static void test_no_view(void)
{
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    CHECK_OK(hr_nff_load_string(ctx, "f 1 1 1 1 0 1 0 0\ns 0 0 0 1\n", NULL, &r));
    CHECK(r.scene && r.has_camera == 0);
    CHECK(r.camera.width == 640 && r.camera.height == 480);
    CHECK(hr_camera_validate(ctx, &r.camera) == HR_OK);
    /* No light and no `b`: the background is black. */
    hr_scene_globals g = {0};
    g.struct_size = sizeof g;
    CHECK_OK(hr_scene_get_globals(r.scene, &g));
    CHECK(g.background.r == 0 && g.background.g == 0 && g.background.b == 0);
    CHECK(hr_scene_light_count(r.scene) == 0);
    hr_scene_destroy(r.scene);
}

/* The scene renders at its own size with finite pixels. */
static void test_render(const hr_sdl_result *r)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 2;
    hr_image *img = NULL;
    CHECK_OK(hr_render(r->scene, &r->camera, &o, &img, NULL));
    if (!img) return;
    CHECK(hr_image_width(img) == 64 && hr_image_height(img) == 48);
    const float *p = hr_image_data(img);
    int finite = 1;
    for (int i = 0; i < 64 * 48 * 3; i++) finite &= isfinite(p[i]) != 0;
    CHECK(finite);
    hr_image_destroy(img);
}

/* A polygon of `n` vertices round the origin in the plane z = 0, radius 1,
 * every other vertex pulled in to `inner` (1: convex). */
static char *ring_polygon(int n, double inner)
{
    const size_t size = 64 + (size_t)n * 64;
    char *text = malloc(size);
    if (!text) return NULL;
    size_t used = (size_t)snprintf(text, size, "f 1 1 1 1 0 1 0 0\np %d\n", n);
    for (int i = 0; i < n && used < size; i++) {
        const double a = 2.0 * PI * i / n, r = i % 2 ? inner : 1.0;
        used += (size_t)snprintf(text + used, size - used, "%.17g %.17g 0\n", r * cos(a),
                                 r * sin(a));
    }
    return text;
}

/* Past 1024 vertices a convex polygon is cut as a strip (O(n)): it covers
 * the disk and nothing outside it. */
static void test_large_convex_polygon(void)
{
    const int n = 3000;
    char *text = ring_polygon(n, 1.0);
    if (!text) return;
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    CHECK_OK(hr_nff_load_string(ctx, text, "ring", &r));
    free(text);
    if (!r.scene) return;
    CHECK_OK(hr_scene_commit(r.scene));
    const hr_vec3 down = {0, 0, -1};
    /* The inscribed radius is cos(pi / n); a point inside it is covered,
     * one outside the circumscribed circle is not. */
    for (int k = 0; k < 16; k++) {
        const double a = 2.0 * PI * (k + 0.3) / 16, inside = 0.9999 * cos(PI / n);
        expect_hit(r.scene, (hr_vec3){inside * cos(a), inside * sin(a), 1}, down, 0, 1.0,
                   "inside a 3000-gon");
        expect_miss(r.scene, (hr_vec3){1.0001 * cos(a), 1.0001 * sin(a), 1}, down,
                    "outside a 3000-gon");
    }
    expect_hit(r.scene, (hr_vec3){0, 0, 1}, down, 0, 1.0, "a 3000-gon's centre");
    hr_scene_destroy(r.scene);
}

/* A concave polygon of 16384 vertices, a star of alternate radii 1 and
 * 0.5 (ear clipping with its grid and heap: a fraction of a second, where
 * a pass over the polygon for each cut took seconds): every tip is
 * covered, every notch between two tips is empty. */
static void test_large_concave_polygon(void)
{
    enum { N = 16384 };
    char *text = malloc(64 + (size_t)N * 48);
    if (!text) return;
    size_t used = (size_t)sprintf(text, "f 1 1 1 1 0 1 0 0\np %d\n", N);
    for (int i = 0; i < N; i++) {
        const double a = 2.0 * PI * i / N, radius = i % 2 ? 0.5 : 1.0;
        used += (size_t)sprintf(text + used, "%.17g %.17g 0\n", radius * cos(a), radius * sin(a));
    }
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    CHECK_OK(hr_nff_load_string(ctx, text, "star", &r));
    free(text);
    if (!r.scene) return;
    CHECK_OK(hr_scene_commit(r.scene));
    const hr_vec3 down = {0, 0, -1};
    /* At radius 0.75 along vertex i: inside the tip of an even i, in the
     * notch of an odd one (its edges pass 1e-4 away either side). */
    for (int i = 0; i < N; i += 97) {
        const double a = 2.0 * PI * i / N;
        const hr_vec3 o = {0.75 * cos(a), 0.75 * sin(a), 1};
        if (i % 2) expect_miss(r.scene, o, down, "a star's notch");
        else expect_hit(r.scene, o, down, 0, 1.0, "a star's tip");
    }
    expect_hit(r.scene, (hr_vec3){0, 0, 1}, down, 0, 1.0, "a star's centre");
    hr_scene_destroy(r.scene);
}

/* Self-crossing polygons of 16384 vertices (random points) have no ears
 * to find in the grid: each cut scans the polygon, some 10^8 steps each,
 * and a file of hundreds of them took many minutes. The file's clipping
 * budget (2^30 steps) refuses the polygon that passes it, naming its line;
 * the eight before it were cut. */
static void test_clipping_budget(void)
{
    enum { N = 16384, POLYGONS = 9 };
    char *text = malloc((size_t)POLYGONS * (16 + (size_t)N * 32));
    if (!text) return;
    size_t used = 0;
    uint64_t state = 12345;
    for (int k = 0; k < POLYGONS; k++) {
        used += (size_t)sprintf(text + used, "p %d\n", N);
        for (int i = 0; i < N; i++) {
            double xy[2];
            for (int c = 0; c < 2; c++) {
                state = state * 6364136223846793005ull + 1442695040888963407ull;
                xy[c] = (double)(state >> 11) * 0x1p-53;
            }
            used += (size_t)sprintf(text + used, "%.6f %.6f %d\n", xy[0], xy[1], k);
        }
    }
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    const hr_status st = hr_nff_load_string(ctx, text, "tangle.nff", &r);
    free(text);
    const char *msg = hr_context_last_error(ctx);
    CHECK_MSG(st == HR_ERROR_SDL && r.scene == NULL, "status %d: %s", (int)st, msg);
    char expected[64];
    snprintf(expected, sizeof expected, "tangle.nff:%d:1: 'p 16384': ear clipping", 1 + 7 * (N + 1));
    CHECK_MSG(strstr(msg, expected) == msg && strstr(msg, "budget of 1073741824 steps"), "%s", msg);
    if (r.scene) hr_scene_destroy(r.scene);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    hr_sdl_result r;
    if (load(ENTITIES, &r)) {
        check_scene(&r);
        test_render(&r);
        hr_scene_destroy(r.scene);
    }
    test_string_and_gzip();
    test_no_view();
    test_large_convex_polygon();
    test_large_concave_polygon();
    test_clipping_budget();
    hr_context_destroy(ctx);
    return hr_test_end();
}
