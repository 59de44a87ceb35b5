/* The scene's doors to its pixmaps (Hill's makePixmap): the pixmaps
 * themselves are texture's (lib/texture/pixmap.c). */
#include "scene/scene_internal.h"
#include "texture/texture.h"
#include "util/errors.h"

HR_API int32_t hr_scene_has_pixmap(const hr_scene *s, int32_t index)
{
    return s && hri_pixmap_find(&s->pixmaps, index) != NULL;
}

HR_API hr_status hr_scene_set_pixmap(hr_scene *s, int32_t index, const hr_image *image)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (image && s->committed)
        return hri_error(s->ctx, HR_ERROR_STATE, "cannot make a pixmap in a committed scene");
    if (!image) return hri_pixmap_add(s->ctx, &s->pixmaps, index, image);
    char what[64];
    const uint64_t bytes = hri_pixmap_bytes(image, index, what, sizeof what);
    hr_status st = hri_scene_budget_charge(s->ctx, &s->budget, &s->budget.texels, bytes, "%s", what);
    if (st) return st;
    if ((st = hri_pixmap_add(s->ctx, &s->pixmaps, index, image))) s->budget.texels -= bytes;
    return st;
}
