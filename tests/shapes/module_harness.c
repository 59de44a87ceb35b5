#include "module_harness.h"

#include <dlfcn.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"

/* --- The host ------------------------------------------------------------------ */

static void *host_alloc(size_t size)
{
    return calloc(1, size ? size : 1);
}

static void host_free(void *ptr)
{
    free(ptr);
}

/* What harness_trace puts in the `object` of every free slot, to see that
 * a shape leaves it alone. */
#define UNTOUCHED_OBJECT INT64_C(0x5a5a5a5a5a5a5a5a)

static hr_status host_reserve(void *call, hr_intersection *list, int32_t capacity)
{
    (void)call;
    if (capacity <= list->capacity) return HR_OK;
    hr_hit *grown = realloc(list->hits, (size_t)capacity * sizeof *grown);
    if (!grown) return HR_ERROR_OUT_OF_MEMORY;
    /* New slots are marked as harness_trace marks its own. */
    for (int32_t i = list->capacity; i < capacity; i++) {
        memset(&grown[i], 0, sizeof grown[i]);
        grown[i].object = UNTOUCHED_OBJECT;
    }
    list->hits = grown;
    list->capacity = capacity;
    return HR_OK;
}

static hr_intersection *host_scratch_acquire(void *call)
{
    (void)call;
    return calloc(1, sizeof(hr_intersection));
}

static void host_scratch_release(void *call, hr_intersection *list)
{
    (void)call;
    if (!list) return;
    free(list->hits);
    free(list);
}

static hr_vec3 child_to_parent(const harness_child *c, hr_vec3 p)
{
    return harness_vec(c->offset.x + c->scale * p.x, c->offset.y + c->scale * p.y,
                       c->offset.z + c->scale * p.z);
}

/* A child (harness_child) traced as libhitray's host does: the ray into the
 * child's space, the child's hit function for the mode, its hits back in the
 * parent's space after what `out` held, sorted by t among themselves (ties
 * in the child's order), `object` naming the leaf. The error bound is
 * carried through the scale and grown by the rounding of the product and
 * sum (an ulp each, counted as 4 ulps of the largest coordinate). */
static hr_status host_trace_child(void *call, const void *child_ptr, const hr_ray *ray,
                                  double tmin, double tmax, int32_t mode, hr_intersection *out)
{
    const harness_child *c = child_ptr;
    if (!c || !c->shape || !ray || !out) return HR_ERROR_INVALID_ARGUMENT;
    const hr_shape_class *cls = c->shape->cls;
    const int32_t start = out->count;
    hr_status st = host_reserve(call, out, start + HR_MIN_HIT_CAPACITY);
    if (st) return st;
    hr_hit_args args;
    memset(&args, 0, sizeof args);
    args.struct_size = (uint32_t)sizeof args;
    args.shape = c->shape->shape;
    args.ray.origin = harness_vec((ray->origin.x - c->offset.x) / c->scale,
                                  (ray->origin.y - c->offset.y) / c->scale,
                                  (ray->origin.z - c->offset.z) / c->scale);
    args.ray.dir = harness_vec(ray->dir.x / c->scale, ray->dir.y / c->scale, ray->dir.z / c->scale);
    args.tmin = tmin;
    args.tmax = tmax;
    args.out = out;
    args.call = call;
    hr_hit_fn fn = mode == HARNESS_FIRST && cls->first_hit ? cls->first_hit
                   : mode == HARNESS_ANY && cls->any_hit   ? cls->any_hit
                                                           : cls->hit;
    if ((st = fn(&args))) {
        out->count = start;
        return st;
    }
    const int composite = (cls->flags & HR_SHAPE_COMPOSITE) != 0;
    for (int32_t i = start; i < out->count; i++) {
        hr_hit *h = &out->hits[i];
        h->point = child_to_parent(c, h->point);
        const double size = fmax(fabs(h->point.x), fmax(fabs(h->point.y), fabs(h->point.z)));
        h->error = h->error * c->scale + 4 * DBL_EPSILON * size;
        if (!composite) h->object = c->object;
    }
    if (mode != HARNESS_ALL && out->count > start + 1) out->count = start + 1;
    for (int32_t i = start + 1; i < out->count; i++) {
        hr_hit h = out->hits[i];
        int32_t j = i;
        while (j > start && h.t < out->hits[j - 1].t) {
            out->hits[j] = out->hits[j - 1];
            j--;
        }
        out->hits[j] = h;
    }
    return HR_OK;
}

