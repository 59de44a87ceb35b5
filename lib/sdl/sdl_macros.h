/* Internal: SDL macros — `def name { ... }` stores the body as tokens,
 * `use name` pastes them where it stands (through lib/sdl/sdl_source.h). */
#ifndef HITRAY_LIB_SDL_MACROS_H
#define HITRAY_LIB_SDL_MACROS_H

#include <stddef.h>
#include <stdint.h>

#include "sdl/sdl_lexer.h"

/* A stored macro. Its body is a run of the file's own tokens (no copy): the
 * token list lives as long as the whole read, and a body never contains a
 * brace, so the tokens are the macro's text. */
typedef struct sdl_macro {
    const sdl_token *name; /* the name after `def`: its text and its place */
    const sdl_token *body; /* first token of the body */
    size_t body_count;
} sdl_macro;

/* Macros by name, in order of definition, with a hash index. */
typedef struct sdl_macro_table {
    sdl_macro *macros;
    int32_t count;
    int32_t capacity;
    int32_t *slots;    /* open addressing: macro index + 1, 0 = empty */
    size_t slot_count; /* a power of two, at least twice `count` */
} sdl_macro_table;

void sdl_macros_init(sdl_macro_table *table);
void sdl_macros_release(sdl_macro_table *table);
/* Index of the macro called `name`, or -1. */
int32_t sdl_macros_find(const sdl_macro_table *table, const char *name);
/* Add a macro whose name is not in the table yet. HR_OK or
 * HR_ERROR_OUT_OF_MEMORY. */
hr_status sdl_macros_add(sdl_macro_table *table, const sdl_macro *macro);

struct sdl_source;
struct sdl_located;
/* The commands. `keyword` is the `def` / `use` token just read. `def` reads
 * the name, `{`, the body and `}`; `use` reads the name and starts pasting
 * its body. Both report their errors on the source's context. */
hr_status sdl_macro_define(struct sdl_source *src, struct sdl_located keyword);
hr_status sdl_macro_use(struct sdl_source *src, struct sdl_located keyword);

#endif
