/* A byte count from the environment (env_bytes.h). */
#include "util/env_bytes.h"

#include <errno.h>
#include <stdlib.h>

#include "util/errors.h"

hr_status hr_env_bytes(const hr_context *ctx, const char *name, const char *what, uint64_t fallback,
                       uint64_t shown_default, uint64_t max, uint64_t *out)
{
    *out = fallback;
    const char *env = getenv(name);
    if (!env || !*env) return HR_OK;
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(env, &end, 10);
    if (errno || *end || env[0] < '0' || env[0] > '9' || v == 0 || v > max)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT,
                        "%s='%.40s' must be a positive number of bytes (%s; default %llu)", name, env,
                        what, (unsigned long long)shown_default);
    *out = v;
    return HR_OK;
}
