/* Hill's tapered cylinder and its two special cases:
 *   taperedCylinder s   radius 1 at z = 0, radius s at z = 1 (s >= 0)
 *   cylinder            s = 1
 *   cone                s = 0 (the apex at (0, 0, 1))
 * and the wall alone, open at both ends, as NFF's cones and cylinders are:
 *   openTaperedCylinder s   the same wall, no disks; no solid (see
 *                           open_crossings below)
 * and the thick-walled tube of Hill's ECE661 reader (the book's chapter-6
 * ray tracer):
 *   taperedTube s t     taperedCylinder s with a coaxial hole whose radius
 *                       is 1 - t at z = 0 and s - t at z = 1 (the inner
 *                       wall parallel to the outer, t across the axis);
 *                       the base and cap are annuli (see tube_crossings)
 * A closed solid: the wall x^2 + y^2 = (1 + (s-1) z)^2 for 0 <= z <= 1
 * (surface 0), the base disk z = 0, radius 1 (surface 1), and the cap disk
 * z = 1, radius s (surface 2; absent when s = 0, where it is the apex, a
 * point of the wall).
 *
 * The solid is the intersection of the slab 0 <= z <= 1 and the inside of
 * the wall's quadric, Q(p) = x^2 + y^2 - w(z)^2 <= 0 with w(z) = 1 + k z,
 * k = s - 1 (within the slab w >= 0, so Q <= 0 there is exactly our frustum
 * and never the cone's other nappe). A ray's span in the solid is the
 * intersection of its span in the slab (shape_slab_span) and in the quadric
 * (wall_span below). The frustum is convex, so that is one span: one
 * entering and one exiting hit, or none.
 *
 * Seam ownership: the slab is intersected first, so at an exact tie between
 * a disk time and a wall time the disk owns the rim (shape_span_intersect
 * keeps the earlier region on ties). Away from exact ties, the surface whose
 * constraint binds owns the hit, so a sweep across the rim switches from one
 * surface to the other with no gap and no double hit. For the cone, a span
 * end on the z = 1 plane can only be the apex, and is reported as the wall.
 *
 * The quadric along the ray. With u = (o.x, o.y), e = (d.x, d.y),
 * w0 = w(o.z) and omega = k d.z (the rate of w along the ray):
 *   Q(t) = |u + t e|^2 - (w0 + omega t)^2 = a t^2 + 2 b t + c,
 *   a = |e|^2 - omega^2,  b = u.e - w0 omega,  c = |u|^2 - w0^2,
 * and, by Lagrange's identity (the analogue of the sphere's |d|^2 - |o x d|^2),
 *   b^2 - a c = |w0 e - omega u|^2 - (u x e)^2,
 * whose terms are differences of products (Kahan, 1.5 ulp each) instead of
 * the two huge nearly equal products of b^2 - a c for a far ray.
 * - a > 0: inside between the roots.
 * - a < 0 (the ray is steeper than the wall): Q <= 0 on two half-lines, one
 *   in each nappe; ours is where w grows toward +infinity, so the half-line
 *   after the larger root when omega > 0, before the smaller when omega < 0.
 *   A line always meets the double cone here (it must pass w = 0, where
 *   Q >= 0), so a discriminant that rounding made negative is clamped to 0.
 *   A ray through the apex has a double root there: it is one crossing, not
 *   a tangent, and the half-line rule makes it one.
 * - a == 0 (parallel to a generator line, or to the axis of a cylinder):
 *   Q is linear or constant.
 *
 * Points and errors.
 * Wall: p = origin + t dir, z clamped into [0, 1], then moved radially onto
 * the wall at that height: (x, y) scaled by w(z) / sqrt(x^2 + y^2) (pbrt's
 * re-projection for cylinders, with the tapered radius). The exact surface
 * point is (x, y) w(z) / rho at the same z. w~ = fma(k~, z, 1) with
 * k~ = (s - 1)(1 + d) is within gamma(2) R of w, R = 1 + |k| z;
 * rho~ = rho (1 + theta_2); the scale and product add two roundings, so
 * x~ - x w / rho = (x / rho)(w~ (1 + theta_4) - w), at most
 * gamma(2) R + gamma(4) R (1 + gamma(2)) <= gamma(7) R. We report gamma(8) R.
 * (On the axis, only at the apex, rho = 0: the point stays on the axis and
 * w~ is added to the bound.) Like the sphere's, this bounds the distance to
 * the surface, not the displacement along it.
 * Disks: x, y from origin + t dir, z exactly 0 or 1; t = fl(fl(h - o.z)/d.z)
 * has two roundings, see shape_ray_point_error. A point outside the disk's
 * radius is moved radially onto its rim, as the wall's z is clamped into
 * the slab (see disk_fill).
 * Normals: the wall's is the gradient of Q / 2, (x, y, -k w) (+z at the
 * apex, where the gradient vanishes); the disks' are -z and +z. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/shape_module.h>

#include <hitray/shape_kit.h>
#include "../common/shape_builtin.h"

#define SURFACE_WALL 0
#define SURFACE_BASE 1
#define SURFACE_CAP 2
#define SURFACE_INNER 3 /* taperedTube's inner wall */

