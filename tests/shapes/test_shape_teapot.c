/* The `teapot` class of the mesh module: Newell's patches tessellated at
 * load. At several tessellations: the triangle count 64 n^2 - 8 n; a unit,
 * finite normal at every vertex, on the outer side of every triangle it
 * shades; the welded mesh's edges (16 n used once, at the rim, the lid, and
 * the ends of handle and spout, every other one once each way, so no crack
 * between patches); the bounds against the extent of the patch data; rays
 * from outside entering the body and the knob, with the pole's normal
 * straight up; and the parameter's errors. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../shapes/mesh/mesh.h"
#include "hr_test.h"
#include "module_harness.h"

#define HR_PI 3.14159265358979323846

static double dot(hr_vec3 a, hr_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static hr_vec3 sub(hr_vec3 a, hr_vec3 b)
{
    return harness_vec(a.x - b.x, a.y - b.y, a.z - b.z);
}

static hr_vec3 cross(hr_vec3 a, hr_vec3 b)
{
    return harness_vec(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

static int open_teapot(const harness_module *module, const hr_shape_class *cls, double level,
                       harness_shape *out)
{
    char error[256] = "";
    const char *name = "tessellation";
    void *shape = NULL;
    hr_status st = harness_create(cls, &name, &level, 1, &shape, error, sizeof error);
    CHECK_MSG(st == HR_OK, "tessellation %g: %s", level, error);
    if (st) return 0;
    out->module = *module;
    out->cls = cls;
    out->shape = shape;
    return 1;
}

/* --- Welding and edges --------------------------------------------------- */

static const hr_vec3 *sort_points;

static int by_position(const void *pa, const void *pb)
{
    const hr_vec3 *a = &sort_points[*(const uint32_t *)pa], *b = &sort_points[*(const uint32_t *)pb];
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    if (a->z != b->z) return a->z < b->z ? -1 : 1;
    return 0;
}

static int by_edge(const void *pa, const void *pb)
{
    const uint64_t a = *(const uint64_t *)pa, b = *(const uint64_t *)pb;
    return a < b ? -1 : a > b;
}

/* The directed edges of the mesh with vertices welded by exact position:
 * how many have no reverse (*once), and whether any comes twice. */
static void count_edges(const mesh *m, size_t *once, size_t *twice)
{
    uint32_t *order = malloc(m->vertex_count * sizeof *order);
    uint32_t *weld = malloc(m->vertex_count * sizeof *weld);
    const size_t n = 3 * (size_t)m->triangle_count;
    uint64_t *edges = malloc(n * sizeof *edges);
    CHECK(order && weld && edges);
    *once = *twice = 0;
    if (order && weld && edges) {
        for (uint32_t i = 0; i < m->vertex_count; i++) order[i] = i;
        sort_points = m->vertices;
        qsort(order, m->vertex_count, sizeof *order, by_position);
        for (uint32_t i = 0; i < m->vertex_count; i++)
            weld[order[i]] = i > 0 && by_position(&order[i], &order[i - 1]) == 0
                                 ? weld[order[i - 1]]
                                 : order[i];
        for (size_t t = 0; t < m->triangle_count; t++)
            for (int k = 0; k < 3; k++)
                edges[3 * t + k] = (uint64_t)weld[m->corners[3 * t + k]] << 32 |
                                   weld[m->corners[3 * t + (k + 1) % 3]];
        qsort(edges, n, sizeof *edges, by_edge);
        for (size_t i = 0; i < n; i++) {
            if (i + 1 < n && edges[i + 1] == edges[i]) ++*twice;
            const uint64_t reverse = edges[i] << 32 | edges[i] >> 32;
            if (!bsearch(&reverse, edges, n, sizeof *edges, by_edge)) ++*once;
        }
    }
    free(order);
    free(weld);
    free(edges);
}

/* --- The mesh at one tessellation ------------------------------------------ */

