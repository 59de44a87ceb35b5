// hitray._core: the compiled half of the package. Each bind_* lives in the
// file named for its job; the public Python API is in hitray/*.py.
#include "core.h"

PYBIND11_MODULE(_core, m)
{
    m.doc() = "hitray's compiled core: a thin layer over libhitray's C API. "
              "Use the package `hitray`, not this module.";
    if (!hitray_py::context()) throw std::runtime_error("hitray: cannot create a context (out of memory)");
    hitray_py::bind_context(m);
    hitray_py::bind_transform(m);
    hitray_py::bind_camera(m);
    hitray_py::bind_fields(m);
    hitray_py::bind_scene(m);
    hitray_py::bind_trace(m);
    hitray_py::bind_render(m);
    hitray_py::bind_image(m);
    hitray_py::bind_sdl(m);
}
