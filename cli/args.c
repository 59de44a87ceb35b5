/* Option parsing and error reporting for the `hitray` verbs (cli.h). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void report(const char *fmt, va_list ap)
{
    /* The whole message, however long (a 6,000-byte path must not push
     * the reason off its end), in a buffer of its size. */
    char small[2048], *message = small;
    va_list again;
    va_copy(again, ap);
    const int n = vsnprintf(small, sizeof small, fmt, ap);
    if (n >= (int)sizeof small) {
        char *big = malloc((size_t)n + 1);
        if (big) {
            vsnprintf(big, (size_t)n + 1, fmt, again);
            message = big;
        }
    }
    va_end(again);
    /* One line whatever the library said: scripts read stderr line by line;
     * and no byte a terminal would act on (a path or a word may hold one). */
    fputs("hitray: ", stderr);
    for (const char *c = message; *c; c++) {
        const unsigned char b = (unsigned char)*c;
        if (b == '\n') {
            if (c[1]) fputs("; ", stderr);
        } else if (b < 0x20 || b == 0x7f) {
            fprintf(stderr, "\\x%02x", b);
        } else {
            fputc(*c, stderr);
        }
    }
    fputc('\n', stderr);
    if (message != small) free(message);
}

int cli_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(fmt, ap);
    va_end(ap);
    return CLI_EXIT_ERROR;
}

int cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    report(fmt, ap);
    va_end(ap);
    return CLI_EXIT_USAGE;
}

int cli_library_error(const hr_context *ctx, hr_status status)
{
    const char *message = ctx ? hr_context_last_error(ctx) : "";
    if (message && *message) return cli_error("%s", message);
    return cli_error("%s", hr_status_name(status));
}

void cli_parser_init(cli_parser *p, int argc, char **argv, const cli_option *options)
{
    memset(p, 0, sizeof *p);
    p->argc = argc;
    p->argv = argv;
    p->next = 1; /* argv[0] is the verb */
    p->verb = argc > 0 ? argv[0] : "";
    p->options = options;
}

static const cli_option *find_option(const cli_parser *p, const char *arg, size_t len)
{
    for (const cli_option *o = p->options; o->name; o++) {
        if (strlen(o->name) == len && strncmp(o->name, arg, len) == 0) return o;
        if (o->alias && strlen(o->alias) == len && strncmp(o->alias, arg, len) == 0) return o;
    }
    return NULL;
}

/* The verb's option nearest a misspelt one, by the library's measure. */
static const char *suggest_option(const cli_parser *p, const char *arg, size_t len)
{
    char word[64];
    if (len >= sizeof word) return NULL;
    memcpy(word, arg, len);
    word[len] = '\0';
    const char *names[64];
    int32_t n = 0;
    for (const cli_option *o = p->options; o->name && n < 64; o++) names[n++] = o->name;
    return hr_suggest(word, names, n);
}

int cli_next(cli_parser *p, const char **name, const char **value)
{
    *name = NULL;
    *value = NULL;
    if (p->next >= p->argc) return CLI_END;
    const char *arg = p->argv[p->next++];
    if (p->only_positionals || arg[0] != '-' || arg[1] == '\0') {
        *value = arg; /* "-" alone is a positional (conventionally stdin) */
        return CLI_POSITIONAL;
    }
    if (strcmp(arg, "--") == 0) {
        p->only_positionals = 1;
        return cli_next(p, name, value);
    }
    const char *equals = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
    size_t len = equals ? (size_t)(equals - arg) : strlen(arg);
    const cli_option *o = find_option(p, arg, len);
    if (!o) {
        const char *near = suggest_option(p, arg, len);
        if (near)
            cli_usage_error("%s: unknown option '%.*s' (did you mean '%s'? see 'hitray %s --help')", p->verb,
                      (int)len, arg, near, p->verb);
        else
            cli_usage_error("%s: unknown option '%.*s' (see 'hitray %s --help')", p->verb, (int)len, arg,
                      p->verb);
        return CLI_BAD;
    }
    *name = o->name;
    unsigned long bit = 1ul << (o - p->options);
    if (p->seen & bit) {
        cli_usage_error("%s: option %s given twice", p->verb, o->name);
        return CLI_BAD;
    }
    p->seen |= bit;
    if (!o->takes_value) {
        if (equals) {
            cli_usage_error("%s: option %s takes no value", p->verb, o->name);
            return CLI_BAD;
        }
        return CLI_OPTION;
    }
    if (equals) {
        *value = equals + 1;
    } else if (p->next < p->argc) {
        *value = p->argv[p->next++];
    } else {
        cli_usage_error("%s: option %s needs a value", p->verb, o->name);
        return CLI_BAD;
    }
    return CLI_OPTION;
}

