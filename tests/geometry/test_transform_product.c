/* The products behind every transform step, bit for bit: hr_transform_compose
 * (t <- t * o, t^-1 <- o^-1 * t^-1) against the textbook triple loop, whose
 * sum order ((((0 + p0) + p1) + p2) + p3) is the one scenes were built with.
 * Random entries of every magnitude, with signed zeros (0 + -0 is +0, so the
 * leading 0 matters), exact small integers (ties in rounding) and infinities
 * (inf * 0 = NaN): every entry must be the same double, NaN where the loop
 * gives NaN. Translate and scale, which skip the product for a finite
 * pair, against it the same way. Then the checked steps: a scale or
 * rotation that over- or underflows is refused and leaves the pair as it
 * was. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static uint64_t rng_state = 0x6a09e667f3bcc909ull;
static uint64_t next(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return rng_state;
}
static double uniform(void) { return (double)(next() >> 11) * 0x1p-53; }

static double entry(void)
{
    switch (next() % 8) {
    case 0: return 0.0;
    case 1: return -0.0;
    case 2: return (double)((int)(next() % 9) - 4);
    case 3: return next() % 64 ? ldexp(uniform() - 0.5, (int)(next() % 200) - 100)
                               : (next() % 2 ? INFINITY : -INFINITY);
    default: return (uniform() - 0.5) * 10.0;
    }
}

static void reference_product(double r[16], const double a[16], const double b[16])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += a[4 * i + k] * b[4 * k + j];
            r[4 * i + j] = s;
        }
}

static int same_double(double a, double b)
{
    return (isnan(a) && isnan(b)) || memcmp(&a, &b, sizeof a) == 0;
}

int main(void)
{
    long entries = 0, differing = 0;
    for (int trial = 0; trial < 20000; trial++) {
        hr_transform t, o;
        for (int i = 0; i < 16; i++) t.m[i] = entry(), t.inv[i] = entry(), o.m[i] = entry(), o.inv[i] = entry();
        double m[16], inv[16];
        reference_product(m, t.m, o.m);
        reference_product(inv, o.inv, t.inv);
        hr_transform_compose(&t, &o);
        for (int i = 0; i < 16; i++) {
            int same = same_double(t.m[i], m[i]) && same_double(t.inv[i], inv[i]);
            CHECK_MSG(same, "trial %d entry %d: M %a / %a, M^-1 %a / %a", trial, i, t.m[i], m[i],
                      t.inv[i], inv[i]);
            entries += 2, differing += !same;
        }
    }
    fprintf(stderr, "%ld product entries compared with the triple loop, %ld differing\n", entries,
            differing);

    /* Translate and scale, which skip the product for a finite pair
     * (lib/geometry/transform.c), against it: the same pair bit for bit,
     * -0 entries and overflow included, and the same refusals. Half the
     * pairs are finite (the fast steps), half may hold infinities. */
    long steps = 0, step_differing = 0;
    for (int trial = 0; trial < 40000; trial++) {
        hr_transform t;
        for (int i = 0; i < 16; i++) {
            t.m[i] = entry(), t.inv[i] = entry();
            if (trial % 2) t.m[i] = isfinite(t.m[i]) ? t.m[i] : -0.0, t.inv[i] = isfinite(t.inv[i]) ? t.inv[i] : 0.0;
        }
        double v[3];
        for (int a = 0; a < 3; a++) {
            v[a] = entry();
            if (trial % 4 < 2 && !isfinite(v[a])) v[a] = -0.0;
        }
        double step[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, step_inv[16];
        memcpy(step_inv, step, sizeof step);
        double m[16], inv[16];
        hr_transform got = t;
        int same = 1;
        if (trial % 3) {
            step[3] = v[0], step[7] = v[1], step[11] = v[2];
            step_inv[3] = -v[0], step_inv[7] = -v[1], step_inv[11] = -v[2];
            reference_product(m, t.m, step);
            reference_product(inv, step_inv, t.inv);
            hr_transform_translate(&got, v[0], v[1], v[2]);
        } else {
            for (int a = 0; a < 3; a++) {
                if (v[a] == 0 || !isfinite(v[a])) v[a] = 0.75; /* refused before any product */
                step[5 * a] = v[a], step_inv[5 * a] = 1.0 / v[a];
            }
            reference_product(m, t.m, step);
            reference_product(inv, step_inv, t.inv);
            int finite = isfinite(step_inv[0]) && isfinite(step_inv[5]) && isfinite(step_inv[10]);
            for (int i = 0; i < 16; i++) finite = finite && isfinite(m[i]) && isfinite(inv[i]);
            const hr_status st = hr_transform_scale(&got, v[0], v[1], v[2]);
            same = st == (finite ? HR_OK : HR_ERROR_NUMERIC);
            if (!finite) memcpy(m, t.m, sizeof m), memcpy(inv, t.inv, sizeof inv);
        }
        for (int i = 0; i < 16; i++) same = same && same_double(got.m[i], m[i]) && same_double(got.inv[i], inv[i]);
        CHECK_MSG(same, "step trial %d (%s) differs from the product", trial, trial % 3 ? "translate" : "scale");
        steps++, step_differing += !same;
    }
    fprintf(stderr, "%ld translate and scale steps compared with the product, %ld differing\n", steps,
            step_differing);

    /* Scale 1e-200 twice underflows M and overflows M^-1: refused, unchanged. */
    hr_transform t, before;
    hr_transform_identity(&t);
    hr_transform_translate(&t, 1, -0.0, 3);
    CHECK_OK(hr_transform_scale(&t, 1e-200, 1e-200, 1e-200));
    before = t;
    CHECK(hr_transform_scale(&t, 1e-200, 1, 1) == HR_ERROR_NUMERIC);
    CHECK(memcmp(&t, &before, sizeof t) == 0);
    CHECK(hr_transform_scale(&t, 1e-310, 1, 1) == HR_ERROR_NUMERIC);
    CHECK(memcmp(&t, &before, sizeof t) == 0);
    /* A rotation applied to a pair holding an infinity: refused. */
    t.m[3] = INFINITY;
    before = t;
    CHECK(hr_transform_rotate(&t, 30, 0, 0, 1) == HR_ERROR_NUMERIC);
    CHECK(memcmp(&t, &before, sizeof t) == 0);
    return hr_test_end();
}
