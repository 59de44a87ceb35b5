/* Internal: what an SDL word can be — a number or a macro name. */
#ifndef HITRAY_LIB_SDL_WORDS_H
#define HITRAY_LIB_SDL_WORDS_H

#define SDL_NUMBER_OK 0
#define SDL_NUMBER_NOT_A_NUMBER 1 /* not decimal, or trailing junk: "3x", "0x10", "inf" */
#define SDL_NUMBER_TOO_LARGE 2    /* decimal, but beyond the range of a double */

/* Parse a whole word as a decimal number: an optional sign, digits with an
 * optional point (".8", "5.", "-90"), an optional exponent ("1e-3"). Hex,
 * "inf" and "nan" are not SDL numbers. The result does not depend on the
 * C locale of the calling program. Returns SDL_NUMBER_*. */
int sdl_parse_number(const char *word, double *out);

/* 1 if `word` can name a macro: a letter, then letters, digits, '.' or '_'. */
int sdl_is_macro_name(const char *word);

#endif
