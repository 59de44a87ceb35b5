// Shared declarations of the extension hitray._core: the package's one
// context, turning a status into the right hitray.Error, and converting
// Hill's vectors and colours to and from Python tuples.
#pragma once

#include <pybind11/pybind11.h>

#include <array>
#include <string>

#include <hitray/hitray.h>

namespace py = pybind11;

namespace hitray_py {

// The one context the package uses for everything (scenes, SDL, images),
// created on first use and never destroyed: modules it loaded and shape
// classes registered on it (through hitray.abi) must outlive every scene.
hr_context *context();

// What the library said about a failure, copied out of the calling thread's
// error slot so it can be raised later with the GIL held.
struct ErrorReport {
    hr_status status = HR_OK;
    std::string message;
    std::string file;
    int line = 0;
    int column = 0;
};

// Read the calling thread's last error on the package's context; falls back
// to the status name when the slot holds no message for this status.
ErrorReport capture_error(hr_status status);
// Raise the hitray.Error subclass for the report (needs the GIL).
[[noreturn]] void raise_error(const ErrorReport &report);
[[noreturn]] void raise_error(hr_status status, const std::string &message);
// Raise when status is not HR_OK (call with the GIL held, right after the
// failing call on the same thread).
inline void check(hr_status status)
{
    if (status != HR_OK) raise_error(capture_error(status));
}

// Text from the library (messages may quote file names in any encoding):
// undecodable bytes become escapes instead of an exception.
py::str text(const std::string &s);
// A path as Python's os.fsdecode would give it.
py::str path_text(const std::string &s);
// "number", "string", "numbers" or "object": an HR_PARAM_* type by name.
const char *param_type_name(int32_t type);

using vec3 = std::array<double, 3>;
inline hr_vec3 to_vec3(const vec3 &v) { return hr_vec3{v[0], v[1], v[2]}; }
inline hr_color to_color(const vec3 &v) { return hr_color{v[0], v[1], v[2]}; }
py::tuple tuple_of(const hr_vec3 &v);
py::tuple tuple_of(const hr_color &c);

// A camera crosses the boundary as (eye, look, up, view_angle) plus a size.
hr_camera camera_from(const vec3 &eye, const vec3 &look, const vec3 &up, double angle,
                      int32_t width, int32_t height);
py::tuple camera_tuple(const hr_camera &cam);

void bind_context(py::module_ &m);
void bind_transform(py::module_ &m);
void bind_camera(py::module_ &m);
void bind_fields(py::module_ &m);
void bind_scene(py::module_ &m);
void bind_trace(py::module_ &m);
void bind_render(py::module_ &m);
void bind_image(py::module_ &m);
void bind_sdl(py::module_ &m);

}  // namespace hitray_py
