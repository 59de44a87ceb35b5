/* The any-hit search of a closed mesh (shapes/mesh/mesh_trace.c,
 * closed_any_blocks) stops at the first hit it meets a rounding past tmin,
 * where the first-hit search looks on for near ties: its answer must
 * still be exactly whether the first-hit search finds a hit, on every
 * ray. On each ray the first hit must also be the first of the all-hits
 * list, and over the whole line that list's entering and leaving hits
 * must balance; where they do not alternate is counted and printed (a ray
 * in a face's plane: docs/limits.md). 10^6 rays per closed mesh (10^5 under the sanitizers, which make
 * every ray ten times slower and look for other faults), of six kinds, the
 * ones that make crossings a rounding apart most of all:
 * - random rays near the mesh, over random intervals;
 * - rays aimed exactly at a vertex, and at a point of an edge (its middle or
 *   anywhere along it), ending before, at or past it;
 * - shadow rays: from a point of a triangle (inside, on an edge or at a
 *   vertex) to a random light, from tmin 0 or just past it;
 * - grazing rays: through a point of an edge, along a face's plane or a
 *   hair off it;
 * - rays along an edge, from before it;
 * - rays at a point of a triangle, from just before or at it;
 * - rays from a vertex.
 * The meshes: the regular solids and the buckyball; a cube from a file;
 * a gear (a toothed outline extruded, like the SPD's gears, whose faces
 * the NFF reader cuts into triangles); and a Sierpinski tetrahedron, 16
 * tetrahedra meeting at their corners (the SPD's tetra), where a ray
 * through a shared corner leaves one and enters the next at one point;
 * two cubes, one on the other and offset (no edge shared), whose
 * faces between them touch: a ray through them leaves one and enters the
 * other at one point inside both faces; and a cube with a sliver face
 * (write_notched_cube), which any ray through it sees nearly edge on. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../../shapes/mesh/mesh.h"
#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"
#include "random_rays.h"

#define RAYS_PER_MESH (HR_TEST_SANITIZED ? 100000 : 1000000)
#define RAY_KINDS 8
#define HR_PI 3.14159265358979323846

static hr_vec3 vertex_of(const mesh *m, uint32_t tri, int corner)
{
    return m->vertices[m->corners[3 * (size_t)tri + (size_t)corner]];
}

static hr_vec3 lerp(hr_vec3 a, hr_vec3 b, double s)
{
    return harness_vec(a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.z + s * (b.z - a.z));
}

static hr_vec3 sub(hr_vec3 a, hr_vec3 b)
{
    return harness_vec(a.x - b.x, a.y - b.y, a.z - b.z);
}

/* A point of a random triangle: inside it (random barycentrics), on one of
 * its edges, or one of its corners. */
static hr_vec3 point_on(ray_rng *rng, const mesh *m, uint32_t *tri_out)
{
    const uint32_t tri = (uint32_t)(rng_next(rng) % m->triangle_count);
    *tri_out = tri;
    const hr_vec3 a = vertex_of(m, tri, 0), b = vertex_of(m, tri, 1), c = vertex_of(m, tri, 2);
    const uint64_t kind = rng_next(rng) % 4;
    if (kind == 0) return (rng_next(rng) & 1) ? a : b;
    if (kind == 1) return lerp(a, b, rng_uniform(rng, 0.0, 1.0));
    double u = rng_uniform(rng, 0.0, 1.0), v = rng_uniform(rng, 0.0, 1.0);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    return harness_vec(a.x + u * (b.x - a.x) + v * (c.x - a.x), a.y + u * (b.y - a.y) + v * (c.y - a.y),
                       a.z + u * (b.z - a.z) + v * (c.z - a.z));
}

