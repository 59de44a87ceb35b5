/* hitray: the shape module ABI.
 *
 * Every shape (the built-in ones too) is a loadable module that exports one
 * function, `hr_shape_module` (HR_SHAPE_MODULE_ENTRY). The host calls it with
 * its ABI version and a table of host services; the module returns a
 * description of the shape classes it provides. A module needs no symbol of
 * libhitray: everything it may ask of the host is in `hr_host`.
 *
 * Compatibility: the host refuses a module whose `abi_version` differs from
 * HR_SHAPE_ABI_VERSION, naming the module's path. Within one ABI version,
 * structs only grow at the end; the host copies `struct_size` bytes of each
 * hr_shape_class and treats missing fields as zero, so an older module keeps
 * working.
 *
 * The contract of a shape class:
 * - reentrant: no globals written, any number of threads call `hit` at once;
 * - no allocation per call (the host owns hit storage, see hr_hit_args.out);
 * - no NaN or infinity in any hit field;
 * - hits strictly inside the open interval (tmin, tmax), sorted by t;
 * - which hits a shape finds does not depend on tmax, only which of them it
 *   keeps: the host may ask again with a window that ends just after a hit
 *   it has (the tie rule, hr_scene_first_hit); `first_hit` gives the first
 *   crossing `hit` would list (at one t on two surfaces, the one it lists
 *   first);
 * - for a closed solid (HR_SHAPE_CLOSED) entering flags alternate, starting
 *   with whatever the ray origin's side implies;
 * - `hit.error` bounds the distance of `hit.point` from the true surface point
 *   in object space (absolute, per coordinate). Avoiding self-intersection is
 *   the host's job: it offsets spawned rays by this bound, so shapes do not
 *   use a private epsilon for it. */
#ifndef HITRAY_SHAPE_MODULE_H
#define HITRAY_SHAPE_MODULE_H

#include "common.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HR_SHAPE_ABI_VERSION 1u
#define HR_SHAPE_MODULE_ENTRY hr_shape_module
#define HR_SHAPE_MODULE_ENTRY_NAME "hr_shape_module"

/* On entry to any hit function, `out->capacity - out->count` is at least this
 * many hits, so a shape with a bounded number of hits (a quadric: 2, a cube:
 * 2, a torus: 4) never needs host->reserve. */
#define HR_MIN_HIT_CAPACITY 8

/* Modes of hr_host.trace_child. */
#define HR_TRACE_ALL 0   /* every hit, sorted */
#define HR_TRACE_FIRST 1 /* the nearest hit only */
#define HR_TRACE_ANY 2   /* any hit (count 0 or 1; only t is meaningful) */

typedef struct hr_shape_class hr_shape_class;
typedef struct hr_create_args hr_create_args;

/* Host services. The host passes one table that lives as long as the module
 * is loaded. `call` is the host's per-thread context of the current hit call
 * (hr_hit_args.call): pass it back unchanged. */
typedef struct hr_host {
    uint32_t struct_size;
    uint32_t abi_version;
    /* Zero-filled allocation, for shape data made at create time. */
    void *(*alloc)(size_t size);
    void (*free)(void *ptr);
    /* Make `list` hold at least `capacity` hits (keeps its contents). */
    hr_status (*reserve)(void *call, hr_intersection *list, int32_t capacity);
    /* A per-thread scratch list (count 0), for composites that merge the
     * hits of children; release it before returning. NULL: out of memory. */
    hr_intersection *(*scratch_acquire)(void *call);
    void (*scratch_release)(void *call, hr_intersection *list);
    /* Trace a child object given to create as an HR_PARAM_OBJECT parameter.
     * The ray is in the composite's object space; the host moves it through
     * the child's own transform and returns the child's hits in the
     * composite's object space, each hit's `object` naming the leaf whose
     * surface it is. Appends the child's hits to `out`, sorted by t among
     * themselves in the order the child gave hits of equal t (a tangent's
     * entering hit stays before its exiting one); the hits `out` held before
     * are left where and as they were, so a composite can trace several
     * children into one list and tell their hits apart by position. */
    hr_status (*trace_child)(void *call, const void *child, const hr_ray *ray,
                             double tmin, double tmax, int32_t mode,
                             hr_intersection *out);
    /* Bounds of a child object in the composite's object space. */
    void (*child_bounds)(const void *child, hr_bounds *out);
    /* --- Added within ABI 1; present when struct_size covers it
     * (HR_HOST_HAS). A module built against an older header never reads it,
     * and a module that finds it missing must work without it. --- */
    /* The class of a child object (the host's copy: name, flags, ...), so a
     * composite can refuse a child that is no solid (no HR_SHAPE_CLOSED). */
    const hr_shape_class *(*child_class)(const void *child);
    /* Tells the host that create, called with `args` (pass the pointer
     * create was given), read the file at `path` (as opened: a relative
     * name joined to args->base_dir), so the scene can list the files it
     * was built from (hr_scene_file) and a scene shipped elsewhere carries
     * exactly these. Call it for every file a create reads, once the file
     * has been read; a create that fails needs not. HR_OK, or
     * HR_ERROR_OUT_OF_MEMORY (fail create with it). NULL in a host built
     * before it (HR_HOST_HAS), which then lists no shape's files. */
    hr_status (*file_read)(const hr_create_args *args, const char *path);
} hr_host;

