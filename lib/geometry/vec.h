/* Internal: small vector helpers for lib/ (inline, no state). */
#ifndef HITRAY_LIB_GEOMETRY_VEC_H
#define HITRAY_LIB_GEOMETRY_VEC_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include <hitray/common.h>
#include <hitray/shape_kit_math.h>

static inline hr_vec3 v3(double x, double y, double z)
{
    hr_vec3 r = {x, y, z};
    return r;
}
static inline hr_vec3 v3_add(hr_vec3 a, hr_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline hr_vec3 v3_sub(hr_vec3 a, hr_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline hr_vec3 v3_scale(hr_vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline hr_vec3 v3_neg(hr_vec3 a) { return v3(-a.x, -a.y, -a.z); }
static inline double v3_dot(hr_vec3 a, hr_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline hr_vec3 v3_cross(hr_vec3 a, hr_vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double v3_length(hr_vec3 a) { return sqrt(v3_dot(a, a)); }
/* Unit vector; the zero vector stays zero rather than becoming NaN. */
static inline hr_vec3 v3_normalize(hr_vec3 a)
{
    double len = v3_length(a);
    return len > 0.0 ? v3_scale(a, 1.0 / len) : a;
}
static inline hr_vec3 v3_madd(hr_vec3 a, hr_vec3 b, double s)
{
    return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s);
}
static inline int v3_is_finite(hr_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }
/* Whether every component of a and b and the number e is finite, in one
 * comparison instead of a branch per value: x - x is +0 (or -0) for a
 * finite x and NaN for an infinite or NaN one, and a sum with a NaN in it
 * is NaN. Exact for every input (no overflow: each term is 0 or NaN). */
static inline int v3_pair_is_finite(hr_vec3 a, hr_vec3 b, double e)
{
    double zero = (a.x - a.x) + (a.y - a.y) + (a.z - a.z) + (b.x - b.x) + (b.y - b.y) + (b.z - b.z) +
                  (e - e);
    return zero == 0.0;
}
/* Whether all n numbers of x are finite, by the same sum of x - x. */
static inline int doubles_are_finite(const double *x, int n)
{
    double zero = 0.0;
    for (int i = 0; i < n; i++) zero += x[i] - x[i];
    return zero == 0.0;
}
/* nextafter(x, copysign(INFINITY, dir)) for dir != 0, x itself for dir 0,
 * from x's bits: nextafter is a libm call, and this runs for every spawned
 * ray (lib/trace/spawn.c) and for many first hits (lib/trace/trace.c). Infinite and
 * NaN x stay as they are, as nextafter leaves them. */
static inline double step_towards(double x, double dir)
{
    if (dir == 0) return x;
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    const uint64_t magnitude = bits & 0x7fffffffffffffffull;
    if (magnitude >= 0x7ff0000000000000ull) return isnan(x) ? x : nextafter(x, dir * INFINITY);
    /* Zero steps to the smallest subnormal of dir's sign; any other x one
     * unit of its magnitude up when dir points away from zero, else down. */
    const int away = magnitude == 0 || (bits >> 63) == (dir < 0);
    if (magnitude == 0) bits = dir < 0 ? 0x8000000000000000ull : 0;
    bits += away ? 1 : (uint64_t)-1;
    memcpy(&x, &bits, sizeof x);
    return x;
}

/* fmin and fmax inline (each is otherwise a libm call, a dozen of them
 * for every object a scene adds), with glibc's x86-64 results bit for bit:
 * a NaN argument gives the other one, and otherwise minsd's (maxsd's)
 * "a < b ? a : b", so that of two zeros the second is returned. */
static inline double v_fmin(double a, double b) { return a < b || b != b ? a : b; }
static inline double v_fmax(double a, double b) { return a > b || b != b ? a : b; }

/* Largest |component| (inline: fmax is a libm call on the hot path). */
static inline double v3_max_abs(hr_vec3 a)
{
    double x = fabs(a.x), y = fabs(a.y), z = fabs(a.z);
    double m = x > y ? x : y;
    return m > z ? m : z;
}
/* The power of two e such that a * 2^-e is near unit length, for a vector
 * whose squared length would under- or overflow (a component beyond
 * 2^+-200); 0 for every other vector, zero, inf and NaN included. Scaling
 * by 2^-e is exact. The exponent is the shape kit's (frexp's, read off the
 * bits). */
static inline int v3_rescale_exponent(hr_vec3 a)
{
    double big = v3_max_abs(a);
    if (!(big < 0x1p-200 || big > 0x1p200)) return 0;
    int e;
    return shape_vec3_scale_exponent(a, &e) ? e : 0;
}
/* a 2^e, as ldexp gives it per component (shape_ldexp). */
static inline hr_vec3 v3_ldexp(hr_vec3 a, int e)
{
    return e ? shape_vec3_ldexp(a, e) : a;
}
/* a scaled by a power of two so its largest |component| is in [1, 2):
 * exact, for normals of any length before and after a transform, so neither
 * M^-T nor normalising can overflow or underflow. The factor is built from
 * the exponent bits (no libm call on the hot path); zero, infinite and NaN
 * inputs stay as they are. */
static inline hr_vec3 v3_unit_exponent(hr_vec3 a)
{
    int e;
    return shape_vec3_scale_exponent(a, &e) ? v3_ldexp(a, 1 - e) : a;
}

static inline hr_color rgb(double r, double g, double b)
{
    hr_color c = {r, g, b};
    return c;
}
static inline hr_color rgb_add(hr_color a, hr_color b) { return rgb(a.r + b.r, a.g + b.g, a.b + b.b); }
static inline hr_color rgb_mul(hr_color a, hr_color b) { return rgb(a.r * b.r, a.g * b.g, a.b * b.b); }
static inline hr_color rgb_scale(hr_color a, double s) { return rgb(a.r * s, a.g * s, a.b * s); }
static inline int rgb_is_zero(hr_color a) { return a.r == 0.0 && a.g == 0.0 && a.b == 0.0; }

#endif