#define TAPER_MAX 1e6

typedef struct tapered_cylinder {
    const hr_host *host;
    double s;     /* radius at z = 1 */
    double slope; /* k = s - 1: the wall's radius is w(z) = 1 + k z */
    double inner; /* taperedTube: the inner wall's radius at z = 0, fl(1 - t); else 0 */
} tapered_cylinder;

/* The span of the ray inside the quadric Q <= 0, in our nappe, for the wall
 * whose radius is w(z) = r0 + k z (r0 = 1: the outer wall; the tube's inner
 * wall has r0 = 1 - t, the same slope, and w >= 0 in the slab likewise).
 *
 * The coefficients are products of two direction components, which
 * underflow for a direction shorter than about 1e-154: a ray 1e-308 long
 * then had a == b == 0 and was taken for one parallel to the axis, inside
 * the wall everywhere, and left through a cap disk at a point far outside
 * the disk. The roots scale with the direction (d' = 2^e d has roots
 * t' = t / 2^e), so the quadric is solved for the direction scaled by a
 * power of two to a largest component in [1, 2), and the roots are scaled
 * back. Both scalings are exact (barring overflow of a root, which then is
 * infinite and never reported), so every other ray gets the same bits as
 * before. */
SHAPE_FMA_DISPATCH(shape_span, wall_span, (const tapered_cylinder *shape, double r0, const hr_ray *ray),
                   (shape, r0, ray))
{
    const hr_vec3 o = ray->origin;
    int exponent = 0;
    if (shape_vec3_scale_exponent(ray->dir, &exponent)) exponent -= 1; /* to [1, 2) */
    const hr_vec3 d = shape_vec3_ldexp(ray->dir, -exponent);
    const double k = shape->slope;
    const double w0 = fma(k, o.z, r0);
    const double omega = k * d.z;

    shape_sum a = shape_sum_start(0.0), b = shape_sum_start(0.0), c = shape_sum_start(0.0);
    shape_sum_add_product(&a, d.x, d.x);
    shape_sum_add_product(&a, d.y, d.y);
    shape_sum_add_product(&a, -omega, omega);
    shape_sum_add_product(&b, o.x, d.x);
    shape_sum_add_product(&b, o.y, d.y);
    shape_sum_add_product(&b, -w0, omega);
    shape_sum_add_product(&c, o.x, o.x);
    shape_sum_add_product(&c, o.y, o.y);
    shape_sum_add_product(&c, -w0, w0);

    const double cross = shape_difference_of_products(o.x, d.y, o.y, d.x);
    const double vx = shape_difference_of_products(w0, d.x, omega, o.x);
    const double vy = shape_difference_of_products(w0, d.y, omega, o.y);
    shape_sum disc = shape_sum_start(0.0);
    shape_sum_add_product(&disc, vx, vx);
    shape_sum_add_product(&disc, vy, vy);
    shape_sum_add_product(&disc, -cross, cross);

    const double qa = shape_sum_value(a), qb = shape_sum_value(b), qc = shape_sum_value(c);
    double qdisc = shape_sum_value(disc);
    /* Coefficients overflow only for absurdly far rays: call it a miss. */
    if (!(isfinite(qa) && isfinite(qb) && isfinite(qc) && isfinite(qdisc)))
        return shape_span_nowhere();
    if (qa < 0.0 && qdisc < 0.0) qdisc = 0.0;

    double roots[2];
    const int count = shape_solve_half_quadratic(qa, qb, qc, qdisc, roots);
    for (int i = 0; i < count; i++) roots[i] = shape_ldexp(roots[i], -exponent);
    if (qa > 0.0)
        return count == 2 ? shape_span_make(roots[0], SURFACE_WALL, roots[1], SURFACE_WALL)
                          : shape_span_nowhere();
    if (qa < 0.0) {
        if (count != 2) return shape_span_nowhere(); /* cannot happen: disc >= 0 */
        return omega > 0.0 ? shape_span_make(roots[1], SURFACE_WALL, INFINITY, SHAPE_NO_SURFACE)
                           : shape_span_make(-INFINITY, SHAPE_NO_SURFACE, roots[0], SURFACE_WALL);
    }
    /* qa == 0: Q(t) = 2 b t + c, inside where that is <= 0. */
    if (count == 1)
        return qb > 0.0 ? shape_span_make(-INFINITY, SHAPE_NO_SURFACE, roots[0], SURFACE_WALL)
                        : shape_span_make(roots[0], SURFACE_WALL, INFINITY, SHAPE_NO_SURFACE);
    return qc <= 0.0 ? shape_span_everywhere() : shape_span_nowhere();
}

