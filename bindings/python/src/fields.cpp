// hitray._core.material_fields / global_fields and the conversions of
// fields.h, from the rows of include/hitray/scene_fields.h: the Python layer
// takes the fields' names from here, so each is spelled only in that table.
#include "fields.h"

#include <pybind11/stl.h>

#include <cstddef>
#include <cstring>

namespace hitray_py {

namespace {

// How a value crosses, by the member's type: a colour as a 3-tuple, a double
// as a float, an int32_t as an int, `parameters` as a tuple of floats.
enum class Kind { color, number, integer, numbers };
Kind kind_of(const hr_color *) { return Kind::color; }
Kind kind_of(const double *) { return Kind::number; }
Kind kind_of(const int32_t *) { return Kind::integer; }
Kind kind_of(const double *const *) { return Kind::numbers; }

const char *kind_name(Kind k)
{
    switch (k) {
    case Kind::color: return "color";
    case Kind::number: return "number";
    case Kind::integer: return "integer";
    case Kind::numbers: return "numbers";
    }
    return "";
}

struct Field {
    const char *name;     // the member, also the Python name
    const char *sdl_word; // SDL's keyword, an alias in Python
    Kind kind;
    size_t offset;
};

#define MATERIAL_FIELD(field, word, ...)                                                   \
    {#field, word, kind_of(static_cast<decltype(hr_material::field) *>(nullptr)),          \
     offsetof(hr_material, field)},
#define GLOBALS_FIELD(field, word, ...)                                                    \
    {#field, word, kind_of(static_cast<decltype(hr_scene_globals::field) *>(nullptr)),     \
     offsetof(hr_scene_globals, field)},

const std::vector<Field> material_fields = {HR_MATERIAL_FIELDS(MATERIAL_FIELD)};
const std::vector<Field> globals_fields = {HR_SCENE_GLOBALS_FIELDS(GLOBALS_FIELD)};

const Field *find(const std::vector<Field> &fields, const std::string &name)
{
    for (const Field &f : fields)
        if (name == f.name) return &f;
    return nullptr;
}

template <class T> void store(void *record, const Field &f, const T &value)
{
    std::memcpy(static_cast<char *>(record) + f.offset, &value, sizeof value);
}

template <class T> T load(const void *record, const Field &f)
{
    T value;
    std::memcpy(&value, static_cast<const char *>(record) + f.offset, sizeof value);
    return value;
}

// Set field `f` of `record` from `v`; a list of numbers goes into `numbers`.
void set_field(void *record, const Field &f, py::handle v, std::vector<double> &numbers)
{
    switch (f.kind) {
    case Kind::color: store(record, f, to_color(v.cast<vec3>())); break;
    case Kind::number: store(record, f, v.cast<double>()); break;
    case Kind::integer: store(record, f, v.cast<int32_t>()); break;
    case Kind::numbers: numbers = v.cast<std::vector<double>>(); break;
    }
}

// Field `f` of `record`, but for a list of numbers (the caller knows its count).
py::object field_value(const void *record, const Field &f)
{
    switch (f.kind) {
    case Kind::color: return tuple_of(load<hr_color>(record, f));
    case Kind::number: return py::float_(load<double>(record, f));
    case Kind::integer: return py::int_(load<int32_t>(record, f));
    case Kind::numbers: break;
    }
    throw std::logic_error("field_value: a list of numbers");
}

py::list field_list(const std::vector<Field> &fields)
{
    py::list out;
    for (const Field &f : fields) out.append(py::make_tuple(f.name, f.sdl_word, kind_name(f.kind)));
    return out;
}

}  // namespace

hr_material material_from(const py::dict &d, std::vector<double> &parameters)
{
    hr_material m;
    hr_material_default(&m);
    for (auto item : d) {
        std::string key = item.first.cast<std::string>();
        const Field *f = find(material_fields, key);
        if (!f) throw py::type_error("material: unknown field '" + key + "'");
        set_field(&m, *f, item.second, parameters);
    }
    m.parameter_count = static_cast<int32_t>(parameters.size());
    m.parameters = parameters.empty() ? nullptr : parameters.data();
    return m;
}

py::dict material_dict(const hr_material &m)
{
    py::dict d;
    for (const Field &f : material_fields) {
        if (f.kind != Kind::numbers) {
            d[f.name] = field_value(&m, f);
            continue;
        }
        py::list numbers;
        for (int32_t i = 0; i < m.parameter_count; i++) numbers.append(m.parameters[i]);
        d[f.name] = py::tuple(numbers);
    }
    return d;
}

void globals_update(hr_scene_globals &g, const py::dict &d)
{
    std::vector<double> no_list; // the globals have none
    for (auto item : d) {
        std::string key = item.first.cast<std::string>();
        const Field *f = find(globals_fields, key);
        if (!f) throw py::type_error("scene: unknown global '" + key + "'");
        set_field(&g, *f, item.second, no_list);
    }
}

py::dict globals_dict(const hr_scene_globals &g)
{
    py::dict d;
    for (const Field &f : globals_fields) d[f.name] = field_value(&g, f);
    return d;
}

void bind_fields(py::module_ &m)
{
    m.def("material_fields", [] { return field_list(material_fields); },
          "(name, SDL keyword, kind) of each material field, kind one of color, number, "
          "integer, numbers.");
    m.def("global_fields", [] { return field_list(globals_fields); },
          "(name, SDL keyword, kind) of each scene global, kind one of color, number, integer.");
}

}  // namespace hitray_py
