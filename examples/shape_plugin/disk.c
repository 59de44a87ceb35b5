/* An out-of-tree hitray shape module: the flat disk x^2 + y^2 <= radius^2 in
 * the plane z = 0, normal +z. It is written the way a user writes a plugin:
 * it sees only the installed <hitray/shape_module.h> and links nothing of
 * libhitray, so one disk.so serves every program that loads it.
 *
 * What the ABI asks of a shape, and where this file does it:
 * - one exported entry point, defined with HR_DEFINE_SHAPE_MODULE (bottom);
 * - a class table (disk_class): name, parameters, create/destroy, bounds and
 *   the hit functions;
 * - reentrant hit functions that allocate nothing and write no globals: the
 *   shape's data is made once by create and only read afterwards;
 * - hits strictly inside (tmin, tmax), sorted, with no NaN or infinity in any
 *   field, and an honest `error` bound (disk_trace).
 *
 * Like Hill's plane, the disk is not a solid: the side its normal points to
 * counts as outside, so a ray moving against the normal (dir.z < 0) enters.
 * Scale, turn and move it with the object's transform; the radius parameter
 * only saves a scale for the common case. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/shape_module.h>

/* What create makes for each disk object. The host pointer is kept so that
 * destroy gives the memory back the way create got it. */
typedef struct disk_shape {
    const hr_host *host;
    double radius;
} disk_shape;

/* The host checks type and the inclusive range [min, max] before create runs,
 * and fills in the default when the caller gives no radius. A range check
 * cannot say "greater than 0", so create refuses 0 itself. The upper limit
 * matches the scene's other sanity limits (materials stop at 1e6 too); a
 * bigger disk is still one scale away, through the object's transform. */
static const hr_param_spec disk_params[] = {
    {
        .name = "radius",
        .type = HR_PARAM_NUMBER,
        .required = 0,
        .default_number = 1.0,
        .min = 0.0,
        .max = 1e6,
        .help = "radius of the disk in object units; must be > 0",
    },
};

/* The host passes every declared parameter (defaults filled in); look it up
 * by name rather than by position, so adding a parameter later cannot
 * silently shift what create reads. */
static const hr_param *find_param(const hr_create_args *args, const char *name)
{
    for (int32_t i = 0; i < args->param_count; i++)
        if (args->params[i].name && strcmp(args->params[i].name, name) == 0) return &args->params[i];
    return NULL;
}

static hr_status disk_create(const hr_create_args *args, void **out_shape)
{
    const hr_param *radius = find_param(args, "radius");
    const double r = radius ? radius->number : 1.0;
    /* `!(r > 0)` also catches -0, which passes the host's range check. The
     * message names the parameter; the host adds the class and module path. */
    if (!(r > 0.0)) {
        if (args->error && args->error_size > 0)
            snprintf(args->error, args->error_size, "parameter 'radius' must be greater than 0, not %g", r);
        return HR_ERROR_PARAMETER;
    }
    disk_shape *disk = args->host->alloc(sizeof *disk);
    if (!disk) return HR_ERROR_OUT_OF_MEMORY;
    disk->host = args->host;
    disk->radius = r;
    *out_shape = disk;
    return HR_OK;
}

static void disk_destroy(void *shape)
{
    if (!shape) return;
    const hr_host *host = ((disk_shape *)shape)->host;
    host->free(shape);
}

static void disk_bounds(const void *shape, hr_bounds *out)
{
    const double r = ((const disk_shape *)shape)->radius;
    out->lo = (hr_vec3){-r, -r, 0.0};
    out->hi = (hr_vec3){r, r, 0.0};
}

/* Bound on |theta_n|, the relative error of n chained roundings of
 * correctly rounded operations (Higham, ch. 3; pbrt-v4): n u / (1 - n u). */
static double gamma_bound(int n)
{
    const double unit_roundoff = 0.5 * 0x1p-52;
    return n * unit_roundoff / (1.0 - n * unit_roundoff);
}

/* The disk has at most one hit per ray, so "every hit", "the nearest hit"
 * and "any hit" are the same answer: one function serves as hit, first_hit
 * and any_hit. */
