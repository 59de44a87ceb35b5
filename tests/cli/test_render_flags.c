/* The render flags' one parser (cli/render_flags.c) against the library:
 * for every bounded flag, the largest value the parser takes is one
 * hr_render takes too, and one more is refused by both. So a limit changed
 * in the library and not in the command line (or the other way round)
 * fails here; the verbs' use of the one parser is tested by
 * tests/cli/test_cli_render_flags.py. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"
#include "render_flags.h"

static hr_context *ctx;
static cli_scene scene;

static const char scene_text[] = "light 0 5 5 1 1 1\n"
                                 "diffuse 0.8 0.2 0.2\n"
                                 "sphere\n"
                                 "camera 0 0 5 0 0 0 0 1 0 40\n";

/* hr_render with the flags applied, through a 1x1 window at the top left so
 * that the largest image and sample counts cost one pixel. */
static hr_status render_with(const cli_render_flags *f)
{
    hr_camera cam = cli_render_flags_camera(f, &scene);
    hr_render_options o;
    hr_render_options_default(&o);
    cli_render_flags_apply(f, &o);
    o.width = cam.width, o.height = cam.height;
    o.window_width = 1, o.window_height = 1;
    hr_image *image = NULL;
    hr_status st = hr_render(scene.sdl.scene, &cam, &o, &image, NULL);
    hr_image_destroy(image);
    return st;
}

typedef struct bounded_flag {
    const char *name;
    const char *most;   /* the library's limit, as text */
    const char *beyond; /* one past it */
} bounded_flag;

static void check_flag(const bounded_flag *b)
{
    cli_render_flags f;
    cli_render_flags_init(&f);
    CHECK_MSG(cli_render_flags_parse(&f, b->name, b->most), "%s %s refused by the parser", b->name, b->most);
    hr_status st = render_with(&f);
    CHECK_MSG(st == HR_OK, "%s %s taken by the parser, refused by hr_render: %s", b->name, b->most,
              hr_context_last_error(ctx));

    cli_render_flags_init(&f);
    /* The parser's refusal goes to stderr, where the log shows it. */
    CHECK_MSG(!cli_render_flags_parse(&f, b->name, b->beyond), "%s %s taken by the parser", b->name, b->beyond);
    CHECK(!(f.given & cli_render_flag_bit(b->name)));
}

/* What the parser refuses, hr_render refuses too: set past the limit
 * directly, as a caller of the library would. */
static void check_library_refuses(void)
{
    cli_render_flags f;
    cli_render_flags_init(&f);
    f.threads = HR_RENDER_MAX_THREADS + 1;
    CHECK(render_with(&f) == HR_ERROR_INVALID_ARGUMENT);
    cli_render_flags_init(&f);
    f.spp = HR_RENDER_MAX_SAMPLES + 1;
    CHECK(render_with(&f) == HR_ERROR_INVALID_ARGUMENT);
    cli_render_flags_init(&f);
    f.block = HR_RENDER_MAX_BLOCK + 1;
    CHECK(render_with(&f) == HR_ERROR_INVALID_ARGUMENT);
    cli_render_flags_init(&f);
    f.width = HR_RENDER_MAX_SIDE + 1, f.height = 1;
    CHECK(render_with(&f) == HR_ERROR_INVALID_ARGUMENT);
    cli_render_flags_init(&f);
    f.depth = HR_MAX_RECURSION_DEPTH + 1;
    CHECK(render_with(&f) == HR_ERROR_INVALID_ARGUMENT);
}

/* The defaults are hr_render_options_default's, so a verb given no flag
 * renders as a library caller given no option. */
static void check_defaults(void)
{
    cli_render_flags f;
    cli_render_flags_init(&f);
    hr_render_options expected, got;
    hr_render_options_default(&expected);
    hr_render_options_default(&got);
    cli_render_flags_apply(&f, &got);
    CHECK(memcmp(&expected, &got, sizeof got) == 0);
    CHECK(f.given == 0);
}

/* A verb's table: its own options first (one of them may take a flag's
 * name, as savings' --adaptive does), then the flags it asked for, once;
 * an entry with no text puts the shared flag there, and must name one the
 * verb asked for. */
static void check_table(void)
{
    static const cli_option own[] = {{"--output", "-o", 1, "FILE", "where"},
                                     {"--adaptive", NULL, 1, "T[,T...]", "a list"},
                                     {NULL, NULL, 0, NULL, NULL}};
    cli_option table[16];
    int n = cli_render_flags_table(own, CLI_RF_SPP | CLI_RF_ADAPTIVE | CLI_RF_EXACT, table, 16);
    CHECK(n == 4);
    CHECK(!strcmp(table[0].name, "--output") && !strcmp(table[1].name, "--adaptive"));
    CHECK(!strcmp(table[1].help, "a list"));
    CHECK(!strcmp(table[2].name, "--spp") && table[2].takes_value && !strcmp(table[2].value, "N"));
    CHECK(!strcmp(table[3].name, "--exact") && !table[3].takes_value && table[3].help);
    CHECK(table[4].name == NULL);
    CHECK(cli_render_flags_table(own, CLI_RF_SPP | CLI_RF_ADAPTIVE | CLI_RF_EXACT, table, 4) == -1);
    static const cli_option ordered[] = {{"--exact", NULL, 0, NULL, NULL}, {"--output", "-o", 1, "FILE", "where"},
                                         {NULL, NULL, 0, NULL, NULL}};
    CHECK(cli_render_flags_table(ordered, CLI_RF_SPP | CLI_RF_EXACT, table, 16) == 3);
    CHECK(!strcmp(table[0].name, "--exact") && table[0].help && !strcmp(table[2].name, "--spp"));
    CHECK(cli_render_flags_table(ordered, CLI_RF_SPP, table, 16) == -1); /* --exact not asked for */
    static const cli_option stray[] = {{"--output", "-o", 1, "FILE", NULL}, {NULL, NULL, 0, NULL, NULL}};
    CHECK(cli_render_flags_table(stray, CLI_RF_SPP, table, 16) == -1); /* no text, no such flag */
    CHECK(cli_render_flag_bit("--threads") == CLI_RF_THREADS);
    CHECK(cli_render_flag_bit("--output") == 0);
}