static void check_mesh(const mesh *m, uint32_t level)
{
    CHECK_MSG(m->triangle_count == 64 * level * level - 8 * level,
              "tessellation %u: %u triangles, expected %u", level, m->triangle_count,
              64 * level * level - 8 * level);
    CHECK(m->vertex_count == 32 * (level + 1) * (level + 1));
    CHECK(!m->closed);
    /* Every vertex has its normal, a unit vector (stored normalised: 1
     * within a few roundings of the division and the square root). */
    CHECK(m->corner_normals && m->normal_count == m->vertex_count);
    if (!m->corner_normals) return;
    for (uint32_t i = 0; i < m->normal_count; i++) {
        const hr_vec3 n = m->normals[i];
        CHECK_MSG(isfinite(n.x) && isfinite(n.y) && isfinite(n.z) && fabs(dot(n, n) - 1) < 1e-15,
                  "normal %u is (%g %g %g)", i, n.x, n.y, n.z);
    }
    /* Each corner's normal is on the outer side of its triangle (the side of
     * (B - A) x (C - A)): the derivatives and the winding agree, so no
     * shading normal is flipped at any hit. From 6 steps on (mesh_teapot.h:
     * below, the spout's lip and the knob turn by about 90 degrees within a
     * step, and a few corners are past it). */
    int corners_without = 0, against = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *c = m->corners + 3 * (size_t)t, *cn = m->corner_normals + 3 * (size_t)t;
        const hr_vec3 g = cross(sub(m->vertices[c[1]], m->vertices[c[0]]),
                                sub(m->vertices[c[2]], m->vertices[c[0]]));
        /* No sliver: the pole's are skipped, every other has area. */
    CHECK(dot(g, g) > 0);
        for (int k = 0; k < 3; k++) {
            if (cn[k] == MESH_NO_NORMAL) {
                corners_without++;
                continue;
            }
            against += dot(m->normals[cn[k]], g) <= 0;
        }
    }
    CHECK_MSG(corners_without == 0, "tessellation %u: %d corners without a normal", level,
              corners_without);
    CHECK_MSG(level < 6 || against == 0, "tessellation %u: %d corner normals against their triangle",
              level, against);
    /* What the mesh keeps: per triangle 24 bytes of vertex and normal
     * indices; (n+1)^2 vertices and as many normals a patch, 24 bytes each,
     * some half of each a triangle; the BVH's nodes, some 11 bytes a
     * triangle (mesh.h). About 60 bytes a triangle: under 80 at any level. */
    const size_t kept = sizeof *m + 24 * ((size_t)m->vertex_count + m->normal_count) +
                        24 * (size_t)m->triangle_count +
                        (size_t)m->bvh.node_count * sizeof(accel_bvh4_node);
    printf("teapot at tessellation %u: %u triangles, %zu bytes kept (%.1f a triangle)\n", level,
           m->triangle_count, kept, (double)kept / m->triangle_count);
    CHECK(level < 6 || (double)kept / m->triangle_count < 80);
    /* The finest level is checked for its counts, normals and bounds; its
     * million triangles' edges would take the sanitizer builds long. */
    if (level > 40) return;
    size_t once, twice;
    count_edges(m, &once, &twice);
    CHECK_MSG(once == 16 * (size_t)level && twice == 0,
              "tessellation %u: %zu edges without a reverse (expected %u), %zu used twice one way",
              level, once, 16 * level, twice);
}

/* The spout's lip: the cubic in Newell's x through 3.3, 3.525, 3.45, 3.2
 * (the spout's outer column of control points, at y = 0) is the teapot's
 * furthest reach in +x; every row of the spout's patches grows in x along u
 * towards that column, so no other point of the surface reaches as far.
 * Its maximum, where the derivative's quadratic vanishes, in long double. */
static long double spout_reach(void)
{
    const long double p[4] = {3.3L, 3.525L, 3.45L, 3.2L};
    /* x'(t) / 3 = a (1-t)^2 + 2 b t (1-t) + c t^2, a, b, c the differences */
    const long double a = p[1] - p[0], b = p[2] - p[1], c = p[3] - p[2];
    const long double qa = a - 2 * b + c, qb = 2 * (b - a), qc = a;
    const long double t = (-qb - sqrtl(qb * qb - 4 * qa * qc)) / (2 * qa);
    CHECK(t > 0 && t < 1);
    const long double r = 1 - t;
    return r * r * r * p[0] + 3 * r * r * t * p[1] + 3 * r * t * t * p[2] + t * t * t * p[3];
}

/* Bounds: exact where the extreme is a corner of a patch (a vertex at every
 * tessellation): the handle's back at Newell's x = -3, the bottom's centre
 * at z = 0, the knob's top at z = 3.15 and the body at y = -+2, placed as
 * glutSolidTeapot places them (x/2, z/2 - 3/4, -y/2). The spout's reach is
 * inside a patch: the vertices nearest it are at most h/2 from it in the
 * curve's parameter (h = 1/n), so they fall short by at most
 * max|x''| h^2 / 8 (x' vanishes there), x'' = 6 (p2 - 2 p1 + p0) or
 * 6 (p3 - 2 p2 + p1) at the ends, its largest values; halved by the
 * placement. */
