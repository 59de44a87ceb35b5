/* hitray-view, run as `hitray view` (view.h): the options, the order of the
 * checks, and the event loop.
 *
 * Everything that can be refused is refused before a window opens: the
 * options, a missing display, the scene file (its located error), the
 * camera. So a mistake costs one line on stderr and exit status 2 (a
 * usage error) or 1 (a file, the display), and leaves no window behind. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "render_flags.h"
#include "view.h"
#include "view_window.h"

static const char view_help[] =
    "usage: hitray view SCENE [options]\n"
    "\n"
    "Render the scene file SCENE (Hill's SDL, or NFF if it ends in .nff or\n"
    ".nff.gz) in a window as Hill's raytrace loop does: one ray per 16x16\n"
    "block first, then blocks of 8, 4, 2 and 1 pixels, then the full-quality\n"
    "pass (--spp), each pass replacing the last tile by tile as its tiles\n"
    "finish. Keys fly Hill's camera; every move starts the refinement again\n"
    "(the picture stays until the new camera's tiles replace it). The window's\n"
    "title shows the pass, rays per second, the effects that ran and the\n"
    "time to the final pass. Needs a display (X11 or Wayland).\n"
    "\n"
    "options:\n";

static const char view_help_end[] =
    "\n"
    "The final pass is the image 'hitray render' makes with the same scene,\n"
    "size, --spp, --depth, --block, --min-weight, --exact and camera, bit for\n"
    "bit; a block pass is 'hitray render --block N'.\n"
    "\n";

#define DEFAULT_OUTPUT "hitray-view.png"

typedef struct view_request {
    const char *scene_path;
    const char *output;
    const char *screenshot;
    int exit_when_done;
    cli_render_flags flags;
} view_request;

/* Go on, stop after the help, or stop with the exit status of the error
 * reported. */
#define PARSE_OK 0
#define PARSE_HELP (-1)

static int check_image_file(const char *option, const char *path)
{
    if (!strcmp(path, "-")) return cli_usage_error("%s: the viewer saves to files, not to standard output", option);
    int32_t format;
    int rc = cli_output_format(option, path, NULL, &format);
    return rc ? rc : cli_check_writable(option, path);
}

static int parse_request(int argc, char **argv, view_request *r)
{
    memset(r, 0, sizeof *r);
    cli_render_flags_init(&r->flags);
    r->output = DEFAULT_OUTPUT;
    cli_option options[CLI_TABLE_CAPACITY];
    if (cli_render_flags_table(cli_view_options, CLI_VIEW_FLAGS, options, CLI_TABLE_CAPACITY) < 0)
        return cli_error("view: the option table is too small");
    cli_parser p;
    cli_parser_init(&p, argc, argv, options);
    const char *name, *value;
    int kind, positionals = 0, output_given = 0;
    while ((kind = cli_next(&p, &name, &value)) != CLI_END) {
        if (kind == CLI_BAD) return CLI_EXIT_USAGE;
        if (kind == CLI_POSITIONAL) {
            if (positionals++ > 0) return cli_usage_error("view: one scene file only ('%s' is extra)", value);
            r->scene_path = value;
            continue;
        }
        if (!strcmp(name, "--help")) {
            fputs(view_help, stdout);
            cli_print_options(stdout, options);
            fputs(view_help_end, stdout);
            fputs(view_keys_help, stdout);
            return PARSE_HELP;
        }
        int ok = 1;
        if (cli_render_flag_bit(name)) ok = cli_render_flags_parse(&r->flags, name, value);
        else if (!strcmp(name, "--output")) r->output = value, output_given = 1;
        else if (!strcmp(name, "--screenshot")) r->screenshot = value;
        else if (!strcmp(name, "--exit-when-done")) r->exit_when_done = 1;
        if (!ok) return CLI_EXIT_USAGE;
    }
    if (!r->scene_path) return cli_usage_error("view: no scene file given (see 'hitray view --help')");
    /* The default -o is checked when P is pressed: a viewer started in a
     * read-only directory is still of use. */
    int rc = output_given ? check_image_file("--output", r->output) : 0;
    if (!rc && r->screenshot) rc = check_image_file("--screenshot", r->screenshot);
    if (rc) return rc;
    if (cli_render_flags_check(&r->flags)) return CLI_EXIT_USAGE;
    if (r->exit_when_done && !r->screenshot)
        return cli_usage_error("--exit-when-done: needs --screenshot FILE (else the final pass would be lost)");
    return PARSE_OK;
}

