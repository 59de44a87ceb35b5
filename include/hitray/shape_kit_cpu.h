/* hitray shape kit: what this CPU can run (part of <hitray/shape_kit.h>; see
 * there), for a module or the host that keeps a faster path beside the
 * baseline x86-64 one.
 *
 * Read off CPUID and XGETBV directly rather than through
 * __builtin_cpu_supports: that builtin reads a CPU model filled in by the
 * compiler's runtime at load, and some toolchains' runtimes (zig's, which
 * builds the manylinux wheels) leave it all zero, so every check said "no"
 * and the wheels ran the baseline paths only. The answer is worked out once
 * per translation unit and kept; later calls are a load and a test.
 *
 * The environment variable HITRAY_CPU (SHAPE_CPU_ENV) narrows what every
 * such test answers, so that each path can be forced and compared (the
 * images must be the same on every path): "sse2", the baseline x86-64
 * paths alone; "fma", the FMA paths but not the AVX2 ones; "avx2", both
 * (x86-64-v3, which has both); "native" or unset, what the CPU has. It can
 * only take paths away: a value asking for more than the CPU has, or one
 * not listed, leaves what the CPU has, and the library refuses both with a
 * message (hr_scene_create). It is read when a translation unit first asks,
 * so it must be set before the program starts. */
#ifndef HITRAY_SHAPE_KIT_CPU_H
#define HITRAY_SHAPE_KIT_CPU_H

#include <stdlib.h>
#include <string.h>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

#define SHAPE_CPU_KNOWN 1u /* the probe ran */
#define SHAPE_CPU_FMA 2u   /* FMA3, with the OS keeping AVX state */
#define SHAPE_CPU_AVX2 4u  /* AVX2, with the OS keeping AVX state */

/* The features, probed now: CPUID leaf 1 (FMA, AVX, OSXSAVE), XGETBV's XCR0
 * (the OS saves the XMM and YMM registers: bits 1 and 2), CPUID leaf 7
 * (AVX2). AVX-class features count only where the OS saves the YMM state, as
 * libgcc's own checks do. */
static inline unsigned shape_cpu_probe(void)
{
    unsigned features = SHAPE_CPU_KNOWN;
#if defined(__x86_64__) || defined(__i386__)
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d)) return features;
    const int fma = (c >> 12) & 1, osxsave = (c >> 27) & 1, avx = (c >> 28) & 1;
    if (!osxsave || !avx) return features;
    unsigned xcr0_lo, xcr0_hi;
    __asm__ volatile("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
    (void)xcr0_hi;
    if ((xcr0_lo & 6u) != 6u) return features;
    if (fma) features |= SHAPE_CPU_FMA;
    if (__get_cpuid_count(7, 0, &a, &b, &c, &d) && ((b >> 5) & 1)) features |= SHAPE_CPU_AVX2;
#endif
    return features;
}

/* The environment variable that forces a CPU path, and its values. */
#define SHAPE_CPU_ENV "HITRAY_CPU"
#define SHAPE_CPU_CHOICES "native, sse2, fma or avx2"

/* The features HITRAY_CPU's value `v` lets a process use: every one for
 * NULL, "" and "native"; SHAPE_CPU_KNOWN alone for "sse2"; with FMA for
 * "fma"; with FMA and AVX2 for "avx2". 0 for any other value. */
static inline unsigned shape_cpu_allowed_by(const char *v)
{
    if (!v || !*v || !strcmp(v, "native")) return ~0u;
    if (!strcmp(v, "sse2")) return SHAPE_CPU_KNOWN;
    if (!strcmp(v, "fma")) return SHAPE_CPU_KNOWN | SHAPE_CPU_FMA;
    if (!strcmp(v, "avx2")) return SHAPE_CPU_KNOWN | SHAPE_CPU_FMA | SHAPE_CPU_AVX2;
    return 0;
}

/* The features, probed on the first call in this translation unit, less
 * what HITRAY_CPU takes away (a value it does not know takes nothing). Threads
 * racing on that first call store the same value; relaxed atomic accesses
 * (GCC's and clang's builtins, which C and C++ share) make that race well
 * defined and cost a plain load on x86. */
/* The first call's work, out of line, so that the callers (a walk's every
 * ray) inline only the load and the test. */
#if defined(__GNUC__)
__attribute__((noinline, cold, unused))
#endif
static unsigned shape_cpu_features_first(unsigned *known)
{
    const unsigned allowed = shape_cpu_allowed_by(getenv(SHAPE_CPU_ENV));
    const unsigned features = shape_cpu_probe() & (allowed ? allowed : ~0u);
    __atomic_store_n(known, features, __ATOMIC_RELAXED);
    return features;
}
static inline unsigned shape_cpu_features(void)
{
    static unsigned known;
    const unsigned features = __atomic_load_n(&known, __ATOMIC_RELAXED);
    return features ? features : shape_cpu_features_first(&known);
}

static inline int shape_cpu_has_avx2(void) { return (shape_cpu_features() & SHAPE_CPU_AVX2) != 0; }
static inline int shape_cpu_has_fma(void) { return (shape_cpu_features() & SHAPE_CPU_FMA) != 0; }

/* A hot function built twice, for CPUs with FMA (where fma() is one
 * instruction) and for the rest (a call into libm), and picked per call by
 * shape_cpu_has_fma(): with any compiler, unlike target_clones, whose
 * resolver reads the compiler runtime's CPU model. Written before the body:
 *
 *   SHAPE_FMA_DISPATCH(int, crossings, (const hr_ray *ray, double t[2]), (ray, t))
 *   {
 *       ... the body, which makes `static int crossings(ray, t)` ...
 *   }
 *
 * The body becomes an always-inline NAME_body, inlined into NAME_fma
 * (target "fma") and NAME_baseline; NAME chooses between them. Both copies
 * give the same bits where the build contracts no a * b + c
 * (-ffp-contract=off: fma() is correctly rounded either way). A void
 * function uses SHAPE_FMA_DISPATCH_VOID(NAME, PARAMS, ARGS). */
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define SHAPE_FMA_DISPATCH_COPIES_(ret, name, params, args, call)                                 \
    static inline __attribute__((always_inline)) ret name##_body params;                          \
    __attribute__((target("fma"))) static ret name##_fma params { call(name##_body args); }       \
    static ret name##_baseline params { call(name##_body args); }
#define SHAPE_FMA_RETURN_(expression) return expression
#define SHAPE_FMA_STATEMENT_(expression) expression
#define SHAPE_FMA_DISPATCH(ret, name, params, args)                                               \
    SHAPE_FMA_DISPATCH_COPIES_(ret, name, params, args, SHAPE_FMA_RETURN_)                        \
    static ret name params { return shape_cpu_has_fma() ? name##_fma args : name##_baseline args; } \
    static inline __attribute__((always_inline)) ret name##_body params
#define SHAPE_FMA_DISPATCH_VOID(name, params, args)                                               \
    SHAPE_FMA_DISPATCH_COPIES_(void, name, params, args, SHAPE_FMA_STATEMENT_)                    \
    static void name params                                                                       \
    {                                                                                             \
        if (shape_cpu_has_fma())                                                                  \
            name##_fma args;                                                                      \
        else                                                                                      \
            name##_baseline args;                                                                 \
    }                                                                                             \
    static inline __attribute__((always_inline)) void name##_body params
#else
#define SHAPE_FMA_DISPATCH(ret, name, params, args) static ret name params
#define SHAPE_FMA_DISPATCH_VOID(name, params, args) static void name params
#endif

#endif
