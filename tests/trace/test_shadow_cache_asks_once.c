/* A shadow ray asks the object that blocked the last shadow ray towards the
 * same light first (lib/trace/trace.c, hri_scene_trace_shadow). When that
 * object lets the ray pass, the walk after it must not ask it again: its
 * answer for the same ray and window is already known, and for a mesh the
 * second any-hit walk costs as much as the first. A counting shape (a unit
 * sphere whose any-hit calls are counted) checks that each object is asked
 * at most once per shadow ray, and that the answers stay those of a walk
 * with no cache. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static long any_calls;

static hr_status counted_create(const hr_create_args *args, void **out)
{
    (void)args;
    static int one;
    *out = &one;
    return HR_OK;
}

static void counted_destroy(void *shape) { (void)shape; }

static void counted_bounds(const void *shape, hr_bounds *b)
{
    (void)shape;
    b->lo = (hr_vec3){-1, -1, -1};
    b->hi = (hr_vec3){1, 1, 1};
}

/* The unit sphere's crossings in (tmin, tmax), nearest first. */
static hr_status counted_hit(const hr_hit_args *a)
{
    const hr_vec3 o = a->ray.origin, d = a->ray.dir;
    const double qa = d.x * d.x + d.y * d.y + d.z * d.z;
    const double qb = o.x * d.x + o.y * d.y + o.z * d.z;
    const double qc = o.x * o.x + o.y * o.y + o.z * o.z - 1.0;
    const double disc = qb * qb - qa * qc;
    if (!(disc > 0.0) || !(qa > 0.0)) return HR_OK;
    const double root = sqrt(disc), ts[2] = {(-qb - root) / qa, (-qb + root) / qa};
    for (int k = 0; k < 2; k++) {
        if (!(ts[k] > a->tmin && ts[k] < a->tmax)) continue;
        hr_hit *h = &a->out->hits[a->out->count++];
        h->t = ts[k];
        h->point = (hr_vec3){o.x + ts[k] * d.x, o.y + ts[k] * d.y, o.z + ts[k] * d.z};
        h->normal = h->point;
        h->error = 1e-15;
        h->surface = 0;
        h->entering = k == 0;
    }
    return HR_OK;
}

static hr_status counted_any(const hr_hit_args *a)
{
    any_calls++;
    const int32_t start = a->out->count;
    const hr_status st = counted_hit(a);
    if (a->out->count > start + 1) a->out->count = start + 1;
    return st;
}

static const hr_shape_class counted_class = {
    sizeof(hr_shape_class), HR_SHAPE_CLOSED, "counted", "a unit sphere that counts its any-hit calls",
    NULL, 0, 1, counted_create, counted_destroy, counted_bounds, counted_hit, NULL, counted_any, NULL, NULL,
    NULL, 0};

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_register_shape_class(ctx, &counted_class, "test_shadow_cache_asks_once.c"));
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    /* A at the origin, B at x = 5. */
    const hr_transform at_b = tb_place(5, 0, 0, 1);
    CHECK(tb_add(s, "counted", NULL, NULL) == 0);
    CHECK(tb_add(s, "counted", NULL, &at_b) == 1);
    CHECK_OK(hr_scene_commit(s));
    /* 1: through A (blocked: the cache takes A). 2: through A's box beside
     * the sphere (x = y = 0.9), meeting nothing: A is asked first, from the
     * cache, and the walk, which reaches A's box, must not ask it again.
     * 3: through B alone (blocked; the clear ray 2 left the cache empty).
     * 4: through B again (B cached: one call). */
    const hr_ray rays[4] = {{{0, 0, -5}, {0, 0, 10}},
                            {{0.9, 0.9, -5}, {0, 0, 10}},
                            {{5, 0, -5}, {0, 0, 10}},
                            {{5, 0.1, -5}, {0, 0, 10}}};
    const int32_t want[4] = {1, 0, 1, 1};
    /* Asked at most: ray 1 the walk's A; ray 2 the cache's A (the walk
     * skips it; asked again, it is 2); ray 3 the walk's B; ray 4 the
     * cache's B. */
    const long most[4] = {1, 1, 1, 1};
    int32_t hits[4] = {-1, -1, -1, -1};
    long calls[4];
    for (int i = 0; i < 4; i++) {
        /* The first i + 1 rays in one batch (the cache lives for one call);
         * ray i's calls are the batch's less the batch of the rays before. */
        int32_t h[4];
        any_calls = 0;
        CHECK_OK(hr_scene_occluded(s, rays, i + 1, 0.0, 1.0, h));
        calls[i] = any_calls;
        hits[i] = h[i];
    }
    for (int i = 0; i < 4; i++) {
        const long own = calls[i] - (i ? calls[i - 1] : 0);
        CHECK_MSG(hits[i] == want[i], "ray %d: occluded %d, want %d", i + 1, hits[i], want[i]);
        CHECK_MSG(own <= most[i], "ray %d: %ld any-hit calls, at most %ld", i + 1, own, most[i]);
    }
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
    return hr_test_end();
}
