/* No hit leaves the library with t not finite or outside (tmin, tmax). A
 * direction so short that the host rescales it by a power of two
 * (lib/trace/object_trace.h) gives, in the rescaled space, a t that is fine there
 * but overflows when scaled back: such a hit is beyond double's range along
 * the caller's ray, so there is none to report. Checked through first_hit
 * and all_hits for a quadric, two polyhedra and a CSG union, and for a
 * window (tmin, tmax) that the hits in the rescaled space fall inside only
 * before scaling back. */
#include <math.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *ctx;

static hr_scene *load(const char *text)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK_MSG(hr_sdl_load_string(ctx, text, "t_range.sdl", NULL, &r) == HR_OK, "%s: %s", text,
              hr_context_last_error(ctx));
    if (r.scene) CHECK_OK(hr_scene_commit(r.scene));
    return r.scene;
}

static void check_hits(hr_scene *s, const char *what, hr_vec3 o, hr_vec3 d, double tmin, double tmax,
                       int expect_found)
{
    hr_ray ray = {o, d};
    hr_hit h;
    int32_t found = -1;
    CHECK_OK(hr_scene_first_hit(s, &ray, tmin, tmax, &h, &found));
    CHECK_MSG(found == expect_found, "%s: first hit found %d, expected %d", what, (int)found, expect_found);
    if (found) CHECK_MSG(isfinite(h.t) && h.t > tmin && h.t < tmax, "%s: first hit at t = %g", what, h.t);
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &ray, tmin, tmax, &all));
    CHECK_MSG((all.count > 0) == expect_found, "%s: %d hits", what, (int)all.count);
    for (int32_t i = 0; i < all.count; i++)
        CHECK_MSG(isfinite(all.hits[i].t) && all.hits[i].t > tmin && all.hits[i].t < tmax,
                  "%s: hit %d at t = %g", what, (int)i, all.hits[i].t);
    hr_intersection_release(&all);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    const char *scenes[] = {"sphere", "cube", "octahedron", "union sphere cube"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        hr_scene *s = load(scenes[i]);
        if (!s) continue;
        /* |d| = 3e-308: the hits at 6 / 3e-308 and 8 / 3e-308 are past DBL_MAX. */
        check_hits(s, scenes[i], (hr_vec3){0, 0, 7}, (hr_vec3){0, 0, -3e-308}, 0, INFINITY, 0);
        /* |d| = 1e-250: hits at 6e250 and 8e250, both finite. */
        check_hits(s, scenes[i], (hr_vec3){0, 0, 7}, (hr_vec3){0, 0, -1e-250}, 0, INFINITY, 1);
        /* The same ray with a window that excludes both hits. */
        check_hits(s, scenes[i], (hr_vec3){0, 0, 7}, (hr_vec3){0, 0, -1e-250}, 0, 5e250, 0);
        check_hits(s, scenes[i], (hr_vec3){0, 0, 7}, (hr_vec3){0, 0, -1e-250}, 9e250, INFINITY, 0);
        /* A long direction: hits at 6e-250 and 8e-250. */
        check_hits(s, scenes[i], (hr_vec3){0, 0, 7}, (hr_vec3){0, 0, -1e250}, 0, INFINITY, 1);
        hr_scene_destroy(s);
    }
    hr_context_destroy(ctx);
    return hr_test_end();
}
