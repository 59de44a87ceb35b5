/* Tracing: one object through its transform (Hill: the ray goes into object
 * space through M^-1 unnormalised, so t is the same in both spaces; normals
 * come back through the transpose of M^-1), and the whole scene through the
 * BVH (getFirstHit, any hit for shadows, every hit for Intersection). */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "context_internal.h"
#include "errors.h"
#include "query_nesting.h"
#include "scene_internal.h"
#include "transform_inline.h"
#include "ray_cull.h"
#include "vec.h"

hr_status hr_intersection_reserve(hr_intersection *list, int32_t capacity)
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

/* hr_intersection_reserve for a list tracing may be handed: the one list
 * whose storage is borrowed from a caller's stack (tc->borrowed) moves to
 * the heap when it must grow, every other list is realloc'd. */
static hr_status list_reserve(hr_trace_ctx *tc, hr_intersection *list, int32_t capacity)
{
    if (capacity <= list->capacity) return HR_OK;
    if (!tc->borrowed || list->hits != tc->borrowed) return hr_intersection_reserve(list, capacity);
    hr_intersection heap = {NULL, 0, 0};
    hr_status st = hr_intersection_reserve(&heap, capacity);
    if (st) return st;
    memcpy(heap.hits, list->hits, (size_t)list->count * sizeof *heap.hits);
    list->hits = heap.hits;
    list->capacity = heap.capacity;
    return HR_OK;
}

/* Everything but the scratch lists is zeroed; a list is set up when it is
 * first acquired (scratch_ready), so a query neither clears nor frees 64
 * lists it never touches. */
void hr_trace_ctx_init(hr_trace_ctx *tc, const hr_scene *scene)
{
    memset(tc, 0, offsetof(hr_trace_ctx, scratch));
    tc->scene = scene;
}

void hr_trace_ctx_release(hr_trace_ctx *tc)
{
    for (int32_t i = 0; i < tc->scratch_ready; i++) {
        free(tc->scratch[i].hits);
        memset(&tc->scratch[i], 0, sizeof tc->scratch[i]);
    }
    tc->scratch_ready = 0;
    tc->scratch_used = 0;
}

