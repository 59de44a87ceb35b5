/* Internal: the affine products of include/hitray/transform.h as inline
 * functions, so the tracing loop (lib/trace/object_trace.h) does not pay a call
 * per ray and object; lib/geometry/transform.c's exported functions are these same
 * bodies, so both give the same bits. m is row-major object -> world (or its
 * inverse), as in hr_object. */
#ifndef HITRAY_LIB_GEOMETRY_TRANSFORM_INLINE_H
#define HITRAY_LIB_GEOMETRY_TRANSFORM_INLINE_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <hitray/common.h>

/* Coordinate r (0, 1, 2) of M p and of M v: the operations of
 * hri_xform_point and hri_xform_vector for that row, in their order, so one
 * coordinate has the same bits as the whole product's. */
static inline double hri_xform_point_row(const double m[16], hr_vec3 p, int r)
{
    const double *row = m + 4 * r;
    return row[0] * p.x + row[1] * p.y + row[2] * p.z + row[3];
}
static inline double hri_xform_vector_row(const double m[16], hr_vec3 v, int r)
{
    const double *row = m + 4 * r;
    return row[0] * v.x + row[1] * v.y + row[2] * v.z;
}

/* M p (with translation). */
static inline hr_vec3 hri_xform_point(const double m[16], hr_vec3 p)
{
    hr_vec3 r = {hri_xform_point_row(m, p, 0), hri_xform_point_row(m, p, 1),
                 hri_xform_point_row(m, p, 2)};
    return r;
}

/* M v (no translation). */
static inline hr_vec3 hri_xform_vector(const double m[16], hr_vec3 v)
{
    hr_vec3 r = {hri_xform_vector_row(m, v, 0), hri_xform_vector_row(m, v, 1),
                 hri_xform_vector_row(m, v, 2)};
    return r;
}

/* (M^-1)^T n: a normal back to world space, given M^-1. */
static inline hr_vec3 hri_xform_normal(const double inv[16], hr_vec3 n)
{
    hr_vec3 r = {inv[0] * n.x + inv[4] * n.y + inv[8] * n.z,
                 inv[1] * n.x + inv[5] * n.y + inv[9] * n.z,
                 inv[2] * n.x + inv[6] * n.y + inv[10] * n.z};
    return r;
}

/* gamma(3) = 3u / (1 - 3u), u the unit roundoff: the bound on three
 * roundings that every error bound below uses. */
#define HR_XFORM_GAMMA3 (3.0 * DBL_EPSILON * 0.5 / (1.0 - 3.0 * DBL_EPSILON * 0.5))

/* What the error bound of M p (hri_xform_error) takes from M alone, per row:
 * the sum of |linear part| and |translation|. An object works them out
 * once, when its transform is set, instead of on every hit. */
typedef struct hr_xform_error_terms {
    double row_abs[3]; /* |m[4r]| + |m[4r+1]| + |m[4r+2]| */
    double shift_abs[3]; /* |m[4r+3]| */
} hr_xform_error_terms;

static inline hr_xform_error_terms hri_xform_error_terms_of(const double m[16])
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
 * gamma(3) (|M| |p| + |translation|) per row; k = hri_xform_error_terms_of(m). */
static inline double hri_xform_error_with(const double m[16], const hr_xform_error_terms *k,
                                         hr_vec3 p, double e)
{
    double worst = 0.0;
    /* Three rows: unrolled, the loop's counter and branch are a fifth of
     * its instructions (this runs for every hit of a transformed object). */
#pragma GCC unroll 3
    for (int r = 0; r < 3; r++) {
        const double *row = m + 4 * r;
        double carried = k->row_abs[r] * e;
        double rounding = HR_XFORM_GAMMA3 * (fabs(row[0] * p.x) + fabs(row[1] * p.y) + fabs(row[2] * p.z) +
                                    k->shift_abs[r]);
        double total = carried + rounding;
        if (total > worst) worst = total;
    }
    return worst;
}

/* --- Diagonal linear parts --------------------------------------------------
 *
 * A translate and a scale (most objects of Hill's scenes) leave the linear
 * part diagonal: every off-diagonal entry is +0 or -0. Each product above
 * then has one term a row that can matter, and the others add nothing,
 * bit for bit, wherever that term (or the translation) makes the row
 * non-zero: a zero entry times a finite coordinate is +0 or -0, and x + (+-0)
 * is x for every x != 0; only a row that comes out zero may depend on the
 * signs of the zeros added. So the one-term forms below are the full
 * products' bits whenever every coordinate they give is non-zero and
 * finite; a finite coordinate also says the coordinate it came from was
 * finite (an infinity or NaN there would have reached it through the
 * diagonal entry, or through 0 * inf = NaN). Otherwise they return the
 * full product. test_transform_diagonal compares the two on many millions
 * of points, zeros, subnormals, infinities and NaN among them. */

