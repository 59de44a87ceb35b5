// hitray._core.Image: an hr_image whose float pixels numpy sees in place
// (buffer protocol: H x W x C float32, writable), its render statistics,
// the library's writers (PNG, EXR, PPM, PFM; always a complete file) and
// its reader (PNG, BMP, JPEG: for pixmaps).
#include "image_handle.h"

#include <pybind11/numpy.h>

#include <cstring>

namespace hitray_py {

namespace {

ImagePtr from_array(const py::array_t<float, py::array::c_style | py::array::forcecast> &a)
{
    if (a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4))
        throw py::value_error("image: expected an H x W x 3 (or x 4) array");
    if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > INT32_MAX || a.shape(1) > INT32_MAX)
        throw py::value_error("image: width and height must be at least 1");
    hr_image *img = nullptr;
    check(hr_image_create(context(), static_cast<int32_t>(a.shape(1)), static_cast<int32_t>(a.shape(0)),
                          static_cast<int32_t>(a.shape(2)), &img));
    std::memcpy(hr_image_data(img), a.data(), static_cast<size_t>(a.size()) * sizeof(float));
    return std::make_shared<ImageHandle>(img);
}

// A PNG, BMP or JPEG file as linear pixels (hr_image_read).
ImagePtr read(const py::bytes &path)
{
    std::string p = path;
    hr_image *img = nullptr;
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_image_read(context(), p.c_str(), &img);
    }
    check(st);
    return std::make_shared<ImageHandle>(img);
}

py::buffer_info pixels(ImageHandle &self)
{
    const ssize_t h = hr_image_height(self.image), w = hr_image_width(self.image);
    const ssize_t c = hr_image_channels(self.image);
    const ssize_t f = sizeof(float);
    return py::buffer_info(hr_image_data(self.image), f, py::format_descriptor<float>::format(), 3,
                           {h, w, c}, {w * c * f, c * f, f});
}

void save(const ImagePtr &self, const py::bytes &path, int32_t format, int32_t bits, bool linear, bool half)
{
    hr_image_write_options o;
    hr_image_write_options_default(&o);
    o.format = format;
    o.png_bits = bits;
    o.png_linear = linear ? 1 : 0;
    o.exr_half = half ? 1 : 0;
    std::string p = path;
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_image_write(context(), self->image, p.c_str(), &o);
    }
    check(st);
}

py::object stats(const ImagePtr &self)
{
    if (!self->has_stats) return py::none();
    const hr_render_stats &s = self->stats;
    py::dict d;
    d["threads"] = s.threads;
    d["primary"] = s.primary;
    d["shadow"] = s.shadow;
    d["reflected"] = s.reflected;
    d["refracted"] = s.refracted;
    d["seconds"] = s.seconds;
    d["pixels_refined"] = s.pixels_refined;
    d["samples_saved"] = s.samples_saved;
    d["rays_cut"] = s.rays_cut;
    py::list effects;
    for (uint32_t e = 1; e < (1u << HR_EFFECT_COUNT); e <<= 1)
        if (s.effects & e) effects.append(hr_effect_name(e));
    d["effects"] = effects;
    return d;
}

}  // namespace

void bind_image(py::module_ &m)
{
    py::class_<ImageHandle, ImagePtr>(m, "Image", py::buffer_protocol(),
                                      "Linear float pixels (see hitray.Image for the public API).")
        .def_static("from_array", &from_array, py::arg("array"))
        .def_static("read", &read, py::arg("path"))
        .def_buffer(&pixels)
        .def_property_readonly("width", [](const ImagePtr &s) { return hr_image_width(s->image); })
        .def_property_readonly("height", [](const ImagePtr &s) { return hr_image_height(s->image); })
        .def_property_readonly("channels", [](const ImagePtr &s) { return hr_image_channels(s->image); })
        .def_property_readonly("stats", &stats)
        .def("save", &save, py::arg("path"), py::arg("format"), py::arg("bits"), py::arg("linear"),
             py::arg("half"));
}

}  // namespace hitray_py
