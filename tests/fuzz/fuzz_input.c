#include "fuzz_input.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"

fuzz_input fuzz_input_make(const uint8_t *data, size_t size)
{
    fuzz_input in = {data, size, 0};
    return in;
}

uint8_t fuzz_byte(fuzz_input *in)
{
    return in->used < in->size ? in->data[in->used++] : 0;
}

unsigned fuzz_choice(fuzz_input *in, unsigned n)
{
    return n ? fuzz_byte(in) % n : 0;
}

int fuzz_more(const fuzz_input *in)
{
    return in->used < in->size;
}

static uint64_t fuzz_bits(fuzz_input *in, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++) v = v << 8 | fuzz_byte(in);
    return v;
}

/* Values that sit on the edges of double arithmetic or of the shapes'
 * geometry (faces at +-1, the torus's default tube, one ulp off 1). */
static const double special_values[] = {
    0.0,     -0.0,     1.0,          -1.0,         0.5,      -0.5,     2.0,
    0.2,     0.8,      1.2,          1e-6,         1e-12,    1e-300,   DBL_MIN,
    -DBL_MIN, DBL_TRUE_MIN, -DBL_TRUE_MIN, 1e6,      -1e6,     1e15,     1e150,
    1e300,   DBL_MAX,  -DBL_MAX,     1.0 + DBL_EPSILON,      1.0 - DBL_EPSILON / 2,
    -1.0 - DBL_EPSILON, 0.999,       1e-162,       3.0,      1000.0,   INFINITY, -INFINITY,
};

double fuzz_double(fuzz_input *in)
{
    const uint8_t kind = fuzz_byte(in);
    switch (kind % 4) {
    case 0: { /* a small multiple of 1/16 */
        return ((int)fuzz_byte(in) - 128) / 16.0;
    }
    case 1: {
        const size_t n = sizeof special_values / sizeof special_values[0];
        return special_values[fuzz_byte(in) % n];
    }
    case 2: { /* a 16-bit significand at a binary exponent in [-64, 63] */
        const double m = ((double)fuzz_bits(in, 2) - 32768.0) / 32768.0;
        return ldexp(m, (int)(fuzz_byte(in) % 128) - 64);
    }
    default: { /* any bit pattern */
        const uint64_t bits = fuzz_bits(in, 8);
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    }
}

double fuzz_double_in(fuzz_input *in, double lo, double hi)
{
    const double f = (double)fuzz_bits(in, 2) / 65535.0;
    return lo + (hi - lo) * f;
}

void fuzz_require_no_failures(const char *what)
{
    if (hr_test_failures == 0) return;
    fprintf(stderr, "%s: %d contract check(s) failed (above)\n", what, hr_test_failures);
    abort();
}

void fuzz_fail(const char *fmt, ...)
{
    va_list ap;
    fputs("contract broken: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    abort();
}
