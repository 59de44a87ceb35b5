/* Raw intersection speed: the same rays at the same random spheres,
 * through hitray's first-hit query (Hill's getFirstHit) one ray at a time or
 * by batches, or Embree 3's native spheres one ray at a time or by packets.
 *
 *   raycast --engine E[,E...] [--rays camera|random] [--spheres N]
 *           [--rays-side S] [--threads T] [--seed K]
 *
 * Engines: hitray (hr_scene_first_hit per ray), hitray-batch
 * (hr_scene_first_hits on each chunk of rays a thread takes), embree
 * (rtcIntersect1 per ray), embree8 (rtcIntersect8 on 8 rays side by side)
 * and embree1M (rtcIntersect1M, the stream call, on each chunk); both is
 * hitray,embree. Several engines trace the same rays in turn, each its
 * own line, then a line of ratios (rays per second) against the first. Embree's
 * packet calls are told the rays are coherent (RTC_INTERSECT_CONTEXT_FLAG_COHERENT)
 * for camera rays, incoherent for random ones.
 *
 * The scene: N spheres with centres uniform in the unit cube and radius
 * 0.25 N^(-1/3) (a quarter of the mean spacing, so the picture, and the work
 * per ray, look alike for every N). The rays: S x S (default 1000 x 1000)
 * from a pinhole at (0.5, 0.5, -1) through a grid on the cube's front face,
 * margin included, so some rays miss everything (--rays camera, the
 * default: coherent, neighbours in a chunk are neighbouring pixels), or
 * S x S rays from uniform points in the cube in uniform directions (--rays
 * random: incoherent, most start among the spheres). Every engine sees the same
 * spheres: hitray as its generic sphere under translate + scale, Embree as
 * RTC_GEOMETRY_TYPE_SPHERE_POINT (float x, y, z, r).
 *
 * Prints one line of key=value pairs: the build time of the acceleration
 * structure (hitray: add + commit; Embree: buffer + commit), the trace time
 * of all rays and rays per second, the rays that hit, a checksum of the hit
 * object ids, and the peak resident memory of the process. `--engine both`
 * (only with Embree) traces with both and prints how many rays name the same
 * first object: Embree works in float, hitray in double, so a few rays that
 * graze a silhouette may differ. Threads take chunks of rays from a shared
 * counter. Timing uses CLOCK_MONOTONIC; nothing else runs between the clock
 * reads. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include <hitray/hitray.h>

#ifdef HITRAY_BENCH_EMBREE
#include <embree3/rtcore.h>
#endif

#define CHUNK 256 /* rays a thread takes at a time */

typedef struct sphere {
    double x, y, z, r;
} sphere;

enum engine { HITRAY, HITRAY_BATCH, EMBREE, EMBREE8, EMBREE1M, ENGINES };
static const char *const engine_names[ENGINES] = {"hitray", "hitray-batch", "embree", "embree8", "embree1M"};

typedef struct job {
    enum engine engine;
    int64_t side;
    int random; /* --rays random */
    int threads;
    hr_scene *hr;
#ifdef HITRAY_BENCH_EMBREE
    RTCScene rtc;
#endif
    int64_t *ids; /* per ray: first object, -1 for a miss */
    atomic_llong next;
    int failed;
} job;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* xorshift64*: the same spheres for the same seed on every machine. */
static double next_uniform(uint64_t *s)
{
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1p-53;
}

/* Ray i: a camera ray, or (random) one of its own state seeded by i, so
 * every engine and thread count makes the same rays. */
static void ray_of(const job *jb, int64_t i, hr_ray *ray)
{
    hr_vec3 d;
    if (jb->random) {
        uint64_t st = 0x9E3779B97F4A7C15ull * (uint64_t)(i + 1);
        st ^= st >> 31;
        st |= 1;
        ray->origin = (hr_vec3){next_uniform(&st), next_uniform(&st), next_uniform(&st)};
        do {
            d = (hr_vec3){2 * next_uniform(&st) - 1, 2 * next_uniform(&st) - 1, 2 * next_uniform(&st) - 1};
        } while (!(d.x * d.x + d.y * d.y + d.z * d.z <= 1 && d.x * d.x + d.y * d.y + d.z * d.z > 1e-6));
    } else {
        const double margin = 0.1;
        const int64_t side = jb->side;
        double u = (double)(i % side) + 0.5, v = (double)(i / side) + 0.5;
        double x = -margin + (1 + 2 * margin) * u / side, y = -margin + (1 + 2 * margin) * v / side;
        ray->origin = (hr_vec3){0.5, 0.5, -1.0};
        d = (hr_vec3){x - 0.5, y - 0.5, 1.0};
    }
    double len = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    ray->dir = (hr_vec3){d.x / len, d.y / len, d.z / len};
}

