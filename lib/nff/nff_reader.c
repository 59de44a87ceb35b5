/* The NFF entity loop, numbers and messages (lib/nff/nff_reader.h). */
#include "nff/nff_reader.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "util/strutil.h"
#include "sdl/sdl_words.h"

/* The longest word read as a number: far more digits than a double holds. */
#define NFF_MAX_NUMBER_CHARS 400

void nff_reader_init(nff_reader *r, hr_context *ctx, hr_scene *scene, const char *file,
                     const char *text, size_t length)
{
    memset(r, 0, sizeof *r);
    r->ctx = ctx;
    r->scene = scene;
    r->file = file;
    nff_lexer_init(&r->lx, text, length);
    hr_material_default(&r->material);
    r->smooth.smooth = 1;
    /* The SPD's rules (docs/nff.md): the eye ray and four bounces, every
     * non-zero coefficient spawning its ray, no ambient term. */
    hr_scene_globals_default(&r->globals);
    r->globals.max_recursion_depth = 4;
    r->globals.min_reflectivity = 0.0;
    r->globals.min_transparency = 0.0;
    r->globals.background = (hr_color){0.0, 0.0, 0.0};
    r->globals.global_ambient = (hr_color){0.0, 0.0, 0.0};
    hr_camera_default(&r->camera);
}

void nff_reader_release(nff_reader *r)
{
    nff_batch_release(&r->flat);
    nff_batch_release(&r->smooth);
    free(r->lights);
    r->lights = NULL;
}

hr_status nff_error(const nff_reader *r, hr_status status, nff_word at, const char *fmt, ...)
{
    char what[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return hri_error_at(r->ctx, status, r->file, at.line, at.column, "%s:%d:%d: %s", r->file,
                       (int)at.line, (int)at.column, what);
}

const char *nff_describe(nff_word w, char *buf, size_t size)
{
    enum { SHOWN_CHARS = 40 };
    if (w.length == 0) snprintf(buf, size, "end of file");
    else if (w.nul) snprintf(buf, size, "a NUL byte (is this a text file?)");
    else hri_quote_word(w.text, w.length, SHOWN_CHARS, buf, size);
    return buf;
}

/* SDL's decimal grammar (sdl_words.h): no hex, inf or nan, whatever the
 * C locale. Returns SDL_NUMBER_*. */
static int parse_number(nff_word w, double *out)
{
    char buf[NFF_MAX_NUMBER_CHARS + 1];
    if (w.length == 0 || w.length > NFF_MAX_NUMBER_CHARS || w.nul) return SDL_NUMBER_NOT_A_NUMBER;
    memcpy(buf, w.text, w.length);
    buf[w.length] = '\0';
    return sdl_parse_number(buf, out);
}

hr_status nff_read_numbers(nff_reader *r, nff_word entity, const char *what, int count,
                           double *out, nff_word *at)
{
    for (int i = 0; i < count; i++) {
        nff_word w = nff_next(&r->lx);
        if (at) at[i] = w;
        int parsed = parse_number(w, &out[i]);
        if (parsed == SDL_NUMBER_OK) continue;
        char found[96];
        nff_describe(w, found, sizeof found);
        if (parsed == SDL_NUMBER_TOO_LARGE)
            return nff_error(r, HR_ERROR_SDL, w,
                             "number %s after '%.*s' is beyond the range of a double", found,
                             (int)entity.length, entity.text);
        return nff_error(r, HR_ERROR_SDL, w.length ? w : entity,
                         "expected %d number%s after '%.*s' (%s), found %s", count,
                         count == 1 ? "" : "s", (int)entity.length, entity.text, what, found);
    }
    return HR_OK;
}

hr_status nff_read_count(nff_reader *r, nff_word entity, const char *what, double min,
                         double max, int64_t *out)
{
    double v;
    nff_word at;
    hr_status st = nff_read_numbers(r, entity, what, 1, &v, &at);
    if (st) return st;
    if (v != floor(v) || v < min || v > max) {
        char found[96];
        return nff_error(r, HR_ERROR_SDL, at,
                         "expected a whole number in [%.0f, %.0f] after '%.*s' (%s), found %s",
                         min, max, (int)entity.length, entity.text, what,
                         nff_describe(at, found, sizeof found));
    }
    *out = (int64_t)v;
    return HR_OK;
}

hr_status nff_add_object(nff_reader *r, nff_word at, const char *shape, const hr_param *params,
                         int32_t count, const double *transform)
{
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = shape;
    d.param_count = count;
    d.params = count ? params : NULL;
    d.material = &r->material;
    d.transform = transform;
    hr_status st = hr_scene_add_object(r->scene, &d, NULL);
    if (st) {
        char why[1024];
        snprintf(why, sizeof why, "%s", hr_context_last_error(r->ctx));
        return nff_error(r, st, at, "%s", why);
    }
    return HR_OK;
}

static hr_status read_entity(nff_reader *r, nff_word w)
{
    if (nff_word_is(w, "s")) return nff_read_sphere(r, w);
    if (nff_word_is(w, "p")) return nff_read_polygon(r, w, 0);
    if (nff_word_is(w, "pp")) return nff_read_polygon(r, w, 1);
    if (nff_word_is(w, "c")) return nff_read_cone(r, w);
    if (nff_word_is(w, "f")) return nff_read_fill(r, w);
    if (nff_word_is(w, "l")) return nff_read_light(r, w);
    if (nff_word_is(w, "b")) return nff_read_background(r, w);
    if (nff_word_is(w, "v")) return nff_read_view(r, w);
    char found[96];
    return nff_error(r, HR_ERROR_SDL, w,
                     "expected an NFF entity (v, b, l, f, c, s, p, pp or a # comment), found %s",
                     nff_describe(w, found, sizeof found));
}

hr_status nff_reader_run(nff_reader *r)
{
    for (;;) {
        nff_word w = nff_next(&r->lx);
        if (w.length == 0) break;
        hr_status st = read_entity(r, w);
        if (st) return st;
    }
    hr_status st = nff_flush_polygons(r);
    if (!st) st = nff_add_lights(r);
    if (!st && (st = hr_scene_set_globals(r->scene, &r->globals))) {
        char why[1024];
        snprintf(why, sizeof why, "%s", hr_context_last_error(r->ctx));
        st = hri_error(r->ctx, st, "%s: %s", r->file, why);
    }
    return st;
}
