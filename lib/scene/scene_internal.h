/* Internal: what a scene holds, and the per-thread tracing context. */
#ifndef HITRAY_LIB_SCENE_INTERNAL_H
#define HITRAY_LIB_SCENE_INTERNAL_H

#include <math.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "bvh4.h"
#include "geometry/transform_inline.h"

/* Per-material flags worked out at commit, so shade() tests one bit. */
#define HR_MAT_EMITS 1u
#define HR_MAT_AMBIENT 2u
#define HR_MAT_DIFFUSE 4u
#define HR_MAT_SPECULAR 8u
#define HR_MAT_REFLECTS 16u
#define HR_MAT_REFRACTS 32u
#define HR_MAT_INERT_LIGHT 64u /* some light cannot add to its diffuse or specular */
#define HR_MAT_COOK_TORRANCE 128u /* specularFraction > 0: Cook-Torrance, not Phong */
#define HR_MAT_TEXTURED 256u       /* it has a texture (hr_object.texture) */
/* Shading works on an adjusted copy of the material (lib/trace/shade.c). */
#define HR_MAT_ADJUSTED (HR_MAT_COOK_TORRANCE | HR_MAT_TEXTURED)

/* The cache line size objects are aligned to. */
#define HR_OBJECT_ALIGN 64

typedef struct hr_object {
    /* What tracing reads first, together: a ray that misses the object
     * reads cls, shape, the flags and the top three rows of inv, which sit
     * in the first two of the object's cache lines (lib/scene/scene_objects.c
     * allocates it on a line of its own, HR_OBJECT_ALIGN); a hit reads
     * index, m's rows and m_error, the lines after. */
    int64_t index;
    const hr_shape_class *cls;
    void *shape;              /* what the class's create returned */
    int32_t identity;         /* m is the identity: skip the transforms */
    int32_t diagonal;         /* m's and inv's linear parts are diagonal
                                 (hr_xform_is_diagonal): one term a row */
    double inv[16], m[16];    /* m: object -> world (for a child: -> parent); inv: back */
    hr_xform_error_terms m_error; /* hr_xform_error_terms_of(m) */
    /* What tracing does not read. */
    const char *module_path;
    hr_material material;     /* `parameters` points at params_copy */
    double *params_copy;
    int32_t top_level;        /* 0 once consumed by a composite */
    int32_t composite_depth;  /* 0 for a leaf; 1 + the deepest child's */
    int32_t bounded;
    uint32_t mat_flags;       /* HR_MAT_* */
    double specular_cutoff;   /* hr_specular_cutoff of the material's exponent */
    hr_bounds local_bounds;   /* object space */
    /* For an unbounded object's cull in object space (lib/trace/ray_cull.h):
     * bit k when local_bounds has a finite end on axis k, and the largest
     * world direction it reads as object_trace would. */
    uint32_t slab_axes;
    double cull_dir_limit;
    hr_bounds world_bounds;   /* parent space (the world for a top-level object) */
    const struct hr_object *parent; /* the composite that consumed it, or NULL */
    struct hr_texture *texture; /* lib/texture/texture.h; NULL: untextured */
} hr_object;

struct hr_scene {
    hr_context *ctx;
    hr_object **objects;
    int64_t object_count, object_cap;
    hr_light *lights;
    int32_t light_count, light_cap;
    hr_scene_globals globals;
    int32_t committed;
    uint32_t effects;           /* HR_EFFECT_* the scene calls for */
    uint32_t bounce_effects;    /* REFLECTION/REFRACTION the materials call for
                                   at any depth (a render or shade may ask for
                                   more depth than the scene's) */
    accel_bvh4 bvh;             /* over bounded top-level objects */
    hr_bounds bvh_box;          /* around them, widened (lib/trace/ray_cull.h) */
    const hr_object **leaf_objects; /* those objects in the BVH's leaf order */
    const hr_object **unbounded; /* top-level objects outside the BVH */
    int32_t unbounded_count;
    struct hr_pixmap **pixmaps; /* Hill's makePixmap (lib/texture/pixmap.c) */
    int32_t pixmap_count, pixmap_cap;
};

/* Input bounds that keep every pixel finite. With |colour| <= HR_MAX_COLOR,
 * weights in [0, 1] and an exponent >= 0 (so (h.m)^e <= 1), each ray traced
 * adds at most (2 + lights) * 1e12 to its pixel, weighted by products of
 * coefficients <= 1. A pixel is a sum over the rays it traced, so it stays
 * far below float's 3.4e38 for any render that can finish (it would take
 * ~1e20 rays per pixel to get there). A texture's colour is bounded the same
 * way (its parameters and pixmap pixels), and Cook-Torrance's term by
 * HR_COOK_TORRANCE_MAX: each multiplies a ray's share by at most 1e6 more,
 * which still takes ~1e14 rays per pixel to overflow. */