static void host_child_bounds(const void *child_ptr, hr_bounds *out)
{
    const harness_child *c = child_ptr;
    hr_bounds b;
    c->shape->cls->bounds(c->shape->shape, &b);
    out->lo = child_to_parent(c, b.lo);
    out->hi = child_to_parent(c, b.hi);
}

static const hr_shape_class *host_child_class(const void *child_ptr)
{
    const harness_child *c = child_ptr;
    return c->shape->cls;
}

/* A shape tells the file it read: with its create's arguments and a name
 * (the library's host lists it in the scene, test_files_read.c). */
static hr_status host_file_read(const hr_create_args *args, const char *path)
{
    return args && path && path[0] ? HR_OK : HR_ERROR_INVALID_ARGUMENT;
}

static const hr_host test_host = {
    sizeof(hr_host),      HR_SHAPE_ABI_VERSION, host_alloc,       host_free,
    host_reserve,         host_scratch_acquire, host_scratch_release, host_trace_child,
    host_child_bounds,    host_child_class,     host_file_read,
};

const hr_host *harness_host(void)
{
    return &test_host;
}

/* --- Modules and shapes -------------------------------------------------------- */

int harness_load(const char *file_stem, harness_module *out)
{
    char path[sizeof out->path];
    snprintf(path, sizeof path, "%s/%s.so", HR_TEST_SHAPE_DIR, file_stem);
    return harness_load_path(path, out);
}

int harness_load_path(const char *path, harness_module *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path);
    out->handle = dlopen(out->path, RTLD_NOW | RTLD_LOCAL);
    CHECK_MSG(out->handle != NULL, "dlopen %s: %s", out->path, dlerror());
    if (!out->handle) return 0;
    void *sym = dlsym(out->handle, HR_SHAPE_MODULE_ENTRY_NAME);
    CHECK_MSG(sym != NULL, "%s has no %s", out->path, HR_SHAPE_MODULE_ENTRY_NAME);
    if (!sym) return 0;
    hr_shape_module_fn entry;
    memcpy(&entry, &sym, sizeof entry); /* POSIX: dlsym's pointer is a function */
    out->info = entry(HR_SHAPE_ABI_VERSION, &test_host);
    CHECK_MSG(out->info != NULL, "%s: entry point returned NULL", out->path);
    return out->info != NULL;
}

void harness_unload(harness_module *module)
{
    if (module->handle) dlclose(module->handle);
    memset(module, 0, sizeof *module);
}

const hr_shape_class *harness_find_class(const harness_module *module, const char *class_name)
{
    for (int32_t i = 0; module->info && i < module->info->class_count; i++)
        if (strcmp(module->info->classes[i]->name, class_name) == 0)
            return module->info->classes[i];
    return NULL;
}

/* Every parameter of the class at its default (objects unset); 0 if the
 * class has more than the 16 the harness holds. */
static int default_params(const hr_shape_class *cls, hr_param params[16])
{
    memset(params, 0, 16 * sizeof *params);
    if (cls->param_count > 16) return 0;
    for (int32_t i = 0; i < cls->param_count; i++) {
        params[i].name = cls->params[i].name;
        params[i].type = cls->params[i].type;
        params[i].number = cls->params[i].default_number;
        if (cls->params[i].type == HR_PARAM_NUMBERS) {
            params[i].numbers = NULL; /* the host's default: the empty array */
            params[i].count = 0;
        } else {
            params[i].string = "";
            params[i].object = -1;
        }
    }
    return 1;
}

/* The class's create with the test host, as the library would call it. */
static hr_status create_from(const hr_shape_class *cls, const hr_param *params,
                             const void *const *objects, void **out_shape, char *error,
                             size_t error_size)
{
    hr_create_args args;
    memset(&args, 0, sizeof args);
    args.struct_size = (uint32_t)sizeof args;
    args.param_count = cls->param_count;
    args.params = params;
    args.objects = objects;
    args.host = &test_host;
    args.error = error;
    args.error_size = error_size;
    args.base_dir = "";
    if (error && error_size) error[0] = '\0';
    *out_shape = NULL;
    return cls->create(&args, out_shape);
}

