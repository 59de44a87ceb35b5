/* The public queries of a committed scene: its first hit, all its hits
 * (Hill's Intersection) and the colour along a ray (Hill's shade). Each
 * checks its ray, sets up a tracing context of its own and hands it to
 * tracing (trace.c) or shading (shade.c). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "trace/object_trace.h"
#include "trace/query_nesting.h"
#include "trace/ray_cull.h"
#include "trace/trace_context.h"
#include "geometry/vec.h"

/* The checks of every query's arguments, each failure with its message;
 * check_query runs them only for a ray its one test does not pass. */
static __attribute__((noinline)) hr_status check_query_fully(const hr_scene *s, const hr_ray *ray, double tmin,
                                                             double tmax)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!s->committed) return hri_error(s->ctx, HR_ERROR_STATE, "the scene is not committed (call hr_scene_commit)");
    if (!ray) return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: NULL");
    if (!v3_pair_is_finite(ray->origin, ray->dir, 0.0))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: origin and direction must be finite");
    if (ray->dir.x == 0 && ray->dir.y == 0 && ray->dir.z == 0)
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: direction is the zero vector");
    if (isnan(tmin) || isnan(tmax) || !(tmin <= tmax))
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: need tmin <= tmax (got %g, %g)", tmin, tmax);
    return HR_OK;
}

/* check_query_fully's answer, with one branch for a good ray (a finite ray
 * with a direction that is not zero, and tmin <= tmax, which no NaN
 * passes): a single-ray query pays it on every call. */
static inline hr_status check_query(const hr_scene *s, const hr_ray *ray, double tmin, double tmax)
{
    if (s && s->committed && ray) {
        const hr_vec3 d = ray->dir;
        uint64_t x, y, z; /* the direction's bits: zero but for signs when d = 0 */
        memcpy(&x, &d.x, sizeof x);
        memcpy(&y, &d.y, sizeof y);
        memcpy(&z, &d.z, sizeof z);
        if (v3_pair_is_finite(ray->origin, d, 0.0) & (((x | y | z) << 1) != 0) & (tmin <= tmax)) return HR_OK;
    }
    return check_query_fully(s, ray, tmin, tmax);
}

/* finish_query's end for a query that failed or took scratch lists. */
static __attribute__((noinline)) hr_status finish_query_fully(hr_trace_ctx *tc)
{
    hr_status st = tc->status;
    hri_trace_ctx_release(tc);
    if (st) return hri_error(tc->scene->ctx, st, "a shape failed while tracing: %s", hr_status_name(st));
    return HR_OK;
}

/* Ends a query begun with hri_query_enter, which gave `level`: inline, as
 * most queries neither fail nor take a scratch list, and then there is
 * nothing to release. */
static inline hr_status finish_query(hr_trace_ctx *tc, int32_t *level)
{
    hri_query_leave(level);
    if (__builtin_expect(tc->status == HR_OK && tc->scratch_ready == 0, 1)) return HR_OK;
    return finish_query_fully(tc);
}

HR_API hr_status hr_scene_first_hit(const hr_scene *s, const hr_ray *ray, double tmin, double tmax,
                                    hr_hit *out, int32_t *found)
{
    hr_status st = check_query(s, ray, tmin, tmax);
    if (st) return st;
    if (!out || !found) return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "first hit: NULL output");
    int32_t *level;
    if ((st = hri_query_enter(s->ctx, "first hit", &level))) return st;
    hr_trace_ctx tc;
    hri_trace_ctx_init_tracing(&tc, s);
    /* One ray: the list of candidate hits lives on the stack, so the query
     * allocates nothing unless a shape asks for more room (hri_trace_list_reserve). */
    hr_hit room[4 * HR_MIN_HIT_CAPACITY];
    hr_intersection tmp = {room, 0, 4 * HR_MIN_HIT_CAPACITY};
    tc.borrowed = room;
    *found = hri_scene_trace_nearest(&tc, ray, tmin, tmax, out, &tmp);
    if (tmp.hits != room) free(tmp.hits);
    return finish_query(&tc, level);
}

/* The order of all hits: by t, equal t by object (hr_scene_first_hit's
 * tie rule across objects), and hits of one object at equal t in the
 * order its class listed them: a solid crossed where its entering and
 * leaving t round to the same double (a few units wide, seen from 1e16
 * away) enters before it leaves, as its first hit says, whichever surface
 * ids the two crossings have. */
