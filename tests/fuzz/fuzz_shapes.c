/* Fuzz harness: every built-in shape class through the module ABI.
 *
 * The modules are loaded from the build tree by the module harness
 * (tests/shapes/module_harness.c), whose harness_trace checks every point
 * of the contract in shape_module.h on each call: HR_OK, earlier hits
 * untouched, count within the free space (one at most from the fast
 * paths), t strictly inside (tmin, tmax) and sorted, every field finite,
 * error >= 0, a non-zero normal, the surface id in range, `object` left
 * alone, and entering flags alternating for a closed solid.
 *
 * The input picks a class, its parameters (any double, so out-of-range
 * ones too, which create must refuse with a message) and up to four rays
 * with their (tmin, tmax) (any doubles: huge, tiny, subnormal, zero,
 * negative zero, infinite, NaN). On top of harness_trace, for every ray:
 * - first_hit and any_hit agree with hit: a hit exactly when hit has one,
 *   and first_hit's is hit's first (same t, surface and entering);
 * - every hit point lies within the class's bounds grown by its error
 *   bound (each coordinate of the exact surface point is inside the
 *   bounds, and the bound is per coordinate);
 * - for the quadrics, the square, the cube and the torus, the point's
 *   Euclidean distance from the surface it names, computed in __float128
 *   by ref_surface_distance, is at most sqrt(3) times its error bound: the
 *   bound is per coordinate, so sqrt(3) error is the longest offset it
 *   allows (the shapes' accuracy test uses the same factor);
 * - over the whole line (-inf, inf), a bounded closed solid is entered
 *   first, left last, and crossed an even number of times: the line starts
 *   and ends outside it (where the crossings' times fit in a double, see
 *   passage_representable). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fuzz_input.h"
#include "fuzz_modes.h"
#include "hr_test.h"
#include "module_harness.h"
#include "quad_reference.h"

#define MODULE_COUNT 7
static const char *const module_stems[MODULE_COUNT] = {"sphere", "plane",    "square", "cube",
                                                        "cylinder", "torus", "mesh"};
static harness_module modules[MODULE_COUNT];

/* How a class takes its parameters. */
enum { PARAMS_NONE, PARAMS_S, PARAMS_TORUS, PARAMS_FILE };

typedef struct fuzz_class {
    int module;       /* index into module_stems */
    const char *name;
    int params;       /* PARAMS_* */
    int reference;    /* 1: ref_surface_distance knows it */
} fuzz_class;

static const fuzz_class classes[] = {
    {0, "sphere", PARAMS_NONE, 1},       {1, "plane", PARAMS_NONE, 1},
    {2, "square", PARAMS_NONE, 1},       {3, "cube", PARAMS_NONE, 1},
    {4, "cylinder", PARAMS_NONE, 1},     {4, "cone", PARAMS_NONE, 1},
    {4, "taperedCylinder", PARAMS_S, 1}, {5, "torus", PARAMS_TORUS, 1},
    {6, "tetrahedron", PARAMS_NONE, 0},  {6, "octahedron", PARAMS_NONE, 0},
    {6, "dodecahedron", PARAMS_NONE, 0}, {6, "icosahedron", PARAMS_NONE, 0},
    {6, "mesh", PARAMS_FILE, 0},
};
#define CLASS_COUNT ((unsigned)(sizeof classes / sizeof classes[0]))

/* Solver names: the three the torus has, the default (empty) and one it
 * must refuse. */
static const char *const solvers[] = {"", "ferrari", "ferrari-newton", "bracketing", "newton"};
/* Mesh files: the committed test meshes and one that does not exist. */
static const char *const mesh_files[] = {"cube.obj", "cube.3vn", "tetra_hill.3vn",
                                         "smooth_square.obj", "missing.obj"};

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    for (int i = 0; i < MODULE_COUNT; i++) harness_load(module_stems[i], &modules[i]);
    fuzz_require_no_failures("shapes: loading the modules");
    return 0;
}

