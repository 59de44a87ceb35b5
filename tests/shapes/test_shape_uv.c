/* (u, v) of every built-in class that gives them (hr_shape_class.surface_uv)
 * at points worked out by hand: the hit of a ray at a known point of each
 * surface, its (u, v) from the class, against the definition in the class's
 * comment. The hit points carry a few roundings (their error bound is near
 * 1e-16), and u and v are a division, an atan2 or a hypot of them, so 1e-12
 * is far above what they can be off and far below any mistake of a
 * definition (an eighth of a turn, a swapped axis). A mesh's (u, v) are
 * its OBJ file's texture coordinates, interpolated: within 1e-9 (the
 * triangle is found again by a probe 1e-7 of the mesh's size long, and the
 * barycentric weights carry the test's rounding). */
#include <math.h>
#include <string.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"

#define TOL 1e-12

typedef struct uv_case {
    double ox, oy, oz, dx, dy, dz; /* a ray whose first hit is the point */
    int surface;
    double u, v;
} uv_case;

static void check_class(const char *module, const char *name, double s, const uv_case *cases, int n)
{
    harness_shape sh;
    if (!harness_open(&sh, module, name, s)) return;
    CHECK_MSG(HR_CLASS_HAS(sh.cls, surface_uv) && sh.cls->surface_uv, "%s gives no (u, v)", name);
    if (!sh.cls->surface_uv) {
        harness_close(&sh);
        return;
    }
    CHECK_MSG(sh.cls->surface_uv(sh.shape, NULL, NULL) == 1, "%s: the probe is not 1", name);
    for (int i = 0; i < n; i++) {
        const uv_case *c = &cases[i];
        hr_hit hits[HARNESS_MAX_HITS];
        int count = harness_hits(&sh, harness_ray(c->ox, c->oy, c->oz, c->dx, c->dy, c->dz), hits);
        if (count < 1) {
            CHECK_MSG(0, "%s case %d: no hit", name, i);
            continue;
        }
        CHECK_MSG(hits[0].surface == c->surface, "%s case %d: surface %d, expected %d", name, i,
                  (int)hits[0].surface, c->surface);
        double uv[2] = {NAN, NAN};
        CHECK(sh.cls->surface_uv(sh.shape, &hits[0], uv) == 1);
        CHECK_MSG(fabs(uv[0] - c->u) <= TOL && fabs(uv[1] - c->v) <= TOL,
                  "%s case %d at (%g, %g, %g): (u, v) = (%.17g, %.17g), expected (%g, %g)", name, i,
                  hits[0].point.x, hits[0].point.y, hits[0].point.z, uv[0], uv[1], c->u, c->v);
    }
    harness_close(&sh);
}

#define CHECK_CLASS(module, name, s, cases) \
    check_class(module, name, s, cases, (int)(sizeof cases / sizeof cases[0]))

