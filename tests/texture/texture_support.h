/* Helpers of the texture tests: scenes from SDL text, one ray's colour. */
#ifndef HR_TEST_TEXTURE_SUPPORT_H
#define HR_TEST_TEXTURE_SUPPORT_H

#include <hitray/hitray.h>

/* The committed scene of `text` (NULL after a failed check); `base_dir`
 * for relative files, may be NULL. */
hr_scene *tx_scene(hr_context *ctx, const char *text, const char *base_dir);
/* Hill's shade along the ray from `origin` in direction `dir`. */
hr_color tx_shade(const hr_scene *s, hr_vec3 origin, hr_vec3 dir);
/* The colour seen looking straight down -z at (x, y) from z = 10. */
hr_color tx_down(const hr_scene *s, double x, double y);
/* Render at w x h with `threads` threads (the scene's camera), textures
 * point-sampled (HR_TEXTURE_FILTER_NONE: Hill's formulas, as the
 * references have them); tx_render_filtered with the given filter. */
hr_image *tx_render_filtered(hr_context *ctx, const hr_scene *s, const hr_camera *cam, int32_t w, int32_t h,
                             int32_t threads, int32_t filter);
hr_image *tx_render(hr_context *ctx, const hr_scene *s, const hr_camera *cam, int32_t w, int32_t h,
                    int32_t threads);
/* The effects an 8 x 6 render of the scene ran (hr_render_stats.effects). */
uint32_t tx_effects_ran(const hr_scene *s, const hr_camera *cam);
/* The message of the load of `text`, which must fail with `status` (the
 * message is kept in a static buffer until the next call). */
const char *tx_load_error(hr_context *ctx, const char *text, const char *base_dir, hr_status status);
/* A directory of its own for files a test writes (created; malloc'd path). */
char *tx_temp_dir(void);

#endif
