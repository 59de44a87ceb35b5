/* No allocation per ray: the number of malloc/calloc/realloc calls a render
 * makes must not grow with the number of rays. This program defines malloc
 * and its family itself (forwarding to glibc's __libc_* entry points), so
 * every allocation libhitray makes is counted while `counting` is set.
 * (Not built under the sanitizers, which own the allocator.) */
#include <stdatomic.h>
#include <stddef.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

extern void *__libc_malloc(size_t size);
extern void *__libc_calloc(size_t n, size_t size);
extern void *__libc_realloc(void *p, size_t size);
extern void __libc_free(void *p);

static atomic_int counting;
static atomic_long allocations;

void *malloc(size_t size);
void *calloc(size_t n, size_t size);
void *realloc(void *p, size_t size);
void free(void *p);

void *malloc(size_t size)
{
    if (atomic_load(&counting)) atomic_fetch_add(&allocations, 1);
    return __libc_malloc(size);
}

void *calloc(size_t n, size_t size)
{
    if (atomic_load(&counting)) atomic_fetch_add(&allocations, 1);
    return __libc_calloc(n, size);
}

void *realloc(void *p, size_t size)
{
    if (atomic_load(&counting)) atomic_fetch_add(&allocations, 1);
    return __libc_realloc(p, size);
}

void free(void *p) { __libc_free(p); }

static hr_context *ctx;

/* Every kind of ray: a mirror floor, a glass ball, a matte ball, two
 * lights, depth 5. */
static hr_scene *busy_scene(void)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.max_recursion_depth = 5;
    hr_scene_set_globals(s, &g);
    hr_material floor_m;
    hr_material_default(&floor_m);
    floor_m.reflectivity = 0.6;
    hr_transform ft;
    hr_transform_identity(&ft);
    hr_transform_rotate(&ft, -90, 1, 0, 0);
    tb_add(s, "plane", &floor_m, &ft);
    hr_material glass;
    hr_material_default(&glass);
    glass.transparency = 0.9, glass.speed_of_light = 0.67;
    hr_transform b = tb_place(1.2, 1, 0.5, 1);
    tb_add(s, "sphere", &glass, &b);
    hr_material matte;
    hr_material_default(&matte);
    for (int i = 0; i < 20; i++) {
        hr_transform t = tb_place(-3 + 0.3 * i, 0.3, -1 - 0.2 * i, 0.25);
        tb_add(s, i % 2 ? "cube" : "sphere", &matte, &t);
    }
    tb_light(s, 5, 8, 6, 1, 1, 1);
    tb_light(s, -6, 4, 3, 0.3, 0.3, 0.4);
    hr_scene_commit(s);
    return s;
}

static long allocations_of_render(hr_scene *s, int32_t size, int32_t threads, int adaptive, uint64_t *rays)
{
    hr_camera c = tb_mirror_glass_view(size, size);
    hr_render_options o;
    hr_render_options_default(&o);
    o.threads = threads;
    o.tile_size = 8;
    o.samples_per_pixel = 2;
    o.adaptive_threshold = adaptive ? 0.02 : 0;
    o.min_weight = adaptive ? 0.1 : 0;
    hr_render_stats st = {0};
    st.struct_size = sizeof st;
    hr_image *img = NULL;
    atomic_store(&allocations, 0);
    atomic_store(&counting, 1);
    hr_status status = hr_render(s, &c, &o, &img, &st);
    atomic_store(&counting, 0);
    CHECK(status == HR_OK);
    hr_image_destroy(img);
    *rays = st.primary + st.shadow + st.reflected + st.refracted;
    return atomic_load(&allocations);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    hr_scene *s = busy_scene();
    for (int adaptive = 0; adaptive < 2; adaptive++) {
        for (int32_t threads = 1; threads <= 2; threads++) {
            uint64_t small_rays, large_rays;
            long small = allocations_of_render(s, 16, threads, adaptive, &small_rays);
            long large = allocations_of_render(s, 96, threads, adaptive, &large_rays);
            CHECK(large_rays > 30 * small_rays / 2);
            /* The job, the image, the workers, each thread's scratch lists
             * and corner rows: a handful, the same for 36 times the rays.
             * (With two threads, one may find no tile left and never grow
             * its scratch: equal counts are asked of one thread only.) */
            CHECK_MSG(threads > 1 || small == large, "threads %d adaptive %d: %ld allocations for %llu rays, %ld for %llu",
                      (int)threads, adaptive, small, (unsigned long long)small_rays, large,
                      (unsigned long long)large_rays);
            CHECK_MSG(large <= 16 * threads, "%ld allocations in one render", large);
        }
    }
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
    return hr_test_end();
}
