/* The ABI's layouts, pinned. A change to any public struct's size or field
 * offsets fails this file's compilation (static assertions), so a layout
 * change can't slip in by accident: it must be made here on purpose, with
 * HR_SHAPE_ABI_VERSION or the SONAME bumped as the change requires.
 * Numbers are for LP64 (x86_64, aarch64 Linux), the platforms hitray builds on. */
#include <stddef.h>

#include <hitray/hitray.h>

#include "hr_test.h"

#define PIN_SIZE(T, n) _Static_assert(sizeof(T) == (n), "size of " #T " changed")
#define PIN_OFF(T, f, n) _Static_assert(offsetof(T, f) == (n), "offset of " #T "." #f " changed")

PIN_SIZE(hr_vec3, 24);
PIN_SIZE(hr_color, 24);
PIN_SIZE(hr_ray, 48);
PIN_OFF(hr_ray, dir, 24);
PIN_SIZE(hr_bounds, 48);
PIN_SIZE(hr_hit, 80);
PIN_OFF(hr_hit, t, 0);
PIN_OFF(hr_hit, point, 8);
PIN_OFF(hr_hit, normal, 32);
PIN_OFF(hr_hit, error, 56);
PIN_OFF(hr_hit, surface, 64);
PIN_OFF(hr_hit, entering, 68);
PIN_OFF(hr_hit, object, 72);
PIN_SIZE(hr_intersection, 16);
PIN_OFF(hr_intersection, count, 8);
PIN_OFF(hr_intersection, capacity, 12);
PIN_SIZE(hr_param, 40);
PIN_OFF(hr_param, number, 16);
PIN_OFF(hr_param, string, 24);
PIN_OFF(hr_param, object, 32);
/* HR_PARAM_NUMBERS (added within ABI 1) shares the places of string and
 * object, so the struct keeps its first size. */