/* A point a few mesh sizes away, in a random direction. */
static hr_vec3 far_point(ray_rng *rng, const hr_bounds *b)
{
    const hr_vec3 d = rng_unit_vector(rng);
    const double r = rng_uniform(rng, 3.0, 10.0);
    return harness_vec(0.5 * (b->lo.x + b->hi.x) + r * d.x, 0.5 * (b->lo.y + b->hi.y) + r * d.y,
                       0.5 * (b->lo.z + b->hi.z) + r * d.z);
}

/* An interval's end for a ray aimed at a point at t = 1: before it, at it,
 * just past it, or open. */
static double end_near_one(ray_rng *rng)
{
    static const double ends[] = {0.5, 1.0, 1.0 + 0x1p-52, 1.0 + 1e-9, 2.0, INFINITY};
    return ends[rng_next(rng) % (sizeof ends / sizeof ends[0])];
}

/* A tmin for a ray starting on the mesh: 0, or a rounding or a hair past it. */
static double start_near_zero(ray_rng *rng)
{
    static const double starts[] = {0.0, 0x1p-60, 1e-12, 1e-9, 1e-6};
    return starts[rng_next(rng) % (sizeof starts / sizeof starts[0])];
}

static void make_ray(ray_rng *rng, const mesh *m, int kind, hr_ray *ray, double *tmin, double *tmax)
{
    uint32_t tri;
    *tmin = 0.0;
    *tmax = INFINITY;
    switch (kind) {
    case 0:
        *ray = random_ray_near(rng, &m->bounds);
        random_interval(rng, tmin, tmax);
        return;
    case 1: { /* at a vertex */
        const uint32_t v = (uint32_t)(rng_next(rng) % m->vertex_count);
        const hr_vec3 o = far_point(rng, &m->bounds);
        ray->origin = o;
        ray->dir = sub(m->vertices[v], o);
        *tmax = end_near_one(rng);
        return;
    }
    case 2: { /* at an edge */
        tri = (uint32_t)(rng_next(rng) % m->triangle_count);
        const int k = (int)(rng_next(rng) % 3);
        const double s = (rng_next(rng) & 1) ? 0.5 : rng_uniform(rng, 0.0, 1.0);
        const hr_vec3 p = lerp(vertex_of(m, tri, k), vertex_of(m, tri, (k + 1) % 3), s);
        const hr_vec3 o = far_point(rng, &m->bounds);
        ray->origin = o;
        ray->dir = sub(p, o);
        *tmax = end_near_one(rng);
        return;
    }
    case 3: { /* a shadow ray */
        const hr_vec3 p = point_on(rng, m, &tri);
        const hr_vec3 light = far_point(rng, &m->bounds);
        ray->origin = p;
        ray->dir = sub(light, p);
        *tmin = start_near_zero(rng);
        *tmax = (rng_next(rng) & 1) ? 1.0 : INFINITY;
        return;
    }
    case 4: { /* grazing: along a face through a point of its edge */
        tri = (uint32_t)(rng_next(rng) % m->triangle_count);
        const hr_vec3 a = vertex_of(m, tri, 0), b = vertex_of(m, tri, 1), c = vertex_of(m, tri, 2);
        const hr_vec3 e1 = sub(b, a), e2 = sub(c, a);
        const hr_vec3 n = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
        const hr_vec3 p = lerp(a, b, rng_uniform(rng, 0.0, 1.0));
        const double u = rng_uniform(rng, -1.0, 1.0), w = rng_uniform(rng, -1.0, 1.0);
        static const double offs[] = {0.0, 1e-15, -1e-15, 1e-9, -1e-9};
        const double off = offs[rng_next(rng) % 5];
        ray->dir = harness_vec(u * e1.x + w * e2.x + off * n.x, u * e1.y + w * e2.y + off * n.y,
                               u * e1.z + w * e2.z + off * n.z);
        ray->origin = harness_vec(p.x - 3.0 * ray->dir.x, p.y - 3.0 * ray->dir.y, p.z - 3.0 * ray->dir.z);
        *tmax = (rng_next(rng) & 1) ? 3.0 : INFINITY;
        return;
    }
    case 5: { /* along an edge, from before it */
        tri = (uint32_t)(rng_next(rng) % m->triangle_count);
        const int k = (int)(rng_next(rng) % 3);
        const hr_vec3 a = vertex_of(m, tri, k), b = vertex_of(m, tri, (k + 1) % 3);
        ray->dir = sub(b, a);
        ray->origin = lerp(a, b, -rng_uniform(rng, 0.5, 3.0));
        *tmax = (rng_next(rng) & 1) ? end_near_one(rng) : INFINITY;
        return;
    }
    case 6: { /* at a point of a triangle, from just before it */
        const hr_vec3 p = point_on(rng, m, &tri);
        const hr_vec3 o = far_point(rng, &m->bounds);
        static const double starts[] = {1.0 - 1e-9, 1.0 - 1e-15, 1.0 - 0x1p-53, 1.0, 1.0 + 0x1p-52};
        ray->origin = o;
        ray->dir = sub(p, o);
        *tmin = starts[rng_next(rng) % 5];
        return;
    }
    default: { /* from a vertex */
        const uint32_t v = (uint32_t)(rng_next(rng) % m->vertex_count);
        ray->origin = m->vertices[v];
        ray->dir = rng_unit_vector(rng);
        *tmin = start_near_zero(rng);
        return;
    }
    }
}

