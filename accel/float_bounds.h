/* Doubles to floats rounded outward: a float box made with these contains
 * the double box it came from, so a conservative float test of it never
 * loses a hit the double box holds. Beyond float's range a lower bound
 * becomes -inf (an upper bound +inf), and a bound on the far side of the
 * range the largest float, so the box still holds every point it held. */
#ifndef HITRAY_ACCEL_FLOAT_BOUNDS_H
#define HITRAY_ACCEL_FLOAT_BOUNDS_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* The float next to f towards -inf (+inf), for a finite f, from its bits:
 * nextafterf is a libm call, and these run for every ray. */
static inline float accel_float_below(float f)
{
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    if (f == 0.0f) bits = 0x80000001u; /* -0 and +0: the negative subnormal */
    else if (f > 0.0f) bits--;
    else bits++;
    memcpy(&f, &bits, sizeof f);
    return f;
}
static inline float accel_float_above(float f)
{
    return -accel_float_below(-f);
}

/* The largest float not above x (-inf below -FLT_MAX; NaN stays NaN). */
static inline float accel_float_down(double x)
{
    if (x > FLT_MAX) return FLT_MAX;
    if (x < -FLT_MAX) return -INFINITY;
    float f = (float)x;
    return (double)f > x ? accel_float_below(f) : f;
}

/* The smallest float not below x (+inf above FLT_MAX; NaN stays NaN). */
static inline float accel_float_up(double x)
{
    if (x < -FLT_MAX) return -FLT_MAX;
    if (x > FLT_MAX) return INFINITY;
    float f = (float)x;
    return (double)f < x ? accel_float_above(f) : f;
}

/* A float at or above (at or below) x, not necessarily the nearest: one
 * conversion and a step of at least one ulp outward, with no branch, for
 * the per-ray numbers (origin, tmin, tmax). x is clamped to float's range
 * first, so a huge x gives +-FLT_MAX stepped outward, that is +-inf or the
 * largest float, and never NaN. The step |f| 2^-23 is at least one ulp of
 * f, and the conversion is off by at most half an ulp. */
static inline void accel_float_bracket(double x, float *at_most, float *at_least)
{
    double c = x < -FLT_MAX ? -FLT_MAX : x > FLT_MAX ? FLT_MAX : x;
    float f = (float)c, step = fabsf(f) * 0x1p-23f + 0x1p-149f;
    *at_most = f - step;
    *at_least = f + step;
}
static inline float accel_float_at_least(double x)
{
    double c = x < -FLT_MAX ? -FLT_MAX : x > FLT_MAX ? FLT_MAX : x;
    float f = (float)c;
    return f + (fabsf(f) * 0x1p-23f + 0x1p-149f);
}
static inline float accel_float_at_most(double x)
{
    double c = x < -FLT_MAX ? -FLT_MAX : x > FLT_MAX ? FLT_MAX : x;
    float f = (float)c;
    return f - (fabsf(f) * 0x1p-23f + 0x1p-149f);
}

#endif