/* The video drivers to try, from the environment: SDL would otherwise go on
 * from an unreachable display to drivers that draw nowhere (offscreen) and
 * show no window at all. A chosen SDL_VIDEODRIVER is left for SDL to judge.
 * Without any display, say so (SDL would say "No available video device").
 * 0 and `drivers` filled, or the error reported. */
static int choose_drivers(char *drivers, size_t size)
{
    const char *chosen = getenv("SDL_VIDEODRIVER");
    const char *x11 = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    drivers[0] = '\0';
    if (chosen && *chosen) return 0;
    int has_x11 = x11 && *x11, has_wayland = wayland && *wayland;
    if (!has_x11 && !has_wayland)
        return cli_error("view: no display to open a window on (neither DISPLAY nor WAYLAND_DISPLAY is set); "
                         "'hitray render' writes the image to a file instead");
    snprintf(drivers, size, "%s%s%s", has_wayland ? "wayland" : "", has_wayland && has_x11 ? "," : "",
             has_x11 ? "x11" : "");
    return 0;
}

/* Where the window was to go, for the message when it cannot. */
static void describe_display(char *buf, size_t size)
{
    const char *chosen = getenv("SDL_VIDEODRIVER");
    const char *x11 = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    if (chosen && *chosen) snprintf(buf, size, "SDL_VIDEODRIVER '%s'", chosen);
    else if (wayland && *wayland && x11 && *x11)
        snprintf(buf, size, "WAYLAND_DISPLAY '%s' or DISPLAY '%s'", wayland, x11);
    else if (wayland && *wayland) snprintf(buf, size, "WAYLAND_DISPLAY '%s'", wayland);
    else snprintf(buf, size, "DISPLAY '%s'", x11 ? x11 : "");
}

/* --- the running viewer --- */

typedef struct viewer {
    const view_request *req;
    cli_scene scene;
    hr_camera camera;       /* the newest, which the render thread refines */
    view_steps steps;
    view_pass plan[VIEW_MAX_PASSES];
    int passes;
    view_renderer *renderer;
    view_window window;
    uint32_t wake_event;
    uint64_t generation;    /* the newest camera's refinement */
    view_frame shown;       /* what the window shows (image NULL: nothing yet) */
    int shown_current;      /* shown is of the newest camera */
    char error[1024];       /* the newest camera's render error, "" if none */
    char title[1024];
    int woken;              /* the render thread has news (tiles, a frame, an error) */
    uint32_t last_draw;     /* SDL_GetTicks() of the last draw */
    int quit, status;
} viewer;

static void wake_window(void *user)
{
    const viewer *v = user;
    SDL_Event e;
    memset(&e, 0, sizeof e);
    e.type = v->wake_event;
    SDL_PushEvent(&e); /* thread-safe; a full queue only delays the frame to the next poll */
}

static void print_line(const char *text)
{
    fputs(text, stdout);
    fputc('\n', stdout);
    fflush(stdout); /* scripts (and the tests) read it as it comes */
}

/* Write the frame shown; 0 on success (and the line printed). */
static int save_frame(viewer *v, const char *path, const char *verb)
{
    if (!v->shown.image) return cli_error("view: no picture to save yet");
    hr_status st = hr_image_write(v->scene.ctx, v->shown.image, path, NULL);
    if (st != HR_OK) return cli_library_error(v->scene.ctx, st);
    char camera[512];
    view_camera_line(&v->shown.camera, camera, sizeof camera);
    printf("%s %s: ", verb, path); /* a path of any length, whole */
    print_line(camera);
    return 0;
}

static int file_exists(const char *path, void *user)
{
    (void)user;
    return access(path, F_OK) == 0;
}

/* P: the picture shown into -o's file, or the first numbered name beside it
 * no file has yet. */
static void save_numbered(viewer *v)
{
    char path[PATH_MAX];
    if (!view_save_path(v->req->output, file_exists, NULL, path, sizeof path))
        cli_error("view: no free name to save to beside '%s'", v->req->output);
    else
        save_frame(v, path, "saved");
}