#define HR_MAX_COLOR 1e6
#define HR_MAX_EXPONENT 1e6

/* A colour of a material, light or the globals within those bounds. */
static inline int hr_color_in_range(hr_color c)
{
    return isfinite(c.r) && isfinite(c.g) && isfinite(c.b) && fabs(c.r) <= HR_MAX_COLOR &&
           fabs(c.g) <= HR_MAX_COLOR && fabs(c.b) <= HR_MAX_COLOR;
}

/* The checks on a full-size material (scene_materials.c);
 * hr_material_validate is the public door, which first reads only the bytes
 * the caller declared. */
hr_status hr_material_check(hr_context *ctx, const hr_material *m);
/* Destroys the object's shape and frees what it owns (scene_objects.c). */
void hr_object_free(hr_object *o);
/* The material flags of every object and the scene's effects, at commit
 * (scene_effects.c). */
void hr_scene_work_out_effects(hr_scene *s);

/* Per-thread state of tracing: what hr_hit_args.call points to. Scratch
 * lists are reused across rays, so tracing allocates only while they grow. */
#define HR_SCRATCH_MAX 64
#define HR_OCCLUDER_SLOTS 8
typedef struct hr_trace_ctx {
    /* What tracing reads (hr_object_trace and the host services a shape's
     * hit calls); hr_trace_ctx_init_tracing sets only these. */
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
     * path weight would fall below this is not traced; 0: none. */
    double min_weight;
    uint64_t rays_cut;
    uint32_t effects_ran;       /* HR_EFFECT_* whose code ran */
    /* The object that blocked the last shadow ray towards each light (by
     * light index modulo the slots; NULL: it was not blocked), asked first
     * by the next one (hr_scene_trace_shadow). Per thread, so no two
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
static inline void hr_trace_ctx_init(hr_trace_ctx *tc, const hr_scene *scene)
{
    memset(tc, 0, offsetof(hr_trace_ctx, scratch));
    tc->scene = scene;
}
/* hr_trace_ctx_init's tracing part alone, for a query that never shades
 * (first hit, all hits): the shading fields are left unset, and nothing
 * such a query runs reads them. */
static inline void hr_trace_ctx_init_tracing(hr_trace_ctx *tc, const hr_scene *scene)
{
    tc->scene = scene;
    tc->borrowed = NULL;
    tc->status = HR_OK;
    tc->scratch_used = 0;
    tc->scratch_ready = 0;
}
/* Inline, as the query that ends with it mostly has nothing to free. */
static inline void hr_trace_ctx_release(hr_trace_ctx *tc)
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
hr_intersection *hr_trace_scratch_acquire(void *call);
void hr_trace_scratch_release(void *call, hr_intersection *list);

/* Grow a list to hold at least `capacity` hits (intersection.c). */
hr_status hr_intersection_reserve(hr_intersection *list, int32_t capacity);

/* Trace one object with a ray in its parent's space: hits come back in the
 * parent's space (unit normals only when `unit_normals`), appended to `out`
 * in t order, `object` naming the leaf. mode: HR_TRACE_*. */
hr_status hr_object_trace(hr_trace_ctx *tc, const hr_object *obj, const hr_ray *ray,
                          double tmin, double tmax, int32_t mode, int unit_normals,
                          hr_intersection *out);

/* Hill's getFirstHit over the scene; returns 1 on a hit. */
int hr_scene_trace_first(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax,
                         hr_hit *out);
/* The same with the caller's list `tmp` for the candidate hits (a public
 * query's, on its stack) instead of a scratch list. */
int hr_scene_trace_nearest(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax, hr_hit *out,
                           hr_intersection *tmp);
/* Any hit in (tmin, tmax) of a shadow ray towards light number `light`
 * (>= 0); returns 1 on a hit. Asks first the object that blocked the last
 * shadow ray towards that light. */
int hr_scene_trace_shadow(hr_trace_ctx *tc, const hr_ray *ray, double tmin, double tmax,
                          int32_t light);

/* Hill's shade (lib/trace/shade.c). */
/* 1 if light L can add nothing to a material with these HR_MAT_* flags. */
int hr_light_adds_nothing(const hr_light *L, const hr_material *mat, uint32_t flags);
hr_color hr_shade_ray(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth);
/* 2^-HR_DEFAULT_MIN_WEIGHT_BITS: the cut-off renders and hr_scene_shade
 * apply unless told otherwise (render.h). */
static inline double hr_default_min_weight(void) { return 1.0 / (double)(1L << HR_DEFAULT_MIN_WEIGHT_BITS); }

#endif