static int tapered_crossings(const tapered_cylinder *shape, const hr_ray *ray,
                             shape_crossing out[2])
{
    shape_span span =
        shape_slab_span(ray->origin.z, ray->dir.z, 0.0, SURFACE_BASE, 1.0, SURFACE_CAP);
    if (shape_span_is_empty(span)) return 0;
    span = shape_span_intersect(span, wall_span(shape, 1.0, ray));
    const int count = shape_span_crossings(span, out);
    if (shape->s == 0.0)
        for (int i = 0; i < count; i++)
            if (out[i].surface == SURFACE_CAP) out[i].surface = SURFACE_WALL;
    return count;
}

/* The open wall: where the ray crosses the quadric (each finite end of
 * its span in our nappe) at a height within the slab 0 <= z <= 1. A ray
 * entering the quadric's inside is entering; the two crossings need not
 * alternate with anything else, since no disk closes the tube (a ray along
 * the axis of an open cylinder crosses nothing). The slab test is on the
 * height of the crossing point, z = o.z + t d.z, which is the wall's own
 * reading of the rim: wall_fill clamps that same z into [0, 1]. */
static int open_crossings(const tapered_cylinder *shape, const hr_ray *ray,
                          shape_crossing out[2])
{
    const shape_span span = wall_span(shape, 1.0, ray);
    if (shape_span_is_empty(span)) return 0;
    const double t[2] = {span.t_in, span.t_out};
    const int32_t surface[2] = {span.surface_in, span.surface_out};
    int count = 0;
    for (int i = 0; i < 2; i++) {
        if (surface[i] != SURFACE_WALL || !isfinite(t[i])) continue;
        const double z = ray->origin.z + t[i] * ray->dir.z;
        if (!(z >= 0.0 && z <= 1.0)) continue;
        out[count].t = t[i];
        out[count].surface = SURFACE_WALL;
        out[count].entering = i == 0;
        count++;
    }
    return count;
}

