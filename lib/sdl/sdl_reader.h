/* Internal: the SDL reader's state and the commands that change it.
 *
 * The reader is a client of the public API: it keeps Hill's state (a stack
 * of transform pairs, the current material, the globals, the camera) and
 * turns each object command into hr_scene_add_object with a copy of that
 * state. The commands live in files by topic: sdl_transforms.c,
 * sdl_material.c, sdl_settings.c (globals, lights, camera), sdl_objects.c
 * (shapes and CSG); sdl_reader.c runs the command loop. */
#ifndef HITRAY_LIB_SDL_READER_H
#define HITRAY_LIB_SDL_READER_H

#include <hitray/hitray.h>

#include "util/field_table.h"
#include "sdl/sdl_source.h"

/* Unbalanced `push` is harmless, but not without limit: each entry is two
 * 4x4 matrices, and a macro used in a loop can push on every pass. */
#define SDL_MAX_TRANSFORM_DEPTH 65536

/* A reflectivity or transparency command some object used
 * (sdl_thresholds.c). */
#define SDL_COEFFICIENT_KINDS 2 /* 0: reflectivity, 1: transparency */
typedef struct sdl_coefficient_use {
    int kind;
    sdl_located at; /* the command's keyword */
    double value;
} sdl_coefficient_use;

typedef struct sdl_reader {
    hr_context *ctx;
    hr_scene *scene;
    sdl_source *src;
    const char *base_dir; /* for relative file parameters (mesh); may be NULL */

    hr_transform *stack;  /* Hill's affine stack: [count - 1] is current */
    int32_t stack_count, stack_capacity;

    hr_material material; /* current material; `parameters` points to ... */
    double *parameters;   /* ... this array, owned by the reader */

    hr_scene_globals globals; /* given to the scene at the end of the read */
    int32_t has_camera;
    hr_camera camera;

    /* Where the current material's coefficients were set (token NULL: not
     * by a command), and the commands objects used (sdl_thresholds.c). */
    sdl_located coefficient_at[SDL_COEFFICIENT_KINDS];
    sdl_located last_noted[SDL_COEFFICIENT_KINDS];
    sdl_coefficient_use *coefficient_uses;
    size_t coefficient_use_count, coefficient_use_capacity;
} sdl_reader;

/* Set up / tear down everything but the scene, which the caller owns. */
hr_status sdl_reader_init(sdl_reader *r, hr_context *ctx, hr_scene *scene, sdl_source *src,
                          const char *base_dir);
void sdl_reader_release(sdl_reader *r);
/* Run every command of the source, then hand the globals to the scene. */
hr_status sdl_reader_run(sdl_reader *r);

/* A command: `keyword` is its token, just read; it reads its arguments. */
typedef hr_status (*sdl_command_fn)(sdl_reader *r, sdl_located keyword);

/* Arguments, each with a message naming the keyword when it is missing or
 * malformed ("expected a number after 'scale', found 'x'"). `at` (may be
 * NULL) receives the argument's token. */
hr_status sdl_read_number(sdl_reader *r, sdl_located keyword, double *out, sdl_located *at);
hr_status sdl_read_numbers(sdl_reader *r, sdl_located keyword, int count, double *out);
hr_status sdl_read_color(sdl_reader *r, sdl_located keyword, hr_color *out);
/* A number that must be whole and within [min, max]. */
hr_status sdl_read_whole(sdl_reader *r, sdl_located keyword, double min, double max,
                         int64_t *out);
/* The colour or number of the field that `keyword` names in `table`, stored
 * into `record` (a struct of the table's); `at` (may be NULL) receives the
 * number's token, or the keyword's for a colour. */
hr_status sdl_read_field(sdl_reader *r, sdl_located keyword, const hr_field_table *table,
                         void *record, sdl_located *at);

/* Coefficients below their thresholds (sdl_thresholds.c): note the place of
 * a reflectivity or transparency command, note that an object is made with
 * the current material, and at the end of the read warn for each command
 * used whose value the final thresholds hide. */
void sdl_note_coefficient(sdl_reader *r, sdl_located keyword);
hr_status sdl_note_material_use(sdl_reader *r);
void sdl_warn_thresholds(sdl_reader *r);

/* The top of the transform stack. */
hr_transform *sdl_current_transform(sdl_reader *r);

/* The object keywords, by index; NULL past the last. */
const char *sdl_object_keyword(int index);
/* 1 if `word` starts an object: one of Hill's (a shape, a boolean, or an
 * unsupported solid), or, if it is not a command, the name of a shape class
 * some module provides (a user's plugin); sdl_read_object then reads it. */
int sdl_is_object_keyword(sdl_reader *r, const char *word);
/* For an unknown keyword: offer every object keyword and every loaded
 * module's class name to `near`; and whether a module that would provide
 * `word` (its file is named after it: `disk.so` for `disk`) was found but
 * refused, writing why into `why`. */
struct hr_suggester;
void sdl_offer_object_keywords(sdl_reader *r, struct hr_suggester *near);
int sdl_refused_module(sdl_reader *r, const char *word, char *why, size_t size);
/* 1 if `word` is a state command (translate, light, def, ...). */
int sdl_is_command_keyword(const char *word);
/* Read the object that starts at `keyword` (for a boolean: both operands,
 * running any state commands between them), add it, and give its index. */
hr_status sdl_read_object(sdl_reader *r, sdl_located keyword, int64_t *index);
/* Read commands until one starts an object, run those before it, and give
 * that object's keyword. `wanted` says what for, in the message at the end
 * of the file ("operand A of 'union' at f:3:1"). */
hr_status sdl_next_object_keyword(sdl_reader *r, const char *wanted, sdl_located *keyword);

/* The commands, by file. */
hr_status sdl_cmd_translate(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_scale(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_rotate(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_push(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_pop(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_identity_affine(sdl_reader *r, sdl_located keyword);

hr_status sdl_cmd_material_color(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_material_number(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_texture(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_parameters(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_default_materials(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_make_pixmap(sdl_reader *r, sdl_located keyword); /* sdl_pixmap.c */
/* The material with SDL's defaults and no texture parameters. */
void sdl_material_reset(sdl_reader *r);

hr_status sdl_cmd_global_color(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_global_threshold(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_max_recursion_depth(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_light(sdl_reader *r, sdl_located keyword);
hr_status sdl_cmd_camera(sdl_reader *r, sdl_located keyword);

#endif
