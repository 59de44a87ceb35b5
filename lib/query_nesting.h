/* Internal: how deeply scene queries nest on the calling thread (a shape's
 * hit that queries a scene, include/hitray/scene.h HR_MAX_QUERY_NESTING).
 * Every public query enters on the way in and leaves on the way out; a
 * render's threads start at the level of the thread that called hr_render
 * (hr_query_nesting, hr_query_set_nesting in scene.h). */
#ifndef HITRAY_LIB_QUERY_NESTING_H
#define HITRAY_LIB_QUERY_NESTING_H

#include <hitray/hitray.h>

/* One level deeper, or HR_ERROR_STATE (message naming `what`) past
 * HR_MAX_QUERY_NESTING, when the level stays as it was. */
hr_status hr_query_enter(const hr_context *ctx, const char *what);
void hr_query_leave(void);

#endif
