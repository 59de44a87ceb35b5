/* Tracing: the whole scene through the BVH (Hill's getFirstHit, and any hit
 * for shadow rays), each object traced by object_trace.h's inline body, and
 * the per-thread lists tracing takes its room from: the scratch stack and
 * the one list a public query lends from its own stack. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "trace/object_trace.h"
#include "trace/ray_cull.h"
#include "trace/trace_context.h"
#include "geometry/vec.h"

hr_status hri_trace_list_reserve(hr_trace_ctx *tc, hr_intersection *list, int32_t capacity)
{
    if (capacity <= list->capacity) return HR_OK;
    if (!tc->borrowed || list->hits != tc->borrowed) return hri_intersection_reserve(list, capacity);
    hr_intersection heap = {NULL, 0, 0};
    hr_status st = hri_intersection_reserve(&heap, capacity);
    if (st) return st;
    memcpy(heap.hits, list->hits, (size_t)list->count * sizeof *heap.hits);
    list->hits = heap.hits;
    list->capacity = heap.capacity;
    return HR_OK;
}

hr_intersection *hri_trace_scratch_acquire(void *call)
{
    hr_trace_ctx *tc = call;
    if (tc->scratch_used >= HR_SCRATCH_MAX) return NULL;
    hr_intersection *list = &tc->scratch[tc->scratch_used];
    if (tc->scratch_used == tc->scratch_ready) {
        memset(list, 0, sizeof *list);
        tc->scratch_ready++;
    }
    if (hri_intersection_reserve(list, 4 * HR_MIN_HIT_CAPACITY) != HR_OK) return NULL;
    tc->scratch_used++;
    list->count = 0;
    return list;
}

void hri_trace_scratch_release(void *call, hr_intersection *list)
{
    hr_trace_ctx *tc = call;
    /* Lists are a stack: releasing one releases everything acquired after. */
    int32_t i = (int32_t)(list - tc->scratch);
    if (i >= 0 && i < tc->scratch_used) tc->scratch_used = i;
}

hr_status hri_object_trace(hr_trace_ctx *tc, const hr_object *obj, const hr_ray *ray,
                          double tmin, double tmax, int32_t mode, int unit_normals,
                          hr_intersection *out)
{
    return object_trace(tc, obj, ray, tmin, tmax, mode, unit_normals, out);
}

typedef struct first_state {
    hr_trace_ctx *tc;
    const hr_ray *ray;
    double tmin, best;
    /* A first hit's objects are traced below this: the best t (or tmax),
     * or in the BVH walk the double after the best t, which the walk
     * reads back to skip boxes. */
    double window;
    hr_hit *out;
    hr_intersection *tmp;
    int found;
    int any;      /* stop at the first hit (shadow rays) */
    int by_index; /* the BVH walk: ties at the best t go to the lower object index */
    int32_t taken; /* hits that became the best */
    const hr_object *hit_object; /* whose hit ended an any-hit walk */
} first_state;

/* Test one object; returns 1 to stop (any-hit found one). The BVH walk
 * visits objects front to back by their boxes, not by index, so it traces
 * each object up to and including the best t and takes a hit at that very
 * t only from a lower object index (a leaf's, for a composite): the tie
 * rule of hr_scene_all_hits's order. Seen from 1e16 away, two solids a
 * unit apart are met at the same rounded t, and the one visited second
 * must still win when its index is lower. */
static int visit_object(first_state *fs, const hr_object *o)
{
    fs->tmp->count = 0;
    hr_status st = fs->any ? object_trace(fs->tc, o, fs->ray, fs->tmin, fs->best, HR_TRACE_ANY, 0, fs->tmp)
                           : object_trace(fs->tc, o, fs->ray, fs->tmin, fs->window, HR_TRACE_FIRST, 1, fs->tmp);
    if (st != HR_OK) return 0;
    if (fs->tmp->count == 0) return 0;
    if (fs->any) {
        fs->found = 1;
        fs->hit_object = o;
        return 1;
    }
    const hr_hit *h = &fs->tmp->hits[0];
    if (fs->by_index && fs->found && !(h->t < fs->best || h->object < fs->out->object)) return 0;
    fs->found = 1;
    fs->taken++;
    fs->best = h->t;
    fs->window = fs->by_index ? step_towards(h->t, 1.0) : h->t;
    *fs->out = *h;
    return 0;
}

/* The objects of one BVH leaf; a nearer hit lowers fs->window (or
 * fs->best, for any hit), which the walk reads back. */
static int visit_leaf(void *user, uint32_t first, uint32_t count)
{
    first_state *fs = user;
    const hr_object *const *objects = fs->tc->scene->leaf_objects + first;
    for (uint32_t i = 0; i < count; i++)
        if (visit_object(fs, objects[i])) return ACCEL_WALK_STOP;
    return ACCEL_WALK_GO_ON;
}

