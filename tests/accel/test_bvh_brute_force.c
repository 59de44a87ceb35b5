/* The scene's BVH walk against a brute-force loop over every object, on
 * 1.8 x 10^6 random rays (1.8 x 10^5 in the sanitizer builds, which run ten
 * times slower) over varied scenes: spheres, cubes, cylinders, cones and tori
 * under random rotations and non-uniform scales; regular solids and a mesh
 * file (the mesh module); CSG booleans; and the first scene again at the
 * extremes of scale (1e-6 of the size, 1e6 away, and 1e5 times the size).
 *
 * The brute force is hr_scene_all_hits, which traces every top-level object
 * without the BVH and sorts the hits by (t, object, surface). The float
 * boxes and the float walk are only allowed to cost time, never a hit, and
 * the tie rule (at an exact tie in t the object added first wins, then the
 * lower surface) makes the first hit that list's first whatever order the
 * walk meets objects in: the same t, bit for bit, the same object and the
 * same surface. Exact ties are made on purpose: scenes with every object
 * added twice (a coincident copy, which the BVH may meet first), and a grid
 * of axis-aligned cubes sharing faces, each twice, added in a shuffled
 * order, with dyadic rays that meet its shared edges exactly (where the
 * box of a cube added first is entered at exactly the best t found in a
 * later one's). */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

#define RAYS_PER_SCENE (HR_TEST_SANITIZED ? 20000 : 200000)

static uint64_t seed = 0x2545f4914f6cdd1dull;
static double uniform(void)
{
    seed ^= seed >> 12, seed ^= seed << 25, seed ^= seed >> 27;
    return (double)((seed * 2685821657736338717ull) >> 11) * 0x1p-53;
}
static double between(double a, double b) { return a + (b - a) * uniform(); }

typedef struct text {
    char *s;
    size_t len, cap;
} text;

static void add(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void add(text *t, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(t->s + t->len, t->cap - t->len, fmt, ap);
        va_end(ap);
        if (n >= 0 && (size_t)n < t->cap - t->len) {
            t->len += (size_t)n;
            return;
        }
        t->cap = t->cap * 2 + (size_t)n + 256;
        t->s = realloc(t->s, t->cap);
        if (!t->s) abort();
    }
}

/* A random placement: rotation about a random axis, a non-uniform scale,
 * inside a cube of side 2 `extent` about `centre` (SDL applies the last
 * transform first: scale, rotate, then translate). */
static void place(text *t, double centre, double extent, double size)
{
    add(t, "push translate %.17g %.17g %.17g rotate %.17g %.17g %.17g %.17g scale %.17g %.17g %.17g\n",
        centre + between(-extent, extent), centre + between(-extent, extent),
        centre + between(-extent, extent), between(0, 360), between(-1, 1), between(-1, 1),
        between(0.1, 1), size * between(0.3, 1.5), size * between(0.3, 1.5), size * between(0.3, 1.5));
}

/* copies: each object added once, or twice at the same place (an exact tie
 * wherever the ray meets it). */
static void quadrics(text *t, double centre, double extent, double size, int copies)
{
    static const char *shapes[] = {"sphere", "cube", "cylinder", "cone", "taperedCylinder 0.5",
                                   "torus"};
    for (int i = 0; i < 60; i++) {
        place(t, centre, extent, size);
        for (int c = 0; c < copies; c++) add(t, "%s\n", shapes[i % 6]);
        add(t, "pop\n");
    }
}

static void meshes(text *t, int copies)
{
    static const char *shapes[] = {"tetrahedron", "octahedron", "dodecahedron", "icosahedron",
                                   "mesh cube.obj", "mesh tetra_hill.3vn"};
    for (int i = 0; i < 60; i++) {
        place(t, 0, 10, 2);
        for (int c = 0; c < copies; c++) add(t, "%s\n", shapes[i % 6]);
        add(t, "pop\n");
    }
}

