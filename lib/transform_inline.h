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

/* Coordinate r (0, 1, 2) of M p and of M v: the operations of
 * hr_xform_point and hr_xform_vector for that row, in their order, so one
 * coordinate has the same bits as the whole product's. */
static inline double hr_xform_point_row(const double m[16], hr_vec3 p, int r)
{
    const double *row = m + 4 * r;
    return row[0] * p.x + row[1] * p.y + row[2] * p.z + row[3];
}
static inline double hr_xform_vector_row(const double m[16], hr_vec3 v, int r)
{
    const double *row = m + 4 * r;
    return row[0] * v.x + row[1] * v.y + row[2] * v.z;
}

/* M p (with translation). */
static inline hr_vec3 hr_xform_point(const double m[16], hr_vec3 p)
{
    hr_vec3 r = {hr_xform_point_row(m, p, 0), hr_xform_point_row(m, p, 1),
                 hr_xform_point_row(m, p, 2)};
    return r;
}

/* M v (no translation). */
static inline hr_vec3 hr_xform_vector(const double m[16], hr_vec3 v)
{
    hr_vec3 r = {hr_xform_vector_row(m, v, 0), hr_xform_vector_row(m, v, 1),
                 hr_xform_vector_row(m, v, 2)};
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

/* What the error bound of M p (hr_xform_error) takes from M alone, per row:
 * the sum of |linear part| and |translation|. An object works them out
 * once, when its transform is set, instead of on every hit. */
typedef struct hr_xform_error_terms {
    double row_abs[3]; /* |m[4r]| + |m[4r+1]| + |m[4r+2]| */
    double shift_abs[3]; /* |m[4r+3]| */
} hr_xform_error_terms;

static inline hr_xform_error_terms hr_xform_error_terms_of(const double m[16])
{
    hr_xform_error_terms k;
    for (int r = 0; r < 3; r++) {
        const double *row = m + 4 * r;
        k.row_abs[r] = fabs(row[0]) + fabs(row[1]) + fabs(row[2]);
        k.shift_abs[r] = fabs(row[3]);
    }
    return k;
}

/* The error bound of a point after p' = M p, where p carried `e` per
 * coordinate: |M| e carried through, plus the rounding of the product,
 * gamma(3) (|M| |p| + |translation|) per row; k = hr_xform_error_terms_of(m). */
static inline double hr_xform_error_with(const double m[16], const hr_xform_error_terms *k,
                                         hr_vec3 p, double e)
{
    const double gamma3 = 3.0 * DBL_EPSILON * 0.5 / (1.0 - 3.0 * DBL_EPSILON * 0.5);
    double worst = 0.0;
    for (int r = 0; r < 3; r++) {
        const double *row = m + 4 * r;
        double carried = k->row_abs[r] * e;
        double rounding = gamma3 * (fabs(row[0] * p.x) + fabs(row[1] * p.y) + fabs(row[2] * p.z) +
                                    k->shift_abs[r]);
        double total = carried + rounding;
        if (total > worst) worst = total;
    }
    return worst;
}

/* hr_xform_error_with for a matrix whose terms are not kept. */
static inline double hr_xform_error(const double m[16], hr_vec3 p, double e)
{
    const hr_xform_error_terms k = hr_xform_error_terms_of(m);
    return hr_xform_error_with(m, &k, p, e);
}

#endif
