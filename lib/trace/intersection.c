/* Hill's Intersection, the list of hits along a ray: its storage, grown by
 * doubling. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "trace/trace_context.h"

hr_status hri_intersection_reserve(hr_intersection *list, int32_t capacity)
{
    if (capacity <= list->capacity) return HR_OK;
    int64_t cap = list->capacity > 0 ? list->capacity : 16;
    while (cap < capacity) cap *= 2;
    if (cap > INT32_MAX) return HR_ERROR_OUT_OF_MEMORY;
    hr_hit *grown = realloc(list->hits, (size_t)cap * sizeof *grown);
    if (!grown) return HR_ERROR_OUT_OF_MEMORY;
    list->hits = grown;
    list->capacity = (int32_t)cap;
    return HR_OK;
}

HR_API void hr_intersection_init(hr_intersection *list)
{
    if (list) memset(list, 0, sizeof *list);
}

HR_API void hr_intersection_release(hr_intersection *list)
{
    if (!list) return;
    free(list->hits);
    memset(list, 0, sizeof *list);
}
