/* Reading the text of a mesh file: whitespace-separated tokens with their
 * line numbers, numbers in the locale-independent decimal grammar, counts
 * and indices, and messages of the form "file:line: what (found 'token')".
 * The text is a buffer in memory: nothing is read twice and nothing is
 * recursive, whatever the input. */
#ifndef HITRAY_MESH_TEXT_H
#define HITRAY_MESH_TEXT_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/common.h>

/* Coordinates beyond this are refused: the triangle test multiplies three
 * of them, which must stay inside double's range. */
#define MESH_MAX_COORDINATE 1e100

typedef struct mesh_text {
    const char *p, *end;
    long line;
    long last_line; /* of the last token: where "end of file" is reported */
    const char *shown; /* the file's name in messages */
    char *error;
    size_t error_size;
} mesh_text;

typedef struct mesh_token {
    const char *start;
    size_t length; /* 0: no token (end of file, or of the line) */
    long line;
} mesh_token;

void mesh_text_init(mesh_text *t, const char *text, size_t length, const char *shown, char *error,
                    size_t error_size);
/* The next token. With cross_lines 0 it stops at the end of the line
 * (length 0) instead of going on to the next. '#' starts a comment to the
 * end of the line when `comments` is set. */
mesh_token mesh_text_next(mesh_text *t, int cross_lines, int comments);
/* Skips the rest of the current line. */
void mesh_text_skip_line(mesh_text *t);
/* Bytes not yet read: every further token needs at least two of them but
 * the last, so counts in a file can be checked against it before any
 * allocation trusts them. */
size_t mesh_text_remaining(const mesh_text *t);
int mesh_token_is(const mesh_token *tok, const char *word);

/* The most of a token a message quotes. */
#define MESH_QUOTED_BYTES 12

/* Writes "shown:line: <what> (found 'token')" (or "found end of file", or
 * "found end of line") and returns HR_ERROR_PARAMETER. The token is cut at
 * MESH_QUOTED_BYTES ("...") and escaped (\xNN). */
hr_status mesh_text_error(mesh_text *t, const mesh_token *tok, const char *what, ...)
    __attribute__((format(printf, 3, 4)));

/* A finite decimal number within +-MESH_MAX_COORDINATE: 1 on success, 0
 * for something else than a number, -1 for one out of that range. */
int mesh_parse_number(const mesh_token *tok, double *out);
/* Digits only, at most `max`. 1 on success. */
int mesh_parse_whole(const mesh_token *tok, uint64_t max, uint64_t *out);

#endif
