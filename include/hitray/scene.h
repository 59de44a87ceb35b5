/* hitray: scenes — objects, materials, lights, globals — and Hill's queries.
 *
 * Build a scene with hr_scene_add_object / hr_scene_add_light /
 * hr_scene_set_globals, then hr_scene_commit it: commit validates, builds the
 * acceleration structure and works out which effects the scene calls for.
 * A committed scene is immutable and any number of threads may query and
 * render it at once. */
#ifndef HITRAY_SCENE_H
#define HITRAY_SCENE_H

#include "camera.h"
#include "common.h"
#include "scene_fields.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A material as Hill's SDL describes it; every field is per object.
 * hr_material_default gives SDL's defaults (HR_MATERIAL_FIELDS in
 * scene_fields.h names each field's SDL keyword and default). hr_scene_add_object refuses
 * values that could make a pixel infinite: a colour component beyond +-1e6,
 * a reflectivity or transparency outside [0, 1], a specular exponent outside
 * [0, 1e6], a speed of light <= 0. Light colours obey the same +-1e6. */
typedef struct hr_material {
    uint32_t struct_size;
    int32_t texture;          /* 0 none; < 0 a solid texture (-1 checkerboard,
                                 -2 wood, -3 marble); N > 0 the image texture of
                                 pixmap N (hr_scene_set_pixmap). It modulates
                                 the ambient and diffuse colours; `parameters`
                                 tune it (docs/sdl.md lists each one) */
    hr_color ambient;         /* default 0.1 0.1 0.1 */
    hr_color diffuse;         /* default 0.8 0.8 0.8 */
    hr_color specular;        /* default 0 0 0 */
    hr_color emissive;        /* default 0 0 0 */
    double specular_exponent; /* default 1 */
    double reflectivity;      /* default 0; mirror weight in [0, 1] */
    double transparency;      /* default 0; transmission weight in [0, 1] */
    double speed_of_light;    /* default 1; relative speed of light inside */
    double specular_fraction; /* default 0: Phong's specular term. In (0, 1]:
                                 the specular term is Cook-Torrance's, weighted
                                 by this, and the diffuse by 1 minus it */
    double surface_roughness; /* default 1: Beckmann's m (rms slope of the
                                 microfacets) of Cook-Torrance; > 0 */
    int32_t parameter_count;  /* texture parameters (copied at add time) */
    int32_t reserved;
    const double *parameters;
} hr_material;
HR_API void hr_material_default(hr_material *m);
/* Check a material as hr_scene_add_object will (the bounds above); the
 * message names the field and its value. `ctx` may be NULL (no message). */
HR_API hr_status hr_material_validate(hr_context *ctx, const hr_material *m);
/* The name of solid texture `texture` ("checkerboard" for -1, "wood" for
 * -2, "marble" for -3), NULL if there is none: 0, an image texture (N > 0)
 * or past the last. They are numbered from -1 down without gaps, so a
 * program lists them by asking from -1 down to the first NULL. */
HR_API const char *hr_solid_texture_name(int32_t texture);

/* A point light in world coordinates; one colour for diffuse and specular. */
typedef struct hr_light {
    uint32_t struct_size;
    int32_t reserved;
    hr_vec3 position;
    hr_color color;
} hr_light;

/* Bounces are recursive calls: bound them so no scene can exhaust the stack. */
#define HR_MAX_RECURSION_DEPTH 1000

/* Tracing a composite (a CSG boolean) calls its children's hit functions,
 * which may be composites in turn: a chain of nested composites is as deep
 * a recursion. hr_scene_add_object refuses a composite nested deeper than
 * this (a leaf is depth 0, a boolean of leaves 1); nest long chains as
 * balanced trees, ((a | b) | (c | d)), which are log2(leaves) deep. */
#define HR_MAX_COMPOSITE_DEPTH 1000

