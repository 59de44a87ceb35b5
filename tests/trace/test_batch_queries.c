/* The batch queries (hr_scene_first_hits, hr_scene_occluded) against N
 * single hr_scene_first_hit calls, through the public API: the same hit, bit
 * for bit, for every ray of coherent (a camera's grid) and random batches,
 * with misses, exact ties (coincident spheres, cube faces in a plane's
 * plane, two coincident planes, with dyadic rays that meet them at the same
 * t), rays starting inside objects, windows that end early or start
 * behind the origin, batches of every length around the packet widths,
 * and two threads tracing batches of one scene at once; then the errors
 * for bad arguments. */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

/* xorshift64*: the same scene and rays on every run. */
static double uniform(uint64_t *s)
{
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1p-53;
}

/* 1,500 spheres and cubes on a grid of dyadic centres (so their faces and
 * the planes meet dyadic rays at the same t), every tenth added twice
 * (coincident twins: an exact tie at every hit), a floor plane z = -8 twice
 * and a tilted plane. */
static hr_scene *tie_scene(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    uint64_t seed = 5;
    for (int i = 0; i < 1500; i++) {
        double x = floor(32 * uniform(&seed)) / 2 - 8, y = floor(32 * uniform(&seed)) / 2 - 8;
        double z = floor(16 * uniform(&seed)) / 2 - 7, r = i % 3 ? 0.25 + floor(4 * uniform(&seed)) / 8 : 0.5;
        hr_transform t = tb_place(x, y, z, r);
        const char *shape = i % 3 ? "sphere" : "cube";
        CHECK(tb_add(s, shape, NULL, &t) >= 0);
        if (i % 10 == 0) CHECK(tb_add(s, shape, NULL, &t) >= 0);
    }
    hr_transform floor_t = tb_place(0, 0, -8, 1);
    CHECK(tb_add(s, "plane", NULL, &floor_t) >= 0);
    CHECK(tb_add(s, "plane", NULL, &floor_t) >= 0);
    hr_transform tilted;
    hr_transform_identity(&tilted);
    CHECK_OK(hr_transform_rotate(&tilted, 37, 1, 2, 0.5));
    hr_transform_translate(&tilted, 0, 0, -20);
    CHECK(tb_add(s, "plane", NULL, &tilted) >= 0);
    CHECK_OK(hr_scene_commit(s));
    return s;
}

/* A camera's rays: a w x h grid from an eye at (ex, ey, ez) looking down
 * -z, the grid wider than the objects so that the edge rays miss. Dyadic
 * when `dyadic` (multiples of 1/64: exact ties at faces and planes). */
static void camera_rays(hr_ray *rays, int w, int h, hr_vec3 eye, int dyadic)
{
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            hr_ray *r = &rays[j * w + i];
            r->origin = eye;
            double u = (i + 0.5) / w * 2 - 1, v = (j + 0.5) / h * 2 - 1;
            if (dyadic) u = floor(u * 64) / 64, v = floor(v * 64) / 64;
            r->dir = (hr_vec3){0.9 * u, 0.9 * v, -1};
        }
}

/* Random rays, from outside the objects' box and from inside it (inside a
 * sphere or cube, often), every third dyadic. */
static void random_rays(hr_ray *rays, int n, uint64_t *seed)
{
    for (int k = 0; k < n; k++) {
        hr_ray *r = &rays[k];
        double spread = k % 2 ? 20 : 7;
        do {
            r->origin = (hr_vec3){spread * (2 * uniform(seed) - 1), spread * (2 * uniform(seed) - 1),
                                  spread * (2 * uniform(seed) - 1)};
            r->dir = (hr_vec3){2 * uniform(seed) - 1, 2 * uniform(seed) - 1, 2 * uniform(seed) - 1};
            if (k % 3 == 0) {
                r->origin = (hr_vec3){floor(r->origin.x * 4) / 4, floor(r->origin.y * 4) / 4,
                                      floor(r->origin.z * 4) / 4};
                r->dir = (hr_vec3){floor(r->dir.x * 8) / 8, floor(r->dir.y * 8) / 8, floor(r->dir.z * 8) / 8};
            }
            if (k % 11 == 0) r->dir.y = 0; /* a slab the ray runs parallel to */
        } while (r->dir.x == 0 && r->dir.y == 0 && r->dir.z == 0);
    }
}

typedef struct tally {
    int hits, misses, ties, inside;
} tally;

/* The batch of `n` rays, traced in pieces of `piece` rays, against each ray
 * alone; the occlusion batch against each ray's `found`. */
