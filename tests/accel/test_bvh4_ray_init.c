/* The walk's ray preparation has two forms: accel_ray4_init_any for every
 * ray, and accel_ray4_init_common, three axes at a time in SSE2 lanes, for
 * the common one (tmin finite and >= 0, direction components at most 2^39
 * with one at least 2^-39, origin within ACCEL_CULL_RANGE). The walk's
 * conservativeness argument (the top of accel/bvh4.h) is made for the first;
 * the second must give the same accel_ray4 bit for bit wherever it accepts
 * a ray, so that every slab distance, every entry and with them the order
 * leaves are visited in (and every image) is the same whichever ran.
 *
 * The flipped form (accel_ray4_init_common_as with flipped set, what the
 * AVX2 walk runs) must equal the general one followed by accel_ray4_flip.
 *
 * Rays are drawn around every limit of the common case: direction
 * components of every size from 2^-80 to 2^80 and exactly at and next to
 * 2^-39, 2^39 and 1/ACCEL_INV_MAX (where 1/d turns to NaN), zeros of both
 * signs, infinities and NaN; origins up to 2^80 and at and next to 2^64;
 * tmin 0, -0, positive, negative, infinite and NaN. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "bvh4.h"
#include "hr_test.h"

static uint64_t rng_state = 0x243f6a8885a308d3ull;
static uint64_t next_bits(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return rng_state;
}
static double uniform(void) { return (double)(next_bits() >> 11) * 0x1p-53; } /* [0, 1) */
static int chance(double p) { return uniform() < p; }

/* A value of random sign: special values now and then, else one at or next
 * to one of `edges`, else 2^e with e uniform in [lo_exp, hi_exp) and a
 * random mantissa. */
static double draw(const double *edges, int n_edges, int lo_exp, int hi_exp)
{
    const double sign = chance(0.5) ? -1.0 : 1.0;
    const double u = uniform();
    if (u < 0.04) return sign * 0.0;
    if (u < 0.05) return sign * INFINITY;
    if (u < 0.055) return NAN;
    if (u < 0.25) {
        double e = edges[next_bits() % (uint64_t)n_edges];
        int step = (int)(next_bits() % 3) - 1;
        if (step < 0) e = nextafter(e, 0.0);
        if (step > 0) e = nextafter(e, INFINITY);
        return sign * e;
    }
    return sign * ldexp(1.0 + uniform(), lo_exp + (int)(next_bits() % (uint64_t)(hi_exp - lo_exp)));
}

static int same_bits(const void *a, const void *b, size_t size) { return memcmp(a, b, size) == 0; }

/* Every field the walk reads, bit for bit. */
static int same_ray4(const accel_ray4 *a, const accel_ray4 *b)
{
    int same = a->cull == b->cull && same_bits(&a->t_scale, &b->t_scale, sizeof a->t_scale) &&
               same_bits(&a->t_offset, &b->t_offset, sizeof a->t_offset);
    for (int k = 0; k < 3; k++) {
        same &= a->near_at[k] == b->near_at[k] && a->far_at[k] == b->far_at[k];
        same &= same_bits(&a->o_near[k], &b->o_near[k], sizeof a->o_near[k]);
        same &= same_bits(&a->o_far[k], &b->o_far[k], sizeof a->o_far[k]);
        same &= same_bits(&a->inv_near[k], &b->inv_near[k], sizeof a->inv_near[k]);
        same &= same_bits(&a->inv_far[k], &b->inv_far[k], sizeof a->inv_far[k]);
    }
    return same;
}

