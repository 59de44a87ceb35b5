#include "scene_builder.h"

#include "hr_test.h"

#include <stdio.h>
#include <string.h>

hr_material tb_black(void)
{
    hr_material m;
    hr_material_default(&m);
    memset(&m.ambient, 0, sizeof m.ambient);
    memset(&m.diffuse, 0, sizeof m.diffuse);
    return m;
}

int64_t tb_add(hr_scene *s, const char *shape, const hr_material *m, const hr_transform *t)
{
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = shape;
    d.material = m;
    d.transform = t ? t->m : NULL;
    d.inverse = t ? t->inv : NULL;
    int64_t index = -1;
    if (hr_scene_add_object(s, &d, &index) != HR_OK) {
        fprintf(stderr, "tb_add(%s): %s\n", shape, hr_context_last_error(hr_scene_context(s)));
        return -1;
    }
    return index;
}

hr_transform tb_place(double x, double y, double z, double scale)
{
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, x, y, z);
    hr_transform_scale(&t, scale, scale, scale);
    return t;
}

void tb_light(hr_scene *s, double x, double y, double z, double r, double g, double b)
{
    hr_light l = {0};
    l.struct_size = sizeof l;
    l.position = (hr_vec3){x, y, z};
    l.color = (hr_color){r, g, b};
    hr_scene_add_light(s, &l);
}

void tb_dark_globals(hr_scene *s, int32_t depth)
{
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.background = (hr_color){0, 0, 0};
    g.global_ambient = (hr_color){0, 0, 0};
    g.max_recursion_depth = depth;
    hr_scene_set_globals(s, &g);
}

void tb_add_mirror_glass_set(hr_scene *s, int with_mirror_and_glass)
{
    hr_material floor_m;
    hr_material_default(&floor_m);
    if (with_mirror_and_glass) floor_m.reflectivity = 0.6;
    hr_transform ft;
    hr_transform_identity(&ft);
    hr_transform_rotate(&ft, -90, 1, 0, 0);
    tb_add(s, "plane", &floor_m, &ft);
    hr_material red;
    hr_material_default(&red);
    red.diffuse = (hr_color){0.8, 0.1, 0.1};
    red.specular = (hr_color){0.5, 0.5, 0.5};
    red.specular_exponent = 30;
    hr_transform a = tb_place(-1.2, 1, 0, 1);
    tb_add(s, "sphere", &red, &a);
    hr_material glass;
    hr_material_default(&glass);
    if (with_mirror_and_glass) glass.transparency = 0.9, glass.speed_of_light = 0.67;
    hr_transform b = tb_place(1.2, 1, 0.5, 1);
    tb_add(s, "sphere", &glass, &b);
}

hr_scene *tb_mirror_glass_scene(hr_context *ctx)
{
    hr_scene *s = NULL;
    CHECK_OK(hr_scene_create(ctx, &s));
    if (!s) return NULL;
    tb_add_mirror_glass_set(s, 1);
    tb_light(s, 5, 8, 6, 1, 1, 1);
    CHECK_OK(hr_scene_commit(s));
    return s;
}

hr_camera tb_mirror_glass_view(int32_t width, int32_t height)
{
    hr_camera c;
    hr_camera_default(&c);
    c.width = width, c.height = height;
    c.eye = (hr_vec3){0, 2.5, 7};
    c.look = (hr_vec3){0, 0.8, 0};
    return c;
}

hr_object_info tb_object_info(const hr_scene *s, int64_t index)
{
    hr_object_info o;
    memset(&o, 0, sizeof o);
    o.struct_size = sizeof o;
    CHECK_OK(hr_scene_object_info(s, index, &o));
    return o;
}
