/* SDL's object commands (lib/sdl_reader.h): shapes, CSG booleans, and
 * `diamond`, the one solid of Hill's list whose shape is not known.
 *
 * Each leaf object is added with hr_scene_add_object, passing a copy of the
 * current material and the top of the transform stack with its inverse (the
 * exact one Hill's stack keeps). A shape class is named by its SDL keyword;
 * when no module provides it the scene's message is passed on with the place
 * of the keyword. A boolean `union A B` (also intersection, difference)
 * reads A then B, each a whole object (booleans nest), adds them, then adds
 * the boolean node with object parameters `a` and `b`, the identity
 * transform and the default material: each leaf keeps its own. Booleans are
 * read with a stack of pending nodes, not by recursion, so no nesting depth
 * can exhaust the C stack. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "sdl_diag.h"
#include "sdl_reader.h"
#include "sdl_words.h"
#include "suggest.h"

#define ARGS_NONE 0        /* sphere, cube, ... */
#define ARGS_TAPER 1       /* taperedCylinder s */
#define ARGS_FILE 2        /* mesh file */
#define ARGS_OPERANDS 3    /* union A B */
#define ARGS_DIAMOND 4     /* refused: see add_leaf */
#define ARGS_MODULE 5      /* a module's class beyond Hill's list: its parameters */
#define ARGS_TUBE 6        /* torus [tube]: an optional tube radius */
#define SDL_MAX_MODULE_PARAMS 64

static const struct {
    const char *keyword;
    int args;
} objects[] = {
    {"sphere", ARGS_NONE},
    {"cube", ARGS_NONE},
    {"square", ARGS_NONE},
    {"plane", ARGS_NONE},
    {"taperedCylinder", ARGS_TAPER},
    {"cylinder", ARGS_NONE},
    {"cone", ARGS_NONE},
    {"torus", ARGS_TUBE},
    {"mesh", ARGS_FILE},
    {"tetrahedron", ARGS_NONE},
    {"octahedron", ARGS_NONE},
    {"dodecahedron", ARGS_NONE},
    {"icosahedron", ARGS_NONE},
    {"union", ARGS_OPERANDS},
    {"intersection", ARGS_OPERANDS},
    {"difference", ARGS_OPERANDS},
    {"buckyball", ARGS_NONE},
    {"teapot", ARGS_NONE},
    {"diamond", ARGS_DIAMOND},
};
#define OBJECT_COUNT ((int)(sizeof objects / sizeof objects[0]))

const char *sdl_object_keyword(int index)
{
    return index >= 0 && index < OBJECT_COUNT ? objects[index].keyword : NULL;
}

static int object_args(const char *word)
{
    for (int i = 0; i < OBJECT_COUNT; i++)
        if (strcmp(word, objects[i].keyword) == 0) return objects[i].args;
    return -1;
}

/* Whether a module provides a class called `word`, asked of the module
 * listing so that a miss raises no error (the word may be a typo the reader
 * reports as an unknown keyword). */
static int module_class_exists(hr_context *ctx, const char *word)
{
    int32_t n = hr_context_module_count(ctx);
    for (int32_t i = 0; i < n; i++) {
        hr_module_entry e;
        memset(&e, 0, sizeof e);
        e.struct_size = sizeof e;
        if (hr_context_module(ctx, i, &e) != HR_OK || !e.loaded) continue;
        for (int32_t k = 0; k < e.class_count; k++)
            if (strcmp(e.classes[k]->name, word) == 0) return 1;
    }
    return 0;
}

void sdl_offer_object_keywords(sdl_reader *r, hr_suggester *near)
{
    for (int i = 0; i < OBJECT_COUNT; i++) hr_suggester_offer(near, objects[i].keyword);
    int32_t n = hr_context_module_count(r->ctx);
    for (int32_t i = 0; i < n; i++) {
        hr_module_entry e;
        memset(&e, 0, sizeof e);
        e.struct_size = sizeof e;
        if (hr_context_module(r->ctx, i, &e) != HR_OK || !e.loaded) continue;
        for (int32_t k = 0; k < e.class_count; k++) hr_suggester_offer(near, e.classes[k]->name);
    }
}