/* The wall of radius r0 + k z (see wall_span); the bound of the header's
 * analysis with R = r0 + |k| z. */
SHAPE_FMA_DISPATCH_VOID(wall_fill, (const tapered_cylinder *shape, double r0, const hr_ray *ray, hr_hit *hit),
                        (shape, r0, ray, hit))
{
    const double k = shape->slope;
    const hr_vec3 p = shape_ray_at(ray, hit->t);
    const double z = shape_clamp(p.z, 0.0, 1.0);
    const double radius = fma(k, z, r0);
    /* (x, y) rescaled before rho is taken, as the sphere does: below 1e-154
     * their squares are subnormal and rho loses digits. */
    const hr_vec3 q = shape_vec3_rescaled(shape_vec3(p.x, p.y, 0.0));
    const double rho = sqrt(q.x * q.x + q.y * q.y);
    const double bound = shape_gamma(8) * (r0 + fabs(k) * z);
    if (rho > 0.0) {
        const double scale = radius / rho;
        hit->point = shape_vec3(q.x * scale, q.y * scale, z);
        hit->error = bound;
    } else {
        hit->point = shape_vec3(0.0, 0.0, z);
        hit->error = bound + radius;
    }
    hit->normal = shape_vec3(hit->point.x, hit->point.y, -k * radius);
    if (hit->normal.x == 0.0 && hit->normal.y == 0.0 && hit->normal.z == 0.0)
        hit->normal = shape_vec3(0.0, 0.0, 1.0);
}

/* The radius of the tube's inner wall at z = 1, where it bounds the cap's
 * annulus: r0 + k, s - t up to rounding (0 for the solid classes). */
static double tube_cap_inner(const tapered_cylinder *shape)
{
    return shape->inner > 0.0 ? fmax(shape->inner + shape->slope, 0.0) : 0.0;
}

/* A disk's time is an end of the span of the slab that the wall's span
 * did not cut off, so the ray is inside the wall there only as far as
 * rounding of the wall's roots can tell. For s >> 1 the wall meets both
 * disks at an angle of about 1 / |k|, and a point a distance e from the
 * quadric may lie e |k| outside the disk: with s = 1e6, a ray crossing
 * z = 1 just 5e-7 outside the cap's rim, and the quadric 5e-13 above it,
 * had a wall root one ulp before the cap's time and left through the cap
 * 5e-7 off it, against a bound of 1e-9. The root's error has no bound
 * here, so the point is clamped onto the disk instead, as wall_fill clamps
 * z: (x, y) scaled by r / rho where rho > r, on q = (x, y) 2^-e scaled
 * exactly to a largest component in [0.5, 1). There rho~ = |q| (1 +
 * theta_2), scale~ = (r / |q|)(1 + theta_3), x' = qx r / |q| (1 + theta_4),
 * each coordinate within gamma(4) r of the rim point (qx, qy) r / |q|; a
 * cap radius s below DBL_MIN may round the scale and the product to
 * subnormals, off by DBL_TRUE_MIN / 2 each, so the bound is
 * gamma(4) r + DBL_TRUE_MIN. The ray-point bound is kept where it is
 * larger: the clamp is a projection onto the disk, which brings the point
 * no farther from any point of the disk, an exact crossing near the rim
 * included. A point whose rho~ rounded to r or below lies within
 * gamma(3) r outside, which that bound (at least gamma(5) r / sqrt(2))
 * covers. */
