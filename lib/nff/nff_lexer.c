/* NFF words (lib/nff/nff_lexer.h). */
#include "nff/nff_lexer.h"

#include <string.h>

void nff_lexer_init(nff_lexer *lx, const char *text, size_t length)
{
    lx->text = text;
    lx->length = length;
    lx->pos = 0;
    lx->line = 1;
    lx->column = 1;
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

static void advance(nff_lexer *lx)
{
    if (lx->text[lx->pos] == '\n') {
        lx->line++;
        lx->column = 1;
    } else {
        lx->column++;
    }
    lx->pos++;
}

nff_word nff_next(nff_lexer *lx)
{
    for (;;) {
        while (lx->pos < lx->length && is_space(lx->text[lx->pos])) advance(lx);
        if (lx->pos < lx->length && lx->text[lx->pos] == '#') {
            while (lx->pos < lx->length && lx->text[lx->pos] != '\n') advance(lx);
            continue;
        }
        break;
    }
    nff_word w = {lx->text + lx->pos, 0, lx->line, lx->column, 0};
    while (lx->pos < lx->length && !is_space(lx->text[lx->pos])) {
        if (lx->text[lx->pos] == '\0') w.nul = 1;
        advance(lx);
        w.length++;
    }
    return w;
}

nff_word nff_peek(const nff_lexer *lx)
{
    nff_lexer copy = *lx;
    return nff_next(&copy);
}

size_t nff_remaining(const nff_lexer *lx)
{
    return lx->length - lx->pos;
}

int nff_word_is(nff_word w, const char *s)
{
    size_t n = strlen(s);
    return w.length == n && memcmp(w.text, s, n) == 0;
}