/* Order by t; equal t by object then surface, so sorting is deterministic. */
static int hit_before(const hr_hit *a, const hr_hit *b)
{
    if (a->t != b->t) return a->t < b->t;
    if (a->object != b->object) return a->object < b->object;
    return a->surface < b->surface;
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


/* hr_object_trace's body, inline so that the scene walk (visit_object)
 * gets a copy specialised to its mode. */
static inline __attribute__((always_inline)) hr_status
object_trace(hr_trace_ctx *tc, const hr_object *obj, const hr_ray *ray, double tmin, double tmax,
             int32_t mode, int unit_normals, hr_intersection *out)
{
    const hr_shape_class *cls = obj->cls;
    hr_status st;
    if (out->capacity - out->count < HR_MIN_HIT_CAPACITY &&
        (st = list_reserve(tc, out, out->count + HR_MIN_HIT_CAPACITY)))
        return tc->status = st;
    hr_hit_args args;
    args.shape = obj->shape;
    if (obj->identity) {
        args.ray = *ray;
    } else {
        args.ray.origin = hr_xform_point_as(obj->inv, obj->diagonal, ray->origin);
        args.ray.dir = hr_xform_vector_as(obj->inv, obj->diagonal, ray->dir);
    }
    /* A direction whose squared length would under- or overflow (a sphere
     * scaled by 1e-300, a ray into an object scaled by 1e160) is brought near
     * unit length by a power of two, 2^-e, and t scaled by 2^e: exact both
     * ways, so every shape sees a well-scaled ray and no shape needs its own
     * guard. Normal rays skip this with one comparison. */
    int t_exp = v3_rescale_exponent(args.ray.dir);
    const double ray_tmin = tmin, ray_tmax = tmax; /* the caller's window */
    if (t_exp) {
        args.ray.dir = v3_ldexp(args.ray.dir, -t_exp);
        tmin = ldexp(tmin, t_exp);
        tmax = ldexp(tmax, t_exp);
    }
    args.tmin = tmin;
    args.tmax = tmax;
    args.out = out;
    args.call = tc;
    hr_hit_fn fn = cls->hit;
    if (mode == HR_TRACE_FIRST && cls->first_hit) fn = cls->first_hit;
    if (mode == HR_TRACE_ANY) fn = cls->any_hit ? cls->any_hit : cls->first_hit ? cls->first_hit : cls->hit;
    int32_t start = out->count;
    if ((st = fn(&args))) {
        out->count = start;
        return tc->status = st;
    }
    /* A count below where it started, or beyond the room the list has, means
     * the class wrote where it had no room or dropped hits that were not its
     * own: nothing it returned can be trusted, and reading on would leave
     * the list. */
    if (out->count < start || out->count > out->capacity) {
        out->count = start;
        return tc->status = HR_ERROR_MODULE;
    }
    int composite = (cls->flags & HR_SHAPE_COMPOSITE) != 0;
    int32_t kept = start;
    for (int32_t i = start; i < out->count; i++) {
        hr_hit h = out->hits[i];
        /* The host enforces the contract instead of trusting it: a hit outside
         * (tmin, tmax) or with a non-finite field is dropped, before a first
         * or any hit is chosen, so a bad hit cannot hide a good one. Any-hit
         * answers carry only t. */
        if (!(h.t > tmin && h.t < tmax)) continue;
        /* Scaling back may overflow to infinity or round onto an end of the
         * window (the scaled window's ends were rounded too): the hit must be
         * inside the caller's window, checked on the t it will be given. */
        if (t_exp) {
            h.t = ldexp(h.t, -t_exp);
            if (!(h.t > ray_tmin && h.t < ray_tmax && isfinite(h.t))) continue;
        }
        if (mode == HR_TRACE_ANY) {
            out->hits[start] = h;
            out->count = start + 1;
            return HR_OK;
        }
        /* A non-finite point or normal stays non-finite through the
         * transform (each row has a term in every coordinate, and inf * 0 is
         * NaN) and through v3_unit_exponent, so a transformed object's hit
         * is dropped for it by the test after the transform; only a
         * non-finite error could vanish there (a NaN row loses the max), so
         * that is the one value tested first. An untransformed object's hit
         * is tested whole, here. */
        if (obj->identity ? !v3_pair_is_finite(h.point, h.normal, h.error) : !(h.error - h.error == 0.0))
            continue;
        /* A composite's hit names its leaf; one naming no object of the scene
         * is taken as the composite's own, so shading never indexes past the
         * object list. Any other shape leaves `object` unset: it is not read
         * (not even by a branch the compiler may merge, which memcheck flags). */
        if (!composite) h.object = obj->index;
        else if (h.object < 0 || h.object >= tc->scene->object_count) h.object = obj->index;
        /* Normals may have any non-zero length: bring them to a safe scale
         * (exactly, by a power of two) before and after the transform, so
         * neither M^-T nor normalising overflows or underflows. */
        h.normal = v3_unit_exponent(h.normal);
        if (!obj->identity) {
            /* hr_xform_error_as gives the full bound's bits for a finite
             * point; a hit whose point is not finite is dropped below. */
            h.error = hr_xform_error_as(obj->m, &obj->m_error, obj->diagonal, h.point, h.error);
            h.point = hr_xform_point_as(obj->m, obj->diagonal, h.point);
            h.normal = hr_xform_normal_as(obj->inv, obj->diagonal, h.normal);
            h.normal = v3_unit_exponent(h.normal);
            if (!v3_pair_is_finite(h.point, h.normal, h.error)) continue;
        }
        if (unit_normals) h.normal = v3_normalize(h.normal);
        out->hits[kept++] = h;
    }
    out->count = kept;
    if (mode == HR_TRACE_FIRST && kept > start + 1) {
        /* The nearest, whatever order the class listed its hits in. */
        int32_t best = start;
        for (int32_t i = start + 1; i < kept; i++)
            if (hit_before(&out->hits[i], &out->hits[best])) best = i;
        out->hits[start] = out->hits[best];
        out->count = start + 1;
    }
    return HR_OK;
}

hr_status hr_object_trace(hr_trace_ctx *tc, const hr_object *obj, const hr_ray *ray,
                          double tmin, double tmax, int32_t mode, int unit_normals,
                          hr_intersection *out)
{
    return object_trace(tc, obj, ray, tmin, tmax, mode, unit_normals, out);
}

/* --- Whole-scene queries ------------------------------------------------- */

typedef struct first_state {
    hr_trace_ctx *tc;
    const hr_ray *ray;
    double tmin, best;
    hr_hit *out;
    hr_intersection *tmp;
    int found;
    int any; /* stop at the first hit (shadow rays) */
    const hr_object *hit_object; /* whose hit ended an any-hit walk */
} first_state;

/* Test one object; returns 1 to stop (any-hit found one). */
static int visit_object(first_state *fs, const hr_object *o)
{
    fs->tmp->count = 0;
    hr_status st = fs->any ? object_trace(fs->tc, o, fs->ray, fs->tmin, fs->best, HR_TRACE_ANY, 0, fs->tmp)
                           : object_trace(fs->tc, o, fs->ray, fs->tmin, fs->best, HR_TRACE_FIRST, 1, fs->tmp);
    if (st != HR_OK) return 0;
    if (fs->tmp->count == 0) return 0;
    fs->found = 1;
    if (fs->any) {
        fs->hit_object = o;
        return 1;
    }
    fs->best = fs->tmp->hits[0].t;
    *fs->out = fs->tmp->hits[0];
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
static void traverse(first_state *fs)
{
    const hr_scene *s = fs->tc->scene;
    if (!box_misses(&s->bvh_box, fs->ray, fs->tmin, fs->best))
        accel_bvh4_walk(&s->bvh, fs->ray, fs->tmin, &fs->best, visit_leaf, fs);
    int tie_wins = fs->found; /* the best so far is the BVH's */
    for (int32_t i = 0; i < s->unbounded_count; i++) {
        const double best = fs->best;
        const double window = tie_wins ? step_towards(best, 1.0) : best;
        fs->best = window;
        visit_object(fs, s->unbounded[i]);
        if (fs->best == window) fs->best = best; /* no hit (every hit is below the window's end) */
        else tie_wins = 0;
    }
}

static hr_intersection *host_scratch_acquire(void *call);
static void host_scratch_release(void *call, hr_intersection *list);

/* host_scratch_acquire for the scene queries, which take a list for every
 * ray: the list at the top of the stack was set up and given its room by
 * an earlier ray nearly always, and then taking it is a few instructions
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
    return host_scratch_acquire(tc);
}

static int trace_nearest_into(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax,
                              hr_hit *out, hr_intersection *tmp)
{
    first_state fs = {tc, ray, tmin, tmax, out, tmp, 0, 0, NULL};
    traverse(&fs);
    return fs.found;
}

int hr_scene_trace_first(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax, hr_hit *out)
{
    hr_intersection *tmp = scratch_acquire(tc);
    if (!tmp) {
        tc->status = HR_ERROR_OUT_OF_MEMORY;
        return 0;
    }
    int found = trace_nearest_into(tc, ray, tmin, tmax, out, tmp);
    host_scratch_release(tc, tmp);
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
int hr_scene_trace_shadow(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax,
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
        if (hr_object_trace(tc, *slot, ray, tmin, tmax, HR_TRACE_ANY, 0, tmp) == HR_OK && tmp->count > 0) {
            host_scratch_release(tc, tmp);
            return 1;
        }
        tmp->count = 0;
    }
    int32_t first = 0;
    while (first < s->unbounded_count && shadow_passes(s->unbounded[first], ray, tmin, tmax)) first++;
    const int walk = !box_misses(&s->bvh_box, ray, tmin, tmax);
    first_state fs = {tc, ray, tmin, tmax, NULL, tmp, 0, 1, NULL};
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
    if (tmp) host_scratch_release(tc, tmp);
    return fs.found;
}

/* --- Public queries ------------------------------------------------------ */

static inline hr_status check_query(const hr_scene *s, const hr_ray *ray, double tmin, double tmax)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!s->committed) return hr_error(s->ctx, HR_ERROR_STATE, "the scene is not committed (call hr_scene_commit)");
    if (!ray) return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: NULL");
    if (!v3_pair_is_finite(ray->origin, ray->dir, 0.0))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: origin and direction must be finite");
    if (ray->dir.x == 0 && ray->dir.y == 0 && ray->dir.z == 0)
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: direction is the zero vector");
    if (isnan(tmin) || isnan(tmax) || !(tmin <= tmax))
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "ray: need tmin <= tmax (got %g, %g)", tmin, tmax);
    return HR_OK;
}

