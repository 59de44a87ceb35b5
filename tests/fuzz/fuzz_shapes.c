/* Fuzz harness: every shape class of the built-in modules (and of any
 * module named in HITRAY_FUZZ_SHAPE_MODULES) through the module ABI.
 *
 * The modules are loaded by the module harness (tests/shapes/
 * module_harness.c), whose harness_trace checks every point of the
 * contract in shape_module.h on each call: HR_OK, earlier hits untouched,
 * count within the free space (one at most from the fast paths), t
 * strictly inside (tmin, tmax) and sorted, every field finite, error >= 0,
 * a non-zero normal, the surface id in range, `object` left alone, and
 * entering flags alternating for a closed solid.
 *
 * Input: a byte picks the class (composites are left to fuzz_csg.c); then
 * each parameter in the class's order, a number as any double (so out of
 * range too: create must then refuse, with a message, and must accept
 * every value in range) and a string as a choice (the torus's solvers and
 * a few mesh files, the last of each wrong); then up to four rays, six
 * doubles each (huge, tiny, subnormal, zero, negative zero, infinite,
 * NaN: see fuzz_input.h), each with (0, inf), (-inf, inf) or two more
 * doubles as (tmin, tmax). On top of harness_trace, for every ray:
 * - first_hit and any_hit agree with hit, and every hit point lies within
 *   the class's bounds grown by its error bound (fuzz_modes.h);
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
#include <stdlib.h>
#include <string.h>

#include <hitray/shape_kit_module.h>

#include "fuzz_input.h"
#include "fuzz_modes.h"
#include "hr_test.h"
#include "module_harness.h"
#include "quad_reference.h"

/* The built-in modules of one shape each (csg has its own harness), then
 * any listed in HITRAY_FUZZ_SHAPE_MODULES (paths separated by ':'): a
 * plugin built outside the tree is fuzzed the same way (FUZZING.md). */
static const char *const builtin_stems[] = {"sphere", "plane", "square", "cube",
                                            "cylinder", "torus", "mesh"};
#define BUILTIN_COUNT ((int)(sizeof builtin_stems / sizeof builtin_stems[0]))
#define MAX_MODULES 16
#define MAX_CLASSES 64
static harness_module modules[MAX_MODULES];
static int module_count;

/* Every class of those modules but composites, in module order then the
 * module's own order (an input's first byte picks one). */
typedef struct fuzz_class {
    const harness_module *module;
    const hr_shape_class *cls;
    int reference; /* 1: ref_surface_distance knows it (a built-in quadric, ...) */
    int builtin;   /* from a built-in module: its create refuses exactly what
                      its specs' ranges leave out (see create_shape) */
} fuzz_class;
static fuzz_class classes[MAX_CLASSES];
static unsigned class_count;

/* The classes quad_reference.c knows, when a built-in module provides them. */
static const char *const reference_names[] = {"sphere", "plane", "square", "cube",
                                              "cylinder", "cone", "taperedCylinder", "torus"};

/* Values of string parameters the harness knows by name: the torus's
 * solvers and a mesh's files; the last of each must be refused (a solver
 * it does not have, a file that does not exist). A string parameter of
 * another name gets "" or "fuzz", and either answer is accepted. */
static const char *const solvers[] = {"", "ferrari", "ferrari-newton", "bracketing", "newton"};
static const char *const mesh_files[] = {"cube.obj", "cube.3vn", "tetra_hill.3vn",
                                         "smooth_square.obj", "missing.obj"};
static const char *const other_strings[] = {"", "fuzz"};

