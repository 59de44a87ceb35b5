// Hill's affine transform pair (matrix and exact inverse), built by the
// library's own calls so a Python-built object gets bit for bit the matrices
// the SDL reader would give it. Every step post-multiplies: chaining
// translate then scale gives M = T.S (the last step acts on the object first).
#include "core.h"

#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>

namespace hitray_py {

struct Transform {
    hr_transform t;
    Transform() { hr_transform_identity(&t); }
};

namespace {

std::array<double, 16> as_array(const double *m)
{
    std::array<double, 16> a;
    for (int i = 0; i < 16; i++) a[static_cast<size_t>(i)] = m[i];
    return a;
}

std::string format3(const char *what, double a, double b, double c)
{
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s (%g, %g, %g)", what, a, b, c);
    return buf;
}

}  // namespace

void bind_transform(py::module_ &m)
{
    py::class_<Transform>(m, "Transform", "An affine transform and its exact inverse (row-major 4x4).")
        .def(py::init<>())
        .def("copy", [](const Transform &self) { return Transform(self); })
        .def("translate", [](Transform &self, double dx, double dy, double dz) {
            hr_transform_translate(&self.t, dx, dy, dz);
        })
        .def("scale", [](Transform &self, double sx, double sy, double sz) {
            if (hr_transform_scale(&self.t, sx, sy, sz) != HR_OK)
                raise_error(HR_ERROR_NUMERIC,
                            format3("scale", sx, sy, sz) +
                                ": a zero factor has no inverse, or the product leaves double's range");
        })
        .def("rotate", [](Transform &self, double degrees, double ux, double uy, double uz) {
            if (hr_transform_rotate(&self.t, degrees, ux, uy, uz) != HR_OK)
                raise_error(HR_ERROR_NUMERIC,
                            format3("rotate: axis", ux, uy, uz) +
                                " is the zero vector, or the product leaves double's range");
        })
        .def("compose", [](Transform &self, const Transform &other) { hr_transform_compose(&self.t, &other.t); })
        .def_static("from_matrix", [](const std::array<double, 16> &matrix) {
            Transform out;
            if (hr_transform_from_matrix(&out.t, matrix.data()) != HR_OK)
                raise_error(HR_ERROR_NUMERIC,
                            "matrix: singular, not affine (last row must be 0 0 0 1) or not finite");
            return out;
        })
        // Pickled as the pair itself, matrix and inverse bit for bit (a
        // scene shipped to another process, hitray.distributed, must trace
        // the same rays); a pair that is not finite is refused.
        .def(py::pickle(
            [](const Transform &self) { return py::make_tuple(as_array(self.t.m), as_array(self.t.inv)); },
            [](const py::tuple &state) {
                if (state.size() != 2) throw py::value_error("Transform: expected (matrix, inverse)");
                auto matrix = state[0].cast<std::array<double, 16>>(),
                     inv = state[1].cast<std::array<double, 16>>();
                Transform out;
                for (size_t i = 0; i < 16; i++) {
                    if (!std::isfinite(matrix[i]) || !std::isfinite(inv[i]))
                        raise_error(HR_ERROR_NUMERIC, "Transform: a pickled matrix is not finite");
                    out.t.m[i] = matrix[i], out.t.inv[i] = inv[i];
                }
                return out;
            }))
        .def_property_readonly("matrix", [](const Transform &self) { return as_array(self.t.m); })
        .def_property_readonly("inverse", [](const Transform &self) { return as_array(self.t.inv); });
}

}  // namespace hitray_py
