/* Raw intersection speed: the same primary rays at the same random spheres,
 * through hitray's first-hit query (Hill's getFirstHit) or Embree 3's native
 * spheres.
 *
 *   raycast --engine hitray|embree|both [--spheres N] [--rays-side S]
 *           [--threads T] [--seed K]
 *
 * The scene: N spheres with centres uniform in the unit cube and radius
 * 0.25 N^(-1/3) (a quarter of the mean spacing, so the picture, and the work
 * per ray, look alike for every N). The rays: S x S (default 1000 x 1000)
 * from a pinhole at (0.5, 0.5, -1) through a grid on the cube's front face,
 * margin included, so some rays miss everything. Both engines see the same
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

typedef struct job {
    const char *engine;
    int64_t side;
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

static void ray_of(int64_t side, int64_t i, hr_ray *ray)
{
    const double margin = 0.1;
    double u = (double)(i % side) + 0.5, v = (double)(i / side) + 0.5;
    double x = -margin + (1 + 2 * margin) * u / side, y = -margin + (1 + 2 * margin) * v / side;
    ray->origin = (hr_vec3){0.5, 0.5, -1.0};
    hr_vec3 d = {x - 0.5, y - 0.5, 1.0};
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

static int64_t trace_embree(RTCScene scene, const hr_ray *ray)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = (float)ray->origin.x, rh.ray.org_y = (float)ray->origin.y;
    rh.ray.org_z = (float)ray->origin.z;
    rh.ray.dir_x = (float)ray->dir.x, rh.ray.dir_y = (float)ray->dir.y;
    rh.ray.dir_z = (float)ray->dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = INFINITY;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : (int64_t)rh.hit.primID;
}
#endif

static void *worker(void *arg)
{
    job *jb = arg;
    const int64_t total = jb->side * jb->side;
    const int use_hitray = strcmp(jb->engine, "hitray") == 0;
    for (;;) {
        int64_t first = atomic_fetch_add(&jb->next, CHUNK);
        if (first >= total) break;
        int64_t last = first + CHUNK < total ? first + CHUNK : total;
        for (int64_t i = first; i < last; i++) {
            hr_ray ray;
            ray_of(jb->side, i, &ray);
            if (use_hitray) {
                hr_hit hit;
                int32_t found = 0;
                if (hr_scene_first_hit(jb->hr, &ray, 0.0, INFINITY, &hit, &found) != HR_OK) {
                    jb->failed = 1;
                    return NULL;
                }
                jb->ids[i] = found ? hit.object : -1;
            }
#ifdef HITRAY_BENCH_EMBREE
            else {
                jb->ids[i] = trace_embree(jb->rtc, &ray);
            }
#endif
        }
    }
    return NULL;
}

/* Trace every ray with `engine` on `threads` threads; returns the seconds. */
static double trace_all(job *jb, const char *engine)
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
    fprintf(stderr, "usage: raycast --engine hitray|embree|both [--spheres N] [--rays-side S] "
                    "[--threads T] [--seed K]\n");
    exit(2);
}

int main(int argc, char **argv)
{
    const char *engine = NULL;
    int64_t n = 100000, side = 1000;
    int threads = 1;
    uint64_t seed = 12345;
    for (int i = 1; i < argc; i++) {
        if (i + 1 >= argc) usage();
        if (!strcmp(argv[i], "--engine")) engine = argv[++i];
        else if (!strcmp(argv[i], "--spheres")) n = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--rays-side")) side = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--threads")) threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--seed")) seed = strtoull(argv[++i], NULL, 10);
        else usage();
    }
    if (!engine || n < 1 || side < 1 || threads < 1 || threads > 256 || seed == 0) usage();
    int want_hitray = !strcmp(engine, "hitray") || !strcmp(engine, "both");
    int want_embree = !strcmp(engine, "embree") || !strcmp(engine, "both");
    if (!want_hitray && !want_embree) usage();
#ifndef HITRAY_BENCH_EMBREE
    if (want_embree) {
        fprintf(stderr, "raycast: built without Embree (install libembree-dev and rebuild)\n");
        return 2;
    }
#endif

    sphere *s = malloc((size_t)n * sizeof *s);
    job jb = {0};
    jb.side = side;
    jb.threads = threads;
    jb.ids = malloc((size_t)(side * side) * sizeof *jb.ids);
    int64_t *other = want_hitray && want_embree ? malloc((size_t)(side * side) * sizeof *other) : NULL;
    if (!s || !jb.ids || (want_hitray && want_embree && !other)) {
        fprintf(stderr, "raycast: out of memory\n");
        return 1;
    }
    const double radius = 0.25 / cbrt((double)n);
    for (int64_t i = 0; i < n; i++) {
        s[i].x = next_uniform(&seed), s[i].y = next_uniform(&seed), s[i].z = next_uniform(&seed);
        s[i].r = radius;
    }

    hr_context *ctx = NULL;
    double build_s = 0, trace_s = 0;
    const char *name = want_hitray ? "hitray" : "embree";
    if (want_hitray) {
        double t0 = now();
        if (!build_hitray(&jb, s, n, &ctx)) {
            fprintf(stderr, "raycast: hitray: %s\n", ctx ? hr_context_last_error(ctx) : "no context");
            return 1;
        }
        build_s = now() - t0;
        trace_s = trace_all(&jb, "hitray");
        if (trace_s < 0) {
            fprintf(stderr, "raycast: hitray: %s\n", hr_context_last_error(ctx));
            return 1;
        }
    }
#ifdef HITRAY_BENCH_EMBREE
    if (want_embree) {
        if (other) memcpy(other, jb.ids, (size_t)(side * side) * sizeof *other);
        double t0 = now();
        if (!build_embree(&jb, s, n)) {
            fprintf(stderr, "raycast: embree: the scene did not build\n");
            return 1;
        }
        double eb = now() - t0;
        double et = trace_all(&jb, "embree");
        if (!want_hitray) build_s = eb, trace_s = et;
    }
#endif
    if (other) { /* report hitray's answers; the agreement is symmetric */
        int64_t *swap = jb.ids;
        jb.ids = other, other = swap;
    }
    int64_t hits = 0, agree = 0;
    uint64_t checksum = 0;
    for (int64_t i = 0; i < side * side; i++) {
        if (jb.ids[i] >= 0) hits++, checksum += (uint64_t)jb.ids[i] * (uint64_t)(i + 1);
        if (other && other[i] == jb.ids[i]) agree++;
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    printf("engine=%s spheres=%lld rays=%lld threads=%d build_s=%.6f trace_s=%.6f "
           "rays_per_s=%.0f hits=%lld checksum=%llu peak_rss_kb=%ld",
           name, (long long)n, (long long)(side * side), threads, build_s, trace_s,
           (double)(side * side) / trace_s, (long long)hits, (unsigned long long)checksum,
           ru.ru_maxrss);
    if (other) printf(" same_first_object=%lld", (long long)agree);
    printf("\n");
#ifdef HITRAY_BENCH_EMBREE
    if (want_embree) {
        rtcReleaseScene(jb.rtc);
        rtcReleaseDevice(device);
    }
#endif
    if (jb.hr) hr_scene_destroy(jb.hr);
    if (ctx) hr_context_destroy(ctx);
    free(other);
    free(jb.ids);
    free(s);
    return 0;
}
