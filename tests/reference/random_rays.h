/* Reproducible random rays for stress tests: a fixed-seed generator
 * (splitmix64, so every platform draws the same numbers) and rays aimed
 * around a shape's bounds, salted with the special values that break naive
 * code (zero and negative-zero direction components, origins on faces). */
#ifndef HR_TEST_RANDOM_RAYS_H
#define HR_TEST_RANDOM_RAYS_H

#include <stdint.h>

#include <hitray/common.h>

typedef struct ray_rng {
    uint64_t state;
} ray_rng;

void rng_seed(ray_rng *rng, uint64_t seed);
uint64_t rng_next(ray_rng *rng);
/* Uniform in [lo, hi). */
double rng_uniform(ray_rng *rng, double lo, double hi);
/* 1 with probability p. */
int rng_chance(ray_rng *rng, double p);
hr_vec3 rng_unit_vector(ray_rng *rng);

/* A ray for the shape whose bounds are `b` (infinite sides are taken as
 * +-2): origin in the bounds grown by 2 on every side; direction aimed at a
 * random point of the bounds most of the time, otherwise random; its length
 * random over 2^-3..2^3 (object-space rays are not unit length). One ray in
 * eight has a direction component replaced by +0 or -0, and one in sixteen
 * an origin coordinate snapped to a face value of the bounds or to 0. */
hr_ray random_ray_near(ray_rng *rng, const hr_bounds *b);

/* A ray from `distance` away in a random direction, aimed at a random point
 * of the bounds `b` (infinite sides taken as +-2), its direction's length
 * random over 2^-3..2^3. */
hr_ray random_ray_far(ray_rng *rng, const hr_bounds *b, double distance);

/* A ray grazing the torus of ring radius 1 and tube radius `tube`: through a
 * random point of its surface along a random tangent direction (unit
 * length), moved off the surface along the normal by +-10^-(4..12), from 4
 * away. */
hr_ray random_ray_grazing_torus(ray_rng *rng, double tube);

/* A random (tmin, tmax): mostly (0, inf), sometimes finite ends. */
void random_interval(ray_rng *rng, double *tmin, double *tmax);

#endif
