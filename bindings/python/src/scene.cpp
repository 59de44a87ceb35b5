// hitray._core.Scene: building an hr_scene (objects, lights, globals),
// committing it, and Hill's single-ray queries on it: getFirstHit, the
// Intersection of every hit, shade. The vectorised trace is in trace.cpp.
#include "fields.h"
#include "image_handle.h"
#include "scene_handle.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <vector>

namespace hitray_py {

const hr_scene *committed_scene(const ScenePtr &s)
{
    if (!hr_scene_is_committed(s->scene))
        raise_error(HR_ERROR_STATE, "the scene is not committed");
    return s->scene;
}

namespace {

ScenePtr new_scene()
{
    hr_scene *s = nullptr;
    check(hr_scene_create(context(), &s));
    return std::make_shared<SceneHandle>(s);
}

// One parameter as the Python layer sends it: (name, kind, value), kind
// "number", "string" (bytes), "object" (an index of this scene) or
// "numbers" (a C-contiguous float64 numpy array, lent to the library for
// the call: no copy, whatever its size).
using DoubleArray = py::array_t<double, py::array::c_style>;
struct ParamArg {
    std::string name;
    std::string string;
    DoubleArray numbers; // holds the array while the library reads it
    hr_param param{};
};

int64_t add_object(const ScenePtr &s, const std::string &shape, const py::list &params,
                   const py::dict &material, const py::object &transform, const py::bytes &base_dir)
{
    std::vector<ParamArg> args(params.size());
    for (size_t i = 0; i < params.size(); i++) {
        py::tuple p = params[i].cast<py::tuple>();
        ParamArg &a = args[i];
        a.name = p[0].cast<std::string>();
        std::string kind = p[1].cast<std::string>();
        if (kind == "number") {
            a.param.type = HR_PARAM_NUMBER;
            a.param.number = p[2].cast<double>();
        } else if (kind == "string") {
            a.param.type = HR_PARAM_STRING;
            a.string = p[2].cast<std::string>();
        } else if (kind == "object") {
            a.param.type = HR_PARAM_OBJECT;
            a.param.object = p[2].cast<int64_t>();
        } else if (kind == "numbers") {
            // The Python layer made it float64 and contiguous; anything else
            // is refused rather than silently copied here.
            if (!py::isinstance<DoubleArray>(p[2]))
                throw py::type_error("parameter '" + a.name + "': expected a contiguous float64 array");
            a.numbers = p[2].cast<DoubleArray>();
            a.param.type = HR_PARAM_NUMBERS;
            a.param.numbers = a.numbers.size() ? a.numbers.data() : nullptr;
            a.param.count = static_cast<int64_t>(a.numbers.size());
        } else {
            throw py::value_error("parameter '" + a.name + "': unknown kind '" + kind + "'");
        }
    }
    std::vector<hr_param> list(args.size());
    for (size_t i = 0; i < args.size(); i++) {
        list[i] = args[i].param;
        list[i].name = args[i].name.c_str();
        if (list[i].type == HR_PARAM_STRING) list[i].string = args[i].string.c_str();
    }
    std::vector<double> texture_parameters;
    hr_material mat = material_from(material, texture_parameters);
    std::array<double, 16> m = transform.attr("matrix").cast<std::array<double, 16>>();
    std::array<double, 16> inv = transform.attr("inverse").cast<std::array<double, 16>>();
    std::string dir = base_dir;

    hr_object_desc desc{};
    desc.struct_size = sizeof desc;
    desc.shape = shape.c_str();
    desc.param_count = static_cast<int32_t>(list.size());
    desc.params = list.empty() ? nullptr : list.data();
    desc.material = &mat;
    desc.transform = m.data();
    desc.inverse = inv.data();
    desc.base_dir = dir.c_str();
    int64_t index = -1;
    hr_status st;
    {
        // A module's create may read a file (a mesh) or run Python code
        // (a shape from hitray.abi, which takes the GIL itself).
        py::gil_scoped_release release;
        st = hr_scene_add_object(s->scene, &desc, &index);
    }
    check(st);
    return index;
}

// Hill's makePixmap: the image becomes pixmap `index` (copied).
void set_pixmap(const ScenePtr &s, int32_t index, const ImagePtr &image)
{
    check(hr_scene_set_pixmap(s->scene, index, image->image));
}

void add_light(const ScenePtr &s, const vec3 &position, const vec3 &color)
{
    hr_light light{};
    light.struct_size = sizeof light;
    light.position = to_vec3(position);
    light.color = to_color(color);
    check(hr_scene_add_light(s->scene, &light));
}

py::dict get_globals(const ScenePtr &s)
{
    hr_scene_globals g{};
    g.struct_size = sizeof g;
    check(hr_scene_get_globals(s->scene, &g));
    return globals_dict(g);
}

void set_globals(const ScenePtr &s, const py::dict &d)
{
    hr_scene_globals g{};
    g.struct_size = sizeof g;
    check(hr_scene_get_globals(s->scene, &g));
    globals_update(g, d);
    check(hr_scene_set_globals(s->scene, &g));
}

void commit(const ScenePtr &s)
{
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_scene_commit(s->scene);
    }
    check(st);
}

py::tuple matrix_tuple(const double *m)
{
    py::list out;
    for (int i = 0; i < 16; i++) out.append(m[i]);
    return py::tuple(out);
}

py::object bounds_value(const hr_bounds &b)
{
    return py::make_tuple(tuple_of(b.lo), tuple_of(b.hi));
}

py::dict object_info(const ScenePtr &s, int64_t index)
{
    hr_object_info info{};
    info.struct_size = sizeof info;
    check(hr_scene_object_info(s->scene, index, &info));
    py::dict d;
    d["top_level"] = info.top_level != 0;
    d["shape"] = text(info.shape);
    d["module"] = path_text(info.module_path ? info.module_path : "");
    d["material"] = material_dict(info.material);
    d["transform"] = matrix_tuple(info.transform);
    d["inverse"] = matrix_tuple(info.inverse);
    d["bounds"] = bounds_value(info.world_bounds);
    // (name, type as param_type_name says it, value): a number, a string,
    // an operand's index, or an array's length (the scene keeps no copy).
    py::list params;
    for (int32_t i = 0; i < info.param_count; i++) {
        const hr_param &p = info.params[i];
        py::object value;
        if (p.type == HR_PARAM_NUMBER) value = py::float_(p.number);
        else if (p.type == HR_PARAM_STRING) value = path_text(p.string ? p.string : "");
        else if (p.type == HR_PARAM_OBJECT) value = py::int_(p.object);
        else value = py::int_(p.count);
        params.append(py::make_tuple(text(p.name), param_type_name(p.type), value));
    }
    d["params"] = params;
    return d;
}

py::object scene_bounds(const ScenePtr &s)
{
    hr_bounds b;
    int32_t found = 0;
    check(hr_scene_bounds(s->scene, &b, &found));
    return found ? bounds_value(b) : py::object(py::none());
}

py::list effects(const ScenePtr &s)
{
    uint32_t bits = hr_scene_effects(committed_scene(s));
    py::list names;
    for (uint32_t e = 1; e < (1u << HR_EFFECT_COUNT); e <<= 1)
        if (bits & e) names.append(hr_effect_name(e));
    return names;
}

py::tuple hit_tuple(const hr_hit &h)
{
    return py::make_tuple(h.t, tuple_of(h.point), tuple_of(h.normal), h.surface, h.entering != 0,
                          h.object, h.error);
}

// hr_hit_spawn_origin reads only the point and its error bound.
py::tuple spawn_origin(const vec3 &point, double error, const vec3 &side)
{
    hr_hit hit{};
    hit.point = to_vec3(point);
    hit.error = error;
    return tuple_of(hr_hit_spawn_origin(&hit, to_vec3(side)));
}

hr_ray ray_of(const vec3 &origin, const vec3 &direction)
{
    return hr_ray{to_vec3(origin), to_vec3(direction)};
}

py::object first_hit(const ScenePtr &s, const vec3 &origin, const vec3 &direction, double tmin, double tmax)
{
    const hr_scene *scene = committed_scene(s);
    hr_ray ray = ray_of(origin, direction);
    hr_hit hit{};
    int32_t found = 0;
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_scene_first_hit(scene, &ray, tmin, tmax, &hit, &found);
    }
    check(st);
    return found ? py::object(hit_tuple(hit)) : py::object(py::none());
}