hr_status harness_create(const hr_shape_class *cls, const char *const *names,
                         const double *values, int count, void **out_shape, char *error,
                         size_t error_size)
{
    hr_param given[16];
    if (count < 0 || count > 16) return HR_ERROR_INVALID_ARGUMENT;
    memset(given, 0, sizeof given);
    for (int g = 0; g < count; g++) {
        given[g].name = names[g];
        given[g].type = HR_PARAM_NUMBER;
        given[g].number = values[g];
    }
    return harness_create_params(cls, given, count, out_shape, error, error_size);
}

hr_status harness_create_params(const hr_shape_class *cls, const hr_param *given, int count,
                                void **out_shape, char *error, size_t error_size)
{
    hr_param params[16];
    if (!default_params(cls, params)) return HR_ERROR_INVALID_ARGUMENT;
    for (int g = 0; g < count; g++)
        for (int32_t i = 0; i < cls->param_count; i++)
            if (strcmp(cls->params[i].name, given[g].name) == 0 &&
                cls->params[i].type == HR_PARAM_NUMBERS) {
                params[i].numbers = given[g].count ? given[g].numbers : NULL;
                params[i].count = given[g].count;
            } else if (strcmp(cls->params[i].name, given[g].name) == 0) {
                params[i].number = given[g].number;
                params[i].string = given[g].string ? given[g].string : "";
            }
    const void *objects[16] = {NULL};
    return create_from(cls, params, objects, out_shape, error, error_size);
}

hr_status harness_create_composite(const hr_shape_class *cls, const char *const *names,
                                   const harness_child *const *children, int count,
                                   void **out_shape, char *error, size_t error_size)
{
    hr_param params[16];
    const void *objects[16] = {NULL};
    if (!default_params(cls, params)) return HR_ERROR_INVALID_ARGUMENT;
    for (int32_t i = 0; i < cls->param_count; i++) {
        for (int g = 0; g < count; g++)
            if (strcmp(cls->params[i].name, names[g]) == 0) {
                objects[i] = children[g];
                params[i].object = children[g] ? children[g]->object : -1;
            }
    }
    return create_from(cls, params, objects, out_shape, error, error_size);
}

static int open_with(harness_shape *out, const char *file_stem, const char *class_name,
                     double s_or_nan, double t);

int harness_open(harness_shape *out, const char *file_stem, const char *class_name,
                 double s_or_nan)
{
    return open_with(out, file_stem, class_name, s_or_nan, NAN);
}

int harness_open_ref(harness_shape *out, const harness_class_ref *ref)
{
    return open_with(out, ref->module, ref->name, ref->s, ref->t > 0 ? ref->t : NAN);
}

static int open_with(harness_shape *out, const char *file_stem, const char *class_name,
                     double s_or_nan, double t)
{
    memset(out, 0, sizeof *out);
    if (!harness_load(file_stem, &out->module)) return 0;
    out->cls = harness_find_class(&out->module, class_name);
    CHECK_MSG(out->cls != NULL, "%s has no class '%s'", out->module.path, class_name);
    if (!out->cls) return 0;
    /* The number parameters of the catalog's classes: `s` of the tapered
     * cylinder and tube, `tube` of the torus (a class ignores the other),
     * `t` of the tube. */
    const char *names[] = {"s", "tube", "t"};
    const double values[] = {s_or_nan, s_or_nan, t};
    char error[256];
    hr_status st = harness_create(out->cls, names, values,
                                  isnan(s_or_nan) ? 0 : isnan(t) ? 2 : 3, &out->shape, error,
                                  sizeof error);
    CHECK_MSG(st == HR_OK && out->shape, "create %s: status %d: %s", class_name, (int)st, error);
    return st == HR_OK && out->shape;
}

void harness_close(harness_shape *shape)
{
    if (shape->cls && shape->shape) shape->cls->destroy(shape->shape);
    harness_unload(&shape->module);
    memset(shape, 0, sizeof *shape);
}

/* --- Tracing with the contract checked ------------------------------------------- */

/* The host's list holds this many older hits before the call, to check that
 * a shape appends and leaves them alone. */
#define EARLIER_HITS 2

static const char *mode_name(int32_t mode)
{
    return mode == HARNESS_ALL ? "hit" : mode == HARNESS_FIRST ? "first_hit" : "any_hit";
}