int sdl_refused_module(sdl_reader *r, const char *word, char *why, size_t size)
{
    const size_t length = strlen(word);
    int32_t n = hr_context_module_count(r->ctx);
    for (int32_t i = 0; i < n; i++) {
        hr_module_entry e;
        memset(&e, 0, sizeof e);
        e.struct_size = sizeof e;
        if (hr_context_module(r->ctx, i, &e) != HR_OK || e.loaded) continue;
        const char *slash = strrchr(e.path, '/');
        const char *base = slash ? slash + 1 : e.path;
        /* "disk.so", or "libdisk.so" as CMake names a module by default. */
        if (strncmp(base, "lib", 3) == 0 && strncmp(base + 3, word, length) == 0 && base[3 + length] == '.')
            base += 3;
        if (strncmp(base, word, length) == 0 && base[length] == '.') {
            snprintf(why, size, "%s", e.error);
            return 1;
        }
    }
    return 0;
}

int sdl_is_object_keyword(sdl_reader *r, const char *word)
{
    if (object_args(word) >= 0) return 1;
    /* Hill's commands keep their meaning whatever a module calls its class. */
    return !sdl_is_command_keyword(word) && module_class_exists(r->ctx, word);
}

/* A class from a module beyond Hill's list, in the form of Hill's own
 * `taperedCylinder s` and `mesh FILE`: its name, then one argument per
 * parameter in the order the class declares them (`hitray shapes` lists
 * them): a number for a number, a word for a string. Object parameters
 * (composites) have no SDL form here. */
static hr_status read_module_params(sdl_reader *r, sdl_located keyword, hr_param *params,
                                    int32_t *count)
{
    const hr_shape_class *cls;
    if (hr_context_find_shape_class(r->ctx, keyword.token->text, &cls, NULL) != HR_OK)
        return sdl_error(r->src, HR_ERROR_MODULE, keyword, "%s", hr_context_last_error(r->ctx));
    if (cls->param_count > SDL_MAX_MODULE_PARAMS)
        return sdl_error(r->src, HR_ERROR_UNSUPPORTED, keyword,
                         "shape '%s' has %d parameters; SDL reads at most %d",
                         keyword.token->text, (int)cls->param_count, SDL_MAX_MODULE_PARAMS);
    for (int32_t i = 0; i < cls->param_count; i++) {
        const hr_param_spec *spec = &cls->params[i];
        hr_param *p = &params[i];
        memset(p, 0, sizeof *p);
        p->name = spec->name;
        p->type = spec->type;
        if (spec->type == HR_PARAM_NUMBER) {
            hr_status st = sdl_read_number(r, keyword, &p->number, NULL);
            if (st) return st;
        } else if (spec->type == HR_PARAM_STRING) {
            sdl_located word;
            hr_status st = sdl_source_next(r->src, &word);
            if (st) return st;
            if (word.token->kind != SDL_TOKEN_WORD) {
                char found[64];
                return sdl_error(r->src, HR_ERROR_SDL, word, "expected a word for '%s' of '%s', found %s",
                                 spec->name, keyword.token->text,
                                 sdl_describe(word.token, found, sizeof found));
            }
            p->string = word.token->text;
        } else {
            return sdl_error(r->src, HR_ERROR_UNSUPPORTED, keyword,
                             "shape '%s' takes %s parameters ('%s'), which SDL cannot give",
                             keyword.token->text,
                             spec->type == HR_PARAM_NUMBERS ? "array" : "object", spec->name);
        }
    }
    *count = cls->param_count;
    return HR_OK;
}

/* Add one object; any refusal is reported at its keyword. */
static hr_status add(sdl_reader *r, sdl_located keyword, const hr_param *params, int32_t count,
                     const hr_material *material, const hr_transform *transform, int64_t *index)
{
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = keyword.token->text;
    d.param_count = count;
    d.params = count ? params : NULL;
    d.material = material;
    d.transform = transform ? transform->m : NULL;
    d.inverse = transform ? transform->inv : NULL;
    d.base_dir = r->base_dir;
    hr_status st = hr_scene_add_object(r->scene, &d, index);
    if (st) return sdl_error(r->src, st, keyword, "%s", hr_context_last_error(r->ctx));
    return HR_OK;
}