static void check_bounds(const harness_shape *s, uint32_t level)
{
    hr_bounds b;
    s->cls->bounds(s->shape, &b);
    CHECK_MSG(b.lo.x == -1.5 && b.lo.y == -0.75 && b.hi.y == 0.5 * 3.15 - 0.75 && b.lo.z == -1.0 &&
                  b.hi.z == 1.0,
              "tessellation %u: bounds (%.17g %.17g %.17g) .. (%.17g %.17g %.17g)", level, b.lo.x,
              b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
    const long double reach = 0.5L * spout_reach();
    const double curvature = 6 * fmax(fabs(3.45 - 2 * 3.525 + 3.3), fabs(3.2 - 2 * 3.45 + 3.525));
    const double h = 1.0 / level, short_by = 0.5 * curvature * h * h / 8;
    CHECK_MSG(b.hi.x <= reach + 1e-15L && b.hi.x >= reach - short_by - 1e-15L,
              "tessellation %u: reaches x = %.17g, the spout's lip %.17Lg (may fall short by %g)",
              level, b.hi.x, reach, short_by);
}

/* Rays from outside: horizontal ones at the body's widest, from the front
 * and the back (+-z, away from handle and spout), enter within the
 * tessellation's sagitta of radius 1 with a normal facing them; one down
 * the axis enters at the knob's top pole, its normal straight up (the
 * limit the derivatives give there). */
static void check_rays(const harness_shape *s, uint32_t level)
{
    const double y = 0.5 * 0.9 - 0.75; /* Newell's z = 0.9: radius 2 all round */
    const double sag = 1 - cos(HR_PI / (4.0 * level)) + 0.01; /* 0.01: the 45-degree bulge */
    for (int k = 0; k < 16; k++) {
        const double a = HR_PI / 4 + k * (HR_PI / 2) / 15; /* from +z round to -x's side */
        for (int side = 0; side < 2; side++) {
            const double dx = side ? -cos(a) : cos(a), dz = side ? sin(a) : -sin(a);
            const hr_ray ray = harness_ray(-5 * dx, y, -5 * dz, dx, 0, dz);
            hr_hit h[HARNESS_MAX_HITS];
            const int n = harness_trace(s, ray, 0, INFINITY, HARNESS_FIRST, h);
            CHECK(n == 1);
            if (n != 1) continue;
            CHECK(h[0].entering);
            CHECK(dot(h[0].normal, ray.dir) < 0);
            const double r = hypot(h[0].point.x, h[0].point.z);
            CHECK_MSG(r <= 1 + 0.01 && r >= 1 - sag, "tessellation %u: the body at radius %.17g",
                      level, r);
        }
    }
    hr_hit h[HARNESS_MAX_HITS];
    const int n = harness_trace(s, harness_ray(0, 3, 0, 0, -1, 0), 0, INFINITY, HARNESS_FIRST, h);
    CHECK(n == 1);
    if (n == 1) {
        CHECK(h[0].entering);
        CHECK_MSG(fabs(h[0].point.y - (0.5 * 3.15 - 0.75)) <= 1e-15, "knob top at %.17g",
                  h[0].point.y);
        const double len = sqrt(dot(h[0].normal, h[0].normal));
        CHECK_MSG(h[0].normal.y / len > 1 - 1e-12, "knob normal (%g %g %g)", h[0].normal.x,
                  h[0].normal.y, h[0].normal.z);
    }
    /* And up through the bottom's centre: leaving is not what a ray from
     * below does; it enters, the normal straight down. */
    const int m = harness_trace(s, harness_ray(0, -3, 0, 0, 1, 0), 0, INFINITY, HARNESS_FIRST, h);
    CHECK(m == 1);
    if (m == 1) {
        CHECK(h[0].entering);
        CHECK(h[0].point.y == -0.75 || fabs(h[0].point.y + 0.75) <= h[0].error);
        const double len = sqrt(dot(h[0].normal, h[0].normal));
        CHECK(h[0].normal.y / len < -(1 - 1e-12));
    }
}

static void check_errors(const hr_shape_class *cls)
{
    const char *name = "tessellation";
    const double bad[] = {2.5, 1, 0, 129, -3, NAN};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char error[256] = "";
        void *shape = NULL;
        hr_status st = harness_create(cls, &name, &bad[i], 1, &shape, error, sizeof error);
        CHECK_MSG(st == HR_ERROR_PARAMETER && shape == NULL, "tessellation %g accepted", bad[i]);
        CHECK_MSG(strstr(error, "parameter 'tessellation'") && strstr(error, "whole number"),
                  "tessellation %g: '%s'", bad[i], error);
        if (shape) cls->destroy(shape);
    }
}

int main(void)
{
    harness_module module;
    if (!harness_load("mesh", &module)) return hr_test_end();
    const hr_shape_class *cls = harness_find_class(&module, "teapot");
    CHECK(cls != NULL);
    if (cls) {
        CHECK(cls->flags == HR_SHAPE_SDL_BARE && cls->param_count == 1);
        CHECK(strcmp(cls->params[0].name, "tessellation") == 0 &&
              cls->params[0].default_number == 12 && cls->params[0].type == HR_PARAM_NUMBER);
        const uint32_t levels[] = {2, 3, 5, 6, 7, 12, 40, 128};
        for (size_t i = 0; i < sizeof levels / sizeof levels[0]; i++) {
            harness_shape s;
            if (!open_teapot(&module, cls, levels[i], &s)) continue;
            check_mesh(s.shape, levels[i]);
            check_bounds(&s, levels[i]);
            if (levels[i] >= 3) check_rays(&s, levels[i]);
            cls->destroy(s.shape);
        }
        check_errors(cls);
    }
    harness_unload(&module);
    return hr_test_end();
}
