/* Internal: NFF text as words. NFF is one entity a line, but its layouts
 * differ in where lines break (a `c` on one line or three), so the reader
 * takes words in order and asks about lines only where the format does:
 * whether a light's colour is on its own line. `#` starts a comment that
 * runs to the end of the line. Nothing is allocated: a word is a slice of
 * the text. */
#ifndef HITRAY_LIB_NFF_LEXER_H
#define HITRAY_LIB_NFF_LEXER_H

#include <stddef.h>
#include <stdint.h>

typedef struct nff_word {
    const char *text; /* into the source text; not NUL-terminated */
    size_t length;    /* 0 at the end of the text */
    int32_t line, column; /* 1-based; at the end, where the text ends */
    int nul;          /* 1: the word holds a NUL byte (the text is no text) */
} nff_word;

typedef struct nff_lexer {
    const char *text;
    size_t length, pos;
    int32_t line, column; /* of text[pos] */
} nff_lexer;

void nff_lexer_init(nff_lexer *lx, const char *text, size_t length);
/* The next word, or one of length 0 at the end. */
nff_word nff_next(nff_lexer *lx);
/* The next word without taking it. */
nff_word nff_peek(const nff_lexer *lx);
/* Bytes not yet read: a bound on what the rest of the file can hold. */
size_t nff_remaining(const nff_lexer *lx);
/* 1 if the word is exactly `s`. */
int nff_word_is(nff_word w, const char *s);

#endif