/* A shape's hit may itself query a scene (hr_scene_first_hit, all_hits,
 * shade, hr_render): a shape written in Python can call back into the scene
 * being traced. Each such query nests inside the one that called the shape,
 * on the same thread (a render's threads carry the render's level): past this
 * many levels a query is refused with HR_ERROR_STATE, so a shape that
 * queries its own scene fails with an error instead of exhausting the stack
 * and memory. */
#define HR_MAX_QUERY_NESTING 16

/* The calling thread's nesting level (0 outside any query), and setting it:
 * for a binding that runs hr_render or a query on a thread of its own on
 * behalf of a caller, which gives that thread the caller's level so the
 * bound still holds. */
HR_API int32_t hr_query_nesting(void);
HR_API void hr_query_set_nesting(int32_t level);

/* Scene-wide settings, with SDL's defaults from hr_scene_globals_default
 * (HR_SCENE_GLOBALS_FIELDS in scene_fields.h). */
typedef struct hr_scene_globals {
    uint32_t struct_size;
    int32_t max_recursion_depth; /* default 3: primary rays are depth 0;
                                    at most HR_MAX_RECURSION_DEPTH */
    hr_color background;         /* default 0 0 0.6 */
    hr_color global_ambient;     /* default 0.1 0.1 0.1 */
    double min_reflectivity;     /* default 0.5: reflect only if >= this */
    double min_transparency;     /* default 0.5: refract only if >= this */
} hr_scene_globals;
HR_API void hr_scene_globals_default(hr_scene_globals *g);

/* One object to add: a shape class by name with its parameters, a material
 * and a transform. Everything is copied; the pointers need not outlive the
 * call. */
typedef struct hr_object_desc {
    uint32_t struct_size;
    int32_t param_count;
    const char *shape;           /* class name, e.g. "sphere" */
    const hr_param *params;      /* may be NULL when param_count is 0 */
    const hr_material *material; /* NULL: hr_material_default */
    const double *transform;     /* 16 doubles, row-major, object -> world;
                                    NULL: identity */
    const double *inverse;       /* its exact inverse if the caller has it
                                    (Hill's reader keeps one); NULL: computed */
    const char *base_dir;        /* for relative file parameters; NULL: "" */
} hr_object_desc;

HR_API hr_status hr_scene_create(hr_context *ctx, hr_scene **out);
HR_API void hr_scene_destroy(hr_scene *scene);
HR_API hr_context *hr_scene_context(const hr_scene *scene);

/* Add an object; `out_index` (may be NULL) receives its index, which is also
 * the `object` field of its hits. Objects used as HR_PARAM_OBJECT children
 * of a composite are consumed by it and not traced on their own. Fails with
 * HR_ERROR_MODULE (no module provides the class), HR_ERROR_PARAMETER (the
 * class refused a parameter, named in the message, or a composite would nest
 * deeper than HR_MAX_COMPOSITE_DEPTH), HR_ERROR_NUMERIC (a
 * singular transform) or HR_ERROR_STATE (the scene is committed). */
HR_API hr_status hr_scene_add_object(hr_scene *scene, const hr_object_desc *desc,
                                     int64_t *out_index);
HR_API hr_status hr_scene_add_light(hr_scene *scene, const hr_light *light);
HR_API hr_status hr_scene_set_globals(hr_scene *scene, const hr_scene_globals *g);
HR_API hr_status hr_scene_get_globals(const hr_scene *scene, hr_scene_globals *out);
HR_API hr_status hr_scene_commit(hr_scene *scene);
HR_API int32_t hr_scene_is_committed(const hr_scene *scene);

/* Hill's makePixmap: make `image` (RGB or RGBA, linear floats; alpha is
 * dropped) pixmap number `index` (>= 1) of the scene, for objects whose
 * material has texture `index`. The pixels are copied. Each number is made
 * once, before the objects that use it are added: hr_scene_add_object
 * refuses an image texture whose pixmap is not there. Fails with
 * HR_ERROR_INVALID_ARGUMENT (index < 1, made already, an image with a NaN
 * or infinite pixel or a component beyond +-1e6) or HR_ERROR_STATE. */