/* Whether the host table `host` has `field` (it may come from an older
 * host, built before the field was added). */
#define HR_HOST_HAS(host, field)                                               \
    ((host)->struct_size >= offsetof(hr_host, field) + sizeof((host)->field))

/* Arguments of a shape's create. */
struct hr_create_args {
    uint32_t struct_size;
    int32_t param_count;
    /* The parameters given, each already checked by the host against the
     * class's hr_param_spec list (known name, right type, in range); a
     * parameter the caller omitted is present with its default value. */
    const hr_param *params;
    /* objects[i] is the child handle of params[i] when its type is
     * HR_PARAM_OBJECT (for hr_host.trace_child), NULL otherwise. */
    const void *const *objects;
    const hr_host *host;
    /* On refusal, write one line here naming the parameter and what is
     * wrong (the host adds the class and module path) and return
     * HR_ERROR_PARAMETER. */
    char *error;
    size_t error_size;
    /* Directory of the scene file being read, for relative file parameters
     * (mesh files); "" when not reading a file. */
    const char *base_dir;
};

/* Arguments of a hit call. Everything is in the shape's object space. */
typedef struct hr_hit_args {
    const void *shape; /* what create returned */
    hr_ray ray;
    double tmin, tmax; /* report hits with tmin < t < tmax */
    /* Append hits here (out->hits[out->count++]); at least
     * HR_MIN_HIT_CAPACITY free slots on entry, host->reserve for more. */
    hr_intersection *out;
    void *call; /* host context for hr_host services */
    /* --- Added within ABI 1. sizeof(hr_hit_args) of the host that filled
     * this in: a module reads a field added after it only when struct_size
     * covers it (HR_HIT_ARGS_HAS), since an older host passes less. --- */
    uint32_t struct_size;
} hr_hit_args;

/* Whether the hit arguments `args` have `field` (an older host, built
 * before the field was added, passes a smaller struct). */
#define HR_HIT_ARGS_HAS(args, field)                                           \
    ((args)->struct_size >= offsetof(hr_hit_args, field) + sizeof((args)->field))

typedef hr_status (*hr_hit_fn)(const hr_hit_args *args);

/* Describes one parameter of a shape class. */
typedef struct hr_param_spec {
    const char *name;
    int32_t type;        /* HR_PARAM_* */
    int32_t required;    /* 1: the caller must give it; 0: default applies */
    double default_number;
    double min, max;     /* range of a number (each element of an array),
                            checked by the host; inclusive unless flags
                            say otherwise; min > max: no range */
    const char *help;    /* one line: meaning, unit, what choices cost */
    /* --- Added within ABI 1: the host reads it only from a class whose
     * param_spec_size covers it (a class built against an older header
     * declares none and reads as flags 0). --- */
    int32_t flags;       /* HR_PARAM_* flags below */
} hr_param_spec;

/* Flags of a parameter (hr_param_spec.flags): the end of its range that is
 * excluded, so a range can say "> 0" (a radius) rather than ">= a tiny
 * number". */
#define HR_PARAM_MIN_EXCLUSIVE 1 /* the number must be > min */
#define HR_PARAM_MAX_EXCLUSIVE 2 /* the number must be < max */

/* Flags of a shape class. */
#define HR_SHAPE_CLOSED 1    /* a solid: entering/exiting alternate (CSG-able) */
#define HR_SHAPE_COMPOSITE 2 /* takes HR_PARAM_OBJECT children (CSG) */
/* SDL writes the class's keyword alone, as Hill's SDL does: its leading
 * optional number parameters are read only where numbers follow the keyword
 * (`torus` or `torus 0.1`), and the rest take their defaults. Without this
 * flag SDL reads every declared parameter after the keyword, in order. */
#define HR_SHAPE_SDL_BARE 4

