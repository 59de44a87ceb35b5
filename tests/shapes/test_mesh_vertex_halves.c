/* A closed mesh's whole-line list is walked in two halves, each from t = 0
 * (shapes/mesh/mesh_trace.c, walk), and a crossing within its t error of
 * 0 may be kept by either; the second walk keeps it only when the first
 * has not (kept_in_phase). That used to be judged by the hit's t, flag
 * and point, which every triangle round a vertex can share: the buckyball
 * and a ray along one of its edges (from test_mesh_any_hit_closed's rays
 * along an edge), which passes within 1e-17 of the edge's far vertex at
 * t = 1.668 and there meets four triangles of the three faces round it,
 * seen nearly edge on (t error bounds of 399 to 5.8e18, so all within
 * their error of 0). The first walk kept two, entering and leaving; the
 * second dropped its entering one as a copy of the first walk's, and the
 * list held three hits, entering, leaving, leaving: no longer alternating
 * (the harness checks that on every call) and no longer balanced.
 * Checked, over (-inf, inf) and (0, inf): four hits, alternating from an
 * entering one, all at the vertex (each point on the ray's line, in quad
 * precision, within its error bound times sqrt(3), the bound being per
 * coordinate); first_hit gives the list's first. */
#include <math.h>
#include <stdio.h>

#include "hr_test.h"
#include "module_harness.h"
#include "quad_reference.h"

/* Distance from p to the ray's point at t, in quad. */
static double off_line(hr_ray ray, double t, hr_vec3 p)
{
    const quad dx = (quad)ray.origin.x + (quad)t * ray.dir.x - p.x;
    const quad dy = (quad)ray.origin.y + (quad)t * ray.dir.y - p.y;
    const quad dz = (quad)ray.origin.z + (quad)t * ray.dir.z - p.z;
    return sqrt(ref_to_double(dx * dx + dy * dy + dz * dz));
}

static void check_interval(const harness_shape *shape, hr_ray ray, double tmin)
{
    hr_hit all[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS];
    const int n_all = harness_trace(shape, ray, tmin, INFINITY, HARNESS_ALL, all);
    const int n_first = harness_trace(shape, ray, tmin, INFINITY, HARNESS_FIRST, first);
    CHECK_MSG(n_all == 4 && n_first == 1, "tmin %g: %d hits, %d first hits", tmin, n_all, n_first);
    for (int i = 0; i < n_all; i++) {
        CHECK_MSG(all[i].entering == !(i & 1), "tmin %g: hit %d has entering %d", tmin, i, (int)all[i].entering);
        CHECK_MSG(fabs(all[i].t - 1.668037075522035) < 1e-14, "tmin %g: hit %d at t %.17g", tmin, i, all[i].t);
        const double off = off_line(ray, all[i].t, all[i].point);
        CHECK_MSG(off <= sqrt(3.0) * all[i].error, "tmin %g: hit %d lies %g off the line, its error bound %g",
                  tmin, i, off, all[i].error);
        CHECK_MSG(all[i].point.x == all[0].point.x && all[i].point.y == all[0].point.y &&
                      all[i].point.z == all[0].point.z,
                  "tmin %g: hit %d is not at the vertex of hit 0", tmin, i);
    }
    if (n_all >= 1 && n_first == 1)
        CHECK_MSG(first[0].t == all[0].t && first[0].entering == all[0].entering,
                  "tmin %g: first hit t %a entering %d, all hits' first t %a entering %d", tmin, first[0].t,
                  (int)first[0].entering, all[0].t, (int)all[0].entering);
}

int main(void)
{
    harness_shape shape;
    if (!harness_open(&shape, "mesh", "buckyball", NAN)) return hr_test_end();
    const hr_ray ray = harness_ray(-0.77142243160521962, -0.54457634384906872, -0.53834079613547303,
                                   -0.12470325566120588, 0.32647736182880471, 0.20177410616759883);
    check_interval(&shape, ray, -INFINITY);
    check_interval(&shape, ray, 0.0);
    harness_close(&shape);
    return hr_test_end();
}
