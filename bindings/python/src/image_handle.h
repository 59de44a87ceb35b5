// The owner of one hr_image (pixels shared zero-copy with numpy through the
// buffer protocol) and the statistics of the render that made it.
#pragma once

#include "core.h"

#include <memory>

namespace hitray_py {

struct ImageHandle {
    hr_image *image = nullptr;
    hr_render_stats stats{};
    bool has_stats = false;
    explicit ImageHandle(hr_image *i) : image(i) {}
    ImageHandle(const ImageHandle &) = delete;
    ImageHandle &operator=(const ImageHandle &) = delete;
    ~ImageHandle() { hr_image_destroy(image); }
};

using ImagePtr = std::shared_ptr<ImageHandle>;

}  // namespace hitray_py