/* Whether `value` is in the range the class states for parameter `name`. */
static int in_spec(const hr_shape_class *cls, const char *name, double value)
{
    for (int32_t i = 0; i < cls->param_count; i++)
        if (strcmp(cls->params[i].name, name) == 0)
            return value >= cls->params[i].min && value <= cls->params[i].max;
    return 0;
}

/* Whether the whole-line check applies: the ray is finite and the line's
 * passage through the (finite) bounds lies at times below 1e300, computed in
 * __float128 (which holds them all). A solid's crossings lie in that
 * passage, so then each is a double a hit can carry; beyond, a crossing at
 * t = 1e310 (a subnormal direction, say) is rightly dropped, and its pair
 * with it is not. */
static int passage_representable(const hr_ray *ray, const hr_bounds *b)
{
    const double o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    const double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    const double lo[3] = {b->lo.x, b->lo.y, b->lo.z}, hi[3] = {b->hi.x, b->hi.y, b->hi.z};
    quad t0 = 0, t1 = 0;
    int bounded = 0;
    for (int k = 0; k < 3; k++) {
        if (!isfinite(o[k]) || !isfinite(d[k]) || !isfinite(lo[k]) || !isfinite(hi[k])) return 0;
        if (d[k] == 0) continue; /* a miss or not, the slab bounds no time */
        quad ta = ((quad)lo[k] - o[k]) / d[k], tb = ((quad)hi[k] - o[k]) / d[k];
        if (ta > tb) {
            const quad swap = ta;
            ta = tb, tb = swap;
        }
        if (!bounded || ta > t0) t0 = ta;
        if (!bounded || tb < t1) t1 = tb;
        bounded = 1;
    }
    const quad limit = 1e300;
    return bounded && t0 > -limit && t0 < limit && t1 > -limit && t1 < limit;
}

static void check_ray(const harness_shape *shape, const fuzz_class *fc, ref_shape ref,
                      hr_ray ray, double tmin, double tmax)
{
    const hr_shape_class *cls = shape->cls;
    hr_hit all[HARNESS_MAX_HITS];
    const int n_all = fuzz_trace_modes(shape, ray, tmin, tmax, all);
    hr_bounds b;
    cls->bounds(shape->shape, &b);
    for (int i = 0; i < n_all && i < HARNESS_MAX_HITS; i++) {
        const hr_hit *h = &all[i];
        if (fc->reference) {
            const double distance = ref_surface_distance(ref, h->surface, h->point);
            if (!(distance <= sqrt(3.0) * h->error * (1 + 4 * DBL_EPSILON)))
                fuzz_fail(FUZZ_RAY_FMT "hit %d at (%a, %a, %a) on surface %d is %.3g from it, "
                                  "error bound %.3g",
                          FUZZ_RAY_ARGS(cls->name, ray, tmin, tmax), i, h->point.x, h->point.y, h->point.z,
                          (int)h->surface, distance, h->error);
        }
    }
    if ((cls->flags & HR_SHAPE_CLOSED) && tmin == -INFINITY && tmax == INFINITY && n_all > 0 &&
        n_all <= HARNESS_MAX_HITS && passage_representable(&ray, &b) &&
        (n_all % 2 != 0 || !all[0].entering || all[n_all - 1].entering))
        fuzz_fail(FUZZ_RAY_FMT "over the whole line %d hits, the first %s, the last %s",
                  FUZZ_RAY_ARGS(cls->name, ray, tmin, tmax), n_all, all[0].entering ? "entering" : "exiting",
                  all[n_all - 1].entering ? "entering" : "exiting");
}

/* Creates the class with parameters from the input. Returns 1 with the
 * shape made, 0 when create refused (which must be exactly when a
 * parameter is out of the class's stated range, and with a message);
 * `number` receives the number parameter (s or tube), NaN for none. */
