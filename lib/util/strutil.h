/* Internal: the few string helpers C11 lacks. */
#ifndef HITRAY_LIB_UTIL_STRUTIL_H
#define HITRAY_LIB_UTIL_STRUTIL_H

#include <stddef.h>

/* malloc'd copy of s (NULL if out of memory or s is NULL). */
char *hri_strdup(const char *s);
/* malloc'd "a/b" (a may be "" giving "b"). */
char *hri_path_join(const char *a, const char *b);
/* malloc'd directory part of a path ("." if none). */
char *hri_path_dirname(const char *path);
/* 1 if s ends with suffix. */
int hri_str_ends_with(const char *s, const char *suffix);
/* v in the fewest significant digits (up to 17) that read back as v, so a
 * message never shows 1.0000001 as 1; `buf` holds HR_SHORTEST_BYTES. */
#define HR_SHORTEST_BYTES 32
const char *hri_shortest(double v, char *buf);

/* A word of a file for a message: in single quotes, its first `shown`
 * bytes (then "..."), anything but printable ASCII (and the quote and the
 * backslash) as \xNN, so that a scene's bytes never reach a terminal that
 * would act on them (an escape sequence, a title, a cleared screen).
 * `buf` holds HR_QUOTED_BYTES(shown); the result is cut to `size`. */
#define HR_QUOTED_BYTES(shown) (4 * (size_t)(shown) + 8)
const char *hri_quote_word(const char *text, size_t length, size_t shown, char *buf, size_t size);

#endif