/* Ends a query begun with hr_query_enter, which gave `level`. */
static hr_status finish_query(hr_trace_ctx *tc, int32_t *level)
{
    hr_query_leave(level);
    hr_status st = tc->status;
    hr_trace_ctx_release(tc);
    if (st) return hr_error(tc->scene->ctx, st, "a shape failed while tracing: %s", hr_status_name(st));
    return HR_OK;
}

HR_API hr_status hr_scene_first_hit(const hr_scene *s, const hr_ray *ray, double tmin, double tmax,
                                    hr_hit *out, int32_t *found)
{
    hr_status st = check_query(s, ray, tmin, tmax);
    if (st) return st;
    if (!out || !found) return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "first hit: NULL output");
    int32_t *level;
    if ((st = hr_query_enter(s->ctx, "first hit", &level))) return st;
    hr_trace_ctx tc;
    hr_trace_ctx_init_tracing(&tc, s);
    /* One ray: the list of candidate hits lives on the stack, so the query
     * allocates nothing unless a shape asks for more room (list_reserve). */
    hr_hit room[4 * HR_MIN_HIT_CAPACITY];
    hr_intersection tmp = {room, 0, 4 * HR_MIN_HIT_CAPACITY};
    tc.borrowed = room;
    *found = trace_nearest_into(&tc, ray, tmin, tmax, out, &tmp);
    if (tmp.hits != room) free(tmp.hits);
    return finish_query(&tc, level);
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

