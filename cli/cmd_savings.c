/* hitray savings: what each opt-in saving saves in rays and costs in error.
 *
 * The scene is rendered in full (the reference), then with every effect's
 * code forced on (what the effect analysis saves: the same image, more
 * rays), with adaptive supersampling, with the contribution cut-off, and
 * with both. Each row says how many rays it cast, how many fewer than the
 * reference, and how far its image is from the reference's. Nothing is
 * written but the report: the numbers come from the renders themselves. */
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "render_flags.h"

static const char savings_help[] =
    "usage: hitray savings SCENE [options]\n"
    "\n"
    "Render SCENE in full, then with each saving, and print per render the rays\n"
    "cast, the rays saved against the full render, and the error against it.\n"
    "Error is measured per channel of each pixel as shown: the sRGB-encoded\n"
    "value clamped to 0..1 (the PNG's value before rounding). rmse is over\n"
    "every channel of every pixel; max is the largest; differing counts the\n"
    "pixels with any channel not bit-identical.\n"
    "\n"
    "rows:\n"
    "  full                  the reference: --spp samples in every pixel, every\n"
    "                        reflected and refracted ray the scene calls for\n"
    "  effects-all           every effect's code forced on: the same image; the\n"
    "                        rays it adds are what the effect analysis saves\n"
    "  adaptive              one row per --adaptive value (none for 0)\n"
    "  min-weight            one row per --min-weight value (none for 0)\n"
    "  both                  adaptive and min-weight together (when each has\n"
    "                        one value)\n"
    "\n"
    "options:\n";

#define MAX_VALUES 8

typedef struct savings_request {
    const char *scene_path;
    cli_render_flags flags; /* size, spp, depth, threads */
    double adaptive[MAX_VALUES], min_weight[MAX_VALUES];
    int adaptive_count, min_weight_count;
    int json;
} savings_request;

/* "0.02,0.05,0.1": each a number within 0..1; 0 adds no row. */
static int parse_values(const char *option, const char *text, double *out, int *count)
{
    char item[64];
    *count = 0;
    for (const char *p = text;;) {
        const char *comma = strchr(p, ',');
        size_t n = comma ? (size_t)(comma - p) : strlen(p);
        if (*count == MAX_VALUES) return !cli_usage_error("%s: at most %d values", option, MAX_VALUES);
        if (n >= sizeof item) return !cli_usage_error("%s: '%s' is not a list of numbers", option, text);
        memcpy(item, p, n);
        item[n] = '\0';
        double v;
        if (!cli_parse_fraction(option, item, &v)) return 0;
        if (v > 0) out[(*count)++] = v;
        if (!comma) return 1;
        p = comma + 1;
    }
}

/* --adaptive and --min-weight are savings' own: each takes a list, a row
 * per value. */
const cli_option cli_savings_options[] = {
    {"--size", NULL, 1, "WxH", "image size in pixels (default 320x240)"},
    {"--spp", NULL, 1, "N", "samples per pixel of the full render, and of the pixels adaptive supersampling "
                            "refines (default 16)"},
    {"--adaptive", NULL, 1, "T[,T...]", "adaptive thresholds, 0..1 (default 0.05); up to 8"},
    {"--min-weight", NULL, 1, "W[,W...]", "contribution cut-offs, 0..1 (default 0.05); up to 8"},
    {"--depth", NULL, 1, "N", "recursion depth (default: the scene's)"},
    {"--threads", NULL, 1, "N", "threads (default 0: every core); the numbers are the same whatever the count"},
    {"--json", NULL, 0, NULL, "one JSON object per row instead of the table"},
    {"--help", "-h", 0, NULL, "this help"},
    {NULL, NULL, 0, NULL, NULL},
};

/* 0: go on; -1: stop with success (help printed); else the exit status of
 * the error reported (CLI_EXIT_USAGE). */
