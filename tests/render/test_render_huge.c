/* The largest render hr_render accepts: 65536 pixels a side, tile size 1,
 * is 2^31 or more tiles, past int32. Cancelled at the first tile, it must
 * report the cancel (not overflow its tile count into nothing done, a
 * spurious out of memory or an image never rendered). The image alone is
 * 24 GiB (untouched pages cost nothing); where it cannot be had, the test
 * says so and passes. */
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

/* Sanitizer allocators abort on a failed allocation by default; this test
 * needs the NULL it can skip on. (Visible: the build hides symbols.) */
#define HR_SANITIZER_HOOK __attribute__((visibility("default"), used))
HR_SANITIZER_HOOK const char *__asan_default_options(void);
HR_SANITIZER_HOOK const char *__asan_default_options(void) { return "allocator_may_return_null=1"; }
HR_SANITIZER_HOOK const char *__tsan_default_options(void);
HR_SANITIZER_HOOK const char *__tsan_default_options(void) { return "allocator_may_return_null=1"; }

static int32_t calls;

static int32_t cancel_at_once(void *user, double fraction)
{
    (void)user, (void)fraction;
    calls++;
    return 1;
}

static void huge(hr_context *ctx, int32_t w, int32_t h)
{
    hr_image *probe = NULL;
    if (hr_image_create(ctx, w, h, 3, &probe) != HR_OK) {
        printf("skipped %dx%d: no memory for the image here\n", (int)w, (int)h);
        return;
    }
    hr_image_destroy(probe);
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    CHECK(tb_add(s, "sphere", NULL, NULL) >= 0);
    CHECK_OK(hr_scene_commit(s));
    hr_camera cam;
    hr_camera_default(&cam);
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = w, o.height = h;
    o.tile_size = 1;
    o.threads = 2;
    o.progress = cancel_at_once;
    calls = 0;
    hr_image *img = NULL;
    hr_status st = hr_render(s, &cam, &o, &img, NULL);
    CHECK_MSG(st == HR_ERROR_CANCELLED && calls == 1 && img == NULL,
              "%dx%d, tile 1: status %d (%s), %d progress calls", (int)w, (int)h, (int)st,
              hr_context_last_error(ctx), (int)calls);
    hr_image_destroy(img);
    hr_scene_destroy(s);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    huge(ctx, 65536, 32768); /* 2^31 tiles */
    huge(ctx, 65536, 65536); /* 2^32 tiles */
    hr_context_destroy(ctx);
    return hr_test_end();
}
