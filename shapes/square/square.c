/* The generic square of Hill's chapter 12: z = 0 with |x| <= 1, |y| <= 1,
 * normal +z.
 *
 * A plane hit (shape_z0_crossing) kept when its point is inside the square.
 * The edges belong to the square (<=), tested on the very point that is
 * reported, so the decision and the reported point never disagree. Not a
 * solid: moving against the normal is entering, as for the plane. */
#include <math.h>

#include <hitray/shape_module.h>

#include <hitray/shape_kit.h>
#include "../common/shape_builtin.h"
#include "../common/shape_uv.h"
#include "../common/shape_z0.h"

static void square_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    (void)shape;
    shape_z0_fill(ray, hit);
}

static hr_status square_trace(const hr_hit_args *args, int32_t mode)
{
    shape_crossing crossing;
    int count = shape_z0_crossing(&args->ray, &crossing);
    /* Only a crossing the report could pass on is worth the bounds test. */
    if (count && crossing.t > args->tmin && crossing.t < args->tmax) {
        hr_hit probe;
        probe.t = crossing.t;
        shape_z0_fill(&args->ray, &probe);
        if (!(fabs(probe.point.x) <= 1.0 && fabs(probe.point.y) <= 1.0)) count = 0;
    }
    return shape_report(args, mode, &crossing, count, square_fill);
}

SHAPE_DEFINE_HIT_MODES(square, square_trace)

static void square_bounds(const void *shape, hr_bounds *out)
{
    (void)shape;
    shape_set_bounds(out, -1.0, -1.0, 0.0, 1.0, 1.0, 0.0);
}

/* (u, v): x and y taken from [-1, 1] to [0, 1], so an image covers the
 * square once with its default parameters. */
static int32_t square_uv(const void *shape, const hr_hit *hit, double uv[2])
{
    (void)shape;
    SHAPE_UV_PROBE(hit, uv);
    uv[0] = 0.5 * (hit->point.x + 1.0);
    uv[1] = 0.5 * (hit->point.y + 1.0);
    return 1;
}

static const char *const square_surface_names[1] = {"square"};

static const hr_shape_class square_class = {
    .struct_size = sizeof(hr_shape_class),
    .flags = 0,
    .name = "square",
    .help = "the square z = 0, |x| <= 1, |y| <= 1, normal +z (not a solid)",
    .params = NULL,
    .param_count = 0,
    .surface_count = 1,
    .surface_names = square_surface_names,
    .create = shape_plain_create,
    .destroy = shape_plain_destroy,
    .bounds = square_bounds,
    .hit = square_hit,
    .surface_uv = square_uv,
    .first_hit = square_first_hit,
    .any_hit = square_any_hit,
};

static const hr_shape_class *const square_classes[] = {&square_class};

static const hr_module_info square_module = {
    .struct_size = sizeof(hr_module_info),
    .abi_version = HR_SHAPE_ABI_VERSION,
    .name = "square",
    .description = "Hill's generic square: z = 0, |x|, |y| <= 1",
    .classes = square_classes,
    .class_count = 1,
    SHAPE_BUILTIN_METADATA,
};

/* The host checks abi_version and explains a mismatch. */
HR_DEFINE_SHAPE_MODULE(host_version, host)
{
    (void)host_version;
    (void)host;
    return &square_module;
}
