/* The printf-style front ends of hr_context_set_error and hr_context_warn
 * (lib/util/errors.h). */
#include "util/errors.h"

#include <stdarg.h>
#include <stdio.h>

static void raise_error(const hr_context *ctx, hr_status status, const char *file, int32_t line,
                        int32_t column, const char *fmt, va_list ap) HR_PRINTF(6, 0);
static void raise_error(const hr_context *ctx, hr_status status, const char *file, int32_t line,
                        int32_t column, const char *fmt, va_list ap)
{
    if (!ctx) return;
    char message[HR_ERROR_MESSAGE_SIZE];
    vsnprintf(message, sizeof message, fmt, ap);
    hr_context_set_error(ctx, status, file, line, column, message);
}

hr_status hr_error(const hr_context *ctx, hr_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    raise_error(ctx, status, NULL, 0, 0, fmt, ap);
    va_end(ap);
    return status;
}

hr_status hr_error_at(const hr_context *ctx, hr_status status, const char *file,
                      int32_t line, int32_t column, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    raise_error(ctx, status, file, line, column, fmt, ap);
    va_end(ap);
    return status;
}

void hr_warn(const hr_context *ctx, int32_t code, const char *file, int32_t line, int32_t column,
             const char *fmt, ...)
{
    if (!ctx) return;
    char message[HR_ERROR_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    hr_context_warn(ctx, code, file, line, column, message);
}