static int build_hitray(job *jb, const sphere *s, int64_t n, hr_context **ctx)
{
    if (hr_context_create(ctx) != HR_OK || hr_scene_create(*ctx, &jb->hr) != HR_OK) return 0;
    for (int64_t i = 0; i < n; i++) {
        hr_transform t;
        hr_transform_identity(&t);
        hr_transform_translate(&t, s[i].x, s[i].y, s[i].z);
        hr_transform_scale(&t, s[i].r, s[i].r, s[i].r);
        hr_object_desc d = {0};
        d.struct_size = sizeof d;
        d.shape = "sphere";
        d.transform = t.m;
        d.inverse = t.inv;
        if (hr_scene_add_object(jb->hr, &d, NULL) != HR_OK) return 0;
    }
    return hr_scene_commit(jb->hr) == HR_OK;
}

#ifdef HITRAY_BENCH_EMBREE
static RTCDevice device;

static int build_embree(job *jb, const sphere *s, int64_t n)
{
    device = rtcNewDevice(NULL);
    if (!device) return 0;
    jb->rtc = rtcNewScene(device);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                       4 * sizeof(float), (size_t)n);
    if (!v) return 0;
    for (int64_t i = 0; i < n; i++) {
        v[4 * i] = (float)s[i].x, v[4 * i + 1] = (float)s[i].y;
        v[4 * i + 2] = (float)s[i].z, v[4 * i + 3] = (float)s[i].r;
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(jb->rtc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(jb->rtc);
    return rtcGetDeviceError(device) == RTC_ERROR_NONE;
}

static void embree_ray(const hr_ray *ray, struct RTCRayHit *rh)
{
    memset(rh, 0, sizeof *rh);
    rh->ray.org_x = (float)ray->origin.x, rh->ray.org_y = (float)ray->origin.y;
    rh->ray.org_z = (float)ray->origin.z;
    rh->ray.dir_x = (float)ray->dir.x, rh->ray.dir_y = (float)ray->dir.y;
    rh->ray.dir_z = (float)ray->dir.z;
    rh->ray.tnear = 0.0f;
    rh->ray.tfar = INFINITY;
    rh->ray.mask = 0xFFFFFFFFu;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
}

static int64_t embree_id(unsigned geom, unsigned prim)
{
    return geom == RTC_INVALID_GEOMETRY_ID ? -1 : (int64_t)prim;
}

/* Embree on rays[0 .. count) into ids: one at a time, by packets of 8 or
 * as one stream. */
static void trace_embree(const job *jb, const hr_ray *rays, int64_t count, int64_t *ids)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    if (jb->engine != EMBREE)
        ctx.flags = jb->random ? RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT : RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    if (jb->engine == EMBREE) {
        for (int64_t i = 0; i < count; i++) {
            struct RTCRayHit rh;
            embree_ray(&rays[i], &rh);
            rtcIntersect1(jb->rtc, &ctx, &rh);
            ids[i] = embree_id(rh.hit.geomID, rh.hit.primID);
        }
    } else if (jb->engine == EMBREE8) {
        for (int64_t at = 0; at < count; at += 8) {
            struct RTCRayHit8 rh;
            int valid[8];
            for (int k = 0; k < 8; k++) {
                struct RTCRayHit one;
                valid[k] = at + k < count ? -1 : 0;
                embree_ray(&rays[valid[k] ? at + k : at], &one);
                rh.ray.org_x[k] = one.ray.org_x, rh.ray.org_y[k] = one.ray.org_y, rh.ray.org_z[k] = one.ray.org_z;
                rh.ray.dir_x[k] = one.ray.dir_x, rh.ray.dir_y[k] = one.ray.dir_y, rh.ray.dir_z[k] = one.ray.dir_z;
                rh.ray.tnear[k] = 0.0f, rh.ray.tfar[k] = INFINITY, rh.ray.time[k] = 0.0f;
                rh.ray.mask[k] = 0xFFFFFFFFu, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect8(valid, jb->rtc, &ctx, &rh);
            for (int k = 0; k < 8 && at + k < count; k++) ids[at + k] = embree_id(rh.hit.geomID[k], rh.hit.primID[k]);
        }
    } else {
        struct RTCRayHit rh[CHUNK];
        for (int64_t i = 0; i < count; i++) embree_ray(&rays[i], &rh[i]);
        rtcIntersect1M(jb->rtc, &ctx, rh, (unsigned)count, sizeof rh[0]);
        for (int64_t i = 0; i < count; i++) ids[i] = embree_id(rh[i].hit.geomID, rh[i].hit.primID);
    }
}
#endif

/* hitray on rays[0 .. count) into ids: one query a ray, or one batch. */
static int trace_hitray(const job *jb, const hr_ray *rays, int64_t count, int64_t *ids)
{
    if (jb->engine == HITRAY_BATCH) {
        hr_hit hits[CHUNK];
        int32_t found[CHUNK];
        if (hr_scene_first_hits(jb->hr, rays, count, 0.0, INFINITY, hits, found) != HR_OK) return 0;
        for (int64_t i = 0; i < count; i++) ids[i] = found[i] ? hits[i].object : -1;
        return 1;
    }
    for (int64_t i = 0; i < count; i++) {
        hr_hit hit;
        int32_t found = 0;
        if (hr_scene_first_hit(jb->hr, &rays[i], 0.0, INFINITY, &hit, &found) != HR_OK) return 0;
        ids[i] = found ? hit.object : -1;
    }
    return 1;
}

static void *worker(void *arg)
{
    job *jb = arg;
    const int64_t total = jb->side * jb->side;
    const int use_hitray = jb->engine == HITRAY || jb->engine == HITRAY_BATCH;
    hr_ray rays[CHUNK];
    for (;;) {
        int64_t first = atomic_fetch_add(&jb->next, CHUNK);
        if (first >= total) break;
        int64_t count = first + CHUNK < total ? CHUNK : total - first;
        for (int64_t i = 0; i < count; i++) ray_of(jb, first + i, &rays[i]);
        if (use_hitray) {
            if (!trace_hitray(jb, rays, count, jb->ids + first)) {
                jb->failed = 1;
                return NULL;
            }
        }
#ifdef HITRAY_BENCH_EMBREE
        else {
            trace_embree(jb, rays, count, jb->ids + first);
        }
#endif
    }
    return NULL;
}

/* Trace every ray with `engine` on `threads` threads; returns the seconds. */
static double trace_all(job *jb, enum engine engine)
{
    jb->engine = engine;
    atomic_store(&jb->next, 0);
    pthread_t tid[256];
    double t0 = now();
    for (int k = 0; k < jb->threads; k++)
        if (pthread_create(&tid[k], NULL, worker, jb) != 0) return -1;
    for (int k = 0; k < jb->threads; k++) pthread_join(tid[k], NULL);
    return jb->failed ? -1 : now() - t0;
}

static void usage(void)
{
    fprintf(stderr, "usage: raycast --engine E[,E...] [--rays camera|random] [--spheres N] [--rays-side S] "
                    "[--threads T] [--seed K]\n"
                    "  engines: hitray, hitray-batch, embree, embree8, embree1M (both: hitray,embree)\n");
    exit(2);
}

/* The engines named by a comma-separated list, in order, into order[];
 * returns how many (0 on an unknown name or a repeat). */
static int parse_engines(const char *list, enum engine order[ENGINES])
{
    if (!strcmp(list, "both")) list = "hitray,embree";
    int n = 0;
    const char *p = list;
    while (*p) {
        size_t len = strcspn(p, ",");
        int found = -1;
        for (int e = 0; e < ENGINES; e++)
            if (strlen(engine_names[e]) == len && !strncmp(p, engine_names[e], len)) found = e;
        if (found < 0 || n == ENGINES) return 0;
        for (int k = 0; k < n; k++)
            if ((int)order[k] == found) return 0;
        order[n++] = (enum engine)found;
        p += len;
        if (*p == ',') p++;
    }
    return n;
}

int main(int argc, char **argv)
{
    const char *engine = NULL, *kind = "camera";
    int64_t n = 100000, side = 1000;
    int threads = 1;
    uint64_t seed = 12345;
    for (int i = 1; i < argc; i++) {
        if (i + 1 >= argc) usage();
        if (!strcmp(argv[i], "--engine")) engine = argv[++i];
        else if (!strcmp(argv[i], "--rays")) kind = argv[++i];
        else if (!strcmp(argv[i], "--spheres")) n = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--rays-side")) side = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--threads")) threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--seed")) seed = strtoull(argv[++i], NULL, 10);
        else usage();
    }
    enum engine order[ENGINES];
    int engines = engine ? parse_engines(engine, order) : 0;
    if (!engines || n < 1 || side < 1 || threads < 1 || threads > 256 || seed == 0) usage();
    if (strcmp(kind, "camera") && strcmp(kind, "random")) usage();
    int want_hitray = 0, want_embree = 0;
    for (int k = 0; k < engines; k++) {
        if (order[k] == HITRAY || order[k] == HITRAY_BATCH) want_hitray = 1;
        else want_embree = 1;
    }
