// Conversions between the library's types and Python values: text from the
// library, vectors and colours as tuples, Hill's camera as a tuple.
#include "core.h"

namespace hitray_py {

py::str text(const std::string &s)
{
    PyObject *o = PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "backslashreplace");
    if (!o) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(o);
}

py::str path_text(const std::string &s)
{
    PyObject *o = PyUnicode_DecodeFSDefaultAndSize(s.data(), static_cast<Py_ssize_t>(s.size()));
    if (!o) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(o);
}

py::tuple tuple_of(const hr_vec3 &v) { return py::make_tuple(v.x, v.y, v.z); }
py::tuple tuple_of(const hr_color &c) { return py::make_tuple(c.r, c.g, c.b); }

hr_camera camera_from(const vec3 &eye, const vec3 &look, const vec3 &up, double angle,
                      int32_t width, int32_t height)
{
    hr_camera cam;
    hr_camera_default(&cam);
    cam.eye = to_vec3(eye);
    cam.look = to_vec3(look);
    cam.up = to_vec3(up);
    cam.view_angle = angle;
    cam.width = width;
    cam.height = height;
    return cam;
}

py::tuple camera_tuple(const hr_camera &cam)
{
    return py::make_tuple(tuple_of(cam.eye), tuple_of(cam.look), tuple_of(cam.up), cam.view_angle);
}

const char *param_type_name(int32_t type)
{
    return type == HR_PARAM_NUMBER    ? "number"
           : type == HR_PARAM_STRING  ? "string"
           : type == HR_PARAM_NUMBERS ? "numbers"
                                      : "object";
}

}  // namespace hitray_py
