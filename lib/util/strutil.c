#include "util/strutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

char *hri_strdup(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *copy = malloc(n);
    if (copy) memcpy(copy, s, n);
    return copy;
}

char *hri_path_join(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    int slash = na > 0 && a[na - 1] != '/';
    char *p = malloc(na + (size_t)slash + nb + 1);
    if (!p) return NULL;
    memcpy(p, a, na);
    if (slash) p[na] = '/';
    memcpy(p + na + (size_t)slash, b, nb + 1);
    return p;
}

char *hri_path_dirname(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return hri_strdup(".");
    if (slash == path) return hri_strdup("/");
    size_t n = (size_t)(slash - path);
    char *d = malloc(n + 1);
    if (!d) return NULL;
    memcpy(d, path, n);
    d[n] = '\0';
    return d;
}

int hri_str_ends_with(const char *s, const char *suffix)
{
    size_t ns = strlen(s), nx = strlen(suffix);
    return ns >= nx && memcmp(s + ns - nx, suffix, nx) == 0;
}

const char *hri_shortest(double v, char *buf)
{
    for (int digits = 1; digits <= 17; digits++) {
        snprintf(buf, HR_SHORTEST_BYTES, "%.*g", digits, v);
        if (strtod(buf, NULL) == v) break;
    }
    return buf;
}

const char *hri_quote_word(const char *text, size_t length, size_t shown, char *buf, size_t size)
{
    if (size == 0) return buf;
    size_t k = 0;
    const size_t n = length < shown ? length : shown;
    /* Room for the widest piece (\xNN), the closing quote, "..." and the
     * terminator is kept at every step. */
    if (k + 1 < size) buf[k++] = '\'';
    size_t i = 0;
    for (; i < n && k + 9 < size; i++) {
        const unsigned char c = (unsigned char)text[i];
        if (c >= 0x20 && c < 0x7f && c != '\'' && c != '\\') buf[k++] = (char)c;
        else k += (size_t)snprintf(buf + k, size - k, "\\x%02x", c);
    }
    if (i < length && k + 4 < size) buf[k++] = '.', buf[k++] = '.', buf[k++] = '.';
    if (k + 1 < size) buf[k++] = '\'';
    buf[k] = '\0';
    return buf;
}
