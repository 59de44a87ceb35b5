/* The render flags render, view and savings share (render_flags.h). */
#include <math.h>
#include <string.h>

#include "render_flags.h"

typedef struct render_flag {
    cli_option option;
    unsigned bit;
} render_flag;

/* Each flag as `hitray render --help` describes it; a verb that means
 * something else by one (the viewer's --spp is its final pass's) gives its
 * own text in its own table. */
static const render_flag flags[] = {
    {{"--size", NULL, 1, "WxH", "image size in pixels (default: an NFF file's resolution, else 640x480)"},
     CLI_RF_SIZE},
    {{"--spp", NULL, 1, "N", "samples per pixel (default 1: the pixel centre)"}, CLI_RF_SPP},
    {{"--threads", NULL, 1, "N", "threads (default 0: every core); the image is the same whatever the count"},
     CLI_RF_THREADS},
    {{"--depth", NULL, 1, "N", "recursion depth for reflection and refraction (default: the scene's "
                               "maxRecursionDepth)"},
     CLI_RF_DEPTH},
    {{"--block", NULL, 1, "N", "Hill's blocksize: one ray per NxN pixels (default 1)"}, CLI_RF_BLOCK},
    {{"--camera", NULL, 1, "EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE",
      "eye, look-at point, up vector, vertical view angle in degrees; overrides the scene's camera (a scene "
      "with none is framed automatically)"},
     CLI_RF_CAMERA},
    {{"--effects", NULL, 1, "auto|all",
      "auto (default): run only the effects the scene calls for; all: run every effect's code (same "
      "image), to measure what the analysis saves"},
     CLI_RF_EFFECTS},
    {{"--adaptive", NULL, 1, "T",
      "adaptive supersampling: sample pixel corners, give the --spp pattern (N >= 2) only to pixels whose "
      "corners differ by more than T (0..1, sRGB-encoded)"},
     CLI_RF_ADAPTIVE},
    {{"--min-weight", NULL, 1, "W",
      "trace no reflected or refracted ray whose weight (product of the coefficients on its path) is "
      "below W (default: what is cut of a sample weighs under 2^-24 in all, which changes no pixel of a "
      "normal scene)"},
     CLI_RF_MIN_WEIGHT},
    {{"--exact", NULL, 0, NULL, "trace every contribution, however small (no cut-off, no ray budget)"},
     CLI_RF_EXACT},
    {{"--window", NULL, 1, "X,Y,W,H",
      "render only the W x H pixels whose top left is X,Y (from the image's top left); each is bit for bit "
      "that pixel of the full render"},
     CLI_RF_WINDOW},
    {{"--texture-filter", NULL, 1, "footprint|none",
      "footprint (default): in a scene with a texture, average each texture over the pixel's footprint "
      "(ray differentials through mirrors and glass; mip-maps for pixmaps); none: point-sample it at "
      "the hit"},
     CLI_RF_TEXTURE_FILTER},
};
#define FLAG_COUNT (int)(sizeof flags / sizeof flags[0])

void cli_render_flags_init(cli_render_flags *f)
{
    hr_render_options o;
    hr_render_options_default(&o);
    memset(f, 0, sizeof *f);
    f->width = o.width, f->height = o.height;
    f->spp = o.samples_per_pixel, f->threads = o.threads, f->depth = o.max_depth, f->block = o.block_size;
    f->effects = o.effects;
    f->adaptive = o.adaptive_threshold, f->min_weight = o.min_weight, f->exact = o.exact;
    f->texture_filter = o.texture_filter;
}

static int named(const cli_option *table, const char *name)
{
    for (const cli_option *o = table; o->name; o++)
        if (!strcmp(o->name, name)) return 1;
    return 0;
}

static const render_flag *find_flag(const char *name)
{
    for (int i = 0; i < FLAG_COUNT; i++)
        if (!strcmp(flags[i].option.name, name)) return &flags[i];
    return NULL;
}

int cli_render_flags_table(const cli_option *own, unsigned which, cli_option *out, int capacity)
{
    int n = 0;
    for (const cli_option *o = own; o->name; o++) {
        if (n + 1 >= capacity) return -1;
        out[n] = *o;
        if (!o->help) { /* the shared flag here, in the verb's order */
            const render_flag *shared = find_flag(o->name);
            if (!shared || !(which & shared->bit)) return -1;
            out[n] = shared->option;
        }
        n++;
    }
    for (int i = 0; i < FLAG_COUNT; i++) {
        if (!(which & flags[i].bit) || named(own, flags[i].option.name)) continue;
        if (n + 1 >= capacity) return -1;
        out[n++] = flags[i].option;
    }
    memset(&out[n], 0, sizeof out[n]);
    return n;
}

unsigned cli_render_flag_bit(const char *name)
{
    const render_flag *f = find_flag(name);
    return f ? f->bit : 0;
}

static int parse_effects(const char *option, const char *text, int32_t *out)
{
    if (!strcmp(text, "auto")) *out = HR_EFFECTS_AUTO;
    else if (!strcmp(text, "all")) *out = HR_EFFECTS_ALL;
    else return !cli_usage_error("%s: '%s' is neither 'auto' nor 'all'", option, text);
    return 1;
}

