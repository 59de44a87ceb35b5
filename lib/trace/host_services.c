/* The host services every shape module is given (hr_host, the table a
 * context holds): memory, hit lists and the tracing of a composite's
 * children. The scratch lists are the scene walk's own stack (trace.c).
 * hr_context_create is here, above core, because it fills a new context's
 * table with these: core calls no layer above it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/context_internal.h"
#include "scene/scene_budget.h"
#include "trace/object_trace.h"
#include "trace/trace_context.h"


static hr_status host_reserve(void *call, hr_intersection *list, int32_t capacity)
{
    if (!list || capacity < 0) return HR_ERROR_INVALID_ARGUMENT;
    return call ? hri_trace_list_reserve(call, list, capacity) : hri_intersection_reserve(list, capacity);
}

/* Sorts the hits from `start` on by t, leaving those before `start` alone:
 * a composite traces its children one after the other into one list and
 * tells their hits apart by position. Stable insertion sort on t alone: the
 * tail is one shape's answer, already sorted by contract, and hits of equal
 * t keep the shape's order (a tangent enters before it leaves, whatever the
 * surface ids), so this costs one pass unless a shape broke the contract. */
static void sort_tail_by_t(hr_intersection *list, int32_t start)
{
    for (int32_t i = start + 1; i < list->count; i++) {
        hr_hit h = list->hits[i];
        int32_t j = i;
        while (j > start && h.t < list->hits[j - 1].t) {
            list->hits[j] = list->hits[j - 1];
            j--;
        }
        list->hits[j] = h;
    }
}

static hr_status host_trace_child(void *call, const void *child, const hr_ray *ray, double tmin,
                                  double tmax, int32_t mode, hr_intersection *out)
{
    if (!call || !child || !ray || !out) return HR_ERROR_INVALID_ARGUMENT;
    int32_t start = out->count;
    /* Composites ask for every hit (csg.c does but for its probes): that
     * mode gets object_trace's copy made for it. */
    hr_status st = mode == HR_TRACE_ALL ? object_trace(call, child, ray, tmin, tmax, HR_TRACE_ALL, 0, out)
                                        : hri_object_trace(call, child, ray, tmin, tmax, mode, 0, out);
    if (st == HR_OK) sort_tail_by_t(out, start);
    return st;
}

static void host_child_bounds(const void *child, hr_bounds *out)
{
    const hr_object *o = child;
    *out = o->world_bounds;
}

static const hr_shape_class *host_child_class(const void *child)
{
    const hr_object *o = child;
    return o->cls;
}

static void host_services_init(hr_host *host)
{
    memset(host, 0, sizeof *host);
    host->struct_size = sizeof *host;
    host->abi_version = HR_SHAPE_ABI_VERSION;
    /* Shape data counts against the scene budget of the scene being built. */
    host->alloc = hri_scene_budget_alloc;
    host->free = hri_scene_budget_free;
    host->reserve = host_reserve;
    host->scratch_acquire = hri_trace_scratch_acquire;
    host->scratch_release = hri_trace_scratch_release;
    host->trace_child = host_trace_child;
    host->child_bounds = host_child_bounds;
    host->child_class = host_child_class;
    host->file_read = hri_scene_create_file_read;
}

HR_API hr_status hr_context_create(hr_context **out)
{
    if (!out) return HR_ERROR_INVALID_ARGUMENT;
    *out = hri_context_new();
    if (!*out) return HR_ERROR_OUT_OF_MEMORY;
    host_services_init(&(*out)->host);
    return HR_OK;
}
