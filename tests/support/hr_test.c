#include "hr_test.h"

#include <stdarg.h>
#include <stdint.h>
#include <string.h>

int hr_test_failures = 0;
unsigned long long hr_test_checks = 0;

void hr_test_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    hr_test_failures++;
    fprintf(stderr, "%s:%d: FAIL: ", file, line);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

int hr_test_end(void)
{
    fprintf(stderr, "%llu checks, %d failed\n", hr_test_checks, hr_test_failures);
    return hr_test_failures == 0 ? 0 : 1;
}

/* Map a double onto a monotonic integer line so ulps are a subtraction. */
static int64_t ordered_bits(double x)
{
    int64_t i;
    memcpy(&i, &x, sizeof i);
    return i < 0 ? INT64_MIN - i : i;
}

double hr_test_ulps(double a, double b)
{
    if (isnan(a) || isnan(b)) return HUGE_VAL;
    int64_t ia = ordered_bits(a), ib = ordered_bits(b);
    return ia > ib ? (double)((uint64_t)ia - (uint64_t)ib) : (double)((uint64_t)ib - (uint64_t)ia);
}
