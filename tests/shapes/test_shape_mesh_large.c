/* A million-triangle mesh: a UV sphere written as OBJ into the build tree,
 * read, built and traced by the module, then loaded through SDL and
 * rendered by the library. Checks: every ray aimed inside the sphere
 * enters once and leaves once, with its points on the unit sphere within
 * the tessellation's sag; rays that pass outside miss; the first-hit and
 * any-hit paths agree; the render has finite pixels and shows the mesh.
 * Prints the memory the shape keeps per triangle.
 *
 * Under AddressSanitizer or ThreadSanitizer the sphere has 40,000
 * triangles instead: a sanitizer makes every load and allocation several
 * times slower, and the
 * million-triangle size is covered by the plain build; nothing here
 * depends on the size beyond the counts printed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"
#include "random_rays.h"

/* 2 slices (stacks - 1) triangles: 1000 x 500 x 2 = 1,000,000. */
#define SLICES (HR_TEST_SANITIZED ? 200 : 1000)
#define STACKS (HR_TEST_SANITIZED ? 101 : 501)

/* --- A host that counts the bytes it hands out ------------------------------ */

static size_t live_bytes, peak_bytes;

static void *counting_alloc(size_t size)
{
    size_t *block = calloc(1, sizeof(size_t) * 2 + size);
    if (!block) return NULL;
    block[0] = size;
    live_bytes += size;
    if (live_bytes > peak_bytes) peak_bytes = live_bytes;
    return block + 2;
}

static void counting_free(void *ptr)
{
    if (!ptr) return;
    size_t *block = (size_t *)ptr - 2;
    live_bytes -= block[0];
    free(block);
}

/* --- The sphere --------------------------------------------------------------- */

static long write_sphere(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    const double pi = acos(-1.0);
    fprintf(f, "# UV sphere, %d slices, %d stacks\nv 0 0 1\n", SLICES, STACKS);
    for (int k = 1; k < STACKS; k++) {
        const double theta = pi * k / STACKS;
        for (int j = 0; j < SLICES; j++) {
            const double phi = 2 * pi * j / SLICES;
            fprintf(f, "v %.17g %.17g %.17g\n", sin(theta) * cos(phi), sin(theta) * sin(phi),
                    cos(theta));
        }
    }
    fprintf(f, "v 0 0 -1\n");
    const long south = 2 + (long)(STACKS - 1) * SLICES;
    long triangles = 0;
    /* Ring k (1-based) vertex j: 2 + (k - 1) SLICES + j; counter-clockwise
     * seen from outside. */
#define RING(k, j) (2 + (long)((k)-1) * SLICES + ((j) % SLICES))
    for (int j = 0; j < SLICES; j++, triangles++) fprintf(f, "f 1 %ld %ld\n", RING(1, j), RING(1, j + 1));
    for (int k = 1; k + 1 < STACKS; k++)
        for (int j = 0; j < SLICES; j++, triangles += 2)
            fprintf(f, "f %ld %ld %ld %ld\n", RING(k, j), RING(k + 1, j), RING(k + 1, j + 1),
                    RING(k, j + 1));
    for (int j = 0; j < SLICES; j++, triangles++)
        fprintf(f, "f %ld %ld %ld\n", south, RING(STACKS - 1, j + 1), RING(STACKS - 1, j));
#undef RING
    return fclose(f) == 0 ? triangles : -1;
}

/* The largest distance of the facets from the unit sphere: a facet's
 * corners are on it, and its middle sags by at most 1 - cos(a / 2) for the
 * largest angle a between neighbouring corners (2 pi / SLICES). Doubled for
 * the quads' diagonals; compared with a tolerance of 4x that. */
static double sag(void)
{
    const double a = 2 * acos(-1.0) / SLICES;
    return 2 * (1 - cos(a / 2)) * 2;
}

static void trace_sphere(const harness_shape *s)
{
    ray_rng rng;
    rng_seed(&rng, 77);
    const double tol = 4 * sag();
    int inside = 0, outside = 0;
    for (int i = 0; i < 4000; i++) {
        hr_vec3 o = rng_unit_vector(&rng);
        const double r = rng_uniform(&rng, 1.5, 4);
        o = harness_vec(o.x * r, o.y * r, o.z * r);
        /* Aim at a point at distance `miss` from the centre, across the ray. */
        hr_vec3 w = rng_unit_vector(&rng);
        const double miss = rng_uniform(&rng, 0, 2.0);
        hr_vec3 target = harness_vec(w.x * miss, w.y * miss, w.z * miss);
        hr_ray ray = harness_ray(o.x, o.y, o.z, target.x - o.x, target.y - o.y, target.z - o.z);
        /* Distance of the line from the centre. */
        const hr_vec3 d = ray.dir;
        const double dd = d.x * d.x + d.y * d.y + d.z * d.z;
        const double od = o.x * d.x + o.y * d.y + o.z * d.z;
        const double oo = o.x * o.x + o.y * o.y + o.z * o.z;
        const double closest = sqrt(fmax(0, oo - od * od / dd));
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(s, ray, h);
        /* The origin is outside: a ray moving away from the centre
         * (od >= 0) has the sphere behind it. */
        if (od >= 0) {
            CHECK_MSG(n == 0, "ray %d moving away: %d hits", i, n);
        } else if (closest < 1 - 20 * tol) {
            inside++;
            CHECK_MSG(n == 2 && h[0].entering == 1 && h[1].entering == 0,
                      "ray %d (closest %.9g): %d hits", i, closest, n);
            for (int k = 0; k < n; k++) {
                const hr_vec3 p = h[k].point;
                const double rr = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
                CHECK_MSG(rr <= 1 + 1e-12 && rr >= 1 - tol, "ray %d hit %d: |p| = %.17g", i, k, rr);
            }
            hr_hit first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
            CHECK(harness_trace(s, ray, 0, INFINITY, HARNESS_FIRST, first) == 1 && n > 0 &&
                  first[0].t == h[0].t);
            CHECK(harness_trace(s, ray, 0, INFINITY, HARNESS_ANY, any) == 1);
        } else if (closest > 1 + 1e-9) {
            outside++;
            CHECK_MSG(n == 0, "ray %d (closest %.9g): %d hits", i, closest, n);
        }
    }
    CHECK_MSG(inside > 1000 && outside > 500, "%d rays inside, %d outside", inside, outside);
}

