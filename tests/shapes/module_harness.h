/* A test host for shape modules: loads a module file straight from the build
 * tree with dlopen, hands it a small hr_host, creates shapes and calls their
 * hit functions, checking the module contract (shape_module.h) on every call.
 * It needs nothing of libhitray, so the shapes can be tested on their own. */
#ifndef HR_TEST_MODULE_HARNESS_H
#define HR_TEST_MODULE_HARNESS_H

#include <hitray/shape_module.h>

/* Hit-function modes of harness_trace (the same numbers as HR_TRACE_*). */
#define HARNESS_ALL HR_TRACE_ALL
#define HARNESS_FIRST HR_TRACE_FIRST
#define HARNESS_ANY HR_TRACE_ANY

/* The most hits a call may return (the free space the host promises). */
#define HARNESS_MAX_HITS HR_MIN_HIT_CAPACITY

typedef struct harness_module {
    void *handle;
    const hr_module_info *info;
    char path[512];
} harness_module;

/* One shape made by a class, with the module that owns the class. */
typedef struct harness_shape {
    harness_module module;
    const hr_shape_class *cls;
    void *shape;
} harness_shape;

/* The host table passed to every module and create call. */
const hr_host *harness_host(void);

/* Loads HR_TEST_SHAPE_DIR/<file_stem>.so and calls its entry point.
 * Returns 1 on success; on failure records a test failure and returns 0. */
int harness_load(const char *file_stem, harness_module *out);
/* The same for the module file at `path` (a plugin built elsewhere). */
int harness_load_path(const char *path, harness_module *out);
void harness_unload(harness_module *module);
const hr_shape_class *harness_find_class(const harness_module *module, const char *class_name);

/* Calls cls->create with every parameter of the class at its default, then
 * the number parameters in `names`/`values` (count of them) overriding.
 * Returns create's status; `error` receives create's message. */
hr_status harness_create(const hr_shape_class *cls, const char *const *names,
                         const double *values, int count, void **out_shape, char *error,
                         size_t error_size);

/* Calls cls->create with every parameter of the class at its default, then
 * the parameters in `given` (count of them; number, string or array,
 * matched by name) overriding. Returns create's status; `error` receives create's
 * message. */
hr_status harness_create_params(const hr_shape_class *cls, const hr_param *given, int count,
                                void **out_shape, char *error, size_t error_size);

/* A child object for a composite under test (what the host's trace_child
 * and child_bounds receive): `shape` placed in the parent's space by
 * p = offset + scale * q, standing for object number `object` of a scene
 * (the index the host writes into its leaf hits). The harness's trace_child
 * works as libhitray's does: see module_harness.c. */
typedef struct harness_child {
    const harness_shape *shape;
    hr_vec3 offset;
    double scale;
    int64_t object;
} harness_child;

/* Calls cls->create with the object parameters in `names` given the
 * children in `children` (count of them), every other parameter at its
 * default. Returns create's status; `error` receives create's message. */
hr_status harness_create_composite(const hr_shape_class *cls, const char *const *names,
                                   const harness_child *const *children, int count,
                                   void **out_shape, char *error, size_t error_size);

/* Loads the module, finds the class and creates a shape with default
 * parameters (and `s`, or the torus's `tube`, when s_or_nan is not NaN).
 * Returns 1 on success. */
int harness_open(harness_shape *out, const char *file_stem, const char *class_name,
                 double s_or_nan);
void harness_close(harness_shape *shape);

/* Calls the class's hit (HARNESS_ALL), first_hit or any_hit on `ray` and
 * copies what it appended into hits[] (HARNESS_MAX_HITS of room); returns
 * the count (at most HARNESS_MAX_HITS: the rest of a longer list is checked,
 * not copied). Every call checks: HR_OK; the existing entries of the host's
 * list untouched; count within the free space or what host->reserve grew it
 * to (at most 1 for first/any);
 * t strictly inside (tmin, tmax); sorted; every field finite; error >= 0;
 * normal non-zero; surface id in range; entering 0 or 1; `object` not
 * written; for a closed shape in HARNESS_ALL mode, entering flags
 * alternating. */
int harness_trace(const harness_shape *shape, hr_ray ray, double tmin, double tmax,
                  int32_t mode, hr_hit hits[HARNESS_MAX_HITS]);

/* harness_trace in HARNESS_ALL mode with every check but a closed shape's
 * alternation, for a test that counts the lists that do not alternate. */
int harness_all_hits_as_listed(const harness_shape *shape, hr_ray ray, double tmin, double tmax,
                               hr_hit hits[HARNESS_MAX_HITS]);

/* harness_trace in HARNESS_ALL mode over (0, +infinity). */
int harness_hits(const harness_shape *shape, hr_ray ray, hr_hit hits[HARNESS_MAX_HITS]);

/* Every class of the built-in modules, with a few tapers of taperedCylinder
 * and taperedTube (s is NaN for classes without parameters, and for the
 * torus's default tube; t, taperedTube's thickness, is 0 elsewhere). */
typedef struct harness_class_ref {
    const char *module;
    const char *name;
    double s;
    double t;
} harness_class_ref;

/* harness_open for a catalog entry (passes its t as well). */
int harness_open_ref(harness_shape *out, const harness_class_ref *ref);

extern const harness_class_ref harness_catalog[];
extern const int harness_catalog_count;

hr_ray harness_ray(double ox, double oy, double oz, double dx, double dy, double dz);
hr_vec3 harness_vec(double x, double y, double z);

/* Checks one hit against values worked out by hand: t within 4 ulps (hand
 * values are decimals rounded to double, and the shapes' t carries a few
 * roundings); the surface id and entering flag exactly; the point within the
 * hit's own error bound plus 4 ulps of the expected coordinates (their
 * rounding to double); the normal's direction within 1e-12 of `normal`
 * (any length is allowed from a shape, so both are normalised). */
void harness_expect_hit(const char *what, const hr_hit *hit, double t, int surface, int entering,
                        hr_vec3 point, hr_vec3 normal);

#endif