py::list all_hits(const ScenePtr &s, const vec3 &origin, const vec3 &direction, double tmin, double tmax)
{
    const hr_scene *scene = committed_scene(s);
    hr_ray ray = ray_of(origin, direction);
    hr_intersection list;
    hr_intersection_init(&list);
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_scene_all_hits(scene, &ray, tmin, tmax, &list);
    }
    if (st != HR_OK) {
        ErrorReport report = capture_error(st);
        hr_intersection_release(&list);
        raise_error(report);
    }
    py::list out;
    try {
        for (int32_t i = 0; i < list.count; i++) out.append(hit_tuple(list.hits[i]));
    } catch (...) {
        hr_intersection_release(&list);
        throw;
    }
    hr_intersection_release(&list);
    return out;
}

py::tuple shade(const ScenePtr &s, const vec3 &origin, const vec3 &direction, int32_t depth)
{
    const hr_scene *scene = committed_scene(s);
    hr_ray ray = ray_of(origin, direction);
    hr_color c{};
    hr_status st;
    {
        py::gil_scoped_release release;
        st = hr_scene_shade(scene, &ray, depth, &c);
    }
    check(st);
    return tuple_of(c);
}

py::tuple frame_camera(const ScenePtr &s, int32_t width, int32_t height, double angle)
{
    hr_camera cam;
    hr_camera_default(&cam);
    cam.width = width;
    cam.height = height;
    cam.view_angle = angle;
    check(hr_scene_frame_camera(s->scene, &cam));
    return camera_tuple(cam);
}

}  // namespace

