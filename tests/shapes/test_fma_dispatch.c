/* SHAPE_FMA_DISPATCH (include/hitray/shape_kit_cpu.h): the copy built for
 * FMA CPUs and the baseline copy give the same bits, on a body made of what
 * the shapes' hot functions are made of: compensated sums of products
 * (fma() inside), Kahan's difference of products, and plain a * b + c,
 * which a compiler that contracts (clang's default -ffp-contract=on, GCC's
 * GNU modes) would fuse in the FMA copy only. The build's -ffp-contract=off
 * keeps them apart; built with contraction, this test fails. Also: the
 * dispatcher returns what the copy for this CPU returns, and the void form
 * does the same through a pointer. Runs the FMA copy only where the CPU has
 * FMA. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <hitray/shape_kit.h>

#include "hr_test.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint64_t next(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return rng_state;
}
static double uniform(void) { return (double)(next() >> 11) * 0x1p-53; } /* [0, 1) */
static double value(void)
{
    const double sign = next() % 2 ? -1.0 : 1.0;
    switch (next() % 6) {
    case 0: return sign * ldexp(1.0 + uniform(), (int)(next() % 200) - 100);
    case 1: return (double)((int)(next() % 9) - 4);
    default: return sign * uniform() * 8.0;
    }
}

SHAPE_FMA_DISPATCH(double, mixed, (const double *v), (v))
{
    shape_sum s = shape_sum_start(v[0]);
    shape_sum_add_product(&s, v[1], v[2]);
    shape_sum_add_product(&s, v[3], v[4]);
    const double kahan = shape_difference_of_products(v[5], v[6], v[7], v[0]);
    const double plain = v[1] * v[2] + v[3] * v[4] + v[5]; /* fused where contraction is on */
    return shape_sum_value(s) + kahan * plain;
}

SHAPE_FMA_DISPATCH_VOID(mixed_into, (const double *v, double *out), (v, out)) { *out = mixed_body(v); }

static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

int main(void)
{
    const long trials = HR_TEST_SANITIZED ? 200000 : 2000000;
    long differ = 0, checked = 0, dispatch_wrong = 0;
    for (long i = 0; i < trials; i++) {
        double v[8];
        for (int k = 0; k < 8; k++) v[k] = value();
        const double base = mixed_baseline(v);
        double chosen = base;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
        if (shape_cpu_has_fma()) {
            chosen = mixed_fma(v);
            checked++;
            if (!same(chosen, base) && differ++ < 5)
                CHECK_MSG(0, "v = %a %a %a %a %a %a %a %a: FMA copy %a, baseline %a", v[0], v[1], v[2],
                          v[3], v[4], v[5], v[6], v[7], chosen, base);
        }
#endif
        double via_void;
        mixed_into(v, &via_void);
        dispatch_wrong += !same(mixed(v), chosen) || !same(via_void, chosen);
    }
    printf("SHAPE_FMA_DISPATCH: %ld inputs, %ld through the FMA copy, %ld differ\n", trials, checked, differ);
    CHECK(differ == 0);
    CHECK(dispatch_wrong == 0);
    return hr_test_end();
}
