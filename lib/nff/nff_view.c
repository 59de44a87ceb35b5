/* NFF's settings (lib/nff/nff_reader.h): the viewpoint `v`, the background `b`,
 * lights `l` and the material `f`. docs/nff.md explains each mapping.
 *
 * `v` is a block of six lines in a fixed order (NFF.TXT):
 *   from x y z / at x y z / up x y z / angle deg / hither d / resolution w h
 * `angle` is the full field of view across the image, edge to edge, which
 * is Hill's view angle for the square images of the SPD (for others it is
 * taken as the vertical angle, as Hill's camera has it). `hither` is read
 * and checked but not used: hitray's rays start at the eye, and no SPD
 * scene has anything nearer than its hither distance. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/color_bounds.h"
#include "util/errors.h"
#include "nff/nff_reader.h"

/* The largest image side `resolution` may give. */
#define NFF_MAX_RESOLUTION 65536

/* One line of the `v` block: its keyword, then `count` numbers. */
static hr_status view_line(nff_reader *r, nff_word v, const char *keyword, const char *what,
                           int count, double *out)
{
    nff_word w = nff_next(&r->lx);
    if (!nff_word_is(w, keyword)) {
        char found[96];
        nff_describe(w, found, sizeof found);
        return nff_error(r, HR_ERROR_SDL, w.length ? w : v,
                         "expected '%s' in the 'v' block begun at line %d (from, at, up, angle, "
                         "hither, resolution, in that order), found %s",
                         keyword, (int)v.line, found);
    }
    return nff_read_numbers(r, w, what, count, out, NULL);
}

hr_status nff_read_view(nff_reader *r, nff_word v)
{
    double from[3], at[3], up[3], angle, hither, size[2];
    hr_status st;
    if ((st = view_line(r, v, "from", "x y z", 3, from)) ||
        (st = view_line(r, v, "at", "x y z", 3, at)) ||
        (st = view_line(r, v, "up", "x y z", 3, up)) ||
        (st = view_line(r, v, "angle", "degrees", 1, &angle)) ||
        (st = view_line(r, v, "hither", "distance", 1, &hither)) ||
        (st = view_line(r, v, "resolution", "width height", 2, size)))
        return st;
    if (!(hither >= 0.0))
        return nff_error(r, HR_ERROR_SDL, v, "'hither' %g of the 'v' block must be >= 0", hither);
    for (int i = 0; i < 2; i++)
        if (!(size[i] >= 1.0 && size[i] <= NFF_MAX_RESOLUTION && size[i] == floor(size[i])))
            return nff_error(r, HR_ERROR_SDL, v,
                             "'resolution' %g %g of the 'v' block must be two whole numbers in "
                             "[1, %d]",
                             size[0], size[1], NFF_MAX_RESOLUTION);
    hr_camera cam = r->camera;
    cam.eye = (hr_vec3){from[0], from[1], from[2]};
    cam.look = (hr_vec3){at[0], at[1], at[2]};
    cam.up = (hr_vec3){up[0], up[1], up[2]};
    cam.view_angle = angle;
    cam.width = (int32_t)size[0];
    cam.height = (int32_t)size[1];
    if (hr_camera_validate(r->ctx, &cam) != HR_OK) {
        char why[512];
        const char *msg = hr_context_last_error(r->ctx);
        if (strncmp(msg, "camera: ", 8) == 0) msg += 8;
        snprintf(why, sizeof why, "%s", msg);
        return nff_error(r, HR_ERROR_SDL, v, "the 'v' block cannot make rays: %s", why);
    }
    r->camera = cam;
    r->has_camera = 1;
    return HR_OK;
}

/* A colour the scene would refuse is reported at the entity that gave it. */
static hr_status check_color(nff_reader *r, nff_word at, const char *what, const double *c)
{
    for (int i = 0; i < 3; i++)
        if (!(fabs(c[i]) <= HR_MAX_COLOR))
            return nff_error(r, HR_ERROR_SDL, at, "the %s %g %g %g of '%.*s' is beyond +-%g",
                             what, c[0], c[1], c[2], (int)at.length, at.text, HR_MAX_COLOR);
    return HR_OK;
}

hr_status nff_read_background(nff_reader *r, nff_word b)
{
    double c[3];
    hr_status st = nff_read_numbers(r, b, "r g b", 3, c, NULL);
    if (!st) st = check_color(r, b, "colour", c);
    if (st) return st;
    r->globals.background = (hr_color){c[0], c[1], c[2]};
    return HR_OK;
}

