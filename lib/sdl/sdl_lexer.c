/* SDL tokens (lib/sdl/sdl_lexer.h). The lexer only cuts text; what a word means
 * (keyword, number, name) is decided by the reader, so that every message can
 * say what was expected where. */
#include "sdl/sdl_lexer.h"

#include <stdlib.h>
#include <string.h>

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* A word ends at white space, a brace, the start of a comment or a NUL. */
static int ends_word(char c)
{
    return c == '\n' || is_blank(c) || c == '{' || c == '}' || c == '!' || c == '\0';
}

static hr_status push_token(sdl_token_list *list, const char *text, int32_t kind, int32_t line,
                            int32_t column)
{
    if (list->count + 1 >= list->capacity) {
        size_t capacity = list->capacity ? 2 * list->capacity : 256;
        if (capacity > SIZE_MAX / sizeof(sdl_token)) return HR_ERROR_OUT_OF_MEMORY;
        sdl_token *grown = realloc(list->tokens, capacity * sizeof(sdl_token));
        if (!grown) return HR_ERROR_OUT_OF_MEMORY;
        list->tokens = grown;
        list->capacity = capacity;
    }
    sdl_token *t = &list->tokens[list->count++];
    t->text = text;
    t->kind = kind;
    t->line = line;
    t->column = column;
    return HR_OK;
}

hr_status sdl_lex(const char *text, size_t length, sdl_token_list *out, int32_t *bad_line,
                  int32_t *bad_column)
{
    memset(out, 0, sizeof *out);
    /* Each byte yields at most itself and a terminating NUL, so the store
     * never needs to grow and token texts can point into it. */
    if (length > (SIZE_MAX - 2) / 2) return HR_ERROR_OUT_OF_MEMORY;
    out->text_store = malloc(2 * length + 2);
    if (!out->text_store) return HR_ERROR_OUT_OF_MEMORY;
    char *store = out->text_store;
    size_t used = 0;

    int32_t line = 1, column = 1;
    size_t i = 0;
    /* A UTF-8 byte order mark written by some editors is not part of the text. */
    if (length >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) i = 3;
    hr_status st = HR_OK;
    while (i < length && st == HR_OK) {
        char c = text[i];
        if (c == '\n') {
            if (line < INT32_MAX) line++;
            column = 1, i++;
        } else if (is_blank(c)) {
            if (column < INT32_MAX) column++;
            i++;
        } else if (c == '!') {
            while (i < length && text[i] != '\n') i++; /* the newline ends the comment */
        } else if (c == '\0') {
            *bad_line = line, *bad_column = column;
            return HR_ERROR_SDL;
        } else if (c == '{' || c == '}') {
            char *t = store + used;
            t[0] = c, t[1] = '\0';
            used += 2;
            st = push_token(out, t, c == '{' ? SDL_TOKEN_OPEN : SDL_TOKEN_CLOSE, line, column);
            if (column < INT32_MAX) column++;
            i++;
        } else {
            char *t = store + used;
            int32_t start_column = column;
            size_t n = 0;
            while (i < length && !ends_word(text[i])) t[n++] = text[i++];
            t[n] = '\0';
            used += n + 1;
            /* Columns past INT32_MAX on one line only blur messages. */
            column = n > (size_t)(INT32_MAX - column) ? INT32_MAX : column + (int32_t)n;
            st = push_token(out, t, SDL_TOKEN_WORD, line, start_column);
        }
    }
    if (st == HR_OK) {
        /* The end token; push_token always leaves room for it. */
        st = push_token(out, store + used, SDL_TOKEN_END, line, column);
        store[used] = '\0';
        if (st == HR_OK) out->count--; /* `count` excludes the end token */
    }
    return st;
}

void sdl_token_list_release(sdl_token_list *list)
{
    if (!list) return;
    free(list->tokens);
    free(list->text_store);
    memset(list, 0, sizeof *list);
}