static void check_mesh(const char *what, const harness_shape *s, uint64_t seed)
{
    const mesh *m = s->shape;
    /* Closed: the any-hit search's early stop applies. */
    CHECK_MSG(m->closed, "%s: not closed", what);
    if (!m->closed) return;
    ray_rng rng;
    rng_seed(&rng, seed);
    hr_hit any[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS], all[HARNESS_MAX_HITS], line[HARNESS_MAX_HITS];
    long blocked = 0, mismatches = 0, first_mismatches = 0, unbalanced = 0;
    long unalternating[RAY_KINDS] = {0};
    for (long i = 0; i < RAYS_PER_MESH; i++) {
        hr_ray ray;
        double tmin, tmax;
        make_ray(&rng, m, (int)(i % RAY_KINDS), &ray, &tmin, &tmax);
        const int n_any = harness_trace(s, ray, tmin, tmax, HARNESS_ANY, any);
        const int n_first = harness_trace(s, ray, tmin, tmax, HARNESS_FIRST, first);
        blocked += n_any > 0;
        /* first_hit is the all-hits list's first, on every ray. */
        const int n_all = harness_all_hits_as_listed(s, ray, tmin, tmax, all);
        if (((n_all > 0) != (n_first > 0) ||
             (n_all > 0 && (all[0].t != first[0].t || all[0].entering != first[0].entering))) &&
            ++first_mismatches <= 5)
            CHECK_MSG(0, "%s: ray %ld (kind %ld) o=(%a, %a, %a) d=(%a, %a, %a) (%a, %a): %d hits, the first at %a "
                         "entering %d; first_hit %d at %a entering %d",
                      what, i, i % RAY_KINDS, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y,
                      ray.dir.z, tmin, tmax, n_all, n_all ? all[0].t : 0.0, n_all ? (int)all[0].entering : -1,
                      n_first, n_first ? first[0].t : 0.0, n_first ? (int)first[0].entering : -1);
        /* Over the whole line the flags balance; where they do not
         * alternate is counted (docs/limits.md: a ray in a face's plane). */
        const int n_line = harness_all_hits_as_listed(s, ray, -INFINITY, INFINITY, line);
        int entering = 0, alternates = 1;
        for (int k = 0; k < n_line; k++) {
            entering += line[k].entering;
            if (line[k].entering != !(k & 1)) alternates = 0;
        }
        unbalanced += 2 * entering != n_line;
        unalternating[i % RAY_KINDS] += !alternates;
        if ((n_any > 0) != (n_first > 0) && ++mismatches <= 5)
            CHECK_MSG(0,
                      "%s: ray %ld (kind %ld) o=(%a, %a, %a) d=(%a, %a, %a) (%a, %a): any-hit %d, "
                      "first-hit %d",
                      what, i, i % RAY_KINDS, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y,
                      ray.dir.z, tmin, tmax, n_any, n_first);
    }
    CHECK_MSG(mismatches == 0, "%s: %ld of %d rays disagree", what, mismatches, RAYS_PER_MESH);
    CHECK_MSG(first_mismatches == 0, "%s: on %ld of %d rays first_hit is not the all-hits list's first", what,
              first_mismatches, RAYS_PER_MESH);
    CHECK_MSG(unbalanced == 0, "%s: on %ld of %d rays the whole line's flags do not balance", what, unbalanced,
              RAYS_PER_MESH);
    printf("%s: whole-line lists that do not alternate, by kind of ray:", what);
    for (int k = 0; k < RAY_KINDS; k++) printf(" %ld", unalternating[k]);
    printf("\n");
    /* Both answers occur often (a test that can fail either way). */
    CHECK_MSG(blocked > RAYS_PER_MESH / 10 && blocked < RAYS_PER_MESH - RAYS_PER_MESH / 10,
              "%s: %ld of %d rays blocked", what, blocked, RAYS_PER_MESH);
    printf("%s: %u triangles, %ld of %d rays blocked, answers agree\n", what, m->triangle_count,
           blocked, RAYS_PER_MESH);
}

