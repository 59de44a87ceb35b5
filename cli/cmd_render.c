/* hitray render: an SDL scene file to an image file.
 *
 * Every argument is checked, and the output files' directories too, before
 * the scene is loaded or a ray is cast: a typo should cost nothing, and a
 * long render should not end in "cannot write". */
#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "render_flags.h"

static const char render_help[] =
    "usage: hitray render SCENE -o OUT [options]\n"
    "\n"
    "Render the scene file SCENE (Hill's SDL, or NFF if it ends in .nff or\n"
    ".nff.gz, or a mesh alone if it ends in .obj or .3vn, framed by a default\n"
    "camera and lit by one light; - reads SDL from standard input) and write\n"
    "the image to OUT; its extension picks the format: .png (8-bit sRGB),\n"
    ".exr (float), .ppm, .pfm (float), .jpg or .jpeg, .hdr (Radiance, float),\n"
    ".bmp, .tga.\n"
    "OUT - writes the image to standard output (PNG unless --format).\n"
    "Prints one summary line: size, time, rays cast, rays per second (on\n"
    "stderr when the image goes to standard output).\n"
    "\n"
    "options:\n";
static const char render_help_end[] = "\n" CLI_EXIT_HELP;

typedef struct render_request {
    const char *scene_path;
    const char *output;
    const char *exr_output;
    const char *stats_json;
    const char *format_name; /* --format, or NULL */
    int32_t format;          /* HR_FORMAT_*: --format's, or OUT's extension's */
    cli_render_flags flags;
    int png16, linear_png, exr_half, stats, quiet;
    int32_t jpeg_quality; /* 0: the library's default */
} render_request;

/* In --help's order; the entries with no text are the shared render
 * flags (render_flags.c). */
const cli_option cli_render_options[] = {
    {"--output", "-o", 1, "FILE", "the image to write (required; - for standard output)"},
    {"--format", NULL, 1, "NAME", "the image format, whatever OUT's extension: png, exr, ppm, pfm, jpeg, hdr, "
                                  "bmp or tga"},
    {"--jpeg-quality", NULL, 1, "N", "JPEG quality 1..100 (default 90)"},
    {"--window", NULL, 1, NULL, NULL},
    {"--quiet", "-q", 0, NULL, "no summary line, no progress bar (errors and warnings still go to stderr)"},
    {"--exr", NULL, 1, "FILE", "also write the linear image as OpenEXR"},
    {"--size", NULL, 1, NULL, NULL},
    {"--spp", NULL, 1, NULL, NULL},
    {"--threads", NULL, 1, NULL, NULL},
    {"--depth", NULL, 1, NULL, NULL},
    {"--block", NULL, 1, NULL, NULL},
    {"--camera", NULL, 1, NULL, NULL},
    {"--png16", NULL, 0, NULL, "16-bit PNG"},
    {"--linear-png", NULL, 0, NULL, "PNG values written linearly, not sRGB-encoded"},
    {"--exr-half", NULL, 0, NULL, "EXR with 16-bit half floats"},
    {"--effects", NULL, 1, NULL, NULL},
    {"--adaptive", NULL, 1, NULL, NULL},
    {"--min-weight", NULL, 1, NULL, NULL},
    {"--exact", NULL, 0, NULL, NULL},
    {"--stats", NULL, 0, NULL, "also print rays by kind and the effects that ran"},
    {"--stats-json", NULL, 1, "FILE", "write the statistics as one JSON object"},
    {"--help", "-h", 0, NULL, "this help"},
    {NULL, NULL, 0, NULL, NULL},
};

/* `-o -`: the image goes to standard output, and the summary to stderr. */
static int writes_stdout(const render_request *r) { return r->output && !strcmp(r->output, "-"); }

/* Two outputs named alike would overwrite each other (by name only: two
 * spellings of one path are not caught). */
static int check_distinct(const char *option_a, const char *a, const char *option_b, const char *b)
{
    if (a && b && strcmp(a, b) == 0) return cli_usage_error("render: %s and %s both name '%s'", option_a, option_b, a);
    return 0;
}

/* An output that is the scene file itself (by name, or the same file under
 * another name) would be overwritten by the render of it. */
