/* Hill's transform pairs: worked examples and exactness. */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static void check_matrix(const double got[16], const double want[16], double tol, const char *what)
{
    for (int i = 0; i < 16; i++)
        CHECK_MSG(fabs(got[i] - want[i]) <= tol, "%s[%d][%d] = %.17g, expected %.17g", what,
                  i / 4, i % 4, got[i], want[i]);
}

int main(void)
{
    /* Hill's example: translate 2 4 9 then scale 1 4 4 gives M = T S and
     * M^-1 = S^-1 T^-1. The lecture slide prints -4 in M^-1's second row; the
     * product gives -1 (= -4 * 1/4): the slide has a typo. Exact in binary. */
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, 2, 4, 9);
    CHECK_OK(hr_transform_scale(&t, 1, 4, 4));
    const double m[16] = {1, 0, 0, 2, 0, 4, 0, 4, 0, 0, 4, 9, 0, 0, 0, 1};
    const double inv[16] = {1, 0, 0, -2, 0, 0.25, 0, -1, 0, 0, 0.25, -2.25, 0, 0, 0, 1};
    check_matrix(t.m, m, 0.0, "M");
    check_matrix(t.inv, inv, 0.0, "M^-1");

    /* The same from the raw matrix: the computed inverse is exact here too. */
    hr_transform u;
    CHECK_OK(hr_transform_from_matrix(&u, m));
    check_matrix(u.inv, inv, 0.0, "inverse of M");

    /* Quarter turns are exact: rotate 90 about z maps x to y. */
    hr_transform r;
    hr_transform_identity(&r);
    CHECK_OK(hr_transform_rotate(&r, 90, 0, 0, 2));
    hr_vec3 x = {1, 0, 0};
    hr_vec3 y = hr_transform_point(r.m, x);
    CHECK(y.x == 0 && y.y == 1 && y.z == 0);
    hr_vec3 back = hr_transform_point(r.inv, y);
    CHECK(back.x == 1 && back.y == 0 && back.z == 0);

    /* A general rotation: M M^-1 = I within a few ulps (Rodrigues'
     * matrix is orthonormal to rounding, its transpose the inverse). */
    hr_transform g;
    hr_transform_identity(&g);
    CHECK_OK(hr_transform_rotate(&g, 33.3, 1, 2, 3));
    hr_transform_translate(&g, 5, -7, 1e3);
    CHECK_OK(hr_transform_scale(&g, 2, 3, 0.5));
    hr_transform prod = g;
    hr_transform inverse_only;
    for (int i = 0; i < 16; i++) inverse_only.m[i] = g.inv[i], inverse_only.inv[i] = g.m[i];
    hr_transform_compose(&prod, &inverse_only);
    const double id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    /* Entries of M reach ~1e3 (the translation), so 1e-12 is ~10 ulps of it. */
    check_matrix(prod.m, id, 1e-12, "M*M^-1");

    /* Normals go through the transpose of the inverse: a sphere scaled by
     * (1, 4, 4) has at object point (0, 1, 1)/sqrt2 the world normal
     * proportional to (0, 1/4, 1/4), i.e. direction (0, 1, 1). */
    hr_vec3 n = hr_transform_normal(t.inv, (hr_vec3){0, 1, 1});
    CHECK(n.x == 0 && n.y == 0.25 && n.z == 0.25);

    /* Refusals: zero scale, zero axis, singular or non-affine matrix. */
    CHECK(hr_transform_scale(&t, 0, 1, 1) == HR_ERROR_NUMERIC);
    CHECK(hr_transform_rotate(&t, 10, 0, 0, 0) == HR_ERROR_NUMERIC);
    /* Each step fine, the product out of range: refused, t unchanged. */
    hr_transform w;
    hr_transform_identity(&w);
    CHECK_OK(hr_transform_scale(&w, 1e-200, 1, 1));
    hr_transform kept = w;
    CHECK(hr_transform_scale(&w, 1e-200, 1, 1) == HR_ERROR_NUMERIC);
    CHECK(memcmp(&w, &kept, sizeof w) == 0);
    const double singular[16] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK(hr_transform_from_matrix(&u, singular) == HR_ERROR_NUMERIC);
    /* Badly scaled is not singular: diag(1e6, 1e-6, 1) has condition 1e12
     * and an exact inverse; a matrix with two rows equal to 1e-16 is. */
    const double skewed[16] = {1e6, 0, 0, 0, 0, 1e-6, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK_OK(hr_transform_from_matrix(&u, skewed));
    CHECK(u.inv[0] == 1e-6 && u.inv[5] == 1e6 && u.inv[10] == 1);
    const double nearly[16] = {1, 1, 0, 0, 1, 1 + 0x1p-52, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    CHECK(hr_transform_from_matrix(&u, nearly) == HR_ERROR_NUMERIC);
    const double projective[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};
    CHECK(hr_transform_from_matrix(&u, projective) == HR_ERROR_NUMERIC);
    return hr_test_end();
}