static void check_solid(const char *name, uint64_t seed)
{
    harness_shape s;
    if (!harness_open(&s, "mesh", name, NAN)) return;
    check_mesh(name, &s, seed);
    harness_close(&s);
}

static void check_file(const char *what, const char *path, uint64_t seed)
{
    harness_shape s;
    if (!mesh_open_file(&s, path)) return;
    check_mesh(what, &s, seed);
    harness_close(&s);
}

/* A gear of `teeth` teeth: its outline at radii 1 (roots) and 1.25 (tips),
 * four points a tooth, extruded from z = -0.2 to 0.2; the faces fanned from
 * their centres (the outline is star-shaped about it), the sides as quads. */
static int write_gear(const char *path, int teeth)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return 0;
    const int n = 4 * teeth;
    for (int side = 0; side < 2; side++) {
        const double z = side ? 0.2 : -0.2;
        for (int i = 0; i < n; i++) {
            const double a = 2.0 * HR_PI * i / n, r = (i % 4 == 1 || i % 4 == 2) ? 1.25 : 1.0;
            fprintf(f, "v %.17g %.17g %.17g\n", r * cos(a), r * sin(a), z);
        }
        fprintf(f, "v 0 0 %.17g\n", z);
    }
    /* Vertices: bottom ring 1..n, bottom centre n+1, top ring n+2..2n+1, top centre 2n+2. */
    for (int i = 0; i < n; i++) {
        const int j = (i + 1) % n;
        fprintf(f, "f %d %d %d\n", n + 1, j + 1, i + 1);                   /* bottom, facing -z */
        fprintf(f, "f %d %d %d\n", 2 * n + 2, n + 2 + i, n + 2 + j);       /* top, facing +z */
        fprintf(f, "f %d %d %d %d\n", i + 1, j + 1, n + 2 + j, n + 2 + i); /* side, outwards */
    }
    return fclose(f) == 0;
}

/* The Sierpinski tetrahedron of `depth` levels: 4^depth tetrahedra, each
 * wound outwards, meeting their neighbours at corners only. */