static int parse_request(int argc, char **argv, savings_request *r)
{
    memset(r, 0, sizeof *r);
    cli_render_flags_init(&r->flags);
    r->flags.width = 320, r->flags.height = 240, r->flags.spp = 16;
    r->adaptive[0] = 0.05, r->min_weight[0] = 0.05;
    r->adaptive_count = r->min_weight_count = 1;
    cli_option options[CLI_TABLE_CAPACITY];
    if (cli_render_flags_table(cli_savings_options, CLI_SAVINGS_FLAGS, options, CLI_TABLE_CAPACITY) < 0)
        return cli_error("savings: the option table is too small");
    cli_parser p;
    cli_parser_init(&p, argc, argv, options);
    const char *name, *value;
    int kind;
    while ((kind = cli_next(&p, &name, &value)) != CLI_END) {
        if (kind == CLI_BAD) return CLI_EXIT_USAGE;
        if (kind == CLI_POSITIONAL) {
            if (r->scene_path) return cli_usage_error("savings: one scene file only ('%s' is extra)", value);
            r->scene_path = value;
            continue;
        }
        if (!strcmp(name, "--help")) {
            fputs(savings_help, stdout);
            cli_print_options(stdout, options);
            return -1;
        }
        /* Its own options first: --adaptive and --min-weight are also render
         * flags' names. */
        int ok = 1;
        if (!strcmp(name, "--adaptive")) ok = parse_values(name, value, r->adaptive, &r->adaptive_count);
        else if (!strcmp(name, "--min-weight"))
            ok = parse_values(name, value, r->min_weight, &r->min_weight_count);
        else if (!strcmp(name, "--json")) r->json = 1;
        else ok = cli_render_flags_parse(&r->flags, name, value);
        if (!ok) return CLI_EXIT_USAGE;
    }
    if (!r->scene_path) return cli_usage_error("savings: no scene file given (see 'hitray savings --help')");
    /* Adaptive supersampling, a row of every report, refines with --spp. */
    if (r->flags.spp < 2)
        return cli_usage_error("--spp: savings needs N >= 2 (the samples a refined pixel gets), not %d",
                               (int)r->flags.spp);
    return 0;
}

/* The sRGB curve (IEC 61966-2-1) of a value clamped to [0, 1]: the value a
 * PNG shows, before it is rounded to a code. */