static void add_module(const char *path_or_stem, int builtin)
{
    if (module_count == MAX_MODULES) fuzz_fail("shapes: more than %d modules", MAX_MODULES);
    harness_module *m = &modules[module_count];
    if (!(builtin ? harness_load(path_or_stem, m) : harness_load_path(path_or_stem, m)))
        fuzz_require_no_failures("shapes: loading the modules");
    module_count++;
    for (int32_t i = 0; i < m->info->class_count; i++) {
        const hr_shape_class *cls = m->info->classes[i];
        if (cls->flags & HR_SHAPE_COMPOSITE) continue;
        if (class_count == MAX_CLASSES) fuzz_fail("shapes: more than %d classes", MAX_CLASSES);
        fuzz_class *fc = &classes[class_count++];
        fc->module = m;
        fc->cls = cls;
        fc->reference = 0;
        fc->builtin = builtin;
        for (size_t k = 0; builtin && k < sizeof reference_names / sizeof reference_names[0]; k++)
            if (strcmp(cls->name, reference_names[k]) == 0) fc->reference = 1;
    }
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    for (int i = 0; i < BUILTIN_COUNT; i++) add_module(builtin_stems[i], 1);
    const char *extra = getenv("HITRAY_FUZZ_SHAPE_MODULES");
    while (extra && *extra) {
        const char *end = strchr(extra, ':');
        const size_t n = end ? (size_t)(end - extra) : strlen(extra);
        char path[512];
        if (n > 0 && n < sizeof path) {
            memcpy(path, extra, n);
            path[n] = '\0';
            add_module(path, 0);
        }
        extra = end ? end + 1 : NULL;
    }
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
    const int n_all =
        fuzz_trace_modes(shape, ray, tmin, tmax, (cls->flags & HR_SHAPE_CLOSED) != 0, 0.0, all);
    hr_bounds b;
    cls->bounds(shape->shape, &b);
    for (int i = 0; i < n_all && i < HARNESS_MAX_HITS; i++) {
        const hr_hit *h = &all[i];
        if (fc->reference) {
            const double distance = ref_surface_distance(ref, h->surface, h->point);
            if (!(distance <= sqrt(3.0) * h->error * (1 + 4 * DBL_EPSILON)))
                fuzz_fail(FUZZ_RAY_FMT "hit %d at (%a, %a, %a) on surface %d is %.3g from it, "
                                       "error bound %.3g",
                          FUZZ_RAY_ARGS(cls->name, ray, tmin, tmax), i, h->point.x, h->point.y,
                          h->point.z, (int)h->surface, distance, h->error);
        }
    }
    if ((cls->flags & HR_SHAPE_CLOSED) && tmin == -INFINITY && tmax == INFINITY && n_all > 0 &&
        n_all < HARNESS_MAX_HITS && passage_representable(&ray, &b) &&
        (n_all % 2 != 0 || !all[0].entering || all[n_all - 1].entering))
        fuzz_fail(FUZZ_RAY_FMT "over the whole line %d hits, the first %s, the last %s",
                  FUZZ_RAY_ARGS(cls->name, ray, tmin, tmax), n_all,
                  all[0].entering ? "entering" : "exiting",
                  all[n_all - 1].entering ? "entering" : "exiting");
}

/* The given number named `name`, NaN when absent. */
static double given_number(const hr_param *given, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (given[i].type == HR_PARAM_NUMBER && strcmp(given[i].name, name) == 0)
            return given[i].number;
    return NAN;
}

/* Relations between parameters that no single range can state, so a
 * built-in class refuses them in create: taperedTube's wall may be no
 * thicker than its cap's radius (t <= s). */
static int relations_hold(const hr_shape_class *cls, const hr_param *given, int count)
{
    if (strcmp(cls->name, "taperedTube") == 0)
        return given_number(given, count, "t") <= given_number(given, count, "s");
    return 1;
}

/* Creates the class with every parameter from the input, in the class's
 * order: a number parameter any double, a string one a choice. Returns 1
 * with the shape made, 0 when it was not. A refusal must come with
 * HR_ERROR_PARAMETER (HR_ERROR_IO for a mesh file) and a message.
 * The host checks ranges before create (shape_module.h), so a module may
 * rely on it; the built-in modules refuse out-of-range values all the same
 * (in case a host or a test passes them) and nothing else but a wrong
 * string or a broken relation (relations_hold), so for them both ways are
 * checked. A plugin is given only what
 * a host would pass it, and may refuse more than its ranges say (the
 * example disk refuses a radius of 0). `number` receives the first number
 * parameter (s, tube), NaN for none. */
