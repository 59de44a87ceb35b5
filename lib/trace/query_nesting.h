/* Internal: how deeply scene queries nest on the calling thread (a shape's
 * hit that queries a scene, include/hitray/scene.h HR_MAX_QUERY_NESTING).
 * Every public query enters on the way in and leaves on the way out; a
 * render's threads start at the level of the thread that called hr_render
 * (hr_query_nesting, hr_query_set_nesting in scene.h). */
#ifndef HITRAY_LIB_TRACE_QUERY_NESTING_H
#define HITRAY_LIB_TRACE_QUERY_NESTING_H

#include <hitray/hitray.h>

/* The calling thread's level (query_nesting.c). */
extern _Thread_local int32_t hri_query_level;

/* hri_query_enter's error, out of line: the message for `what`. */
hr_status hri_query_too_deep(const hr_context *ctx, const char *what);

/* One level deeper, or HR_ERROR_STATE (message naming `what`) past
 * HR_MAX_QUERY_NESTING, when the level stays as it was. *level
 * points at the calling thread's level, which hri_query_leave takes: in a
 * library loaded by dlopen every look-up of a thread-local variable is a
 * call (__tls_get_addr), so a query looks it up once, not twice. Inline, so
 * that a single-ray query pays that look-up and two compares, not a call
 * besides. */
static inline hr_status hri_query_enter(const hr_context *ctx, const char *what, int32_t **level)
{
    int32_t *l = &hri_query_level;
    /* Opaque to the compiler, so that it keeps the pointer rather than
     * looking the address up again (a second call) to leave. */
    __asm__("" : "+r"(l));
    *level = l;
    if (__builtin_expect(*l >= HR_MAX_QUERY_NESTING, 0)) return hri_query_too_deep(ctx, what);
    ++*l;
    return HR_OK;
}

/* One level back up, with the pointer hri_query_enter gave this thread. */
static inline void hri_query_leave(int32_t *level)
{
    if (*level > 0) (*level)--;
}

#endif
