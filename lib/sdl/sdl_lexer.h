/* Internal: SDL text cut into tokens, each with its line and column.
 *
 * Words are separated by white space; `{` and `}` are tokens of their own even
 * when glued to a word; `!` starts a comment to the end of the line and also
 * ends the word it is glued to. Lines and columns are 1-based and count bytes
 * (a tab is one column, a UTF-8 character as many columns as it has bytes). */
#ifndef HITRAY_LIB_SDL_LEXER_H
#define HITRAY_LIB_SDL_LEXER_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/common.h>

#define SDL_TOKEN_WORD 0  /* a keyword, number, macro name or file name */
#define SDL_TOKEN_OPEN 1  /* { */
#define SDL_TOKEN_CLOSE 2 /* } */
#define SDL_TOKEN_END 3   /* the end of the text: always the last token */

typedef struct sdl_token {
    const char *text; /* NUL-terminated; "{", "}", or "" for the end */
    int32_t kind;     /* SDL_TOKEN_* */
    int32_t line;
    int32_t column;
} sdl_token;

typedef struct sdl_token_list {
    sdl_token *tokens; /* count + 1 entries: the last one is SDL_TOKEN_END */
    size_t count;      /* tokens before the end */
    size_t capacity;
    char *text_store;  /* the texts of all tokens, each NUL-terminated */
} sdl_token_list;

/* Cut `length` bytes of `text` into `out` (released by the caller, also on
 * error). Returns HR_OK, HR_ERROR_OUT_OF_MEMORY, or HR_ERROR_SDL for a NUL
 * byte outside a comment, whose place is then in *bad_line / *bad_column. */
hr_status sdl_lex(const char *text, size_t length, sdl_token_list *out, int32_t *bad_line,
                  int32_t *bad_column);
void sdl_token_list_release(sdl_token_list *list);

#endif
