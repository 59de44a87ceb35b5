#define _POSIX_C_SOURCE 200809L /* mkdtemp, strdup */
#include "texture_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"

hr_scene *tx_scene(hr_context *ctx, const char *text, const char *base_dir)
{
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    if (hr_sdl_load_string(ctx, text, "test.sdl", base_dir, &r) != HR_OK) {
        CHECK_MSG(0, "load: %s", hr_context_last_error(ctx));
        return NULL;
    }
    CHECK_OK(hr_scene_commit(r.scene));
    return r.scene;
}

hr_color tx_shade(const hr_scene *s, hr_vec3 origin, hr_vec3 dir)
{
    hr_ray ray = {origin, dir};
    hr_color c = {-1, -1, -1};
    CHECK_OK(hr_scene_shade(s, &ray, -1, &c));
    return c;
}

hr_color tx_down(const hr_scene *s, double x, double y)
{
    return tx_shade(s, (hr_vec3){x, y, 10}, (hr_vec3){0, 0, -1});
}

hr_image *tx_render_filtered(hr_context *ctx, const hr_scene *s, const hr_camera *cam, int32_t w, int32_t h,
                             int32_t threads, int32_t filter)
{
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = w, o.height = h, o.threads = threads, o.tile_size = 8, o.texture_filter = filter;
    hr_image *img = NULL;
    CHECK_MSG(hr_render(s, cam, &o, &img, NULL) == HR_OK, "render: %s", hr_context_last_error(ctx));
    return img;
}

hr_image *tx_render(hr_context *ctx, const hr_scene *s, const hr_camera *cam, int32_t w, int32_t h,
                    int32_t threads)
{
    return tx_render_filtered(ctx, s, cam, w, h, threads, HR_TEXTURE_FILTER_NONE);
}

uint32_t tx_effects_ran(const hr_scene *s, const hr_camera *cam)
{
    hr_render_stats st = {0};
    st.struct_size = sizeof st;
    hr_render_options o;
    hr_render_options_default(&o);
    o.width = 8, o.height = 6;
    hr_image *img = NULL;
    CHECK_OK(hr_render(s, cam, &o, &img, &st));
    hr_image_destroy(img);
    return st.effects;
}

const char *tx_load_error(hr_context *ctx, const char *text, const char *base_dir, hr_status status)
{
    static char message[1024];
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    hr_status st = hr_sdl_load_string(ctx, text, "test.sdl", base_dir, &r);
    CHECK_MSG(st == status, "load gave status %d, expected %d (%s)", (int)st, (int)status,
              st ? hr_context_last_error(ctx) : "no error");
    if (st == HR_OK) {
        hr_scene_destroy(r.scene);
        return "";
    }
    snprintf(message, sizeof message, "%s", hr_context_last_error(ctx));
    return message;
}

char *tx_temp_dir(void)
{
    const char *base = getenv("TMPDIR");
    char templ[4096];
    snprintf(templ, sizeof templ, "%s/hitray-texture-XXXXXX", base && *base ? base : "/tmp");
    char *made = mkdtemp(templ);
    CHECK_MSG(made != NULL, "mkdtemp failed");
    return made ? strdup(made) : NULL;
}
