/* What the walk tests of accel/ share: a seeded xorshift generator (define
 * ACCEL_TEST_SEED before including, one per test, so each keeps its own
 * sequence), random directions, and the exact slab test of a double ray
 * against a double box in __float128: the inputs are doubles, and
 * (b - o) / d to 113 bits decides every case whose answer is not a tie
 * within 2^-100. */
#ifndef HITRAY_TESTS_ACCEL_TEST_RAYS_H
#define HITRAY_TESTS_ACCEL_TEST_RAYS_H

#include <math.h>
#include <stdint.h>

#include <hitray/common.h>

typedef __float128 quad;

static uint64_t rng_state = ACCEL_TEST_SEED;
static double uniform(void) /* [0, 1) */
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * 0x1p-53;
}
static double between(double a, double b) { return a + (b - a) * uniform(); }

static hr_vec3 random_dir(void)
{
    for (;;) {
        hr_vec3 v = {between(-1, 1), between(-1, 1), between(-1, 1)};
        if (v.x * v.x + v.y * v.y + v.z * v.z > 1e-4) return v;
    }
}

/* Where the ray enters the box within [tmin, tmax], exact, then rounded to
 * double (monotone, so the least entry over boxes is the same whichever
 * walk finds it), or NAN when it misses the box there. */
static double quad_entry(const hr_ray *ray, const hr_bounds *b, double tmin, double tmax)
{
    const double o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    const double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    const double lo[3] = {b->lo.x, b->lo.y, b->lo.z}, hi[3] = {b->hi.x, b->hi.y, b->hi.z};
    quad t0 = tmin, t1 = tmax;
    for (int a = 0; a < 3; a++) {
        if (d[a] == 0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return NAN;
            continue;
        }
        quad n = ((quad)lo[a] - o[a]) / d[a], f = ((quad)hi[a] - o[a]) / d[a];
        if (n > f) {
            quad t = n;
            n = f, f = t;
        }
        if (n > t0) t0 = n;
        if (f < t1) t1 = f;
    }
    return t0 <= t1 ? (double)t0 : NAN;
}

/* Whether the ray meets the box within [tmin, tmax], exactly. */
static inline int quad_meets(const hr_ray *ray, const hr_bounds *b, double tmin, double tmax)
{
    return !isnan(quad_entry(ray, b, tmin, tmax));
}

#endif
