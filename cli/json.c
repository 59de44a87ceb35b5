/* Writing JSON values (cli.h). */
#include <math.h>
#include <string.h>

#include "cli.h"

void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *c = (const unsigned char *)(s ? s : ""); *c; c++) {
        switch (*c) {
        case '"': fputs("\\\"", f); break;
        case '\\': fputs("\\\\", f); break;
        case '\n': fputs("\\n", f); break;
        case '\r': fputs("\\r", f); break;
        case '\t': fputs("\\t", f); break;
        default:
            if (*c < 0x20) fprintf(f, "\\u%04x", (unsigned)*c);
            else fputc(*c, f); /* UTF-8 passes through unchanged */
        }
    }
    fputc('"', f);
}

void json_number(FILE *f, double v)
{
    /* 17 significant digits: parsing the text gives back the same double.
     * A number %g prints without '.' or exponent ("1", "-0") gets ".0", so
     * readers that tell integers from floats (Python's json) keep it a
     * double, and -0.0 keeps its sign. */
    if (!isfinite(v)) {
        fputs("null", f);
        return;
    }
    char buf[40];
    snprintf(buf, sizeof buf, "%.17g", v);
    fputs(buf, f);
    if (!strpbrk(buf, ".eEn")) fputs(".0", f);
}

void json_vec3(FILE *f, hr_vec3 v)
{
    fputc('[', f);
    json_number(f, v.x);
    fputs(", ", f);
    json_number(f, v.y);
    fputs(", ", f);
    json_number(f, v.z);
    fputc(']', f);
}