static inline __attribute__((always_inline)) void disk_fill(const tapered_cylinder *shape, const hr_ray *ray,
                                                            hr_hit *hit, const int tube)
{
    const int cap = hit->surface == SURFACE_CAP;
    const double r = cap ? shape->s : 1.0;
    const double x = ray->origin.x + hit->t * ray->dir.x;
    const double y = ray->origin.y + hit->t * ray->dir.y;
    hit->point = shape_vec3(x, y, cap ? 1.0 : 0.0);
    hit->normal = shape_vec3(0.0, 0.0, cap ? 1.0 : -1.0);
    hit->error = shape_ray_point_error(ray, hit->t, 2);
    int exponent;
    if (!shape_vec3_scale_exponent(shape_vec3(x, y, 0.0), &exponent)) return;
    const hr_vec3 q = shape_vec3_ldexp(shape_vec3(x, y, 0.0), -exponent);
    const double rho = sqrt(q.x * q.x + q.y * q.y);
    /* The tube's annuli: a point inside the hole is moved out onto the
     * inner rim the same way (the same bound with the inner radius). A
     * cylinder's disks have no hole, and its copy no such test. */
    double rim;
    if (rho > shape_ldexp(r, -exponent)) rim = r;
    else if (tube && rho > 0.0 && rho < shape_ldexp(cap ? tube_cap_inner(shape) : shape->inner, -exponent))
        rim = cap ? tube_cap_inner(shape) : shape->inner;
    else return;
    const double scale = rim / rho;
    hit->point.x = q.x * scale;
    hit->point.y = q.y * scale;
    hit->error = fmax(hit->error, shape_gamma(4) * rim + DBL_TRUE_MIN);
}

static void tapered_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    if (hit->surface == SURFACE_WALL) wall_fill(shape, 1.0, ray, hit);
    else disk_fill(shape, ray, hit, 0);
}

static hr_status tapered_trace(const hr_hit_args *args, int32_t mode)
{
    shape_crossing crossings[2];
    const int count = tapered_crossings(args->shape, &args->ray, crossings);
    return shape_report(args, mode, crossings, count, tapered_fill);
}

SHAPE_DEFINE_HIT_MODES(tapered, tapered_trace)

static void open_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    wall_fill(shape, 1.0, ray, hit);
}

static hr_status open_trace(const hr_hit_args *args, int32_t mode)
{
    shape_crossing crossings[2];
    const int count = open_crossings(args->shape, &args->ray, crossings);
    return shape_report(args, mode, crossings, count, open_fill);
}

SHAPE_DEFINE_HIT_MODES(open, open_trace)

/* taperedTube: the frustum with a coaxial hole. The solid is the outer
 * frustum (slab, then the outer wall, as tapered_crossings) minus the inner
 * one (the same slab, then the inner wall). The inner frustum lies inside
 * the outer, touching it only on the slab's faces, and both are convex, so
 * the ray's visit is the outer span with the inner span cut out of it: up
 * to two pieces, four crossings. Where the ray enters (or leaves) the hole
 * through the base or cap, the two spans share that end bit for bit (one
 * shape_slab_span), the piece between them is empty and is dropped: the
 * ray passes through the hole without touching the tube. A piece that
 * rounding turned inside out (a hair-thin wall) is dropped likewise. */
static int tube_crossings(const tapered_cylinder *shape, const hr_ray *ray, shape_crossing out[4])
{
    const shape_span slab =
        shape_slab_span(ray->origin.z, ray->dir.z, 0.0, SURFACE_BASE, 1.0, SURFACE_CAP);
    if (shape_span_is_empty(slab)) return 0;
    const shape_span outer = shape_span_intersect(slab, wall_span(shape, 1.0, ray));
    if (shape_span_is_empty(outer)) return 0;
    shape_span hole = shape_span_intersect(slab, wall_span(shape, shape->inner, ray));
    if (shape_span_is_empty(hole)) return shape_span_crossings(outer, out);
    if (hole.surface_in == SURFACE_WALL) hole.surface_in = SURFACE_INNER;
    if (hole.surface_out == SURFACE_WALL) hole.surface_out = SURFACE_INNER;
    const shape_span pieces[2] = {
        shape_span_make(outer.t_in, outer.surface_in, hole.t_in, hole.surface_in),
        shape_span_make(hole.t_out, hole.surface_out, outer.t_out, outer.surface_out)};
    int count = 0;
    for (int i = 0; i < 2; i++)
        if (pieces[i].t_in < pieces[i].t_out) count += shape_span_crossings(pieces[i], out + count);
    return count;
}