void bind_scene(py::module_ &m)
{
    py::class_<SceneHandle, ScenePtr>(m, "Scene", "One hr_scene (see hitray.Scene for the public API).")
        .def(py::init(&new_scene))
        .def("add_object", &add_object, py::arg("shape"), py::arg("params"), py::arg("material"),
             py::arg("transform"), py::arg("base_dir"))
        .def("add_light", &add_light, py::arg("position"), py::arg("color"))
        .def("set_pixmap", &set_pixmap, py::arg("index"), py::arg("image"))
        .def("has_pixmap", [](const ScenePtr &s, int32_t index) { return hr_scene_has_pixmap(s->scene, index) != 0; },
             py::arg("index"))
        .def("get_globals", &get_globals)
        .def("set_globals", &set_globals, py::arg("values"))
        .def("commit", &commit)
        .def_property_readonly("committed", [](const ScenePtr &s) { return hr_scene_is_committed(s->scene) != 0; })
        .def_property_readonly("object_count", [](const ScenePtr &s) { return hr_scene_object_count(s->scene); })
        .def_property_readonly("light_count", [](const ScenePtr &s) { return hr_scene_light_count(s->scene); })
        .def_property_readonly("files", [](const ScenePtr &s) {
            py::list out;
            for (int64_t i = 0; i < hr_scene_file_count(s->scene); i++) out.append(py::bytes(hr_scene_file(s->scene, i)));
            return out;
        })
        .def("object_info", &object_info, py::arg("index"))
        .def("light", [](const ScenePtr &s, int32_t index) {
            hr_light l{};
            l.struct_size = sizeof l;
            check(hr_scene_light(s->scene, index, &l));
            return py::make_tuple(tuple_of(l.position), tuple_of(l.color));
        }, py::arg("index"))
        .def("bounds", &scene_bounds)
        .def("effects", &effects)
        .def("first_hit", &first_hit, py::arg("origin"), py::arg("direction"), py::arg("tmin"), py::arg("tmax"))
        .def("all_hits", &all_hits, py::arg("origin"), py::arg("direction"), py::arg("tmin"), py::arg("tmax"))
        .def("shade", &shade, py::arg("origin"), py::arg("direction"), py::arg("depth"))
        .def("frame_camera", &frame_camera, py::arg("width"), py::arg("height"), py::arg("angle"));
    m.def("spawn_origin", &spawn_origin, py::arg("point"), py::arg("error"), py::arg("side"),
          "hr_hit_spawn_origin: where a ray leaving a hit toward `side` starts.");
}

}  // namespace hitray_py
