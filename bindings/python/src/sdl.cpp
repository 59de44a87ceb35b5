// hitray._core.load_sdl_file / load_sdl_string: Hill's SDL through the
// library's reader, on the package's context (so shape classes registered
// on it are SDL keywords too); load_nff_file / load_nff_string the same for
// NFF. Each returns (scene, camera or None).
#include "scene_handle.h"

namespace hitray_py {

namespace {

py::tuple result_tuple(const hr_sdl_result &r)
{
    auto scene = std::make_shared<SceneHandle>(r.scene);
    py::object cam = r.has_camera ? py::object(camera_tuple(r.camera)) : py::object(py::none());
    return py::make_tuple(scene, cam);
}

py::tuple load_file(const py::bytes &path)
{
    std::string p = path;
    hr_sdl_result r{};
    r.struct_size = sizeof r;
    hr_status st;
    {
        // A module's create (a mesh reading its file, a Python shape) runs here.
        py::gil_scoped_release release;
        st = hr_sdl_load_file(context(), p.c_str(), &r);
    }
    check(st);
    return result_tuple(r);
}

py::tuple load_string(const py::bytes &text, const py::object &name, const py::object &base_dir)
{
    std::string t = text;
    std::string n = name.is_none() ? std::string() : name.cast<std::string>();
    std::string b = base_dir.is_none() ? std::string() : base_dir.cast<std::string>();
    hr_sdl_result r{};
    r.struct_size = sizeof r;
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_sdl_load_string(context(), t.c_str(), name.is_none() ? nullptr : n.c_str(),
                                base_dir.is_none() ? nullptr : b.c_str(), &r);
    }
    check(st);
    return result_tuple(r);
}

py::tuple load_nff_file(const py::bytes &path)
{
    std::string p = path;
    hr_sdl_result r{};
    r.struct_size = sizeof r;
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_nff_load_file(context(), p.c_str(), &r);
    }
    check(st);
    return result_tuple(r);
}

py::tuple load_nff_string(const py::bytes &text, const py::object &name)
{
    std::string t = text;
    std::string n = name.is_none() ? std::string() : name.cast<std::string>();
    hr_sdl_result r{};
    r.struct_size = sizeof r;
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_nff_load_string(context(), t.c_str(), name.is_none() ? nullptr : n.c_str(), &r);
    }
    check(st);
    return result_tuple(r);
}

}  // namespace

void bind_sdl(py::module_ &m)
{
    m.def("load_sdl_file", &load_file, py::arg("path"));
    m.def("load_sdl_string", &load_string, py::arg("text"), py::arg("name"), py::arg("base_dir"));
    m.def("load_nff_file", &load_nff_file, py::arg("path"));
    m.def("load_nff_string", &load_nff_string, py::arg("text"), py::arg("name"));
}

}  // namespace hitray_py