/* The inner wall bounds the solid from inside: its outward normal points
 * toward the axis, the inner quadric's gradient reversed. */
static void tube_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    const tapered_cylinder *c = shape;
    if (hit->surface == SURFACE_WALL) {
        wall_fill(c, 1.0, ray, hit);
    } else if (hit->surface == SURFACE_INNER) {
        wall_fill(c, c->inner, ray, hit);
        hit->normal = shape_vec3(-hit->normal.x, -hit->normal.y, -hit->normal.z);
    } else {
        disk_fill(c, ray, hit, 1);
    }
}

static hr_status tube_trace(const hr_hit_args *args, int32_t mode)
{
    shape_crossing crossings[4];
    const int count = tube_crossings(args->shape, &args->ray, crossings);
    return shape_report(args, mode, crossings, count, tube_fill);
}

SHAPE_DEFINE_HIT_MODES(tube, tube_trace)

static void tapered_bounds(const void *shape, hr_bounds *out)
{
    const tapered_cylinder *c = shape;
    const double r = c->s > 1.0 ? c->s : 1.0;
    out->lo = shape_vec3(-r, -r, 0.0);
    out->hi = shape_vec3(r, r, 1.0);
}

/* The box of the two end disks under m (the wall is their convex hull):
 * a disk of radius r about c spanned by the images u, v of the x and y
 * axes reaches c_i +- r sqrt(u_i^2 + v_i^2) along world axis i. The
 * rounding of those few operations is far below the pad of 16 ulps of the
 * terms' magnitudes added here. */
static void tapered_transformed_bounds(const void *shape, const double m[16], hr_bounds *out)
{
    const tapered_cylinder *c = shape;
    double lo[3], hi[3];
    for (int i = 0; i < 3; i++) {
        const double *row = m + 4 * i;
        const double reach = sqrt(row[0] * row[0] + row[1] * row[1]);
        const double base = row[3], cap = row[2] + row[3];
        const double base_lo = base - reach, base_hi = base + reach;
        const double cap_lo = cap - c->s * reach, cap_hi = cap + c->s * reach;
        const double pad = 16.0 * DBL_EPSILON * (fabs(row[2]) + fabs(row[3]) + (1.0 + c->s) * reach);
        lo[i] = (base_lo < cap_lo ? base_lo : cap_lo) - pad;
        hi[i] = (base_hi > cap_hi ? base_hi : cap_hi) + pad;
    }
    out->lo = shape_vec3(lo[0], lo[1], lo[2]);
    out->hi = shape_vec3(hi[0], hi[1], hi[2]);
}

/* --- Creation ----------------------------------------------------------------- */

static hr_status tapered_make(const hr_create_args *args, double s, void **out_shape)
{
    tapered_cylinder *shape = args->host->alloc(sizeof *shape);
    if (!shape) return HR_ERROR_OUT_OF_MEMORY;
    shape->host = args->host;
    shape->s = s;
    shape->slope = s - 1.0;
    shape->inner = 0.0;
    *out_shape = shape;
    return HR_OK;
}

/* The host has checked the range already; the module still refuses what it
 * cannot draw, in case a host (or a test) passes something else. */
static hr_status tapered_cylinder_create(const hr_create_args *args, void **out_shape)
{
    const hr_param *s_param = shape_param(args, "s");
    const double s = s_param ? s_param->number : 1.0;
    if (!(s >= 0.0 && s <= TAPER_MAX)) {
        if (args->error && args->error_size)
            snprintf(args->error, args->error_size,
                     "parameter 's' = %g must be a number in [0, %g]", s, TAPER_MAX);
        return HR_ERROR_PARAMETER;
    }
    return tapered_make(args, s, out_shape);
}

