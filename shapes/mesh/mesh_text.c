/* Tokens, numbers and messages of the mesh readers (mesh_text.h). */
#include "mesh_text.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "mesh_number.h"

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

/* What a byte is to the tokenizer, looked up rather than compared five
 * ways a byte (most of a mesh file is token bytes). */
enum { BYTE_SPACE = 1, BYTE_NEWLINE = 2, BYTE_HASH = 4 };
static const unsigned char byte_class[256] = {
    [' '] = BYTE_SPACE, ['\t'] = BYTE_SPACE, ['\r'] = BYTE_SPACE, ['\f'] = BYTE_SPACE,
    ['\v'] = BYTE_SPACE, ['\n'] = BYTE_NEWLINE, ['#'] = BYTE_HASH,
};

static int is_space(char c)
{
    return byte_class[(unsigned char)c] == BYTE_SPACE;
}

mesh_token mesh_text_next(mesh_text *t, int cross_lines, int comments)
{
    /* The position in a local: the class table is bytes, which the
     * compiler must otherwise assume may alias t->p. */
    const char *p = t->p, *const end = t->end;
    mesh_token tok = {NULL, 0, t->line};
    for (;;) {
        while (p < end && is_space(*p)) p++;
        if (p < end && comments && *p == '#')
            while (p < end && *p != '\n') p++;
        if (p < end && *p == '\n') {
            if (!cross_lines) {
                t->p = p;
                tok.line = t->line;
                return tok;
            }
            p++;
            t->line++;
            continue;
        }
        break;
    }
    t->p = p;
    tok.line = t->line;
    if (p >= end) {
        tok.line = t->last_line;
        return tok;
    }
    t->last_line = t->line;
    tok.start = p;
    const unsigned char stop = BYTE_SPACE | BYTE_NEWLINE | (comments ? BYTE_HASH : 0);
    while (p < end && !(byte_class[(unsigned char)*p] & stop)) p++;
    t->p = p;
    tok.length = (size_t)(p - tok.start);
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
 * digit before the exponent. The converter alone would also take inf and nan
 * (and strtod hex). */
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
    /* Tokens this long are refused before any conversion: no coordinate
     * needs 500 characters, and the limit is the one the readers have
     * always applied. */
    if (tok->length == 0 || tok->length >= 504) return 0;
    if (!is_decimal(tok->start, tok->length)) return 0;
    double value;
    if (!mesh_decimal_to_double(tok->start, tok->length, &value)) return 0;
    if (!isfinite(value) || fabs(value) > MESH_MAX_COORDINATE) return -1;
    *out = value;
    return 1;
}

int mesh_parse_whole(const mesh_token *tok, uint64_t max, uint64_t *out)
{
    if (tok->length == 0) return 0;
    /* value * 10 + digit <= max, without a division a digit. */
    const uint64_t max_tenth = max / 10, max_last = max % 10;
    uint64_t value = 0;
    for (size_t i = 0; i < tok->length; i++) {
        if (!is_digit(tok->start[i])) return 0;
        uint64_t digit = (uint64_t)(tok->start[i] - '0');
        if (value > max_tenth || (value == max_tenth && digit > max_last)) return 0;
        value = value * 10 + digit;
    }
    *out = value;
    return 1;
}
