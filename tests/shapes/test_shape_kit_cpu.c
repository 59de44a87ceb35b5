/* The shape kit's CPU checks (include/hitray/shape_kit_cpu.h) against the
 * compiler's own __builtin_cpu_supports where the toolchain's runtime fills
 * that in (GCC's libgcc, and clang with libgcc or compiler-rt): the two must
 * agree on this machine, whatever it is, or a faster path would be taken
 * where it faults, or left where it runs. Also: the answer is kept (a second
 * call gives the same), and the probe only ever adds features to "known". */
#define _POSIX_C_SOURCE 200809L /* unsetenv */
#include <stdlib.h>

#include <hitray/shape_kit.h>

#include "hr_test.h"

int main(void)
{
    /* The CPU's own answer, whatever path HITRAY_CPU would force
     * (test_cpu_path_switch tests that). */
    unsetenv(SHAPE_CPU_ENV);
    const unsigned features = shape_cpu_features();
    CHECK(features & SHAPE_CPU_KNOWN);
    CHECK(features == shape_cpu_probe());
    CHECK(shape_cpu_features() == features);
    CHECK(features == (features & (SHAPE_CPU_KNOWN | SHAPE_CPU_FMA | SHAPE_CPU_AVX2)));
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    CHECK_MSG(shape_cpu_has_avx2() == (__builtin_cpu_supports("avx2") != 0),
              "avx2: the kit says %d, the compiler's runtime %d", shape_cpu_has_avx2(),
              __builtin_cpu_supports("avx2") != 0);
    CHECK_MSG(shape_cpu_has_fma() == (__builtin_cpu_supports("fma") != 0),
              "fma: the kit says %d, the compiler's runtime %d", shape_cpu_has_fma(),
              __builtin_cpu_supports("fma") != 0);
#endif
    return hr_test_end();
}