/* taperedTube s t: 0 < t < 1 keeps the hole's base radius 1 - t above 0,
 * t <= s its cap radius s - t at or above 0 (t = s: the hole narrows to a
 * point at the cap's centre). The host has checked each range alone. */
static hr_status tube_create(const hr_create_args *args, void **out_shape)
{
    const hr_param *s_param = shape_param(args, "s"), *t_param = shape_param(args, "t");
    const double s = s_param ? s_param->number : NAN, t = t_param ? t_param->number : NAN;
    const char *problem = NULL;
    if (!(s >= 0.0 && s <= TAPER_MAX)) problem = "s";
    else if (!(t > 0.0 && t < 1.0 && t <= s)) problem = "t";
    if (problem) {
        if (args->error && args->error_size) {
            if (problem[0] == 's')
                snprintf(args->error, args->error_size,
                         "parameter 's' = %g must be a number in [0, %g]", s, TAPER_MAX);
            else
                snprintf(args->error, args->error_size,
                         "parameter 't' = %g must be above 0, below 1 and at most s = %g (the "
                         "wall's thickness: the hole's radius is 1 - t at z = 0, s - t at z = 1)",
                         t, s);
        }
        return HR_ERROR_PARAMETER;
    }
    hr_status st = tapered_make(args, s, out_shape);
    if (st == HR_OK) ((tapered_cylinder *)*out_shape)->inner = 1.0 - t;
    return st;
}

static hr_status cylinder_create(const hr_create_args *args, void **out_shape)
{
    return tapered_make(args, 1.0, out_shape);
}

static hr_status cone_create(const hr_create_args *args, void **out_shape)
{
    return tapered_make(args, 0.0, out_shape);
}

static void tapered_destroy(void *shape)
{
    if (!shape) return;
    const hr_host *host = ((tapered_cylinder *)shape)->host;
    host->free(shape);
}

/* --- Classes ------------------------------------------------------------------ */

static const hr_param_spec tapered_params[] = {
    {"s", HR_PARAM_NUMBER, 0, 1.0, 0.0, TAPER_MAX,
     "radius at z = 1 (the radius at z = 0 is 1): 0 makes a cone, 1 a cylinder", 0},
};

/* Hill's `taperedTube s t`: both given, as his reader reads them. */
static const hr_param_spec tube_params[] = {
    {"s", HR_PARAM_NUMBER, 1, 1.0, 0.0, TAPER_MAX, "the outer radius at z = 1 (1 at z = 0)", 0},
    {"t", HR_PARAM_NUMBER, 1, 0.1, 0.0, 1.0,
     "the wall's thickness across the axis: the hole's radius is 1 - t at z = 0, s - t at "
     "z = 1 (t <= s)",
     HR_PARAM_MIN_EXCLUSIVE | HR_PARAM_MAX_EXCLUSIVE},
};

/* (u, v): on the wall (and the tube's inner wall), u the turn about z from
 * +x in [0, 1) and v the height z in [0, 1]; on the base and cap disks (the
 * tube's annuli) the same u and v the
 * distance from the axis as a fraction of the disk's radius (0 at the
 * centre, 1 on the rim). */
static int32_t tapered_uv(const void *shape, const hr_hit *hit, double uv[2])
{
    SHAPE_UV_PROBE(hit, uv);
    const tapered_cylinder *c = shape;
    const hr_vec3 p = hit->point;
    uv[0] = shape_turn(p.y, p.x);
    if (hit->surface == SURFACE_WALL || hit->surface == SURFACE_INNER) {
        uv[1] = p.z;
    } else {
        const double radius = hit->surface == SURFACE_CAP ? c->s : 1.0;
        const double r = hypot(p.x, p.y) / radius;
        uv[1] = isfinite(r) ? r : 0.0;
    }
    return 1;
}

