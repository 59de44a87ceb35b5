/* The batch queries of a committed scene (include/hitray/scene.h): the
 * first hits of N rays (hr_scene_first_hits) and whether each of N rays is
 * blocked (hr_scene_occluded). What the single queries do per call (the
 * scene's checks, the nesting level, the tracing context and its list of
 * candidate hits) is done here once per batch; each ray is then traced by
 * the single query's own walk (trace.c), or rays side by side by the
 * packet walk (batch_trace.c), which gives the same answers. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "util/errors.h"
#include "trace/batch_trace.h"
#include "trace/query_nesting.h"
#include "trace/trace_context.h"
#include "geometry/vec.h"

/* The checks of a batch: the scene, the arrays and the window once, then
 * every ray as hr_scene_first_hit checks its one (scene_queries.c), before
 * anything is traced or written. `hits` is NULL for the occlusion batch. */
static hr_status check_batch(const hr_scene *s, const char *what, const hr_ray *rays, int64_t count,
                             double tmin, double tmax, const hr_hit *hits, const int32_t *found)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!s->committed) return hri_error(s->ctx, HR_ERROR_STATE, "the scene is not committed (call hr_scene_commit)");
    if (count < 0) return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "%s: count %lld is negative", what, (long long)count);
    const int first = what[0] == 'f'; /* "first hits", else "occluded" */
    if (count > 0 && (!rays || (first && !hits) || !found))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "%s: %s is NULL", what,
                         !rays ? "rays" : first && !hits ? "hits" : first ? "found" : "hit");
    if (isnan(tmin) || isnan(tmax) || !(tmin <= tmax))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "%s: need tmin <= tmax (got %g, %g)", what, tmin, tmax);
    for (int64_t i = 0; i < count; i++) {
        const hr_ray *r = &rays[i];
        if (!v3_pair_is_finite(r->origin, r->dir, 0.0))
            return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT,
                             "%s: ray %lld: origin and direction must be finite", what, (long long)i);
        if (r->dir.x == 0 && r->dir.y == 0 && r->dir.z == 0)
            return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "%s: ray %lld: direction is the zero vector",
                             what, (long long)i);
    }
    return HR_OK;
}

/* Either batch, `what` naming it: first hits into hits[] and found[], or
 * (hits NULL) occlusion into found[]. */
static hr_status run_batch(const hr_scene *s, const char *what, const hr_ray *rays, int64_t count, double tmin,
                           double tmax, hr_hit *hits, int32_t *found)
{
    hr_status st = check_batch(s, what, rays, count, tmin, tmax, hits, found);
    int32_t *level;
    if (st || (st = hri_query_enter(s->ctx, what, &level))) return st;
    hr_trace_ctx tc;
    int64_t failed;
    if (hits) {
        hri_trace_ctx_init_tracing(&tc, s);
        /* One list of candidate hits for the whole batch, on the stack as
         * the single query's (to the heap only if a shape asks for more). */
        hr_hit room[4 * HR_MIN_HIT_CAPACITY];
        hr_intersection tmp = {room, 0, 4 * HR_MIN_HIT_CAPACITY};
        tc.borrowed = room;
        failed = hri_trace_first_batch(&tc, rays, count, tmin, tmax, hits, found, &tmp);
        if (tmp.hits != room) free(tmp.hits);
    } else {
        /* The whole context: the shadow walk keeps the object that blocked
         * the last ray (its shadow cache), which neighbouring rays share. */
        hri_trace_ctx_init(&tc, s);
        failed = hri_trace_occluded_batch(&tc, rays, count, tmin, tmax, found);
    }
    hri_query_leave(level);
    st = tc.status;
    hri_trace_ctx_release(&tc);
    if (st)
        return hri_error(s->ctx, st, "%s: ray %lld: a shape failed while tracing: %s", what, (long long)failed,
                         hr_status_name(st));
    return HR_OK;
}

HR_API hr_status hr_scene_first_hits(const hr_scene *s, const hr_ray *rays, int64_t count, double tmin,
                                     double tmax, hr_hit *hits, int32_t *found)
{
    return run_batch(s, "first hits", rays, count, tmin, tmax, count > 0 ? hits : NULL, found);
}

HR_API hr_status hr_scene_occluded(const hr_scene *s, const hr_ray *rays, int64_t count, double tmin,
                                   double tmax, int32_t *hit)
{
    return run_batch(s, "occluded", rays, count, tmin, tmax, NULL, hit);
}
