/* SDL's object commands (lib/sdl/sdl_reader.h): a shape class's keyword,
 * then the parameters the class declares (hr_param_spec), in its order: a
 * number for a number, a word for a string, a whole object for an object
 * parameter. So Hill's `taperedCylinder s`, `mesh FILE` and `union A B`
 * (also intersection, difference) are read the same way as a module's class,
 * and the reader knows no shape's parameters; a class Hill writes alone but
 * which has optional parameters (`torus`, whose tube radius may follow)
 * says so with HR_SHAPE_SDL_BARE. `diamond`, the one solid of Hill's list
 * whose shape is not known, is refused.
 *
 * Each leaf object is added with hr_scene_add_object, passing a copy of the
 * current material and the top of the transform stack with its inverse (the
 * exact one Hill's stack keeps). When no module provides the class the
 * scene's message is passed on with the place of the keyword. An object
 * with operands reads each as a whole object (they nest), adds them, then
 * adds itself with the identity transform and the default material: each
 * leaf keeps its own. Operands are read with a stack of pending objects, not
 * by recursion, so no nesting depth can exhaust the C stack. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_reader.h"
#include "sdl/sdl_words.h"
#include "util/suggest.h"

/* Hill's object words. What follows each is its class's business: the
 * parameters it declares (read_params). `diamond` has no class (add_diamond). */
static const char *const objects[] = {
    "sphere", "cube", "square", "plane", "taperedCylinder", "cylinder", "cone",
    "torus", "mesh", "tetrahedron", "octahedron", "dodecahedron", "icosahedron",
    "union", "intersection", "difference", "buckyball", "teapot", "diamond",
    "taperedTube", /* the ECE661 reader's (the book's chapter-6 ray tracer) */
};
#define OBJECT_COUNT ((int)(sizeof objects / sizeof objects[0]))

const char *sdl_object_keyword(int index)
{
    return index >= 0 && index < OBJECT_COUNT ? objects[index] : NULL;
}

