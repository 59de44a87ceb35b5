/* The scene queries take a scratch list for every ray, inline when the list
 * on top of the per-thread stack was set up by an earlier ray (lib/trace/trace.c,
 * scratch_acquire), else through the host's scratch_acquire. Either way the
 * list a query holds is its own: a shape that asks the host for a scratch
 * list while the query traces it must get another list, empty, and what it
 * writes there must not reach the query's answer. A render on one thread
 * keeps its context from ray to ray, so after the first ray every camera
 * and shadow ray takes the inline way; hr_scene_shade and
 * hr_scene_first_hit start from a fresh context, the other way. The class
 * below is a unit ball that takes a list, checks it, fills it with junk and
 * gives it back on every call; the render must match hr_scene_shade pixel
 * for pixel. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>
#include <hitray/shape_module.h>

#include "hr_test.h"

static long calls, wrong;

typedef struct ball {
    const hr_host *host;
} ball;

static hr_status ball_create(const hr_create_args *a, void **out)
{
    ball *b = a->host->alloc(sizeof *b);
    if (!b) return HR_ERROR_OUT_OF_MEMORY;
    b->host = a->host;
    *out = b;
    return HR_OK;
}

static void ball_destroy(void *shape)
{
    ball *b = shape;
    b->host->free(b);
}

static void ball_bounds(const void *shape, hr_bounds *b)
{
    (void)shape;
    b->lo = (hr_vec3){-1, -1, -1};
    b->hi = (hr_vec3){1, 1, 1};
}

/* Takes a scratch list, checks it is another list than the one it answers
 * into and that it is empty, leaves junk in it and gives it back. */
static void use_scratch(const hr_hit_args *a)
{
    const ball *b = a->shape;
    calls++;
    hr_intersection *list = b->host->scratch_acquire(a->call);
    if (!list) {
        wrong++;
        return;
    }
    if (list == a->out || list->hits == a->out->hits || list->count != 0 || list->capacity < HR_MIN_HIT_CAPACITY)
        wrong++;
    for (int i = 0; i < HR_MIN_HIT_CAPACITY; i++) {
        memset(&list->hits[i], 0, sizeof list->hits[i]);
        list->hits[i].t = 1e-3 * (i + 1);
    }
    list->count = HR_MIN_HIT_CAPACITY;
    b->host->scratch_release(a->call, list);
}

static hr_status ball_hit(const hr_hit_args *a)
{
    use_scratch(a);
    const hr_vec3 o = a->ray.origin, d = a->ray.dir;
    const double qa = d.x * d.x + d.y * d.y + d.z * d.z, qb = o.x * d.x + o.y * d.y + o.z * d.z,
                 qc = o.x * o.x + o.y * o.y + o.z * o.z - 1.0;
    const double disc = qb * qb - qa * qc;
    if (!(disc > 0)) return HR_OK;
    const double root = sqrt(disc), ts[2] = {(-qb - root) / qa, (-qb + root) / qa};
    for (int i = 0; i < 2; i++) {
        if (!(ts[i] > a->tmin && ts[i] < a->tmax)) continue;
        hr_hit *h = &a->out->hits[a->out->count++];
        memset(h, 0, sizeof *h);
        h->t = ts[i];
        h->point = (hr_vec3){o.x + ts[i] * d.x, o.y + ts[i] * d.y, o.z + ts[i] * d.z};
        h->normal = h->point;
        h->error = 1e-9;
        h->entering = i == 0;
    }
    return HR_OK;
}

static const hr_shape_class ball_class = {
    sizeof(hr_shape_class), HR_SHAPE_CLOSED, "scratchBall", "a unit ball that borrows scratch lists",
    NULL, 0, 1, ball_create, ball_destroy, ball_bounds, ball_hit, NULL, NULL, NULL, NULL, NULL, 0
};

int main(void)
{
    hr_context *ctx;
    CHECK(hr_context_create(&ctx) == HR_OK);
    CHECK(hr_context_register_shape_class(ctx, &ball_class, "test_scratch_lists.c") == HR_OK);
    const char *sdl = "camera 0 4 9  0 0 0  0 1 0  40\n"
                      "light 5 9 4 .7 .7 .7\nlight -6 8 2 .4 .4 .5\n"
                      "globalAmbient .1 .1 .1\nmaxRecursionDepth 2\n"
                      "push rotate -90 1 0 0 diffuse .6 .6 .6 plane pop\n"
                      "push translate -1.5 1 0 diffuse .8 .3 .2 specular .5 .5 .5 scratchBall pop\n"
                      "push translate 1.5 1.2 -.5 scale .8 .8 .8 diffuse .2 .5 .8 reflectivity .4 scratchBall pop\n"
                      "push translate 0 .5 2 scale .5 .5 .5 diffuse .3 .8 .3 scratchBall pop\n";
    hr_sdl_result res = {.struct_size = sizeof res};
    if (hr_sdl_load_string(ctx, sdl, "scratch_lists.sdl", NULL, &res) != HR_OK) {
        CHECK_MSG(0, "%s", hr_context_last_error(ctx));
        return hr_test_end();
    }
    CHECK(hr_scene_commit(res.scene) == HR_OK);
    hr_camera cam = res.camera;
    cam.width = 64, cam.height = 48;
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = 1;
    hr_image *img = NULL;
    CHECK(hr_render(res.scene, &cam, &o, &img, NULL) == HR_OK);
    const long render_calls = calls;
    long differ = 0, hits = 0;
    const float *px = img ? hr_image_data(img) : NULL;
    for (int y = 0; px && y < cam.height; y++)
        for (int x = 0; x < cam.width; x++) {
            hr_ray r;
            hr_color want;
            hr_camera_ray(&cam, x + 0.5, y + 0.5, &r);
            CHECK(hr_scene_shade(res.scene, &r, -1, &want) == HR_OK);
            const float *got = px + 3 * (y * cam.width + x);
            if (got[0] != (float)want.r || got[1] != (float)want.g || got[2] != (float)want.b) differ++;
            hr_hit h;
            int32_t found = 0;
            CHECK(hr_scene_first_hit(res.scene, &r, 0.0, INFINITY, &h, &found) == HR_OK);
            hits += found;
        }
    printf("%ld ball calls in the render, %ld in all; %ld wrong lists, %ld pixels differ, %ld first hits\n",
           render_calls, calls, wrong, differ, hits);
    CHECK(render_calls > 1000);
    CHECK(wrong == 0);
    CHECK(differ == 0);
    CHECK(hits > cam.width * cam.height / 2);
    hr_image_destroy(img);
    hr_scene_destroy(res.scene);
    hr_context_destroy(ctx);
    return hr_test_end();
}
