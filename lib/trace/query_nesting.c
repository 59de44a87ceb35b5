/* How deeply scene queries nest on the calling thread (query_nesting.h). */
#include "trace/query_nesting.h"

#include "util/errors.h"

static _Thread_local int32_t level;

hr_status hri_query_enter(const hr_context *ctx, const char *what, int32_t **level_out)
{
    int32_t *l = &level;
    if (*l >= HR_MAX_QUERY_NESTING)
        return hri_error(ctx, HR_ERROR_STATE,
                        "%s: scene queries nested more than %d deep (a shape's hit that queries "
                        "the scene it is part of calls itself without end)",
                        what, HR_MAX_QUERY_NESTING);
    ++*l;
    *level_out = l;
    return HR_OK;
}

HR_API int32_t hr_query_nesting(void) { return level; }

HR_API void hr_query_set_nesting(int32_t l) { level = l < 0 ? 0 : l; }
