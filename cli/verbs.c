/* The verbs of `hitray` (cli.h): one table, read by the dispatch and the
 * help (main.c), the "did you mean" and the shell completion
 * (cmd_completion.c). A verb added here is in all of them. */
#include "cli.h"
#include "render_flags.h"

const cli_verb cli_verbs[] = {
    {"render", cmd_render, "SCENE -o OUT",
     "render a scene file (SDL, NFF, or a mesh alone) to an image\n(.png .exr .ppm .pfm .jpg .hdr .bmp .tga)",
     cli_render_options, CLI_RENDER_FLAGS, "FILE"},
    {"hits", cmd_hits, "SCENE --origin X,Y,Z --dir X,Y,Z [--all]", "where a ray meets the scene, as JSON lines",
     cli_hits_options, 0, "FILE"},
    {"shapes", cmd_shapes, "", "list the shape modules found and their parameters", cli_shapes_options, 0, NULL},
    {"savings", cmd_savings, "SCENE", "rays saved and error caused by each opt-in saving", cli_savings_options,
     CLI_SAVINGS_FLAGS, "FILE"},
    {"view", cmd_view, "SCENE",
     "render in a window, coarse to fine, and fly Hill's camera\n(runs hitray-view, built where SDL2 is installed)",
     cli_view_options, CLI_VIEW_FLAGS, "FILE"},
    {"completion", cmd_completion, "bash|zsh", "the shell completion script of hitray, for bash or zsh",
     cli_completion_options, 0, "bash|zsh"},
};
const cli_option cli_top_options[] = {
    {"--help", "-h", 0, NULL, "this help; 'hitray <command> --help' for a command's"},
    {"--version", NULL, 0, NULL, "the version of hitray and of the library it runs on"},
    {NULL, NULL, 0, NULL, NULL},
};

const int32_t cli_verb_count = (int32_t)(sizeof cli_verbs / sizeof cli_verbs[0]);
