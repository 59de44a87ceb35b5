/* The SDL reader's command loop and argument reading (lib/sdl/sdl_reader.h). */
#include "sdl/sdl_reader.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_words.h"
#include "util/suggest.h"

static hr_status cmd_def(sdl_reader *r, sdl_located keyword)
{
    return sdl_macro_define(r->src, keyword);
}

static hr_status cmd_use(sdl_reader *r, sdl_located keyword)
{
    return sdl_macro_use(r->src, keyword);
}

/* The command of each material and global field (include/hitray/scene_fields.h)
 * by its member's type: texture is the one integer of a material, its
 * parameters the one list, maxRecursionDepth the one integer of the globals. */
#define MATERIAL_COMMAND(field, word, ...)                                     \
    {word, _Generic(((hr_material *)0)->field, hr_color: sdl_cmd_material_color, \
                    double: sdl_cmd_material_number, int32_t: sdl_cmd_texture,   \
                    const double *: sdl_cmd_parameters)},
#define GLOBALS_COMMAND(field, word, ...)                                      \
    {word, _Generic(((hr_scene_globals *)0)->field, hr_color: sdl_cmd_global_color, \
                    double: sdl_cmd_global_threshold,                            \
                    int32_t: sdl_cmd_max_recursion_depth)},

/* Every state command of SDL.md; objects are in sdl_objects.c. */
static const struct {
    const char *keyword;
    sdl_command_fn run;
} commands[] = {
    {"translate", sdl_cmd_translate},
    {"scale", sdl_cmd_scale},
    {"rotate", sdl_cmd_rotate},
    {"push", sdl_cmd_push},
    {"pop", sdl_cmd_pop},
    {"identityAffine", sdl_cmd_identity_affine},
    HR_MATERIAL_FIELDS(MATERIAL_COMMAND)
    {"defaultMaterials", sdl_cmd_default_materials},
    {"makePixmap", sdl_cmd_make_pixmap},
    HR_SCENE_GLOBALS_FIELDS(GLOBALS_COMMAND)
    {"light", sdl_cmd_light},
    {"camera", sdl_cmd_camera},
    {"def", cmd_def},
    {"use", cmd_use},
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

hr_status sdl_reader_init(sdl_reader *r, hr_context *ctx, hr_scene *scene, sdl_source *src,
                          const char *base_dir)
{
    memset(r, 0, sizeof *r);
    r->ctx = ctx;
    r->scene = scene;
    r->src = src;
    r->base_dir = base_dir;
    r->stack = malloc(16 * sizeof *r->stack);
    if (!r->stack) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    r->stack_capacity = 16;
    r->stack_count = 1;
    hr_transform_identity(&r->stack[0]);
    sdl_material_reset(r);
    hr_scene_globals_default(&r->globals);
    hr_camera_default(&r->camera);
    return HR_OK;
}

void sdl_reader_release(sdl_reader *r)
{
    if (!r) return;
    free(r->stack);
    free(r->parameters);
    free(r->coefficient_uses);
    memset(r, 0, sizeof *r);
}

hr_transform *sdl_current_transform(sdl_reader *r) { return &r->stack[r->stack_count - 1]; }

hr_status sdl_read_number(sdl_reader *r, sdl_located keyword, double *out, sdl_located *at)
{
    sdl_located t;
    hr_status st = sdl_source_next(r->src, &t);
    if (st) return st;
    if (at) *at = t;
    int parsed = t.token->kind == SDL_TOKEN_WORD ? sdl_parse_number(t.token->text, out)
                                                 : SDL_NUMBER_NOT_A_NUMBER;
    if (parsed == SDL_NUMBER_OK) return HR_OK;
    char found[64], run_on[256];
    sdl_describe(t.token, found, sizeof found);
    sdl_describe_run_on(r->src, keyword, t, run_on, sizeof run_on);
    if (parsed == SDL_NUMBER_TOO_LARGE)
        return sdl_error(r->src, HR_ERROR_SDL, t,
                         "number %s after '%s' is beyond the range of a double%s", found,
                         keyword.token->text, run_on);
    return sdl_error(r->src, HR_ERROR_SDL, t, "expected a number after '%s', found %s%s",
                     keyword.token->text, found, run_on);
}

hr_status sdl_read_numbers(sdl_reader *r, sdl_located keyword, int count, double *out)
{
    for (int i = 0; i < count; i++) {
        hr_status st = sdl_read_number(r, keyword, &out[i], NULL);
        if (st) return st;
    }
    return HR_OK;
}

hr_status sdl_read_color(sdl_reader *r, sdl_located keyword, hr_color *out)
{
    double v[3];
    hr_status st = sdl_read_numbers(r, keyword, 3, v);
    if (st) return st;
    out->r = v[0], out->g = v[1], out->b = v[2];
    return HR_OK;
}

hr_status sdl_read_whole(sdl_reader *r, sdl_located keyword, double min, double max,
                         int64_t *out)
{
    double v;
    sdl_located at;
    hr_status st = sdl_read_number(r, keyword, &v, &at);
    if (st) return st;
    /* SDL writes integers as numbers; only whole ones make sense. */
    if (v != floor(v))
        return sdl_error(r->src, HR_ERROR_SDL, at, "expected a whole number after '%s', found '%s'",
                         keyword.token->text, at.token->text);
    if (v < min || v > max)
        return sdl_error(r->src, HR_ERROR_SDL, at, "'%s' must be between %.0f and %.0f, found '%s'",
                         keyword.token->text, min, max, at.token->text);
    *out = (int64_t)v;
    return HR_OK;
}

hr_status sdl_read_field(sdl_reader *r, sdl_located keyword, const hr_field_table *table,
                         void *record, sdl_located *at)
{
    const hr_field *f = hri_field_find(table, keyword.token->text);
    hr_status st;
    if (f && f->kind == HR_FIELD_COLOR) {
        hr_color c;
        if ((st = sdl_read_color(r, keyword, &c))) return st;
        memcpy(hri_field_in(record, f), &c, sizeof c);
        if (at) *at = keyword;
        return HR_OK;
    }
    if (f && f->kind == HR_FIELD_NUMBER) {
        double v;
        if ((st = sdl_read_number(r, keyword, &v, at))) return st;
        memcpy(hri_field_in(record, f), &v, sizeof v);
        return HR_OK;
    }
    return hri_error(r->ctx, HR_ERROR_SDL, "internal: '%s' is not a colour or number field",
                    keyword.token->text);
}

static int equal_ignoring_case(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char ca = *a >= 'A' && *a <= 'Z' ? (char)(*a - 'A' + 'a') : *a;
        char cb = *b >= 'A' && *b <= 'Z' ? (char)(*b - 'A' + 'a') : *b;
        if (ca != cb) return 0;
    }
    return *a == *b;
}