PIN_OFF(hr_param, numbers, 24);
PIN_OFF(hr_param, count, 32);
PIN_SIZE(hr_param_spec, 56);
PIN_OFF(hr_param_spec, default_number, 16);
PIN_OFF(hr_param_spec, help, 40);
/* Appended within ABI 1 (hr_shape_class.param_spec_size gives the stride). */
PIN_OFF(hr_param_spec, flags, 48);
PIN_SIZE(hr_host, 80);
PIN_OFF(hr_host, alloc, 8);
PIN_OFF(hr_host, trace_child, 48);
PIN_OFF(hr_host, child_bounds, 56);
/* child_class was added within ABI 1, after the first layout: at the end. */
PIN_OFF(hr_host, child_class, 64);
/* file_read, within ABI 1 too, after it. */
PIN_OFF(hr_host, file_read, 72);
PIN_SIZE(hr_create_args, 56);
PIN_OFF(hr_create_args, params, 8);
PIN_OFF(hr_create_args, objects, 16);
PIN_OFF(hr_create_args, host, 24);
PIN_OFF(hr_create_args, error, 32);
PIN_OFF(hr_create_args, base_dir, 48);
PIN_SIZE(hr_hit_args, 96);
PIN_OFF(hr_hit_args, ray, 8);
PIN_OFF(hr_hit_args, tmin, 56);
PIN_OFF(hr_hit_args, out, 72);
PIN_OFF(hr_hit_args, call, 80);
/* Appended within ABI 1: the host's size of the struct. */
PIN_OFF(hr_hit_args, struct_size, 88);
PIN_SIZE(hr_shape_class, 120);
PIN_OFF(hr_shape_class, name, 8);
PIN_OFF(hr_shape_class, params, 24);
PIN_OFF(hr_shape_class, create, 40);
PIN_OFF(hr_shape_class, hit, 64);
PIN_OFF(hr_shape_class, first_hit, 72);
PIN_OFF(hr_shape_class, any_hit, 80);
PIN_OFF(hr_shape_class, transformed_bounds, 88);
PIN_OFF(hr_shape_class, surface_uv, 96);
PIN_OFF(hr_shape_class, surface_names, 104);
/* Appended within ABI 1: the stride of params. */
PIN_OFF(hr_shape_class, param_spec_size, 112);
PIN_SIZE(hr_module_info, 64);
PIN_OFF(hr_module_info, classes, 24);
PIN_OFF(hr_module_info, class_count, 32);
/* Appended within ABI 1: a module's metadata. */
PIN_OFF(hr_module_info, version, 40);
PIN_OFF(hr_module_info, author, 48);
PIN_OFF(hr_module_info, url, 56);
PIN_SIZE(hr_material, 168);
PIN_OFF(hr_material, ambient, 8);
PIN_OFF(hr_material, diffuse, 32);
PIN_OFF(hr_material, specular, 56);
PIN_OFF(hr_material, emissive, 80);
PIN_OFF(hr_material, specular_exponent, 104);
PIN_OFF(hr_material, speed_of_light, 128);
PIN_OFF(hr_material, parameter_count, 152);
PIN_OFF(hr_material, parameters, 160);
PIN_SIZE(hr_light, 56);
PIN_OFF(hr_light, position, 8);
PIN_OFF(hr_light, color, 32);
PIN_SIZE(hr_scene_globals, 72);
PIN_OFF(hr_scene_globals, background, 8);
PIN_OFF(hr_scene_globals, min_reflectivity, 56);
PIN_SIZE(hr_object_info, 512);
PIN_OFF(hr_object_info, shape, 8);
PIN_OFF(hr_object_info, material, 24);
PIN_OFF(hr_object_info, transform, 192);
PIN_OFF(hr_object_info, world_bounds, 448);
/* Appended within ABI 1: the object's parameters. */
PIN_OFF(hr_object_info, params, 496);
PIN_OFF(hr_object_info, param_count, 504);
PIN_SIZE(hr_object_desc, 56);
PIN_OFF(hr_object_desc, shape, 8);
PIN_OFF(hr_object_desc, transform, 32);
PIN_OFF(hr_object_desc, base_dir, 48);
PIN_SIZE(hr_camera, 96);
PIN_OFF(hr_camera, eye, 16);
PIN_OFF(hr_camera, view_angle, 88);
/* Both grew at their ends (older callers pass a smaller struct_size). */
PIN_SIZE(hr_render_options, 136);
PIN_OFF(hr_render_options, progress, 40);
PIN_OFF(hr_render_options, progress_user, 48);
PIN_OFF(hr_render_options, adaptive_threshold, 56);
PIN_OFF(hr_render_options, min_weight, 64);
PIN_OFF(hr_render_options, exact, 72);
PIN_OFF(hr_render_options, reserved2, 76);
PIN_OFF(hr_render_options, cancel, 80);
/* The render window (issue 14), appended after cancel. */
PIN_OFF(hr_render_options, window_x, 88);
PIN_OFF(hr_render_options, window_y, 92);
PIN_OFF(hr_render_options, window_width, 96);
PIN_OFF(hr_render_options, window_height, 100);
/* The per-tile callback (issue 18), appended after the window. */
PIN_OFF(hr_render_options, tile_done, 104);
PIN_OFF(hr_render_options, tile_user, 112);
/* The ray budget (issue 29), appended after the tile callback. */
PIN_OFF(hr_render_options, ray_budget, 120);
/* The texture filter (issue 30), appended after the ray budget. */
PIN_OFF(hr_render_options, texture_filter, 128);
PIN_OFF(hr_render_options, reserved3, 132);
PIN_SIZE(hr_render_stats, 96);
PIN_OFF(hr_render_stats, primary, 8);
PIN_OFF(hr_render_stats, seconds, 40);
PIN_OFF(hr_render_stats, effects, 48);
PIN_OFF(hr_render_stats, pixels_refined, 56);
PIN_OFF(hr_render_stats, samples_saved, 64);
PIN_OFF(hr_render_stats, rays_cut, 72);
/* The ray budget's counts (issue 29). */
PIN_OFF(hr_render_stats, rays_over_budget, 80);
PIN_OFF(hr_render_stats, pixels_over_budget, 88);
PIN_SIZE(hr_image_write_options, 24);
PIN_SIZE(hr_error_info, 32);
PIN_SIZE(hr_module_entry, 80);
PIN_OFF(hr_module_entry, class_count, 48);
/* Appended within ABI 1: the module's metadata. */
PIN_OFF(hr_module_entry, version, 56);
PIN_OFF(hr_module_entry, author, 64);
PIN_OFF(hr_module_entry, url, 72);
/* hr_warning (the warning callback's argument, added within ABI 1). */
PIN_SIZE(hr_warning, 32);
PIN_OFF(hr_warning, code, 4);
PIN_OFF(hr_warning, message, 8);
PIN_OFF(hr_warning, file, 16);
PIN_OFF(hr_warning, line, 24);
PIN_OFF(hr_warning, column, 28);
PIN_SIZE(hr_sdl_result, 112);
PIN_OFF(hr_sdl_result, camera, 16);
PIN_SIZE(hr_transform, 256);

int main(void)
{
    /* The layouts are checked at compile time; here, the version the library
     * reports is the one the headers describe. */
    int32_t major, minor, patch;
    hr_version(&major, &minor, &patch);
    CHECK(major == HR_VERSION_MAJOR);
    CHECK(minor == HR_VERSION_MINOR);
    CHECK(patch == HR_VERSION_PATCH);
    return hr_test_end();
}