/* The tiles finished since the last call into the texture, and the window
 * drawn. `all`: the whole picture (the first draw). */
static void show_tiles(viewer *v, int all)
{
    view_rect changed;
    const uint8_t *pixels = view_renderer_take_pixels(v->renderer, &changed);
    if (all) changed = (view_rect){0, 0, v->window.width, v->window.height};
    view_window_update(&v->window, pixels, &changed);
    v->last_draw = SDL_GetTicks();
    v->woken = 0;
}

static void take_frames(viewer *v)
{
    view_frame frame;
    int final = 0;
    while (view_renderer_take(v->renderer, &frame)) {
        hr_image_destroy(v->shown.image);
        v->shown = frame;
        v->shown_current = frame.generation == v->generation;
        final = v->shown_current && frame.pass == frame.passes - 1;
    }
    /* The window shows the passes tile by tile; a frame's tiles are all in
     * by the time it is handed out, so the final pass is on the screen
     * before it is written. */
    show_tiles(v, 0);
    if (final && v->req->screenshot) {
        int failed = save_frame(v, v->req->screenshot, "wrote") != 0;
        if (v->req->exit_when_done) v->quit = 1, v->status = failed ? CLI_EXIT_ERROR : CLI_EXIT_OK;
    }
    char message[sizeof v->error];
    if (!v->error[0] && view_renderer_error(v->renderer, message, sizeof message)) {
        memcpy(v->error, message, sizeof message);
        cli_error("%s", message);
        if (v->req->exit_when_done) v->quit = 1, v->status = CLI_EXIT_ERROR;
    }
}

static view_action key_action(SDL_Keycode key)
{
    switch (key) {
    case SDLK_w: return VIEW_FORWARD;
    case SDLK_s: return VIEW_BACK;
    case SDLK_a: return VIEW_LEFT;
    case SDLK_d: return VIEW_RIGHT;
    case SDLK_r: return VIEW_UP;
    case SDLK_f: return VIEW_DOWN;
    case SDLK_LEFT: return VIEW_YAW_LEFT;
    case SDLK_RIGHT: return VIEW_YAW_RIGHT;
    case SDLK_UP: return VIEW_PITCH_UP;
    case SDLK_DOWN: return VIEW_PITCH_DOWN;
    case SDLK_q: return VIEW_ROLL_LEFT;
    case SDLK_e: return VIEW_ROLL_RIGHT;
    case SDLK_LEFTBRACKET: return VIEW_FINER;
    case SDLK_RIGHTBRACKET: return VIEW_COARSER;
    case SDLK_c: return VIEW_PRINT_CAMERA;
    case SDLK_p: return VIEW_SAVE;
    case SDLK_h: return VIEW_HELP;
    case SDLK_ESCAPE: return VIEW_QUIT;
    default: return VIEW_NONE;
    }
}

static void on_key(viewer *v, SDL_Keycode key)
{
    view_action action = key_action(key);
    char line[512];
    switch (action) {
    case VIEW_NONE: return;
    case VIEW_QUIT: v->quit = 1; return;
    case VIEW_HELP: fputs(view_keys_help, stdout), fflush(stdout); return;
    case VIEW_PRINT_CAMERA:
        view_camera_line(&v->camera, line, sizeof line);
        print_line(line);
        view_camera_option(&v->camera, line, sizeof line);
        print_line(line);
        return;
    case VIEW_SAVE: save_numbered(v); return;
    default: break;
    }
    if (!view_apply(action, &v->camera, &v->steps)) return; /* a step change */
    v->generation = view_renderer_restart(v->renderer, &v->camera);
    v->shown_current = 0;
    v->error[0] = '\0';
}

static void update_title(viewer *v)
{
    view_status s;
    memset(&s, 0, sizeof s);
    s.scene_name = v->req->scene_path;
    s.has_frame = v->shown.image && v->shown_current;
    s.last = v->shown;
    s.passes = v->passes;
    view_renderer_progress(v->renderer, &s.running_pass, &s.running_fraction);
    s.plan = v->plan;
    s.width = v->camera.width, s.height = v->camera.height;
    s.steps = v->steps;
    s.error = v->error[0] ? v->error : NULL;
    char title[sizeof v->title];
    view_status_text(&s, title, sizeof title);
    if (strcmp(title, v->title) != 0) {
        memcpy(v->title, title, sizeof title);
        view_window_title(&v->window, title);
    }
}

