/* A mesh's first hit is the first of its all-hits list even where the
 * rounding of the crossings' t (the triangle test's t error bound) is far
 * larger than their spacing: rays nearly along faces far from the origin
 * (shapes/mesh/mesh_trace.c). Two meshes fuzzing found:
 * - closed: twelve triangles, two vertices at -6.7e15 and the rest within
 *   20 of the origin, seen from 1e16 away along a line through a vertex.
 *   The line crosses four faces at t = 1 + 3.6e-17 .. 5.4e-17 (exactly,
 *   in rational arithmetic), entering first; their computed t lie 0.994 ..
 *   1.009 with t errors of 2 to 13. The all-hits list, sorted by computed
 *   t, began with a leaving crossing and its repair (alternate_closed)
 *   looked only within the points' error bounds (1e-15 in t), while the
 *   first-hit search, pruning by the boxes of the exact crossings, gave an
 *   entering one;
 * - open: the triangles of two copies of a concave NFF polygon with a
 *   vertex at z = -3e14 (and of other polygons), seen from 3e14 away. The crossing with the least computed t
 *   (also the first exactly, t = 1 - 8.4e-15) lay in a box past the first
 *   crossing the walk met (computed t 2e-4 later, t error 0.56), and the
 *   first-hit search pruned it.
 * Checked: first_hit's t and entering flag are those of all hits' first
 * (over the whole line for the closed mesh, from 0 for the open one), and
 * the closed mesh's list is entered first. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"

static const char closed_obj[] =
    "v -1 1 -3\n"
    "v -6666666666633330 -1 -0\n"
    "v -0 1 -1\n"
    "v -6666666663533302 -1 -0\n"
    "v 1 -1 1\n"
    "v -1 19 -2\n"
    "v -2 -21 1\n"
    "v 1 -1 3\n"
    "v 1 1 1\n"
    "v -1 1 1\n"
    "f 1 2 6\n"
    "f 2 7 6\n"
    "f 2 3 7\n"
    "f 4 7 3\n"
    "f 4 8 7\n"
    "f 1 8 4\n"
    "f 1 4 3\n"
    "f 1 3 2\n"
    "f 1 5 8\n"
    "f 1 6 5\n"
    "f 5 7 8\n"
    "f 5 6 7\n";

/* The open mesh: four 12-gons (as OBJ vertices 1-12, 13-24, 25-36,
 * 37-48) sharing their first ten corners, two tails taking turns, and the
 * triangles the NFF reader cut them into, in the BVH's order. */
static const char *const polygon_corners[10] = {
    "6 3 -4", "12 3 -4", "12 3 -2", "16 4 -2", "11 3 -304444444444444",
    "20 3 -3", "10 3 -2", "8 3 -2", "8 3 -3", "7 1 -3",
};
static const char *const polygon_tails[2][2] = {
    {"7 3 3", "20 0.40000000000000002 1.5"},
    {"7 3 -10", "1.0049999999999999 0.25 1"},
};
static const char open_faces[] =
    "f 41 48 40\n"
    "f 41 47 48\n"
    "f 17 23 24\n"
    "f 17 24 16\n"
    "f 34 35 29\n"
    "f 10 11 5\n"
    "f 11 12 5\n"
    "f 36 28 29\n"
    "f 29 30 34\n"
    "f 35 36 29\n"
    "f 12 4 5\n"
    "f 17 18 23\n"
    "f 41 42 47\n"
    "f 5 6 10\n"
    "f 21 22 23\n"
    "f 45 46 47\n"
    "f 43 45 47\n"
    "f 19 21 23\n"
    "f 42 43 47\n"
    "f 18 19 23\n"
    "f 37 38 39\n"
    "f 1 2 3\n"
    "f 25 26 27\n"
    "f 13 14 15\n"
    "f 31 32 33\n"
    "f 43 44 45\n"
    "f 19 20 21\n"
    "f 7 8 9\n"
    "f 30 31 33\n"
    "f 6 7 9\n"
    "f 12 3 4\n"
    "f 12 1 3\n"
    "f 36 27 28\n"
    "f 48 37 39\n"
    "f 48 39 40\n"
    "f 36 25 27\n"
    "f 24 15 16\n"
    "f 24 13 15\n";;

static int write_open(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) return 0;
    for (int polygon = 0; polygon < 4; polygon++) {
        for (int k = 0; k < 10; k++) fprintf(f, "v %s\n", polygon_corners[k]);
        for (int k = 0; k < 2; k++) fprintf(f, "v %s\n", polygon_tails[polygon % 2][k]);
    }
    fputs(open_faces, f);
    return fclose(f) == 0;
}

static int write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) return 0;
    fputs(text, f);
    return fclose(f) == 0;
}

static int write_closed(const char *path)
{
    return write_file(path, closed_obj);
}

static void check_first_of_all(const char *name, int (*write)(const char *), hr_ray ray, double tmin, int closed,
                              int crossings)
{
    char path[1024];
    mesh_build_path(name, path, sizeof path);
    CHECK(write(path));
    harness_shape shape;
    if (!mesh_open_file(&shape, path)) {
        CHECK_MSG(0, "%s: not opened", name);
        return;
    }
    hr_hit all[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS];
    const int n_all = harness_trace(&shape, ray, tmin, INFINITY, HARNESS_ALL, all);
    const int n_first = harness_trace(&shape, ray, tmin, INFINITY, HARNESS_FIRST, first);
    CHECK_MSG(n_all == crossings && n_first == 1, "%s: %d hits, %d first hits", name, n_all, n_first);
    if (n_all > 0 && n_first == 1) {
        CHECK_MSG(first[0].t == all[0].t && first[0].entering == all[0].entering,
                  "%s: first hit t %a entering %d, all hits' first t %a entering %d", name, first[0].t,
                  (int)first[0].entering, all[0].t, (int)all[0].entering);
        if (closed) CHECK_MSG(all[0].entering, "%s: the whole line's first crossing leaves", name);
    }
    harness_close(&shape);
}

int main(void)
{
    check_first_of_all("t_error_order_closed.obj", write_closed,
                       harness_ray(0x1.1c37937e01e58p+53, 0x1.1c37937e01e56p+53, 0x1.d9b1f5d203291p+52,
                                   -0x1.7af4c4a802874p+53, -0x1.1c37937e01e56p+53, -0x1.d9b1f5d203291p+52),
                       -INFINITY, 1, 4);
    check_first_of_all("t_error_order_open.obj", write_open,
                       harness_ray(0x1.ce01a1a68e417p+46, 0x1.29010c7d5b5dcp+47, 0x1.7f1e55adc3e8ep+47,
                                   -0x1.ce01a1a68e1aep+46, -0x1.29010c7d5b5a8p+47, -0x1.fc1047ef2d04dp+47),
                       0.0, 0, 8);
    return hr_test_end();
}
