/* The acceleration claims, counted: first-hit queries visit the BVH front
 * to back and stop once nothing nearer can be left, shadow rays use the
 * any-hit path, and no ray asks a plain shape for all its hits (only a
 * composite would). An in-process shape class counts its calls by mode. */
#include <math.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

/* Calls per entry point, over every countingSphere (single-threaded). */
static struct {
    long all, first, any;
} calls;

static hr_status create(const hr_create_args *a, void **out)
{
    (void)a;
    static int token;
    *out = &token;
    return HR_OK;
}
static void destroy(void *p) { (void)p; }
static void bounds(const void *p, hr_bounds *b)
{
    (void)p;
    *b = (hr_bounds){{-1, -1, -1}, {1, 1, 1}};
}

/* The unit sphere's hits in (tmin, tmax), nearest first, at most `limit`. */
static hr_status sphere_hits(const hr_hit_args *a, int limit)
{
    const hr_vec3 o = a->ray.origin, d = a->ray.dir;
    double A = d.x * d.x + d.y * d.y + d.z * d.z;
    double B = o.x * d.x + o.y * d.y + o.z * d.z;
    double C = o.x * o.x + o.y * o.y + o.z * o.z - 1.0;
    double disc = B * B - A * C;
    if (disc < 0) return HR_OK;
    double q = -(B + copysign(sqrt(disc), B));
    double t0 = C / q, t1 = q / A;
    if (t0 > t1) {
        double t = t0;
        t0 = t1, t1 = t;
    }
    const double ts[2] = {t0, t1};
    for (int i = 0; i < 2 && limit > 0; i++) {
        if (!(ts[i] > a->tmin && ts[i] < a->tmax)) continue;
        hr_hit *h = &a->out->hits[a->out->count++];
        memset(h, 0, sizeof *h);
        h->t = ts[i];
        h->point = (hr_vec3){o.x + ts[i] * d.x, o.y + ts[i] * d.y, o.z + ts[i] * d.z};
        h->normal = h->point;
        h->error = 1e-12;
        h->entering = i == 0;
        limit--;
    }
    return HR_OK;
}
static hr_status hit_all(const hr_hit_args *a)
{
    calls.all++;
    return sphere_hits(a, 2);
}
static hr_status hit_first(const hr_hit_args *a)
{
    calls.first++;
    return sphere_hits(a, 1);
}
static hr_status hit_any(const hr_hit_args *a)
{
    calls.any++;
    return sphere_hits(a, 1);
}

static const hr_shape_class counting_sphere = {sizeof(hr_shape_class), HR_SHAPE_CLOSED, "countingSphere",
                                               "a unit sphere that counts its calls", NULL, 0, 1, create,
                                               destroy, bounds, hit_all, hit_first, hit_any, NULL, NULL, NULL, 0};

static hr_context *ctx;

static void reset(void) { memset(&calls, 0, sizeof calls); }

/* 60 spheres in a row along z, 3 apart: a ray down the row meets them all,
 * yet only the leaf holding the nearest (at most 4 objects) is tested. */
static void first_hit_stops_early(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material m;
    hr_material_default(&m);
    for (int i = 0; i < 60; i++) {
        hr_transform t = tb_place(0, 0, -3.0 * i, 1);
        tb_add(s, "countingSphere", &m, &t);
    }
    CHECK_OK(hr_scene_commit(s));
    const hr_ray rays[2] = {{{0, 0, 5}, {0, 0, -1}}, {{0, 0, -200}, {0, 0, 1}}};
    const double nearest_t[2] = {4, 200 - 177 - 1};
    for (int i = 0; i < 2; i++) {
        reset();
        hr_hit h;
        int32_t found = 0;
        CHECK_OK(hr_scene_first_hit(s, &rays[i], 0, INFINITY, &h, &found));
        CHECK(found && h.t == nearest_t[i]);
        CHECK_MSG(calls.first >= 1 && calls.first <= 4, "direction %d: %ld first-hit calls for 60 objects", i,
                  calls.first);
        CHECK(calls.all == 0 && calls.any == 0);
    }
    hr_scene_destroy(s);
}

/* A render: camera rays ask for the first hit, shadow rays for any hit,
 * nothing asks for all hits; a shadow ray blocked by a whole row of
 * spheres stops at the first one it tests. */
static void render_uses_first_and_any(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material m;
    hr_material_default(&m);
    tb_add(s, "countingSphere", &m, NULL);
    /* A column of blockers straight above the sphere, the light above it. */
    for (int i = 1; i <= 30; i++) {
        hr_transform t = tb_place(0, 2.0 + 2.5 * i, 0, 1);
        tb_add(s, "countingSphere", &m, &t);
    }
    tb_light(s, 0, 100, 0, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    hr_camera c;
    hr_camera_default(&c);
    c.eye = (hr_vec3){0, 0.5, 4};
    c.look = (hr_vec3){0, 0, 0};
    c.view_angle = 12;
    c.width = c.height = 6;
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    hr_render_stats st = {0};
    st.struct_size = sizeof st;
    hr_image *img = NULL;
    reset();
    CHECK_OK(hr_render(s, &c, &o, &img, &st));
    CHECK(calls.all == 0);
    CHECK(st.reflected == 0 && st.refracted == 0);
    CHECK(st.shadow > 0);
    /* Each shadow ray of a lit point stops at its first blocker; the ones
     * from the top of the sphere meet the column. A traversal that tested
     * every blocker would make ~30 calls per shadow ray. */
    CHECK_MSG(calls.any <= 4 * (long)st.shadow, "%ld any-hit calls for %llu shadow rays", calls.any,
              (unsigned long long)st.shadow);
    CHECK(calls.any >= (long)st.shadow);
    /* The camera rays: one first-hit query each, front to back. */
    CHECK_MSG(calls.first <= 4 * (long)st.primary, "%ld first-hit calls for %llu camera rays", calls.first,
              (unsigned long long)st.primary);
    hr_image_destroy(img);
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_register_shape_class(ctx, &counting_sphere, "test_traversal.c"));
    first_hit_stops_early();
    render_uses_first_and_any();
    hr_context_destroy(ctx);
    return hr_test_end();
}
