/* HITRAY_CPU, the switch that forces a CPU path: what each value lets the
 * shape kit's CPU checks answer (include/hitray/shape_kit_cpu.h), in a
 * child process per value since the answer is kept from the first call;
 * and the library's refusal of a value that names no path or one the CPU
 * cannot run (lib/util/env_cpu.h), for this CPU and for CPUs without FMA
 * or AVX2, so that asking for AVX2 where there is none is refused with a
 * message, never run. */
#define _POSIX_C_SOURCE 200809L /* setenv, unsetenv, fork */
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <hitray/hitray.h>
#include <hitray/shape_kit.h>

#include "util/env_cpu.h"

#include "hr_test.h"

/* In a child: HITRAY_CPU=value, then the kit's answer must be what the CPU
 * has, less what the value takes away. */
static void forced(const char *value, unsigned allowed)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        setenv(SHAPE_CPU_ENV, value, 1);
        const unsigned want = shape_cpu_probe() & allowed;
        const int ok = shape_cpu_features() == want && shape_cpu_has_avx2() == ((want & SHAPE_CPU_AVX2) != 0) &&
                       shape_cpu_has_fma() == ((want & SHAPE_CPU_FMA) != 0);
        _exit(ok ? 0 : 1);
    }
    int status = 0;
    CHECK(pid > 0 && waitpid(pid, &status, 0) == pid);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "HITRAY_CPU=%s: the kit's answer is not the CPU's less the value's", value);
}

static void refused(hr_context *ctx, const char *value, unsigned have, hr_status want, const char *says)
{
    const hr_status st = hri_cpu_path_check(ctx, value, have);
    CHECK_MSG(st == want, "HITRAY_CPU=%s on features %u: status %d, want %d", value, have, (int)st, (int)want);
    if (st != HR_OK)
        CHECK_MSG(strstr(hr_context_last_error(ctx), says) != NULL, "HITRAY_CPU=%s: message '%s' lacks '%s'", value,
                  hr_context_last_error(ctx), says);
}

int main(void)
{
    const unsigned all = SHAPE_CPU_KNOWN | SHAPE_CPU_FMA | SHAPE_CPU_AVX2;
    CHECK(shape_cpu_allowed_by(NULL) == ~0u && shape_cpu_allowed_by("") == ~0u);
    CHECK(shape_cpu_allowed_by("native") == ~0u);
    CHECK(shape_cpu_allowed_by("sse2") == SHAPE_CPU_KNOWN);
    CHECK(shape_cpu_allowed_by("fma") == (SHAPE_CPU_KNOWN | SHAPE_CPU_FMA));
    CHECK(shape_cpu_allowed_by("avx2") == all);
    CHECK(shape_cpu_allowed_by("AVX2") == 0 && shape_cpu_allowed_by("avx512") == 0 && shape_cpu_allowed_by(" sse2") == 0);
    forced("sse2", SHAPE_CPU_KNOWN);
    forced("fma", SHAPE_CPU_KNOWN | SHAPE_CPU_FMA);
    forced("avx2", all);
    forced("native", all);
    forced("nonsense", all); /* takes nothing away: the library refuses it */

    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    refused(ctx, NULL, SHAPE_CPU_KNOWN, HR_OK, "");
    refused(ctx, "native", SHAPE_CPU_KNOWN, HR_OK, "");
    refused(ctx, "sse2", SHAPE_CPU_KNOWN, HR_OK, "");
    refused(ctx, "avx2", all, HR_OK, "");
    refused(ctx, "fma", SHAPE_CPU_KNOWN | SHAPE_CPU_FMA, HR_OK, "");
    refused(ctx, "avx", all, HR_ERROR_INVALID_ARGUMENT, "HITRAY_CPU='avx' is not a CPU path: use native, sse2, fma or avx2");
    refused(ctx, "avx2", SHAPE_CPU_KNOWN, HR_ERROR_UNSUPPORTED, "HITRAY_CPU=avx2: this CPU (or its operating system) has no AVX2 or FMA; it runs native or sse2");
    refused(ctx, "avx2", SHAPE_CPU_KNOWN | SHAPE_CPU_FMA, HR_ERROR_UNSUPPORTED, "has no AVX2; it runs native, sse2 or fma");
    refused(ctx, "fma", SHAPE_CPU_KNOWN, HR_ERROR_UNSUPPORTED, "has no FMA; it runs native or sse2");
    /* Through the API: a scene is refused while the value is bad. */
    setenv(SHAPE_CPU_ENV, "fast", 1);
    hr_scene *s = NULL;
    CHECK(hr_scene_create(ctx, &s) == HR_ERROR_INVALID_ARGUMENT && s == NULL);
    CHECK(strstr(hr_context_last_error(ctx), "HITRAY_CPU='fast'") != NULL);
    setenv(SHAPE_CPU_ENV, "sse2", 1);
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
    return hr_test_end();
}
