/* Where a closed mesh's all-hits repair (shapes/mesh/mesh_trace.c,
 * alternate_closed) puts a pair: at the better known of its two crossings.
 * A shapes fuzz input: a triangleMesh tetrahedron 1e38 across, wound
 * inwards (its faces' normals point in; the mesh is closed all the same),
 * one corner 4.4 from the line x = y = z and another within 1e-16 of its
 * own size from it, and the ray (-8, -8, -8) + t (-8, -8, -8), which runs
 * along the edge between them. In quad precision on the doubles the line
 * meets face (0, 3, 2) at t = -1 (leaving, at its corner 0) and face
 * (1, 2, 3) at t = 3.778e36 (entering, well inside it). The triangle test
 * sees the first nearly edge on (t error bound 3.9e36) and the second
 * clearly (bound 1.7e32). The repair, expecting a closed mesh to be
 * entered first, makes the two one place; it used to put the pair at the
 * leaving crossing's t, -1, before tmin = 0: hit and first_hit found
 * nothing over (0, inf) while any_hit met the entering crossing. Checked:
 * over (0, inf) and over the whole line, hit gives the pair, entering
 * first, at the entering crossing's t (within 1e-4 of it: the module's
 * bound is 4.5e-5 of t); first_hit and any_hit give the entering hit. */
#include <math.h>
#include <string.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"
#include "quad_reference.h"

static const double points[12] = {0x1p-575, -0x1.7c7c7c73e3838p-147, 0x1.1cp+2,
                                  -0x1.7c7c7c7a6c7c7p+125, -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c73938ffffp+125,
                                  0x1.8p+1, -0x1.2p+2, -0x1.5c7c7c7c7c7c7p+125,
                                  -0x1.7c7c7c7c7c7c7p+125, -0x1.7c7c7c7c7c7p+125, -0x1p+3};
static const double triangles[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

/* Where the ray's line meets the plane of triangle (a, b, c), in quad:
 * the normal as A x B + B x C + C x A, whose products of doubles are
 * exact, so only the sums round (113 bits, against a result needed to
 * 1e-4). */
static double plane_crossing(hr_ray ray, int a, int b, int c)
{
    quad p[3][3];
    const int corner[3] = {a, b, c};
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) p[k][i] = points[3 * corner[k] + i];
    quad n[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        const quad *u = p[k], *v = p[(k + 1) % 3];
        n[0] += u[1] * v[2] - u[2] * v[1];
        n[1] += u[2] * v[0] - u[0] * v[2];
        n[2] += u[0] * v[1] - u[1] * v[0];
    }
    const quad o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const quad d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
    quad num = 0, den = 0;
    for (int i = 0; i < 3; i++) num += n[i] * (p[0][i] - o[i]), den += n[i] * d[i];
    return ref_to_double(num / den);
}

static void check_interval(const harness_shape *shape, hr_ray ray, double tmin, double entering_t)
{
    hr_hit all[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
    const int n_all = harness_trace(shape, ray, tmin, INFINITY, HARNESS_ALL, all);
    const int n_first = harness_trace(shape, ray, tmin, INFINITY, HARNESS_FIRST, first);
    const int n_any = harness_trace(shape, ray, tmin, INFINITY, HARNESS_ANY, any);
    CHECK_MSG(n_all == 2 && n_first == 1 && n_any == 1, "tmin %g: hit %d, first_hit %d, any_hit %d", tmin, n_all,
              n_first, n_any);
    if (n_all != 2 || n_first != 1) return;
    CHECK_MSG(all[0].entering && !all[1].entering && all[1].t == all[0].t &&
                  fabs(all[0].t - entering_t) <= 1e-4 * entering_t,
              "tmin %g: hits at t %.17g entering %d, t %.17g entering %d; the entering crossing at %.17g", tmin,
              all[0].t, (int)all[0].entering, all[1].t, (int)all[1].entering, entering_t);
    CHECK_MSG(first[0].t == all[0].t && first[0].entering, "tmin %g: first hit t %.17g entering %d", tmin,
              first[0].t, (int)first[0].entering);
}

int main(void)
{
    harness_shape shape;
    memset(&shape, 0, sizeof shape);
    if (!harness_load("mesh", &shape.module)) return hr_test_end();
    shape.cls = harness_find_class(&shape.module, "triangleMesh");
    CHECK(shape.cls != NULL);
    const hr_param given[2] = {mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", triangles, 12)};
    char error[512] = "";
    const hr_status st =
        shape.cls ? harness_create_params(shape.cls, given, 2, &shape.shape, error, sizeof error) : HR_ERROR_PARAMETER;
    CHECK_MSG(st == HR_OK, "create: %s", error);
    if (st != HR_OK) {
        harness_unload(&shape.module);
        return hr_test_end();
    }
    const hr_ray ray = harness_ray(-8.0, -8.0, -8.0, -8.0, -8.0, -8.0);
    const double leaving_t = plane_crossing(ray, 0, 3, 2), entering_t = plane_crossing(ray, 1, 2, 3);
    /* The geometry as described: the leaving crossing 3.8e36 before. */
    CHECK_MSG(fabs(leaving_t + 1.0) < 1e-12 && entering_t > 3.7e36 && entering_t < 3.8e36,
              "the line meets the faces' planes at t = %.17g and %.17g", leaving_t, entering_t);
    check_interval(&shape, ray, 0.0, entering_t);
    check_interval(&shape, ray, -INFINITY, entering_t);
    harness_close(&shape);
    return hr_test_end();
}
