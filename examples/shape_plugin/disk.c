/* An out-of-tree hitray shape module: the flat disk x^2 + y^2 <= radius^2 in
 * the plane z = 0, normal +z. It is written the way a user writes a plugin:
 * it sees only the installed headers (<hitray/shape_module.h>, the ABI, and
 * <hitray/shape_kit.h>, the header-only kit the built-in shapes are made
 * of) and links nothing of libhitray, so one disk.so serves every program
 * that loads it.
 *
 * What the ABI asks of a shape, and where this file does it:
 * - a class table and one exported entry point: SHAPE_CLASS and
 *   SHAPE_MODULE_OF (bottom), which fill in the bounds and hit functions
 *   named disk_* (SHAPE_DEFINE_HIT_MODES makes hit, first_hit and any_hit
 *   from the one disk_trace);
 * - reentrant hit functions that allocate nothing and write no globals: the
 *   shape's data is made once by create and only read afterwards;
 * - hits strictly inside (tmin, tmax), sorted, with no NaN or infinity in any
 *   field (shape_report), and an honest `error` bound (the kit's
 *   shape_z0_fill, the same as the built-in plane's).
 *
 * Like Hill's plane, the disk is not a solid: the side its normal points to
 * counts as outside, so a ray moving against the normal (dir.z < 0) enters.
 * Scale, turn and move it with the object's transform; the radius parameter
 * only saves a scale for the common case. */
#include <math.h>

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

static hr_status disk_create(const hr_create_args *args, void **out_shape)
{
    const hr_param *radius = shape_param(args, "radius");
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

/* The disk has at most one crossing per ray, so every mode gets the same
 * answer; shape_report keeps it only inside (tmin, tmax) (which also drops
 * an infinite t from a tiny d.z) and only when every field is finite. */
static hr_status disk_trace(const hr_hit_args *args, int32_t mode)
{
    const disk_shape *disk = args->shape;
    const hr_ray *ray = &args->ray;

    /* A ray parallel to the plane never crosses it (shape_z0_crossing makes
     * no infinity or NaN); one lying in the plane sees the disk edge-on,
     * which has no area. */
    shape_crossing crossing;
    if (!shape_z0_crossing(ray, &crossing)) return HR_OK;
    if (!(crossing.t > args->tmin && crossing.t < args->tmax)) return HR_OK;

    /* Inside or on the rim (the rim belongs to the disk). The test is made
     * on the very point that is reported, so the decision and the point
     * never disagree. hypot neither overflows nor underflows where
     * x*x + y*y would (radius 1e-200, or a point at 1e200); an infinite
     * coordinate (a far ray whose arithmetic overflowed) fails it. */
    hr_hit probe = {.t = crossing.t};
    shape_z0_fill(ray, &probe);
    if (!(hypot(probe.point.x, probe.point.y) <= disk->radius)) return HR_OK;

    /* The host guarantees HR_MIN_HIT_CAPACITY (>= 1) free slots on entry, so
     * one hit needs no host->reserve. hit->object belongs to the host. */
    return shape_report(args, mode, &crossing, 1, shape_z0_report_fill);
}

SHAPE_DEFINE_HIT_MODES(disk, disk_trace)

/* hr_hit.surface 0, named for `hitray shapes` and the bindings. */
static const char *const disk_surface_names[1] = {"disk"};

/* Not HR_SHAPE_CLOSED: a flat disk bounds no volume. */
SHAPE_CLASS(disk, .name = "disk",
            .help = "the disk x^2 + y^2 <= radius^2 in z = 0, normal +z (not a solid)",
            SHAPE_PARAMS(disk_params), .surface_count = 1, .surface_names = disk_surface_names,
            .create = disk_create, .destroy = disk_destroy);
/* The metadata `hitray shapes` shows (each may be NULL). */
SHAPE_MODULE_OF(disk, "example plugin: a flat disk of a given radius",
                SHAPE_METADATA("1.0.0", "the hitray authors (an example)", NULL));
