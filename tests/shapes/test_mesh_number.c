/* The mesh readers' number reader (mesh_parse_number: the decimal grammar
 * checked in C, the conversion by fast_float behind mesh_decimal_to_double)
 * against strtod, which the readers used before: on every input both must
 * give the same answer (a number, not a number, out of range) and, for a
 * number, the same bits (the sign of zero included).
 *
 * The inputs: random doubles of every exponent printed with %.17g (exact
 * round trip), fewer digits (rounding), %e with 25 digits (more than a
 * double holds) and %f (long integers and long fractions); coordinates as
 * mesh files write them; the points halfway between neighbouring doubles,
 * normal and subnormal, written exactly (in long double) and then cut to
 * 40, 200 and 480 digits (the hardest cases of round-half-even, which need
 * fast_float's big-number path); a list of edge cases (the range limits of
 * double and of the readers, subnormals, overflow, underflow, huge
 * exponents, signs, hex, inf, nan, malformed text); and random strings over
 * the grammar's alphabet and a few other characters.
 *
 * The reference is strtod in the "C" locale on a NUL-terminated copy, kept
 * to the readers' rules: the whole token is one number, only decimal
 * characters (so no hex, inf or nan), shorter than 504 bytes, finite and
 * within MESH_MAX_COORDINATE. */
#include <locale.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"
#include "mesh_text.h"
#include "random_rays.h"

static long compared, mismatches;

static int reference_parse(const char *s, size_t n, double *out)
{
    if (n == 0 || n >= 504) return 0;
    for (size_t i = 0; i < n; i++)
        if (s[i] == '\0' || !strchr("0123456789+-.eE", s[i])) return 0;
    char buffer[512];
    memcpy(buffer, s, n);
    buffer[n] = '\0';
    char *end = NULL;
    const double value = strtod(buffer, &end);
    if (end != buffer + n) return 0;
    if (!isfinite(value) || fabs(value) > MESH_MAX_COORDINATE) return -1;
    *out = value;
    return 1;
}

static void compare_text(const char *s, size_t n)
{
    double expected = 0.0, got = 0.0;
    const int want = reference_parse(s, n, &expected);
    const mesh_token tok = {s, n, 1};
    const int have = mesh_parse_number(&tok, &got);
    compared++;
    if (want == have && (want != 1 || memcmp(&expected, &got, sizeof got) == 0)) return;
    if (mismatches++ < 20)
        fprintf(stderr, "'%.*s': strtod %d %a, mesh_parse_number %d %a\n", (int)(n < 80 ? n : 80),
                s, want, want == 1 ? expected : 0.0, have, have == 1 ? got : 0.0);
}

static void compare(const char *s)
{
    compare_text(s, strlen(s));
}

/* The same number with a '+', with 'E', and negated. */
static void compare_variants(const char *s)
{
    char buffer[1100];
    compare(s);
    if (s[0] != '-' && s[0] != '+') {
        snprintf(buffer, sizeof buffer, "+%s", s);
        compare(buffer);
        snprintf(buffer, sizeof buffer, "-%s", s);
        compare(buffer);
    }
    snprintf(buffer, sizeof buffer, "%s", s);
    char *e = strchr(buffer, 'e');
    if (e) {
        *e = 'E';
        compare(buffer);
    }
}

static double random_double(ray_rng *rng)
{
    for (;;) {
        uint64_t bits = rng_next(rng);
        double d;
        memcpy(&d, &bits, sizeof d);
        if (isfinite(d)) return d;
    }
}

static void random_doubles(ray_rng *rng, int count)
{
    static const char *const formats[] = {"%.17g", "%.16g", "%.15g", "%.9g", "%.6g", "%.1g",
                                          "%.25e", "%.3e"};
    char buffer[1100];
    for (int i = 0; i < count; i++) {
        const double d = random_double(rng);
        for (size_t f = 0; f < sizeof formats / sizeof *formats; f++) {
            snprintf(buffer, sizeof buffer, formats[f], d);
            compare_variants(buffer);
        }
        /* %f: up to 309 integer digits, or a long fraction. */
        if (fabs(d) < 1e200 && fabs(d) > 1e-200) {
            snprintf(buffer, sizeof buffer, "%.*f", (int)(rng_next(rng) % 40), d);
            compare(buffer);
        }
    }
}

/* Coordinates of the kind mesh files hold. */
static void coordinates(ray_rng *rng, int count)
{
    char buffer[64];
    for (int i = 0; i < count; i++) {
        const double x = rng_uniform(rng, -10.0, 10.0) * pow(10.0, (double)(rng_next(rng) % 7) - 3);
        snprintf(buffer, sizeof buffer, "%.*g", 1 + (int)(rng_next(rng) % 17), x);
        compare(buffer);
        snprintf(buffer, sizeof buffer, "%.*f", (int)(rng_next(rng) % 12), x);
        compare(buffer);
    }
}

/* The exact midpoint between d and the next double up, d >= 0, written
 * with `digits` significant digits (long double holds the midpoint
 * exactly, and glibc prints long doubles exactly). */