static void handle(viewer *v, const SDL_Event *e)
{
    if (e->type == SDL_QUIT) v->quit = 1;
    else if (e->type == SDL_KEYDOWN) on_key(v, e->key.keysym.sym);
    else if (e->type == SDL_WINDOWEVENT) view_window_redraw(&v->window);
    else if (e->type == v->wake_event) v->woken = 1;
}

/* Title updates while a pass runs: often enough to read as live. */
#define TITLE_INTERVAL_MS 100
/* Tiles finish far faster than a screen shows them (hundreds a second in
 * the block passes): draw what came at most this often. */
#define DRAW_INTERVAL_MS 15

static void event_loop(viewer *v)
{
    while (!v->quit) {
        int wait = TITLE_INTERVAL_MS;
        if (v->woken) {
            int32_t since = (int32_t)(SDL_GetTicks() - v->last_draw);
            wait = since >= DRAW_INTERVAL_MS ? 0 : DRAW_INTERVAL_MS - since;
        }
        SDL_Event e;
        if (SDL_WaitEventTimeout(&e, wait)) {
            handle(v, &e);
            while (!v->quit && SDL_PollEvent(&e)) handle(v, &e);
        }
        if (v->woken && (int32_t)(SDL_GetTicks() - v->last_draw) >= DRAW_INTERVAL_MS) take_frames(v);
        update_title(v);
    }
}

static int run(viewer *v)
{
    const view_request *r = v->req;
    hr_render_options o;
    hr_render_options_default(&o);
    cli_render_flags_apply(&r->flags, &o); /* the plan sets each pass's block size and samples */
    o.width = v->camera.width;
    o.height = v->camera.height;
    v->passes = view_pass_plan(r->flags.block, r->flags.spp, v->plan);
    v->steps = view_steps_for(&v->camera);
    v->wake_event = SDL_RegisterEvents(1);
    if (v->wake_event == (uint32_t)-1) return cli_error("view: SDL has no event type left for the render thread");
    snprintf(v->title, sizeof v->title, "hitray view: %s", r->scene_path);
    if (view_window_open(&v->window, v->camera.width, v->camera.height, v->title)) return CLI_EXIT_ERROR;
    v->generation = 1;
    v->renderer = view_renderer_start(v->scene.sdl.scene, v->scene.ctx, &o, v->plan, v->passes, &v->camera,
                                      wake_window, v);
    if (!v->renderer) {
        view_window_close(&v->window);
        return cli_error("view: cannot start the render thread");
    }
    show_tiles(v, 1); /* black, and whatever tiles are in already */
    event_loop(v);
    view_renderer_stop(v->renderer);
    hr_image_destroy(v->shown.image);
    view_window_close(&v->window);
    return v->status;
}

int main(int argc, char **argv)
{
    /* Messages name the verb the user typed, however this was started. */
    char verb[] = "view";
    if (argc > 0) argv[0] = verb;
    view_request req;
    int parsed = parse_request(argc, argv, &req);
    if (parsed != PARSE_OK) return parsed == PARSE_HELP ? CLI_EXIT_OK : parsed;
    char drivers[32];
    if (choose_drivers(drivers, sizeof drivers)) return CLI_EXIT_ERROR;

    viewer v;
    memset(&v, 0, sizeof v);
    v.req = &req;
    if (cli_scene_load(&v.scene, req.scene_path)) return CLI_EXIT_ERROR;
    int rc = cli_scene_commit(&v.scene);
    if (!rc) {
        v.camera = cli_render_flags_camera(&req.flags, &v.scene);
        hr_status st = hr_camera_validate(v.scene.ctx, &v.camera);
        if (st != HR_OK) rc = cli_library_error(v.scene.ctx, st);
    }
    if (!rc && drivers[0]) SDL_SetHint(SDL_HINT_VIDEODRIVER, drivers);
    if (!rc && SDL_Init(SDL_INIT_VIDEO) != 0) {
        char where[512];
        describe_display(where, sizeof where);
        rc = cli_error("view: cannot open a window on %s: %s", where, SDL_GetError());
    }
    if (!rc) {
        rc = run(&v);
        SDL_Quit();
    }
    cli_scene_free(&v.scene);
    return rc;
}
