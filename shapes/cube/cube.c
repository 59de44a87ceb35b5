/* The generic cube of Hill's chapter 12: corners (+-1, +-1, +-1).
 * Surfaces 0..5 are the faces +x, -x, +y, -y, +z, -z.
 *
 * Hit: the slab method. The cube is the intersection of the slabs
 * |x| <= 1, |y| <= 1, |z| <= 1; the ray's span in each slab is found with
 * shape_slab_span (which handles zero direction components, +0 and -0 alike,
 * without dividing), and the cube's span is their intersection. Entering and
 * exiting faces come from whichever slab ends the span, so they are always
 * consistent, and a ray through an edge or a corner is entered and left
 * exactly once. Faces are closed: a ray grazing a face from within its plane
 * is inside that slab, and a ray touching only an edge is a zero-length visit
 * (enter and leave at the same t).
 *
 * Ownership of an edge or corner hit at an exact tie: the slabs are
 * intersected in the order x, y, z and a tie keeps the earlier one, so the
 * x faces own their edges and corners, then the y faces.
 *
 * Point: origin + t dir with the face coordinate set exactly to +-1 and the
 * other two clamped into [-1, 1] (a projection onto the face, which can only
 * move the point closer to the exact one, as that lies on the face). t is
 * fl(fl(+-1 - o) / d), two roundings, so the error is shape_ray_point_error
 * with 2. */
#include <math.h>

#include <hitray/shape_module.h>

#include <hitray/shape_kit.h>
#include "../common/shape_builtin.h"

/* Face ids: 2 axis for the +1 face of an axis, 2 axis + 1 for the -1 face. */
static shape_span cube_axis_span(double o, double d, int axis)
{
    return shape_slab_span(o, d, -1.0, 2 * axis + 1, 1.0, 2 * axis);
}

static int cube_crossings(const hr_ray *ray, shape_crossing out[2])
{
    const hr_vec3 o = ray->origin, d = ray->dir;
    shape_span span = cube_axis_span(o.x, d.x, 0);
    span = shape_span_intersect(span, cube_axis_span(o.y, d.y, 1));
    span = shape_span_intersect(span, cube_axis_span(o.z, d.z, 2));
    return shape_span_crossings(span, out);
}

static void cube_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    (void)shape;
    const int axis = hit->surface / 2;
    const double side = hit->surface % 2 == 0 ? 1.0 : -1.0;
    hr_vec3 p = shape_ray_at(ray, hit->t);
    p = shape_vec3(shape_clamp(p.x, -1.0, 1.0), shape_clamp(p.y, -1.0, 1.0),
                   shape_clamp(p.z, -1.0, 1.0));
    hr_vec3 n = shape_vec3(0.0, 0.0, 0.0);
    if (axis == 0) p.x = side, n.x = side;
    else if (axis == 1) p.y = side, n.y = side;
    else p.z = side, n.z = side;
    hit->point = p;
    hit->normal = n;
    hit->error = shape_ray_point_error(ray, hit->t, 2);
}

static hr_status cube_trace(const hr_hit_args *args, int32_t mode)
{
    shape_crossing crossings[2];
    const int count = cube_crossings(&args->ray, crossings);
    return shape_report(args, mode, crossings, count, cube_fill);
}

SHAPE_DEFINE_HIT_MODES(cube, cube_trace)

static void cube_bounds(const void *shape, hr_bounds *out)
{
    (void)shape;
    shape_set_bounds(out, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0);
}

/* (u, v) per face, each face's two other coordinates taken from [-1, 1]
 * to [0, 1] and oriented so that an image reads the right way round seen
 * from outside: on the four side faces v runs up +z and u to the viewer's
 * right; on the top (+z) and bottom (-z) v runs along +y. Every face shows
 * the whole image once with the default parameters. */
static int32_t cube_uv(const void *shape, const hr_hit *hit, double uv[2])
{
    (void)shape;
    SHAPE_UV_PROBE(hit, uv);
    const hr_vec3 p = hit->point;
    /* Per surface (+x, -x, +y, -y, +z, -z): the coordinate along u and its
     * sign, then the coordinate along v. */
    static const struct {
        int u_axis;
        double u_sign;
        int v_axis;
    } faces[6] = {{1, 1, 2}, {1, -1, 2}, {0, -1, 2}, {0, 1, 2}, {0, 1, 1}, {0, -1, 1}};
    const int f = hit->surface >= 0 && hit->surface < 6 ? hit->surface : 0;
    const double c[3] = {p.x, p.y, p.z};
    uv[0] = 0.5 * (faces[f].u_sign * c[faces[f].u_axis] + 1.0);
    uv[1] = 0.5 * (c[faces[f].v_axis] + 1.0);
    return 1;
}

/* Surface i is the face of its axis and sign (cube_fill's order). */
static const char *const cube_surface_names[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

SHAPE_CLASS(cube, .flags = HR_SHAPE_CLOSED, .name = "cube",
            .help = "cube with corners (+-1, +-1, +-1); surfaces +x, -x, +y, -y, +z, -z",
            .surface_count = 6, .surface_names = cube_surface_names, .create = shape_plain_create,
            .destroy = shape_plain_destroy, .surface_uv = cube_uv);
SHAPE_MODULE_OF(cube, "Hill's generic cube: corners (+-1, +-1, +-1)", SHAPE_BUILTIN_METADATA);
