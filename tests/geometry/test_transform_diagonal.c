/* The one-term forms of the affine products for a diagonal linear part
 * (lib/geometry/transform_inline.h: hri_xform_point_as, _vector_as, _normal_as,
 * hri_xform_error_as) against the full products, bit for bit. Tracing takes
 * a translated and scaled object's rays and hits through them, so every
 * image depends on their giving the full products' bits, signed zeros
 * and NaN included, for every input: matrices with diagonal entries of
 * every magnitude and sign, off-diagonal zeros of both signs, translations
 * zero (either sign), tiny or huge; coordinates zero (either sign),
 * subnormal, huge, infinite and NaN. Both ways out of the one-term forms
 * (their result, and the full product they fall back to) must be taken
 * often. Then hri_xform_is_diagonal on the pairs hr_transform builds. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "geometry/transform_inline.h"

static uint64_t rng_state = 0xbb67ae8584caa73bull;
static uint64_t next(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return rng_state;
}
static double uniform(void) { return (double)(next() >> 11) * 0x1p-53; } /* [0, 1) */
static double sign(void) { return next() % 2 ? -1.0 : 1.0; }

/* A coordinate: mostly ordinary, often one of the values where the signs
 * of zeros, underflow or non-finite arithmetic decide. */
static double coordinate(int finite)
{
    switch (next() % 16) {
    case 0: return sign() * 0.0;
    case 1: return sign() * 0x1p-1074 * (double)(1 + next() % 1000); /* subnormal */
    case 2: return sign() * ldexp(1.0 + uniform(), (int)(next() % 2000) - 1000);
    case 3: return finite ? sign() * DBL_MAX : sign() * INFINITY;
    case 4: return finite ? sign() * DBL_MIN : NAN;
    case 5: return (double)((int)(next() % 9) - 4);
    default: return sign() * (uniform() * 10.0);
    }
}

/* A diagonal entry (never zero: the matrix is invertible) and a
 * translation. */
static double diagonal_entry(void)
{
    switch (next() % 6) {
    case 0: return sign() * ldexp(1.0 + uniform(), (int)(next() % 1200) - 600);
    case 1: return sign() * (double)(1 + next() % 4);
    default: return sign() * (0.01 + uniform() * 100.0);
    }
}
static double translation(void)
{
    switch (next() % 6) {
    case 0: return sign() * 0.0;
    case 1: return sign() * ldexp(1.0 + uniform(), (int)(next() % 2000) - 1000);
    default: return sign() * uniform() * 100.0;
    }
}

static void random_diagonal(double m[16])
{
    for (int i = 0; i < 16; i++) m[i] = sign() * 0.0;
    m[0] = diagonal_entry(), m[5] = diagonal_entry(), m[10] = diagonal_entry();
    m[3] = translation(), m[7] = translation(), m[11] = translation();
    m[12] = m[13] = m[14] = 0.0, m[15] = 1.0;
}

/* The same bits, or NaN both: a NaN's sign and payload depend on which
 * operand of a sum or product the compiler put first (it may swap them),
 * and tracing drops every NaN it meets. */
static int same_double(double a, double b) { return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b)); }
static int same_vec(hr_vec3 a, hr_vec3 b)
{
    return same_double(a.x, b.x) && same_double(a.y, b.y) && same_double(a.z, b.z);
}

static void test_products(void)
{
    const long cases = HR_TEST_SANITIZED ? 300000 : 3000000;
    long fast = 0, full = 0, mismatched = 0;
    for (long i = 0; i < cases; i++) {
        double m[16];
        random_diagonal(m);
        CHECK(hri_xform_is_diagonal(m));
        const int finite = next() % 2;
        const hr_vec3 p = {coordinate(finite), coordinate(finite), coordinate(finite)};
        const hr_vec3 point = hri_xform_point_as(m, 1, p), vector = hri_xform_vector_as(m, 1, p),
                      normal = hri_xform_normal_as(m, 1, p);
        const hr_vec3 one_term = {m[0] * p.x + m[3], m[5] * p.y + m[7], m[10] * p.z + m[11]};
        if (hri_xform_nonzero_finite(one_term)) fast++;
        else full++;
        int same = same_vec(point, hri_xform_point(m, p)) && same_vec(vector, hri_xform_vector(m, p)) &&
                   same_vec(normal, hri_xform_normal(m, p));
        /* Not diagonal: always the full product. */
        same &= same_vec(hri_xform_point_as(m, 0, p), hri_xform_point(m, p));
        if (isfinite(p.x) && isfinite(p.y) && isfinite(p.z)) {
            const hr_xform_error_terms k = hri_xform_error_terms_of(m);
            const double e = next() % 4 ? uniform() * 1e-10 : fabs(coordinate(1));
            same &= same_double(hri_xform_error_as(m, &k, 1, p, e), hri_xform_error_with(m, &k, p, e));
        }
        if (!same && mismatched++ < 5)
            CHECK_MSG(0, "m diag (%a %a %a) shift (%a %a %a), p (%a %a %a): the one-term form differs", m[0],
                      m[5], m[10], m[3], m[7], m[11], p.x, p.y, p.z);
    }
    printf("diagonal products: %ld cases, %ld one-term, %ld full, %ld differ\n", cases, fast, full, mismatched);
    CHECK(mismatched == 0);
    CHECK(fast > cases / 10 && full > cases / 10);
}

/* Translations and scales give pairs whose linear parts are diagonal,
 * inverse included; a rotation does not. */
static void test_detection(void)
{
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, 0.25, -3.0, 7.5);
    hr_transform_scale(&t, 0.1, 2.0, -4.0);
    hr_transform_translate(&t, 1.0, 0.0, -2.0);
    CHECK(hri_xform_is_diagonal(t.m) && hri_xform_is_diagonal(t.inv));
    hr_transform_rotate(&t, 30.0, 0.0, 0.0, 1.0);
    CHECK(!hri_xform_is_diagonal(t.m) && !hri_xform_is_diagonal(t.inv));
}

int main(void)
{
    test_products();
    test_detection();
    return hr_test_end();
}
