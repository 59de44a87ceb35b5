/* The tie rule: at an exact tie in t the object added first wins, then the
 * lower surface id (hit_before's order, the brute force's answer), whatever
 * order the BVH visits leaves in.
 *
 * 1,000 coincident pairs of spheres of two colours (every pair one sphere
 * added twice, at the same place and size, so every ray that meets one
 * meets the other at the same t, bit for bit), in both orders: red then
 * green, and green then red. Every first hit must name the first-added
 * sphere of its pair, and the render must be, bit for bit, the render of
 * the first-added spheres alone (a shadow ray asks whether anything blocks
 * it, which a duplicate does not change). The spheres overlap and nest, so
 * the BVH holds each pair's two copies in one leaf or in two, and meets
 * them in either order. Without the rule about half the lit pixels showed
 * the later sphere. Then the same with a plane: two coincident planes and
 * a field of cubes whose top faces lie in the planes' z = 0, added in each
 * order, for the unbounded objects tested after the walk. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

#define PAIRS 1000
#define W 160
#define H 120

static hr_context *ctx;

static double uniform(uint64_t *s)
{
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1p-53;
}

static hr_material coloured(double r, double g, double b)
{
    hr_material m;
    hr_material_default(&m);
    m.ambient = (hr_color){0.2 * r, 0.2 * g, 0.2 * b};
    m.diffuse = (hr_color){r, g, b};
    m.specular = (hr_color){0.3, 0.3, 0.3};
    m.specular_exponent = 20;
    return m;
}

/* which: 1 the red copies only, 2 the green only, 3 red then green in each
 * pair, 4 green then red. */
static hr_scene *spheres(int which)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    const hr_material red = coloured(0.9, 0.1, 0.1), green = coloured(0.1, 0.9, 0.1);
    uint64_t seed = 2026;
    for (int i = 0; i < PAIRS; i++) {
        hr_transform t = tb_place(16 * uniform(&seed) - 8, 12 * uniform(&seed) - 6, 8 * uniform(&seed) - 4,
                                  0.1 + 0.5 * uniform(&seed));
        const hr_material *first = which == 4 ? &green : &red, *second = which == 4 ? &red : &green;
        if (which == 2) first = &green;
        tb_add(s, "sphere", first, &t);
        if (which >= 3) tb_add(s, "sphere", second, &t);
    }
    tb_light(s, 10, 20, 30, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    return s;
}

static hr_camera view(void)
{
    hr_camera c;
    hr_camera_default(&c); /* looking at the origin */
    c.width = W, c.height = H, c.eye = (hr_vec3){3, 4, 24};
    return c;
}

static hr_image *render(const hr_scene *s)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = W, o.height = H, o.threads = 2;
    hr_camera c = view();
    hr_image *img = NULL;
    CHECK_MSG(hr_render(s, &c, &o, &img, NULL) == HR_OK, "render: %s", hr_context_last_error(ctx));
    return img;
}

/* Every first hit of a camera ray names the first copy of its pair: in a
 * scene of pairs objects 2i and 2i + 1 are one pair, so the object must be
 * even. Returns how many rays met a sphere. */
static int first_copies_win(const hr_scene *s, const char *name)
{
    hr_camera c = view();
    int hits = 0, later = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            hr_ray r;
            CHECK_OK(hr_camera_ray(&c, x + 0.5, y + 0.5, &r));
            hr_hit h;
            int32_t found = 0;
            CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, &h, &found));
            if (!found) continue;
            hits++;
            if (h.object % 2 && later++ < 3)
                fprintf(stderr, "%s: pixel %d,%d: first hit on object %lld, the later copy\n", name, x, y,
                        (long long)h.object);
        }
    CHECK_MSG(later == 0, "%s: %d of %d first hits name the later-added copy", name, later, hits);
    return hits;
}

static void same_image(hr_image *a, hr_image *b, const char *what)
{
    CHECK(a && b);
    if (!a || !b) return;
    const float *p = hr_image_data(a), *q = hr_image_data(b);
    int differ = 0;
    for (int k = 0; k < W * H * 3; k += 3) differ += memcmp(p + k, q + k, 3 * sizeof *p) != 0;
    CHECK_MSG(differ == 0, "%s: %d of %d pixels differ", what, differ, W * H);
}