/* A keyword spelled with other capitals, for the message. */
static const char *same_but_case(const char *word)
{
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        if (equal_ignoring_case(word, commands[i].keyword)) return commands[i].keyword;
    for (int i = 0; sdl_object_keyword(i); i++)
        if (equal_ignoring_case(word, sdl_object_keyword(i))) return sdl_object_keyword(i);
    return NULL;
}

static hr_status not_a_command(sdl_reader *r, sdl_located t)
{
    char found[64];
    sdl_describe(t.token, found, sizeof found);
    double number;
    /* A mesh file read as SDL fails on its first word ('v', or a count). */
    const char *file = r->src->file ? r->src->file : "";
    size_t file_len = strlen(file);
    const char *ext = file_len > 4 ? file + file_len - 4 : "";
    if (equal_ignoring_case(ext, ".obj") || equal_ignoring_case(ext, ".3vn"))
        return sdl_error(r->src, HR_ERROR_SDL, t,
                         "unexpected %s: '%s' is a mesh file, not SDL (an SDL scene reads it with "
                         "'mesh %s'; 'hitray render' renders it as the scene)", found, file, file);
    /* ... and by another name, its first word is an OBJ one. */
    static const char *const obj_words[] = {"v", "vn", "vt", "mtllib", "usemtl"};
    for (size_t i = 0; i < sizeof obj_words / sizeof obj_words[0]; i++)
        if (t.token->kind == SDL_TOKEN_WORD && strcmp(t.token->text, obj_words[i]) == 0)
            return sdl_error(r->src, HR_ERROR_SDL, t,
                             "unknown keyword %s: this reads like an OBJ mesh file, not SDL (an SDL "
                             "scene reads a mesh file with 'mesh FILE.obj'; 'hitray render FILE.obj' "
                             "renders it as the scene)", found);
    if (t.token->kind == SDL_TOKEN_OPEN)
        return sdl_error(r->src, HR_ERROR_SDL, t,
                         "unexpected '{': only 'def NAME {' opens a block");
    if (t.token->kind == SDL_TOKEN_CLOSE)
        return sdl_error(r->src, HR_ERROR_SDL, t, "unmatched '}': no 'def' is open");
    if (sdl_parse_number(t.token->text, &number) != SDL_NUMBER_NOT_A_NUMBER)
        return sdl_error(r->src, HR_ERROR_SDL, t,
                         "expected a keyword, found the number %s (one too many for the "
                         "command before it?)",
                         found);
    const char *spelled = same_but_case(t.token->text);
    if (spelled)
        return sdl_error(r->src, HR_ERROR_SDL, t,
                         "unknown keyword %s (keywords are case-sensitive: '%s')", found, spelled);
    /* The book's prose calls it the exponent; its SDL keyword is longer. */
    if (strcmp(t.token->text, "exponent") == 0)
        return sdl_error(r->src, HR_ERROR_SDL, t,
                         "unknown keyword %s (did you mean 'specularExponent'? the book's "
                         "'exponent' is Phong's specular exponent)", found);
    char refused[1024];
    if (sdl_refused_module(r, t.token->text, refused, sizeof refused))
        return sdl_error(r->src, HR_ERROR_MODULE, t,
                         "unknown keyword %s: a module for it was found but refused: %s", found,
                         refused);
    hr_suggester near;
    hri_suggester_init(&near, t.token->text);
    for (size_t i = 0; i < COMMAND_COUNT; i++) hri_suggester_offer(&near, commands[i].keyword);
    sdl_offer_object_keywords(r, &near);
    if (near.best)
        return sdl_error(r->src, HR_ERROR_SDL, t, "unknown keyword %s (did you mean '%s'?)", found,
                         near.best);
    /* No typo of a known word: perhaps a shape whose module is elsewhere.
     * The library's message says where modules were looked for. */
    const hr_shape_class *cls = NULL;
    char searched[1024];
    if (hr_context_find_shape_class(r->ctx, t.token->text, &cls, NULL) != HR_OK) {
        snprintf(searched, sizeof searched, "%s", hr_context_last_error(r->ctx));
        return sdl_error(r->src, HR_ERROR_SDL, t,
                         "unknown keyword %s: no SDL command, and %s (HITRAY_SHAPE_PATH, ':'-separated, "
                         "names more directories to search)", found, searched);
    }
    return sdl_error(r->src, HR_ERROR_SDL, t, "unknown keyword %s", found);
}

