/* Internal: the per-thread tracing context (what hr_hit_args.call points
 * to), its scratch lists, and the entry points of tracing and shading that
 * the renderer and the public queries call. */
#ifndef HITRAY_LIB_TRACE_CONTEXT_H
#define HITRAY_LIB_TRACE_CONTEXT_H

#include <math.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "scene/scene_internal.h"
#include "trace/ray_diff.h"

/* Per-thread state of tracing: what hr_hit_args.call points to. Scratch
 * lists are reused across rays, so tracing allocates only while they grow. */
#define HR_SCRATCH_MAX 64
#define HR_OCCLUDER_SLOTS 8
typedef struct hr_trace_ctx {
    /* What tracing reads (hri_object_trace and the host services a shape's
     * hit calls); hri_trace_ctx_init_tracing sets only these. */
    const hr_scene *scene;
    const hr_hit *borrowed;     /* storage of a list on a caller's stack (one
                                   public query's): growing that list copies
                                   it to the heap instead of realloc'ing */
    hr_status status;           /* first failure inside a shape, if any */
    int32_t scratch_used;
    int32_t scratch_ready;      /* scratch[0 .. scratch_ready) are initialised
                                   (set up on first use, so a context costs
                                   nothing for lists a query never needs) */
    /* What shading reads besides. */
    uint64_t rays_shadow, rays_reflected, rays_refracted;
    int32_t force_all_effects;
    /* Cancelling from inside a pixel: a render can spend forever in one
     * pixel (glass facing glass at depth 60 is 2^60 rays), and a progress
     * callback called only between tiles could then never stop it. Every
     * HR_POLL_INTERVAL shade calls the renderer's `poll` runs (it may call
     * the progress callback); shade returns at once while `*cancelled`. */
    const atomic_int *cancelled; /* NULL: nothing can cancel (public queries) */
    const int32_t *cancel_flag;  /* hr_render_options.cancel (may be NULL) */
    void (*poll)(void *user);
    void *poll_user;
    uint32_t shade_calls;
    /* Contribution cut-off (hr_render_options.min_weight): a bounce whose
     * path weight would fall below its allowance is not traced. A camera
     * ray's allowance is min_weight (0: none); with split_cut_off (the
     * default cut-off) a hit that spawns two bounces gives each half of its
     * own, so the allowances of what is cut add up to min_weight at most. */
    double min_weight;
    int32_t split_cut_off;
    uint64_t rays_cut;
    /* The ray budget (hr_render_options.ray_budget): the rays one camera
     * ray may cast, shared out among its bounces (shade.c); 0: none. */
    double ray_budget;
    /* The most levels of bounces below a ray (max_depth - depth) whose
     * whole tree, at two bounces a hit and a shadow ray a light, fits the
     * budget: a ray with no more levels below it can never reach the
     * budget, and shade skips its bookkeeping (INT32_MAX: no budget). */
    int32_t budget_free_levels;
    uint64_t rays_over_budget;
    uint32_t effects_ran;       /* HR_EFFECT_* whose code ran */
    /* The object that blocked the last shadow ray towards each light (by
     * light index modulo the slots; NULL: it was not blocked), asked first
     * by the next one (hri_scene_trace_shadow). Per thread, so no two
     * threads share them; they change how fast a shadow ray is answered,
     * never the answer. */
    const hr_object *occluder[HR_OCCLUDER_SLOTS];
    /* Last, so that setting up a context skips them (scratch_ready). */
    hr_intersection scratch[HR_SCRATCH_MAX];
} hr_trace_ctx;

#define HR_POLL_INTERVAL 65536u

/* Everything but the scratch lists is zeroed; a list is set up when it is
 * first acquired (scratch_ready), so a query neither clears nor frees 64
 * lists it never touches. */
static inline void hri_trace_ctx_init(hr_trace_ctx *tc, const hr_scene *scene)
{
    memset(tc, 0, offsetof(hr_trace_ctx, scratch));
    tc->scene = scene;
    tc->budget_free_levels = INT32_MAX; /* ray_budget 0: none */
}
/* hri_trace_ctx_init's tracing part alone, for a query that never shades
 * (first hit, all hits): the shading fields are left unset, and nothing
 * such a query runs reads them. */
