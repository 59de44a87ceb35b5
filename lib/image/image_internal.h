/* Internal: an image whose pixels are left as they come, for a writer
 * that stores every one of them before anyone reads it (hr_render: the
 * tiles cover the image, and an image whose render stopped early is
 * destroyed unread). Zeroing it first would write every page twice, once
 * in the single thread before the render starts. */
#ifndef HITRAY_LIB_IMAGE_INTERNAL_H
#define HITRAY_LIB_IMAGE_INTERNAL_H

#include <hitray/image.h>

/* hr_image_create without the zeroing: the same checks, errors and
 * alignment. */
hr_status hri_image_create_unset(hr_context *ctx, int32_t width, int32_t height, int32_t channels,
                                hr_image **out);

#endif
