/* hitray: basic types shared by the whole public ABI.
 *
 * Everything here is plain C11 with fixed-width integers and doubles, so the
 * layouts are the same for every compiler on a platform and cffi can parse it.
 * Structs a caller fills and that may grow start with `struct_size`: set it to
 * sizeof(the struct) you compiled against; the library reads only that many
 * bytes and treats the rest as zero/default, so old callers keep working. */
#ifndef HITRAY_COMMON_H
#define HITRAY_COMMON_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define HR_EXPORT_ATTR __declspec(dllexport)
#define HR_IMPORT_ATTR __declspec(dllimport)
#else
#define HR_EXPORT_ATTR __attribute__((visibility("default")))
#define HR_IMPORT_ATTR
#endif

/* HR_API marks every symbol libhitray exports. The library is built with
 * hidden visibility by default and HITRAY_BUILDING_LIBRARY defined. */
#ifdef HITRAY_BUILDING_LIBRARY
#define HR_API HR_EXPORT_ATTR
#else
#define HR_API HR_IMPORT_ATTR
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Library version (semantic). The ABI is that of SONAME libhitray.so.0. */
#define HR_VERSION_MAJOR 0
#define HR_VERSION_MINOR 1
#define HR_VERSION_PATCH 0

/* Status codes: every call that can fail returns one. The message of the last
 * error is kept per context and per thread (hr_context_last_error). */
typedef int32_t hr_status;
#define HR_OK 0
#define HR_ERROR_INVALID_ARGUMENT 1 /* a NULL pointer, a bad size, a bad option */
#define HR_ERROR_OUT_OF_MEMORY 2
#define HR_ERROR_IO 3             /* a file could not be read or written */
#define HR_ERROR_MODULE 4         /* a shape module is missing or refused */
#define HR_ERROR_PARAMETER 5      /* a shape refused its parameters */
#define HR_ERROR_SDL 6            /* a scene file has an error (file:line:col) */
#define HR_ERROR_STATE 7          /* e.g. editing a committed scene */
#define HR_ERROR_CANCELLED 8      /* the progress callback asked to stop */
#define HR_ERROR_UNSUPPORTED 9    /* a feature this build does not have */
#define HR_ERROR_NUMERIC 10       /* a degenerate transform, NaN input, ... */

/* Opaque handles, reached only through functions so they can grow. */
typedef struct hr_context hr_context; /* modules, errors (context.h) */
typedef struct hr_scene hr_scene;     /* objects, lights, globals (scene.h) */
typedef struct hr_image hr_image;     /* linear float pixels (image.h) */

/* A point or direction, double precision. */
typedef struct hr_vec3 {
    double x, y, z;
} hr_vec3;

/* A linear RGB colour; components are not clamped. */
typedef struct hr_color {
    double r, g, b;
} hr_color;

/* A ray: origin + t * dir. `dir` need not be unit length: Hill's rays keep
 * the same t in world and object space because the direction is carried
 * through the inverse transform without renormalising. */
typedef struct hr_ray {
    hr_vec3 origin;
    hr_vec3 dir;
} hr_ray;

/* An axis-aligned box. An unbounded shape (the plane) reports infinities. */
typedef struct hr_bounds {
    hr_vec3 lo, hi;
} hr_bounds;

/* Hill's HitInfo: one place where a ray meets a surface.
 * From the scene queries everything is in world space; from a shape module's
 * `hit` everything is in that shape's object space. */
typedef struct hr_hit {
    double t;          /* ray parameter of the hit */
    hr_vec3 point;     /* where the ray meets the surface: origin + t * dir
                          as the shape computes it, which may be from the
                          surface rather than the ray (a mesh's from the
                          triangle's weights, a square's with z exactly 0),
                          within `error` of the exact point either way */
    hr_vec3 normal;    /* outward normal; unit length in world space, any
                          non-zero length from a shape module */
    double error;      /* bound on the distance of `point` from the true surface
                          point (per coordinate, absolute); the host offsets
                          spawned rays by it instead of a fixed epsilon */
    int32_t surface;   /* which surface of the shape, 0 .. its class's
                          surface_count - 1, named by the class's
                          surface_names (shape_module.h) */
    int32_t entering;  /* 1: the ray enters the solid here; 0: it leaves */
    int64_t object;    /* index of the object in the scene (file order); a CSG
                          hit names the leaf whose surface it is. Shape modules
                          leave it alone: the host fills it. */
} hr_hit;

/* Hill's Intersection: every hit along a ray, sorted by t, with no fixed
 * limit. The storage belongs to whoever created the record (the host inside a
 * render; the caller for hr_scene_all_hits, released with
 * hr_intersection_release). */
typedef struct hr_intersection {
    hr_hit *hits;
    int32_t count;
    int32_t capacity;
} hr_intersection;

/* Parameter types of a shape (hr_param.type, hr_param_spec.type). */
#define HR_PARAM_NUMBER 1 /* uses hr_param.number */
#define HR_PARAM_STRING 2 /* uses hr_param.string (e.g. a mesh file) */
#define HR_PARAM_OBJECT 3 /* uses hr_param.object: another object of the
                             same scene, consumed by a composite (CSG) */
/* Added within ABI 1 (a host that predates it refuses a class declaring
 * one, as a malformed parameter, rather than misread it):
 * uses hr_param.numbers and hr_param.count, an array of `count` doubles,
 * for shapes made from data rather than a file (a triangle mesh's vertices
 * and corner indices). The host checks every element as it checks a number
 * (finite, within the spec's [min, max]) and hands the caller's pointer to
 * the shape's create: the array need only live through the call that makes
 * the object. Its default is the empty array (numbers NULL, count 0). */
#define HR_PARAM_NUMBERS 4

/* One named parameter given to a shape when an object is made. The unions
 * keep ABI 1's layout: `numbers` shares the place of `string`, `count` that
 * of `object`, and which one a parameter uses follows from its type. */
typedef struct hr_param {
    const char *name;
    int32_t type;         /* HR_PARAM_* */
    int32_t reserved;     /* set to 0 */
    double number;
    union {
        const char *string;
        const double *numbers; /* HR_PARAM_NUMBERS */
    };
    union {
        int64_t object;   /* object index as returned by hr_scene_add_object */
        int64_t count;    /* HR_PARAM_NUMBERS: elements of `numbers` */
    };
} hr_param;

#ifdef __cplusplus
}
#endif
#endif