static void compare_batch(const hr_scene *s, const hr_ray *rays, int n, int piece, double tmin, double tmax,
                          tally *tl, const char *what)
{
    hr_hit *hits = calloc((size_t)n, sizeof *hits);
    int32_t *found = calloc((size_t)n, sizeof *found), *blocked = calloc((size_t)n, sizeof *blocked);
    CHECK(hits && found && blocked);
    for (int at = 0; at < n; at += piece) {
        int len = n - at < piece ? n - at : piece;
        CHECK_OK(hr_scene_first_hits(s, rays + at, len, tmin, tmax, hits + at, found + at));
        CHECK_OK(hr_scene_occluded(s, rays + at, len, tmin, tmax, blocked + at));
    }
    hr_intersection all;
    hr_intersection_init(&all);
    for (int k = 0; k < n; k++) {
        hr_hit one;
        memset(&one, 0, sizeof one);
        int32_t got = 0;
        CHECK_OK(hr_scene_first_hit(s, &rays[k], tmin, tmax, &one, &got));
        CHECK_MSG(found[k] == got, "%s ray %d: batch found %d, single %d", what, k, (int)found[k], (int)got);
        CHECK_MSG(blocked[k] == got, "%s ray %d: occluded %d, single found %d", what, k, (int)blocked[k],
                  (int)got);
        if (!got || !found[k]) {
            tl->misses += !got;
            continue;
        }
        tl->hits++;
        tl->inside += !one.entering;
        CHECK_MSG(memcmp(&one, &hits[k], sizeof one) == 0,
                  "%s ray %d: batch t = %a object %lld surface %d, single t = %a object %lld surface %d",
                  what, k, hits[k].t, (long long)hits[k].object, (int)hits[k].surface, one.t,
                  (long long)one.object, (int)one.surface);
        CHECK_OK(hr_scene_all_hits(s, &rays[k], tmin, tmax, &all));
        tl->ties += all.count > 1 && all.hits[1].t == all.hits[0].t;
    }
    hr_intersection_release(&all);
    free(hits);
    free(found);
    free(blocked);
}

static void coherent_batches_match_single_rays(void)
{
    hr_scene *s = tie_scene();
    enum { W = 96, H = 72 };
    hr_ray *rays = malloc(W * H * sizeof *rays);
    CHECK(rays != NULL);
    tally tl = {0};
    camera_rays(rays, W, H, (hr_vec3){0.5, -0.25, 12}, 1);
    compare_batch(s, rays, W * H, W * H, 0, INFINITY, &tl, "dyadic camera");
    compare_batch(s, rays, W * H, 13, 0, 15, &tl, "dyadic camera, tmax 15");
    camera_rays(rays, W, H, (hr_vec3){0.3, 0.7, 11.1}, 0);
    compare_batch(s, rays, W * H, 256, 0, INFINITY, &tl, "camera");
    /* An eye among the objects: rays from inside spheres and cubes. */
    camera_rays(rays, W, H, (hr_vec3){-1.5, 2.5, -3}, 1);
    compare_batch(s, rays, W * H, 8, 0, INFINITY, &tl, "camera inside");
    compare_batch(s, rays, W * H, 7, -2, INFINITY, &tl, "camera inside, tmin -2");
    CHECK_MSG(tl.hits > 10000 && tl.misses > 1000 && tl.ties > 1000 && tl.inside > 100,
              "%d hits, %d misses, %d ties, %d from inside", tl.hits, tl.misses, tl.ties, tl.inside);
    free(rays);
    hr_scene_destroy(s);
}

static void random_batches_match_single_rays(void)
{
    hr_scene *s = tie_scene();
    enum { N = 6000 };
    hr_ray *rays = malloc(N * sizeof *rays);
    CHECK(rays != NULL);
    uint64_t seed = 77;
    random_rays(rays, N, &seed);
    tally tl = {0};
    compare_batch(s, rays, N, N, 0, INFINITY, &tl, "random");
    for (int piece = 1; piece <= 17; piece++) compare_batch(s, rays, 300, piece, 0, INFINITY, &tl, "random piece");
    compare_batch(s, rays, N, 64, 0, 3, &tl, "random, tmax 3");
    CHECK_MSG(tl.hits > 3000 && tl.misses > 1000 && tl.ties > 100 && tl.inside > 300,
              "%d hits, %d misses, %d ties, %d from inside", tl.hits, tl.misses, tl.ties, tl.inside);
    free(rays);
    hr_scene_destroy(s);
}

/* Two threads, each tracing the whole batch of one scene at once. */
typedef struct thread_job {
    const hr_scene *scene;
    const hr_ray *rays;
    int n;
    hr_hit *hits;
    int32_t *found;
    hr_status status;
} thread_job;

