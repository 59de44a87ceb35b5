/* Per-context, per-thread error messages (lib/errors.h). Each context owns a
 * pthread key; a thread's slot is allocated on its first error and freed when
 * the thread exits or the context is destroyed. */
#include "sized_copy.h"
#include "errors.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context_internal.h"
#include "error_slot.h"

static hr_error_slot *slot_of(const hr_context *ctx, int create)
{
    hr_error_slot *slot = pthread_getspecific(ctx->error_key);
    if (!slot && create) {
        slot = calloc(1, sizeof *slot);
        if (slot && pthread_setspecific(ctx->error_key, slot) != 0) {
            free(slot);
            slot = NULL;
        }
    }
    return slot;
}

static hr_status record(const hr_context *ctx, hr_status status, const char *file,
                        int32_t line, int32_t column, const char *fmt, va_list ap)
{
    if (!ctx) return status;
    hr_error_slot *slot = slot_of(ctx, 1);
    char fallback[256];
    char *message = slot ? slot->message : fallback;
    size_t size = slot ? sizeof slot->message : sizeof fallback;
    vsnprintf(message, size, fmt, ap);
    if (slot) {
        slot->status = status;
        snprintf(slot->file, sizeof slot->file, "%s", file ? file : "");
        slot->line = line;
        slot->column = column;
    }
    if (ctx->error_fn) ctx->error_fn(ctx->error_user, status, message);
    return status;
}

hr_status hr_error(const hr_context *ctx, hr_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    record(ctx, status, NULL, 0, 0, fmt, ap);
    va_end(ap);
    return status;
}

hr_status hr_error_at(const hr_context *ctx, hr_status status, const char *file,
                      int32_t line, int32_t column, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    record(ctx, status, file, line, column, fmt, ap);
    va_end(ap);
    return status;
}

HR_API const char *hr_context_last_error(const hr_context *ctx)
{
    hr_error_slot *slot = ctx ? slot_of(ctx, 0) : NULL;
    return slot ? slot->message : "";
}

HR_API hr_status hr_context_last_error_info(const hr_context *ctx, hr_error_info *out)
{
    if (!ctx || !out || out->struct_size < sizeof(uint32_t)) return HR_ERROR_INVALID_ARGUMENT;
    hr_error_info info = {0};
    hr_error_slot *slot = slot_of(ctx, 0);
    info.status = slot ? slot->status : HR_OK;
    info.message = slot ? slot->message : "";
    info.file = slot ? slot->file : "";
    info.line = slot ? slot->line : 0;
    info.column = slot ? slot->column : 0;
    HR_SIZED_COPY_OUT(out, &info);
    return HR_OK;
}

HR_API void hr_context_set_error_callback(hr_context *ctx, hr_error_fn fn, void *user)
{
    if (!ctx) return;
    ctx->error_fn = fn;
    ctx->error_user = user;
}

void hr_warn(const hr_context *ctx, int32_t code, const char *file, int32_t line, int32_t column,
             const char *fmt, ...)
{
    if (!ctx || !ctx->warning_fn) return;
    char message[2048]; /* as an error slot holds: a placed SDL message fits */
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    hr_warning w = {sizeof w, code, message, file ? file : "", line, column};
    ctx->warning_fn(ctx->warning_user, &w);
}

HR_API void hr_context_set_warning_callback(hr_context *ctx, hr_warning_fn fn, void *user)
{
    if (!ctx) return;
    ctx->warning_fn = fn;
    ctx->warning_user = user;
}

HR_API const char *hr_status_name(hr_status status)
{
    switch (status) {
    case HR_OK: return "ok";
    case HR_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case HR_ERROR_OUT_OF_MEMORY: return "out of memory";
    case HR_ERROR_IO: return "input/output error";
    case HR_ERROR_MODULE: return "shape module error";
    case HR_ERROR_PARAMETER: return "bad shape parameter";
    case HR_ERROR_SDL: return "scene file error";
    case HR_ERROR_STATE: return "wrong state";
    case HR_ERROR_CANCELLED: return "cancelled";
    case HR_ERROR_UNSUPPORTED: return "unsupported";
    case HR_ERROR_NUMERIC: return "numerical error";
    default: return "unknown status";
    }
}
