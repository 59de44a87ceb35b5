/* The generic plane of Hill's chapter 12: all of z = 0, normal +z.
 *
 * Not a solid: the side the normal points to counts as outside, so a ray
 * moving against the normal enters. Hit: t = -o.z / d.z (one rounding; see
 * shape_z0_crossing for parallel rays and shape_z0_fill for the point and
 * its error bound). Unbounded: its bounds are infinite in x and y. */
#include <math.h>

#include <hitray/shape_module.h>

#include <hitray/shape_kit.h>
#include "../common/shape_builtin.h"

static hr_status plane_trace(const hr_hit_args *args, int32_t mode)
{
    shape_crossing crossing;
    const int count = shape_z0_crossing(&args->ray, &crossing);
    return shape_report(args, mode, &crossing, count, shape_z0_report_fill);
}

SHAPE_DEFINE_HIT_MODES(plane, plane_trace)

static void plane_bounds(const void *shape, hr_bounds *out)
{
    (void)shape;
    shape_set_bounds(out, -INFINITY, -INFINITY, 0.0, INFINITY, INFINITY, 0.0);
}

/* (u, v): x and y themselves, so an image tiles the plane in unit squares
 * with its default parameters. */
static int32_t plane_uv(const void *shape, const hr_hit *hit, double uv[2])
{
    (void)shape;
    SHAPE_UV_PROBE(hit, uv);
    uv[0] = hit->point.x;
    uv[1] = hit->point.y;
    return 1;
}

static const char *const plane_surface_names[1] = {"plane"};

SHAPE_CLASS(plane, .name = "plane", .help = "the whole plane z = 0, normal +z (not a solid)",
            .surface_count = 1, .surface_names = plane_surface_names, .create = shape_plain_create,
            .destroy = shape_plain_destroy, .surface_uv = plane_uv);
SHAPE_MODULE_OF(plane, "Hill's generic plane: z = 0", SHAPE_BUILTIN_METADATA);
