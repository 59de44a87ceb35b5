// The fields of a material and of the scene globals between the C structs
// and Python dicts keyed by the fields' names, as the rows of
// include/hitray/scene_fields.h give them.
#pragma once

#include "core.h"

#include <vector>

namespace hitray_py {

// A material from a dict of some of its fields, SDL's defaults for the rest;
// its texture parameters are stored in `parameters`, which it points into.
hr_material material_from(const py::dict &d, std::vector<double> &parameters);
py::dict material_dict(const hr_material &m);

// Set the globals the dict names, keeping the others.
void globals_update(hr_scene_globals &g, const py::dict &d);
py::dict globals_dict(const hr_scene_globals &g);

}  // namespace hitray_py
