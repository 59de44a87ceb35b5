/* The `buckyball` class of the mesh module, the truncated icosahedron: 60
 * vertices on the unit sphere; its triangles gathered back into their
 * faces, 12 pentagons and 20 hexagons; the 90 edges of those faces all of
 * the length a long-double reference gives; Euler's V - E + F = 2; closed,
 * and every ray through the centre crosses it twice, between the inscribed
 * and the circumscribed sphere. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../../shapes/mesh/mesh.h"
#include "hr_test.h"
#include "module_harness.h"

#define HR_PI 3.14159265358979323846
#include "random_rays.h"

#define MAX_FACES 64
#define MAX_EDGES 256

static hr_vec3 unit_normal(const mesh *m, uint32_t t)
{
    const uint32_t *c = m->corners + 3 * (size_t)t;
    const hr_vec3 a = m->vertices[c[0]], b = m->vertices[c[1]], d = m->vertices[c[2]];
    const double e1[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, e2[3] = {d.x - a.x, d.y - a.y, d.z - a.z};
    hr_vec3 n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
    const double len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    return harness_vec(n.x / len, n.y / len, n.z / len);
}

/* Triangles of one face share its plane: their unit normals agree to a few
 * roundings (1e-15), while those of neighbouring faces differ by the
 * dihedral angle's 0.36 rad or more. */
static int same_plane(hr_vec3 a, hr_vec3 b)
{
    return fabs(a.x - b.x) < 1e-9 && fabs(a.y - b.y) < 1e-9 && fabs(a.z - b.z) < 1e-9;
}

typedef struct face {
    hr_vec3 normal;
    uint32_t vertices[8];
    int vertex_count;
    int triangle_count;
} face;

static void add_vertex(face *f, uint32_t v)
{
    for (int i = 0; i < f->vertex_count; i++)
        if (f->vertices[i] == v) return;
    if (f->vertex_count < 8) f->vertices[f->vertex_count] = v;
    f->vertex_count++;
}