static double shown(float linear)
{
    double v = linear > 0.0f ? (linear < 1.0f ? (double)linear : 1.0) : 0.0;
    if (v == 1.0) return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

typedef struct difference {
    double rmse, max;
    uint64_t differing; /* pixels with any channel not bit-identical */
} difference;

static difference compare(hr_image *reference, hr_image *image)
{
    difference d = {0, 0, 0};
    size_t pixels = (size_t)hr_image_width(reference) * (size_t)hr_image_height(reference);
    const float *a = hr_image_data(reference), *b = hr_image_data(image);
    double sum = 0.0;
    for (size_t i = 0; i < pixels; i++) {
        int same = 1;
        for (int c = 0; c < 3; c++) {
            same &= memcmp(&a[3 * i + c], &b[3 * i + c], sizeof(float)) == 0;
            double e = fabs(shown(a[3 * i + c]) - shown(b[3 * i + c]));
            sum += e * e;
            if (e > d.max) d.max = e;
        }
        d.differing += !same;
    }
    d.rmse = sqrt(sum / (3.0 * (double)pixels));
    return d;
}

typedef struct row {
    const char *name;
    double parameter; /* the threshold or weight; NAN for none */
    hr_render_stats stats;
    difference error;
} row;

static uint64_t total_rays(const hr_render_stats *s) { return s->primary + s->shadow + s->reflected + s->refracted; }

static void print_json_row(const row *w, const row *full)
{
    fputs("{\"render\": ", stdout);
    json_string(stdout, w->name);
    fputs(", \"parameter\": ", stdout);
    json_number(stdout, w->parameter);
    const hr_render_stats *s = &w->stats;
    printf(", \"rays\": %" PRIu64 ", \"primary\": %" PRIu64 ", \"shadow\": %" PRIu64 ", \"reflected\": %" PRIu64
           ", \"refracted\": %" PRIu64 ", \"rays_saved\": %" PRId64 ", \"pixels_refined\": %" PRIu64
           ", \"rays_cut\": %" PRIu64 ", \"rmse\": ",
           total_rays(s), s->primary, s->shadow, s->reflected, s->refracted,
           (int64_t)(total_rays(&full->stats) - total_rays(s)), s->pixels_refined, s->rays_cut);
    json_number(stdout, w->error.rmse);
    fputs(", \"max_error\": ", stdout);
    json_number(stdout, w->error.max);
    printf(", \"pixels_differing\": %" PRIu64 "}\n", w->error.differing);
}

static void print_table(const savings_request *r, const row *rows, int n)
{
    printf("%s: %dx%d, %d spp\n", r->scene_path, (int)r->flags.width, (int)r->flags.height, (int)r->flags.spp);
    printf("%-18s %12s %12s %8s %10s %10s %10s\n", "render", "rays", "saved", "saved%", "rmse", "max", "differing");
    uint64_t full = total_rays(&rows[0].stats);
    for (int i = 0; i < n; i++) {
        char label[64];
        if (isnan(rows[i].parameter)) snprintf(label, sizeof label, "%s", rows[i].name);
        else snprintf(label, sizeof label, "%s %g", rows[i].name, rows[i].parameter);
        uint64_t rays = total_rays(&rows[i].stats);
        int64_t saved = (int64_t)(full - rays);
        printf("%-18s %12" PRIu64 " %12" PRId64 " %7.1f%% %10.6f %10.6f %10" PRIu64 "\n", label, rays, saved,
               full ? 100.0 * (double)saved / (double)full : 0.0, rows[i].error.rmse, rows[i].error.max,
               rows[i].error.differing);
    }
}

static int render_row(const savings_request *r, cli_scene *s, const hr_camera *cam, row *w, hr_image **image,
                      int32_t effects, double adaptive, double min_weight)
{
    hr_render_options o;
    hr_render_options_default(&o);
    cli_render_flags_apply(&r->flags, &o);
    o.effects = effects;
    o.adaptive_threshold = adaptive;
    o.min_weight = min_weight;
    o.exact = min_weight == 0.0; /* the rows without a cut-off are the exact reference */
    memset(&w->stats, 0, sizeof w->stats);
    w->stats.struct_size = sizeof w->stats;
    /* Each row's render has its own bar, named by the row. */
    char label[96];
    if (isnan(w->parameter)) snprintf(label, sizeof label, "savings: %s", w->name);
    else snprintf(label, sizeof label, "savings: %s %g", w->name, w->parameter);
    cli_progress progress;
    o.progress = cli_progress_update;
    o.progress_user = &progress;
    cli_progress_begin(&progress, label);
    hr_status st = hr_render(s->sdl.scene, cam, &o, image, &w->stats);
    cli_progress_end(&progress);
    cli_interrupt_release();
    if (st == HR_ERROR_CANCELLED && cli_interrupted()) {
        cli_error("savings interrupted");
        return CLI_EXIT_INTERRUPTED;
    }
    return st == HR_OK ? 0 : cli_library_error(s->ctx, st);
}

typedef struct variant {
    const char *name;
    double parameter; /* NAN: none to show */
    int32_t effects;
    double adaptive, min_weight;
} variant;

static int run_savings(const savings_request *r, cli_scene *s)
{
    hr_camera cam = cli_render_flags_camera(&r->flags, s);
    variant variants[3 + 2 * MAX_VALUES];
    int nv = 0;
    variants[nv++] = (variant){"effects-all", NAN, HR_EFFECTS_ALL, 0, 0};
    for (int i = 0; i < r->adaptive_count; i++)
        variants[nv++] = (variant){"adaptive", r->adaptive[i], HR_EFFECTS_AUTO, r->adaptive[i], 0};
    for (int i = 0; i < r->min_weight_count; i++)
        variants[nv++] = (variant){"min-weight", r->min_weight[i], HR_EFFECTS_AUTO, 0, r->min_weight[i]};
    if (r->adaptive_count == 1 && r->min_weight_count == 1)
        variants[nv++] = (variant){"both", NAN, HR_EFFECTS_AUTO, r->adaptive[0], r->min_weight[0]};
    row rows[4 + 2 * MAX_VALUES];
    int n = 0;
    hr_image *reference = NULL;
    rows[n] = (row){"full", NAN, {0}, {0, 0, 0}};
    int rc = render_row(r, s, &cam, &rows[n++], &reference, HR_EFFECTS_AUTO, 0, 0);
    if (rc) return rc;
    for (int i = 0; i < nv && !rc; i++) {
        const variant *v = &variants[i];
        row *w = &rows[n];
        w->name = v->name;
        w->parameter = v->parameter;
        hr_image *image = NULL;
        rc = render_row(r, s, &cam, w, &image, v->effects, v->adaptive, v->min_weight);
        if (rc) break;
        w->error = compare(reference, image);
        hr_image_destroy(image);
        n++;
    }
    hr_image_destroy(reference);
    if (rc) return rc;
    if (r->json) {
        for (int i = 0; i < n; i++) print_json_row(&rows[i], &rows[0]);
    } else {
        print_table(r, rows, n);
    }
    return fflush(stdout) == 0 ? CLI_EXIT_OK : cli_error("cannot write to standard output");
}

int cmd_savings(int argc, char **argv)
{
    savings_request r;
    int parsed = parse_request(argc, argv, &r);
    if (parsed) return parsed < 0 ? CLI_EXIT_OK : parsed;
    cli_scene s;
    if (cli_scene_load(&s, r.scene_path)) return CLI_EXIT_ERROR;
    int rc = cli_scene_commit(&s) ? CLI_EXIT_ERROR : run_savings(&r, &s);
    cli_scene_free(&s);
    return rc;
}