static void check_contract(const harness_shape *shape, const hr_ray *ray, double tmin,
                           double tmax, int32_t mode, int alternation, const hr_intersection *list)
{
    const char *name = shape->cls->name;
    const int count = list->count - EARLIER_HITS;
#define RAY_FMT "%s %s ray (%.17g, %.17g, %.17g) + t (%.17g, %.17g, %.17g), t in (%g, %g): "
#define RAY_ARGS                                                                            \
    name, mode_name(mode), ray->origin.x, ray->origin.y, ray->origin.z, ray->dir.x, ray->dir.y, \
        ray->dir.z, tmin, tmax
    /* The free space promised, or what the shape grew the list to through
     * host->reserve (a mesh may have any number of hits). */
    CHECK_MSG(count >= 0 && count <= list->capacity - EARLIER_HITS, RAY_FMT "count %d", RAY_ARGS,
              count);
    CHECK_MSG(mode == HARNESS_ALL || count <= 1, RAY_FMT "%d hits from a fast path", RAY_ARGS,
              count);
    for (int i = 0; i < EARLIER_HITS; i++)
        CHECK_MSG(list->hits[i].t == -1.0 - i && list->hits[i].object == i,
                  RAY_FMT "an earlier hit was overwritten", RAY_ARGS);
    for (int i = 0; i < count; i++) {
        const hr_hit *h = &list->hits[EARLIER_HITS + i];
        const int finite = isfinite(h->t) && isfinite(h->point.x) && isfinite(h->point.y) &&
                           isfinite(h->point.z) && isfinite(h->normal.x) &&
                           isfinite(h->normal.y) && isfinite(h->normal.z) && isfinite(h->error);
        CHECK_MSG(finite, RAY_FMT "hit %d has a non-finite field", RAY_ARGS, i);
        CHECK_MSG(h->t > tmin && h->t < tmax, RAY_FMT "hit %d at t = %.17g is outside", RAY_ARGS,
                  i, h->t);
        CHECK_MSG(i == 0 || h[-1].t <= h->t, RAY_FMT "hits %d, %d unsorted", RAY_ARGS, i - 1, i);
        CHECK_MSG(h->error >= 0.0, RAY_FMT "hit %d has error %g", RAY_ARGS, i, h->error);
        CHECK_MSG(h->normal.x != 0.0 || h->normal.y != 0.0 || h->normal.z != 0.0,
                  RAY_FMT "hit %d has a zero normal", RAY_ARGS, i);
        CHECK_MSG(h->surface >= 0 && h->surface < shape->cls->surface_count,
                  RAY_FMT "hit %d has surface %d", RAY_ARGS, i, (int)h->surface);
        CHECK_MSG(h->entering == 0 || h->entering == 1, RAY_FMT "hit %d has entering = %d",
                  RAY_ARGS, i, (int)h->entering);
        CHECK_MSG(h->object == UNTOUCHED_OBJECT, RAY_FMT "hit %d: the shape wrote `object`",
                  RAY_ARGS, i);
        if (alternation && mode == HARNESS_ALL && (shape->cls->flags & HR_SHAPE_CLOSED) && i > 0)
            CHECK_MSG(h->entering != h[-1].entering, RAY_FMT "hits %d, %d do not alternate",
                      RAY_ARGS, i - 1, i);
    }
#undef RAY_FMT
#undef RAY_ARGS
}

/* harness_trace, with the closed shape's alternation checked or not. */
static int trace_checked(const harness_shape *shape, hr_ray ray, double tmin, double tmax, int32_t mode,
                         int alternation, hr_hit hits[HARNESS_MAX_HITS])
{
    /* Exactly the promised free space, so AddressSanitizer sees any write past it. */
    hr_intersection list;
    list.capacity = EARLIER_HITS + HR_MIN_HIT_CAPACITY;
    list.hits = malloc((size_t)list.capacity * sizeof *list.hits);
    if (!list.hits) {
        CHECK_MSG(0, "out of memory");
        return 0;
    }
    for (int32_t i = 0; i < list.capacity; i++) {
        memset(&list.hits[i], 0, sizeof list.hits[i]);
        list.hits[i].t = -1.0 - i;
        list.hits[i].object = i < EARLIER_HITS ? i : UNTOUCHED_OBJECT;
    }
    list.count = EARLIER_HITS;

    hr_hit_args args;
    memset(&args, 0, sizeof args);
    args.struct_size = (uint32_t)sizeof args;
    args.shape = shape->shape;
    args.ray = ray;
    args.tmin = tmin;
    args.tmax = tmax;
    args.out = &list;
    args.call = NULL;
    const hr_shape_class *cls = shape->cls;
    hr_hit_fn fn = mode == HARNESS_FIRST ? cls->first_hit : mode == HARNESS_ANY ? cls->any_hit
                                                                                : cls->hit;
    hr_status st = fn(&args);
    CHECK_MSG(st == HR_OK, "%s %s returned %d", cls->name, mode_name(mode), (int)st);
    check_contract(shape, &ray, tmin, tmax, mode, alternation, &list);

    int count = list.count - EARLIER_HITS;
    if (count < 0) count = 0;
    if (count > HARNESS_MAX_HITS) count = HARNESS_MAX_HITS;
    memcpy(hits, list.hits + EARLIER_HITS, (size_t)count * sizeof *hits);
    free(list.hits);
    return count;
}

