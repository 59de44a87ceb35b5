/* The render flags that `hitray render`, `hitray view` and `hitray savings`
 * share: one table, one parser, one set of limits (the library's own, from
 * hitray/render.h) and one copy into hr_render_options. The viewer promises
 * that its final pass is `hitray render`'s image bit for bit; one parser is
 * how the promise holds as flags are added.
 *
 * A verb says which flags it takes (CLI_RF_* bits), joins them to its own
 * options for the parser (cli_render_flags_table), hands each option it
 * reads to cli_render_flags_parse, and after the last argument checks the
 * combination (cli_render_flags_check). */
#ifndef HITRAY_CLI_RENDER_FLAGS_H
#define HITRAY_CLI_RENDER_FLAGS_H

#include "cli.h"

#define CLI_RF_SIZE (1u << 0)       /* --size WxH */
#define CLI_RF_SPP (1u << 1)        /* --spp N */
#define CLI_RF_THREADS (1u << 2)    /* --threads N */
#define CLI_RF_DEPTH (1u << 3)      /* --depth N */
#define CLI_RF_BLOCK (1u << 4)      /* --block N */
#define CLI_RF_CAMERA (1u << 5)     /* --camera EX,...,ANGLE */
#define CLI_RF_EFFECTS (1u << 6)    /* --effects auto|all */
#define CLI_RF_ADAPTIVE (1u << 7)   /* --adaptive T */
#define CLI_RF_MIN_WEIGHT (1u << 8) /* --min-weight W */
#define CLI_RF_EXACT (1u << 9)      /* --exact */
#define CLI_RF_WINDOW (1u << 10)    /* --window X,Y,W,H */
#define CLI_RF_TEXTURE_FILTER (1u << 11) /* --texture-filter footprint|none */

/* The render flags each verb takes. The viewer's passes set their own
 * block sizes and samples and keep every effect's analysis on
 * (view/view_passes.c): --effects, --adaptive and --window are not the
 * viewer's. savings renders every pixel and has its own --adaptive and
 * --min-weight, lists of values. */
#define CLI_RENDER_FLAGS                                                                                     \
    (CLI_RF_SIZE | CLI_RF_SPP | CLI_RF_THREADS | CLI_RF_DEPTH | CLI_RF_BLOCK | CLI_RF_CAMERA | CLI_RF_EFFECTS | \
     CLI_RF_ADAPTIVE | CLI_RF_MIN_WEIGHT | CLI_RF_EXACT | CLI_RF_WINDOW | CLI_RF_TEXTURE_FILTER)
#define CLI_VIEW_FLAGS                                                                                       \
    (CLI_RF_SIZE | CLI_RF_SPP | CLI_RF_THREADS | CLI_RF_DEPTH | CLI_RF_BLOCK | CLI_RF_CAMERA | CLI_RF_MIN_WEIGHT | \
     CLI_RF_EXACT | CLI_RF_TEXTURE_FILTER)
#define CLI_SAVINGS_FLAGS (CLI_RF_SIZE | CLI_RF_SPP | CLI_RF_DEPTH | CLI_RF_THREADS)

typedef struct cli_render_flags {
    unsigned given;        /* the CLI_RF_* flags the user gave */
    int32_t width, height; /* 0: the scene file's size */
    int32_t spp, threads, depth, block;
    double camera[10];     /* eye, look-at point, up, view angle */
    int32_t effects;       /* HR_EFFECTS_AUTO or HR_EFFECTS_ALL */
    double adaptive, min_weight;
    int32_t exact;
    int32_t window[4]; /* x, y, width, height; all 0: the whole image */
    int32_t texture_filter; /* HR_TEXTURE_FILTER_* */
} cli_render_flags;

/* The defaults: hr_render_options_default's (the scene's size and depth). */
void cli_render_flags_init(cli_render_flags *f);

/* The verb's option table: `own` (ending with a zeroed entry) followed by
 * the render flags in `which` it does not name. An entry of `own` with no
 * help text is the render flag of that name, put there (so a verb orders
 * its help); one with a text is the verb's own, even if a render flag has
 * its name. Returns the entries written before the zeroed end, or -1 if
 * `capacity` (counting the end) is too small or an entry with no text
 * names no render flag in `which`. */
#define CLI_TABLE_CAPACITY 40
int cli_render_flags_table(const cli_option *own, unsigned which, cli_option *out, int capacity);

/* The CLI_RF_* bit of a render flag's name, 0 for any other option. */
unsigned cli_render_flag_bit(const char *name);

/* Parse one render flag's value: 1 on success, 0 after reporting the usage
 * error (the name, the text, the library's limit). `name` must be a render flag
 * (cli_render_flag_bit != 0). */
int cli_render_flags_parse(cli_render_flags *f, const char *name, const char *value);

/* The combinations hr_render refuses, refused before any work with the
 * flags' names: 0, or CLI_EXIT_USAGE after reporting. */
int cli_render_flags_check(const cli_render_flags *f);

/* --window against the image's size (known once the scene is loaded): 0,
 * or CLI_EXIT_USAGE after reporting a window that does not lie inside. */
int cli_render_flags_check_window(const cli_render_flags *f, int32_t width, int32_t height);

/* The flags into `o` (from hr_render_options_default): everything but the
 * camera, which the caller makes (cli_render_flags_camera). */
void cli_render_flags_apply(const cli_render_flags *f, hr_render_options *o);

/* The camera: --camera's values where given, else the scene file's (or one
 * that frames a scene with none), at the flags' size. */
hr_camera cli_render_flags_camera(const cli_render_flags *f, const cli_scene *s);

#endif
