/* HITRAY_CPU, the switch that forces a CPU path (<hitray/shape_kit_cpu.h>),
 * checked where a scene is made, so that a bad value is refused with a
 * message instead of quietly running the CPU's own paths. */
#ifndef HITRAY_LIB_UTIL_ENV_CPU_H
#define HITRAY_LIB_UTIL_ENV_CPU_H

#include <stdlib.h>

#include <hitray/hitray.h>
#include <hitray/shape_kit_cpu.h>

#include "util/errors.h"

/* HR_OK when HITRAY_CPU's value `v` is NULL, empty or a path a CPU with
 * the features `have` (shape_cpu_probe) can run; an
 * HR_ERROR_INVALID_ARGUMENT naming the variable and its values for any
 * other value, an HR_ERROR_UNSUPPORTED naming what is missing for a path
 * this CPU (or its operating system) cannot run. Inline, as it raises
 * errors (util/errors.h). */
static inline hr_status hri_cpu_path_check(const hr_context *ctx, const char *v, unsigned have)
{
    const unsigned allowed = shape_cpu_allowed_by(v);
    if (!allowed)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "%s='%.40s' is not a CPU path: use %s (or leave it unset)",
                        SHAPE_CPU_ENV, v, SHAPE_CPU_CHOICES);
    const unsigned missing = allowed & ~have & (SHAPE_CPU_FMA | SHAPE_CPU_AVX2);
    if (allowed == ~0u || !missing) return HR_OK;
    return hri_error(ctx, HR_ERROR_UNSUPPORTED, "%s=%s: this CPU (or its operating system) has no %s; it runs %s",
                    SHAPE_CPU_ENV, v,
                    missing & SHAPE_CPU_AVX2 ? (missing & SHAPE_CPU_FMA ? "AVX2 or FMA" : "AVX2") : "FMA",
                    have & SHAPE_CPU_FMA ? "native, sse2 or fma" : "native or sse2");
}

/* The same for this process's HITRAY_CPU on this CPU. */
static inline hr_status hri_env_cpu_check(const hr_context *ctx)
{
    return hri_cpu_path_check(ctx, getenv(SHAPE_CPU_ENV), shape_cpu_probe());
}

#endif
