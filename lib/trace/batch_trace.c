/* Tracing a batch of rays for their first hits (batch_trace.h). */
#include "trace/batch_trace.h"

int64_t hri_trace_first_batch(hr_trace_ctx *tc, const hr_ray *rays, int64_t count, double tmin, double tmax,
                              hr_hit *hits, int32_t *found, hr_intersection *tmp)
{
    for (int64_t i = 0; i < count; i++) {
        found[i] = hri_scene_trace_nearest(tc, &rays[i], tmin, tmax, &hits[i], tmp);
        if (tc->status) {
            for (int64_t j = i; j < count; j++) found[j] = 0;
            return i;
        }
    }
    return -1;
}

int64_t hri_trace_occluded_batch(hr_trace_ctx *tc, const hr_ray *rays, int64_t count, double tmin, double tmax,
                                 int32_t *hit)
{
    for (int64_t i = 0; i < count; i++) {
        hit[i] = hri_scene_trace_shadow(tc, &rays[i], tmin, tmax, 0);
        if (tc->status) {
            for (int64_t j = i; j < count; j++) hit[j] = 0;
            return i;
        }
    }
    return -1;
}
