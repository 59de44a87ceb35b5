/* A byte count from the environment, for the limits docs/limits.md lists. */
#ifndef HITRAY_LIB_UTIL_ENV_BYTES_H
#define HITRAY_LIB_UTIL_ENV_BYTES_H

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>

#include <hitray/hitray.h>

#include "util/errors.h"

/* *out = the positive decimal byte count in environment variable `name`,
 * at most `max`; `fallback` where it is unset or empty. Anything else is an
 * HR_ERROR_INVALID_ARGUMENT naming the variable, `what` it limits and the
 * default `shown_default`. Inline, as it raises errors (util/errors.h). */
static inline hr_status hri_env_bytes(const hr_context *ctx, const char *name, const char *what,
                                     uint64_t fallback, uint64_t shown_default, uint64_t max, uint64_t *out)
{
    *out = fallback;
    const char *env = getenv(name);
    if (!env || !*env) return HR_OK;
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(env, &end, 10);
    if (errno || *end || env[0] < '0' || env[0] > '9' || v == 0 || v > max)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "%s='%.40s' must be a positive number of bytes (%s; default %llu)", name, env,
                        what, (unsigned long long)shown_default);
    *out = v;
    return HR_OK;
}

#endif
