/* Error messages of the SDL reader (lib/sdl/sdl_diag.h). */
#include "sdl/sdl_diag.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "util/strutil.h"

/* Messages are kept in a fixed slot (a few KiB): a long chain of macro
 * levels shows its outer and inner ends and says how many it left out. */
#define SHOWN_OUTER_LEVELS 3
#define SHOWN_INNER_LEVELS 4
#define MESSAGE_SIZE 2048

typedef struct text {
    char data[MESSAGE_SIZE];
    size_t length;
} text;

static void append(text *t, const char *fmt, ...) HR_PRINTF(2, 3);
static void append(text *t, const char *fmt, ...)
{
    if (t->length + 1 >= sizeof t->data) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(t->data + t->length, sizeof t->data - t->length, fmt, ap);
    va_end(ap);
    if (n > 0) t->length += (size_t)n;
    if (t->length >= sizeof t->data) t->length = sizeof t->data - 1;
}

/* The message for `what` at `at`, with the macro levels that led there;
 * *origin is the token in the file's own text where it arose. */
static void place_message(const sdl_source *src, sdl_located at, const char *what, text *t,
                          const sdl_token **origin)
{
    /* The expansions that led to `at`, innermost first. */
    int32_t chain[SDL_MAX_MACRO_NESTING + 1];
    int32_t levels = 0;
    for (int32_t e = at.expansion; e >= 0 && levels < SDL_MAX_MACRO_NESTING + 1;
         e = src->expansions[e].parent)
        chain[levels++] = e;

    *origin = levels > 0 ? src->expansions[chain[levels - 1]].use : at.token;
    for (int32_t k = levels - 1; k >= 0; k--) {
        int32_t outer_rank = levels - 1 - k; /* 0 for the outermost */
        if (levels > SHOWN_OUTER_LEVELS + SHOWN_INNER_LEVELS && outer_rank == SHOWN_OUTER_LEVELS) {
            int32_t skipped = levels - SHOWN_OUTER_LEVELS - SHOWN_INNER_LEVELS;
            append(t, "... (%d more macro levels) ...: ", (int)skipped);
            k -= skipped - 1;
            continue;
        }
        const sdl_expansion *e = &src->expansions[chain[k]];
        const sdl_token *name = src->macros.macros[e->macro].name;
        append(t, "%s:%d:%d: in macro '%s' (defined at %s:%d:%d): ", src->file, (int)e->use->line,
               (int)e->use->column, name->text, src->file, (int)name->line, (int)name->column);
    }
    append(t, "%s:%d:%d: %s", src->file, (int)at.token->line, (int)at.token->column, what);
}

/* The caller's message, then the whole placed message, and its origin. */
static void format_at(const sdl_source *src, sdl_located at, const char *fmt, va_list ap, text *t,
                      const sdl_token **origin) HR_PRINTF(3, 0);
static void format_at(const sdl_source *src, sdl_located at, const char *fmt, va_list ap, text *t,
                      const sdl_token **origin)
{
    /* The caller's part first: its arguments may point into the context's
     * error slot (a message being passed on), which hri_error_at rewrites. */
    char what[MESSAGE_SIZE];
    vsnprintf(what, sizeof what, fmt, ap);
    place_message(src, at, what, t, origin);
}

hr_status sdl_error(const sdl_source *src, hr_status status, sdl_located at, const char *fmt, ...)
{
    text t = {{0}, 0};
    const sdl_token *origin;
    va_list ap;
    va_start(ap, fmt);
    format_at(src, at, fmt, ap, &t, &origin);
    va_end(ap);
    return hri_error_at(src->ctx, status, src->file, origin->line, origin->column, "%s", t.data);
}

void sdl_warning(const sdl_source *src, int32_t code, sdl_located at, const char *fmt, ...)
{
    text t = {{0}, 0};
    const sdl_token *origin;
    va_list ap;
    va_start(ap, fmt);
    format_at(src, at, fmt, ap, &t, &origin);
    va_end(ap);
    hri_warn(src->ctx, code, src->file, origin->line, origin->column, "%s", t.data);
}

const char *sdl_describe_run_on(const sdl_source *src, sdl_located keyword, sdl_located found,
                                char *buf, size_t size)
{
    buf[0] = '\0';
    if (keyword.expansion < 0 || keyword.expansion == found.expansion) return buf;
    const sdl_expansion *e = &src->expansions[keyword.expansion];
    const sdl_token *name = src->macros.macros[e->macro].name;
    snprintf(buf, size,
             " (the arguments of '%s' in macro '%s', defined at %s:%d:%d, run on past the end of "
             "its body)",
             keyword.token->text, name->text, src->file, (int)name->line, (int)name->column);
    return buf;
}

const char *sdl_describe(const sdl_token *token, char *buf, size_t size)
{
    enum { SHOWN_CHARS = 40 };
    if (token->kind == SDL_TOKEN_END) snprintf(buf, size, "end of file");
    else hri_quote_word(token->text, strlen(token->text), SHOWN_CHARS, buf, size);
    return buf;
}