static int create_shape(fuzz_input *in, const fuzz_class *fc, harness_shape *shape,
                        double *number)
{
    *number = NAN;
    const hr_shape_class *cls = shape->cls;
    hr_param given[16];
    memset(given, 0, sizeof given);
    int count = 0, valid = 1, known = 1;
    char path[600];
    double arrays[4][12];
    int array_count = 0;
    for (int32_t i = 0; i < cls->param_count && count < 16; i++) {
        const hr_param_spec *spec = &cls->params[i];
        hr_param *p = &given[count++];
        p->name = spec->name;
        p->type = spec->type;
        if (spec->type == HR_PARAM_NUMBER) {
            p->number = fuzz_double(in);
            if (isnan(*number)) *number = p->number;
            if (!shape_param_accepts(spec, p->number)) valid = 0;
            /* The teapot's steps a side are counted: a fraction is refused. */
            if (strcmp(spec->name, "tessellation") == 0 && p->number != floor(p->number))
                valid = 0;
        } else if (spec->type == HR_PARAM_STRING) {
            const char *const *values = other_strings;
            unsigned n = sizeof other_strings / sizeof other_strings[0];
            const int solver = strcmp(spec->name, "solver") == 0;
            const int file = strcmp(spec->name, "file") == 0;
            if (solver) values = solvers, n = sizeof solvers / sizeof solvers[0];
            if (file) values = mesh_files, n = sizeof mesh_files / sizeof mesh_files[0];
            const unsigned k = fuzz_choice(in, n);
            p->string = values[k];
            if (file) {
                snprintf(path, sizeof path, "%s/tests/data/meshes/%s", HR_TEST_SOURCE_DIR,
                         values[k]);
                p->string = path;
            }
            if ((solver || file) && k == n - 1) valid = 0;
            if (!solver && !file) known = 0;
        } else if (spec->type == HR_PARAM_NUMBERS && array_count < 4) {
            /* A tetrahedron's worth from the input: 12 doubles for points or
             * normals (or none), its faces as corner indices, the last choice
             * naming a vertex it lacks. Points may coincide, so a refusal
             * ("no triangle with area") is as right as a mesh: not known. */
            double *a = arrays[array_count++];
            static const double faces[2][12] = {{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3},
                                                {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 4}};
            p->numbers = a;
            p->count = 12;
            if (strcmp(spec->name, "triangles") == 0) {
                const unsigned k = fuzz_choice(in, 2);
                memcpy(a, faces[k], sizeof faces[k]);
                if (k == 1) valid = 0;
            } else {
                if (!spec->required && fuzz_choice(in, 2) == 0) p->count = 0;
                for (int j = 0; j < p->count; j++) {
                    a[j] = fuzz_double(in);
                    if (!isfinite(a[j]) || !shape_param_accepts(spec, a[j])) valid = 0;
                }
            }
            known = 0;
        }
    }
    if (!relations_hold(cls, given, count)) valid = 0;
    if (!fc->builtin && !valid) return 0; /* the host refuses it, create never sees it */
    if (!fc->builtin) known = 0;
    char error[512];
    const hr_status st =
        harness_create_params(cls, given, count, &shape->shape, error, sizeof error);
    if (st == HR_OK) {
        if (!valid) fuzz_fail("%s: create accepted a parameter out of its range", cls->name);
        if (!shape->shape) fuzz_fail("%s: create returned HR_OK and no shape", cls->name);
        return 1;
    }
    if (valid && known)
        fuzz_fail("%s: create refused valid parameters: status %d: %s", cls->name, (int)st,
                  error);
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
    const fuzz_class *fc = &classes[fuzz_choice(&in, class_count)];
    harness_shape shape;
    memset(&shape, 0, sizeof shape);
    shape.module = *fc->module;
    shape.cls = fc->cls;
    double number;
    if (!create_shape(&in, fc, &shape, &number)) return 0;
    const ref_shape ref = ref_shape_of(fc->cls->name, number, NAN);
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