HR_API hr_status hr_scene_set_pixmap(hr_scene *scene, int32_t index, const hr_image *image);
/* Whether pixmap `index` is made (1) or not (0). */
HR_API int32_t hr_scene_has_pixmap(const hr_scene *scene, int32_t index);

/* The files a scene was built from: every file a reader or a shape read
 * while the scene was made (the SDL or NFF scene file, a makePixmap image,
 * a mesh's file), once each, in the order first read, each as the path it
 * was read at, made absolute with the working directory of then (".." and
 * symbolic links kept as they were). A scene's text may name other files,
 * in a comment or a macro never used: those were not read and are not
 * listed. hitray.distributed ships exactly these. A string stays valid
 * until the scene is destroyed; hr_scene_file is NULL for an index out of
 * range. */
HR_API int64_t hr_scene_file_count(const hr_scene *scene);
HR_API const char *hr_scene_file(const hr_scene *scene, int64_t index);
/* Lists `path` among the scene's files (once; a relative path is made
 * absolute first). The readers call it for the files they read and the
 * host for a shape's (hr_host.file_read); a program that builds a scene
 * from files of its own may call it too. Fails with HR_ERROR_INVALID_ARGUMENT
 * (NULL or empty path) or HR_ERROR_OUT_OF_MEMORY. */
HR_API hr_status hr_scene_note_file(hr_scene *scene, const char *path);

/* Introspection. */
HR_API int64_t hr_scene_object_count(const hr_scene *scene);
HR_API int32_t hr_scene_light_count(const hr_scene *scene);
typedef struct hr_object_info {
    uint32_t struct_size;
    int32_t top_level;      /* 0 if consumed by a composite */
    const char *shape;      /* class name */
    const char *module_path;
    hr_material material;   /* its `parameters` point into the scene */
    double transform[16];
    double inverse[16];
    hr_bounds world_bounds; /* infinities for unbounded objects */
    /* Appended within ABI 1 (a caller's struct_size without them gets
     * the fields before): the parameters the object was created with,
     * one per parameter its class declares, in the class's order, the
     * defaults filled in. Names and strings point into the scene; an
     * HR_PARAM_OBJECT's `object` is the index of the operand (whose
     * transform is relative to this object's); an HR_PARAM_NUMBERS keeps
     * its count but not the array (numbers is NULL). */
    const hr_param *params;
    int32_t param_count;
} hr_object_info;
HR_API hr_status hr_scene_object_info(const hr_scene *scene, int64_t index,
                                      hr_object_info *out);
HR_API hr_status hr_scene_light(const hr_scene *scene, int32_t index, hr_light *out);

/* World bounds of the bounded top-level objects; *found is 0 if none. */
HR_API hr_status hr_scene_bounds(const hr_scene *scene, hr_bounds *out, int32_t *found);

/* Effects a committed scene calls for (bit set of HR_EFFECT_*). */
#define HR_EFFECT_EMISSION 1u
#define HR_EFFECT_AMBIENT 2u
#define HR_EFFECT_DIFFUSE 4u
#define HR_EFFECT_SPECULAR 8u
#define HR_EFFECT_SHADOWS 16u
#define HR_EFFECT_REFLECTION 32u
#define HR_EFFECT_REFRACTION 64u
#define HR_EFFECT_SUPERSAMPLING 128u /* set in render statistics only */
#define HR_EFFECT_TEXTURE 256u       /* a solid or image texture was looked up */
#define HR_EFFECT_COUNT 9
HR_API uint32_t hr_scene_effects(const hr_scene *scene);
/* Name of one effect bit ("shadows", ...), NULL for an unknown bit. */
HR_API const char *hr_effect_name(uint32_t effect);

/* Hill's getFirstHit: the nearest hit of any object with tmin < t < tmax.
 * *found is 1 and *out filled (world space, unit normal) on a hit. The tie
 * rule: at an exact tie in t the object added first wins (the lower
 * `object`), then the lower `surface`: the first of hr_scene_all_hits's
 * list, whatever order the BVH meets objects in (an object's own hits at
 * one t count as the one its class's first_hit gives: a ray grazing a
 * cube's edge enters there, it does not leave first; for a class without
 * first_hit, the lower surface). Renders use the same rule, so
 * coincident objects show the first-added one on every CPU path. */