static int check_not_scene(const char *option, const char *output, const char *scene)
{
    if (!output || !scene || !strcmp(output, "-")) return 0;
    struct stat a, b;
    if (strcmp(output, scene) == 0 ||
        (stat(output, &a) == 0 && stat(scene, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino))
        return cli_usage_error("render: %s '%s' is the scene file: the render would overwrite it",
                               option, output);
    return 0;
}

/* What parse_request found: go on, stop after printing the help, or stop
 * with the exit status of the error it reported (CLI_EXIT_USAGE for the
 * command line, CLI_EXIT_ERROR for an output that cannot be written). */
#define PARSE_OK 0
#define PARSE_HELP (-1)

static int parse_request(int argc, char **argv, render_request *r)
{
    memset(r, 0, sizeof *r);
    cli_render_flags_init(&r->flags);
    cli_option options[CLI_TABLE_CAPACITY];
    if (cli_render_flags_table(cli_render_options, CLI_RENDER_FLAGS, options, CLI_TABLE_CAPACITY) < 0)
        return cli_usage_error("render: the option table is too small");
    cli_parser p;
    cli_parser_init(&p, argc, argv, options);
    const char *name, *value;
    int kind, positionals = 0;
    while ((kind = cli_next(&p, &name, &value)) != CLI_END) {
        if (kind == CLI_BAD) return CLI_EXIT_USAGE;
        if (kind == CLI_POSITIONAL) {
            if (positionals++ > 0) return cli_usage_error("render: one scene file only ('%s' is extra)", value);
            r->scene_path = value;
            continue;
        }
        if (!strcmp(name, "--help")) {
            fputs(render_help, stdout);
            cli_print_options(stdout, options);
            fputs(render_help_end, stdout);
            return PARSE_HELP;
        }
        if (cli_render_flag_bit(name)) {
            if (!cli_render_flags_parse(&r->flags, name, value)) return CLI_EXIT_USAGE;
        } else if (!strcmp(name, "--output")) r->output = value;
        else if (!strcmp(name, "--exr")) r->exr_output = value;
        else if (!strcmp(name, "--stats-json")) r->stats_json = value;
        else if (!strcmp(name, "--png16")) r->png16 = 1;
        else if (!strcmp(name, "--linear-png")) r->linear_png = 1;
        else if (!strcmp(name, "--exr-half")) r->exr_half = 1;
        else if (!strcmp(name, "--stats")) r->stats = 1;
        else if (!strcmp(name, "--format")) r->format_name = value;
        else if (!strcmp(name, "--quiet")) r->quiet = 1;
        else if (!strcmp(name, "--jpeg-quality")) {
            if (!cli_parse_int(name, value, 1, 100, &r->jpeg_quality)) return CLI_EXIT_USAGE;
        }
    }
    if (!r->scene_path) return cli_usage_error("render: no scene file given (see 'hitray render --help')");
    if (!r->output) return cli_usage_error("render: no output file given (use -o OUT.png)");
    if (check_not_scene("--output", r->output, r->scene_path) ||
        check_not_scene("--exr", r->exr_output, r->scene_path) ||
        check_not_scene("--stats-json", r->stats_json, r->scene_path))
        return CLI_EXIT_USAGE;
    if (cli_render_flags_check(&r->flags)) return CLI_EXIT_USAGE;
    if (cli_output_format("--output", r->output, r->format_name, &r->format)) return CLI_EXIT_USAGE;
    if (r->jpeg_quality && r->format != HR_FORMAT_JPEG)
        return cli_usage_error("--jpeg-quality: the output '%s' is %s, not JPEG", r->output,
                               hr_image_format_name(r->format));
    /* An image on a terminal is a screenful of noise, and no one meant it. */
    if (writes_stdout(r) && isatty(STDOUT_FILENO))
        return cli_usage_error("render: -o -: standard output is a terminal (redirect it to a file or a pipe)");
    /* --exr always writes OpenEXR: a file named otherwise would lie about
     * its content. */
    size_t exr_len = r->exr_output ? strlen(r->exr_output) : 0;
    if (r->exr_output && *r->exr_output &&
        (exr_len < 4 || strcasecmp(r->exr_output + exr_len - 4, ".exr") != 0))
        return cli_usage_error("--exr: '%s' does not end in .exr", r->exr_output);
    int rc = writes_stdout(r) ? 0 : cli_check_writable("--output", r->output);
    if (!rc && r->exr_output) rc = cli_check_writable("--exr", r->exr_output);
    if (!rc && r->stats_json) rc = cli_check_writable("--stats-json", r->stats_json);
    if (rc) return rc;
    if (check_distinct("--output", r->output, "--exr", r->exr_output) ||
        check_distinct("--output", r->output, "--stats-json", r->stats_json) ||
        check_distinct("--exr", r->exr_output, "--stats-json", r->stats_json))
        return CLI_EXIT_USAGE;
    return PARSE_OK;
}

static uint64_t total_rays(const hr_render_stats *s) { return s->primary + s->shadow + s->reflected + s->refracted; }

/* "2.41 M": rays per second at a glance. */
static void format_rate(char *buf, size_t size, double rate)
{
    if (rate >= 1e9) snprintf(buf, size, "%.2f G", rate / 1e9);
    else if (rate >= 1e6) snprintf(buf, size, "%.2f M", rate / 1e6);
    else if (rate >= 1e3) snprintf(buf, size, "%.2f k", rate / 1e3);
    else snprintf(buf, size, "%.0f ", rate);
}

static void print_effects(FILE *f, uint32_t effects, int as_json)
{
    int first = 1;
    for (int bit = 0; bit < 32; bit++) {
        const char *name = (effects >> bit) & 1u ? hr_effect_name(1u << bit) : NULL;
        if (!name) continue;
        fputs(first ? "" : ", ", f);
        if (as_json) json_string(f, name);
        else fputs(name, f);
        first = 0;
    }
    if (first && !as_json) fputs("none", f);
}

static void print_summary(FILE *f, const render_request *r, const hr_image *image, const hr_render_stats *s)
{
    uint64_t rays = total_rays(s);
    char rate[32];
    format_rate(rate, sizeof rate, s->seconds > 0 ? (double)rays / s->seconds : 0.0);
    fprintf(f, "rendered %dx%d (%d spp) in %.3f s on %d thread%s: %" PRIu64 " rays, %srays/s -> %s%s%s\n",
           (int)hr_image_width(image), (int)hr_image_height(image), (int)r->flags.spp, s->seconds, (int)s->threads,
           s->threads == 1 ? "" : "s", rays, rate, writes_stdout(r) ? "standard output" : r->output,
           r->exr_output ? ", " : "", r->exr_output ? r->exr_output : "");
    if (r->stats) {
        fprintf(f, "rays: primary %" PRIu64 ", shadow %" PRIu64 ", reflected %" PRIu64 ", refracted %" PRIu64 "\n",
               s->primary, s->shadow, s->reflected, s->refracted);
        fputs("effects: ", f);
        print_effects(f, s->effects, 0);
        fputc('\n', f);
        if (r->flags.adaptive > 0)
            fprintf(f, "adaptive: %" PRIu64 " of %" PRIu64 " pixels refined, %" PRId64 " camera rays saved\n",
                   s->pixels_refined, (uint64_t)hr_image_width(image) * (uint64_t)hr_image_height(image),
                   s->samples_saved);
        if (r->flags.min_weight > 0 || s->rays_cut > 0) fprintf(f, "cut-off: %" PRIu64 " rays not traced\n", s->rays_cut);
    }
}

/* The statistics as JSON, in a malloc'd buffer (NULL if out of memory). */
static char *stats_json(const hr_image *image, const hr_render_stats *s, size_t *size)
{
    char *text = NULL;
    FILE *f = open_memstream(&text, size);
    if (!f) return NULL;
    fprintf(f,
            "{\"primary\": %" PRIu64 ", \"shadow\": %" PRIu64 ", \"reflected\": %" PRIu64
            ", \"refracted\": %" PRIu64 ", \"seconds\": ",
            s->primary, s->shadow, s->reflected, s->refracted);
    json_number(f, s->seconds);
    fputs(", \"effects\": [", f);
    print_effects(f, s->effects, 1);
    fprintf(f,
            "], \"pixels_refined\": %" PRIu64 ", \"samples_saved\": %" PRId64 ", \"rays_cut\": %" PRIu64
            ", \"threads\": %d, \"width\": %d, \"height\": %d}\n",
            s->pixels_refined, s->samples_saved, s->rays_cut, (int)s->threads, (int)hr_image_width(image),
            (int)hr_image_height(image));
    if (ferror(f)) {
        fclose(f);
        free(text);
        return NULL;
    }
    fclose(f);
    return text;
}

/* Every output of the command or none (hr_file_batch): the PNG, the EXR and
 * the statistics are each written in full beside their targets before any
 * is put in place, so a full disk while writing the last leaves the old
 * files as they were. */
static int write_outputs(const render_request *r, hr_context *ctx, const hr_image *image,
                         const hr_render_stats *stats, const char *image_path)
{
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.format = r->format;
    o.png_bits = r->png16 ? 16 : 8;
    o.png_linear = r->linear_png;
    o.exr_half = r->exr_half;
    o.jpeg_quality = r->jpeg_quality;
    hr_file_batch *batch = NULL;
    hr_status st = hr_file_batch_create(ctx, &batch);
    if (st == HR_OK) st = hr_file_batch_add_image(batch, image, image_path, &o);
    if (st == HR_OK && r->exr_output) {
        o.format = HR_FORMAT_EXR;
        st = hr_file_batch_add_image(batch, image, r->exr_output, &o);
    }
    if (st == HR_OK && r->stats_json) {
        size_t size = 0;
        char *json = stats_json(image, stats, &size);
        if (!json) {
            hr_file_batch_destroy(batch);
            return cli_error("cannot write '%s': out of memory", r->stats_json);
        }
        st = hr_file_batch_add_bytes(batch, r->stats_json, json, size);
        free(json);
    }
    if (st == HR_OK) st = hr_file_batch_commit(batch);
    hr_file_batch_destroy(batch);
    return st == HR_OK ? 0 : cli_library_error(ctx, st);
}

/* `-o -`: the image is written as a file is (all or nothing, with the
 * other outputs) into a private folder, then copied to standard output.
 * The folder is made before the render, so a $TMPDIR that cannot take it
 * costs nothing. */
typedef struct stdout_image {
    char dir[4096];
    char path[4200];
} stdout_image;

static int stdout_image_begin(stdout_image *t, const render_request *r)
{
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !*tmp) tmp = "/tmp";
    if (snprintf(t->dir, sizeof t->dir, "%s/hitray-render-XXXXXX", tmp) >= (int)sizeof t->dir)
        return cli_error("-o -: TMPDIR '%s' is too long", tmp);
    if (!mkdtemp(t->dir)) return cli_error("-o -: cannot make a folder in '%s': %s", tmp, strerror(errno));
    snprintf(t->path, sizeof t->path, "%s/image%s", t->dir, hr_image_format_extension(r->format));
    return 0;
}