static hr_status disk_hit(const hr_hit_args *args)
{
    const disk_shape *disk = args->shape;
    const hr_vec3 o = args->ray.origin, d = args->ray.dir;

    /* A ray parallel to the plane (d.z is +0 or -0) never crosses it; one
     * lying in the plane sees the disk edge-on, which has no area. Testing
     * before dividing means no infinity or NaN is ever made here. */
    if (d.z == 0.0) return HR_OK;

    /* o.z + t d.z = 0: one rounding. A tiny d.z can make t infinite; the
     * strict interval test drops that (and t == tmin) before it is used. */
    const double t = -o.z / d.z;
    if (!(t > args->tmin && t < args->tmax)) return HR_OK;

    /* The point: x and y from the ray, z exactly 0, so it lies on the
     * plane of the disk and is off only along it. */
    const hr_vec3 point = {o.x + t * d.x, o.y + t * d.y, 0.0};

    /* Inside or on the rim (the rim belongs to the disk). The test is made
     * on the very point that is reported, so the decision and the point
     * never disagree. hypot neither overflows nor underflows where
     * x*x + y*y would (radius 1e-200, or a point at 1e200); an infinite
     * coordinate (a far ray whose arithmetic overflowed) fails it. */
    if (!(hypot(point.x, point.y) <= disk->radius)) return HR_OK;

    /* Error of the point, per coordinate, taking the ray as exact: t carries
     * one rounding (t~ = t (1 + theta_1)); x~ = fl(o.x + fl(t~ d.x)) is then
     * within gamma(3) (|o.x| + |t d.x|) of the exact o.x + t d.x, and one
     * more gamma covers evaluating this bound with the computed t~. z is
     * exact, so only x and y count. This bounds the distance to the exact
     * intersection point, which is what the host needs to offset new rays. */
    const double error =
        gamma_bound(4) * fmax(fabs(o.x) + fabs(t * d.x), fabs(o.y) + fabs(t * d.y));
    /* Finite point, but |o| + |t d| can still overflow when the two nearly
     * cancel at 1e308: such a hit is dropped, never passed on as infinity. */
    if (!isfinite(error)) return HR_OK;

    /* The host guarantees HR_MIN_HIT_CAPACITY (>= 1) free slots on entry, so
     * one hit needs no host->reserve. */
    hr_hit *hit = &args->out->hits[args->out->count++];
    hit->t = t;
    hit->point = point;
    hit->normal = (hr_vec3){0.0, 0.0, 1.0};
    hit->error = error;
    hit->surface = 0;
    hit->entering = d.z < 0.0; /* moving against the normal, as for the plane */
    /* hit->object belongs to the host: it fills it in. */
    return HR_OK;
}

static const hr_shape_class disk_class = {
    .struct_size = sizeof(hr_shape_class),
    .flags = 0, /* not HR_SHAPE_CLOSED: a flat disk bounds no volume */
    .name = "disk",
    .help = "the disk x^2 + y^2 <= radius^2 in z = 0, normal +z (not a solid)",
    .params = disk_params,
    .param_count = (int32_t)(sizeof disk_params / sizeof disk_params[0]),
    .surface_count = 1,
    .create = disk_create,
    .destroy = disk_destroy,
    .bounds = disk_bounds,
    .hit = disk_hit,
    .first_hit = disk_hit,
    .any_hit = disk_hit,
};

static const hr_shape_class *const disk_classes[] = {&disk_class};

static const hr_module_info disk_module = {
    .struct_size = sizeof(hr_module_info),
    .abi_version = HR_SHAPE_ABI_VERSION,
    .name = "disk",
    .description = "example plugin: a flat disk of a given radius",
    .classes = disk_classes,
    .class_count = 1,
};

/* The one exported symbol. The host compares abi_version with its own and
 * explains a mismatch (naming this file), so the module always answers with
 * its description and leaves that judgement to the host. */
HR_DEFINE_SHAPE_MODULE(host_version, host)
{
    (void)host_version;
    (void)host;
    return &disk_module;
}