/* --help's options block: the text from column 25, wrapped within 78
 * columns, on the next line after an option too long for its column. */
static void check_help(void)
{
    static const cli_option table[] = {
        {"--output", "-o", 1, "FILE", "the image to write"},
        {"--camera", NULL, 1, "EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE", "eye"},
        {"--exact", NULL, 0, NULL,
         "one two three four five six seven eight nine ten eleven twelve thirteen fourteen"},
        {NULL, NULL, 0, NULL, NULL},
    };
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    CHECK(f != NULL);
    cli_print_options(f, table);
    CHECK(fclose(f) == 0);
    CHECK_MSG(text && !strcmp(text, "  -o, --output FILE     the image to write\n"
                    "  --camera EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE\n"
                    "                        eye\n"
                    "  --exact               one two three four five six seven eight nine ten\n"
                    "                        eleven twelve thirteen fourteen\n"),
              "printed:\n%s", text ? text : "(nothing)");
    free(text);
}

static void check_combinations(void)
{
    cli_render_flags f;
    cli_render_flags_init(&f);
    CHECK(cli_render_flags_parse(&f, "--adaptive", "0.1"));
    CHECK(cli_render_flags_check(&f) != 0); /* needs --spp >= 2 */
    CHECK(cli_render_flags_parse(&f, "--spp", "4"));
    CHECK(cli_render_flags_check(&f) == 0);
    CHECK(render_with(&f) == HR_OK);
    cli_render_flags_init(&f);
    CHECK(cli_render_flags_parse(&f, "--exact", NULL));
    CHECK(cli_render_flags_parse(&f, "--min-weight", "0.5"));
    CHECK(cli_render_flags_check(&f) != 0);
    /* --texture-filter: footprint (the default) or none, into the
     * library's field; anything else refused; the library refuses a
     * filter it does not know. */
    cli_render_flags_init(&f);
    CHECK(f.texture_filter == HR_TEXTURE_FILTER_FOOTPRINT);
    CHECK(cli_render_flags_parse(&f, "--texture-filter", "none"));
    hr_render_options o;
    hr_render_options_default(&o);
    cli_render_flags_apply(&f, &o);
    CHECK(o.texture_filter == HR_TEXTURE_FILTER_NONE);
    CHECK(render_with(&f) == HR_OK);
    CHECK(cli_render_flags_parse(&f, "--texture-filter", "footprint"));
    CHECK(f.texture_filter == HR_TEXTURE_FILTER_FOOTPRINT);
    CHECK(!cli_render_flags_parse(&f, "--texture-filter", "trilinear"));
    f.texture_filter = 2;
    CHECK(render_with(&f) == HR_ERROR_INVALID_ARGUMENT);
}

int main(void)
{
    CHECK(hr_context_create(&ctx) == HR_OK);
    scene.ctx = ctx;
    scene.sdl.struct_size = sizeof scene.sdl;
    scene.path = "flags.sdl";
    CHECK(hr_sdl_load_string(ctx, scene_text, scene.path, NULL, &scene.sdl) == HR_OK);
    CHECK(hr_scene_commit(scene.sdl.scene) == HR_OK);

    char side[32], side_beyond[32], samples[16], samples_beyond[16], threads[16], threads_beyond[16];
    char block[16], block_beyond[16], depth[16], depth_beyond[16];
    snprintf(side, sizeof side, "%dx1", HR_RENDER_MAX_SIDE);
    snprintf(side_beyond, sizeof side_beyond, "%dx1", HR_RENDER_MAX_SIDE + 1);
    snprintf(samples, sizeof samples, "%d", HR_RENDER_MAX_SAMPLES);
    snprintf(samples_beyond, sizeof samples_beyond, "%d", HR_RENDER_MAX_SAMPLES + 1);
    snprintf(threads, sizeof threads, "%d", HR_RENDER_MAX_THREADS);
    snprintf(threads_beyond, sizeof threads_beyond, "%d", HR_RENDER_MAX_THREADS + 1);
    snprintf(block, sizeof block, "%d", HR_RENDER_MAX_BLOCK);
    snprintf(block_beyond, sizeof block_beyond, "%d", HR_RENDER_MAX_BLOCK + 1);
    snprintf(depth, sizeof depth, "%d", HR_MAX_RECURSION_DEPTH);
    snprintf(depth_beyond, sizeof depth_beyond, "%d", HR_MAX_RECURSION_DEPTH + 1);
    const bounded_flag bounded[] = {
        {"--size", side, side_beyond},
        {"--spp", samples, samples_beyond},
        {"--threads", threads, threads_beyond},
        {"--block", block, block_beyond},
        {"--depth", depth, depth_beyond},
    };
    for (size_t i = 0; i < sizeof bounded / sizeof bounded[0]; i++) check_flag(&bounded[i]);
    check_library_refuses();
    check_defaults();
    check_table();
    check_help();
    check_combinations();
    cli_scene_free(&scene);
    return hr_test_end();
}