/* Every off-diagonal entry of m's linear part is zero. */
static inline int hri_xform_is_diagonal(const double m[16])
{
    return m[1] == 0 && m[2] == 0 && m[4] == 0 && m[6] == 0 && m[8] == 0 && m[9] == 0;
}

/* Every coordinate non-zero and finite, by one test of their product: a
 * zero, infinite or NaN coordinate makes it 0, an infinity or NaN (0 * inf
 * included), and an under- or overflow of the product can only turn a yes
 * into a no, which costs the full product and nothing else. Read from the
 * bits, 0 < |prod| <= DBL_MAX is one unsigned compare. */
static inline int hri_xform_nonzero_finite(hr_vec3 r)
{
    const double prod = r.x * r.y * r.z;
    uint64_t bits;
    memcpy(&bits, &prod, sizeof bits);
    return (bits & ~(UINT64_C(1) << 63)) - 1 < UINT64_C(0x7fefffffffffffff);
}

/* The one-term forms of M p and of (M^-1)^T n for a diagonal linear part,
 * into *r; 1 when they are the full products' bits (every coordinate
 * non-zero and finite, so the result is finite too), 0 otherwise. */
static inline int hri_xform_point_diagonal(const double m[16], hr_vec3 p, hr_vec3 *r)
{
    const hr_vec3 q = {m[0] * p.x + m[3], m[5] * p.y + m[7], m[10] * p.z + m[11]};
    *r = q;
    return hri_xform_nonzero_finite(q);
}
static inline int hri_xform_normal_diagonal(const double inv[16], hr_vec3 n, hr_vec3 *r)
{
    const hr_vec3 q = {inv[0] * n.x, inv[5] * n.y, inv[10] * n.z};
    *r = q;
    return hri_xform_nonzero_finite(q);
}

/* hri_xform_point, hri_xform_vector and hri_xform_normal, the same bits, one
 * term a row when `diagonal` (hri_xform_is_diagonal of the matrix given). */
static inline hr_vec3 hri_xform_point_as(const double m[16], int diagonal, hr_vec3 p)
{
    hr_vec3 r;
    if (diagonal && hri_xform_point_diagonal(m, p, &r)) return r;
    return hri_xform_point(m, p);
}
static inline hr_vec3 hri_xform_vector_as(const double m[16], int diagonal, hr_vec3 v)
{
    if (diagonal) {
        const hr_vec3 r = {m[0] * v.x, m[5] * v.y, m[10] * v.z};
        if (hri_xform_nonzero_finite(r)) return r;
    }
    return hri_xform_vector(m, v);
}
static inline hr_vec3 hri_xform_normal_as(const double inv[16], int diagonal, hr_vec3 n)
{
    hr_vec3 r;
    if (diagonal && hri_xform_normal_diagonal(inv, n, &r)) return r;
    return hri_xform_normal(inv, n);
}

/* hri_xform_error_with, the same bits, for a FINITE p: with m diagonal, a
 * row's |products| are +0 but for the diagonal one, and adding +0 to a sum
 * of magnitudes changes nothing (+0 + +0 is +0). */
static inline double hri_xform_error_as(const double m[16], const hr_xform_error_terms *k, int diagonal,
                                       hr_vec3 p, double e)
{
    if (!diagonal) return hri_xform_error_with(m, k, p, e);
    const double at[3] = {p.x, p.y, p.z};
    double worst = 0.0;
#pragma GCC unroll 3
    for (int r = 0; r < 3; r++) {
        double carried = k->row_abs[r] * e;
        double rounding = HR_XFORM_GAMMA3 * (fabs(m[5 * r] * at[r]) + k->shift_abs[r]);
        double total = carried + rounding;
        if (total > worst) worst = total;
    }
    return worst;
}

/* hri_xform_error_with for a matrix whose terms are not kept. */
static inline double hri_xform_error(const double m[16], hr_vec3 p, double e)
{
    const hr_xform_error_terms k = hri_xform_error_terms_of(m);
    return hri_xform_error_with(m, &k, p, e);
}

#endif
