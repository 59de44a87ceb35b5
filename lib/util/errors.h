/* Internal: raising errors on a context. Every public call that fails goes
 * through hri_error*, which formats the message and raises it through the
 * public hr_context_set_error (stored for the calling thread, passed to the
 * context's error callback) and returns the status, so a failing call is
 * one line: `return hri_error(ctx, HR_ERROR_IO, "cannot open '%s': %s", ...)`.
 * Built on the public API alone, so that the library and the scene file
 * readers, its clients, raise errors the same way; defined here, inline,
 * so that each call is one to the public setters from the caller's own
 * layer (a layer raising errors uses core, which keeps them; a reader calls
 * the public API) and util itself calls no layer above it. */
#ifndef HITRAY_LIB_UTIL_ERRORS_H
#define HITRAY_LIB_UTIL_ERRORS_H

#include <stdarg.h>
#include <stdio.h>

#include <hitray/hitray.h>

#if defined(__GNUC__)
#define HR_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define HR_PRINTF(f, a)
#endif

/* The bytes of a message, terminator included, that a context keeps (a
 * placed SDL message fits); a longer one is cut. */
#define HR_ERROR_MESSAGE_SIZE 2048

static inline void hri_raise_error(const hr_context *ctx, hr_status status, const char *file, int32_t line,
                                  int32_t column, const char *fmt, va_list ap) HR_PRINTF(6, 0);
static inline void hri_raise_error(const hr_context *ctx, hr_status status, const char *file, int32_t line,
                                  int32_t column, const char *fmt, va_list ap)
{
    if (!ctx) return;
    char message[HR_ERROR_MESSAGE_SIZE];
    vsnprintf(message, sizeof message, fmt, ap);
    hr_context_set_error(ctx, status, file, line, column, message);
}

/* Record `status` with a printf-style message; returns `status`. A NULL ctx
 * records nothing (used where no context exists yet). */
static inline hr_status hri_error(const hr_context *ctx, hr_status status, const char *fmt, ...)
    HR_PRINTF(3, 4);
static inline hr_status hri_error(const hr_context *ctx, hr_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    hri_raise_error(ctx, status, NULL, 0, 0, fmt, ap);
    va_end(ap);
    return status;
}

/* The same, with the place in a scene file (line/column 1-based). The message
 * should already start with "file:line:col: "; the parts are kept for
 * hr_context_last_error_info. */
static inline hr_status hri_error_at(const hr_context *ctx, hr_status status, const char *file,
                                    int32_t line, int32_t column, const char *fmt, ...) HR_PRINTF(6, 7);
static inline hr_status hri_error_at(const hr_context *ctx, hr_status status, const char *file,
                                    int32_t line, int32_t column, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    hri_raise_error(ctx, status, file, line, column, fmt, ap);
    va_end(ap);
    return status;
}

/* Report a warning (HR_WARNING_*) to the context's warning callback, if
 * any; `file` may be NULL (not in a file), line and column 0 (unknown). The
 * message should start with "file:line:col: " where there is a place. */
static inline void hri_warn(const hr_context *ctx, int32_t code, const char *file, int32_t line,
                           int32_t column, const char *fmt, ...) HR_PRINTF(6, 7);
static inline void hri_warn(const hr_context *ctx, int32_t code, const char *file, int32_t line,
                           int32_t column, const char *fmt, ...)
{
    if (!ctx) return;
    char message[HR_ERROR_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    hr_context_warn(ctx, code, file, line, column, message);
}

#endif