int cli_parse_int(const char *option, const char *text, long min, long max, int32_t *out)
{
    char *end = NULL;
    errno = 0;
    long v = strtol(text, &end, 10);
    /* strtol would also skip leading blanks; a number starts with a sign or digit. */
    int starts_well = text[0] == '-' || text[0] == '+' || (text[0] >= '0' && text[0] <= '9');
    if (!starts_well || end == text || *end != '\0' || errno == ERANGE) {
        cli_usage_error("%s: '%s' is not a whole number", option, text);
        return 0;
    }
    if (v < min || v > max) {
        cli_usage_error("%s: %ld is out of range %ld..%ld", option, v, min, max);
        return 0;
    }
    *out = (int32_t)v;
    return 1;
}

static int parse_double(const char *text, const char **end, double *out)
{
    char *stop = NULL;
    double v = strtod(text, &stop);
    /* strtod skips leading blanks and accepts "nan", "inf" and hexadecimal
     * ("0x1p3"): none is a decimal number as the options document them. */
    int hex = strpbrk(text, "xX") != NULL && strpbrk(text, "xX") < stop;
    /* ERANGE with a finite result is underflow: a subnormal or zero, the
     * nearest double, as the SDL reader takes it too. Overflow gives an
     * infinity, refused. */
    if (stop == text || isspace((unsigned char)text[0]) || !isfinite(v) || hex) return 0;
    *end = stop;
    *out = v;
    return 1;
}

int cli_parse_doubles(const char *option, const char *text, int count, double *out)
{
    const char *p = text;
    for (int i = 0; i < count; i++) {
        const char *end = NULL;
        if (!parse_double(p, &end, &out[i]) || (i + 1 < count ? *end != ',' : *end != '\0')) {
            cli_usage_error("%s: '%s' is not %d comma-separated numbers", option, text, count);
            return 0;
        }
        p = end + 1;
    }
    return 1;
}

int cli_parse_fraction(const char *option, const char *text, double *out)
{
    const char *end = NULL;
    double v;
    if (!parse_double(text, &end, &v) || *end != '\0') {
        cli_usage_error("%s: '%s' is not a number", option, text);
        return 0;
    }
    if (!(v >= 0.0 && v <= 1.0)) {
        cli_usage_error("%s: %s is out of range 0..1", option, text);
        return 0;
    }
    *out = v;
    return 1;
}

int cli_parse_size(const char *option, const char *text, int32_t *width, int32_t *height)
{
    char *end = NULL;
    errno = 0;
    long w = strtol(text, &end, 10);
    int ok = end != text && (*end == 'x' || *end == 'X') && errno != ERANGE;
    long h = 0;
    if (ok) {
        const char *hs = end + 1;
        h = strtol(hs, &end, 10);
        ok = end != hs && *end == '\0' && errno != ERANGE && hs[0] >= '0' && hs[0] <= '9';
    }
    ok = ok && text[0] >= '0' && text[0] <= '9';
    if (!ok) {
        cli_usage_error("%s: '%s' is not WIDTHxHEIGHT (for example 640x480)", option, text);
        return 0;
    }
    if (w < 1 || h < 1 || w > HR_RENDER_MAX_SIDE || h > HR_RENDER_MAX_SIDE) {
        cli_usage_error("%s: %ldx%ld is out of range: each side must be 1..%d", option, w, h, HR_RENDER_MAX_SIDE);
        return 0;
    }
    *width = (int32_t)w;
    *height = (int32_t)h;
    return 1;
}