static void *trace_thread(void *arg)
{
    thread_job *j = arg;
    for (int rep = 0; rep < 3 && j->status == HR_OK; rep++)
        j->status = hr_scene_first_hits(j->scene, j->rays, j->n, 0, INFINITY, j->hits, j->found);
    return NULL;
}

static void threads_trace_batches_at_once(void)
{
    hr_scene *s = tie_scene();
    enum { N = 4000 };
    hr_ray *rays = malloc(N * sizeof *rays);
    thread_job jobs[2];
    hr_hit *want = calloc(N, sizeof *want);
    int32_t *want_found = calloc(N, sizeof *want_found);
    CHECK(rays && want && want_found);
    uint64_t seed = 3;
    random_rays(rays, N, &seed);
    CHECK_OK(hr_scene_first_hits(s, rays, N, 0, INFINITY, want, want_found));
    pthread_t tid[2];
    for (int k = 0; k < 2; k++) {
        jobs[k] = (thread_job){s, rays, N, calloc(N, sizeof(hr_hit)), calloc(N, sizeof(int32_t)), HR_OK};
        CHECK(jobs[k].hits && jobs[k].found);
        CHECK(pthread_create(&tid[k], NULL, trace_thread, &jobs[k]) == 0);
    }
    for (int k = 0; k < 2; k++) {
        pthread_join(tid[k], NULL);
        CHECK_OK(jobs[k].status);
        CHECK(memcmp(jobs[k].found, want_found, N * sizeof *want_found) == 0);
        for (int i = 0; i < N; i++)
            if (want_found[i]) CHECK_MSG(memcmp(&jobs[k].hits[i], &want[i], sizeof want[i]) == 0, "thread %d ray %d", k, i);
        free(jobs[k].hits);
        free(jobs[k].found);
    }
    free(want);
    free(want_found);
    free(rays);
    hr_scene_destroy(s);
}

/* The error names what is wrong (and the ray's index), and nothing is
 * written, not even for the good rays before a bad one. */
