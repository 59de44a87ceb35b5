/* How deeply scene queries nest on the calling thread (query_nesting.h). */
#include "trace/query_nesting.h"

#include "util/errors.h"

_Thread_local int32_t hri_query_level;

hr_status hri_query_too_deep(const hr_context *ctx, const char *what)
{
    return hri_error(ctx, HR_ERROR_STATE,
                     "%s: scene queries nested more than %d deep (a shape's hit that queries "
                     "the scene it is part of calls itself without end)",
                     what, HR_MAX_QUERY_NESTING);
}

HR_API int32_t hr_query_nesting(void) { return hri_query_level; }

HR_API void hr_query_set_nesting(int32_t l) { hri_query_level = l < 0 ? 0 : l; }
