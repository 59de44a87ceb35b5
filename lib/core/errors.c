/* Per-context, per-thread error messages: hr_context_set_error and what
 * reads them back (the library raises them through lib/util/errors.h).
 * Each context owns a pthread key; a thread's slot is allocated on its first
 * error and freed when the thread exits or the context is destroyed. */
#include "util/sized_copy.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/context_internal.h"
#include "core/error_slot.h"

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

/* `text` into one of the slot's buffers, cut to fit. It may already lie
 * there: a caller passing on this thread's last error, or its file. */
static void keep(char *buffer, size_t size, const char *text)
{
    size_t length = strnlen(text, size - 1);
    memmove(buffer, text, length);
    buffer[length] = '\0';
}

/* `text` into `buffer` (size bytes, at most HR_ERROR_MESSAGE_SIZE) with
 * every control byte but the newline and the tab written as \xNN: a
 * message quotes words of files from anywhere, and no caller's quoting can
 * be missed on the way to a terminal. `text` may lie in `buffer`. */
static void keep_escaped(char *buffer, size_t size, const char *text)
{
    char copy[HR_ERROR_MESSAGE_SIZE];
    keep(copy, sizeof copy < size ? sizeof copy : size, text);
    size_t k = 0;
    for (const char *p = copy; *p && k + 1 < size; p++) {
        const unsigned char c = (unsigned char)*p;
        if ((c >= 0x20 && c != 0x7f) || c == '\n' || c == '\t') {
            buffer[k++] = (char)c;
        } else {
            if (k + 5 >= size) break;
            k += (size_t)snprintf(buffer + k, size - k, "\\x%02x", c);
        }
    }
    buffer[k] = '\0';
}

HR_API hr_status hr_context_set_error(const hr_context *ctx, hr_status status, const char *file,
                                      int32_t line, int32_t column, const char *message)
{
    if (!ctx) return status;
    if (!message) message = "";
    hr_error_slot *slot = slot_of(ctx, 1);
    if (slot) {
        keep_escaped(slot->message, sizeof slot->message, message);
        keep(slot->file, sizeof slot->file, file ? file : "");
        slot->status = status;
        slot->line = line;
        slot->column = column;
        message = slot->message;
    }
    if (ctx->error_fn) ctx->error_fn(ctx->error_user, status, message);
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

HR_API void hr_context_warn(const hr_context *ctx, int32_t code, const char *file, int32_t line,
                            int32_t column, const char *message)
{
    if (!ctx || !ctx->warning_fn) return;
    char escaped[HR_ERROR_MESSAGE_SIZE];
    keep_escaped(escaped, sizeof escaped, message ? message : "");
    hr_warning w = {sizeof w, code, escaped, file ? file : "", line, column};
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
