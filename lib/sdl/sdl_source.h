/* Internal: the stream of SDL tokens the reader consumes — the file's tokens
 * with macro bodies pasted in where `use` stands.
 *
 * Pasting is done with a stack of frames (the file at the bottom, one frame
 * per macro being expanded) rather than by copying text, and every token read
 * comes with the chain of expansions it came from, so a message can name the
 * `use` lines and the definitions that led to it. A frame is popped only when
 * a read finds it empty, so a `use` that is the last token of a body still
 * sees its own macro below it: a macro that uses itself is caught at once. */
#ifndef HITRAY_LIB_SDL_SOURCE_H
#define HITRAY_LIB_SDL_SOURCE_H

#include <hitray/hitray.h>

#include "sdl/sdl_lexer.h"
#include "sdl/sdl_macros.h"

/* Bounds on expansion, so that no file can make the reader hang or exhaust
 * memory. Real scenes nest macros a few levels and expand a few thousand
 * tokens; these leave generous room above that. */
#define SDL_MAX_MACRO_NESTING 200         /* macro frames on the stack at once */
#define SDL_MAX_EXPANDED_TOKENS 1000000u  /* tokens read from macro bodies, in all */

/* A token and where it came from. */
typedef struct sdl_located {
    const sdl_token *token;
    int32_t expansion; /* -1: the file itself; else an index into expansions */
} sdl_located;

/* One expansion of a macro: which, started by which `use`, inside which
 * other expansion. Kept until the end of the read, so a located token stays
 * describable after its frame is gone. */
typedef struct sdl_expansion {
    int32_t parent; /* -1: the `use` is in the file itself */
    int32_t macro;  /* index in the macro table */
    const sdl_token *use; /* the `use` keyword */
} sdl_expansion;

typedef struct sdl_frame {
    const sdl_token *next, *end;
    int32_t expansion; /* -1 for the file's frame */
} sdl_frame;

typedef struct sdl_source {
    hr_context *ctx;
    const char *file; /* the name used in messages */
    const sdl_token_list *tokens;
    sdl_macro_table macros;
    sdl_frame *frames;
    int32_t frame_count, frame_capacity;
    sdl_expansion *expansions;
    int32_t expansion_count, expansion_capacity;
    size_t expanded_tokens; /* tokens read from macro bodies so far */
} sdl_source;

/* The source keeps pointers to `file` and `tokens`: they must outlive it. */
hr_status sdl_source_init(sdl_source *src, hr_context *ctx, const char *file,
                          const sdl_token_list *tokens);
void sdl_source_release(sdl_source *src);

/* The next token, from the innermost macro being expanded, else the file;
 * at the end, the file's end token (again on every later call). Fails only
 * when expansion passes SDL_MAX_EXPANDED_TOKENS. */
hr_status sdl_source_next(sdl_source *src, sdl_located *out);

/* The token sdl_source_next would give now, without taking it (and without
 * counting it against the expansion limit). For optional arguments. */
sdl_located sdl_source_peek(const sdl_source *src);

/* Start pasting the body of `macro`, named by `name` after the `use` keyword
 * `use`. Refuses a macro that is already being expanded (it would repeat
 * without end: bodies are fixed text with no conditions) and nesting deeper
 * than SDL_MAX_MACRO_NESTING. */
hr_status sdl_source_expand(sdl_source *src, int32_t macro, sdl_located use, sdl_located name);

/* 1 if `at` came from a macro body rather than from the file itself. */
int sdl_source_in_macro(sdl_located at);

#endif