/* A first hit: the BVH front to back, boxes further than the best hit so
 * far skipped (the whole walk when the ray misses the box around the BVH's
 * objects, box_misses), then the unbounded objects within the best hit's t,
 * so that one an object hides costs its shape a miss, not a hit taken back
 * to world space. The answer is the one of testing the unbounded objects
 * first, as this walk once did: the BVH's nearest hit below an unbounded
 * object's t is the same with or without that t as its bound (a shape's
 * hits do not depend on tmax but for which it keeps), and on a tie the
 * object tested first kept the hit, so an unbounded object wins a tie with
 * the BVH's best (its window then ends just after it) and loses one with an
 * unbounded object before it. */
int hri_scene_trace_nearest(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax, hr_hit *out,
                           hr_intersection *tmp)
{
    first_state fs = {.tc = tc, .ray = ray, .tmin = tmin, .best = tmax, .window = tmax, .out = out, .tmp = tmp,
                      .by_index = 1};
    const hr_scene *s = tc->scene;
    if (!box_misses(&s->bvh_box, ray, tmin, fs.best))
        accel_bvh4_walk(&s->bvh, ray, tmin, &fs.window, visit_leaf, &fs);
    fs.by_index = 0;
    int tie_wins = fs.found; /* the best so far is the BVH's */
    for (int32_t i = 0; i < s->unbounded_count; i++) {
        fs.window = tie_wins ? step_towards(fs.best, 1.0) : fs.best;
        const int32_t taken = fs.taken;
        visit_object(&fs, s->unbounded[i]);
        if (fs.taken != taken) tie_wins = 0;
    }
    return fs.found;
}

/* hri_trace_scratch_acquire for the scene walks, which take a list for
 * every ray: the list at the top of the stack was set up and given its room
 * by an earlier ray nearly always, and then taking it is a few instructions
 * inline instead of a call that checks and reserves again. */
static inline __attribute__((always_inline)) hr_intersection *scratch_acquire(hr_trace_ctx *tc)
{
    if (tc->scratch_used < tc->scratch_ready) {
        hr_intersection *list = &tc->scratch[tc->scratch_used];
        if (list->capacity >= 4 * HR_MIN_HIT_CAPACITY) {
            tc->scratch_used++;
            list->count = 0;
            return list;
        }
    }
    return hri_trace_scratch_acquire(tc);
}

int hri_scene_trace_first(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax, hr_hit *out)
{
    hr_intersection *tmp = scratch_acquire(tc);
    if (!tmp) {
        tc->status = HR_ERROR_OUT_OF_MEMORY;
        return 0;
    }
    int found = hri_scene_trace_nearest(tc, ray, tmin, tmax, out, tmp);
    hri_trace_scratch_release(tc, tmp);
    return found;
}

/* Whether a shadow ray certainly misses the unbounded object `o`. */
static inline __attribute__((always_inline)) int shadow_passes(const hr_object *o, const hr_ray *ray, double tmin, double tmax)
{
    return o->slab_axes && unbounded_misses(o, ray, tmin, tmax);
}

/* A shadow ray asks first the object that blocked the last shadow ray
 * towards the same light (the shadow cache of Haines and Greenberg): a
 * shadow falls across many neighbouring pixels, so that object often
 * blocks this ray too, and one object test replaces the walk. Then the
 * unbounded objects (planes) that unbounded_misses does not cull, and the
 * BVH, children in slot order, unless the ray misses the box around its
 * objects (box_misses), stopping at the first hit. The answer is the same
 * in any order: the ray is blocked if any object has a hit in (tmin, tmax).
 * A ray that the culls leave nothing to ask (most shadow rays over a floor)
 * takes no scratch list. */
int hri_scene_trace_shadow(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax,
                          int32_t light)
{
    const hr_scene *s = tc->scene;
    const hr_object **slot = &tc->occluder[(uint32_t)light % HR_OCCLUDER_SLOTS];
    hr_intersection *tmp = NULL;
    if (*slot) {
        if (!(tmp = scratch_acquire(tc))) {
            tc->status = HR_ERROR_OUT_OF_MEMORY;
            return 0;
        }
        if (hri_object_trace(tc, *slot, ray, tmin, tmax, HR_TRACE_ANY, 0, tmp) == HR_OK && tmp->count > 0) {
            hri_trace_scratch_release(tc, tmp);
            return 1;
        }
        tmp->count = 0;
    }
    int32_t first = 0;
    while (first < s->unbounded_count && shadow_passes(s->unbounded[first], ray, tmin, tmax)) first++;
    const int walk = !box_misses(&s->bvh_box, ray, tmin, tmax);
    first_state fs = {.tc = tc, .ray = ray, .tmin = tmin, .best = tmax, .window = tmax, .tmp = tmp, .any = 1};
    if (first < s->unbounded_count || walk) {
        if (!tmp && !(fs.tmp = tmp = scratch_acquire(tc))) {
            tc->status = HR_ERROR_OUT_OF_MEMORY;
            return 0;
        }
        for (int32_t i = first; i < s->unbounded_count && !fs.found; i++)
            if (i == first || !shadow_passes(s->unbounded[i], ray, tmin, tmax))
                visit_object(&fs, s->unbounded[i]);
        if (!fs.found && walk) accel_bvh4_walk_any(&s->bvh, ray, tmin, &fs.best, visit_leaf, &fs);
    }
    *slot = fs.hit_object;
    if (tmp) hri_trace_scratch_release(tc, tmp);
    return fs.found;
}
