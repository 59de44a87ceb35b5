/* Loading a scene file for the verbs that need one (cli.h). */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "cli.h"

int cli_is_nff(const char *path)
{
    size_t n = strlen(path);
    return (n >= 4 && strcasecmp(path + n - 4, ".nff") == 0) ||
           (n >= 7 && strcasecmp(path + n - 7, ".nff.gz") == 0);
}

/* The library's warnings, one line each on stderr (never stdout, which
 * `hitray hits` and `--json` keep for their records). */
static void print_warning(void *user, const hr_warning *w)
{
    (void)user;
    cli_status(NULL, NULL); /* a status line being shown ends first */
    fprintf(stderr, "hitray: warning: %s\n", w->message);
}

int cli_scene_load(cli_scene *s, const char *path)
{
    memset(s, 0, sizeof *s);
    hr_status st = hr_context_create(&s->ctx);
    if (st != HR_OK) return cli_error("cannot start the library: %s", hr_status_name(st));
    hr_context_set_warning_callback(s->ctx, print_warning, NULL);
    s->sdl.struct_size = sizeof s->sdl;
    s->path = path;
    cli_status("loading", path);
    st = cli_is_nff(path) ? hr_nff_load_file(s->ctx, path, &s->sdl)
                          : hr_sdl_load_file(s->ctx, path, &s->sdl);
    cli_status(NULL, NULL);
    if (st != HR_OK) {
        int rc = cli_library_error(s->ctx, st);
        cli_scene_free(s);
        return rc;
    }
    return 0;
}

int cli_scene_commit(cli_scene *s)
{
    /* Building the BVH of a large mesh takes seconds. */
    cli_status("building the scene of", s->path);
    hr_status st = hr_scene_commit(s->sdl.scene);
    cli_status(NULL, NULL);
    return st == HR_OK ? 0 : cli_library_error(s->ctx, st);
}

void cli_scene_free(cli_scene *s)
{
    hr_scene_destroy(s->sdl.scene);
    hr_context_destroy(s->ctx);
    memset(s, 0, sizeof *s);
}

hr_camera cli_scene_camera(const cli_scene *s, int32_t width, int32_t height)
{
    hr_camera cam = s->sdl.camera;
    if (!s->sdl.has_camera) hr_scene_frame_camera(s->sdl.scene, &cam);
    cam.width = width;
    cam.height = height;
    return cam;
}

hr_camera cli_camera_from_values(const cli_scene *s, const double c[10], int32_t width, int32_t height)
{
    hr_camera cam = s->sdl.camera;
    cam.eye = (hr_vec3){c[0], c[1], c[2]};
    cam.look = (hr_vec3){c[3], c[4], c[5]};
    cam.up = (hr_vec3){c[6], c[7], c[8]};
    cam.view_angle = c[9];
    cam.width = width;
    cam.height = height;
    return cam;
}
