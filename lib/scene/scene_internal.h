/* Internal: what a scene holds: its objects, lights, pixmaps and BVH. */
#ifndef HITRAY_LIB_SCENE_INTERNAL_H
#define HITRAY_LIB_SCENE_INTERNAL_H

#include <math.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "bvh8.h"
#include "scene/material_store.h"
#include "util/color_bounds.h"
#include "geometry/transform_inline.h"
#include "scene/scene_budget.h"
#include "texture/texture.h"

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
                                 (hri_xform_is_diagonal): one term a row */
    double inv[16], m[16];    /* m: object -> world (for a child: -> parent); inv: back */
    hr_xform_error_terms m_error; /* hri_xform_error_terms_of(m) */
    /* What tracing does not read. */
    const char *module_path;
    const hr_material *material; /* the scene's copy (hri_material_store), shared
                                    by every object of the same material */
    int32_t top_level;        /* 0 once consumed by a composite */
    int32_t composite_depth;  /* 0 for a leaf; 1 + the deepest child's */
    int32_t bounded;
    uint32_t mat_flags;       /* HR_MAT_* (scene/material_analysis.h) */
    double specular_cutoff;   /* hri_specular_cutoff of the material's exponent */
    hr_bounds local_bounds;   /* object space */
    /* For an unbounded object's cull in object space (lib/scene/cull_prepare.h, lib/trace/ray_cull.h):
     * bit k when local_bounds has a finite end on axis k, and the largest
     * world direction it reads as object_trace would. */
    uint32_t slab_axes;
    double cull_dir_limit;
    hr_bounds world_bounds;   /* parent space (the world for a top-level object) */
    const struct hr_object *parent; /* the composite that consumed it, or NULL */
    hr_texture *texture;       /* NULL: untextured */
    hr_param *params;          /* as created, for introspection (hri_params_keep) */
} hr_object;

/* The memory objects are carved from, one slab for many objects (the
 * scene's list, newest first): a slab of cap objects, each on
 * HR_OBJECT_ALIGN, after this header (rounded up to it). One allocation
 * every few thousand objects, where an aligned allocation each cost about
 * 660 instructions and its padding (lib/scene/scene_objects.c). */
typedef struct hri_object_slab {
    struct hri_object_slab *next;
    size_t used, cap;
} hri_object_slab;

struct hr_scene {
    hr_context *ctx;
    hr_object **objects;
    int64_t object_count, object_cap;
    hri_object_slab *slabs;     /* where the objects live */
    hri_material_store materials; /* what their materials point at */
    hr_light *lights;
    int32_t light_count, light_cap;
    hr_scene_globals globals;
    hr_material default_material; /* hr_material_default's, made once: an object
                                     added without a material copies it */
    int32_t committed;
    uint32_t effects;           /* HR_EFFECT_* the scene calls for */
    uint32_t bounce_effects;    /* REFLECTION/REFRACTION the materials call for
                                   at any depth (a render or shade may ask for
                                   more depth than the scene's) */
    accel_bvh4 bvh;             /* over bounded top-level objects */
    accel_bvh8 bvh8;            /* bvh collapsed to 8 wide, on AVX2 CPUs (else not built) */
    hr_bounds bvh_box;          /* around them, widened (lib/scene/cull_prepare.h) */
    const hr_object **leaf_objects; /* those objects in the BVH's leaf order */
    const hr_object **unbounded; /* top-level objects outside the BVH */
    int32_t unbounded_count;
    hr_pixmap_set pixmaps;      /* Hill's makePixmap (lib/texture/pixmap.c) */
    hr_scene_budget budget;     /* what its objects, shape data and texels may take */
    char **files;               /* the files it was built from (scene_files.c) */
    int64_t file_count, file_cap;
};

/* The checks on a full-size material (scene_materials.c);
 * hr_material_validate is the public door, which first reads only the bytes
 * the caller declared. */
hr_status hri_material_check(hr_context *ctx, const hr_material *m);
/* The scene's list of files (scene_files.c): freed with the scene; a
 * shape's create is bracketed by begin and end, so that hr_host.file_read
 * (hri_scene_create_file_read, with the create's own arguments) notes the
 * file in the scene being built. */
void hri_scene_files_free(hr_scene *s);
void hri_scene_create_begin(hr_scene *s, const hr_create_args *args);
void hri_scene_create_end(void);
hr_status hri_scene_create_file_read(const hr_create_args *args, const char *path);
/* Destroys the object's shape and frees what it owns (scene_objects.c);
 * its own memory is its slab's, freed with the scene (hri_object_slabs_free). */
void hri_object_free(hr_object *o);
void hri_object_slabs_free(hri_object_slab *slab);

#endif