/* The vtable of one shape class. */
struct hr_shape_class {
    uint32_t struct_size; /* sizeof(hr_shape_class) the module was built with */
    int32_t flags;        /* HR_SHAPE_* */
    const char *name;     /* as used by SDL and hr_object_desc.shape */
    const char *help;     /* one line */
    const hr_param_spec *params;
    int32_t param_count;
    int32_t surface_count; /* surfaces ids are 0 .. surface_count-1 (named
                              by surface_names); a composite passes on its
                              leaves' ids and declares 0 */
    hr_status (*create)(const hr_create_args *args, void **out_shape);
    void (*destroy)(void *shape);
    /* Object-space bounds; infinities for an unbounded shape. */
    void (*bounds)(const void *shape, hr_bounds *out);
    hr_hit_fn hit;       /* required: every hit in (tmin, tmax), sorted */
    hr_hit_fn first_hit; /* optional: at most the nearest hit */
    hr_hit_fn any_hit;   /* optional: count 0 or 1; for shadow rays */
    /* --- Added within ABI 1. The host copies struct_size bytes of a class
     * and zeroes the rest, so a class built against an older header reads
     * as not having these (HR_CLASS_HAS). --- */
    /* Optional: bounds of the shape under the affine map m (object to
     * parent space, row-major 4x4 as in hr_transform, last row 0 0 0 1),
     * for a class that can bound it tighter than the map of its object-space
     * box (a rotated cylinder: the box of its two end disks). The box must
     * hold the mapped shape including the rounding of its own computation.
     * The host keeps the tighter of it and the mapped box, per axis. NULL:
     * the host maps the corners of `bounds`. */
    void (*transformed_bounds)(const void *shape, const double m[16], hr_bounds *out);
    /* Optional: where on the surface a hit lies, (u, v), for image textures
     * (hr_material.texture > 0). `hit` is one of this shape's own hits in
     * object space: its point, its normal (any non-zero length) and its
     * surface id are set, as `hit` returned them up to rounding. Writes
     * uv[0] = u and uv[1] = v, finite, in the class's own units (the
     * material's texture parameters say which range the image covers, and it
     * tiles outside it). Returns 1. Called with `hit` and `uv` NULL, it says
     * whether this shape gives (u, v) at all (1) or not (0: a mesh whose file
     * has no texture coordinates); the host asks once, when an object with an
     * image texture is added, and refuses it on 0. Called only for textured
     * hits, never on an untextured scene; reentrant and allocation-free like
     * `hit`. NULL: the class gives no (u, v). */
    int32_t (*surface_uv)(const void *shape, const hr_hit *hit, double uv[2]);
    /* Optional: the name of each surface, surface_count entries (a cube's
     * "+x", "-x", ...; a tapered cylinder's "wall", "base", "cap"), so that
     * hr_hit.surface can be read without knowing the class. NULL: the
     * surfaces are known by number only. */
    const char *const *surface_names;
    /* The size of each entry of `params` (its stride), so hr_param_spec
     * can grow within ABI 1; the host copies each entry into its own
     * full-size spec, missing fields zero. 0 means the layout of the header
     * the class was built with: in a class whose struct_size covers this
     * field, the spec ending at `flags` (56 bytes); in an older class, the
     * first one, ending at `help` (48 bytes). So a class never sets it by
     * hand. As everywhere in ABI 1, the promise is that older modules keep
     * working on newer hosts, not the reverse. */
    uint32_t param_spec_size;
};

/* Whether a class declared with `struct_size` has `field`. The host's copy
 * of every class is full-size, missing fields zero, so on a class the host
 * hands out (hr_host.child_class) the field itself can be tested. */
#define HR_CLASS_HAS(cls, field)                                               \
    ((cls)->struct_size >= offsetof(hr_shape_class, field) + sizeof((cls)->field))

/* What a module's entry point returns. */
typedef struct hr_module_info {
    uint32_t struct_size;
    uint32_t abi_version; /* HR_SHAPE_ABI_VERSION the module was built for */
    const char *name;
    const char *description;
    const hr_shape_class *const *classes;
    int32_t class_count;
    /* --- Added within ABI 1; the host reads them only when struct_size
     * covers them (HR_MODULE_HAS), so a module built against an older
     * header is shown without them. Each may be NULL. --- */
    const char *version; /* the module's own version, e.g. "1.2.0" */
    const char *author;  /* who made it */
    const char *url;     /* where it comes from (home page, repository) */
} hr_module_info;

/* Whether the module info `info` has `field` (it may come from a module
 * built before the field was added). */
#define HR_MODULE_HAS(info, field)                                             \
    ((info)->struct_size >= offsetof(hr_module_info, field) + sizeof((info)->field))

typedef const hr_module_info *(*hr_shape_module_fn)(uint32_t host_abi_version,
                                                     const hr_host *host);

/* The entry point every module defines (declared here so a module's
 * definition has a prototype; the host finds it with dlsym). */
HR_EXPORT_ATTR const hr_module_info *HR_SHAPE_MODULE_ENTRY(uint32_t host_abi_version,
                                                           const hr_host *host);

/* A module defines its entry point with this macro, so the name and
 * signature cannot drift:
 *   HR_DEFINE_SHAPE_MODULE(host_version, host) { ...; return &info; } */
#define HR_DEFINE_SHAPE_MODULE(version_arg, host_arg)                          \
    HR_EXPORT_ATTR const hr_module_info *HR_SHAPE_MODULE_ENTRY(                \
        uint32_t version_arg, const hr_host *host_arg)

#ifdef __cplusplus
}
#endif
#endif
