/* The checks of a scene file reader's answer (fuzz_reader_checks.h). */
#include "fuzz_reader_checks.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_input.h"
#include "fuzz_mesh_t_error.h"

static int hit_finite(const hr_hit *h)
{
    return isfinite(h->t) && isfinite(h->point.x) && isfinite(h->point.y) &&
           isfinite(h->point.z) && isfinite(h->normal.x) && isfinite(h->normal.y) &&
           isfinite(h->normal.z) && isfinite(h->error) && h->error >= 0;
}

void fuzz_reader_check_error(hr_context *ctx, const char *tag, const char *name, hr_status st,
                            const hr_sdl_result *r, size_t length)
{
    if (r->scene) fuzz_fail("%s: status %d and still a scene", tag, (int)st);
    if (st == HR_ERROR_OUT_OF_MEMORY) return;
    const char *message = hr_context_last_error(ctx);
    const size_t n = strlen(name);
    int line = 0, column = 0, used = 0;
    if (strncmp(message, name, n) != 0 || message[n] != ':' ||
        sscanf(message + n + 1, "%d:%d: %n", &line, &column, &used) != 2 || !used)
        fuzz_fail("%s: status %d, the message does not start with '%s:<line>:<col>: ': %s", tag,
                  (int)st, name, message);
    hr_error_info info = {.struct_size = sizeof info};
    hr_context_last_error_info(ctx, &info);
    if (info.status != st || strcmp(info.file, name) != 0 || info.line < 1 || info.column < 1 ||
        (size_t)info.line > length + 1 || (size_t)info.column > length + 1)
        fuzz_fail("%s: error info status %d file '%s' line %d column %d for status %d: %s", tag,
                  (int)info.status, info.file, (int)info.line, (int)info.column, (int)st,
                  message);
}

/* Whether `h`, listed before the first hit, is a hit the first-hit walk
 * may pass by rounding: within 1e-6 of the list's first t (relative), or a
 * mesh crossing whose computed t lies before the first hit by at most
 * twice the largest t error bound of the line's crossings with its mesh
 * (fuzz_mesh_t_error.h).
 * - Within 1e-6: the first-hit query skips objects whose world box the
 *   ray misses, while each object intersects the ray carried into its own
 *   space, rounded; for an eye 4e18 away that rounding moves the line more
 *   than the boxes are widened, and a crossing one ulp nearer than the
 *   first hit, in a box the world ray misses, is seen by the all-hits
 *   query only.
 * - A mesh's t error: the walk ends its window at its best hit's t and
 *   prunes boxes past it, and the boxes bound the exact crossings, while
 *   the list sorts computed t, which for a ray crossing a triangle 3e14
 *   long lies up to its t error bound (0.5 at t = 1) from its crossing.
 *   Two NFF meshes crossed on one plane, at exactly one t, gave t 2e-5
 *   apart, each within its bound of the exact t, and the first hit named
 *   the later one: its window ended before the other's box
 *   (nff_mesh_first_hit_other_object_past_t_error.nff). Rounding gives no
 *   order there, as within one mesh (the mesh harness allows the same). */
static int passed_by_rounding(const hr_scene *scene, const hr_ray *ray, const hr_hit *h,
                              const hr_hit *first, double list_t)
{
    const double gap = first->t - h->t;
    return gap <= 1e-6 * fabs(list_t) || gap <= 2.0 * fuzz_scene_mesh_t_error(scene, h->object, ray);
}

/* The first hit is one of the list, its object's first hit listed at its
 * t with the same entering flag (a solid whose two crossings round to one
 * t, seen from far away, enters before it leaves in both), and every hit
 * listed before it is one the walk may pass by rounding (above). At a tie
 * between objects both queries name the object added first (the tie rule,
 * trace.c); a listed hit at the first hit's t is still accepted, because
 * of the far-eye rounding above. */
int fuzz_first_hit_is_first(const hr_scene *scene, const hr_ray *ray, const hr_hit *first,
                            const hr_intersection *all)
{
    int32_t at = 0;
    while (at < all->count && !(all->hits[at].t == first->t && all->hits[at].object == first->object)) at++;
    if (at == all->count || all->hits[at].entering != first->entering) return 0;
    for (int32_t i = 0; i < at; i++)
        if (!passed_by_rounding(scene, ray, &all->hits[i], first, all->hits[0].t)) return 0;
    return 1;
}

/* Whether the ray's origin, far out, is rounded by more than the thickness
 * of `object`: an eye 7e18 away (a scene framed around objects 1e11 apart)
 * is known to within 1024 units, so for a torus 2e-4 thick the world-space
 * box test (the first-hit query) and the object's own rounded copy of the
 * ray (the all-hits query) may disagree on whether the line meets it at
 * all, each within rounding of the line. Then which hit comes first is not
 * checked, only the hits themselves. Origins within 1e12 of the world's
 * centre are always checked in full (thin objects, squares, included). */
static int origin_blurs_object(const hr_scene *scene, const hr_ray *ray, int64_t object)
{
    hr_object_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    if (hr_scene_object_info(scene, object, &info) != HR_OK) return 0;
    const hr_bounds *b = &info.world_bounds;
    const double thickness = fmin(fmin(b->hi.x - b->lo.x, b->hi.y - b->lo.y), b->hi.z - b->lo.z);
    const double o = fmax(fmax(fabs(ray->origin.x), fabs(ray->origin.y)), fabs(ray->origin.z));
    return o > 1e12 && 64.0 * DBL_EPSILON * o > thickness;
}

