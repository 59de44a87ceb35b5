/* The generic sphere of Hill's chapter 12: radius 1, centred at the origin.
 *
 * Hit: the ray o + t d meets |p|^2 = 1 where a t^2 + 2 b t + c = 0 with
 *   a = d.d,  b = o.d,  c = o.o - 1.
 * The textbook discriminant b^2 - a c loses everything for a far ray: both
 * terms are about |o|^2 |d|^2 and their difference about |d|^2, so at
 * |o| = 1e6 twelve of the sixteen digits cancel. By Lagrange's identity
 *   b^2 - a c = |d|^2 - |o x d|^2,
 * which is |d|^2 (1 - distance^2 of the ray's line from the centre), the
 * form Ray Tracing Gems ch. 7 recommends; with each component of o x d taken
 * to 1.5 ulp by Kahan's difference of products, and a, b, c and the
 * discriminant summed with compensated products (shape_sum), the only
 * cancellation left is the true one of a near-tangent ray. The stable root
 * pair then gives both roots to a few ulps (see tests/shapes for the measured
 * accuracy against quad-precision roots). An exact tangent has disc == 0 and
 * is reported as a double root: entering and exiting at the same t.
 *
 * Point: origin + t dir, then re-projected onto the sphere, p / |p| (as pbrt
 * does), which removes the error that t's rounding puts along the ray.
 * Error of the re-projected point: |p|^2 = px^2 + py^2 + pz^2 is computed
 * with relative error theta_3, its square root adds theta_1 (and halves the
 * rest), and the division and product one rounding each, so each coordinate
 * is p_i / |p| (1 + theta_5) with p / |p| exactly on the sphere: the point is
 * within gamma(5) |p_i| <= gamma(5) of a point of the surface. We report
 * gamma(6), the extra gamma for evaluating the bound. This bounds the
 * distance to the surface (what the host needs to offset new rays); the
 * displacement along the surface that the error of t causes is not in it.
 *
 * The outward normal is the re-projected point itself. */
#include <math.h>

#include <hitray/shape_module.h>

#include <hitray/shape_kit.h>
#include "../common/shape_builtin.h"
#include "sphere_coefficients.h"

/* The crossings from the coefficients: the discriminant by Lagrange's
 * identity, then the stable root pair. Inline into each form below. */
static inline __attribute__((always_inline)) int sphere_crossings_from(const hr_ray *ray,
                                                                       sphere_coefficients k,
                                                                       shape_crossing out[2])
{
    const hr_vec3 o = ray->origin, d = ray->dir;
    const hr_vec3 cross = shape_vec3(shape_difference_of_products(o.y, d.z, o.z, d.y),
                                     shape_difference_of_products(o.z, d.x, o.x, d.z),
                                     shape_difference_of_products(o.x, d.y, o.y, d.x));
    shape_sum disc = k.a;
    shape_sum_add_product(&disc, -cross.x, cross.x);
    shape_sum_add_product(&disc, -cross.y, cross.y);
    shape_sum_add_product(&disc, -cross.z, cross.z);

    const double qa = shape_sum_value(k.a), qb = shape_sum_value(k.b), qc = shape_sum_value(k.c);
    const double qdisc = shape_sum_value(disc);
    /* Coefficients overflow only for rays beyond 1e150 or so: call it a miss.
     * One test for the four (x - x is 0 for a finite x, NaN otherwise). */
    if (!((qa - qa) + (qb - qb) + (qc - qc) + (qdisc - qdisc) == 0.0)) return 0;

    double roots[2];
    /* a > 0 for any usable direction; a == 0 (|d| < 1e-162 underflows) gives
     * one "root" of the degenerate linear equation: not a sphere hit. */
    if (shape_solve_half_quadratic(qa, qb, qc, qdisc, roots) != 2) return 0;
    return shape_span_crossings(shape_span_make(roots[0], 0, roots[1], 0), out);
}

/* The scalar form, which runs where the CPU lacks FMA (the lanes run where it
 * has it). */
static int sphere_crossings(const hr_ray *ray, shape_crossing out[2])
{
    return sphere_crossings_from(ray, sphere_coefficients_scalar(ray), out);
}