int main(void)
{
    /* Longitude from +x about z, latitude from the south pole. */
    const uv_case sphere[] = {
        {5, 0, 0, -1, 0, 0, 0, 0.0, 0.5},      {0, 5, 0, 0, -1, 0, 0, 0.25, 0.5},
        {-5, 0, 0, 1, 0, 0, 0, 0.5, 0.5},      {0, -5, 0, 0, 1, 0, 0, 0.75, 0.5},
        {0, 0, 5, 0, 0, -1, 0, 0.0, 1.0},      {0, 0, -5, 0, 0, 1, 0, 0.0, 0.0},
        {5, 0, 0.5, -1, 0, 0, 0, 0.0, 2.0 / 3.0}, /* latitude 30 degrees */
        {0, 5, -0.5, 0, -1, 0, 0, 0.25, 1.0 / 3.0},
    };
    CHECK_CLASS("sphere", "sphere", NAN, sphere);

    /* Wall: turn and height; base and cap: turn and the fraction of the
     * radius. */
    const uv_case cylinder[] = {
        {5, 0, 0.25, -1, 0, 0, 0, 0.0, 0.25}, {0, 5, 0.75, 0, -1, 0, 0, 0.25, 0.75},
        {-5, 0, 0.5, 1, 0, 0, 0, 0.5, 0.5},   {0.5, 0, -5, 0, 0, 1, 1, 0.0, 0.5},
        {0, 0.5, 5, 0, 0, -1, 2, 0.25, 0.5},  {0, -0.25, -5, 0, 0, 1, 1, 0.75, 0.25},
    };
    CHECK_CLASS("cylinder", "cylinder", NAN, cylinder);
    const uv_case tapered[] = {
        {0, 0.25, 5, 0, 0, -1, 2, 0.25, 0.5}, /* cap radius 0.5 */
        {-0.5, 0, -5, 0, 0, 1, 1, 0.5, 0.5},
    };
    CHECK_CLASS("cylinder", "taperedCylinder", 0.5, tapered);
    const uv_case cone[] = {{0, 0.5, -5, 0, 0, 1, 1, 0.25, 0.5}, {0, -5, 0.5, 0, 1, 0, 0, 0.75, 0.5}};
    CHECK_CLASS("cylinder", "cone", NAN, cone);
    check_class("cylinder", "openTaperedCylinder", 1.0, cylinder, 3); /* the wall's cases */

    const uv_case square[] = {
        {0.5, -0.5, 5, 0, 0, -1, 0, 0.75, 0.25},
        {-1 + 1e-9, 1 - 1e-9, 5, 0, 0, -1, 0, 0.5e-9, 1 - 0.5e-9}, /* near a corner */
    };
    CHECK_CLASS("square", "square", NAN, square);
    const uv_case plane[] = {{3.25, -2.5, 5, 0, 0, -1, 0, 3.25, -2.5}};
    CHECK_CLASS("plane", "plane", NAN, plane);

    /* Per face, read from outside: side faces u to the right, v up +z;
     * top and bottom v along +y. */
    const uv_case cube[] = {
        {5, 0.5, -0.5, -1, 0, 0, 0, 0.75, 0.25}, {-5, 0.5, -0.5, 1, 0, 0, 1, 0.25, 0.25},
        {0.5, 5, 0, 0, -1, 0, 2, 0.25, 0.5},     {0.5, -5, 0, 0, 1, 0, 3, 0.75, 0.5},
        {0.5, -0.5, 5, 0, 0, -1, 4, 0.75, 0.25}, {0.5, -0.5, -5, 0, 0, 1, 5, 0.25, 0.25},
    };
    CHECK_CLASS("cube", "cube", NAN, cube);

    /* Tube 0.2: u about z, v about the tube from the outer equator. */
    const uv_case torus[] = {
        {5, 0, 0, -1, 0, 0, 0, 0.0, 0.0},  {1, 0, 5, 0, 0, -1, 0, 0.0, 0.25},
        {0, 5, 0, 0, -1, 0, 0, 0.25, 0.0}, {0, 0, 0, 1, 0, 0, 0, 0.0, 0.5},
        {-1, 0, -5, 0, 0, 1, 0, 0.5, 0.75},
    };
    CHECK_CLASS("torus", "torus", NAN, torus);

    /* The mesh: its OBJ file's texture coordinates, interpolated, found
     * from the point alone (mesh_uv.c); none where the file has none. */
    harness_shape sq;
    char path[4096];
    if (mesh_open_file(&sq, mesh_data_path("textured_square.obj", path, sizeof path))) {
        CHECK(sq.cls->surface_uv && sq.cls->surface_uv(sq.shape, NULL, NULL) == 1);
        /* u = x + 1, v = (y + 1) / 2: points in either triangle, and on the
         * diagonal between them. */
        const double at[][2] = {{0.5, -0.5}, {-0.25, 0.6}, {0.3, 0.3}, {-0.9, -0.95}, {0.99, 0.98}};
        for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
            hr_hit hits[HARNESS_MAX_HITS];
            if (harness_hits(&sq, harness_ray(at[i][0], at[i][1], 5, 0, 0, -1), hits) < 1) {
                CHECK_MSG(0, "textured square: no hit at (%g, %g)", at[i][0], at[i][1]);
                continue;
            }
            double uv[2] = {NAN, NAN};
            CHECK(sq.cls->surface_uv(sq.shape, &hits[0], uv) == 1);
            CHECK_NEAR(uv[0], at[i][0] + 1.0, 1e-9);
            CHECK_NEAR(uv[1], 0.5 * (at[i][1] + 1.0), 1e-9);
        }
        harness_close(&sq);
    }
    harness_shape bare;
    if (mesh_open_file(&bare, mesh_data_path("cube.obj", path, sizeof path))) {
        CHECK(bare.cls->surface_uv && bare.cls->surface_uv(bare.shape, NULL, NULL) == 0);
        harness_close(&bare);
    }
    if (mesh_open_file(&bare, mesh_data_path("smooth_square.obj", path, sizeof path))) {
        /* One face has texture coordinates, the other not: none. */
        CHECK(bare.cls->surface_uv(bare.shape, NULL, NULL) == 0);
        harness_close(&bare);
    }
    return hr_test_end();
}