int harness_trace(const harness_shape *shape, hr_ray ray, double tmin, double tmax,
                  int32_t mode, hr_hit hits[HARNESS_MAX_HITS])
{
    return trace_checked(shape, ray, tmin, tmax, mode, 1, hits);
}

int harness_all_hits_as_listed(const harness_shape *shape, hr_ray ray, double tmin, double tmax,
                               hr_hit hits[HARNESS_MAX_HITS])
{
    return trace_checked(shape, ray, tmin, tmax, HARNESS_ALL, 0, hits);
}

int harness_hits(const harness_shape *shape, hr_ray ray, hr_hit hits[HARNESS_MAX_HITS])
{
    return harness_trace(shape, ray, 0.0, INFINITY, HARNESS_ALL, hits);
}

hr_ray harness_ray(double ox, double oy, double oz, double dx, double dy, double dz)
{
    hr_ray r = {{ox, oy, oz}, {dx, dy, dz}};
    return r;
}

hr_vec3 harness_vec(double x, double y, double z)
{
    hr_vec3 v = {x, y, z};
    return v;
}

static hr_vec3 unit(hr_vec3 v)
{
    const double n = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return n > 0 ? harness_vec(v.x / n, v.y / n, v.z / n) : v;
}

void harness_expect_hit(const char *what, const hr_hit *hit, double t, int surface, int entering,
                        hr_vec3 point, hr_vec3 normal)
{
    CHECK_MSG(hr_test_ulps(hit->t, t) <= 4, "%s: t = %.17g, expected %.17g", what, hit->t, t);
    CHECK_MSG(hit->surface == surface, "%s: surface %d, expected %d", what, (int)hit->surface,
              surface);
    CHECK_MSG(hit->entering == entering, "%s: entering %d, expected %d", what,
              (int)hit->entering, entering);
    const double got[3] = {hit->point.x, hit->point.y, hit->point.z};
    const double want[3] = {point.x, point.y, point.z};
    for (int i = 0; i < 3; i++) {
        const double tol = hit->error + 4 * DBL_EPSILON * fmax(1.0, fabs(want[i]));
        CHECK_MSG(fabs(got[i] - want[i]) <= tol,
                  "%s: point[%d] = %.17g, expected %.17g (tol %g, error bound %g)", what, i,
                  got[i], want[i], tol, hit->error);
    }
    const hr_vec3 n = unit(hit->normal), m = unit(normal);
    CHECK_MSG(fabs(n.x - m.x) <= 1e-12 && fabs(n.y - m.y) <= 1e-12 && fabs(n.z - m.z) <= 1e-12,
              "%s: normal (%g, %g, %g), expected (%g, %g, %g)", what, n.x, n.y, n.z, m.x, m.y,
              m.z);
}

const harness_class_ref harness_catalog[] = {
    {"sphere", "sphere", NAN, 0},
    {"plane", "plane", NAN, 0},
    {"square", "square", NAN, 0},
    {"cube", "cube", NAN, 0},
    {"cylinder", "cylinder", NAN, 0},
    {"cylinder", "cone", NAN, 0},
    {"cylinder", "taperedCylinder", 0.5, 0},
    {"cylinder", "taperedCylinder", 0.0, 0},
    {"cylinder", "taperedCylinder", 3.0, 0},
    {"cylinder", "taperedCylinder", 1000.0, 0},
    {"cylinder", "taperedTube", 1.0, 0.25},
    {"cylinder", "taperedTube", 0.75, 0.125},
    {"cylinder", "taperedTube", 3.0, 0.5},
    {"cylinder", "taperedTube", 0.5, 0.5},
    {"torus", "torus", NAN, 0},
};
const int harness_catalog_count = (int)(sizeof harness_catalog / sizeof harness_catalog[0]);
