/* The `hitray` command: what its files share.
 *
 * Every verb is a function taking its own arguments (argv[0] is the verb) and
 * returning the process exit status (CLI_EXIT_*), any error after one line
 * "hitray: <message>" on stderr. Nothing here reaches past the public API in
 * include/hitray. */
#ifndef HITRAY_CLI_H
#define HITRAY_CLI_H

#include <stdint.h>
#include <signal.h>
#include <stdio.h>

#include <hitray/hitray.h>

/* The exit statuses, as --help and the man page list them (CLI_EXIT_HELP). */
#define CLI_EXIT_OK 0
#define CLI_EXIT_ERROR 1         /* a scene or input error: the file, the library, the output */
#define CLI_EXIT_USAGE 2         /* the command line itself: an option, a value, a missing argument */
#define CLI_EXIT_INTERRUPTED 130 /* the shell's convention for SIGINT */
#define CLI_EXIT_HELP                                                                   \
    "exit status:\n"                                                                   \
    "  0    success\n"                                                                 \
    "  1    a scene or input error (a file that cannot be read or written, a scene\n"  \
    "       the library refuses), explained in one line on stderr\n"                   \
    "  2    a usage error: an unknown command or option, a value out of range, a\n"   \
    "       missing argument (nothing was read or written)\n"                          \
    "  130  interrupted (Ctrl-C); nothing was written\n"

int cmd_render(int argc, char **argv);
int cmd_hits(int argc, char **argv);
int cmd_shapes(int argc, char **argv);
int cmd_savings(int argc, char **argv);
int cmd_view(int argc, char **argv);
int cmd_completion(int argc, char **argv);

/* --- errors (args.c) --- */

/* Print "hitray: <message>" as one line on stderr (newlines in the message
 * become "; ") and return CLI_EXIT_ERROR. */
int cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* The same for a mistake in the command line: returns CLI_EXIT_USAGE. */
int cli_usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* The context's last error, or a fallback naming the status. */
int cli_library_error(const hr_context *ctx, hr_status status);

/* --- options (args.c) --- */

/* One option of a verb: what the parser accepts, and what --help and the
 * shell completion (cmd_completion.c) say of it, from this one entry. */
typedef struct cli_option {
    const char *name;  /* "--size" */
    const char *alias; /* "-o", or NULL */
    int takes_value;
    /* The value as the help names it: "WxH", "N"; "FILE" (or ending in it)
     * a file name, completed as one; "auto|all" its choices. NULL when the
     * option takes none. */
    const char *value;
    /* Its text in --help, wrapped there. NULL in a verb's table: the render
     * flag of that name, with its shared text (cli_render_flags_table). */
    const char *help;
} cli_option;

typedef struct cli_parser {
    int argc;
    char **argv;
    int next;               /* index of the next argument to read */
    const char *verb;       /* for messages */
    const cli_option *options; /* ends with a zeroed entry */
    int only_positionals;   /* after "--" */
    unsigned long seen;     /* bit i: options[i] was given (each at most once) */
} cli_parser;

#define CLI_END 0
#define CLI_OPTION 1
#define CLI_POSITIONAL 2
#define CLI_BAD -1 /* already reported on stderr */

void cli_parser_init(cli_parser *p, int argc, char **argv, const cli_option *options);
/* The next argument: an option (*name is its table name, *value its value
 * or NULL), a positional (*value), the end, or an error (reported). Accepts
 * "--name value", "--name=value" and "-o value"; an option given twice is
 * an error. */
int cli_next(cli_parser *p, const char **name, const char **value);

/* The "options:" lines of --help: each option with its value's name, its
 * text from column 25, wrapped within 78 columns. */
void cli_print_options(FILE *f, const cli_option *table);

/* The verbs (verbs.c): one table for the dispatch, the help, the "did you
 * mean" and the shell completion. */
typedef struct cli_verb {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *synopsis; /* what follows the name in the help */
    const char *summary;  /* lines after the first start with '\n' and are indented */
    const cli_option *options; /* its own options (ending with a zeroed entry) */
    unsigned render_flags;     /* and the shared render flags it takes (CLI_RF_*) */
    /* What its positional argument is, for the completion: "FILE" a file
     * name, "a|b" its choices, NULL none. */
    const char *operand;
} cli_verb;
extern const cli_verb cli_verbs[];
extern const int32_t cli_verb_count;
/* The options of `hitray` itself, before a verb. */
extern const cli_option cli_top_options[];

/* Each verb's own options, for its parser, its --help and the completion
 * (the render flags it shares are added by cli_render_flags_table). */
