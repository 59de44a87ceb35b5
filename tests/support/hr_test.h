/* A minimal assertion helper for the C tests: checks count failures and
 * print where they happened; a test's main ends with `return hr_test_end();`
 * which exits non-zero if any check failed. */
#ifndef HR_TEST_H
#define HR_TEST_H

#include <math.h>
#include <stdio.h>

/* 1 under AddressSanitizer or ThreadSanitizer (gcc or clang), which make
 * every load and allocation several times slower: the large tests scale
 * down there. */
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define HR_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define HR_TEST_SANITIZED 1
#endif
#endif
#ifndef HR_TEST_SANITIZED
#define HR_TEST_SANITIZED 0
#endif

extern int hr_test_failures;
/* Wide: a fuzz harness checks its contract through these macros for
 * every input, and a 30-minute mesh run passed 2^31 checks (an int's
 * overflow, which UBSan stops the run on). */
extern unsigned long long hr_test_checks;

void hr_test_fail(const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
int hr_test_end(void);
/* Distance in units in the last place between two doubles (0 if equal,
 * huge if either is NaN or they differ in sign). */
double hr_test_ulps(double a, double b);

#define CHECK(cond)                                                            \
    do {                                                                       \
        hr_test_checks++;                                                      \
        if (!(cond)) hr_test_fail(__FILE__, __LINE__, "CHECK(%s)", #cond);     \
    } while (0)

#define CHECK_MSG(cond, ...)                                                   \
    do {                                                                       \
        hr_test_checks++;                                                      \
        if (!(cond)) hr_test_fail(__FILE__, __LINE__, __VA_ARGS__);            \
    } while (0)

/* |a - b| <= tol, and neither is NaN. */
#define CHECK_NEAR(a, b, tol)                                                  \
    do {                                                                       \
        double hr_a_ = (double)(a), hr_b_ = (double)(b), hr_t_ = (double)(tol); \
        hr_test_checks++;                                                      \
        if (!(fabs(hr_a_ - hr_b_) <= hr_t_))                                   \
            hr_test_fail(__FILE__, __LINE__, "%s = %.17g, expected %s = %.17g (tol %g)", \
                         #a, hr_a_, #b, hr_b_, hr_t_);                         \
    } while (0)

/* A call returning hr_status must return HR_OK. */
#define CHECK_OK(expr)                                                         \
    do {                                                                       \
        int hr_s_ = (int)(expr);                                               \
        hr_test_checks++;                                                      \
        if (hr_s_ != 0) hr_test_fail(__FILE__, __LINE__, "%s returned %d", #expr, hr_s_); \
    } while (0)

#endif
