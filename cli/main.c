/* hitray: the command-line front end of the library. This file only picks
 * the verb; each verb lives in its own cmd_*.c. */
#include <string.h>

#include "cli.h"

static const char usage[] =
    "usage: hitray <command> [options]\n"
    "\n"
    "A ray tracer after F.S. Hill's Computer Graphics Using OpenGL, chapter 12.\n"
    "\n"
    "commands:\n"
    "  render SCENE -o OUT   render an SDL or NFF scene file to an image (.png .exr .ppm .pfm)\n"
    "  hits SCENE --origin X,Y,Z --dir X,Y,Z [--all]\n"
    "                        where a ray meets the scene, as JSON lines\n"
    "  shapes                list the shape modules found and their parameters\n"
    "  savings SCENE         rays saved and error caused by each opt-in saving\n"
    "  view SCENE            render in a window, coarse to fine, and fly Hill's camera\n"
    "                        (runs hitray-view, built where SDL2 is installed)\n"
    "\n"
    "options:\n"
    "  -h, --help            this help; 'hitray <command> --help' for a command's\n"
    "  --version             the version of hitray and of the library it runs on\n"
    "\n"
    "Exit status: 0 on success, 1 on an error (explained in one line on stderr).\n";

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
    if (argc < 2) return cli_error("no command given (see 'hitray --help')");
    const char *verb = argv[1];
    int help = !strcmp(verb, "-h") || !strcmp(verb, "--help") || !strcmp(verb, "help");
    int version = !strcmp(verb, "--version") || !strcmp(verb, "-V");
    /* `hitray --help render` is a typo for `hitray render --help`: say so
     * rather than print the general help as if nothing were wrong. */
    if ((help || version) && argc > 2)
        return cli_error("'%s' takes nothing after it, found '%s' (for a command's help: "
                         "'hitray <command> --help')",
                         verb, argv[2]);
    if (help) {
        fputs(usage, stdout);
        return CLI_EXIT_OK;
    }
    if (version) return print_version();
    if (!strcmp(verb, "render")) return cmd_render(argc - 1, argv + 1);
    if (!strcmp(verb, "hits")) return cmd_hits(argc - 1, argv + 1);
    if (!strcmp(verb, "shapes")) return cmd_shapes(argc - 1, argv + 1);
    if (!strcmp(verb, "savings")) return cmd_savings(argc - 1, argv + 1);
    if (!strcmp(verb, "view")) return cmd_view(argc - 1, argv + 1);
    if (verb[0] == '-') return cli_error("unknown option '%s' (see 'hitray --help')", verb);
    static const char *const verbs[] = {"render", "hits", "shapes", "savings"};
    const char *near = hr_suggest(verb, verbs, (int32_t)(sizeof verbs / sizeof verbs[0]));
    if (near) return cli_error("unknown command '%s' (did you mean '%s'? see 'hitray --help')", verb, near);
    return cli_error("unknown command '%s' (see 'hitray --help')", verb);
}
