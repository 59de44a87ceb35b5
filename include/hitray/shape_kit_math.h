/* hitray shape kit: the small numerical toolkit the built-in shapes use and
 * a plugin may use too (part of <hitray/shape_kit.h>; see there).
 *
 * Everything is static inline, so each module stays one self-contained
 * loadable file that links nothing of libhitray.
 *
 * Error analysis follows pbrt-v4 (and Higham, "Accuracy and Stability of
 * Numerical Algorithms", ch. 3): with u the unit roundoff (2^-53 for double),
 * every correctly rounded operation returns x (1 + d) with |d| <= u, and a
 * chain of n such factors is (1 + theta_n) with |theta_n| <= gamma(n) =
 * n u / (1 - n u). The shapes state their error bounds in these terms.
 *
 * What hr_hit.error bounds here, taking the ray's origin and direction as
 * exact: per coordinate, how far `point` may be from a point of the exact
 * surface. Curved surfaces (sphere, tapered wall) re-project the point onto
 * the surface, as pbrt does, and bound the rounding of that projection: the
 * bound is then what the host needs to offset new rays off the surface, but
 * it does not cover the sideways slip that the error of t causes along the
 * surface (for a grazing ray that slip can be much larger). Flat surfaces
 * set their plane coordinate exactly and bound the other two by the rounding
 * of origin + t dir (shape_ray_point_error), which covers the distance to
 * the exact intersection point itself. tests/shapes/test_shape_accuracy.c
 * checks both against quad-precision references.
 *
 * The routines below avoid the usual losses of ray/quadric code:
 * - two_product / two_sum are Knuth's and Dekker's error-free transforms
 *   (they need the FMA of C99's fma(), which glibc maps to the instruction
 *   where the CPU has one and emulates exactly where it does not);
 * - shape_sum accumulates products with those transforms (Ogita, Rump and
 *   Oishi's Dot2): the result is as accurate as a sum of products evaluated
 *   in twice the working precision and rounded once, so a coefficient such
 *   as |o|^2 - 1 keeps full relative accuracy even when it cancels;
 * - difference_of_products is Kahan's a*b - c*d, within 1.5 ulp;
 * - solve_half_quadratic uses the root pair that never subtracts nearly
 *   equal numbers, and leaves the discriminant to the caller, who knows a
 *   form of it that stays accurate for its geometry. */
#ifndef HITRAY_SHAPE_KIT_MATH_H
#define HITRAY_SHAPE_KIT_MATH_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* --- Rounding-error bookkeeping ------------------------------------------ */

#define SHAPE_UNIT_ROUNDOFF (DBL_EPSILON * 0.5)

/* Bound on |theta_n|, the relative error of n chained roundings. */
static inline double shape_gamma(int n)
{
    return (n * SHAPE_UNIT_ROUNDOFF) / (1.0 - n * SHAPE_UNIT_ROUNDOFF);
}

/* --- Small vector helpers ------------------------------------------------- */

static inline hr_vec3 shape_vec3(double x, double y, double z)
{
    hr_vec3 v = {x, y, z};
    return v;
}

/* origin + t * dir, the point of a ray at time t. */
static inline hr_vec3 shape_ray_at(const hr_ray *ray, double t)
{
    return shape_vec3(ray->origin.x + t * ray->dir.x, ray->origin.y + t * ray->dir.y,
                      ray->origin.z + t * ray->dir.z);
}

static inline double shape_max3(double a, double b, double c)
{
    double m = a > b ? a : b;
    return m > c ? m : c;
}

