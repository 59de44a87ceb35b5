/* Numbers and macro names of SDL (lib/sdl/sdl_words.h). */
#include "sdl/sdl_words.h"

#include <langinfo.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int is_digit(char c) { return c >= '0' && c <= '9'; }
static int is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/* 1 if the whole word matches the decimal grammar. strtod alone would accept
 * hex, "inf", "nan" and stop silently before trailing junk. */
static int is_decimal(const char *s)
{
    if (*s == '+' || *s == '-') s++;
    int digits = 0;
    while (is_digit(*s)) s++, digits++;
    if (*s == '.') {
        s++;
        while (is_digit(*s)) s++, digits++;
    }
    if (digits == 0) return 0;
    if (*s == 'e' || *s == 'E') {
        s++;
        if (*s == '+' || *s == '-') s++;
        if (!is_digit(*s)) return 0;
        while (is_digit(*s)) s++;
    }
    return *s == '\0';
}

/* strtod reads the decimal point of the current locale; a program that set,
 * say, a German locale would read "0.5" as 0. Swap the point for the locale's
 * own before converting. The point comes from nl_langinfo, which reads the
 * calling thread's locale like strtod: localeconv() fills one static struct
 * that any other thread's call rewrites meanwhile. */
static double convert(const char *word, int *ok)
{
    const char *point = nl_langinfo(RADIXCHAR);
    char *end = NULL;
    double value;
    if (!point || !*point || strcmp(point, ".") == 0 || !strchr(word, '.')) {
        value = strtod(word, &end);
        *ok = end && *end == '\0';
    } else {
        size_t n = strlen(word), np = strlen(point);
        char *copy = malloc(n + np + 1);
        if (!copy) {
            *ok = 0;
            return 0.0;
        }
        const char *dot = strchr(word, '.');
        size_t before = (size_t)(dot - word);
        memcpy(copy, word, before);
        memcpy(copy + before, point, np);
        strcpy(copy + before + np, dot + 1);
        value = strtod(copy, &end);
        *ok = end && *end == '\0';
        free(copy);
    }
    return value;
}

int sdl_parse_number(const char *word, double *out)
{
    if (!is_decimal(word)) return SDL_NUMBER_NOT_A_NUMBER;
    int ok;
    double value = convert(word, &ok);
    if (!ok) return SDL_NUMBER_NOT_A_NUMBER;
    /* Underflow rounds to zero or a subnormal, which is a fine value;
     * overflow gives infinity, which no SDL argument can use. */
    if (!isfinite(value)) return SDL_NUMBER_TOO_LARGE;
    *out = value;
    return SDL_NUMBER_OK;
}

int sdl_is_macro_name(const char *word)
{
    if (!is_letter(*word)) return 0;
    for (word++; *word; word++)
        if (!is_letter(*word) && !is_digit(*word) && *word != '.' && *word != '_') return 0;
    return 1;
}
