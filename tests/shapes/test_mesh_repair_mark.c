/* A closed mesh's all-hits repair (shapes/mesh/mesh_trace.c,
 * alternate_closed) and the caller's interval: a crossing moved up onto the
 * place of one the triangle test refuses only for its t error keeps its own
 * mark, and the pair is kept with it. A fuzz input (a closed .3vn mesh of six
 * quadrilaterals whose corners are a cube's, moved: the surface passes
 * through itself) and the ray (13.5, 8.5, 8) + t (-11.5, -8.5, -8), t in
 * (0, inf). In rational arithmetic on the doubles the line
 * - lies in the plane of triangle (3, 6, 2) from vertex 3 = (2, 0, 0) at
 *   t = 1 to its edge 2-6 at t = 25/23, where it leaves the solid: the
 *   winding number is 0 before t = 1 and -1 on (25/23, 9/8);
 * - enters at t = 9/8 through triangle (0, 1, 5), weights (13/20, 1/16,
 *   23/80), clearly inside it;
 * so the ray meets the mesh twice in (0, inf), both well past tmin. The
 * triangle test (on the sheared, rounded corners) sees triangle (3, 6, 2)
 * at vertex 3, leaving, t = 1 with a t error bound of 9.5, and refuses it
 * for tmin = 0 (it may lie before 0), and triangle (0, 1, 5) at t = 1.125,
 * t error 1e-13. The whole line's list, which the repair expects to be
 * entered first, moves the entering crossing onto the leaving one (0.125
 * apart, inside the slack of four t errors); the moved crossing took the
 * refused one's mark and both were dropped: hit and first_hit found
 * nothing where any_hit (its shortcut, closed_any_blocks) found the
 * entering crossing. Checked: all three find the ray blocked, first_hit
 * gives hit's first, and the pair is one place entered first, at the
 * entering crossing's t (the better known of the two: 9/8 within its
 * bound of 1e-13, where the refused one's is 9.5); over the whole line
 * too. */
#include <math.h>
#include <stdio.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"

static const char mesh_3vn[] =
    "8 6 6\n"
    "-1 -1 -1\n1 -2 -1\n1 0 3\n2 0 0\n0 0 0\n4 -1 -1\n1 -1 -2\n-1 1 1\n"
    "1 -1 1\n1 1 1\n-1 1 1\n0 0 -1\n0 0 1\n0 -1 0\n"
    "4 0 3 2 1 0 0 0 0\n"
    "4 4 5 6 7 1 1 1 1\n"
    "4 0 1 5 4 2 2 2 2\n"
    "4 3 7 6 2 3 3 3 3\n"
    "4 0 4 7 3 4 4 4 4\n"
    "4 1 2 6 5 5 5 5 5\n";

static void check_interval(const harness_shape *shape, hr_ray ray, double tmin)
{
    hr_hit all[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
    const int n_all = harness_trace(shape, ray, tmin, INFINITY, HARNESS_ALL, all);
    const int n_first = harness_trace(shape, ray, tmin, INFINITY, HARNESS_FIRST, first);
    const int n_any = harness_trace(shape, ray, tmin, INFINITY, HARNESS_ANY, any);
    CHECK_MSG(n_all == 2 && n_first == 1 && n_any == 1, "tmin %g: hit %d, first_hit %d, any_hit %d", tmin, n_all,
              n_first, n_any);
    if (n_all != 2 || n_first != 1) return;
    /* One place, entered first: the repair's zero-length visit, at the
     * entering crossing's t (9/8 exactly, t error bound 1e-13). */
    CHECK_MSG(all[0].entering && !all[1].entering && fabs(all[0].t - 1.125) <= 1e-13 && all[1].t == all[0].t,
              "tmin %g: hits at t %a entering %d, t %a entering %d", tmin, all[0].t, (int)all[0].entering,
              all[1].t, (int)all[1].entering);
    CHECK_MSG(first[0].t == all[0].t && first[0].entering == all[0].entering,
              "tmin %g: first hit t %a entering %d, all hits' first t %a entering %d", tmin, first[0].t,
              (int)first[0].entering, all[0].t, (int)all[0].entering);
}

int main(void)
{
    char path[1024];
    mesh_build_path("repair_mark.3vn", path, sizeof path);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return hr_test_end();
    fputs(mesh_3vn, f);
    CHECK(fclose(f) == 0);
    harness_shape shape;
    if (!mesh_open_file(&shape, path)) return hr_test_end();
    const hr_ray ray = harness_ray(13.5, 8.5, 8.0, -11.5, -8.5, -8.0);
    check_interval(&shape, ray, 0.0);
    check_interval(&shape, ray, -INFINITY);
    harness_close(&shape);
    return hr_test_end();
}
