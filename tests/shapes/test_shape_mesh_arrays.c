/* The mesh module's triangleMesh class and the host's HR_PARAM_NUMBERS
 * parameters: a tetrahedron handed over as arrays is traced like the same
 * mesh read from a file (watertight: every ray through it enters once and
 * leaves once), normals are interpolated, and every wrong array is refused
 * with a message naming the parameter, by the host (type, count, pointer,
 * non-finite or out-of-range element) or by the module (counts that do not
 * fit together, an index past the vertices, a non-whole index) - also when
 * create is called directly, as a host that skipped its checks would. */
#include <float.h>
#include <math.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"

static hr_context *ctx;

static const double points[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
/* Counter-clockwise seen from outside. */
static const double faces[12] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};

static hr_status add(hr_scene *s, const hr_param *params, int32_t count)
{
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = "triangleMesh";
    d.params = params;
    d.param_count = count;
    return hr_scene_add_object(s, &d, NULL);
}

/* Rays from all round through the origin: each enters once, leaves once. */
static void test_tetrahedron(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    const hr_param p[2] = {mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", faces, 12)};
    CHECK_OK(add(s, p, 2));
    CHECK_OK(hr_scene_commit(s));
    hr_intersection all;
    hr_intersection_init(&all);
    for (int k = 0; k < 64; k++) {
        const double a = 0.7 * k, b = 0.3 + 0.11 * k;
        hr_vec3 d = {cos(a) * sin(b), sin(a) * sin(b), cos(b)};
        hr_ray ray = {{-5 * d.x, -5 * d.y, -5 * d.z}, d};
        CHECK_OK(hr_scene_all_hits(s, &ray, 0.0, INFINITY, &all));
        CHECK_MSG(all.count == 2 && all.hits[0].entering && !all.hits[1].entering,
                  "ray %d: %d hits", k, (int)all.count);
        all.count = 0;
    }
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* Per-vertex normals, interpolated: at a face's centroid the normal is the
 * mean of its corners' normals (here the vertices' directions). */
static void test_normals(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    const hr_param p[3] = {mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", faces, 12),
                           mesh_numbers_param("normals", points, 12)};
    CHECK_OK(add(s, p, 3));
    CHECK_OK(hr_scene_commit(s));
    /* Face (0, 1, 2): centroid (1/3, 1/3, -1/3), mean normal the same. */
    const hr_vec3 c = {1.0 / 3, 1.0 / 3, -1.0 / 3};
    hr_ray ray = {{3 * c.x, 3 * c.y, 3 * c.z}, {-c.x, -c.y, -c.z}};
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &ray, 0.0, INFINITY, &h, &found));
    const double len = sqrt(1.0 / 3);
    CHECK_MSG(found && fabs(h.normal.x - c.x / len) < 1e-12 && fabs(h.normal.y - c.y / len) < 1e-12 &&
                  fabs(h.normal.z - c.z / len) < 1e-12,
              "normal %.17g %.17g %.17g", h.normal.x, h.normal.y, h.normal.z);
    hr_scene_destroy(s);
}

typedef struct bad_arrays {
    hr_param params[3];
    int32_t count;
    hr_status status;
    const char *message; /* a part of the message */
} bad_arrays;

