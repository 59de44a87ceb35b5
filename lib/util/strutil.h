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

#endif
