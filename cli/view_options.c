/* hitray view's options (cli.h): read by the viewer, hitray-view, and known
 * to `hitray` too, whose completion offers them. */
#include "cli.h"

/* In --help's order; the entries with no text are the shared render flags
 * (render_flags.c), those with a text say what the viewer makes of them. */
const cli_option cli_view_options[] = {
    {"--size", NULL, 1, NULL, NULL},
    {"--spp", NULL, 1, "N", "samples per pixel of the final pass (default 1); the block passes cast one ray per "
                            "block"},
    {"--threads", NULL, 1, "N", "threads (default 0: every core)"},
    {"--depth", NULL, 1, NULL, NULL},
    {"--block", NULL, 1, "N", "the finest pass: one ray per NxN block (default 1); refining stops there, to "
                              "frame a slow scene fast"},
    {"--camera", NULL, 1, "EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE", "the first camera, as for 'hitray render'"},
    {"--min-weight", NULL, 1, NULL, NULL},
    {"--exact", NULL, 0, NULL, NULL},
    {"--output", "-o", 1, "FILE", "where the P key saves the picture: FILE, or once that exists FILE numbered "
                                  "(hitray-view-2.png, -3, ...), so that no picture is overwritten (default "
                                  "hitray-view.png; .png .exr .ppm .pfm .jpg .hdr .bmp .tga)"},
    {"--screenshot", NULL, 1, "FILE", "write every final pass to FILE and print 'wrote FILE: camera ...' (for "
                                      "scripts)"},
    {"--exit-when-done", NULL, 0, NULL, "quit after the first final pass (and its --screenshot)"},
    {"--help", "-h", 0, NULL, "this help"},
    {NULL, NULL, 0, NULL, NULL},
};