static void check_refusals(void)
{
    static const double nan_point[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, NAN};
    static const double past[12] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 4};
    static const double half[12] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 1.5};
    static const double negative[3] = {0, -1, 2};
    hr_param as_number;
    memset(&as_number, 0, sizeof as_number);
    as_number.name = "points";
    as_number.type = HR_PARAM_NUMBER;
    as_number.number = 1;
    const hr_param tris = mesh_numbers_param("triangles", faces, 12);
    const bad_arrays cases[] = {
        {{as_number, tris}, 2, HR_ERROR_PARAMETER,
         "parameter 'points' must be an array of numbers, not a number"},
        {{mesh_numbers_param("points", points, -3), tris}, 2, HR_ERROR_PARAMETER,
         "parameter 'points' has count -3"},
        {{mesh_numbers_param("points", NULL, 12), tris}, 2, HR_ERROR_PARAMETER,
         "parameter 'points' has count 12 and a NULL pointer"},
        {{mesh_numbers_param("points", nan_point, 12), tris}, 2, HR_ERROR_PARAMETER,
         "element 11 of parameter 'points' must be a finite number"},
        {{mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", negative, 3)}, 2, HR_ERROR_PARAMETER,
         "element 1 of parameter 'triangles' = -1 is outside [0, "},
        {{mesh_numbers_param("points", points, 10), tris}, 2, HR_ERROR_PARAMETER,
         "parameter 'points' must hold 3 numbers per vertex"},
        {{mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", faces, 11)}, 2, HR_ERROR_PARAMETER,
         "parameter 'triangles' must hold 3 vertex indices per triangle"},
        {{mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", past, 12)}, 2, HR_ERROR_PARAMETER,
         "element 11 (corner 2 of triangle 3) is 4, not a vertex index in [0, 4)"},
        {{mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", half, 12)}, 2, HR_ERROR_PARAMETER,
         "is 1.5, not a vertex index"},
        {{mesh_numbers_param("points", points, 12), tris, mesh_numbers_param("normals", points, 9)}, 3, HR_ERROR_PARAMETER,
         "parameter 'normals' must be empty or hold one normal per vertex (12 numbers), not 9"},
        {{tris}, 1, HR_ERROR_PARAMETER, "parameter 'points' is required"},
    };
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        hr_status st = add(s, cases[i].params, cases[i].count);
        CHECK_MSG(st == cases[i].status && strstr(hr_context_last_error(ctx), cases[i].message),
                  "case %zu: status %d: %s", i, (int)st, hr_context_last_error(ctx));
    }
    CHECK(hr_scene_object_count(s) == 0);
    hr_scene_destroy(s);
}

/* The module refuses what the host would have, when its create is called
 * with no host checks in between (the test harness's host). */
static void check_module_alone(void)
{
    harness_module module;
    if (!harness_load("mesh", &module)) return;
    const hr_shape_class *cls = harness_find_class(&module, "triangleMesh");
    CHECK(cls != NULL);
    if (!cls) return;
    static const double nan_normal[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, INFINITY};
    const hr_param bad[3] = {mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", faces, 12),
                             mesh_numbers_param("normals", nan_normal, 12)};
    void *shape = NULL;
    char error[256] = "";
    CHECK(harness_create_params(cls, bad, 3, &shape, error, sizeof error) == HR_ERROR_PARAMETER);
    CHECK_MSG(strstr(error, "element 11 of parameter 'normals' is not a finite number"), "%s",
              error);
    CHECK(shape == NULL);
    /* Past the readers' coordinate limit (found by fuzz_shapes: a corner at
     * DBL_MAX gave a hit with every weight 0, outside the bounds). */
    static const double huge_point[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, DBL_MAX};
    const hr_param huge[2] = {mesh_numbers_param("points", huge_point, 12), mesh_numbers_param("triangles", faces, 12)};
    CHECK(harness_create_params(cls, huge, 2, &shape, error, sizeof error) == HR_ERROR_PARAMETER);
    CHECK_MSG(strstr(error, "element 11 of parameter 'points' is 1.79769e+308, beyond the "
                            "coordinates a mesh takes (at most 1e+100)"),
              "%s", error);
    CHECK(shape == NULL);
    const hr_param good[2] = {mesh_numbers_param("points", points, 12), mesh_numbers_param("triangles", faces, 12)};
    CHECK_OK(harness_create_params(cls, good, 2, &shape, error, sizeof error));
    if (shape) cls->destroy(shape);
    harness_unload(&module);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    test_tetrahedron();
    test_normals();
    check_refusals();
    check_module_alone();
    hr_context_destroy(ctx);
    return hr_test_end();
}
