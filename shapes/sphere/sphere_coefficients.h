/* The sphere's quadratic coefficients (shapes/sphere/sphere.c): a = d.d,
 * b = o.d and c = o.o - 1, each a compensated sum of three products, in
 * the order x, y, z. Two forms with the same bits: three scalar sums, and
 * (on x86-64 CPUs with AVX and FMA) the three sums as three lanes of one
 * vector, step for step the scalar operations: a product, its error by a
 * fused multiply-subtract, Knuth's TwoSum, and the low part's sum, each
 * rounding lane by lane as the scalar operation does. Nine compensated
 * steps become three. tests/shapes/test_sphere_coefficients.c compares the
 * two on millions of rays. A header, so that the test can call both. */
#ifndef HITRAY_SHAPES_SPHERE_COEFFICIENTS_H
#define HITRAY_SHAPES_SPHERE_COEFFICIENTS_H

#include <hitray/shape_kit_cpu.h>
#include <hitray/shape_kit_math.h>


typedef struct sphere_coefficients {
    shape_sum a, b, c;
} sphere_coefficients;

static inline __attribute__((always_inline)) sphere_coefficients
sphere_coefficients_scalar(const hr_ray *ray)
{
    const hr_vec3 o = ray->origin, d = ray->dir;
    sphere_coefficients k = {shape_sum_start(0.0), shape_sum_start(0.0), shape_sum_start(-1.0)};
    shape_sum_add_product(&k.a, d.x, d.x);
    shape_sum_add_product(&k.a, d.y, d.y);
    shape_sum_add_product(&k.a, d.z, d.z);
    shape_sum_add_product(&k.b, o.x, d.x);
    shape_sum_add_product(&k.b, o.y, d.y);
    shape_sum_add_product(&k.b, o.z, d.z);
    shape_sum_add_product(&k.c, o.x, o.x);
    shape_sum_add_product(&k.c, o.y, o.y);
    shape_sum_add_product(&k.c, o.z, o.z);
    return k;
}

/* GCC and clang alike (the build turns off contraction: -ffp-contract=off). */
#if defined(__GNUC__) && defined(__x86_64__)
#define SPHERE_COEFFICIENT_LANES 1
#include <immintrin.h>

/* Whether this CPU runs sphere_coefficients_lanes (FMA only where the OS
 * also keeps AVX state: shape_kit_cpu.h). */
static inline int sphere_coefficient_lanes_usable(void) { return shape_cpu_has_fma(); }

/* Lane 0 sums d_i d_i, lane 1 o_i d_i, lane 2 o_i o_i (from -1); lane 3,
 * d_i d_i again, is not read. shape_sum_add_product's operations in its
 * order: the sum's error (high - a_virtual) + (product - b_virtual), then
 * low + (product_error + sum_error). */
__attribute__((target("avx,fma"))) static inline sphere_coefficients sphere_coefficients_lanes(const hr_ray *ray)
{
    const double *o = &ray->origin.x, *d = &ray->dir.x;
    __m256d high = _mm256_setr_pd(0.0, 0.0, -1.0, 0.0), low = _mm256_setzero_pd();
#define SPHERE_LANE_STEP(i)                                                                        \
    do {                                                                                           \
        const __m256d d_ = _mm256_broadcast_sd(d + (i)), o_ = _mm256_broadcast_sd(o + (i));        \
        const __m256d u_ = _mm256_blend_pd(d_, o_, 0x6), v_ = _mm256_blend_pd(d_, o_, 0x4);        \
        const __m256d product_ = _mm256_mul_pd(u_, v_);                                            \
        const __m256d product_error_ = _mm256_fmsub_pd(u_, v_, product_);                          \
        const __m256d sum_ = _mm256_add_pd(high, product_);                                        \
        const __m256d b_virtual_ = _mm256_sub_pd(sum_, high);                                      \
        const __m256d a_virtual_ = _mm256_sub_pd(sum_, b_virtual_);                                \
        const __m256d sum_error_ =                                                                 \
            _mm256_add_pd(_mm256_sub_pd(high, a_virtual_), _mm256_sub_pd(product_, b_virtual_));  \
        high = sum_;                                                                               \
        low = _mm256_add_pd(low, _mm256_add_pd(product_error_, sum_error_));                       \
    } while (0)
    SPHERE_LANE_STEP(0);
    SPHERE_LANE_STEP(1);
    SPHERE_LANE_STEP(2);
#undef SPHERE_LANE_STEP
    double h[4], l[4];
    _mm256_storeu_pd(h, high);
    _mm256_storeu_pd(l, low);
    const sphere_coefficients k = {{h[0], l[0]}, {h[1], l[1]}, {h[2], l[2]}};
    return k;
}
#else
#define SPHERE_COEFFICIENT_LANES 0
#endif

#endif
