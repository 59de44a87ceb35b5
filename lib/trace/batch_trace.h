/* Internal: tracing a batch of rays for their first hits (batch_trace.c),
 * what hr_scene_first_hits (batch_queries.c) runs once it has checked them. */
#ifndef HITRAY_LIB_TRACE_BATCH_TRACE_H
#define HITRAY_LIB_TRACE_BATCH_TRACE_H

#include <stdint.h>

#include "trace/trace_context.h"

/* rays[i]'s first hit in (tmin, tmax) into hits[i] and found[i], for i <
 * count, each the answer hri_scene_trace_nearest gives that ray alone; tmp
 * is the list of candidate hits. Returns -1, or the index of the ray a
 * shape failed on (tc->status set): found[] is then 0 for every ray. */
int64_t hri_trace_first_batch(hr_trace_ctx *tc, const hr_ray *rays, int64_t count, double tmin, double tmax,
                              hr_hit *hits, int32_t *found, hr_intersection *tmp);

/* Whether rays[i] meets anything in (tmin, tmax), into hit[i], by the
 * shadow rays' walk (hri_scene_trace_shadow, its cache slot 0). Returns as
 * hri_trace_first_batch; hit[] is 0 from a failed ray on. */
int64_t hri_trace_occluded_batch(hr_trace_ctx *tc, const hr_ray *rays, int64_t count, double tmin, double tmax,
                                 int32_t *hit);

#endif