extern const cli_option cli_render_options[], cli_hits_options[], cli_shapes_options[], cli_savings_options[],
    cli_view_options[], cli_completion_options[];

/* Strict number parsing: the whole text must be the number. Each reports its
 * own error naming `option` (a usage error) and returns 0 on failure, 1 on
 * success. */
int cli_parse_int(const char *option, const char *text, long min, long max, int32_t *out);
int cli_parse_doubles(const char *option, const char *text, int count, double *out);
int cli_parse_size(const char *option, const char *text, int32_t *width, int32_t *height);
/* One decimal number within 0..1. */
int cli_parse_fraction(const char *option, const char *text, double *out);

/* --- output files (output_path.c) --- */

/* The format an output is written in: the one --format names (format_name;
 * NULL when not given), else the one the file name's extension names; "-"
 * (standard output) with no --format is PNG. 0, or CLI_EXIT_USAGE after
 * reporting an unknown name, an extension that names none, or one that
 * names another format than --format (the message names `option`). */
int cli_output_format(const char *option, const char *path, const char *format_name, int32_t *format);
/* The directory a file would go to must exist and be writable, and the name
 * must be one a file can have there; otherwise the error (naming `option`)
 * is reported and its exit status returned (CLI_EXIT_USAGE for an empty
 * name, else CLI_EXIT_ERROR). 0 when it can be written. */
int cli_check_writable(const char *option, const char *path);

/* --- output helpers --- */

/* JSON values (json.c): strings escaped, doubles with %.17g so they
 * round-trip, non-finite doubles as null (JSON has no infinity). */
void json_string(FILE *f, const char *s);
void json_number(FILE *f, double v);
void json_vec3(FILE *f, hr_vec3 v);

/* A progress bar on stderr, drawn only when stderr is a terminal
 * (progress.c). The callback also lets Ctrl-C stop a render cleanly; the
 * Ctrl-C handler cli_progress_begin installs stays until
 * cli_interrupt_release, so that a Ctrl-C while the files are written lets
 * them be finished instead of killing the process half way. */
typedef struct cli_progress {
    int draw;       /* stderr is a terminal */
    int last_shown; /* per cent last drawn, -1 before the first */
    double started; /* seconds, monotonic */
    const char *label; /* what is running: "rendering", "savings: full" */
} cli_progress;
void cli_progress_begin(cli_progress *p, const char *label);
/* --quiet: no bar and no status line, even on a terminal. */
void cli_set_quiet(int on);
int32_t cli_progress_update(void *user, double fraction);
void cli_progress_end(cli_progress *p);
/* A stage with no fraction to show ("loading scene.sdl ..."), on the
 * terminal only; NULL clears the line. */
void cli_status(const char *what, const char *name);
/* Hold SIGINT, SIGTERM, SIGHUP and SIGQUIT while output files are written
 * (cli_release_signals delivers any that came), so no signal can leave a
 * half-written temporary file. */
void cli_hold_signals(sigset_t *previous);
void cli_release_signals(const sigset_t *previous);
void cli_interrupt_release(void);
/* 1 once SIGINT arrived during a render. */
int cli_interrupted(void);
double cli_now(void);

/* A scene file loaded (and then committed), with its camera
 * (scene_file.c). */
typedef struct cli_scene {
    hr_context *ctx;
    hr_sdl_result sdl;
    const char *path; /* for messages */
} cli_scene;
/* 0 on success; on failure the error is reported and everything freed.
 * A name ending in .nff or .nff.gz (any case) is read as NFF, any other as
 * Hill's SDL; "-" is SDL read from standard input (named CLI_STDIN_NAME in
 * messages, its relative file names taken from the current directory). */
#define CLI_STDIN_NAME "<stdin>"
int cli_scene_load(cli_scene *s, const char *path);
int cli_is_nff(const char *path);
/* .obj or .3vn (any case): a mesh file, rendered as a scene of that mesh
 * alone, framed and lit (a default camera and one light fitted to it). */
int cli_is_mesh(const char *path);
int cli_scene_commit(cli_scene *s);
/* The scene file's camera at width x height, or, for a file that sets none,
 * one that frames what is there (Hill's default at (0,0,5) may see nothing
 * of such a scene). */
hr_camera cli_scene_camera(const cli_scene *s, int32_t width, int32_t height);
/* The scene's camera with eye, look-at point, up vector and view angle
 * replaced by c[0..9] (the --camera option's values), at width x height. */
hr_camera cli_camera_from_values(const cli_scene *s, const double c[10], int32_t width, int32_t height);
void cli_scene_free(cli_scene *s);

#endif
