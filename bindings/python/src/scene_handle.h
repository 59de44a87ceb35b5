// The owner of one hr_scene, shared between the Python Scene that builds it
// and every render or trace still using it (so dropping the Python object
// mid-render is safe). Commit happens once; a committed scene is immutable
// and any number of threads may query it.
#pragma once

#include "core.h"

#include <memory>

namespace hitray_py {

struct SceneHandle {
    hr_scene *scene = nullptr;
    explicit SceneHandle(hr_scene *s) : scene(s) {}
    SceneHandle(const SceneHandle &) = delete;
    SceneHandle &operator=(const SceneHandle &) = delete;
    ~SceneHandle() { hr_scene_destroy(scene); }
};

using ScenePtr = std::shared_ptr<SceneHandle>;

// The scene's handle, refusing one that is not committed (HR_ERROR_STATE).
const hr_scene *committed_scene(const ScenePtr &s);

}  // namespace hitray_py
