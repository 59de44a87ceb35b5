/* Tokens, numbers and messages of the mesh readers (mesh_text.h). */
#include "mesh_text.h"

#include <langinfo.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mesh_text_init(mesh_text *t, const char *text, size_t length, const char *shown, char *error,
                    size_t error_size)
{
    t->p = text;
    t->end = text + length;
    /* A UTF-8 byte order mark, as some editors write, is not a token. */
    if (length >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) t->p += 3;
    t->line = 1;
    t->last_line = 1;
    t->shown = shown;
    t->error = error;
    t->error_size = error_size;
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

mesh_token mesh_text_next(mesh_text *t, int cross_lines, int comments)
{
    mesh_token tok = {NULL, 0, t->line};
    for (;;) {
        while (t->p < t->end && is_space(*t->p)) t->p++;
        if (t->p < t->end && comments && *t->p == '#')
            while (t->p < t->end && *t->p != '\n') t->p++;
        if (t->p < t->end && *t->p == '\n') {
            if (!cross_lines) {
                tok.line = t->line;
                return tok;
            }
            t->p++;
            t->line++;
            continue;
        }
        break;
    }
    tok.line = t->line;
    if (t->p >= t->end) {
        tok.line = t->last_line;
        return tok;
    }
    t->last_line = t->line;
    tok.start = t->p;
    while (t->p < t->end && !is_space(*t->p) && *t->p != '\n' && !(comments && *t->p == '#'))
        t->p++;
    tok.length = (size_t)(t->p - tok.start);
    return tok;
}

void mesh_text_skip_line(mesh_text *t)
{
    while (t->p < t->end && *t->p != '\n') t->p++;
}

size_t mesh_text_remaining(const mesh_text *t)
{
    return (size_t)(t->end - t->p);
}

int mesh_token_is(const mesh_token *tok, const char *word)
{
    size_t n = strlen(word);
    return tok->length == n && memcmp(tok->start, word, n) == 0;
}

hr_status mesh_text_error(mesh_text *t, const mesh_token *tok, const char *what, ...)
{
    char message[256];
    va_list ap;
    va_start(ap, what);
    vsnprintf(message, sizeof message, what, ap);
    va_end(ap);
    /* The token cut at MESH_QUOTED_BYTES, anything but printable ASCII (and
     * the quote and backslash) escaped as \xNN: the file named may be any
     * file (`mesh /etc/shadow`), and a message must not pass on more of it
     * than a mistyped number needs, nor bytes a terminal would act on. */
    char found[4 * MESH_QUOTED_BYTES + 8];
    if (tok && tok->length) {
        size_t n = tok->length < MESH_QUOTED_BYTES ? tok->length : MESH_QUOTED_BYTES, k = 0;
        found[k++] = '\'';
        for (size_t i = 0; i < n; i++) {
            unsigned char c = (unsigned char)tok->start[i];
            if (c >= 0x20 && c < 0x7f && c != '\'' && c != '\\') found[k++] = (char)c;
            else k += (size_t)snprintf(found + k, sizeof found - k, "\\x%02x", c);
        }
        if (tok->length > n) found[k++] = '.', found[k++] = '.', found[k++] = '.';
        found[k++] = '\'';
        found[k] = '\0';
    } else {
        snprintf(found, sizeof found, "%s",
                 t->p >= t->end ? "end of file" : "end of line");
    }
    long line = tok ? tok->line : t->line;
    if (t->error && t->error_size)
        snprintf(t->error, t->error_size, "%s:%ld: %s (found %s)", t->shown, line, message, found);
    return HR_ERROR_PARAMETER;
}

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* The decimal grammar: [+-] digits [. digits] [e [+-] digits], at least one
 * digit before the exponent. strtod alone would also take hex, inf and nan. */
static int is_decimal(const char *s, size_t n)
{
    size_t i = 0, digits = 0;
    if (i < n && (s[i] == '+' || s[i] == '-')) i++;
    while (i < n && is_digit(s[i])) i++, digits++;
    if (i < n && s[i] == '.') {
        i++;
        while (i < n && is_digit(s[i])) i++, digits++;
    }
    if (digits == 0) return 0;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-')) i++;
        if (!(i < n && is_digit(s[i]))) return 0;
        while (i < n && is_digit(s[i])) i++;
    }
    return i == n;
}

int mesh_parse_number(const mesh_token *tok, double *out)
{
    /* Longer numbers than this carry no more information for a double. */
    char buffer[512];
    if (tok->length == 0 || tok->length >= sizeof buffer - 8) return 0;
    if (!is_decimal(tok->start, tok->length)) return 0;
    /* strtod reads the decimal point of the calling thread's locale: write
     * that point in place of '.' (nl_langinfo reads the same locale, and
     * unlike localeconv shares no static buffer between threads). */
    const char *point = nl_langinfo(RADIXCHAR);
    size_t k = 0;
    for (size_t i = 0; i < tok->length; i++) {
        if (tok->start[i] == '.' && point && point[0] && strcmp(point, ".") != 0) {
            size_t np = strlen(point);
            if (np > 4) return 0;
            memcpy(buffer + k, point, np);
            k += np;
        } else {
            buffer[k++] = tok->start[i];
        }
    }
    buffer[k] = '\0';
    char *end = NULL;
    double value = strtod(buffer, &end);
    if (!end || *end != '\0') return 0;
    if (!isfinite(value) || fabs(value) > MESH_MAX_COORDINATE) return -1;
    *out = value;
    return 1;
}

int mesh_parse_whole(const mesh_token *tok, uint64_t max, uint64_t *out)
{
    if (tok->length == 0) return 0;
    uint64_t value = 0;
    for (size_t i = 0; i < tok->length; i++) {
        if (!is_digit(tok->start[i])) return 0;
        uint64_t digit = (uint64_t)(tok->start[i] - '0');
        if (value > (max - digit) / 10) return 0;
        value = value * 10 + digit;
    }
    *out = value;
    return 1;
}
