/* The sphere's quadratic coefficients in vector lanes against the scalar
 * sums (shapes/sphere/sphere_coefficients.h), bit for bit: a = d.d,
 * b = o.d, c = o.o - 1, each as its compensated pair (high, low), on
 * millions of rays with origins and directions of every magnitude from
 * subnormal to beyond where the squares overflow, signed zeros, exact
 * small integers (ties in rounding), near-unit directions and origins on
 * and near the sphere. Where a sum is NaN both must be NaN (the sphere
 * calls that a miss; a NaN's payload depends on operand order). Runs where
 * the CPU has AVX and FMA; elsewhere only the scalar form exists. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"
#include "../../shapes/sphere/sphere_coefficients.h"

static uint64_t rng_state = 0x3c6ef372fe94f82bull;
static uint64_t next(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return rng_state;
}
static double uniform(void) { return (double)(next() >> 11) * 0x1p-53; } /* [0, 1) */
static double sign(void) { return next() % 2 ? -1.0 : 1.0; }

static double component(void)
{
    switch (next() % 12) {
    case 0: return sign() * 0.0;
    case 1: return sign() * 0x1p-1074 * (double)(1 + next() % 4096);
    case 2: return sign() * ldexp(1.0 + uniform(), (int)(next() % 1200) - 600);
    case 3: return (double)((int)(next() % 9) - 4);
    case 4: return next() % 8 ? sign() * ldexp(1.0 + uniform(), 500 + (int)(next() % 30)) : sign() * INFINITY;
    case 5: return sign() * (1.0 + ldexp(uniform(), -40)); /* near the unit sphere */
    default: return sign() * uniform() * 4.0;
    }
}

static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b)); }
static int same_sum(shape_sum a, shape_sum b) { return same(a.high, b.high) && same(a.low, b.low); }

int main(void)
{
#if SPHERE_COEFFICIENT_LANES
    if (!sphere_coefficient_lanes_usable()) {
        printf("no AVX and FMA here: only the scalar coefficients run\n");
        return hr_test_end();
    }
    const long rays = HR_TEST_SANITIZED ? 400000 : 4000000;
    long mismatched = 0, with_low = 0;
    for (long i = 0; i < rays; i++) {
        hr_ray ray;
        if (next() % 3) {
            /* A direction near unit length from an origin in the usual range. */
            ray.origin = (hr_vec3){sign() * uniform() * 8.0, sign() * uniform() * 8.0, sign() * uniform() * 8.0};
            ray.dir = (hr_vec3){sign() * uniform(), sign() * uniform(), sign() * uniform()};
        } else {
            ray.origin = (hr_vec3){component(), component(), component()};
            ray.dir = (hr_vec3){component(), component(), component()};
        }
        const sphere_coefficients s = sphere_coefficients_scalar(&ray), v = sphere_coefficients_lanes(&ray);
        with_low += s.a.low != 0 || s.b.low != 0 || s.c.low != 0;
        if (!(same_sum(s.a, v.a) && same_sum(s.b, v.b) && same_sum(s.c, v.c)) && mismatched++ < 5)
            CHECK_MSG(0, "origin (%a, %a, %a) dir (%a, %a, %a): the lanes differ", ray.origin.x, ray.origin.y,
                      ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z);
    }
    printf("sphere coefficients: %ld rays, %ld with a non-zero low part, %ld differ\n", rays, with_low,
           mismatched);
    CHECK(mismatched == 0);
    CHECK(with_low > rays / 2);
#else
    printf("not x86-64 GCC or clang: only the scalar coefficients exist\n");
#endif
    return hr_test_end();
}