static int create_shape(fuzz_input *in, const fuzz_class *fc, harness_shape *shape,
                        double *number)
{
    *number = NAN;
    const hr_shape_class *cls = shape->cls;
    hr_param given[2];
    memset(given, 0, sizeof given);
    int count = 0, valid = 1;
    char path[600];
    if (fc->params == PARAMS_S || fc->params == PARAMS_TORUS) {
        given[0].name = fc->params == PARAMS_S ? "s" : "tube";
        given[0].type = HR_PARAM_NUMBER;
        given[0].number = fuzz_double(in);
        valid = in_spec(cls, given[0].name, given[0].number);
        *number = given[0].number;
        count = 1;
    }
    if (fc->params == PARAMS_TORUS) {
        const unsigned k = fuzz_choice(in, sizeof solvers / sizeof solvers[0]);
        given[1].name = "solver";
        given[1].type = HR_PARAM_STRING;
        given[1].string = solvers[k];
        valid = valid && strcmp(solvers[k], "newton") != 0;
        count = 2;
    }
    if (fc->params == PARAMS_FILE) {
        const unsigned k = fuzz_choice(in, sizeof mesh_files / sizeof mesh_files[0]);
        snprintf(path, sizeof path, "%s/tests/data/meshes/%s", HR_TEST_SOURCE_DIR, mesh_files[k]);
        given[0].name = "file";
        given[0].type = HR_PARAM_STRING;
        given[0].string = path;
        valid = strcmp(mesh_files[k], "missing.obj") != 0;
        count = 1;
    }
    char error[512];
    const hr_status st =
        harness_create_params(cls, given, count, &shape->shape, error, sizeof error);
    if (st == HR_OK) {
        if (!valid) fuzz_fail("%s: create accepted a parameter out of its range", cls->name);
        if (!shape->shape) fuzz_fail("%s: create returned HR_OK and no shape", cls->name);
        return 1;
    }
    if (valid) fuzz_fail("%s: create refused valid parameters: status %d: %s", cls->name,
                         (int)st, error);
    if (shape->shape) fuzz_fail("%s: create refused and still made a shape", cls->name);
    if (!error[0]) fuzz_fail("%s: create refused (status %d) without a message", cls->name,
                             (int)st);
    if (st != HR_ERROR_PARAMETER && st != HR_ERROR_IO)
        fuzz_fail("%s: create refused with status %d: %s", cls->name, (int)st, error);
    return 0;
}

static void read_interval(fuzz_input *in, double *tmin, double *tmax)
{
    switch (fuzz_choice(in, 4)) {
    case 0: *tmin = 0.0, *tmax = INFINITY; break;
    case 1: *tmin = -INFINITY, *tmax = INFINITY; break;
    default: *tmin = fuzz_double(in), *tmax = fuzz_double(in); break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in = fuzz_input_make(data, size);
    const fuzz_class *fc = &classes[fuzz_choice(&in, CLASS_COUNT)];
    harness_shape shape;
    memset(&shape, 0, sizeof shape);
    shape.module = modules[fc->module];
    shape.cls = harness_find_class(&shape.module, fc->name);
    if (!shape.cls) fuzz_fail("no class '%s' in %s", fc->name, shape.module.path);
    double number;
    if (!create_shape(&in, fc, &shape, &number)) return 0;
    const ref_shape ref = ref_shape_of(fc->name, number);
    for (int r = 0; r < 4 && (r == 0 || fuzz_more(&in)); r++) {
        hr_ray ray;
        ray.origin.x = fuzz_double(&in);
        ray.origin.y = fuzz_double(&in);
        ray.origin.z = fuzz_double(&in);
        ray.dir.x = fuzz_double(&in);
        ray.dir.y = fuzz_double(&in);
        ray.dir.z = fuzz_double(&in);
        double tmin, tmax;
        read_interval(&in, &tmin, &tmax);
        check_ray(&shape, fc, ref, ray, tmin, tmax);
    }
    shape.cls->destroy(shape.shape);
    return 0;
}
