/* The "options:" block of a verb's --help, printed from its option table
 * (cli.h), so that the help lists exactly what the parser takes. */
#include <string.h>

#include "cli.h"

/* Help columns: the option and its value, then its text from column 25, no
 * line past column 78. */
#define TEXT_COLUMN 24
#define LAST_COLUMN 78

void cli_print_options(FILE *f, const cli_option *table)
{
    for (const cli_option *o = table; o->name; o++) {
        int width = fprintf(f, "  %s%s%s%s%s", o->alias ? o->alias : "", o->alias ? ", " : "", o->name,
                            o->value ? " " : "", o->value ? o->value : "");
        /* Two blanks at least between the option and its text. */
        if (width > TEXT_COLUMN - 2) {
            fputc('\n', f);
            width = 0;
        }
        fprintf(f, "%*s", TEXT_COLUMN - width, "");
        int column = TEXT_COLUMN;
        const char *text = o->help ? o->help : "";
        while (*text) {
            size_t word = strcspn(text, " ");
            if (column > TEXT_COLUMN && column + 1 + (int)word > LAST_COLUMN) {
                fprintf(f, "\n%*s", TEXT_COLUMN, "");
                column = TEXT_COLUMN;
            } else if (column > TEXT_COLUMN) {
                fputc(' ', f);
                column++;
            }
            fwrite(text, 1, word, f);
            column += (int)word;
            text += word;
            while (*text == ' ') text++;
        }
        fputc('\n', f);
    }
}
