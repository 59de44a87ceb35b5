/* Internal: the NFF reader's state and the entities that change it.
 *
 * Like the SDL reader, a client of the public API only: each sphere and
 * cone becomes an object (hr_scene_add_object with the current material and
 * a transform), polygons gather into one triangleMesh object per material
 * (nff_polygons.c), lights are kept until the end of the file (their
 * colour without one depends on how many there are). nff_reader.c runs the
 * entity loop and reads numbers; nff_view.c reads the camera and settings;
 * nff_shapes.c makes spheres and cones. */
#ifndef HITRAY_LIB_NFF_READER_H
#define HITRAY_LIB_NFF_READER_H

#include <hitray/hitray.h>

#include "nff/nff_lexer.h"

/* The polygons of one material waiting to become one mesh: flat ones and,
 * apart, smooth ones (`pp`), whose vertices carry normals. Arrays of
 * doubles, in the layout the triangleMesh parameters take. */
typedef struct nff_mesh_batch {
    double *points, *normals, *triangles;
    size_t point_count, triangle_count; /* vertices and triangles, not doubles */
    size_t point_capacity, normal_capacity, triangle_capacity;
    int smooth;
    nff_word first; /* its first polygon, where a refusal of the mesh is reported */
} nff_mesh_batch;

typedef struct nff_light {
    hr_vec3 position;
    hr_color color;
    int has_color;
    nff_word at; /* the `l`, for a message */
} nff_light;

typedef struct nff_reader {
    hr_context *ctx;
    hr_scene *scene;
    const char *file; /* the name used in messages */
    nff_lexer lx;

    hr_material material;     /* from the last `f`; hr_material_default before one */
    nff_word material_at;     /* that `f` (line 0: none yet) */
    nff_mesh_batch flat, smooth;

    nff_light *lights;
    size_t light_count, light_capacity;

    hr_scene_globals globals;
    int has_camera;
    hr_camera camera;

    /* Steps the ear clipper has taken over the file's polygons (corners
     * tested and scanned), held to NFF_CLIP_WORK_BUDGET (nff_polygons.c). */
    uint64_t clip_work;
} nff_reader;

void nff_reader_init(nff_reader *r, hr_context *ctx, hr_scene *scene, const char *file,
                     const char *text, size_t length);
void nff_reader_release(nff_reader *r);
/* Read every entity, then add the lights and meshes and set the globals. */
hr_status nff_reader_run(nff_reader *r);

/* Raise `status` with "file:line:col: " and the message, at word `at`. */
hr_status nff_error(const nff_reader *r, hr_status status, nff_word at, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* A word for "found ...": 'word' (long words shortened), "end of file" or
 * a NUL byte. Writes into buf and returns it. */
const char *nff_describe(nff_word w, char *buf, size_t size);
/* `count` numbers after the entity `entity` ("expected 4 numbers after 's',
 * found 'x'"); `what` lists them for the message ("x y z radius"). `at`
 * (may be NULL) receives the word of each number. */
hr_status nff_read_numbers(nff_reader *r, nff_word entity, const char *what, int count,
                           double *out, nff_word *at);
/* A whole number within [min, max] after `entity`, for counts and sizes. */
hr_status nff_read_count(nff_reader *r, nff_word entity, const char *what, double min,
                         double max, int64_t *out);
/* Add an object of class `shape` with the current material. */
hr_status nff_add_object(nff_reader *r, nff_word at, const char *shape, const hr_param *params,
                         int32_t count, const double *transform);

/* The entities, by file. */
hr_status nff_read_view(nff_reader *r, nff_word v);
hr_status nff_read_background(nff_reader *r, nff_word b);
hr_status nff_read_light(nff_reader *r, nff_word l);
hr_status nff_read_fill(nff_reader *r, nff_word f);
hr_status nff_add_lights(nff_reader *r);

hr_status nff_read_sphere(nff_reader *r, nff_word s);
hr_status nff_read_cone(nff_reader *r, nff_word c);

hr_status nff_read_polygon(nff_reader *r, nff_word p, int smooth);
/* Turn the waiting polygons into mesh objects (at a new `f`, at the end). */
hr_status nff_flush_polygons(nff_reader *r);
void nff_batch_release(nff_mesh_batch *b);

#endif
