/* A byte count from the environment, for the limits docs/limits.md lists. */
#ifndef HITRAY_LIB_UTIL_ENV_BYTES_H
#define HITRAY_LIB_UTIL_ENV_BYTES_H

#include <stdint.h>

#include <hitray/hitray.h>

/* *out = the positive decimal byte count in environment variable `name`,
 * at most `max`; `fallback` where it is unset or empty. Anything else is an
 * HR_ERROR_INVALID_ARGUMENT naming the variable, `what` it limits and the
 * default `shown_default`. */
hr_status hr_env_bytes(const hr_context *ctx, const char *name, const char *what, uint64_t fallback,
                       uint64_t shown_default, uint64_t max, uint64_t *out);

#endif