static void cast(const char *tag, const hr_scene *scene, hr_ray ray)
{
    hr_hit first;
    int32_t found = 0;
    if (hr_scene_first_hit(scene, &ray, 0.0, INFINITY, &first, &found) != HR_OK) return;
    hr_intersection all;
    hr_intersection_init(&all);
    if (hr_scene_all_hits(scene, &ray, 0.0, INFINITY, &all) == HR_OK) {
        for (int32_t i = 0; i < all.count; i++) {
            const hr_hit *h = &all.hits[i];
            if (!hit_finite(h) || !(h->t > 0.0) || (i > 0 && h[-1].t > h->t))
                fuzz_fail("%s: all hits: hit %d of %d at t = %g is not finite, sorted and "
                          "after 0", tag,
                          (int)i, (int)all.count, h->t);
        }
        if (found != (all.count > 0) || (found && !hit_finite(&first)))
            fuzz_fail("%s: first hit found %d, all hits %d", tag, (int)found, (int)all.count);
        if (found && !fuzz_first_hit_is_first(scene, &ray, &first, &all) &&
            !origin_blurs_object(scene, &ray, all.hits[0].object))
            fuzz_fail("%s: first hit t = %a (object %d), first of all hits t = %a (object %d)", tag,
                      first.t, (int)first.object, all.hits[0].t, (int)all.hits[0].object);
    }
    hr_intersection_release(&all);
    hr_color colour;
    if (hr_scene_shade(scene, &ray, 3, &colour) == HR_OK &&
        !(isfinite(colour.r) && isfinite(colour.g) && isfinite(colour.b)))
        fuzz_fail("%s: shade gave (%g, %g, %g)", tag, colour.r, colour.g, colour.b);
}

void fuzz_reader_check_rays(hr_context *ctx, const char *tag, const hr_sdl_result *r)
{
    if (hr_scene_commit(r->scene) != HR_OK) {
        if (!hr_context_last_error(ctx)[0]) fuzz_fail("%s: commit failed without a message", tag);
        return;
    }
    const hr_vec3 e = r->camera.eye, l = r->camera.look;
    const hr_vec3 d = {l.x - e.x, l.y - e.y, l.z - e.z};
    const double n = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const double spread = n > 0 && isfinite(n) ? 0.2 * n : 1.0;
    for (int k = 0; k < 5; k++) {
        hr_ray ray = {e, d};
        if (k == 1) ray.dir.x += spread;
        if (k == 2) ray.dir.y += spread;
        if (k == 3) ray.dir.x -= spread, ray.dir.y -= spread;
        if (k == 4) ray.dir.z += spread;
        cast(tag, r->scene, ray);
    }
}

/* What a warning must be: a known code, and a message that names the
 * scene (and, when it has a place, starts with that place) or, from
 * commit, no file at all. */
typedef struct warning_check {
    const char *tag, *name;
} warning_check;

static void check_warning(void *user, const hr_warning *w)
{
    const warning_check *c = user;
    if (w->struct_size != sizeof *w || !w->message || !w->file)
        fuzz_fail("%s: a malformed warning", c->tag);
    if (w->code != HR_WARNING_EMPTY_SCENE && w->code != HR_WARNING_BELOW_THRESHOLD)
        fuzz_fail("%s: warning code %d: %s", c->tag, (int)w->code, w->message);
    if (!*w->file) return;
    const size_t n = strlen(c->name);
    if (strcmp(w->file, c->name) != 0 || strncmp(w->message, c->name, n) != 0 || w->message[n] != ':')
        fuzz_fail("%s: a warning in file '%s' does not start with '%s:': %s", c->tag, w->file,
                  c->name, w->message);
    int line = 0, column = 0, used = 0;
    if (w->line > 0 && (sscanf(w->message + n + 1, "%d:%d: %n", &line, &column, &used) != 2 ||
                        !used || line != w->line || column != w->column))
        fuzz_fail("%s: a warning at %d:%d whose message says otherwise: %s", c->tag, (int)w->line,
                  (int)w->column, w->message);
}

void fuzz_reader_input(hr_context *ctx, const char *tag, const char *name,
                      fuzz_reader_fn read, const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text) return;
    memcpy(text, data, size);
    text[size] = '\0';
    hr_sdl_result r = {.struct_size = sizeof r};
    warning_check check = {tag, name};
    hr_context_set_warning_callback(ctx, check_warning, &check);
    const hr_status st = read(ctx, text, name, &r);
    const size_t length = strlen(text);
    free(text);
    if (st != HR_OK) {
        hr_context_set_warning_callback(ctx, NULL, NULL);
        fuzz_reader_check_error(ctx, tag, name, st, &r, length);
        return;
    }
    if (!r.scene) fuzz_fail("%s: HR_OK and no scene", tag);
    fuzz_reader_check_rays(ctx, tag, &r);
    hr_context_set_warning_callback(ctx, NULL, NULL);
    hr_scene_destroy(r.scene);
}
