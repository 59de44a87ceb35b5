/* A closed mesh's first hit is the first of its all-hits list where the
 * list's repair (alternate_closed, shapes/mesh/mesh_trace.c) could move a
 * crossing up from past the caller's tmax onto one inside it, the two
 * lying apart by less than the earlier one's t error bound allows but by
 * more than the points' error bounds. A fuzz input: twelve triangles on a
 * cube's vertices, three of them pulled out to 6.7e14 .. 1.7e30, and the ray
 * from (3.3e14, -4.2e30, 0) along (-3.3e14, 4.2e30, -1) over (0.5, 0.75).
 * In rational arithmetic on the doubles the line leaves a face at
 * t = 0.715909 (computed 0.715835, t error bound 0.084) and enters two
 * faces 0.284 later, at t = 1 - 2.4e-31 (computed 1, t error 2e-15), and
 * leaves a third at t = 1: the line leaves first (the surface passes
 * through itself), which rounding settles (0.284 is past the two bounds).
 * - The list moved the entering crossing up onto the leaving one (its
 *   slack held four times the leaving one's t error bound, 0.335), and
 *   listed first an entering hit at t = 0.715835; the first-hit search,
 *   which looks past the caller's tmax by the points' slack only (1e-15
 *   here), never met the entering one and gave the leaving hit.
 * - With the slack at twice the t error bound (0.168) nothing is moved and
 *   both give the leaving hit, the exact answer (`near_tie_far_ray.obj` below).
 * - With vertex 7 at x = -33 instead of -66 the leaving crossing is
 *   computed at t = 0.7505 with a t error bound of 0.145: 0.25 before the
 *   entering ones, inside twice that bound, and the list moves one up
 *   whatever the slack's factor. The pair lies where the entering
 *   crossings do (their t is the better known), at t = 1, past tmax = 0.8,
 *   so over (0.5, 0.8) the list is empty; the first-hit search, whose best
 *   is the leaving crossing and whose window past it is cut at its end
 *   past tmax, must answer from that list: no hit
 *   (`near_tie_cut_window.obj`).
 * Checked: first_hit's t and entering flag are those of all hits' first
 * over the interval, and for the fuzz input that the hit leaves. */
#include <math.h>
#include <stdio.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"

static const char vertices_head[] = "v 1 -1 -1\n"
                                    "v 2 1 -1\n"
                                    "v -1 2 -1\n"
                                    "v 666666066626666 -1999999999 1\n"
                                    "v 1 2 0\n"
                                    "v 1 2 0\n";
static const char vertices_tail[] = "v 1 -1666666666666666017413150766661 -1\n"
                                    "v 1 -166666666666666601741315071 6666666\n"
                                    "v -1 1 1\n"
                                    "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                    "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

/* The mesh with vertex 7 at (x7, 1.7e29, -1). */
static int write_mesh(const char *path, const char *x7)
{
    FILE *f = fopen(path, "w");
    if (!f) return 0;
    fprintf(f, "%sv %s 16666666666666666666666666661 -1\n%s", vertices_head, x7, vertices_tail);
    return fclose(f) == 0;
}

/* entering: the flag the first hit must have, or -1 for no hit. */
static void check_first_of_all(const char *name, const char *x7, double tmax, int entering)
{
    char path[1024];
    mesh_build_path(name, path, sizeof path);
    CHECK(write_mesh(path, x7));
    harness_shape shape;
    if (!mesh_open_file(&shape, path)) {
        CHECK_MSG(0, "%s: not opened", name);
        return;
    }
    const hr_ray ray = harness_ray(0x1.2f2a250ae414p+48, -0x1.a7400b3526074p+101, 0.0, -0x1.2f2a250ae413p+48,
                                   0x1.a7400b3526074p+101, -1.0);
    hr_hit all[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS];
    const int n_all = harness_trace(&shape, ray, 0.5, tmax, HARNESS_ALL, all);
    const int n_first = harness_trace(&shape, ray, 0.5, tmax, HARNESS_FIRST, first);
    const int expected = entering >= 0;
    CHECK_MSG((n_all >= 1) == expected && n_first == expected, "%s: %d hits, %d first hits", name, n_all,
              n_first);
    if (n_all >= 1 && n_first == 1) {
        CHECK_MSG(first[0].t == all[0].t && first[0].entering == all[0].entering,
                  "%s: first hit t %a entering %d, all hits' first t %a entering %d", name, first[0].t,
                  (int)first[0].entering, all[0].t, (int)all[0].entering);
        if (entering >= 0)
            CHECK_MSG(first[0].entering == entering, "%s: the first hit has entering %d, not %d", name,
                      (int)first[0].entering, entering);
    }
    harness_close(&shape);
}

int main(void)
{
    check_first_of_all("near_tie_far_ray.obj", "-66", 0.75, 0);
    check_first_of_all("near_tie_cut_window.obj", "-33", 0.8, -1);
    return hr_test_end();
}