static hr_status add_leaf(sdl_reader *r, sdl_located keyword, int args, int64_t *index)
{
    hr_status noted = sdl_note_material_use(r);
    if (noted) return noted;
    hr_param param;
    memset(&param, 0, sizeof param);
    int32_t count = 0;
    if (args == ARGS_MODULE) {
        hr_param params[SDL_MAX_MODULE_PARAMS];
        hr_status st = read_module_params(r, keyword, params, &count);
        if (st) return st;
        return add(r, keyword, params, count, &r->material, sdl_current_transform(r), index);
    }
    /* Hill's readers made `diamond` a Mesh read from diamond.3vn, a file
     * that was never published with his code (the scenes that came with
     * it name it, and it is absent), so the diamond's shape is unknown. */
    if (args == ARGS_DIAMOND)
        return sdl_error(r->src, HR_ERROR_UNSUPPORTED, keyword,
                         "'diamond' is not supported: Hill's reader loaded it from the mesh file "
                         "diamond.3vn, which was never published, so its shape is unknown; "
                         "give a mesh of your own with 'mesh FILE'");
    if (args == ARGS_TAPER) {
        hr_status st = sdl_read_number(r, keyword, &param.number, NULL);
        if (st) return st;
        param.name = "s";
        param.type = HR_PARAM_NUMBER;
        count = 1;
    } else if (args == ARGS_TUBE) {
        /* Optional: a number cannot start the next command, so one here is
         * the tube radius; without it the class's default (0.2). */
        double ignored;
        sdl_located next = sdl_source_peek(r->src);
        if (next.token->kind == SDL_TOKEN_WORD &&
            sdl_parse_number(next.token->text, &ignored) != SDL_NUMBER_NOT_A_NUMBER) {
            hr_status st = sdl_read_number(r, keyword, &param.number, NULL);
            if (st) return st;
            param.name = "tube";
            param.type = HR_PARAM_NUMBER;
            count = 1;
        }
    } else if (args == ARGS_FILE) {
        sdl_located file;
        hr_status st = sdl_source_next(r->src, &file);
        if (st) return st;
        if (file.token->kind != SDL_TOKEN_WORD) {
            char found[64];
            return sdl_error(r->src, HR_ERROR_SDL, file, "expected a file name after '%s', found %s",
                             keyword.token->text, sdl_describe(file.token, found, sizeof found));
        }
        param.name = "file";
        param.type = HR_PARAM_STRING;
        param.string = file.token->text;
        count = 1;
    }
    return add(r, keyword, &param, count, &r->material, sdl_current_transform(r), index);
}

/* A boolean whose operands are still being read. */
typedef struct pending {
    sdl_located keyword;
    int64_t a; /* index of operand A, -1 until it is read */
} pending;

static hr_status next_operand(sdl_reader *r, const pending *p, sdl_located *keyword)
{
    char wanted[160];
    snprintf(wanted, sizeof wanted, "an object for operand %s of '%s' at %s:%d:%d",
             p->a < 0 ? "A" : "B", p->keyword.token->text, r->src->file,
             (int)p->keyword.token->line, (int)p->keyword.token->column);
    return sdl_next_object_keyword(r, wanted, keyword);
}

static hr_status add_boolean(sdl_reader *r, const pending *p, int64_t b, int64_t *index)
{
    hr_param params[2];
    memset(params, 0, sizeof params);
    params[0].name = "a";
    params[0].type = HR_PARAM_OBJECT;
    params[0].object = p->a;
    params[1].name = "b";
    params[1].type = HR_PARAM_OBJECT;
    params[1].object = b;
    return add(r, p->keyword, params, 2, NULL, NULL, index);
}

hr_status sdl_read_object(sdl_reader *r, sdl_located keyword, int64_t *index)
{
    pending *stack = NULL;
    size_t count = 0, capacity = 0;
    hr_status st = HR_OK;
    int64_t last = -1;
    for (;;) {
        int args = object_args(keyword.token->text);
        if (args < 0) args = ARGS_MODULE; /* the caller found a module's class */
        if (args == ARGS_OPERANDS) {
            if (count == capacity) {
                capacity = capacity ? 2 * capacity : 8;
                pending *grown = realloc(stack, capacity * sizeof *grown);
                if (!grown) {
                    st = hr_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
                    break;
                }
                stack = grown;
            }
            stack[count].keyword = keyword;
            stack[count].a = -1;
            count++;
            if ((st = next_operand(r, &stack[count - 1], &keyword))) break;
            continue;
        }
        if ((st = add_leaf(r, keyword, args, &last))) break;
        /* The object just added completes operand A or B of the innermost
         * pending boolean; a completed boolean is in turn an operand. */
        while (count > 0 && stack[count - 1].a >= 0) {
            if ((st = add_boolean(r, &stack[count - 1], last, &last))) break;
            count--;
        }
        if (st || count == 0) break;
        stack[count - 1].a = last;
        if ((st = next_operand(r, &stack[count - 1], &keyword))) break;
    }
    free(stack);
    if (st == HR_OK && index) *index = last;
    return st;
}