#ifndef HITRAY_BENCH_EMBREE
    if (want_embree) {
        fprintf(stderr, "raycast: built without Embree (install libembree-dev and rebuild)\n");
        return 2;
    }
#endif

    const int64_t rays = side * side;
    sphere *s = malloc((size_t)n * sizeof *s);
    job jb = {0};
    jb.side = side;
    jb.threads = threads;
    jb.random = !strcmp(kind, "random");
    int64_t *first_ids = engines > 1 ? malloc((size_t)rays * sizeof *first_ids) : NULL;
    jb.ids = malloc((size_t)rays * sizeof *jb.ids);
    if (!s || !jb.ids || (engines > 1 && !first_ids)) {
        fprintf(stderr, "raycast: out of memory\n");
        return 1;
    }
    const double radius = 0.25 / cbrt((double)n);
    for (int64_t i = 0; i < n; i++) {
        s[i].x = next_uniform(&seed), s[i].y = next_uniform(&seed), s[i].z = next_uniform(&seed);
        s[i].r = radius;
    }

    hr_context *ctx = NULL;
    double build_s[2] = {0, 0}, first_rate = 0;
    if (want_hitray) {
        double t0 = now();
        if (!build_hitray(&jb, s, n, &ctx)) {
            fprintf(stderr, "raycast: hitray: %s\n", ctx ? hr_context_last_error(ctx) : "no context");
            return 1;
        }
        build_s[0] = now() - t0;
    }
