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
    /* The window objects are traced in, (tmin, best): for a first hit,
     * best is the caller's tmax until a hit is found, then the step above
     * the nearest hit's t, so that a hit at exactly that t is still seen
     * (the tie rule, visit_object). */
    double tmin, best;
    hr_hit *out;
    hr_intersection *tmp;
    int found;
    int any; /* stop at the first hit (shadow rays) */
    const hr_object *hit_object; /* whose hit ended an any-hit walk */
    /* An any-hit walk's object already asked, with the same ray and
     * window, and found clear (the shadow cache's, hri_scene_trace_shadow):
     * the walk passes it by. NULL: none. */
    const hr_object *asked;
} first_state;

/* Test one object; returns 1 to stop (any-hit found one).
 *
 * The tie rule: the first hit is the least hit in hit_before's order, (t,
 * object, surface), the answer of testing every object and sorting (the
 * brute force, hr_scene_all_hits): at an exact tie in t the object added
 * first wins, then the lower surface. The walk meets objects in an order of
 * its own, so an object it meets later must still be able to give a hit at
 * exactly the best t (to win it if it was added first): once a hit is
 * found, the window ends one step above its t, and a hit at that same t
 * replaces it only if hit_before says so. The walk culls against that
 * window's end too, and its box test keeps a box whose entry is at the end
 * (accel/bvh4.h), so a box entered at exactly the best t is visited. Each
 * object is asked for its own least hit (object_trace), which does not
 * depend on the window's end but for which hits it keeps, so the answer is
 * the brute force's in any order the objects are met. */
static int visit_object(first_state *fs, const hr_object *o)
{
    if (o == fs->asked) return 0;
    fs->tmp->count = 0;
    hr_status st = fs->any ? object_trace(fs->tc, o, fs->ray, fs->tmin, fs->best, HR_TRACE_ANY, 0, fs->tmp)
                           : object_trace(fs->tc, o, fs->ray, fs->tmin, fs->best, HR_TRACE_FIRST, 1, fs->tmp);
    if (st != HR_OK) return 0;
    if (fs->tmp->count == 0) return 0;
    if (fs->any) {
        fs->found = 1;
        fs->hit_object = o;
        return 1;
    }
    const hr_hit *h = &fs->tmp->hits[0];
    /* Within the window: at or before the best hit's t; a tie is decided
     * by the rest of hit_before's order. */
    if (fs->found && h->t == fs->out->t && !hit_before(h, fs->out)) return 0;
    fs->found = 1;
    fs->best = step_towards(h->t, 1.0);
    *fs->out = *h;
    return 0;
}

/* The objects of one BVH leaf; a nearer hit lowers fs->best, which the
 * walk reads back. */
static int visit_leaf(void *user, uint32_t first, uint32_t count)
{
    first_state *fs = user;
    const hr_object *const *objects = fs->tc->scene->leaf_objects + first;
    for (uint32_t i = 0; i < count; i++)
        if (visit_object(fs, objects[i])) return ACCEL_WALK_STOP;
    return ACCEL_WALK_GO_ON;
}

/* A first hit: the BVH front to back (8 wide on AVX2 CPUs, accel/bvh8.h,
 * which meets leaves in an order of its own), boxes further than the best
 * hit so far skipped (the whole walk when the ray misses the box around the BVH's
 * objects, box_misses), then the unbounded objects within the best hit's
 * window, so that one an object hides costs its shape a miss, not a hit
 * taken back to world space. The tie rule (visit_object) makes the answer
 * the same whatever the order: an unbounded object added before the BVH's
 * best wins a tie with it, one added after loses. */
int hri_scene_trace_nearest(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax, hr_hit *out,
                           hr_intersection *tmp)
{
    first_state fs = {tc, ray, tmin, tmax, out, tmp, 0, 0, NULL, NULL};
    const hr_scene *s = tc->scene;
    if (!box_misses(&s->bvh_box, ray, tmin, fs.best))
        accel_bvh8_walk(&s->bvh8, &s->bvh, ray, tmin, &fs.best, visit_leaf, &fs);
    for (int32_t i = 0; i < s->unbounded_count; i++) visit_object(&fs, s->unbounded[i]);
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
 * objects (box_misses), stopping at the first hit; the cached object, which
 * has just answered this ray and window with no hit, is not asked again
 * (a shape's answer depends on nothing else: a mesh's any-hit walk costs
 * as much the second time). The answer is the same in any order: the ray
 * is blocked if any object has a hit in (tmin, tmax).
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
    first_state fs = {tc, ray, tmin, tmax, NULL, tmp, 0, 1, NULL, *slot};
    if (first < s->unbounded_count || walk) {
        if (!tmp && !(fs.tmp = tmp = scratch_acquire(tc))) {
            tc->status = HR_ERROR_OUT_OF_MEMORY;
            return 0;
        }
        for (int32_t i = first; i < s->unbounded_count && !fs.found; i++)
            if (i == first || !shadow_passes(s->unbounded[i], ray, tmin, tmax))
                visit_object(&fs, s->unbounded[i]);
        if (!fs.found && walk) accel_bvh8_walk_any(&s->bvh8, &s->bvh, ray, tmin, &fs.best, visit_leaf, &fs);
    }
    *slot = fs.hit_object;
    if (tmp) hri_trace_scratch_release(tc, tmp);
    return fs.found;
}
