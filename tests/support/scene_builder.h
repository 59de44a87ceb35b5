/* Test helpers for building small scenes in code. */
#ifndef HR_TEST_SCENE_BUILDER_H
#define HR_TEST_SCENE_BUILDER_H

#include <hitray/hitray.h>

/* A material with every coefficient zero (black, inert) except speed 1. */
hr_material tb_black(void);
/* Add `shape` with material `m` and transform `t` (NULL: identity);
 * returns the index, or -1 after printing the context's error. */
int64_t tb_add(hr_scene *s, const char *shape, const hr_material *m, const hr_transform *t);
/* identity then translate, then uniform scale. */
hr_transform tb_place(double x, double y, double z, double scale);
void tb_light(hr_scene *s, double x, double y, double z, double r, double g, double b);
/* Globals with no ambient light and a black background. */
void tb_dark_globals(hr_scene *s, int32_t depth);
/* A floor (a mirror when `with_mirror_and_glass`), a red specular ball and
 * a ball (glass when `with_mirror_and_glass`): objects 0, 1, 2; no lights. */
void tb_add_mirror_glass_set(hr_scene *s, int with_mirror_and_glass);
/* A new committed scene of `ctx`: that set with mirror and glass, lit by
 * one white light at (5, 8, 6). NULL after a failed check. */
hr_scene *tb_mirror_glass_scene(hr_context *ctx);
/* The camera that frames that set at the given size. */
hr_camera tb_mirror_glass_view(int32_t width, int32_t height);
/* hr_scene_object_info of object `index`, the whole struct (a failed
 * check leaves it zeroed). */
hr_object_info tb_object_info(const hr_scene *s, int64_t index);

#endif