/* The image to standard output, the folder removed first (a closed pipe
 * that kills the process while copying leaves nothing behind). */
static int stdout_image_send(const stdout_image *t)
{
    FILE *f = fopen(t->path, "rb");
    int open_errno = errno;
    remove(t->path);
    rmdir(t->dir);
    if (!f) return cli_error("-o -: cannot read back '%s': %s", t->path, strerror(open_errno));
    char buf[1 << 16];
    size_t n;
    int failed = 0;
    while (!failed && (n = fread(buf, 1, sizeof buf, f)) > 0) failed = fwrite(buf, 1, n, stdout) != n;
    failed = failed || ferror(f);
    fclose(f);
    if (failed || fflush(stdout) != 0) return cli_error("cannot write the image to standard output");
    return 0;
}

static void stdout_image_discard(const stdout_image *t)
{
    remove(t->path);
    rmdir(t->dir);
}

static int render_and_write(const render_request *r, cli_scene *s)
{
    hr_camera cam = cli_render_flags_camera(&r->flags, s);
    if (cli_render_flags_check_window(&r->flags, cam.width, cam.height)) return CLI_EXIT_USAGE;
    stdout_image to_stdout;
    if (writes_stdout(r) && stdout_image_begin(&to_stdout, r)) return CLI_EXIT_ERROR;
    hr_render_options o;
    hr_render_options_default(&o);
    cli_render_flags_apply(&r->flags, &o);
    o.width = cam.width, o.height = cam.height;
    cli_progress progress;
    o.progress = cli_progress_update;
    o.progress_user = &progress;

    hr_render_stats stats;
    memset(&stats, 0, sizeof stats);
    stats.struct_size = sizeof stats;
    hr_image *image = NULL;
    cli_progress_begin(&progress, "rendering");
    hr_status st = hr_render(s->sdl.scene, &cam, &o, &image, &stats);
    /* A signal that kills the process mid-write would leave a temporary file
     * (the library writes beside the target, then renames): SIGTERM, SIGHUP,
     * SIGQUIT and a second Ctrl-C wait until the files are complete. They
     * are held before the bar is cleared, so a cleared bar means "writing,
     * and safe from signals". */
    sigset_t held;
    cli_hold_signals(&held);
    cli_progress_end(&progress);
    int rc = CLI_EXIT_OK;
    if (st == HR_ERROR_CANCELLED && cli_interrupted()) {
        cli_error("render interrupted; nothing written");
        rc = CLI_EXIT_INTERRUPTED;
    } else if (st != HR_OK) {
        rc = cli_library_error(s->ctx, st);
    } else {
        rc = write_outputs(r, s->ctx, image, &stats, writes_stdout(r) ? to_stdout.path : r->output);
        if (!rc && writes_stdout(r)) rc = stdout_image_send(&to_stdout);
    }
    if (writes_stdout(r)) stdout_image_discard(&to_stdout);
    cli_release_signals(&held);
    if (!rc && !r->quiet) print_summary(writes_stdout(r) ? stderr : stdout, r, image, &stats);
    hr_image_destroy(image);
    if (rc) return rc;
    return fflush(stdout) == 0 ? CLI_EXIT_OK : cli_error("cannot write to standard output");
}

int cmd_render(int argc, char **argv)
{
    render_request r;
    int parsed = parse_request(argc, argv, &r);
    if (parsed != PARSE_OK) return parsed == PARSE_HELP ? CLI_EXIT_OK : parsed;
    cli_set_quiet(r.quiet);
    cli_scene s;
    if (cli_scene_load(&s, r.scene_path)) return CLI_EXIT_ERROR;
    int rc = cli_scene_commit(&s) ? CLI_EXIT_ERROR : render_and_write(&r, &s);
    cli_interrupt_release();
    cli_scene_free(&s);
    return rc;
}