static int is_hill_object(const char *word)
{
    for (int i = 0; i < OBJECT_COUNT; i++)
        if (strcmp(word, objects[i]) == 0) return 1;
    return 0;
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
    for (int i = 0; i < OBJECT_COUNT; i++) hri_suggester_offer(near, objects[i]);
    int32_t n = hr_context_module_count(r->ctx);
    for (int32_t i = 0; i < n; i++) {
        hr_module_entry e;
        memset(&e, 0, sizeof e);
        e.struct_size = sizeof e;
        if (hr_context_module(r->ctx, i, &e) != HR_OK || !e.loaded) continue;
        for (int32_t k = 0; k < e.class_count; k++) hri_suggester_offer(near, e.classes[k]->name);
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
    if (is_hill_object(word)) return 1;
    /* Hill's commands keep their meaning whatever a module calls its class. */
    return !sdl_is_command_keyword(word) && module_class_exists(r->ctx, word);
}


/* An object whose parameters are still being read: the innermost one is on
 * top; one waiting for an operand has the operand's frame above it. */
typedef struct pending {
    sdl_located keyword;
    const hr_shape_class *cls; /* NULL: no module provides it */
    size_t base;               /* its first parameter in the parameter stack */
    int32_t count;             /* parameters read so far */
    int composite;             /* takes operands: added without material or transform */
} pending;

typedef struct object_stacks {
    pending *frames;
    size_t frame_count, frame_capacity;
    hr_param *params;
    size_t param_count, param_capacity;
} object_stacks;

static hr_status grow(sdl_reader *r, void **items, size_t *capacity, size_t needed, size_t size)
{
    if (needed <= *capacity) return HR_OK;
    size_t wanted = *capacity ? 2 * *capacity : 8;
    void *grown = realloc(*items, wanted * size);
    if (!grown) return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    *items = grown;
    *capacity = wanted;
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

static int takes_operands(const hr_shape_class *cls)
{
    for (int32_t i = 0; i < cls->param_count; i++)
        if (cls->params[i].type == HR_PARAM_OBJECT) return 1;
    return 0;
}

/* Start reading the object at `keyword`: a frame for it on the stack. */
static hr_status begin(sdl_reader *r, object_stacks *s, sdl_located keyword)
{
    /* Hill's readers made `diamond` a Mesh read from diamond.3vn, a file
     * that was never published with his code (the scenes that came with
     * it name it, and it is absent), so the diamond's shape is unknown. */
    if (strcmp(keyword.token->text, "diamond") == 0)
        return sdl_error(r->src, HR_ERROR_UNSUPPORTED, keyword,
                         "'diamond' is not supported: Hill's reader loaded it from the mesh file "
                         "diamond.3vn, which was never published, so its shape is unknown; "
                         "give a mesh of your own with 'mesh FILE'");
    hr_status st = grow(r, (void **)&s->frames, &s->frame_capacity, s->frame_count + 1,
                        sizeof *s->frames);
    if (st) return st;
    pending *p = &s->frames[s->frame_count++];
    memset(p, 0, sizeof *p);
    p->keyword = keyword;
    p->base = s->param_count;
    /* A class no module provides is left to the scene, whose message names it. */
    if (hr_context_find_shape_class(r->ctx, keyword.token->text, &p->cls, NULL) != HR_OK)
        p->cls = NULL;
    p->composite = p->cls && takes_operands(p->cls);
    if (!p->composite) return sdl_note_material_use(r);
    return HR_OK;
}

/* Operands are lettered in order, as Hill's `union A B`. */
static hr_status next_operand(sdl_reader *r, const pending *p, sdl_located *keyword)
{
    int letter = 0;
    for (int32_t i = 0; i < p->count; i++)
        if (p->cls->params[i].type == HR_PARAM_OBJECT) letter++;
    char wanted[160];
    snprintf(wanted, sizeof wanted, "an object for operand %c of '%s' at %s:%d:%d",
             'A' + letter % 26, p->keyword.token->text, r->src->file,
             (int)p->keyword.token->line, (int)p->keyword.token->column);
    return sdl_next_object_keyword(r, wanted, keyword);
}

/* Whether the next token is a number, which cannot start a command. */
static int number_follows(sdl_reader *r)
{
    double ignored;
    sdl_located next = sdl_source_peek(r->src);
    return next.token->kind == SDL_TOKEN_WORD &&
           sdl_parse_number(next.token->text, &ignored) != SDL_NUMBER_NOT_A_NUMBER;
}

/* Read the top frame's parameters in the order its class declares them: a
 * number for a number, a word for a string. At an object parameter the
 * operand's keyword goes to `operand` (*waits set) and reading stops until
 * the operand is added. A class declaring HR_SHAPE_SDL_BARE stops at the
 * first parameter that is not a number directly given. */
static hr_status read_params(sdl_reader *r, object_stacks *s, int *waits, sdl_located *operand)
{
    pending *p = &s->frames[s->frame_count - 1];
    *waits = 0;
    const int32_t declared = p->cls ? p->cls->param_count : 0;
    const int bare = p->cls && (p->cls->flags & HR_SHAPE_SDL_BARE);
    while (p->count < declared) {
        const hr_param_spec *spec = &p->cls->params[p->count];
        if (bare && !(spec->type == HR_PARAM_NUMBER && number_follows(r))) break;
        hr_status st = grow(r, (void **)&s->params, &s->param_capacity, s->param_count + 1,
                            sizeof *s->params);
        if (st) return st;
        hr_param *param = &s->params[s->param_count];
        memset(param, 0, sizeof *param);
        param->name = spec->name;
        param->type = spec->type;
        if (spec->type == HR_PARAM_OBJECT) {
            /* The slot is kept for the operand's index; its own
             * parameters go above it. */
            s->param_count++;
            if ((st = next_operand(r, p, operand))) return st;
            *waits = 1;
            return HR_OK;
        }
        if (spec->type == HR_PARAM_NUMBER) {
            if ((st = sdl_read_number(r, p->keyword, &param->number, NULL))) return st;
        } else if (spec->type == HR_PARAM_STRING) {
            sdl_located word;
            if ((st = sdl_source_next(r->src, &word))) return st;
            if (word.token->kind != SDL_TOKEN_WORD) {
                char found[64];
                return sdl_error(r->src, HR_ERROR_SDL, word, "expected a word for '%s' of '%s', found %s",
                                 spec->name, p->keyword.token->text,
                                 sdl_describe(word.token, found, sizeof found));
            }
            param->string = word.token->text;
        } else {
            return sdl_error(r->src, HR_ERROR_UNSUPPORTED, p->keyword,
                             "shape '%s' takes array parameters ('%s'), which SDL cannot give",
                             p->keyword.token->text, spec->name);
        }
        s->param_count++;
        p->count++;
    }
    return HR_OK;
}

/* Add the top frame's object and pop it. */
static hr_status finish(sdl_reader *r, object_stacks *s, int64_t *index)
{
    const pending *p = &s->frames[s->frame_count - 1];
    /* A scene of parameterless objects never allocates the parameter
     * stack, and NULL + 0 is undefined. */
    const hr_param *params = s->params ? s->params + p->base : NULL;
    hr_status st = add(r, p->keyword, params, p->count,
                       p->composite ? NULL : &r->material,
                       p->composite ? NULL : sdl_current_transform(r), index);
    s->param_count = p->base;
    s->frame_count--;
    return st;
}

hr_status sdl_read_object(sdl_reader *r, sdl_located keyword, int64_t *index)
{
    object_stacks s;
    memset(&s, 0, sizeof s);
    int64_t last = -1;
    hr_status st = begin(r, &s, keyword);
    while (st == HR_OK) {
        int waits;
        sdl_located operand;
        if ((st = read_params(r, &s, &waits, &operand))) break;
        if (waits) {
            st = begin(r, &s, operand);
            continue;
        }
        /* The object just added is the awaited operand of the frame below,
         * which then reads on. */
        if ((st = finish(r, &s, &last)) || s.frame_count == 0) break;
        pending *p = &s.frames[s.frame_count - 1];
        s.params[p->base + p->count].object = last;
        p->count++;
    }
    free(s.frames);
    free(s.params);
    if (st == HR_OK && index) *index = last;
    return st;
}
