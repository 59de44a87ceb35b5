/* The shape kit's power-of-two helpers (include/hitray/shape_kit_math.h)
 * against libm, bit for bit: they read frexp's exponent off a double's bits
 * and build 2^e from bits rather than call frexp and ldexp, on the host's
 * path for every normal it rescales, so any disagreement would move a
 * pixel. Checked on every binary exponent (subnormals included), on random
 * vectors whose components span the whole range, and on zero, infinities
 * and NaN, which no scaling helps. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <hitray/shape_kit.h>

#include "hr_test.h"

static uint64_t state = 0x9e3779b97f4a7c15ull;
static uint64_t next_bits(void)
{
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return state * 2685821657736338717ull;
}

/* A double of any finite magnitude, subnormals included, either sign. */
static double any_finite(void)
{
    for (;;) {
        uint64_t bits = next_bits();
        double x;
        memcpy(&x, &bits, sizeof x);
        if (isfinite(x)) return x;
    }
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* frexp's exponent of the largest |component|, as the kit must give it. */
static int reference_exponent(hr_vec3 v)
{
    int e;
    frexp(fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))), &e);
    return e;
}

static void check_exponent(hr_vec3 v)
{
    int e = 12345;
    CHECK_MSG(shape_vec3_scale_exponent(v, &e) == 1 && e == reference_exponent(v),
              "(%a %a %a): exponent %d, frexp's %d", v.x, v.y, v.z, e, reference_exponent(v));
}

static void check_ldexp(double x, int e)
{
    const double want = ldexp(x, e);
    CHECK_MSG(same_bits(shape_ldexp(x, e), want), "shape_ldexp(%a, %d) = %a, ldexp %a", x, e,
              shape_ldexp(x, e), want);
    const hr_vec3 v = shape_vec3_ldexp(shape_vec3(x, -x, x * 0.75), e);
    CHECK_MSG(same_bits(v.x, want) && same_bits(v.y, ldexp(-x, e)) && same_bits(v.z, ldexp(x * 0.75, e)),
              "shape_vec3_ldexp(%a, %d)", x, e);
}

int main(void)
{
    /* Every binary exponent, from the least subnormal to the largest normal,
     * in each component's place and with both signs. */
    for (int k = -1074; k <= 1023; k++) {
        const double p = ldexp(1.0, k), q = ldexp(1.5, k - 1);
        check_exponent(shape_vec3(p, 0.0, 0.0));
        check_exponent(shape_vec3(0.0, -q, 0.0));
        check_exponent(shape_vec3(p * 0.5, 0.0, -p));
    }
    check_exponent(shape_vec3(DBL_MAX, -DBL_MAX, 1.0));
    check_exponent(shape_vec3(DBL_MIN, DBL_TRUE_MIN, 0.0));

    /* Random components over the whole range. */
    for (int i = 0; i < 1000000; i++) check_exponent(shape_vec3(any_finite(), any_finite(), any_finite()));

    /* Zero and the non-finite give no exponent and leave it alone. */
    const hr_vec3 no_scale[] = {shape_vec3(0.0, -0.0, 0.0), shape_vec3(INFINITY, 1.0, 1.0),
                                shape_vec3(1.0, -INFINITY, 1.0), shape_vec3(1.0, 1.0, NAN),
                                shape_vec3(NAN, NAN, NAN)};
    for (size_t i = 0; i < sizeof no_scale / sizeof no_scale[0]; i++) {
        int e = 12345;
        CHECK_MSG(shape_vec3_scale_exponent(no_scale[i], &e) == 0 && e == 12345, "case %zu", i);
        const hr_vec3 r = shape_vec3_rescaled(no_scale[i]);
        CHECK(memcmp(&r, &no_scale[i], sizeof r) == 0);
    }

    /* 2^e products against ldexp, inside and beyond the normal exponents
     * (overflow, and rounding into the subnormals), for random x. */
    for (int e = -1100; e <= 1100; e++) {
        check_ldexp(1.0, e);
        for (int i = 0; i < 40; i++) check_ldexp(any_finite(), e);
    }

    /* Rescaled vectors: largest component in [0.5, 1), the others by the
     * same exact factor. */
    for (int i = 0; i < 200000; i++) {
        const hr_vec3 v = shape_vec3(any_finite(), any_finite(), any_finite());
        const hr_vec3 r = shape_vec3_rescaled(v);
        const double big = fmax(fabs(r.x), fmax(fabs(r.y), fabs(r.z)));
        CHECK_MSG(big >= 0.5 && big < 1.0, "(%a %a %a) rescaled to max %a", v.x, v.y, v.z, big);
        const int e = reference_exponent(v);
        CHECK(same_bits(r.x, ldexp(v.x, -e)) && same_bits(r.y, ldexp(v.y, -e)) &&
              same_bits(r.z, ldexp(v.z, -e)));
    }
    return hr_test_end();
}