static int parse_texture_filter(const char *option, const char *text, int32_t *out)
{
    if (!strcmp(text, "footprint")) *out = HR_TEXTURE_FILTER_FOOTPRINT;
    else if (!strcmp(text, "none")) *out = HR_TEXTURE_FILTER_NONE;
    else return !cli_usage_error("%s: '%s' is neither 'footprint' nor 'none'", option, text);
    return 1;
}

/* X,Y,W,H: whole pixels, a corner at or right of and below the top left,
 * and at least one pixel (the library reads a side of 0 as "to the edge",
 * which a user writing a size would not mean). */
static int parse_window(const char *option, const char *text, int32_t window[4])
{
    double v[4];
    if (!cli_parse_doubles(option, text, 4, v)) return 0;
    for (int i = 0; i < 4; i++) {
        long min = i < 2 ? 0 : 1;
        if (v[i] < (double)min || v[i] > HR_RENDER_MAX_SIDE || v[i] != floor(v[i]))
            return !cli_usage_error("%s: '%s': X and Y must be whole numbers 0..%d, W and H 1..%d (pixels)",
                                    option, text, HR_RENDER_MAX_SIDE, HR_RENDER_MAX_SIDE);
        window[i] = (int32_t)v[i];
    }
    return 1;
}

int cli_render_flags_parse(cli_render_flags *f, const char *name, const char *value)
{
    unsigned bit = cli_render_flag_bit(name);
    int ok = 1;
    switch (bit) {
    case CLI_RF_SIZE: ok = cli_parse_size(name, value, &f->width, &f->height); break;
    case CLI_RF_SPP: ok = cli_parse_int(name, value, 1, HR_RENDER_MAX_SAMPLES, &f->spp); break;
    case CLI_RF_THREADS: ok = cli_parse_int(name, value, 0, HR_RENDER_MAX_THREADS, &f->threads); break;
    case CLI_RF_DEPTH: ok = cli_parse_int(name, value, 0, HR_MAX_RECURSION_DEPTH, &f->depth); break;
    case CLI_RF_BLOCK: ok = cli_parse_int(name, value, 1, HR_RENDER_MAX_BLOCK, &f->block); break;
    case CLI_RF_CAMERA: ok = cli_parse_doubles(name, value, 10, f->camera); break;
    case CLI_RF_EFFECTS: ok = parse_effects(name, value, &f->effects); break;
    case CLI_RF_ADAPTIVE: ok = cli_parse_fraction(name, value, &f->adaptive); break;
    case CLI_RF_MIN_WEIGHT: ok = cli_parse_fraction(name, value, &f->min_weight); break;
    case CLI_RF_EXACT: f->exact = 1; break;
    case CLI_RF_WINDOW: ok = parse_window(name, value, f->window); break;
    case CLI_RF_TEXTURE_FILTER: ok = parse_texture_filter(name, value, &f->texture_filter); break;
    default: return !cli_usage_error("%s: not a render flag", name); /* a verb's mistake, not the user's */
    }
    if (ok) f->given |= bit;
    return ok;
}

int cli_render_flags_check(const cli_render_flags *f)
{
    if (f->adaptive > 0 && f->spp < 2)
        return cli_usage_error("--adaptive: needs --spp N with N >= 2 (the samples a refined pixel gets)");
    if (f->adaptive > 0 && f->block > 1) return cli_usage_error("--adaptive: cannot be combined with --block");
    if (f->exact && f->min_weight > 0) return cli_usage_error("--exact: cannot be combined with --min-weight");
    return 0;
}

int cli_render_flags_check_window(const cli_render_flags *f, int32_t width, int32_t height)
{
    if (!(f->given & CLI_RF_WINDOW)) return 0;
    const int32_t *w = f->window;
    if ((int64_t)w[0] + w[2] > width || (int64_t)w[1] + w[3] > height)
        return cli_usage_error("--window: %d,%d,%d,%d does not lie inside the %dx%d image", (int)w[0], (int)w[1],
                               (int)w[2], (int)w[3], (int)width, (int)height);
    return 0;
}

void cli_render_flags_apply(const cli_render_flags *f, hr_render_options *o)
{
    o->width = f->width;
    o->height = f->height;
    o->samples_per_pixel = f->spp;
    o->threads = f->threads;
    o->max_depth = f->depth;
    o->block_size = f->block;
    o->effects = f->effects;
    o->adaptive_threshold = f->adaptive;
    o->min_weight = f->min_weight;
    o->exact = f->exact;
    o->window_x = f->window[0];
    o->window_y = f->window[1];
    o->window_width = f->window[2];
    o->window_height = f->window[3];
    o->texture_filter = f->texture_filter;
}

hr_camera cli_render_flags_camera(const cli_render_flags *f, const cli_scene *s)
{
    int32_t width = f->width ? f->width : s->sdl.camera.width;
    int32_t height = f->width ? f->height : s->sdl.camera.height;
    if (f->given & CLI_RF_CAMERA) return cli_camera_from_values(s, f->camera, width, height);
    return cli_scene_camera(s, width, height);
}