static void midpoint(double d, int digits)
{
    const double next = nextafter(d, INFINITY);
    if (!isfinite(next)) return;
    const long double mid = ((long double)d + (long double)next) / 2.0L;
    char buffer[1100];
    snprintf(buffer, sizeof buffer, "%.*Le", digits - 1, mid);
    compare_variants(buffer);
}

static void midpoints(ray_rng *rng, int count)
{
    static const int digits[] = {40, 200, 480};
    for (int i = 0; i < count; i++) {
        double d = fabs(random_double(rng));
        /* A third of them subnormal, a third near 1. */
        if (i % 3 == 1) d = ldexp(d, -1074 - ilogb(d) + (int)(rng_next(rng) % 52));
        if (i % 3 == 2) d = ldexp(d, -ilogb(d) + (int)(rng_next(rng) % 9) - 4);
        for (size_t k = 0; k < sizeof digits / sizeof *digits; k++) midpoint(d, digits[k]);
    }
}

static void edge_cases(void)
{
    static const char *const cases[] = {
        /* The readers' range: 1e100 is in, the double after it out. */
        "1e100", "1.0000000000000000e100", "1.00000000000000016e100", "1.0000000000000002e100",
        "-1e100", "100000000000000000000000000000000000000000000000000000000000000000000000000000"
                  "00000000000000000000000", "9.999999999999999e99",
        /* Double's range. */
        "1.7976931348623157e308", "1.7976931348623158e308", "1.7976931348623159e308", "1e309",
        "2.2250738585072014e-308", "2.2250738585072011e-308", "2.2250738585072012e-308",
        "4.9406564584124654e-324", "2.4703282292062328e-324", "2.4703282292062327e-324",
        "2.470328229206232720882538e-324", "1e-324", "1e-400", "-1e-400", "0e999999999999",
        "1e999999999999999999999", "1e-999999999999999999999", "-0", "+0", "0", "-0.0", "0.0e0",
        "00000000000000000000000000000000000001", "0.000000000000000000000000000000000000001",
        /* Forms of the grammar. */
        ".5", "5.", "-.5", "+5.", "1.e5", ".1e-5", "1E+05", "1e-05", "007", "1e0000000000000000005",
        "123456789012345678901234567890", "0.1", "0.2", "0.3", "9007199254740993",
        "9007199254740992.5", "9007199254740993.0000000000000000000000000000001",
        /* Not numbers. */
        "", "+", "-", ".", "e", "e5", ".e5", "1e", "1e+", "1e-", "+-1", "-+1", "--1", "++1",
        "1.2.3", "1,5", "1e5.5", "1e5e5", " 1", "1 ", "1d5", "1f", "0x10", "0x1p3", "0X1P-3",
        "inf", "-inf", "+inf", "infinity", "INF", "nan", "-nan", "NaN", "nan(1)", "1e+-5", "-e5",
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) compare_variants(cases[i]);
    /* Lengths around the 504-byte limit. */
    char buffer[600];
    for (size_t n = 500; n < 508; n++) {
        memset(buffer, '1', n);
        buffer[1] = '.';
        buffer[n] = '\0';
        compare(buffer);
    }
    /* A NUL inside the token: strtod would stop there. */
    compare_text("1\0" "5", 3);
}

static void random_strings(ray_rng *rng, int count)
{
    static const char alphabet[] = "0123456789+-.eE0123456789.e-xXpinfaINFA ,_";
    char buffer[32];
    for (int i = 0; i < count; i++) {
        const size_t n = 1 + rng_next(rng) % 24;
        /* Mostly the grammar's own characters, which make near-numbers. */
        const size_t letters = rng_chance(rng, 0.8) ? 26 : sizeof alphabet - 1;
        for (size_t k = 0; k < n; k++) buffer[k] = alphabet[rng_next(rng) % letters];
        compare_text(buffer, n);
    }
}

/* The readers read '.' whatever the locale: under one with a decimal comma
 * (where one is installed), the same bits as in "C". */
static void comma_locale(void)
{
    static const char *const names[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "de_DE"};
    const char *used = NULL;
    for (size_t i = 0; i < sizeof names / sizeof *names && !used; i++)
        if (setlocale(LC_NUMERIC, names[i])) used = names[i];
    if (!used) {
        printf("no decimal-comma locale installed: the locale check is skipped\n");
        return;
    }
    double value = 0.0;
    const mesh_token tok = {"0.1", 3, 1};
    CHECK(mesh_parse_number(&tok, &value) == 1 && value == 0.1);
    const mesh_token comma = {"0,1", 3, 1};
    CHECK(mesh_parse_number(&comma, &value) == 0);
    setlocale(LC_NUMERIC, "C");
}

int main(void)
{
    ray_rng rng;
    rng_seed(&rng, 12);
    edge_cases();
    random_doubles(&rng, 60000);
    coordinates(&rng, 200000);
    midpoints(&rng, 20000);
    random_strings(&rng, 400000);
    comma_locale();
    printf("%ld texts compared with strtod, %ld differ\n", compared, mismatches);
    CHECK(compared > 1000000);
    CHECK_MSG(mismatches == 0, "%ld of %ld texts read differently from strtod", mismatches,
              compared);
    return hr_test_end();
}