static void render_sphere(const char *path)
{
    hr_context *ctx = NULL;
    CHECK_OK(hr_context_create(&ctx));
    if (!ctx) return;
    char text[2048];
    snprintf(text, sizeof text,
             "light 4 5 6 1 1 1\ncamera 0 0 5 0 0 0 0 1 0 40\ndiffuse 0.8 0.5 0.3\nmesh %s\n", path);
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    if (hr_sdl_load_string(ctx, text, "large.sdl", NULL, &r) != HR_OK) {
        CHECK_MSG(0, "load: %s", hr_context_last_error(ctx));
        hr_context_destroy(ctx);
        return;
    }
    CHECK_OK(hr_scene_commit(r.scene));
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = 64, o.height = 48, o.threads = 2;
    hr_image *img = NULL;
    CHECK_MSG(hr_render(r.scene, &r.camera, &o, &img, NULL) == HR_OK, "render: %s",
              hr_context_last_error(ctx));
    if (img) {
        const float *p = hr_image_data(img);
        int finite = 1, lit = 0;
        for (int k = 0; k < 64 * 48 * 3; k += 3) {
            finite &= isfinite(p[k]) && isfinite(p[k + 1]) && isfinite(p[k + 2]);
            lit += p[k] > p[k + 2]; /* the orange mesh, not the blue background */
        }
        CHECK_MSG(finite, "a pixel is not finite");
        /* The sphere fills about pi / (4 * 5^2 * tan^2(20 deg) * 4/3) of the frame. */
        CHECK_MSG(lit > 64 * 48 / 8, "only %d pixels show the mesh", lit);
        hr_image_destroy(img);
    }
    hr_scene_destroy(r.scene);
    hr_context_destroy(ctx);
}

int main(void)
{
    char path[1024];
    mesh_build_path("mesh_large_sphere.obj", path, sizeof path);
    const long triangles = write_sphere(path);
    CHECK(triangles == 2L * SLICES * (STACKS - 1));
    if (triangles <= 0) return hr_test_end() | 1;

    /* The module's own allocations, counted. */
    harness_module module;
    if (!harness_load("mesh", &module)) return hr_test_end() | 1;
    const hr_shape_class *cls = harness_find_class(&module, "mesh");
    hr_host host = *harness_host();
    host.alloc = counting_alloc;
    host.free = counting_free;
    hr_param param = {.name = "file", .type = HR_PARAM_STRING, .number = 0.0, .string = path, .object = 0};
    const void *objects[1] = {NULL};
    char error[512] = "";
    hr_create_args args;
    memset(&args, 0, sizeof args);
    args.struct_size = sizeof args;
    args.param_count = 1;
    args.params = &param;
    args.objects = objects;
    args.host = &host;
    args.error = error;
    args.error_size = sizeof error;
    args.base_dir = "";
    harness_shape s;
    memset(&s, 0, sizeof s);
    s.module = module;
    s.cls = cls;
    CHECK_MSG(cls->create(&args, &s.shape) == HR_OK, "create: %s", error);
    if (!s.shape) return hr_test_end() | 1;
    printf("mesh: %ld triangles, %zu bytes kept (%.1f bytes per triangle), %zu bytes at the peak "
           "of reading and building\n",
           triangles, live_bytes, (double)live_bytes / (double)triangles, peak_bytes);
    /* Vertices (24 B, half as many as triangles), corners (12 B) and nodes
     * (32 B, about one per 1.5 to 3 triangles): well under 64 B a triangle. */
    CHECK_MSG((double)live_bytes / (double)triangles < 64, "%.1f bytes per triangle",
              (double)live_bytes / (double)triangles);
    trace_sphere(&s);
    cls->destroy(s.shape);
    CHECK_MSG(live_bytes == 0, "%zu bytes not given back", live_bytes);
    harness_unload(&module);

    render_sphere(path);
    remove(path);
    return hr_test_end();
}
