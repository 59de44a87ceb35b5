/* The tmin rule of the mesh module's triangle test (mesh_hit_past in
 * shapes/mesh/mesh_triangle.h) for a ray that runs in a face's plane. A
 * CSG fuzz input: the octahedron at (ox, ox, 2) scaled by 2, ox =
 * 0x1.5757575757576p+0, and the world ray (2 ox, -1.75, -1.75) + t (1/8,
 * 7/8, 1) over (0, inf). In object space (as the host carries it, one
 * rounding in y) the line lies within that rounding of the plane of the
 * face x + y - z = 1 and runs on the face from t = 3.5328 to t = 3.75: in
 * rational arithmetic it touches the solid along that segment and starts 3
 * units away from it. The triangle test sees the face edge on, entering at
 * t = 3.5328 with a t error bound of 367, and the next face leaving at
 * t = 3.75. "Within its t error of tmin = 0" refused the entering crossing
 * alone: over (0, inf) the closed solid, seen from outside, began with a
 * leaving hit, and a CSG union above it stayed inside for ever. The
 * crossing lies in its triangle, whose corners all lie at t >= 1.75 along
 * the ray, so it lies past 0; and the line runs over the face from 3.5328
 * only (mesh_prism_least), so it lies past any tmin before that. Checked
 * over (0, inf): entered first, left last, the whole line's hits past 0,
 * first_hit and any_hit agreeing; and from 1, 2.964 and 3.5 the same
 * two hits.
 * And the rule still refuses the face a ray starts on: from a point of
 * the face, outward there is nothing, inward one leaving hit at t = 2/3. */
#include <math.h>

#include "hr_test.h"
#include "module_harness.h"

static void check_from_outside(const harness_shape *shape, hr_ray ray)
{
    hr_hit all[HARNESS_MAX_HITS], line[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
    const int n_all = harness_trace(shape, ray, 0.0, INFINITY, HARNESS_ALL, all);
    const int n_line = harness_trace(shape, ray, -INFINITY, INFINITY, HARNESS_ALL, line);
    const int n_first = harness_trace(shape, ray, 0.0, INFINITY, HARNESS_FIRST, first);
    const int n_any = harness_trace(shape, ray, 0.0, INFINITY, HARNESS_ANY, any);
    CHECK_MSG(n_all == 2 && n_line == 2 && n_first == 1 && n_any == 1,
              "hits %d over (0, inf), %d over the line, first_hit %d, any_hit %d", n_all, n_line, n_first,
              n_any);
    if (n_all != 2 || n_line != 2 || n_first != 1) return;
    CHECK_MSG(all[0].entering && !all[1].entering, "entering %d then %d", (int)all[0].entering,
              (int)all[1].entering);
    /* Where the line touches the face, 3.5328 to 3.75 (the entering t is as
     * uncertain as the ray is close to the face's plane). */
    CHECK_MSG(all[0].t > 3.5 && all[0].t <= 3.75 && fabs(all[1].t - 3.75) < 1e-12, "t %.17g and %.17g",
              all[0].t, all[1].t);
    for (int k = 0; k < 2; k++)
        CHECK_MSG(line[k].t == all[k].t && line[k].entering == all[k].entering,
                  "the whole line's hit %d: t %.17g entering %d, (0, inf)'s: t %.17g entering %d", k, line[k].t,
                  (int)line[k].entering, all[k].t, (int)all[k].entering);
    CHECK_MSG(first[0].t == all[0].t && first[0].entering == all[0].entering, "first_hit t %.17g entering %d",
              first[0].t, (int)first[0].entering);
    /* From later starts, clear of the face (the CSG fuzz input's second
     * form started at 2.964, where the corners' depths, from 1.75, allowed
     * a crossing before it; the line runs over the face from 3.5328 only):
     * the same two hits. */
    const double later[] = {1.0, 2.964126409122831, 3.5};
    for (int k = 0; k < 3; k++) {
        hr_hit part[HARNESS_MAX_HITS];
        const int n_part = harness_trace(shape, ray, later[k], INFINITY, HARNESS_ALL, part);
        CHECK_MSG(n_part == 2 && part[0].t == all[0].t && part[0].entering && part[1].t == all[1].t,
                  "over (%.17g, inf): %d hits, the first at t %.17g entering %d", later[k], n_part,
                  n_part ? part[0].t : 0.0, n_part ? (int)part[0].entering : -1);
    }
}

int main(void)
{
    harness_shape shape;
    if (!harness_open(&shape, "mesh", "octahedron", NAN)) return hr_test_end();
    const double ox = 0x1.5757575757576p+0;
    /* The world ray carried through the inverse of scale 2, then
     * translate (ox, ox, 2). */
    const hr_ray ray = harness_ray(0.5 * (2.0 * ox) - 0.5 * ox, 0.5 * -1.75 - 0.5 * ox, 0.5 * -1.75 - 1.0,
                                   0.0625, 0.4375, 0.5);
    check_from_outside(&shape, ray);

    /* From the face's centroid. */
    const double third = 1.0 / 3.0;
    hr_hit h[HARNESS_MAX_HITS];
    int n = harness_trace(&shape, harness_ray(third, third, -third, 1.0, 1.0, -1.0), 0.0, INFINITY, HARNESS_ALL, h);
    CHECK_MSG(n == 0, "outward from the face: %d hits, the first at t %g", n, n ? h[0].t : 0.0);
    n = harness_trace(&shape, harness_ray(third, third, -third, -1.0, -1.0, 1.0), 0.0, INFINITY, HARNESS_ALL, h);
    CHECK_MSG(n == 1 && !h[0].entering && fabs(h[0].t - 2.0 / 3.0) < 1e-15, "inward from the face: %d hits", n);
    harness_close(&shape);
    return hr_test_end();
}
