/* hitray: affine transforms as Hill keeps them — a matrix and its inverse.
 *
 * Matrices are 4x4, row-major, acting on column vectors: p' = M p. Every
 * operation post-multiplies (M <- M * T; M^-1 <- T^-1 * M^-1), so the
 * transform applied last in code acts on the object first, as in OpenGL and
 * Hill's SDL. Inverses are built from the exact inverse of each step, never
 * by inverting the product. */
#ifndef HITRAY_TRANSFORM_H
#define HITRAY_TRANSFORM_H

#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hr_transform {
    double m[16];   /* object -> world, row-major */
    double inv[16]; /* world -> object */
} hr_transform;

HR_API void hr_transform_identity(hr_transform *t);
HR_API void hr_transform_translate(hr_transform *t, double dx, double dy, double dz);
/* A zero factor is refused (HR_ERROR_NUMERIC): the inverse would not exist.
 * So is a step after which the matrix or its inverse would leave double's
 * range (over- or underflow); a refused step leaves `t` unchanged. The same
 * holds for hr_transform_rotate. */
HR_API hr_status hr_transform_scale(hr_transform *t, double sx, double sy, double sz);
/* Right-handed rotation by `degrees` about the axis (normalised here); a
 * zero axis is refused (HR_ERROR_NUMERIC). */
HR_API hr_status hr_transform_rotate(hr_transform *t, double degrees,
                                     double ux, double uy, double uz);
/* t <- t * other (other applies to the object first). */
HR_API void hr_transform_compose(hr_transform *t, const hr_transform *other);
/* Set from an arbitrary matrix, computing the inverse; refuses a singular or
 * non-affine matrix (HR_ERROR_NUMERIC). */
HR_API hr_status hr_transform_from_matrix(hr_transform *t, const double m[16]);

HR_API hr_vec3 hr_transform_point(const double m[16], hr_vec3 p);
HR_API hr_vec3 hr_transform_vector(const double m[16], hr_vec3 v);
/* Normal transform: multiply by the transpose of `inv` (not normalised). */
HR_API hr_vec3 hr_transform_normal(const double inv[16], hr_vec3 n);

#ifdef __cplusplus
}
#endif
#endif
