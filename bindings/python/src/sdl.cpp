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

// Runs a reader with the GIL released (a module's create, a mesh reading
// its file or a Python shape, runs inside it) and converts its result.
template <typename Read> py::tuple load_with(Read read)
{
    hr_sdl_result r{};
    r.struct_size = sizeof r;
    hr_status st;
    {
        py::gil_scoped_release release;
        st = read(&r);
    }
    check(st);
    return result_tuple(r);
}

const char *or_null(const py::object &o, const std::string &s)
{
    return o.is_none() ? nullptr : s.c_str();
}

py::tuple load_file(const py::bytes &path)
{
    std::string p = path;
    return load_with([&](hr_sdl_result *r) { return hr_sdl_load_file(context(), p.c_str(), r); });
}

py::tuple load_string(const py::bytes &text, const py::object &name, const py::object &base_dir)
{
    std::string t = text;
    std::string n = name.is_none() ? std::string() : name.cast<std::string>();
    std::string b = base_dir.is_none() ? std::string() : base_dir.cast<std::string>();
    return load_with([&](hr_sdl_result *r) {
        return hr_sdl_load_string(context(), t.c_str(), or_null(name, n), or_null(base_dir, b), r);
    });
}

py::tuple load_nff_file(const py::bytes &path)
{
    std::string p = path;
    return load_with([&](hr_sdl_result *r) { return hr_nff_load_file(context(), p.c_str(), r); });
}

py::tuple load_nff_string(const py::bytes &text, const py::object &name)
{
    std::string t = text;
    std::string n = name.is_none() ? std::string() : name.cast<std::string>();
    return load_with([&](hr_sdl_result *r) {
        return hr_nff_load_string(context(), t.c_str(), or_null(name, n), r);
    });
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
