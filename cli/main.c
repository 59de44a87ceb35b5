/* hitray: the command-line front end of the library. This file only picks
 * the verb; each verb lives in its own cmd_*.c. */
#include <string.h>

#include "cli.h"

/* The verbs: one table for the dispatch, the help and the "did you mean". */
typedef struct cli_verb {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *synopsis; /* what follows the name in the help */
    const char *summary;  /* lines after the first start with '\n' and are indented */
} cli_verb;

static const cli_verb verbs[] = {
    {"render", cmd_render, "SCENE -o OUT", "render an SDL or NFF scene file to an image (.png .exr .ppm .pfm)"},
    {"hits", cmd_hits, "SCENE --origin X,Y,Z --dir X,Y,Z [--all]", "where a ray meets the scene, as JSON lines"},
    {"shapes", cmd_shapes, "", "list the shape modules found and their parameters"},
    {"savings", cmd_savings, "SCENE", "rays saved and error caused by each opt-in saving"},
    {"view", cmd_view, "SCENE",
     "render in a window, coarse to fine, and fly Hill's camera\n(runs hitray-view, built where SDL2 is installed)"},
};
#define VERB_COUNT (int32_t)(sizeof verbs / sizeof verbs[0])

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
    for (int32_t i = 0; i < VERB_COUNT; i++) {
        const cli_verb *v = &verbs[i];
        int width = printf("  %s%s%s", v->name, *v->synopsis ? " " : "", v->synopsis);
        if (width >= SUMMARY_COLUMN - 1) printf("\n%*s", SUMMARY_COLUMN, "");
        else printf("%*s", SUMMARY_COLUMN - width, "");
        for (const char *c = v->summary; *c; c++) {
            putchar(*c);
            if (*c == '\n') printf("%*s", SUMMARY_COLUMN, "");
        }
        putchar('\n');
    }
    fputs("\n"
          "options:\n"
          "  -h, --help            this help; 'hitray <command> --help' for a command's\n"
          "  --version             the version of hitray and of the library it runs on\n"
          "\n" CLI_EXIT_HELP,
          stdout);
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
    for (int32_t i = 0; i < VERB_COUNT; i++)
        if (!strcmp(verb, verbs[i].name)) return verbs[i].run(argc - 1, argv + 1);
    if (verb[0] == '-') return cli_usage_error("unknown option '%s' (see 'hitray --help')", verb);
    const char *names[VERB_COUNT];
    for (int32_t i = 0; i < VERB_COUNT; i++) names[i] = verbs[i].name;
    const char *near = hr_suggest(verb, names, VERB_COUNT);
    if (near) return cli_usage_error("unknown command '%s' (did you mean '%s'? see 'hitray --help')", verb, near);
    return cli_usage_error("unknown command '%s' (see 'hitray --help')", verb);
}
