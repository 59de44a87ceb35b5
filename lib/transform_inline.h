/* Internal: the affine products of include/hitray/transform.h as inline
 * functions, so the tracing loop (lib/trace.c) does not pay a call per ray
 * and object; lib/transform.c's exported functions are these same bodies,
 * so both give the same bits. m is row-major object -> world (or its
 * inverse), as in hr_object. */
#ifndef HITRAY_LIB_TRANSFORM_INLINE_H
#define HITRAY_LIB_TRANSFORM_INLINE_H

#include <float.h>
#include <math.h>

#include <hitray/common.h>

/* M p (with translation). */
static inline hr_vec3 hr_xform_point(const double m[16], hr_vec3 p)
{
    hr_vec3 r = {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
                 m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                 m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
    return r;
}

/* M v (no translation). */
static inline hr_vec3 hr_xform_vector(const double m[16], hr_vec3 v)
{
    hr_vec3 r = {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
                 m[8] * v.x + m[9] * v.y + m[10] * v.z};
    return r;
}

/* (M^-1)^T n: a normal back to world space, given M^-1. */
static inline hr_vec3 hr_xform_normal(const double inv[16], hr_vec3 n)
{
    hr_vec3 r = {inv[0] * n.x + inv[4] * n.y + inv[8] * n.z,
                 inv[1] * n.x + inv[5] * n.y + inv[9] * n.z,
                 inv[2] * n.x + inv[6] * n.y + inv[10] * n.z};
    return r;
}

/* The error bound of a point after p' = M p, where p carried `e` per
 * coordinate: |M| e carried through, plus the rounding of the product,
 * gamma(3) (|M| |p| + |translation|) per row. */
static inline double hr_xform_error(const double m[16], hr_vec3 p, double e)
{
    const double gamma3 = 3.0 * DBL_EPSILON * 0.5 / (1.0 - 3.0 * DBL_EPSILON * 0.5);
    double worst = 0.0;
    for (int r = 0; r < 3; r++) {
        const double *row = m + 4 * r;
        double carried = (fabs(row[0]) + fabs(row[1]) + fabs(row[2])) * e;
        double rounding = gamma3 * (fabs(row[0] * p.x) + fabs(row[1] * p.y) + fabs(row[2] * p.z) +
                                    fabs(row[3]));
        double total = carried + rounding;
        if (total > worst) worst = total;
    }
    return worst;
}

#endif
