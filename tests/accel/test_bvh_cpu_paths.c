/* The scene's first-hit walk on each CPU path: HITRAY_CPU=sse2 walks the
 * 4-wide tree with SSE2, the default on an AVX2 CPU the 8-wide tree
 * (accel/bvh8.h), which meets leaves in another order. The tie rule makes
 * the first hit the same whatever the order, so each path, in a child
 * process of its own (the path is fixed at a process's first check), must
 * give the same hits, byte for byte, on random rays into nested and
 * overlapping spheres and cubes, a third of them added twice at the same
 * place (exact ties in t, the copy with another material), from outside
 * the cloud, from inside it and from earlier hits. */
#define _POSIX_C_SOURCE 200809L /* setenv, fork */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <hitray/hitray.h>
#include <hitray/shape_kit.h>

#include "hr_test.h"
#include "scene_builder.h"

#define OBJECTS 3000
#define RAYS (HR_TEST_SANITIZED ? 20000 : 200000)

static double uniform(uint64_t *s)
{
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * 0x1p-53;
}

/* What one path answers: per ray, found, then the hit (zeroed if none). */
typedef struct answer {
    int32_t found;
    int32_t pad;
    hr_hit hit;
} answer;

/* In the child: the scene, the rays, the answers into `out`. */
static int trace_all(answer *out)
{
    hr_context *ctx;
    hr_scene *s;
    if (hr_context_create(&ctx) != HR_OK || hr_scene_create(ctx, &s) != HR_OK) return 0;
    hr_material a, b;
    hr_material_default(&a);
    hr_material_default(&b);
    b.diffuse = (hr_color){0.1, 0.9, 0.1};
    uint64_t seed = 26;
    for (int i = 0; i < OBJECTS; i++) {
        hr_transform t = tb_place(20 * uniform(&seed) - 10, 20 * uniform(&seed) - 10, 20 * uniform(&seed) - 10,
                                  0.05 + 0.6 * uniform(&seed));
        const char *shape = i % 4 == 3 ? "cube" : "sphere";
        if (tb_add(s, shape, &a, &t) < 0) return 0;
        if (i % 3 == 0 && tb_add(s, shape, &b, &t) < 0) return 0;
    }
    if (hr_scene_commit(s) != HR_OK) return 0;
    uint64_t rs = 2026;
    for (int i = 0; i < RAYS; i++) {
        hr_ray ray;
        const double far = i % 2 ? 30.0 : 8.0; /* outside the cloud, or inside it */
        ray.origin = (hr_vec3){far * (2 * uniform(&rs) - 1), far * (2 * uniform(&rs) - 1), far * (2 * uniform(&rs) - 1)};
        ray.dir = (hr_vec3){-ray.origin.x + 10 * uniform(&rs) - 5, -ray.origin.y + 10 * uniform(&rs) - 5,
                            -ray.origin.z + 10 * uniform(&rs) - 5};
        double tmin = 0.0;
        /* Every fourth ray leaves the last hit, as a bounce does. */
        if (i % 4 == 3 && out[i - 1].found) {
            ray.origin = out[i - 1].hit.point;
            tmin = 1e-9;
        }
        memset(&out[i], 0, sizeof out[i]);
        if (hr_scene_first_hit(s, &ray, tmin, INFINITY, &out[i].hit, &out[i].found) != HR_OK) return 0;
    }
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
    return 1;
}

/* Runs trace_all in a child with HITRAY_CPU=cpu (NULL: unset); 1 if it ran. */
static int on_path(const char *cpu, answer *out)
{
    int fd[2];
    if (pipe(fd) != 0) return 0;
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        close(fd[0]);
        if (cpu) setenv("HITRAY_CPU", cpu, 1);
        else unsetenv("HITRAY_CPU");
        int ok = trace_all(out);
        const char *p = (const char *)out;
        for (size_t left = ok ? RAYS * sizeof *out : 0; left > 0;) {
            ssize_t n = write(fd[1], p, left);
            if (n <= 0) _exit(2);
            p += n, left -= (size_t)n;
        }
        _exit(ok ? 0 : 1);
    }
    close(fd[1]);
    char *p = (char *)out;
    size_t got = 0;
    for (ssize_t n; got < RAYS * sizeof *out && (n = read(fd[0], p + got, RAYS * sizeof *out - got)) > 0;)
        got += (size_t)n;
    close(fd[0]);
    int status = 0;
    CHECK(pid > 0 && waitpid(pid, &status, 0) == pid);
    CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0 && got == RAYS * sizeof *out,
              "HITRAY_CPU=%s: the child failed", cpu ? cpu : "(unset)");
    return got == RAYS * sizeof *out;
}

int main(void)
{
    answer *sse2 = calloc(RAYS, sizeof *sse2), *native = calloc(RAYS, sizeof *native);
    CHECK(sse2 && native);
    if (!shape_cpu_has_avx2()) {
        fprintf(stderr, "no AVX2 here: one path only, nothing to compare\n");
        return hr_test_end();
    }
    if (on_path("sse2", sse2) && on_path(NULL, native)) {
        long found = 0, differ = 0;
        for (int i = 0; i < RAYS; i++) {
            found += sse2[i].found;
            differ += memcmp(&sse2[i], &native[i], sizeof sse2[i]) != 0;
        }
        fprintf(stderr, "%d rays, %ld hits, %ld differ between HITRAY_CPU=sse2 and the default path\n", RAYS, found,
                differ);
        CHECK(found > RAYS / 4);
        CHECK_MSG(differ == 0, "%ld of %d first hits differ between the CPU paths", differ, RAYS);
    }
    free(sse2);
    free(native);
    return hr_test_end();
}