int main(void)
{
    harness_shape s;
    if (!harness_open(&s, "mesh", "buckyball", NAN)) return hr_test_end();
    CHECK(s.cls->flags == HR_SHAPE_CLOSED && s.cls->param_count == 0);
    const mesh *m = s.shape;
    CHECK(m->closed);
    CHECK_MSG(m->vertex_count == 60, "%u vertices", m->vertex_count);
    /* A pentagon fans into 3 triangles, a hexagon into 4. */
    CHECK_MSG(m->triangle_count == 12 * 3 + 20 * 4, "%u triangles", m->triangle_count);

    /* The reference: the vertices (0, +-1, +-3 phi) and the rest, edge 2,
     * circumradius sqrt(9 phi + 10), scaled onto the unit sphere. */
    const long double phi = (1 + sqrtl(5.0L)) / 2;
    const long double edge = 2 / sqrtl(9 * phi + 10);
    /* Each coordinate is the written one divided by its length, a few
     * roundings of numbers below 1 (some 4e-16 each); an edge's length, a
     * difference of two such points, is then good to 2e-15. */
    const long double tol = 2e-15L;
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        const hr_vec3 v = m->vertices[i];
        const long double r = sqrtl((long double)v.x * v.x + (long double)v.y * v.y +
                                    (long double)v.z * v.z);
        CHECK_MSG(fabsl(r - 1) <= 1e-15L, "vertex %u at radius %.20Lg", i, r);
    }

    /* Gather the triangles into faces by their planes. */
    face faces[MAX_FACES];
    int face_count = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const hr_vec3 n = unit_normal(m, t);
        int f = 0;
        while (f < face_count && !same_plane(faces[f].normal, n)) f++;
        if (f == face_count) {
            if (face_count == MAX_FACES) break;
            memset(&faces[f], 0, sizeof faces[f]);
            faces[f].normal = n;
            face_count++;
        }
        faces[f].triangle_count++;
        for (int k = 0; k < 3; k++) add_vertex(&faces[f], m->corners[3 * t + k]);
    }
    int pentagons = 0, hexagons = 0;
    for (int f = 0; f < face_count; f++) {
        pentagons += faces[f].vertex_count == 5 && faces[f].triangle_count == 3;
        hexagons += faces[f].vertex_count == 6 && faces[f].triangle_count == 4;
    }
    CHECK_MSG(face_count == 32 && pentagons == 12 && hexagons == 20,
              "%d faces: %d pentagons, %d hexagons", face_count, pentagons, hexagons);

    /* A face's sides are the edges of its triangles used by one triangle of
     * that face only (the fan's diagonals are used by two). Every side is
     * shared by two faces: 90 in all. */
    uint32_t edges[MAX_EDGES][2];
    int edge_count = 0, sides = 0;
    for (int f = 0; f < face_count; f++) {
        for (uint32_t t = 0; t < m->triangle_count; t++) {
            if (!same_plane(faces[f].normal, unit_normal(m, t))) continue;
            for (int k = 0; k < 3; k++) {
                const uint32_t a = m->corners[3 * t + k], b = m->corners[3 * t + (k + 1) % 3];
                int uses = 0;
                for (uint32_t u = 0; u < m->triangle_count; u++) {
                    if (!same_plane(faces[f].normal, unit_normal(m, u))) continue;
                    for (int j = 0; j < 3; j++) {
                        const uint32_t c = m->corners[3 * u + j], d = m->corners[3 * u + (j + 1) % 3];
                        uses += (c == a && d == b) || (c == b && d == a);
                    }
                }
                if (uses != 1) continue;
                sides++;
                const hr_vec3 p = m->vertices[a], q = m->vertices[b];
                const long double dx = (long double)p.x - q.x, dy = (long double)p.y - q.y,
                                  dz = (long double)p.z - q.z;
                const long double len = sqrtl(dx * dx + dy * dy + dz * dz);
                CHECK_MSG(fabsl(len - edge) <= tol, "side %u-%u is %.20Lg, expected %.20Lg", a, b,
                          len, edge);
                int known = 0;
                for (int e = 0; e < edge_count && !known; e++)
                    known = (edges[e][0] == a && edges[e][1] == b) ||
                            (edges[e][0] == b && edges[e][1] == a);
                if (!known && edge_count < MAX_EDGES) {
                    edges[edge_count][0] = a, edges[edge_count][1] = b;
                    edge_count++;
                }
            }
        }
    }
    CHECK_MSG(sides == 180 && edge_count == 90, "%d sides, %d edges", sides, edge_count);
    CHECK(60 - edge_count + face_count == 2);

    /* Rays through the centre from random directions cross twice, between
     * the inscribed sphere of the hexagons (the nearest faces: the centre of
     * a hexagon of side e is at sqrt(1 - e^2)) and the unit sphere. */
    const double inner = (double)sqrtl(1 - edge * edge);
    ray_rng rng;
    rng_seed(&rng, 60);
    for (int i = 0; i < 2000; i++) {
        const double z = rng_uniform(&rng, -1, 1), a = rng_uniform(&rng, 0, 2 * HR_PI);
        const double r = sqrt(1 - z * z);
        const hr_vec3 d = {r * cos(a), r * sin(a), z};
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(&s, harness_ray(-3 * d.x, -3 * d.y, -3 * d.z, d.x, d.y, d.z), h);
        CHECK(n == 2);
        if (n != 2) continue;
        CHECK(h[0].entering && !h[1].entering);
        for (int k = 0; k < 2; k++) {
            const double dist = fabs(h[k].t - 3);
            CHECK_MSG(dist >= inner - 1e-12 && dist <= 1 + 1e-12, "a crossing at %.17g", dist);
        }
    }
    harness_close(&s);
    return hr_test_end();
}