static inline double shape_clamp(double x, double lo, double hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

static inline int shape_vec3_is_finite(hr_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

/* The power of two that brings v's largest component into [0.5, 1):
 * *exponent = e with max |v_i| = m 2^e, m in [0.5, 1). Returns 0 (and
 * leaves *exponent alone) for a zero or non-finite v, which no scaling
 * helps. */
static inline int shape_vec3_scale_exponent(hr_vec3 v, int *exponent)
{
    const double big = shape_max3(fabs(v.x), fabs(v.y), fabs(v.z));
    /* frexp's answer read off the exponent bits (frexp is a libm call, and
     * this runs for every ray into a cylinder or torus and every normal the
     * host rescales); the same bits say whether big is infinite or NaN (all
     * ones: no exponent) or zero or subnormal (all zeros: frexp, which
     * reads a subnormal's leading digit, or nothing for zero). */
    uint64_t bits;
    memcpy(&bits, &big, sizeof bits);
    const int biased = (int)(bits >> 52); /* big >= 0 or NaN: no sign bit */
    if (biased == 0x7ff) return 0;
    if (biased == 0) {
        if (!(big > 0.0)) return 0;
        frexp(big, exponent);
        return 1;
    }
    *exponent = biased - 1022;
    return 1;
}

/* 2^e as a double, for |e| <= 1022 (a normal number), from its bits. */
static inline double shape_pow2(int e)
{
    const uint64_t bits = (uint64_t)(e + 1023) << 52;
    double p;
    memcpy(&p, &bits, sizeof p);
    return p;
}

/* x 2^e, as ldexp gives it: for |e| <= 1022 the product with the exact
 * power of two, which is rounded once, as ldexp's result is (on overflow
 * and into the subnormals alike); beyond, ldexp itself. */
static inline double shape_ldexp(double x, int e)
{
    return e >= -1022 && e <= 1022 ? x * shape_pow2(e) : ldexp(x, e);
}

/* v 2^e, exact barring overflow or underflow: shape_ldexp per component,
 * the power of two built once (this runs for every ray into a transformed
 * object, through the host's normal rescaling). */
static inline hr_vec3 shape_vec3_ldexp(hr_vec3 v, int e)
{
    if (e >= -1022 && e <= 1022) {
        const double p = shape_pow2(e);
        return shape_vec3(v.x * p, v.y * p, v.z * p);
    }
    return shape_vec3(ldexp(v.x, e), ldexp(v.y, e), ldexp(v.z, e));
}

/* v scaled by a power of two (exactly) to a largest component in
 * [0.5, 1), so that its squares neither underflow nor overflow: a length
 * taken from them then has the relative error the shapes' bounds assume
 * (theta_3 for a sum of three squares) for any finite v, where below about
 * 1e-154 the squares turn subnormal and the length loses digits. Zero and
 * non-finite vectors come back unchanged. Normalising the result gives the
 * same bits as normalising v itself wherever v's squares are safe (the
 * scaling is exact and cancels). */
static inline hr_vec3 shape_vec3_rescaled(hr_vec3 v)
{
    int exponent;
    return shape_vec3_scale_exponent(v, &exponent) ? shape_vec3_ldexp(v, -exponent) : v;
}

/* Rounding error of shape_ray_at(ray, t), per coordinate, when t itself came
 * from `t_roundings` chained roundings of exact inputs (t~ = t (1 + theta_m)).
 * Coordinate i is fl(o_i + fl(t~ d_i)) = (o_i + t d_i (1 + theta_{m+1}))
 * (1 + d), so its distance from the exact o_i + t d_i is at most
 * gamma(m+1) |t d_i| + u |o_i + t d_i| (1 + gamma(m+1)) <= gamma(m+2)
 * (|o_i| + |t d_i|). One more gamma covers evaluating this bound itself
 * with the computed t~ instead of t. */
static inline double shape_ray_point_error(const hr_ray *ray, double t, int t_roundings)
{
    const hr_vec3 o = ray->origin, d = ray->dir;
    const double g = shape_gamma(t_roundings + 3);
    return g * shape_max3(fabs(o.x) + fabs(t * d.x), fabs(o.y) + fabs(t * d.y),
                          fabs(o.z) + fabs(t * d.z));
}

/* --- Hardware FMA where the CPU has one --------------------------------------- */

/* The error-free transforms below need fma(). Built for baseline x86-64 it is
 * a call into libm (which picks the FMA instruction at run time), a dozen
 * calls per sphere test. SHAPE_FMA_CLONES on a shape's hot function makes
 * GCC build it twice, once for CPUs with FMA (fma() becomes one instruction)
 * and once for the rest, and pick one when the module loads. fma() is
 * correctly rounded either way and the build is ISO C (no contraction of
 * a * b + c), so both copies give the same bits. GCC only, and its choice
 * reads the compiler runtime's CPU model, which zig's runtime leaves empty:
 * SHAPE_FMA_DISPATCH (shape_kit_cpu.h), which the built-in shapes use,
 * works with any compiler. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    defined(__has_attribute)
#if __has_attribute(target_clones)
#define SHAPE_FMA_CLONES __attribute__((target_clones("fma", "default")))
#endif
#endif
#ifndef SHAPE_FMA_CLONES
#define SHAPE_FMA_CLONES
#endif

/* --- Error-free transforms and compensated sums ---------------------------- */

/* a * b == product + *error exactly (barring underflow). */
static inline double shape_two_product(double a, double b, double *error)
{
    double product = a * b;
    *error = fma(a, b, -product);
    return product;
}

/* a + b == sum + *error exactly (Knuth's branch-free TwoSum). */
static inline double shape_two_sum(double a, double b, double *error)
{
    double sum = a + b;
    double b_virtual = sum - a;
    double a_virtual = sum - b_virtual;
    *error = (a - a_virtual) + (b - b_virtual);
    return sum;
}

/* A running sum of products carried as an unevaluated pair high + low. */
typedef struct shape_sum {
    double high, low;
} shape_sum;

static inline shape_sum shape_sum_start(double value)
{
    shape_sum s = {value, 0.0};
    return s;
}

static inline void shape_sum_add_product(shape_sum *s, double a, double b)
{
    double product_error, sum_error;
    double product = shape_two_product(a, b, &product_error);
    s->high = shape_two_sum(s->high, product, &sum_error);
    s->low += product_error + sum_error;
}

static inline double shape_sum_value(shape_sum s)
{
    return s.high + s.low;
}

/* a*b - c*d within 1.5 ulp (Kahan): the rounding of c*d is recovered by FMA
 * and added back, so the difference of nearly equal products (a cross product
 * of nearly parallel vectors, say) keeps its relative accuracy. */
static inline double shape_difference_of_products(double a, double b, double c, double d)
{
    double cd = c * d;
    double cd_error = fma(-c, d, cd);
    double difference = fma(a, b, -cd);
    return difference + cd_error;
}

/* --- Quadratics ------------------------------------------------------------- */

/* Real roots of a t^2 + 2 half_b t + c = 0, given disc = half_b^2 - a c
 * (the caller computes it in a form that does not cancel for its geometry;
 * disc < 0 or NaN: no real root). Writes the roots sorted and returns how
 * many there are:
 * - 2 for a proper quadratic; a double root (disc == 0) comes back twice,
 *   bit-identical, so a tangent is reported consistently;
 * - 1 when a == 0 (the equation is linear: t = -c / (2 half_b));
 * - 0 when there is no real root, or a == half_b == 0 (a constant: the
 *   caller decides what c says).
 * The pair q = -(half_b + sign(half_b) sqrt(disc)), t = q / a and t = c / q
 * adds two numbers of the same sign, so neither root suffers cancellation.
 * A root may be infinite when a or q is tiny; never NaN for finite input. */
static inline int shape_solve_half_quadratic(double a, double half_b, double c, double disc,
                                             double roots[2])
{
    if (!(disc >= 0.0)) return 0;
    const double root = sqrt(disc);
    const double q = -(half_b + copysign(root, half_b));
    if (q == 0.0) { /* half_b == 0 and disc == 0: a double root at 0 (if any) */
        if (a == 0.0) return 0;
        roots[0] = roots[1] = 0.0;
        return 2;
    }
    if (a == 0.0) {
        roots[0] = c / q;
        return 1;
    }
    if (disc == 0.0) {
        roots[0] = roots[1] = q / a;
        return 2;
    }
    const double t0 = q / a, t1 = c / q;
    roots[0] = t0 < t1 ? t0 : t1;
    roots[1] = t0 < t1 ? t1 : t0;
    return 2;
}

#ifdef __cplusplus
}
#endif
#endif