static int compare_hits(const void *a, const void *b)
{
    const hr_hit *x = a, *y = b;
    return hit_before(x, y) ? -1 : hit_before(y, x) ? 1 : 0;
}

HR_API hr_status hr_scene_all_hits(const hr_scene *s, const hr_ray *ray, double tmin, double tmax,
                                   hr_intersection *out)
{
    hr_status st = check_query(s, ray, tmin, tmax);
    if (st) return st;
    if (!out || out->count < 0 || out->capacity < 0 || out->count > out->capacity)
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "intersection: NULL or not initialised");
    int32_t *level;
    if ((st = hr_query_enter(s->ctx, "all hits", &level))) return st;
    out->count = 0;
    hr_trace_ctx tc;
    hr_trace_ctx_init_tracing(&tc, s);
    for (int64_t i = 0; i < s->object_count && tc.status == HR_OK; i++) {
        const hr_object *o = s->objects[i];
        if (o->top_level) hr_object_trace(&tc, o, ray, tmin, tmax, HR_TRACE_ALL, 1, out);
    }
    /* qsort's base must not be NULL, even for no elements (a scene with no
     * object never gave the list storage). */
    if (out->count > 1) qsort(out->hits, (size_t)out->count, sizeof *out->hits, compare_hits);
    if (tc.status) out->count = 0;
    return finish_query(&tc, level);
}

