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
    return shape_report(args, mode, &crossing, count, shape_z0_report_fill);
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

SHAPE_CLASS(square, .name = "square",
            .help = "the square z = 0, |x| <= 1, |y| <= 1, normal +z (not a solid)",
            .surface_count = 1, .surface_names = square_surface_names, .create = shape_plain_create,
            .destroy = shape_plain_destroy, .surface_uv = square_uv);
SHAPE_MODULE_OF(square, "Hill's generic square: z = 0, |x|, |y| <= 1", SHAPE_BUILTIN_METADATA);