static void booleans(text *t, int copies)
{
    static const char *ops[] = {"union", "intersection", "difference"};
    for (int i = 0; i < 40; i++) {
        place(t, 0, 10, 1.5);
        const char *op = ops[i % 3];
        const double x = between(-0.8, 0.8), angle = between(0, 90);
        for (int c = 0; c < copies; c++)
            add(t, "%s\n  push translate %.17g 0 0 sphere pop\n  push rotate %.17g 0 1 0 cube pop\n", op, x,
                angle);
        add(t, "pop\n");
    }
}

/* A 6 x 6 x 6 grid of cubes of side 2 about the origin, sharing faces, each
 * added twice, in a shuffled order (so that the order objects are added in
 * is not the BVH's). */
static void cube_grid(text *t)
{
    int cell[216];
    for (int i = 0; i < 216; i++) cell[i] = i;
    for (int i = 215; i > 0; i--) {
        int j = (int)(uniform() * (i + 1)), c = cell[i];
        cell[i] = cell[j], cell[j] = c;
    }
    for (int i = 0; i < 216; i++) {
        const int c = cell[i];
        add(t, "push translate %d %d %d cube cube pop\n", 2 * (c % 6) - 5, 2 * (c / 6 % 6) - 5, 2 * (c / 36) - 5);
    }
}

typedef struct scene_case {
    const char *name;
    double centre, extent; /* where rays start and aim */
} scene_case;

/* Rays from a random point of a cube twice the scene's size towards a
 * random point inside the scene (most meet several objects), a few of
 * them axis-parallel; dyadic: both points on a grid of 1/8. */
static hr_ray random_ray(double centre, double extent, int k, int dyadic)
{
    hr_ray r;
    hr_vec3 from = {centre + between(-2, 2) * extent, centre + between(-2, 2) * extent,
                    centre + between(-2, 2) * extent};
    hr_vec3 to = {centre + between(-1, 1) * extent, centre + between(-1, 1) * extent,
                  centre + between(-1, 1) * extent};
    if (k % 17 == 0) to.y = from.y;
    if (k % 29 == 0) to.x = from.x, to.z = from.z;
    if (dyadic) { /* multiples of 1/8: rays that meet edges and corners exactly */
        from = (hr_vec3){round(8 * from.x) / 8, round(8 * from.y) / 8, round(8 * from.z) / 8};
        to = (hr_vec3){round(8 * to.x) / 8, round(8 * to.y) / 8, round(8 * to.z) / 8};
    }
    r.origin = from;
    r.dir = (hr_vec3){to.x - from.x, to.y - from.y, to.z - from.z};
    if (r.dir.x == 0 && r.dir.y == 0 && r.dir.z == 0) r.dir.x = 1;
    return r;
}