HR_API hr_status hr_scene_shade(const hr_scene *s, const hr_ray *ray, int32_t max_depth, hr_color *out)
{
    hr_status st = check_query(s, ray, 0, INFINITY);
    if (st) return st;
    if (!out) return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "shade: NULL output");
    if (max_depth > HR_MAX_RECURSION_DEPTH)
        return hr_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "shade: depth %d must be at most %d",
                        (int)max_depth, HR_MAX_RECURSION_DEPTH);
    int32_t *level;
    if ((st = hr_query_enter(s->ctx, "shade", &level))) return st;
    hr_trace_ctx tc;
    hr_trace_ctx_init(&tc, s);
    tc.min_weight = hr_default_min_weight(); /* as a render's default */
    int32_t depth = max_depth >= 0 ? max_depth : s->globals.max_recursion_depth;
    /* The colour does not depend on the direction's length, but shapes and
     * shade's normalising square it: bring it near 1 (exactly, by a power
     * of two) so any finite length works, as the header promises. */
    hr_ray r = {ray->origin, v3_unit_exponent(ray->dir)};
    *out = hr_shade_ray(&tc, &r, 0, depth);
    return finish_query(&tc, level);
}

/* --- Host services given to shape modules -------------------------------- */

static void *host_alloc(size_t size) { return calloc(1, size ? size : 1); }
static void host_free(void *p) { free(p); }

static hr_status host_reserve(void *call, hr_intersection *list, int32_t capacity)
{
    if (!list || capacity < 0) return HR_ERROR_INVALID_ARGUMENT;
    return call ? list_reserve(call, list, capacity) : hr_intersection_reserve(list, capacity);
}

static hr_intersection *host_scratch_acquire(void *call)
{
    hr_trace_ctx *tc = call;
    if (tc->scratch_used >= HR_SCRATCH_MAX) return NULL;
    hr_intersection *list = &tc->scratch[tc->scratch_used];
    if (tc->scratch_used == tc->scratch_ready) {
        memset(list, 0, sizeof *list);
        tc->scratch_ready++;
    }
    if (hr_intersection_reserve(list, 4 * HR_MIN_HIT_CAPACITY) != HR_OK) return NULL;
    tc->scratch_used++;
    list->count = 0;
    return list;
}

static void host_scratch_release(void *call, hr_intersection *list)
{
    hr_trace_ctx *tc = call;
    /* Lists are a stack: releasing one releases everything acquired after. */
    int32_t i = (int32_t)(list - tc->scratch);
    if (i >= 0 && i < tc->scratch_used) tc->scratch_used = i;
}

static hr_status host_trace_child(void *call, const void *child, const hr_ray *ray, double tmin,
                                  double tmax, int32_t mode, hr_intersection *out)
{
    if (!call || !child || !ray || !out) return HR_ERROR_INVALID_ARGUMENT;
    int32_t start = out->count;
    /* Composites ask for every hit (csg.c does but for its probes): that
     * mode gets object_trace's copy made for it. */
    hr_status st = mode == HR_TRACE_ALL ? object_trace(call, child, ray, tmin, tmax, HR_TRACE_ALL, 0, out)
                                        : hr_object_trace(call, child, ray, tmin, tmax, mode, 0, out);
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

void hr_host_services_init(hr_host *host)
{
    memset(host, 0, sizeof *host);
    host->struct_size = sizeof *host;
    host->abi_version = HR_SHAPE_ABI_VERSION;
    host->alloc = host_alloc;
    host->free = host_free;
    host->reserve = host_reserve;
    host->scratch_acquire = host_scratch_acquire;
    host->scratch_release = host_scratch_release;
    host->trace_child = host_trace_child;
    host->child_bounds = host_child_bounds;
    host->child_class = host_child_class;
}
