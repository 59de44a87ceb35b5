// Hill's camera moves and rays, on a camera given as (eye, look, up, angle)
// and an image size: the Python Camera keeps its fields, this file runs the
// library's arithmetic on them.
#include "core.h"

#include <pybind11/stl.h>

namespace hitray_py {

namespace {

hr_camera camera_arg(const py::tuple &cam, int32_t width, int32_t height)
{
    if (cam.size() != 4) throw py::value_error("camera: expected (eye, look, up, angle)");
    return camera_from(cam[0].cast<vec3>(), cam[1].cast<vec3>(), cam[2].cast<vec3>(),
                       cam[3].cast<double>(), width, height);
}

}  // namespace

void bind_camera(py::module_ &m)
{
    m.def("camera_default", [] {
        hr_camera cam;
        hr_camera_default(&cam);
        return camera_tuple(cam);
    });
    m.def("camera_validate", [](const py::tuple &cam, int32_t width, int32_t height) {
        hr_camera c = camera_arg(cam, width, height);
        check(hr_camera_validate(context(), &c));
    });
    m.def("camera_move", [](const py::tuple &cam, const std::string &move, double a, double b, double c) {
        hr_camera cm = camera_arg(cam, 640, 480);
        if (move == "slide") hr_camera_slide(&cm, a, b, c);
        else if (move == "roll") hr_camera_roll(&cm, a);
        else if (move == "pitch") hr_camera_pitch(&cm, a);
        else if (move == "yaw") hr_camera_yaw(&cm, a);
        else throw py::value_error("camera_move: unknown move '" + move + "'");
        return camera_tuple(cm);
    });
    m.def("camera_ray", [](const py::tuple &cam, int32_t width, int32_t height, double px, double py_) {
        hr_camera c = camera_arg(cam, width, height);
        check(hr_camera_validate(context(), &c));
        hr_ray ray;
        check(hr_camera_ray(&c, px, py_, &ray));
        return py::make_tuple(tuple_of(ray.origin), tuple_of(ray.dir));
    });
}

}  // namespace hitray_py