static void run_case(hr_context *ctx, const char *name, const char *sdl, double centre, double extent,
                     int dyadic, long min_ties, long min_apart)
{
    hr_sdl_result res = {.struct_size = sizeof res};
    if (hr_sdl_load_string(ctx, sdl, name, HR_TEST_SOURCE_DIR "/tests/data/meshes", &res) != HR_OK) {
        CHECK_MSG(0, "%s: %s", name, hr_context_last_error(ctx));
        return;
    }
    CHECK(hr_scene_commit(res.scene) == HR_OK);
    hr_intersection all;
    hr_intersection_init(&all);
    long hits = 0, ties = 0, apart = 0, wrong = 0;
    for (int k = 0; k < RAYS_PER_SCENE; k++) {
        hr_ray r = random_ray(centre, extent, k, dyadic);
        double tmin = k % 5 == 0 ? 0.25 : 0.0;
        hr_hit first;
        int32_t found = 0;
        if (hr_scene_first_hit(res.scene, &r, tmin, INFINITY, &first, &found) != HR_OK ||
            hr_scene_all_hits(res.scene, &r, tmin, INFINITY, &all) != HR_OK) {
            CHECK_MSG(0, "%s: %s", name, hr_context_last_error(ctx));
            break;
        }
        if (found != (all.count > 0)) {
            if (wrong++ < 5)
                fprintf(stderr, "%s ray %d: first hit found %d, brute force %d hits\n", name, k,
                        (int)found, (int)all.count);
            continue;
        }
        if (!found) continue;
        hits++;
        /* The least hit in (t, object, surface) order, but that one object
         * meeting the ray at one t on two surfaces (a ray grazing a cube's
         * edge enters one face and leaves another there) gives its first
         * crossing, which enters: of the first object's hits at the first
         * t, the first that enters, else the first. */
        const hr_hit *want = &all.hits[0];
        for (int32_t i = 0; i < all.count && all.hits[i].t == all.hits[0].t &&
                            all.hits[i].object == all.hits[0].object && !want->entering;
             i++)
            if (all.hits[i].entering) want = &all.hits[i];
        ties += all.count > 1 && all.hits[1].t == want->t;
        /* A tie between objects that are not copies of one another (in
         * the grid, objects 2i and 2i + 1 are one cube's copies). */
        int split = 0;
        for (int32_t i = 1; i < all.count && all.hits[i].t == want->t; i++)
            split |= all.hits[i].object / 2 != want->object / 2;
        apart += split;
        int same = first.t == want->t && first.object == want->object && first.surface == want->surface;
        if (!same && wrong++ < 5)
            fprintf(stderr,
                    "%s ray %d: first hit t = %.17g object %lld surface %d, brute force t = %.17g object %lld "
                    "surface %d\n",
                    name, k, first.t, (long long)first.object, (int)first.surface, want->t,
                    (long long)want->object, (int)want->surface);
    }
    fprintf(stderr, "%s: %d rays, %ld hits, %ld exact ties (%ld not between objects 2i and 2i + 1), %ld wrong\n", name,
            RAYS_PER_SCENE, hits, ties, apart, wrong);
    CHECK_MSG(wrong == 0, "%s: %ld of %d rays disagree with the brute force", name, wrong, RAYS_PER_SCENE);
    CHECK_MSG(hits > RAYS_PER_SCENE / 5, "%s: only %ld hits", name, hits);
    /* Where a scene is made to have exact ties, they are met often. */
    CHECK_MSG(ties >= min_ties, "%s: only %ld exact ties", name, ties);
    CHECK_MSG(apart >= min_apart, "%s: only %ld exact ties between cubes sharing a face", name, apart);
    hr_intersection_release(&all);
    hr_scene_destroy(res.scene);
}

int main(void)
{
    hr_context *ctx;
    CHECK(hr_context_create(&ctx) == HR_OK);
    text t = {0};

    seed = 11;
    quadrics(&t, 0, 10, 2, 1);
    run_case(ctx, "quadrics", t.s, 0, 10, 0, 0, 0);
    t.len = 0;
    seed = 11; /* the same scene again, tiny and far away */
    quadrics(&t, 1e6, 1e-5, 2e-6, 1);
    run_case(ctx, "quadrics at 1e-6, 1e6 away", t.s, 1e6, 1e-5, 0, 0, 0);
    t.len = 0;
    seed = 11;
    quadrics(&t, 0, 1e6, 2e5, 1);
    run_case(ctx, "quadrics at 1e5", t.s, 0, 1e6, 0, 0, 0);
    t.len = 0;
    meshes(&t, 1);
    run_case(ctx, "meshes", t.s, 0, 10, 0, 0, 0);
    t.len = 0;
    booleans(&t, 1);
    run_case(ctx, "booleans", t.s, 0, 10, 0, 0, 0);
    /* Exact ties: every object twice, then the grid of cubes. */
    const long tie_rays = RAYS_PER_SCENE / 10; /* most rays meet a copied object first */
    t.len = 0;
    seed = 11;
    quadrics(&t, 0, 10, 2, 2);
    run_case(ctx, "quadrics, each twice", t.s, 0, 10, 0, tie_rays, 0);
    t.len = 0;
    meshes(&t, 2);
    run_case(ctx, "meshes, each twice", t.s, 0, 10, 0, tie_rays, 0);
    t.len = 0;
    booleans(&t, 2);
    run_case(ctx, "booleans, each twice", t.s, 0, 10, 0, tie_rays, 0);
    t.len = 0;
    cube_grid(&t);
    run_case(ctx, "cubes sharing faces, each twice", t.s, 0, 6, 1, tie_rays, RAYS_PER_SCENE / 1000);

    free(t.s);
    hr_context_destroy(ctx);
    return hr_test_end();
}
