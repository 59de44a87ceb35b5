/* An out-of-tree hitray shape module: the flat disk x^2 + y^2 <= radius^2 in
 * the plane z = 0, normal +z. It is written the way a user writes a plugin:
 * it sees only the installed headers (<hitray/shape_module.h>, the ABI, and
 * <hitray/shape_kit.h>, the header-only kit the built-in shapes are made
 * of) and links nothing of libhitray, so one disk.so serves every program
 * that loads it.
 *
 * What the ABI asks of a shape, and where this file does it:
 * - one exported entry point, defined with HR_DEFINE_SHAPE_MODULE (bottom);
 * - a class table (disk_class): name, parameters, create/destroy, bounds and
 *   the hit functions (SHAPE_DEFINE_HIT_MODES makes hit, first_hit and
 *   any_hit from the one disk_trace);
 * - reentrant hit functions that allocate nothing and write no globals: the
 *   shape's data is made once by create and only read afterwards;
 * - hits strictly inside (tmin, tmax), sorted, with no NaN or infinity in any
 *   field (shape_report), and an honest `error` bound (disk_fill).
 *
 * Like Hill's plane, the disk is not a solid: the side its normal points to
 * counts as outside, so a ray moving against the normal (dir.z < 0) enters.
 * Scale, turn and move it with the object's transform; the radius parameter
 * only saves a scale for the common case. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/shape_kit.h>
#include <hitray/shape_module.h>

/* What create makes for each disk object. The host pointer is kept so that
 * destroy gives the memory back the way create got it (as the kit's
 * shape_plain does for a class without parameters). */
typedef struct disk_shape {
    const hr_host *host;
    double radius;
} disk_shape;

/* The host checks type and the range (0, 1e6] before create runs (the
 * excluded minimum refuses 0 and -0), and fills in the default when the
 * caller gives no radius. The upper limit matches the scene's other sanity
 * limits (materials stop at 1e6 too); a bigger disk is still one scale away,
 * through the object's transform. */
static const hr_param_spec disk_params[] = {
    {
        .name = "radius",
        .type = HR_PARAM_NUMBER,
        .required = 0,
        .default_number = 1.0,
        .min = 0.0,
        .max = 1e6,
        .flags = HR_PARAM_MIN_EXCLUSIVE,
        .help = "radius of the disk in object units",
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
    shape_set_bounds(out, -r, -r, 0.0, r, r, 0.0);
}

/* The point, normal and error of a crossing of z = 0 at hit->t: x and y
 * from the ray, z exactly 0, so the point lies on the plane of the disk and
 * is off only along it. t carries one rounding (-o.z / d.z), and
 * shape_ray_point_error bounds the rounding of o + t d for it (gamma(4) of
 * |o| + |t d|): the distance to the exact intersection point, which is what
 * the host needs to offset new rays. */
static void disk_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    (void)shape;
    hit->point = shape_vec3(ray->origin.x + hit->t * ray->dir.x,
                            ray->origin.y + hit->t * ray->dir.y, 0.0);
    hit->normal = shape_vec3(0.0, 0.0, 1.0);
    hit->error = shape_ray_point_error(ray, hit->t, 1);
}

/* The disk has at most one crossing per ray, so every mode gets the same
 * answer; shape_report keeps it only inside (tmin, tmax) (which also drops
 * an infinite t from a tiny d.z) and only when every field is finite. */
static hr_status disk_trace(const hr_hit_args *args, int32_t mode)
{
    const disk_shape *disk = args->shape;
    const hr_ray *ray = &args->ray;

    /* A ray parallel to the plane (d.z is +0 or -0) never crosses it; one
     * lying in the plane sees the disk edge-on, which has no area. Testing
     * before dividing means no infinity or NaN is ever made here. */
    if (ray->dir.z == 0.0) return HR_OK;
    shape_crossing crossing = {-ray->origin.z / ray->dir.z, 0, ray->dir.z < 0.0};
    if (!(crossing.t > args->tmin && crossing.t < args->tmax)) return HR_OK;

    /* Inside or on the rim (the rim belongs to the disk). The test is made
     * on the very point that is reported, so the decision and the point
     * never disagree. hypot neither overflows nor underflows where
     * x*x + y*y would (radius 1e-200, or a point at 1e200); an infinite
     * coordinate (a far ray whose arithmetic overflowed) fails it. */
    hr_hit probe = {.t = crossing.t};
    disk_fill(disk, ray, &probe);
    if (!(hypot(probe.point.x, probe.point.y) <= disk->radius)) return HR_OK;

    /* The host guarantees HR_MIN_HIT_CAPACITY (>= 1) free slots on entry, so
     * one hit needs no host->reserve. hit->object belongs to the host. */
    return shape_report(args, mode, &crossing, 1, disk_fill);
}

SHAPE_DEFINE_HIT_MODES(disk, disk_trace)

/* hr_hit.surface 0, named for `hitray shapes` and the bindings. */
static const char *const disk_surface_names[1] = {"disk"};

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
    .first_hit = disk_first_hit,
    .any_hit = disk_any_hit,
    .surface_names = disk_surface_names,
};

static const hr_shape_class *const disk_classes[] = {&disk_class};

static const hr_module_info disk_module = {
    .struct_size = sizeof(hr_module_info),
    .abi_version = HR_SHAPE_ABI_VERSION,
    .name = "disk",
    .description = "example plugin: a flat disk of a given radius",
    .classes = disk_classes,
    .class_count = 1,
    /* Metadata that `hitray shapes` shows (each may be NULL). */
    .version = "1.0.0",
    .author = "the hitray authors (an example)",
    .url = NULL,
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
