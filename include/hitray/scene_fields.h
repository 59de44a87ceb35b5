/* hitray: the fields of a material and of the scene globals that a scene
 * description names, one row each.
 *
 * Every place that names these fields is generated from these tables: the
 * defaults (hr_material_default, hr_scene_globals_default), the SDL reader's
 * keywords, and the Python bindings (each field's Python name, its SDL alias
 * and the conversion of its value). To add a field, add it to the struct in
 * scene.h and a row here; the library refuses to build when a field of the
 * struct has no row.
 *
 *   X(field, sdl_word, default...)
 *
 * field:    the member of hr_material (hr_scene_globals); also its name in
 *           Python, where sdl_word is an alias of it.
 * sdl_word: SDL's keyword for it.
 * default:  SDL's default: r, g, b for an hr_color, one number for a double
 *           or an int32_t; 0 for `parameters` (none), which comes with its
 *           `parameter_count`.
 *
 * The member's type says how a value is read: an hr_color as three numbers,
 * a double as a number, an int32_t as a whole number, `parameters` as a list
 * of numbers. The bounds a value must keep are hr_material_validate's and
 * hr_scene_set_globals'. Rows are in the order of SDL's documentation. */
#ifndef HITRAY_SCENE_FIELDS_H
#define HITRAY_SCENE_FIELDS_H

#define HR_MATERIAL_FIELDS(X)                                                  \
    X(ambient, "ambient", 0.1, 0.1, 0.1)                                       \
    X(diffuse, "diffuse", 0.8, 0.8, 0.8)                                       \
    X(specular, "specular", 0, 0, 0)                                           \
    X(emissive, "emissive", 0, 0, 0)                                           \
    X(specular_exponent, "specularExponent", 1)                                \
    X(reflectivity, "reflectivity", 0)                                         \
    X(transparency, "transparency", 0)                                         \
    X(speed_of_light, "speedOfLight", 1)                                       \
    X(specular_fraction, "specularFraction", 0)                                \
    X(surface_roughness, "surfaceRoughness", 1)                                \
    X(texture, "texture", 0)                                                   \
    X(parameters, "parameters", 0)

#define HR_SCENE_GLOBALS_FIELDS(X)                                             \
    X(background, "background", 0, 0, 0.6)                                     \
    X(global_ambient, "globalAmbient", 0.1, 0.1, 0.1)                          \
    X(min_reflectivity, "minReflectivity", 0.5)                                \
    X(min_transparency, "minTransparency", 0.5)                                \
    X(max_recursion_depth, "maxRecursionDepth", 3)

#endif