#ifdef HITRAY_BENCH_EMBREE
    if (want_embree) {
        double t0 = now();
        if (!build_embree(&jb, s, n)) {
            fprintf(stderr, "raycast: embree: the scene did not build\n");
            return 1;
        }
        build_s[1] = now() - t0;
    }
#endif
    double rate[ENGINES];
    for (int k = 0; k < engines; k++) {
        const enum engine e = order[k];
        const int is_hitray = e == HITRAY || e == HITRAY_BATCH;
        double trace_s = trace_all(&jb, e);
        if (trace_s < 0) {
            fprintf(stderr, "raycast: %s: %s\n", engine_names[e], ctx ? hr_context_last_error(ctx) : "failed");
            return 1;
        }
        rate[k] = (double)rays / trace_s;
        if (k == 0) first_rate = rate[k];
        int64_t hits = 0, agree = 0;
        uint64_t checksum = 0;
        for (int64_t i = 0; i < rays; i++) {
            if (jb.ids[i] >= 0) hits++, checksum += (uint64_t)jb.ids[i] * (uint64_t)(i + 1);
            if (first_ids && k > 0 && first_ids[i] == jb.ids[i]) agree++;
        }
        if (first_ids && k == 0) memcpy(first_ids, jb.ids, (size_t)rays * sizeof *first_ids);
        /* Peak memory is the process's: with both kinds of engine it holds
         * both scenes, so only a run of one kind measures one. */
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        printf("engine=%s spheres=%lld rays=%lld ray_kind=%s threads=%d build_s=%.6f trace_s=%.6f "
               "rays_per_s=%.0f hits=%lld checksum=%llu peak_rss_kb=%ld",
               engine_names[e], (long long)n, (long long)rays, kind, threads, build_s[is_hitray ? 0 : 1],
               trace_s, rate[k], (long long)hits, (unsigned long long)checksum, ru.ru_maxrss);
        if (first_ids && k > 0) printf(" same_first_object=%lld", (long long)agree);
        printf("\n");
    }
    if (engines > 1) {
        printf("ratios (rays/s against %s):", engine_names[order[0]]);
        for (int k = 1; k < engines; k++) printf(" %s=%.3f", engine_names[order[k]], rate[k] / first_rate);
        printf("\n");
    }
    (void)first_rate;
#ifdef HITRAY_BENCH_EMBREE
    if (want_embree) {
        rtcReleaseScene(jb.rtc);
        rtcReleaseDevice(device);
    }
#endif
    if (jb.hr) hr_scene_destroy(jb.hr);
    if (ctx) hr_context_destroy(ctx);
    free(first_ids);
    free(jb.ids);
    free(s);
    return 0;
}
