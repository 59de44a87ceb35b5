/* hitray: the command-line front end of the library. This file only picks
 * the verb (verbs.c lists them); each verb lives in its own cmd_*.c. */
#include <string.h>

#include "cli.h"

/* Help columns: the name and synopsis, then the summary from column 25. */
#define SUMMARY_COLUMN 24

static void print_usage(void)
{
    fputs("usage: hitray <command> [options]\n"
          "\n"
          "A ray tracer after F.S. Hill's Computer Graphics Using OpenGL, chapter 12.\n"
          "\n"
          "commands:\n",
          stdout);
    for (int32_t i = 0; i < cli_verb_count; i++) {
        const cli_verb *v = &cli_verbs[i];
        int width = printf("  %s%s%s", v->name, *v->synopsis ? " " : "", v->synopsis);
        if (width >= SUMMARY_COLUMN - 1) printf("\n%*s", SUMMARY_COLUMN, "");
        else printf("%*s", SUMMARY_COLUMN - width, "");
        for (const char *c = v->summary; *c; c++) {
            putchar(*c);
            if (*c == '\n') printf("%*s", SUMMARY_COLUMN, "");
        }
        putchar('\n');
    }
    fputs("\noptions:\n", stdout);
    cli_print_options(stdout, cli_top_options);
    fputs("\n" CLI_EXIT_HELP, stdout);
}

static int print_version(void)
{
    int32_t major, minor, patch;
    hr_version(&major, &minor, &patch);
    printf("hitray %d.%d.%d (libhitray %d.%d.%d)\n", HR_VERSION_MAJOR, HR_VERSION_MINOR, HR_VERSION_PATCH,
           (int)major, (int)minor, (int)patch);
    return CLI_EXIT_OK;
}

int main(int argc, char **argv)
{
    if (argc < 2) return cli_usage_error("no command given (see 'hitray --help')");
    const char *verb = argv[1];
    int help = !strcmp(verb, "-h") || !strcmp(verb, "--help") || !strcmp(verb, "help");
    int version = !strcmp(verb, "--version") || !strcmp(verb, "-V");
    /* `hitray --help render` is a typo for `hitray render --help`: say so
     * rather than print the general help as if nothing were wrong. */
    if ((help || version) && argc > 2)
        return cli_usage_error("'%s' takes nothing after it, found '%s' (for a command's help: "
                         "'hitray <command> --help')",
                         verb, argv[2]);
    if (help) {
        print_usage();
        return CLI_EXIT_OK;
    }
    if (version) return print_version();
    for (int32_t i = 0; i < cli_verb_count; i++)
        if (!strcmp(verb, cli_verbs[i].name)) return cli_verbs[i].run(argc - 1, argv + 1);
    if (verb[0] == '-') return cli_usage_error("unknown option '%s' (see 'hitray --help')", verb);
    const char *names[32];
    int32_t count = 0;
    for (int32_t i = 0; i < cli_verb_count && count < 32; i++) names[count++] = cli_verbs[i].name;
    const char *near = hr_suggest(verb, names, count);
    if (near) return cli_usage_error("unknown command '%s' (did you mean '%s'? see 'hitray --help')", verb, near);
    return cli_usage_error("unknown command '%s' (see 'hitray --help')", verb);
}
