#include "random_rays.h"

#include <math.h>

void rng_seed(ray_rng *rng, uint64_t seed)
{
    rng->state = seed;
}

uint64_t rng_next(ray_rng *rng)
{
    uint64_t z = (rng->state += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

double rng_uniform(ray_rng *rng, double lo, double hi)
{
    const double unit = (double)(rng_next(rng) >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * unit;
}

int rng_chance(ray_rng *rng, double p)
{
    return rng_uniform(rng, 0.0, 1.0) < p;
}

hr_vec3 rng_unit_vector(ray_rng *rng)
{
    for (;;) {
        hr_vec3 v = {rng_uniform(rng, -1, 1), rng_uniform(rng, -1, 1), rng_uniform(rng, -1, 1)};
        double n2 = v.x * v.x + v.y * v.y + v.z * v.z;
        if (n2 > 1e-4 && n2 <= 1.0) {
            double inv = 1.0 / sqrt(n2);
            v.x *= inv, v.y *= inv, v.z *= inv;
            return v;
        }
    }
}

static double finite_or(double v, double fallback)
{
    return isfinite(v) ? v : fallback;
}

static double *component(hr_vec3 *v, int axis)
{
    return axis == 0 ? &v->x : axis == 1 ? &v->y : &v->z;
}

static double component_value(hr_vec3 v, int axis)
{
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

hr_ray random_ray_near(ray_rng *rng, const hr_bounds *b)
{
    const hr_vec3 lo = {finite_or(b->lo.x, -2), finite_or(b->lo.y, -2), finite_or(b->lo.z, -2)};
    const hr_vec3 hi = {finite_or(b->hi.x, 2), finite_or(b->hi.y, 2), finite_or(b->hi.z, 2)};
    hr_ray ray;
    ray.origin.x = rng_uniform(rng, lo.x - 2, hi.x + 2);
    ray.origin.y = rng_uniform(rng, lo.y - 2, hi.y + 2);
    ray.origin.z = rng_uniform(rng, lo.z - 2, hi.z + 2);
    if (rng_chance(rng, 0.75)) {
        const hr_vec3 target = {rng_uniform(rng, lo.x, hi.x), rng_uniform(rng, lo.y, hi.y),
                                rng_uniform(rng, lo.z, hi.z)};
        ray.dir.x = target.x - ray.origin.x;
        ray.dir.y = target.y - ray.origin.y;
        ray.dir.z = target.z - ray.origin.z;
    } else {
        ray.dir = rng_unit_vector(rng);
    }
    const double length = exp2(rng_uniform(rng, -3, 3));
    ray.dir.x *= length, ray.dir.y *= length, ray.dir.z *= length;
    if (rng_chance(rng, 1.0 / 8))
        *component(&ray.dir, (int)(rng_next(rng) % 3)) = rng_chance(rng, 0.5) ? 0.0 : -0.0;
    if (rng_chance(rng, 1.0 / 16)) {
        const int axis = (int)(rng_next(rng) % 3);
        const int pick = (int)(rng_next(rng) % 3);
        *component(&ray.origin, axis) = pick == 0   ? component_value(lo, axis)
                                        : pick == 1 ? component_value(hi, axis)
                                                    : 0.0;
    }
    if (ray.dir.x == 0 && ray.dir.y == 0 && ray.dir.z == 0) ray.dir.z = 1.0;
    return ray;
}

hr_ray random_ray_far(ray_rng *rng, const hr_bounds *b, double distance)
{
    const double lx = finite_or(b->lo.x, -2), hx = finite_or(b->hi.x, 2);
    const double ly = finite_or(b->lo.y, -2), hy = finite_or(b->hi.y, 2);
    const double lz = finite_or(b->lo.z, -2), hz = finite_or(b->hi.z, 2);
    const hr_vec3 target = {rng_uniform(rng, lx, hx), rng_uniform(rng, ly, hy),
                            rng_uniform(rng, lz, hz)};
    const hr_vec3 away = rng_unit_vector(rng);
    const double length = exp2(rng_uniform(rng, -3, 3));
    hr_ray ray;
    ray.origin.x = target.x + distance * away.x;
    ray.origin.y = target.y + distance * away.y;
    ray.origin.z = target.z + distance * away.z;
    ray.dir.x = -away.x * length;
    ray.dir.y = -away.y * length;
    ray.dir.z = -away.z * length;
    return ray;
}

hr_ray random_ray_grazing_torus(ray_rng *rng, double tube)
{
    const double two_pi = 6.283185307179586;
    const double phi = rng_uniform(rng, 0, two_pi), theta = rng_uniform(rng, 0, two_pi);
    const hr_vec3 n = {cos(theta) * cos(phi), cos(theta) * sin(phi), sin(theta)};
    const hr_vec3 p = {(1 + tube * cos(theta)) * cos(phi), (1 + tube * cos(theta)) * sin(phi),
                       tube * sin(theta)};
    hr_vec3 v = rng_unit_vector(rng); /* made tangent: its normal part removed */
    const double vn = v.x * n.x + v.y * n.y + v.z * n.z;
    v.x -= vn * n.x, v.y -= vn * n.y, v.z -= vn * n.z;
    const double length = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    v.x /= length, v.y /= length, v.z /= length;
    const double off = (rng_chance(rng, 0.5) ? 1 : -1) * pow(10, -rng_uniform(rng, 4, 12));
    hr_ray ray;
    ray.origin.x = p.x + off * n.x - 4 * v.x;
    ray.origin.y = p.y + off * n.y - 4 * v.y;
    ray.origin.z = p.z + off * n.z - 4 * v.z;
    ray.dir = v;
    return ray;
}

void random_interval(ray_rng *rng, double *tmin, double *tmax)
{
    const int kind = (int)(rng_next(rng) % 4);
    *tmin = 0.0;
    *tmax = INFINITY;
    if (kind == 1) *tmax = rng_uniform(rng, 0.0, 4.0);
    if (kind == 2) *tmin = rng_uniform(rng, -2.0, 2.0);
    if (kind == 3) {
        *tmin = rng_uniform(rng, -2.0, 2.0);
        *tmax = *tmin + rng_uniform(rng, 0.0, 3.0);
    }
}