static void bad_arguments_are_refused(void)
{
    hr_scene *s = tie_scene();
    hr_ray rays[4];
    camera_rays(rays, 2, 2, (hr_vec3){0, 0, 12}, 0);
    hr_hit hits[4];
    int32_t found[4] = {7, 7, 7, 7};
    CHECK(hr_scene_first_hits(NULL, rays, 4, 0, INFINITY, hits, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_scene_occluded(NULL, rays, 4, 0, INFINITY, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_scene_first_hits(s, rays, -1, 0, INFINITY, hits, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "count -1 is negative") != NULL);
    CHECK(hr_scene_first_hits(s, NULL, 4, 0, INFINITY, hits, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "rays is NULL") != NULL);
    CHECK(hr_scene_first_hits(s, rays, 4, 0, INFINITY, NULL, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "hits is NULL") != NULL);
    CHECK(hr_scene_first_hits(s, rays, 4, 0, INFINITY, hits, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_scene_occluded(s, rays, 4, 0, INFINITY, NULL) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "occluded: hit is NULL") != NULL);
    CHECK(hr_scene_first_hits(s, rays, 4, 2, 1, hits, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "tmin <= tmax") != NULL);
    CHECK(hr_scene_first_hits(s, rays, 4, NAN, 1, hits, found) == HR_ERROR_INVALID_ARGUMENT);
    rays[2].origin.y = NAN;
    CHECK(hr_scene_first_hits(s, rays, 4, 0, INFINITY, hits, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "ray 2: origin and direction must be finite") != NULL, "%s",
              hr_context_last_error(ctx));
    rays[2].origin.y = 0;
    rays[3].dir.x = INFINITY;
    CHECK(hr_scene_occluded(s, rays, 4, 0, INFINITY, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "ray 3: origin and direction must be finite") != NULL);
    rays[3].dir = (hr_vec3){0, 0, 0};
    CHECK(hr_scene_first_hits(s, rays, 4, 0, INFINITY, hits, found) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "ray 3: direction is the zero vector") != NULL);
    for (int i = 0; i < 4; i++) CHECK(found[i] == 7);
    /* No rays: nothing to do, and nothing need be given. */
    CHECK_OK(hr_scene_first_hits(s, NULL, 0, 0, INFINITY, NULL, NULL));
    CHECK_OK(hr_scene_occluded(s, NULL, 0, 0, INFINITY, NULL));
    hr_scene_destroy(s);
    hr_scene *open;
    CHECK_OK(hr_scene_create(ctx, &open));
    CHECK(hr_scene_first_hits(open, rays, 1, 0, INFINITY, hits, found) == HR_ERROR_STATE);
    CHECK(hr_scene_occluded(open, rays, 1, 0, INFINITY, found) == HR_ERROR_STATE);
    hr_scene_destroy(open);
}

/* A slab [-1, 1]^2 x [0, 1] whose hit asks for room for 200 hits (so the
 * batch's list on the stack must move to the heap) and then answers its top
 * face, or fails for a ray whose origin has x > 0.5. */
static hr_status rogue_create(const hr_create_args *a, void **out)
{
    *out = (void *)a->host;
    return HR_OK;
}

static void rogue_destroy(void *shape) { (void)shape; }

static void rogue_bounds(const void *shape, hr_bounds *b) { *b = (hr_bounds){{-1, -1, 0}, {1, 1, 1}}, (void)shape; }

static hr_status rogue_hit(const hr_hit_args *a)
{
    const hr_host *host = a->shape;
    const hr_ray r = a->ray;
    hr_status st = host->reserve(a->call, a->out, a->out->count + 200);
    if (st == HR_OK && r.origin.x > 0.5) st = HR_ERROR_NUMERIC;
    const double t = r.dir.z < 0 ? (1 - r.origin.z) / r.dir.z : -1;
    const hr_vec3 p = {r.origin.x + t * r.dir.x, r.origin.y + t * r.dir.y, 1};
    if (st == HR_OK && t > a->tmin && t < a->tmax && fabs(p.x) <= 1 && fabs(p.y) <= 1)
        a->out->hits[a->out->count++] = (hr_hit){.t = t, .point = p, .normal = {0, 0, 1}, .entering = 1};
    return st;
}

static const hr_shape_class rogue_class = {
    .struct_size = sizeof(hr_shape_class), .name = "rogueSlab",
    .help = "a slab that asks for room, and fails for x > 0.5", .surface_count = 1,
    .create = rogue_create, .destroy = rogue_destroy, .bounds = rogue_bounds, .hit = rogue_hit,
};

/* 64 rays down -z, origins x from -0.99 up in steps of 1/32 (a packet's
 * worth of coherence): those with x <= 0.5 trace as single rays do, the
 * list growing to the heap on the way; with one beyond, the batch fails
 * with the shape's error naming the first such ray, and found[] is all 0. */
static void a_failing_shape_names_its_ray(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    for (int i = 0; i < 8; i++) {
        hr_transform t = tb_place(-0.875 + 0.25 * i, 0.3, 2, 0.1);
        CHECK(tb_add(s, "sphere", NULL, &t) >= 0);
    }
    CHECK(tb_add(s, "rogueSlab", NULL, NULL) == 8);
    CHECK_OK(hr_scene_commit(s));
    hr_ray rays[64];
    for (int i = 0; i < 64; i++) rays[i] = (hr_ray){{-0.99 + i / 32.0, 0.3, 10}, {0.001, 0, -1}};
    tally tl = {0};
    compare_batch(s, rays, 48, 48, 0, INFINITY, &tl, "rogue, good rays"); /* x up to 0.479 */
    CHECK_MSG(tl.hits == 48, "%d hits", tl.hits);
    hr_hit hits[64];
    int32_t found[64];
    for (int i = 0; i < 64; i++) found[i] = 7;
    CHECK(hr_scene_first_hits(s, rays, 64, 0, INFINITY, hits, found) == HR_ERROR_NUMERIC);
    int bad = 0;
    while (bad < 64 && !(rays[bad].origin.x > 0.5)) bad++;
    char want[64];
    snprintf(want, sizeof want, "first hits: ray %d: a shape failed", bad);
    CHECK_MSG(strstr(hr_context_last_error(ctx), want) != NULL, "%s (want %s)", hr_context_last_error(ctx), want);
    for (int i = 0; i < 64; i++) CHECK(found[i] == 0);
    CHECK(hr_scene_occluded(s, rays, 64, 0, INFINITY, found) == HR_ERROR_NUMERIC);
    snprintf(want, sizeof want, "occluded: ray %d: a shape failed", bad);
    CHECK_MSG(strstr(hr_context_last_error(ctx), want) != NULL, "%s (want %s)", hr_context_last_error(ctx), want);
    CHECK(bad == 48);
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_register_shape_class(ctx, &rogue_class, "test_batch_queries.c"));
    coherent_batches_match_single_rays();
    random_batches_match_single_rays();
    threads_trace_batches_at_once();
    bad_arguments_are_refused();
    a_failing_shape_names_its_ray();
    hr_context_destroy(ctx);
    return hr_test_end();
}