HR_API hr_status hr_scene_first_hit(const hr_scene *scene, const hr_ray *ray,
                                    double tmin, double tmax, hr_hit *out,
                                    int32_t *found);
/* hr_scene_first_hit for `count` rays at once: rays[i]'s nearest hit with
 * tmin < t < tmax in hits[i] and found[i] (1 on a hit; hits[i] is left as
 * it was on a miss). Every answer is bit for bit the one
 * hr_scene_first_hit gives for that ray, ties and rays starting inside an
 * object included; what is done once per query (the scene's checks, the
 * nesting level, the tracing context) is done once per batch, and rays
 * that run side by side may share their walk of the scene. Thread-safe as
 * the single query: any number of threads may each trace a batch of their
 * own. count 0 does nothing (rays, hits and found may then be NULL).
 * Every ray is checked before any is traced: HR_ERROR_INVALID_ARGUMENT
 * for count < 0, a NULL array, a window that is not tmin <= tmax, or a ray
 * that hr_scene_first_hit would refuse (the message names its index: "ray
 * 12: direction is the zero vector"), and then nothing is written. A shape
 * that fails stops the batch with its error, naming the ray; found[] is
 * then 0 for every ray. */
HR_API hr_status hr_scene_first_hits(const hr_scene *scene, const hr_ray *rays, int64_t count,
                                     double tmin, double tmax, hr_hit *hits, int32_t *found);
/* The occlusion batch: hit[i] is 1 when rays[i] meets some object with
 * tmin < t < tmax, 0 when none: the question a renderer's shadow ray asks
 * (direction the light minus the point, tmax 1), answered by the any-hit
 * walk, which stops at the first hit it meets. Arguments and errors as
 * hr_scene_first_hits. */
HR_API hr_status hr_scene_occluded(const hr_scene *scene, const hr_ray *rays, int64_t count,
                                   double tmin, double tmax, int32_t *hit);
/* The origin of a ray leaving the world-space hit `hit` (as
 * hr_scene_first_hit or hr_scene_all_hits return it) toward the side that
 * `side` points to: a unit normal, or its negation to pass into a solid.
 * The point is moved off the surface by the hit's own error bound (not a
 * fixed epsilon), so a ray spawned there does not hit the surface it left.
 * The renderer spawns its shadow, reflected and refracted rays with it. */
HR_API hr_vec3 hr_hit_spawn_origin(const hr_hit *hit, hr_vec3 side);
/* Hill's Intersection of the whole scene: every hit of every top-level object
 * with tmin < t < tmax, sorted by t. `out` is the caller's record: start it
 * zeroed (or from hr_intersection_init) and release it when done; its storage
 * grows as needed. */
HR_API hr_status hr_scene_all_hits(const hr_scene *scene, const hr_ray *ray,
                                   double tmin, double tmax, hr_intersection *out);
HR_API void hr_intersection_init(hr_intersection *list);
HR_API void hr_intersection_release(hr_intersection *list);

/* Hill's shade: the colour seen along `ray`, with reflections and
 * refractions down to the scene's maxRecursionDepth (or `max_depth` if
 * >= 0). The ray's direction need not be unit length. A lone ray stands for
 * no pixel, so it has no footprint: every texture is point-sampled at its
 * hits, as hr_render's HR_TEXTURE_FILTER_NONE does. */
HR_API hr_status hr_scene_shade(const hr_scene *scene, const hr_ray *ray,
                                int32_t max_depth, hr_color *out);

/* Frame the bounded objects: sets eye, look, up and view_angle of `cam`
 * (keeping its size) so every bounded object is in view, looking from the
 * +z side, a little from above and the right. Works on an uncommitted scene. */
HR_API hr_status hr_scene_frame_camera(const hr_scene *scene, hr_camera *cam);

#ifdef __cplusplus
}
#endif
#endif
