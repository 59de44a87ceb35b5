/* The mesh's tie rule (shapes/mesh/mesh_trace.c): at an exact tie in t
 * (and in the entering flag) the triangle with the lower index in the file
 * wins, whatever order the BVH's walk reaches the triangles in. A flat
 * grid of 18 triangles, each written COPIES times, the copies interleaved
 * through the file (copy j of triangle k is face j * 18 + k), every face
 * with its own normal (a tilt of face / 1000 in x) and its own texture
 * coordinate (u = the face's index): coincident triangles that differ only
 * in their per-face data. So many copies of one box cannot share a leaf
 * (at most 8 a leaf), and the walk meets them in several leaves, nearest
 * box first. Random rays from both sides:
 * - the first hit's normal is that of the triangle's first copy;
 * - the all-hits list holds the copies at one t in file order;
 * - the (u, v) at the first hit is the first copy's.
 * Before the rule, the first hit went to whichever copy the walk met
 * first. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"
#include "random_rays.h"

#define GRID 3 /* GRID x GRID squares in the plane z = 0, two triangles each */
#define TRIANGLES (2 * GRID * GRID)
#define COPIES 24

/* The face a normal's tilt names (fill_hit interpolates three equal
 * normals: the tilt comes back within rounding). */
static long face_of_normal(hr_vec3 n)
{
    return n.z != 0.0 ? lround(fabs(n.x / n.z) * 1000.0) : -1;
}

static int write_grid(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) return 0;
    for (int y = 0; y <= GRID; y++)
        for (int x = 0; x <= GRID; x++) fprintf(f, "v %d %d 0\n", x, y);
    const int faces = COPIES * TRIANGLES;
    for (int face = 0; face < faces; face++) {
        fprintf(f, "vn %.17g 0 1\n", (face + 1) / 1000.0);
        fprintf(f, "vt %d 0\n", face + 1);
    }
    for (int copy = 0; copy < COPIES; copy++) {
        for (int k = 0; k < TRIANGLES; k++) {
            const int face = copy * TRIANGLES + k + 1; /* OBJ's indices from 1 */
            const int square = k / 2, sx = square % GRID, sy = square / GRID;
            const int a = sy * (GRID + 1) + sx + 1, b = a + 1, c = a + GRID + 1, d = c + 1;
            if (k % 2 == 0)
                fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a, face, face, b, face, face, d, face, face);
            else
                fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a, face, face, d, face, face, c, face, face);
        }
    }
    return fclose(f) == 0;
}

int main(void)
{
    char path[1024];
    mesh_build_path("mesh_ties.obj", path, sizeof path);
    CHECK(write_grid(path));
    harness_shape grid;
    if (!mesh_open_file(&grid, path)) return hr_test_end() | 1;
    CHECK(grid.cls->surface_uv != NULL);
    hr_intersection list = {NULL, 0, 0};
    CHECK_OK(harness_host()->reserve(NULL, &list, HR_MIN_HIT_CAPACITY));
    ray_rng rng;
    rng_seed(&rng, 26);
    int wrong_first = 0, wrong_order = 0, wrong_uv = 0, hits = 0;
    for (int i = 0; i < 20000; i++) {
        const double side = i % 2 ? -1.0 : 1.0;
        const hr_vec3 target = harness_vec(rng_uniform(&rng, 0.01, GRID - 0.01),
                                           rng_uniform(&rng, 0.01, GRID - 0.01), 0.0);
        const hr_vec3 from = harness_vec(rng_uniform(&rng, -2, GRID + 2), rng_uniform(&rng, -2, GRID + 2),
                                         side * rng_uniform(&rng, 0.5, 4));
        const hr_ray ray = harness_ray(from.x, from.y, from.z, target.x - from.x, target.y - from.y,
                                       target.z - from.z);
        hr_hit first[HARNESS_MAX_HITS];
        if (harness_trace(&grid, ray, 0.0, INFINITY, HARNESS_FIRST, first) != 1) {
            CHECK_MSG(0, "ray %d: no first hit", i);
            continue;
        }
        hits++;
        const long face = face_of_normal(first[0].normal);
        /* Faces 1 .. TRIANGLES are the first copies. */
        if (!(face >= 1 && face <= TRIANGLES) && wrong_first++ < 5)
            CHECK_MSG(0, "ray %d: the first hit is face %ld's, a later copy", i, face);
        double uv[2];
        CHECK(grid.cls->surface_uv(grid.shape, &first[0], uv) == 1);
        if (lround(uv[0]) != face && wrong_uv++ < 5)
            CHECK_MSG(0, "ray %d: (u, v) of face %ld at face %ld's hit", i, lround(uv[0]), face);
        hr_hit_args args;
        memset(&args, 0, sizeof args);
        args.shape = grid.shape;
        args.ray = ray;
        args.tmin = 0.0;
        args.tmax = INFINITY;
        args.out = &list;
        list.count = 0;
        CHECK_OK(grid.cls->hit(&args));
        int ordered = list.count == COPIES;
        for (int k = 0; k < list.count && ordered; k++) {
            ordered = list.hits[k].t == first[0].t &&
                      face_of_normal(list.hits[k].normal) == face + (long)k * TRIANGLES;
        }
        if (!ordered && wrong_order++ < 5)
            CHECK_MSG(0, "ray %d: %d hits, not the copies of face %ld in file order", i, (int)list.count, face);
    }
    CHECK_MSG(wrong_first == 0, "%d of %d first hits on a later copy", wrong_first, hits);
    CHECK_MSG(wrong_order == 0, "%d of %d all-hits lists out of file order", wrong_order, hits);
    CHECK_MSG(wrong_uv == 0, "%d of %d (u, v) from a later copy", wrong_uv, hits);
    free(list.hits);
    harness_close(&grid);
    return hr_test_end();
}