int sdl_is_command_keyword(const char *word)
{
    for (size_t i = 0; i < COMMAND_COUNT; i++)
        if (strcmp(word, commands[i].keyword) == 0) return 1;
    return 0;
}

/* Run one state command (anything but an object). */
static hr_status run_state_command(sdl_reader *r, sdl_located t)
{
    if (t.token->kind == SDL_TOKEN_WORD)
        for (size_t i = 0; i < COMMAND_COUNT; i++)
            if (strcmp(t.token->text, commands[i].keyword) == 0) return commands[i].run(r, t);
    return not_a_command(r, t);
}

hr_status sdl_next_object_keyword(sdl_reader *r, const char *wanted, sdl_located *keyword)
{
    for (;;) {
        sdl_located t;
        hr_status st = sdl_source_next(r->src, &t);
        if (st) return st;
        if (t.token->kind == SDL_TOKEN_END)
            return sdl_error(r->src, HR_ERROR_SDL, t, "expected %s, found end of file", wanted);
        if (t.token->kind == SDL_TOKEN_WORD && sdl_is_object_keyword(r, t.token->text)) {
            *keyword = t;
            return HR_OK;
        }
        if ((st = run_state_command(r, t))) return st;
    }
}

hr_status sdl_reader_run(sdl_reader *r)
{
    sdl_located t;
    for (;;) {
        hr_status st = sdl_source_next(r->src, &t);
        if (st) return st;
        if (t.token->kind == SDL_TOKEN_END) break;
        if (t.token->kind == SDL_TOKEN_WORD && sdl_is_object_keyword(r, t.token->text))
            st = sdl_read_object(r, t, NULL);
        else
            st = run_state_command(r, t);
        if (st) return st;
    }
    /* The globals were checked as they were read; a refusal here would be a
     * rule of the scene's that the reader does not know of. */
    hr_status st = hr_scene_set_globals(r->scene, &r->globals);
    if (st) return sdl_error(r->src, st, t, "%s", hr_context_last_error(r->ctx));
    sdl_warn_thresholds(r);
    return HR_OK;
}
