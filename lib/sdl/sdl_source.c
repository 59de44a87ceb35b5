/* The token stream with macro expansion (lib/sdl/sdl_source.h). */
#include "sdl/sdl_source.h"

#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"

hr_status sdl_source_init(sdl_source *src, hr_context *ctx, const char *file,
                          const sdl_token_list *tokens)
{
    memset(src, 0, sizeof *src);
    src->ctx = ctx;
    src->file = file;
    src->tokens = tokens;
    sdl_macros_init(&src->macros);
    src->frames = malloc(8 * sizeof *src->frames);
    if (!src->frames) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    src->frame_capacity = 8;
    src->frame_count = 1;
    src->frames[0].next = tokens->tokens;
    src->frames[0].end = tokens->tokens + tokens->count;
    src->frames[0].expansion = -1;
    return HR_OK;
}

void sdl_source_release(sdl_source *src)
{
    if (!src) return;
    sdl_macros_release(&src->macros);
    free(src->frames);
    free(src->expansions);
    memset(src, 0, sizeof *src);
}

hr_status sdl_source_next(sdl_source *src, sdl_located *out)
{
    /* Pop exhausted macro frames only now, when a token is wanted. */
    while (src->frame_count > 1 && src->frames[src->frame_count - 1].next ==
                                       src->frames[src->frame_count - 1].end)
        src->frame_count--;
    sdl_frame *top = &src->frames[src->frame_count - 1];
    if (top->next == top->end) {
        /* The file's end token sits just past its last token. */
        out->token = top->end;
        out->expansion = -1;
        return HR_OK;
    }
    out->token = top->next++;
    out->expansion = top->expansion;
    if (top->expansion >= 0 && ++src->expanded_tokens > SDL_MAX_EXPANDED_TOKENS)
        return sdl_error(src, HR_ERROR_SDL, *out,
                         "macro expansion passed %u tokens, so it stops here (macros that "
                         "each use another several times multiply the text without bound)",
                         SDL_MAX_EXPANDED_TOKENS);
    return HR_OK;
}

sdl_located sdl_source_peek(const sdl_source *src)
{
    int32_t f = src->frame_count - 1;
    while (f > 0 && src->frames[f].next == src->frames[f].end) f--;
    const sdl_frame *top = &src->frames[f];
    if (top->next == top->end) return (sdl_located){top->end, -1};
    return (sdl_located){top->next, top->expansion};
}

/* Capacity for at least `needed` items, doubling; 0 if it would overflow. */
static int32_t grown_capacity(int32_t capacity, int32_t needed)
{
    int32_t cap = capacity ? capacity : 16;
    while (cap < needed) {
        if (cap > INT32_MAX / 2) return 0;
        cap *= 2;
    }
    return cap;
}

static hr_status reserve_expansion_and_frame(sdl_source *src)
{
    if (src->expansion_count == INT32_MAX) return HR_ERROR_OUT_OF_MEMORY;
    if (src->expansion_count + 1 > src->expansion_capacity) {
        int32_t cap = grown_capacity(src->expansion_capacity, src->expansion_count + 1);
        sdl_expansion *grown = cap ? realloc(src->expansions, (size_t)cap * sizeof *grown) : NULL;
        if (!grown) return HR_ERROR_OUT_OF_MEMORY;
        src->expansions = grown;
        src->expansion_capacity = cap;
    }
    if (src->frame_count + 1 > src->frame_capacity) {
        int32_t cap = grown_capacity(src->frame_capacity, src->frame_count + 1);
        sdl_frame *grown = cap ? realloc(src->frames, (size_t)cap * sizeof *grown) : NULL;
        if (!grown) return HR_ERROR_OUT_OF_MEMORY;
        src->frames = grown;
        src->frame_capacity = cap;
    }
    return HR_OK;
}

hr_status sdl_source_expand(sdl_source *src, int32_t macro, sdl_located use, sdl_located name)
{
    const sdl_macro *m = &src->macros.macros[macro];
    /* The new expansion sits inside the one the name was read from (the
     * frame on top of the stack). Seeing the same macro in that chain means
     * the body reaches this `use` again every time: it can never end. */
    for (int32_t e = name.expansion; e >= 0; e = src->expansions[e].parent)
        if (src->expansions[e].macro == macro)
            return sdl_error(src, HR_ERROR_SDL, use,
                             "macro '%s' uses itself, so its expansion would never end",
                             m->name->text);
    if (src->frame_count - 1 >= SDL_MAX_MACRO_NESTING) /* the file's frame is not a macro */
        return sdl_error(src, HR_ERROR_SDL, use, "macros nested more than %d levels deep",
                         SDL_MAX_MACRO_NESTING);
    if (reserve_expansion_and_frame(src) != HR_OK)
        return hri_error(src->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory expanding macro '%s'",
                        m->name->text);
    sdl_expansion *e = &src->expansions[src->expansion_count];
    e->parent = name.expansion;
    e->macro = macro;
    e->use = use.token;
    sdl_frame *f = &src->frames[src->frame_count++];
    f->next = m->body;
    f->end = m->body + m->body_count;
    f->expansion = src->expansion_count++;
    return HR_OK;
}

int sdl_source_in_macro(sdl_located at) { return at.expansion >= 0; }
