// The package's one hr_context, and what Python asks of it: the library's
// version and path, modules and shape directories, and the shape classes
// known now (looked up through the context on every call, so a class
// registered later, from hitray.abi say, is seen at once).
#include "core.h"

#include <pybind11/stl.h>

#include <dlfcn.h>

#include <climits>
#include <cstdlib>
#include <vector>

namespace hitray_py {

namespace {

// The library's warnings, kept per thread until the Python layer takes
// them (take_warnings) right after the call that raised them and issues
// them with warnings.warn: the callback itself runs inside library calls,
// often with the GIL released, where Python cannot be entered (and an
// exception from a warnings filter could not pass through C).
struct PendingWarning {
    int32_t code;
    std::string message, file;
    int32_t line, column;
};
thread_local std::vector<PendingWarning> pending_warnings;

void on_warning(void *, const hr_warning *w)
{
    try {
        pending_warnings.push_back({w->code, w->message, w->file, w->line, w->column});
    } catch (...) {
        // Out of memory: a lost warning, not a failed call.
    }
}

py::list take_warnings()
{
    py::list out;
    for (const PendingWarning &w : pending_warnings)
        out.append(py::make_tuple(w.code, text(w.message), path_text(w.file), w.line, w.column));
    pending_warnings.clear();
    return out;
}

}  // namespace

hr_context *context()
{
    // A function-local static is created once, thread-safely. Never
    // destroyed: see core.h.
    static hr_context *const ctx = [] {
        hr_context *c = nullptr;
        if (hr_context_create(&c) != HR_OK) return static_cast<hr_context *>(nullptr);
        hr_context_set_warning_callback(c, on_warning, nullptr);
        return c;
    }();
    return ctx;
}

namespace {

std::string library_path()
{
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void *>(&hr_context_create), &info) || !info.dli_fname) return "";
    char *real = realpath(info.dli_fname, nullptr);
    std::string path = real ? real : info.dli_fname;
    std::free(real);
    return path;
}

py::dict param_spec_dict(const hr_param_spec &p)
{
    py::dict d;
    d["name"] = text(p.name);
    d["type"] = param_type_name(p.type);
    d["required"] = p.required != 0;
    d["default"] = p.default_number;
    d["min"] = p.min;
    d["max"] = p.max;
    d["min_exclusive"] = (p.flags & HR_PARAM_MIN_EXCLUSIVE) != 0;
    d["max_exclusive"] = (p.flags & HR_PARAM_MAX_EXCLUSIVE) != 0;
    d["help"] = text(p.help ? p.help : "");
    return d;
}

py::dict class_dict(const hr_shape_class &cls, const char *module_path)
{
    py::dict d;
    d["name"] = text(cls.name);
    d["help"] = text(cls.help ? cls.help : "");
    d["module"] = path_text(module_path ? module_path : "");
    d["closed"] = (cls.flags & HR_SHAPE_CLOSED) != 0;
    d["composite"] = (cls.flags & HR_SHAPE_COMPOSITE) != 0;
    d["surface_count"] = cls.surface_count;
    py::list surface_names; // empty where the class names none
    if (HR_CLASS_HAS(&cls, surface_names) && cls.surface_names)
        for (int32_t i = 0; i < cls.surface_count; i++)
            surface_names.append(text(cls.surface_names[i] ? cls.surface_names[i] : ""));
    d["surface_names"] = surface_names;
    py::list params;
    for (int32_t i = 0; i < cls.param_count; i++) params.append(param_spec_dict(cls.params[i]));
    d["params"] = params;
    return d;
}

// Every module on the search path (scanned now), loaded or refused.
py::list modules()
{
    py::list out;
    int32_t count = hr_context_module_count(context());
    for (int32_t i = 0; i < count; i++) {
        hr_module_entry e{};
        e.struct_size = sizeof e;
        check(hr_context_module(context(), i, &e));
        py::dict d;
        d["path"] = path_text(e.path);
        d["loaded"] = e.loaded != 0;
        d["name"] = text(e.name);
        d["description"] = text(e.description);
        d["error"] = text(e.error);
        d["version"] = text(e.version);
        d["author"] = text(e.author);
        d["url"] = text(e.url);
        py::list classes;
        for (int32_t j = 0; j < e.class_count; j++) classes.append(text(e.classes[j]->name));
        d["classes"] = classes;
        out.append(d);
    }
    return out;
}

py::dict find_shape_class(const std::string &name)
{
    const hr_shape_class *cls = nullptr;
    const char *module_path = nullptr;
    check(hr_context_find_shape_class(context(), name.c_str(), &cls, &module_path));
    return class_dict(*cls, module_path);
}

}  // namespace

void bind_context(py::module_ &m)
{
    m.def("_context_address", [] { return reinterpret_cast<std::uintptr_t>(context()); },
          "The package's hr_context* as an integer (for hitray.abi).");
    m.def("_library_path", &library_path, "Path of the libhitray this process loaded.");
    m.def("version", [] {
        int32_t major = 0, minor = 0, patch = 0;
        hr_version(&major, &minor, &patch);
        return py::make_tuple(major, minor, patch);
    }, "(major, minor, patch) of the libhitray loaded.");
    m.def("load_module", [](const py::bytes &path) { check(hr_context_load_module(context(), std::string(path).c_str())); },
          py::arg("path"), "Load one shape module file now (its classes win over searched ones).");
    m.def("add_shape_dir", [](const py::bytes &dir) { check(hr_context_add_shape_dir(context(), std::string(dir).c_str())); },
          py::arg("directory"), "Search a directory for shape modules before the default places.");
    m.def("suggest", [](const std::string &word, const std::vector<std::string> &candidates) -> py::object {
        std::vector<const char *> names;
        for (const std::string &c : candidates) names.push_back(c.c_str());
        const char *near = hr_suggest(word.c_str(), names.data(), static_cast<int32_t>(names.size()));
        return near ? py::object(py::str(near)) : py::object(py::none());
    }, py::arg("word"), py::arg("candidates"),
          "hr_suggest: the candidate nearest a misspelt word, or None.");
    m.def("take_warnings", &take_warnings,
          "The calling thread's pending library warnings, as (code, message, file, line, column).");
    m.def("modules", &modules, "Every module on the search path, loaded or refused.");
    m.def("find_shape_class", &find_shape_class, py::arg("name"),
          "The shape class that provides `name`, loading modules if needed.");
}

}  // namespace hitray_py