static void coincident_sphere_pairs(void)
{
    hr_scene *red = spheres(1), *green = spheres(2), *red_first = spheres(3), *green_first = spheres(4);
    int hits = first_copies_win(red_first, "red then green");
    first_copies_win(green_first, "green then red");
    CHECK_MSG(hits > W * H / 4, "only %d of %d rays meet a sphere", hits, W * H);
    hr_image *a = render(red), *b = render(green), *c = render(red_first), *d = render(green_first);
    same_image(c, a, "red then green against red alone");
    same_image(d, b, "green then red against green alone");
    hr_image_destroy(a), hr_image_destroy(b), hr_image_destroy(c), hr_image_destroy(d);
    hr_scene_destroy(red), hr_scene_destroy(green), hr_scene_destroy(red_first), hr_scene_destroy(green_first);
}

/* 1 where (x, y) lies on a cube's top face (well inside it), 0 where it is
 * well outside every one, -1 near a rim, where rounding decides. */
static int on_the_face(double c, int *inside)
{
    /* The distance from the nearest cube centre, -10.5 + 3j (j = 0 .. 7). */
    double j = floor((c + 10.5) / 3 + 0.5);
    if (j < 0) j = 0;
    if (j > 7) j = 7;
    const double d = fabs(c - (3 * j - 10.5));
    if (fabs(d - 1) < 1e-9) return -1;
    *inside &= d < 1;
    return 0;
}
static int over_a_cube(double x, double y)
{
    int inside = 1;
    if (on_the_face(x, &inside) || on_the_face(y, &inside)) return -1;
    return inside;
}

/* Planes are not in the BVH: they are tested after its walk, and must lose
 * a tie to a cube added before them and win one against a cube added after.
 * 64 cubes with their top faces in z = 0 and two planes z = 0, the planes
 * added last (planes_last) or first; rays with dyadic origins and
 * directions, for which a cube's top face and a plane give the same t, bit
 * for bit (the cube's slab and the plane's -o_z / d_z). */
static void planes_and_cubes(int planes_last)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    if (!planes_last) tb_add(s, "plane", NULL, NULL), tb_add(s, "plane", NULL, NULL);
    for (int i = 0; i < 64; i++) {
        hr_transform t = tb_place((i % 8) * 3 - 10.5, (i / 8) * 3 - 10.5, -1.0, 1.0);
        tb_add(s, "cube", NULL, &t);
    }
    if (planes_last) tb_add(s, "plane", NULL, NULL), tb_add(s, "plane", NULL, NULL);
    CHECK_OK(hr_scene_commit(s));
    const int64_t first_plane = planes_last ? 64 : 0;
    uint64_t seed = 5;
    int ties = 0, wrong = 0;
    for (int k = 0; k < 5000; k++) {
        hr_ray r = {{floor(160 * uniform(&seed) - 80) / 8, floor(160 * uniform(&seed) - 80) / 8,
                     floor(80 * uniform(&seed) + 1) / 8},
                    {floor(32 * uniform(&seed) - 16) / 16, floor(32 * uniform(&seed) - 16) / 16,
                     -floor(16 * uniform(&seed) + 1) / 16}};
        hr_hit h;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &r, 0, INFINITY, &h, &found));
        if (!found) continue;
        /* A cube's top face at the planes' t is a tie; the planes' own t
         * is -o_z / d_z. */
        const double plane_t = -r.origin.z / r.dir.z;
        if (h.t != plane_t) continue;
        const int is_cube = planes_last ? h.object < 64 : h.object >= 2;
        const int over = over_a_cube(r.origin.x + plane_t * r.dir.x, r.origin.y + plane_t * r.dir.y);
        if (over < 0) continue; /* near a rim: the cube may or may not meet it */
        if (!over) {
            wrong += h.object != first_plane;
            continue;
        }
        ties++;
        wrong += planes_last ? !is_cube : h.object != first_plane;
        if (planes_last && !is_cube && wrong < 4)
            fprintf(stderr, "planes last, ray %d: a plane (object %lld) won the tie with a cube added before it\n",
                    k, (long long)h.object);
    }
    CHECK_MSG(wrong == 0, "planes %s: %d rays broke the tie rule", planes_last ? "last" : "first", wrong);
    CHECK_MSG(ties > 500, "planes %s: only %d ties", planes_last ? "last" : "first", ties);
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    coincident_sphere_pairs();
    planes_and_cubes(1);
    planes_and_cubes(0);
    hr_context_destroy(ctx);
    return hr_test_end();
}
