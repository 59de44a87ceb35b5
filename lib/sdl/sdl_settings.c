/* SDL's scene settings (lib/sdl/sdl_reader.h): globals, lights and the camera.
 * None of them is moved by the transform stack: lights and the camera are in
 * world coordinates, as in Hill's reader.
 *
 * The thresholds minReflectivity / minTransparency and maxRecursionDepth are
 * stored as written in hr_scene_globals; the library's shading decides with
 * them (a reflected or transmitted ray only where the coefficient is at least
 * the threshold and the depth is below the maximum). The reader only checks
 * that the depth is a whole number >= 0. */
#include <stdint.h>
#include <string.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_reader.h"
#include "sdl/sdl_words.h"

hr_status sdl_cmd_global_color(sdl_reader *r, sdl_located keyword)
{
    hr_status st = sdl_read_field(r, keyword, &hri_globals_field_table, &r->globals, NULL);
    if (st) return st;
    /* Hand them over now, so that a colour the scene refuses is reported
     * here rather than at the end of the file. */
    if ((st = hr_scene_set_globals(r->scene, &r->globals)))
        return sdl_error(r->src, st, keyword, "%s", hr_context_last_error(r->ctx));
    return HR_OK;
}

hr_status sdl_cmd_global_threshold(sdl_reader *r, sdl_located keyword)
{
    return sdl_read_field(r, keyword, &hri_globals_field_table, &r->globals, NULL);
}

hr_status sdl_cmd_max_recursion_depth(sdl_reader *r, sdl_located keyword)
{
    int64_t depth;
    hr_status st = sdl_read_whole(r, keyword, 0.0, (double)HR_MAX_RECURSION_DEPTH, &depth);
    if (st) return st;
    r->globals.max_recursion_depth = (int32_t)depth;
    return HR_OK;
}

/* light x y z r g b: a point light at a world position. */
hr_status sdl_cmd_light(sdl_reader *r, sdl_located keyword)
{
    double v[6];
    hr_status st = sdl_read_numbers(r, keyword, 6, v);
    if (st) return st;
    hr_light light;
    memset(&light, 0, sizeof light);
    light.struct_size = sizeof light;
    light.position = (hr_vec3){v[0], v[1], v[2]};
    light.color = (hr_color){v[3], v[4], v[5]};
    if ((st = hr_scene_add_light(r->scene, &light)))
        return sdl_error(r->src, st, keyword, "%s", hr_context_last_error(r->ctx));
    return HR_OK;
}

/* The project's extension (Hill fixed the camera in C++):
 *   camera ex ey ez  lx ly lz  ux uy uz  viewAngle
 * eye, look-at point, up vector, vertical view angle in degrees. The image
 * size stays 640x480; a later `camera` replaces an earlier one. */
hr_status sdl_cmd_camera(sdl_reader *r, sdl_located keyword)
{
    double v[10];
    for (int i = 0; i < 10; i++) {
        sdl_located at = {NULL, -1}; /* stays so when no token could be read */
        hr_status st = sdl_read_number(r, keyword, &v[i], &at);
        /* Hill's gluLookAt has 9 numbers; this keyword adds the angle. Say
         * how many it takes when some came and then no more. */
        double ignored;
        int not_a_number = at.token && (at.token->kind != SDL_TOKEN_WORD ||
                                        sdl_parse_number(at.token->text, &ignored) ==
                                            SDL_NUMBER_NOT_A_NUMBER);
        if (st == HR_ERROR_SDL && i > 0 && not_a_number) {
            char found[64];
            return sdl_error(r->src, HR_ERROR_SDL, at,
                             "'camera' takes 10 numbers (eye x y z, look-at x y z, up x y z, view "
                             "angle in degrees), found %d before %s",
                             i, sdl_describe(at.token, found, sizeof found));
        }
        if (st) return st;
    }
    hr_camera cam = r->camera;
    cam.eye = (hr_vec3){v[0], v[1], v[2]};
    cam.look = (hr_vec3){v[3], v[4], v[5]};
    cam.up = (hr_vec3){v[6], v[7], v[8]};
    cam.view_angle = v[9];
    if (hr_camera_validate(r->ctx, &cam) != HR_OK) {
        const char *why = hr_context_last_error(r->ctx);
        if (strncmp(why, "camera: ", 8) == 0) why += 8;
        return sdl_error(r->src, HR_ERROR_SDL, keyword, "'camera' cannot make rays: %s", why);
    }
    r->camera = cam;
    r->has_camera = 1;
    return HR_OK;
}
