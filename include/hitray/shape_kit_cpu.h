/* hitray shape kit: what this CPU can run (part of <hitray/shape_kit.h>; see
 * there), for a module or the host that keeps a faster path beside the
 * baseline x86-64 one.
 *
 * Read off CPUID and XGETBV directly rather than through
 * __builtin_cpu_supports: that builtin reads a CPU model filled in by the
 * compiler's runtime at load, and some toolchains' runtimes (zig's, which
 * builds the manylinux wheels) leave it all zero, so every check said "no"
 * and the wheels ran the baseline paths only. The answer is worked out once
 * per translation unit and kept; later calls are a load and a test. */
#ifndef HITRAY_SHAPE_KIT_CPU_H
#define HITRAY_SHAPE_KIT_CPU_H

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

/* The features, probed on the first call in this translation unit. Threads
 * racing on that first call store the same value; relaxed atomic accesses
 * (GCC's and clang's builtins, which C and C++ share) make that race well
 * defined and cost a plain load on x86. */
static inline unsigned shape_cpu_features(void)
{
    static unsigned known;
    unsigned features = __atomic_load_n(&known, __ATOMIC_RELAXED);
    if (!features) {
        features = shape_cpu_probe();
        __atomic_store_n(&known, features, __ATOMIC_RELAXED);
    }
    return features;
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