/* By SURFACE_WALL, SURFACE_BASE, SURFACE_CAP and SURFACE_INNER. */
static const char *const tapered_surface_names[4] = {"wall", "base", "cap", "inner"};

#define TAPERED_CLASS(class_name, class_help, params_list, params_count, create_fn)          \
    {                                                                                       \
        .struct_size = sizeof(hr_shape_class), .flags = HR_SHAPE_CLOSED, .name = class_name, \
        .help = class_help, .params = params_list, .param_count = params_count,             \
        .surface_count = 3, .create = create_fn, .destroy = tapered_destroy,                \
        .bounds = tapered_bounds, .hit = tapered_hit, .first_hit = tapered_first_hit,       \
        .any_hit = tapered_any_hit, .transformed_bounds = tapered_transformed_bounds,       \
        .surface_uv = tapered_uv, .surface_names = tapered_surface_names,                   \
    }

static const hr_shape_class tapered_cylinder_class =
    TAPERED_CLASS("taperedCylinder",
                  "axis +z from z = 0 (radius 1) to z = 1 (radius s); surfaces wall, base, cap",
                  tapered_params, 1, tapered_cylinder_create);
static const hr_shape_class cylinder_class =
    TAPERED_CLASS("cylinder", "taperedCylinder with s = 1; surfaces wall, base, cap", NULL, 0,
                  cylinder_create);
static const hr_shape_class cone_class =
    TAPERED_CLASS("cone", "taperedCylinder with s = 0, apex (0, 0, 1); surfaces wall, base",
                  NULL, 0, cone_create);

/* Not HR_SHAPE_CLOSED: an open tube bounds no solid, so CSG refuses it. */
static const hr_shape_class open_tapered_cylinder_class = {
    .struct_size = sizeof(hr_shape_class),
    .flags = 0,
    .name = "openTaperedCylinder",
    .help = "the wall of taperedCylinder alone, open at both ends (NFF's cones and cylinders); "
            "one surface",
    .params = tapered_params,
    .param_count = 1,
    .surface_count = 1,
    .surface_names = tapered_surface_names, /* the wall alone: SURFACE_WALL is 0 */
    .create = tapered_cylinder_create,
    .destroy = tapered_destroy,
    .bounds = tapered_bounds,
    .transformed_bounds = tapered_transformed_bounds,
    .hit = open_hit,
    .first_hit = open_first_hit,
    .any_hit = open_any_hit,
    .surface_uv = tapered_uv,
};

/* Hill's ECE661 reader's tube (SDL.cpp of the book's chapter-6 ray tracer). */
static const hr_shape_class tapered_tube_class = {
    .struct_size = sizeof(hr_shape_class),
    .flags = HR_SHAPE_CLOSED,
    .name = "taperedTube",
    .help = "taperedCylinder s with a coaxial hole, the wall t thick (hole radius 1 - t at z = 0, "
            "s - t at z = 1); surfaces wall, base, cap (annuli), inner",
    .params = tube_params,
    .param_count = 2,
    .surface_count = 4,
    .surface_names = tapered_surface_names,
    .create = tube_create,
    .destroy = tapered_destroy,
    .bounds = tapered_bounds,
    .transformed_bounds = tapered_transformed_bounds,
    .hit = tube_hit,
    .first_hit = tube_first_hit,
    .any_hit = tube_any_hit,
    .surface_uv = tapered_uv,
};

SHAPE_MODULE("cylinder",
             "Hill's tapered cylinder, cylinder and cone, the open tapered wall, and Hill's "
             "tapered tube",
             SHAPE_BUILTIN_METADATA, &tapered_cylinder_class, &cylinder_class, &cone_class,
             &open_tapered_cylinder_class, &tapered_tube_class);