#if SPHERE_COEFFICIENT_LANES
/* The same bits with a, b and c in the lanes of one vector
 * (sphere_coefficients.h), where the CPU has AVX and FMA. */
__attribute__((target("avx,fma"))) static int sphere_crossings_lanes(const hr_ray *ray, shape_crossing out[2])
{
    return sphere_crossings_from(ray, sphere_coefficients_lanes(ray), out);
}
#endif

static void sphere_fill(const void *shape, const hr_ray *ray, hr_hit *hit)
{
    (void)shape;
    /* Rescaled before its length is taken: a far ray's point can come out
     * tiny (o + t d cancels), and the squares of a point below 1e-154 are
     * subnormal, which put p / |p| 6e-12 off the sphere against a bound
     * of 7e-16. */
    hr_vec3 p = shape_vec3_rescaled(shape_ray_at(ray, hit->t));
    const double length = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    if (length > 0.0) {
        const double scale = 1.0 / length;
        p = shape_vec3(p.x * scale, p.y * scale, p.z * scale);
        hit->point = p;
        hit->normal = p;
        hit->error = shape_gamma(6);
    } else {
        /* Unreachable for a finite hit (the sphere does not pass through the
         * origin), kept so that no input can make a zero normal. */
        hit->point = p;
        hit->normal = shape_vec3(0.0, 0.0, 1.0);
        hit->error = 1.0;
    }
}

static hr_status sphere_trace(const hr_hit_args *args, int32_t mode)
{
    shape_crossing crossings[2];
#if SPHERE_COEFFICIENT_LANES
    const int count = sphere_coefficient_lanes_usable() ? sphere_crossings_lanes(&args->ray, crossings)
                                                        : sphere_crossings(&args->ray, crossings);
#else
    const int count = sphere_crossings(&args->ray, crossings);
#endif
    return shape_report(args, mode, crossings, count, sphere_fill);
}

SHAPE_DEFINE_HIT_MODES(sphere, sphere_trace)

static void sphere_bounds(const void *shape, hr_bounds *out)
{
    (void)shape;
    shape_set_bounds(out, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0);
}

/* The box of the ellipsoid the unit sphere maps to: along world axis i it
 * reaches c_i +- |row i of the linear part|. Padded by 16 ulps of the
 * terms' magnitudes, far above the rounding of these few operations. */
static void sphere_transformed_bounds(const void *shape, const double m[16], hr_bounds *out)
{
    (void)shape;
    double lo[3], hi[3];
    for (int i = 0; i < 3; i++) {
        const double *row = m + 4 * i;
        const double reach = sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]);
        const double pad = 16.0 * DBL_EPSILON * (fabs(row[3]) + reach);
        lo[i] = row[3] - reach - pad;
        hi[i] = row[3] + reach + pad;
    }
    shape_set_bounds(out, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
}

/* (u, v): longitude and latitude, with the poles on the z axis (Hill's
 * parametrisation x = cos v' cos u', y = cos v' sin u', z = sin v'): u the
 * turn about z from +x, in [0, 1); v from 0 at the south pole (-z) to 1
 * at the north pole. */
static int32_t sphere_uv(const void *shape, const hr_hit *hit, double uv[2])
{
    (void)shape;
    SHAPE_UV_PROBE(hit, uv);
    const hr_vec3 p = hit->point;
    uv[0] = shape_turn(p.y, p.x);
    uv[1] = atan2(p.z, hypot(p.x, p.y)) / 3.14159265358979323846 + 0.5;
    return 1;
}

static const char *const sphere_surface_names[1] = {"sphere"};

SHAPE_CLASS(sphere, .flags = HR_SHAPE_CLOSED, .name = "sphere",
            .help = "unit sphere centred at the origin", .surface_count = 1,
            .surface_names = sphere_surface_names, .create = shape_plain_create,
            .destroy = shape_plain_destroy, .transformed_bounds = sphere_transformed_bounds,
            .surface_uv = sphere_uv);
SHAPE_MODULE_OF(sphere, "Hill's generic sphere: radius 1 at the origin", SHAPE_BUILTIN_METADATA);
