/* Internal: raising errors on a context. Every public call that fails goes
 * through hr_error*, which stores the message for the calling thread, calls
 * the context's error callback and returns the status, so a failing call is
 * one line: `return hr_error(ctx, HR_ERROR_IO, "cannot open '%s': %s", ...)`. */
#ifndef HITRAY_LIB_ERRORS_H
#define HITRAY_LIB_ERRORS_H

#include <hitray/hitray.h>

#if defined(__GNUC__)
#define HR_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define HR_PRINTF(f, a)
#endif

/* Record `status` with a printf-style message; returns `status`. A NULL ctx
 * records nothing (used where no context exists yet). */
hr_status hr_error(const hr_context *ctx, hr_status status, const char *fmt, ...)
    HR_PRINTF(3, 4);
/* The same, with the place in a scene file (line/column 1-based). The message
 * should already start with "file:line:col: "; the parts are kept for
 * hr_context_last_error_info. */
hr_status hr_error_at(const hr_context *ctx, hr_status status, const char *file,
                      int32_t line, int32_t column, const char *fmt, ...) HR_PRINTF(6, 7);
/* Report a warning (HR_WARNING_*) to the context's warning callback, if
 * any; `file` may be NULL (not in a file), line and column 0 (unknown). The
 * message should start with "file:line:col: " where there is a place. */
void hr_warn(const hr_context *ctx, int32_t code, const char *file, int32_t line, int32_t column,
             const char *fmt, ...) HR_PRINTF(6, 7);

#endif