static void test_common_matches_any(void)
{
#if defined(__SSE2__)
    const double dir_edges[] = {0x1p-39, 0x1p39, 1.0 / ACCEL_INV_MAX, 0x1p-60, 0x1p60, 1.0};
    const double origin_edges[] = {ACCEL_CULL_RANGE, 0x1p-126, 0x1p-149, 1.0, 0x1p24};
    const double tmin_edges[] = {0.0, 0x1p-1074, 1e-9, 1.0, 1e300};
    const long rays = HR_TEST_SANITIZED ? 200000 : 2000000;
    long accepted = 0, rejected = 0, with_nan_axis = 0, with_zero_axis = 0, mismatched = 0;
    long flipped_mismatched = 0;
    for (long i = 0; i < rays; i++) {
        hr_ray ray;
        /* Mostly one direction scale for all three components, so the
         * common case is met often; sometimes each its own. */
        int shared = (int)(next_bits() % 160) - 80;
        double d[3];
        for (int a = 0; a < 3; a++)
            d[a] = chance(0.3) ? draw(dir_edges, 6, -80, 80)
                               : (chance(0.5) ? -1.0 : 1.0) * ldexp(1.0 + uniform(), shared / 2);
        ray.dir = (hr_vec3){d[0], d[1], d[2]};
        ray.origin = (hr_vec3){draw(origin_edges, 5, -30, 80), draw(origin_edges, 5, -30, 80),
                               draw(origin_edges, 5, -30, 80)};
        double tmin = chance(0.6) ? 0.0 : draw(tmin_edges, 5, -40, 40);
        accel_ray4 fast, any;
        memset(&fast, 0, sizeof fast);
        memset(&any, 0, sizeof any);
        accel_ray4_init_any(&any, &ray, tmin);
        if (!accel_ray4_init_common(&fast, &ray, tmin)) {
            rejected++;
            continue;
        }
        accepted++;
        int nan_axis = 0, zero_axis = 0;
        for (int a = 0; a < 3; a++) {
            nan_axis |= d[a] != 0 && !(fabs(1.0 / d[a]) <= ACCEL_INV_MAX);
            zero_axis |= d[a] == 0;
        }
        with_nan_axis += nan_axis;
        with_zero_axis += zero_axis;
        if (!same_ray4(&fast, &any) && mismatched++ < 5)
            CHECK_MSG(0, "ray %ld: origin (%a, %a, %a) dir (%a, %a, %a) tmin %a: the common preparation differs", i,
                      ray.origin.x, ray.origin.y, ray.origin.z, d[0], d[1], d[2], tmin);
        /* The flipped form (the AVX2 walk's) against the general one then
         * flipped, NaN lanes' signs included. */
        accel_ray4 fast_flipped;
        memset(&fast_flipped, 0, sizeof fast_flipped);
        CHECK(accel_ray4_init_common_as(&fast_flipped, &ray, tmin, 1));
        accel_ray4_flip(&any);
        if (!same_ray4(&fast_flipped, &any) && flipped_mismatched++ < 5)
            CHECK_MSG(0, "ray %ld: origin (%a, %a, %a) dir (%a, %a, %a) tmin %a: the flipped preparation differs",
                      i, ray.origin.x, ray.origin.y, ray.origin.z, d[0], d[1], d[2], tmin);
    }
    printf("ray preparation: %ld rays, %ld common (%ld with a NaN axis, %ld with a zero axis), %ld not, "
           "%ld differ, %ld flipped differ\n",
           rays, accepted, with_nan_axis, with_zero_axis, rejected, mismatched, flipped_mismatched);
    CHECK(mismatched == 0 && flipped_mismatched == 0);
    /* The draw reaches both sides of the common case's limits, and its
     * NaN and zero axes. */
    CHECK(accepted > rays / 10 && rejected > rays / 10);
    CHECK(with_nan_axis > 1000 && with_zero_axis > 1000);
#else
    printf("no SSE2: only the general preparation exists\n");
#endif
}

/* The common form declines what it does not cover, and writes nothing then. */
static void test_common_declines(void)
{
#if defined(__SSE2__)
    const hr_ray unit = {{0.5, -2.0, 3.0}, {0.25, 1.0, -0.5}};
    const struct {
        hr_ray ray;
        double tmin;
    } cases[] = {
        {unit, -1e-9},
        {unit, INFINITY},
        {unit, NAN},
        {{{0.5, -2.0, 3.0}, {0x1p39 * 1.5, 1.0, 1.0}}, 0.0},
        {{{0.5, -2.0, 3.0}, {0x1p-40, -0x1p-40, 0.0}}, 0.0},
        {{{0.5, -2.0, 3.0}, {NAN, 1.0, 1.0}}, 0.0},
        {{{0.5, -2.0, 3.0}, {1.0, INFINITY, 1.0}}, 0.0},
        {{{nextafter(ACCEL_CULL_RANGE, INFINITY), 0.0, 0.0}, {1.0, 0.0, 0.0}}, 0.0},
        {{{0.0, 0.0, NAN}, {1.0, 0.0, 0.0}}, 0.0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        accel_ray4 r;
        memset(&r, 0x5a, sizeof r);
        accel_ray4 untouched = r;
        CHECK_MSG(!accel_ray4_init_common(&r, &cases[i].ray, cases[i].tmin), "case %zu accepted", i);
        CHECK_MSG(!accel_ray4_init_common_as(&r, &cases[i].ray, cases[i].tmin, 1), "case %zu accepted", i);
        CHECK_MSG(memcmp(&r, &untouched, sizeof r) == 0, "case %zu written to", i);
    }
    accel_ray4 r;
    CHECK(accel_ray4_init_common(&r, &unit, 0.0) && r.cull == 1);
#endif
}

int main(void)
{
    test_common_matches_any();
    test_common_declines();
    return hr_test_end();
}