static void sierpinski(FILE *f, const hr_vec3 c[4], int depth, int *next_vertex)
{
    if (depth == 0) {
        for (int k = 0; k < 4; k++) fprintf(f, "v %.17g %.17g %.17g\n", c[k].x, c[k].y, c[k].z);
        const int v = *next_vertex;
        /* Corners (1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1) scaled: these faces face out. */
        fprintf(f, "f %d %d %d\nf %d %d %d\nf %d %d %d\nf %d %d %d\n", v, v + 3, v + 1, v, v + 1, v + 2, v,
                v + 2, v + 3, v + 1, v + 3, v + 2);
        *next_vertex += 4;
        return;
    }
    for (int k = 0; k < 4; k++) {
        hr_vec3 sub_c[4];
        for (int j = 0; j < 4; j++) sub_c[j] = lerp(c[k], c[j], 0.5);
        sierpinski(f, sub_c, depth - 1, next_vertex);
    }
}

static int write_sierpinski(const char *path, int depth)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return 0;
    const hr_vec3 c[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    int next_vertex = 1;
    sierpinski(f, c, depth, &next_vertex);
    return fclose(f) == 0;
}

static int write_touching_cubes(const char *path)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return 0;
    for (int c = 0; c < 2; c++) {
        const double x0 = c ? 0.5 : 0.0, y0 = c ? 0.25 : 0.0, z0 = c ? 1.0 : 0.0;
        for (int k = 0; k < 8; k++)
            fprintf(f, "v %.17g %.17g %.17g\n", x0 + (k & 1), y0 + ((k >> 1) & 1), z0 + ((k >> 2) & 1));
        const int v = 8 * c + 1;
        /* Corner k at (k & 1, k >> 1 & 1, k >> 2 & 1); each face
         * counter-clockwise seen from outside. */
        static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                        {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (int k = 0; k < 6; k++)
            fprintf(f, "f %d %d %d %d\n", v + faces[k][0], v + faces[k][1], v + faces[k][2],
                    v + faces[k][3]);
    }
    return fclose(f) == 0;
}

/* A unit cube whose edge from (0, 0, 1) to (1, 0, 1) is notched: the top
 * face fanned from M = (0.5, 1e-6, 1 - 1e-6), just inside the edge, and a
 * sliver (0, 0, 1), (1, 0, 1), M (its angle at the edge's ends 2.8e-6
 * rad) closing the notch. Rays through the sliver, or grazing it, meet it
 * nearly edge on from every side: t errors far beyond the points'. (With
 * closed_any_blocks' reach left without the hit's own t error, or without
 * its check at tmax, some of its rays disagree.) */
static int write_notched_cube(const char *path)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return 0;
    for (int k = 0; k < 8; k++) fprintf(f, "v %d %d %d\n", k & 1, (k >> 1) & 1, (k >> 2) & 1);
    fprintf(f, "v 0.5 1e-6 0.999999\n");
    /* Corner k (1-based k + 1) at (k & 1, k >> 1 & 1, k >> 2 & 1), M = 9;
     * counter-clockwise seen from outside; the top (4, 5, 7, 6) as a fan
     * from M, and the sliver on the edge 4 -> 5 that the front face runs
     * 5 -> 4. */
    fputs("f 1 3 4 2\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n"
          "f 9 6 8\nf 9 8 7\nf 9 7 5\nf 5 6 9\n",
          f);
    return fclose(f) == 0;
}

int main(void)
{
    check_solid("tetrahedron", 1);
    check_solid("octahedron", 2);
    check_solid("dodecahedron", 3);
    check_solid("icosahedron", 4);
    check_solid("buckyball", 5);
    char path[512];
    check_file("cube.obj", mesh_data_path("cube.obj", path, sizeof path), 6);
    if (write_gear(mesh_build_path("any_hit_gear.obj", path, sizeof path), 24))
        check_file("gear", path, 7);
    if (write_sierpinski(mesh_build_path("any_hit_sierpinski.obj", path, sizeof path), 2))
        check_file("sierpinski", path, 8);
    if (write_touching_cubes(mesh_build_path("any_hit_touching_cubes.obj", path, sizeof path)))
        check_file("touching cubes", path, 9);
    if (write_notched_cube(mesh_build_path("any_hit_notched_cube.obj", path, sizeof path)))
        check_file("notched cube", path, 10);
    return hr_test_end();
}