static inline int listed_before(const hr_hit *a, const hr_hit *b)
{
    return a->t < b->t || (a->t == b->t && a->object < b->object);
}

/* Sorts the list stably by listed_before: bottom-up merges through a
 * buffer, or (when there is no memory for it) insertion, which is stable
 * too. The list is the objects' answers one after the other, each sorted
 * already. */
static void sort_hits_stably(hr_intersection *list)
{
    const size_t n = (size_t)list->count;
    hr_hit *a = list->hits, *buffer = malloc(n * sizeof *buffer);
    if (!buffer) {
        for (size_t i = 1; i < n; i++) {
            hr_hit h = a[i];
            size_t j = i;
            for (; j > 0 && listed_before(&h, &a[j - 1]); j--) a[j] = a[j - 1];
            a[j] = h;
        }
        return;
    }
    hr_hit *from = a, *to = buffer;
    for (size_t width = 1; width < n; width *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * width) {
            const size_t mid = lo + width < n ? lo + width : n;
            const size_t hi = mid + width < n ? mid + width : n;
            size_t i = lo, j = mid, k = lo;
            while (i < mid && j < hi) to[k++] = listed_before(&from[j], &from[i]) ? from[j++] : from[i++];
            while (i < mid) to[k++] = from[i++];
            while (j < hi) to[k++] = from[j++];
        }
        hr_hit *swap = from;
        from = to, to = swap;
    }
    if (from != a) memcpy(a, from, n * sizeof *a);
    free(buffer);
}

HR_API hr_status hr_scene_all_hits(const hr_scene *s, const hr_ray *ray, double tmin, double tmax,
                                   hr_intersection *out)
{
    hr_status st = check_query(s, ray, tmin, tmax);
    if (st) return st;
    if (!out || out->count < 0 || out->capacity < 0 || out->count > out->capacity)
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "intersection: NULL or not initialised");
    int32_t *level;
    if ((st = hri_query_enter(s->ctx, "all hits", &level))) return st;
    out->count = 0;
    hr_trace_ctx tc;
    hri_trace_ctx_init_tracing(&tc, s);
    /* The bounded objects are traced only where the first-hit walk would
     * look (hri_scene_trace_nearest): not when the exact ray misses the box
     * around them. Only a hit that the rounding of an object's own copy of
     * the ray made is skipped so: an eye 1e103 away is known to 1e87, and a
     * cone's copy of a ray passing 5e32 from it met it, while the world ray
     * missed the box and the first hit found nothing. */
    const int in_box = !box_misses(&s->bvh_box, ray, tmin, tmax);
    for (int64_t i = 0; i < s->object_count && tc.status == HR_OK; i++) {
        const hr_object *o = s->objects[i];
        if (o->top_level && (in_box || !o->bounded))
            hri_object_trace(&tc, o, ray, tmin, tmax, HR_TRACE_ALL, 1, out);
    }
    /* qsort's base must not be NULL, even for no elements (a scene with no
     * object never gave the list storage). */
    if (out->count > 1) sort_hits_stably(out);
    if (tc.status) out->count = 0;
    return finish_query(&tc, level);
}

HR_API hr_status hr_scene_shade(const hr_scene *s, const hr_ray *ray, int32_t max_depth, hr_color *out)
{
    hr_status st = check_query(s, ray, 0, INFINITY);
    if (st) return st;
    if (!out) return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "shade: NULL output");
    if (max_depth > HR_MAX_RECURSION_DEPTH)
        return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "shade: depth %d must be at most %d",
                        (int)max_depth, HR_MAX_RECURSION_DEPTH);
    int32_t *level;
    if ((st = hri_query_enter(s->ctx, "shade", &level))) return st;
    hr_trace_ctx tc;
    hri_trace_ctx_init(&tc, s);
    hri_trace_ctx_set_bounds(&tc, 0, 0.0, 0); /* as a render's defaults */
    int32_t depth = max_depth >= 0 ? max_depth : s->globals.max_recursion_depth;
    /* The colour does not depend on the direction's length, but shapes and
     * shade's normalising square it: bring it near 1 (exactly, by a power
     * of two) so any finite length works, as the header promises. */
    hr_ray r = {ray->origin, v3_unit_exponent(ray->dir)};
    *out = hri_shade_ray(&tc, &r, 0, depth);
    return finish_query(&tc, level);
}