static inline void hri_trace_ctx_init_tracing(hr_trace_ctx *tc, const hr_scene *scene)
{
    tc->scene = scene;
    tc->borrowed = NULL;
    tc->status = HR_OK;
    tc->scratch_used = 0;
    tc->scratch_ready = 0;
}
/* Inline, as the query that ends with it mostly has nothing to free. */
static inline void hri_trace_ctx_release(hr_trace_ctx *tc)
{
    for (int32_t i = 0; i < tc->scratch_ready; i++) {
        free(tc->scratch[i].hits);
        memset(&tc->scratch[i], 0, sizeof tc->scratch[i]);
    }
    tc->scratch_ready = 0;
    tc->scratch_used = 0;
}

/* The context's scratch lists, a stack (trace.c): acquire gives the next
 * one, empty, with room for 4 * HR_MIN_HIT_CAPACITY hits (NULL when all
 * HR_SCRATCH_MAX are taken or out of memory); release gives back `list`
 * and every list acquired after it. `call` is the hr_trace_ctx, as the
 * host services (hr_host) take it. */
hr_intersection *hri_trace_scratch_acquire(void *call);
void hri_trace_scratch_release(void *call, hr_intersection *list);

/* Grow a list to hold at least `capacity` hits (intersection.c). */
hr_status hri_intersection_reserve(hr_intersection *list, int32_t capacity);

/* Trace one object with a ray in its parent's space: hits come back in the
 * parent's space (unit normals only when `unit_normals`), appended to `out`
 * in t order, `object` naming the leaf. mode: HR_TRACE_*. */
hr_status hri_object_trace(hr_trace_ctx *tc, const hr_object *obj, const hr_ray *ray,
                          double tmin, double tmax, int32_t mode, int unit_normals,
                          hr_intersection *out);

/* Hill's getFirstHit over the scene; returns 1 on a hit. */
int hri_scene_trace_first(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax,
                         hr_hit *out);
/* The same with the caller's list `tmp` for the candidate hits (a public
 * query's, on its stack) instead of a scratch list. */
int hri_scene_trace_nearest(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax, hr_hit *out,
                           hr_intersection *tmp);
/* Any hit in (tmin, tmax) of a shadow ray towards light number `light`
 * (>= 0); returns 1 on a hit. Asks first the object that blocked the last
 * shadow ray towards that light. */
int hri_scene_trace_shadow(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax,
                          int32_t light);

/* Hill's shade (lib/trace/shade.c). */
hr_color hri_shade_ray(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth);
/* The same for a ray with differentials (lib/trace/ray_diff.h): every
 * texture it and its bounces meet is filtered by the hit's footprint. */
hr_color hri_shade_ray_diff(hr_trace_ctx *tc, const hr_ray *ray, const hr_ray_diff *rd, int32_t depth,
                            int32_t max_depth);
/* The same for a caller that knows the ray's tree cannot reach the ray
 * budget (max_depth - depth <= tc->budget_free_levels), so that a render
 * decides it once, not for every camera ray. */
hr_color hri_shade_ray_unbudgeted(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth);
/* 2^-HR_DEFAULT_MIN_WEIGHT_BITS: the cut-off renders and hr_scene_shade
 * apply unless told otherwise (render.h). */
static inline double hri_default_min_weight(void) { return 1.0 / (double)(1L << HR_DEFAULT_MIN_WEIGHT_BITS); }
/* The cut-off and the ray budget a shading context applies: `exact` none,
 * else min_weight as a cut-off per ray, or (0) the default's 2^-24 shared
 * among the branches; ray_budget rays per camera ray (0: the default). */
static inline void hri_trace_ctx_set_bounds(hr_trace_ctx *tc, int32_t exact, double min_weight,
                                           int64_t ray_budget)
{
    tc->min_weight = exact ? 0.0 : min_weight > 0.0 ? min_weight : hri_default_min_weight();
    tc->split_cut_off = !exact && !(min_weight > 0.0);
    tc->ray_budget = exact && ray_budget <= 0 ? 0.0 : ray_budget > 0 ? (double)ray_budget : HR_DEFAULT_RAY_BUDGET;
    /* A tree of k levels below its root has 2^(k+1) - 1 rays, each casting
     * at most one shadow ray a light. */
    tc->budget_free_levels = INT32_MAX;
    if (tc->ray_budget > 0.0) {
        double per_ray = 1.0 + (double)tc->scene->light_count;
        int32_t k = 0;
        while (k < 60 && per_ray * (ldexp(1.0, k + 2) - 1.0) <= tc->ray_budget) k++;
        tc->budget_free_levels = k;
    }
}

#endif