/* l x y z [r g b]: the colour is there when the word after z is on the
 * same line. */
hr_status nff_read_light(nff_reader *r, nff_word l)
{
    nff_light light;
    memset(&light, 0, sizeof light);
    light.at = l;
    double p[3];
    nff_word at[3];
    hr_status st = nff_read_numbers(r, l, "x y z [r g b]", 3, p, at);
    if (st) return st;
    light.position = (hr_vec3){p[0], p[1], p[2]};
    nff_word next = nff_peek(&r->lx);
    if (next.length && next.line == at[2].line) {
        double c[3];
        if ((st = nff_read_numbers(r, l, "x y z r g b: the colour on the line of the position",
                                   3, c, NULL)) ||
            (st = check_color(r, l, "colour", c)))
            return st;
        light.color = (hr_color){c[0], c[1], c[2]};
        light.has_color = 1;
    }
    if (r->light_count == r->light_capacity) {
        size_t cap = r->light_capacity ? 2 * r->light_capacity : 8;
        nff_light *grown = realloc(r->lights, cap * sizeof *grown);
        if (!grown) return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
        r->lights = grown;
        r->light_capacity = cap;
    }
    r->lights[r->light_count++] = light;
    return HR_OK;
}

/* Lights without a colour share one intensity, 1/sqrt(n) for the n lights
 * of the file, as the SPD's own POV-Ray output has it: the scene's total
 * light then grows as sqrt(n), so adding lights does not wash it out. */
hr_status nff_add_lights(nff_reader *r)
{
    const double share = r->light_count ? 1.0 / sqrt((double)r->light_count) : 0.0;
    for (size_t i = 0; i < r->light_count; i++) {
        const nff_light *n = &r->lights[i];
        hr_light light;
        memset(&light, 0, sizeof light);
        light.struct_size = sizeof light;
        light.position = n->position;
        light.color = n->has_color ? n->color : (hr_color){share, share, share};
        hr_status st = hr_scene_add_light(r->scene, &light);
        if (st) {
            char why[1024];
            snprintf(why, sizeof why, "%s", hr_context_last_error(r->ctx));
            return nff_error(r, st, n->at, "%s", why);
        }
    }
    return HR_OK;
}

/* f r g b Kd Ks Shine T ior, the material of everything after it:
 *   diffuse  Kd (r, g, b)     specular  Ks (1, 1, 1), exponent Shine
 *   reflectivity Ks           transparency T, speed of light 1 / ior
 *   ambient and emission 0 (NFF has neither).
 * The polygons gathered under the previous `f` become their meshes first. */
static const char *const fill_fields[8] = {"r", "g", "b", "Kd", "Ks", "Shine", "T", "ior"};

hr_status nff_read_fill(nff_reader *r, nff_word f)
{
    double v[8];
    nff_word at[8];
    hr_status st = nff_read_numbers(r, f, "r g b Kd Ks Shine T ior", 8, v, at);
    if (st) return st;
    for (int i = 3; i < 8; i++)
        if (v[i] < 0.0)
            return nff_error(r, HR_ERROR_SDL, at[i], "'%s' = %g of 'f' must be >= 0",
                             fill_fields[i], v[i]);
    if (v[6] > 0.0 && !(v[7] > 0.0))
        return nff_error(r, HR_ERROR_SDL, at[7],
                         "'ior' = %g of 'f' must be > 0 for a transmitting material (T = %g)",
                         v[7], v[6]);
    if ((st = nff_flush_polygons(r))) return st;
    hr_material m;
    hr_material_default(&m);
    m.ambient = (hr_color){0.0, 0.0, 0.0};
    m.diffuse = (hr_color){v[3] * v[0], v[3] * v[1], v[3] * v[2]};
    m.specular = (hr_color){v[4], v[4], v[4]};
    m.specular_exponent = v[5];
    m.reflectivity = v[4];
    m.transparency = v[6];
    m.speed_of_light = v[6] > 0.0 ? 1.0 / v[7] : 1.0;
    if (hr_material_validate(r->ctx, &m) != HR_OK) {
        char why[512];
        snprintf(why, sizeof why, "%s", hr_context_last_error(r->ctx));
        return nff_error(r, HR_ERROR_SDL, f, "%s", why);
    }
    r->material = m;
    r->material_at = f;
    return HR_OK;
}
