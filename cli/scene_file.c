/* Loading a scene file for the verbs that need one (cli.h). */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"

int cli_is_nff(const char *path)
{
    size_t n = strlen(path);
    return (n >= 4 && strcasecmp(path + n - 4, ".nff") == 0) ||
           (n >= 7 && strcasecmp(path + n - 7, ".nff.gz") == 0);
}

int cli_is_mesh(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && (strcasecmp(path + n - 4, ".obj") == 0 || strcasecmp(path + n - 4, ".3vn") == 0);
}

/* A mesh file given as the scene: an SDL scene of that one mesh (read
 * from the file's own folder), framed by the camera a scene without one
 * gets, and lit by one white light above and behind that camera's eye, so
 * the side in view is lit and its shading shows the form. */
static hr_status load_mesh_scene(cli_scene *s, const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    char dir[4096], text[4200];
    size_t dir_len = slash ? (size_t)(slash - path) : 1;
    if (dir_len >= sizeof dir || strlen(base) + 8 >= sizeof text) {
        snprintf(text, sizeof text, "'%.100s...': the name is too long", path);
        return hr_context_set_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, NULL, 0, 0, text);
    }
    memcpy(dir, slash ? (slash == path ? "/" : path) : ".", slash == path ? 1 : dir_len);
    dir[slash == path ? 1 : dir_len] = '\0';
    if (strpbrk(base, " \t\n\r!\"{}")) {
        snprintf(text, sizeof text,
                 "'%s': a mesh rendered as the scene needs a name without blanks, '!', '\"' or braces "
                 "(write an SDL scene with 'mesh FILE' instead)", path);
        return hr_context_set_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, NULL, 0, 0, text);
    }
    snprintf(text, sizeof text, "mesh %s\n", base);
    hr_status st = hr_sdl_load_string(s->ctx, text, path, dir, &s->sdl);
    if (st != HR_OK) return st;
    hr_camera cam = s->sdl.camera;
    st = hr_scene_frame_camera(s->sdl.scene, &cam);
    if (st != HR_OK) return st;
    hr_vec3 back = {cam.eye.x - cam.look.x, cam.eye.y - cam.look.y, cam.eye.z - cam.look.z};
    double distance = sqrt(back.x * back.x + back.y * back.y + back.z * back.z);
    hr_light light;
    memset(&light, 0, sizeof light);
    light.struct_size = sizeof light;
    light.position = (hr_vec3){cam.eye.x + 0.5 * back.x + distance * cam.up.x,
                               cam.eye.y + 0.5 * back.y + distance * cam.up.y,
                               cam.eye.z + 0.5 * back.z + distance * cam.up.z};
    light.color = (hr_color){1.0, 1.0, 1.0};
    return hr_scene_add_light(s->sdl.scene, &light);
}

/* The library's warnings, one line each on stderr (never stdout, which
 * `hitray hits` and `--json` keep for their records). */
static void print_warning(void *user, const hr_warning *w)
{
    (void)user;
    cli_status(NULL, NULL); /* a status line being shown ends first */
    fprintf(stderr, "hitray: warning: %s\n", w->message);
}

/* Standard input read to its end into a malloc'd, NUL-ended text, or NULL
 * after reporting why not (a read error, a NUL byte: SDL is text). */
static char *read_stdin(void)
{
    size_t size = 0, capacity = 1 << 16;
    char *text = malloc(capacity);
    while (text) {
        if (size + 1 >= capacity) {
            char *grown = capacity <= SIZE_MAX / 2 ? realloc(text, capacity * 2) : NULL;
            if (!grown) break;
            text = grown;
            capacity *= 2;
        }
        size_t n = fread(text + size, 1, capacity - 1 - size, stdin);
        size += n;
        if (n > 0) continue;
        if (ferror(stdin)) {
            cli_error("cannot read the scene from standard input: %s", strerror(errno));
            free(text);
            return NULL;
        }
        text[size] = '\0';
        if (memchr(text, '\0', size)) {
            cli_error("%s: the scene holds a NUL byte (SDL is text)", CLI_STDIN_NAME);
            free(text);
            return NULL;
        }
        return text;
    }
    free(text);
    cli_error("cannot read the scene from standard input: out of memory");
    return NULL;
}

int cli_scene_load(cli_scene *s, const char *path)
{
    memset(s, 0, sizeof *s);
    hr_status st = hr_context_create(&s->ctx);
    if (st != HR_OK) return cli_error("cannot start the library: %s", hr_status_name(st));
    hr_context_set_warning_callback(s->ctx, print_warning, NULL);
    s->sdl.struct_size = sizeof s->sdl;
    int from_stdin = !strcmp(path, "-");
    s->path = from_stdin ? CLI_STDIN_NAME : path;
    char *text = NULL;
    if (from_stdin && !(text = read_stdin())) {
        cli_scene_free(s);
        return CLI_EXIT_ERROR;
    }
    cli_status("loading", s->path);
    if (from_stdin) st = hr_sdl_load_string(s->ctx, text, CLI_STDIN_NAME, NULL, &s->sdl);
    else if (cli_is_nff(path)) st = hr_nff_load_file(s->ctx, path, &s->sdl);
    else if (cli_is_mesh(path)) st = load_mesh_scene(s, path);
    else st = hr_sdl_load_file(s->ctx, path, &s->sdl);
    free(text);
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
