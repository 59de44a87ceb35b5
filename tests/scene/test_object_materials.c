/* Objects' materials (lib/scene/scene_objects.c, material_store.c).
 * An object added without a material copies the scene's default material
 * unchecked, which is right only because hr_material_default's material
 * passes the checks every given material must: checked here, with a given
 * material still checked (a bad one refused), and an object without one
 * reading back as the default, field for field.
 * Objects of the same material share one copy: many objects of a few
 * materials, texture parameters among them (materials that differ only in
 * a parameter, or in a zero's sign), each read back as it was given, its
 * parameters too, after the caller's arrays were overwritten. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

int main(void)
{
    hr_context *ctx = NULL;
    hr_scene *s = NULL;
    CHECK(hr_context_create(&ctx) == HR_OK && hr_scene_create(ctx, &s) == HR_OK);
    hr_material def;
    hr_material_default(&def);
    CHECK(hr_material_validate(ctx, &def) == HR_OK);

    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "sphere";
    int64_t plain = -1, given = -1;
    CHECK(hr_scene_add_object(s, &d, &plain) == HR_OK);
    hr_material bad = def;
    bad.reflectivity = 2.0;
    d.material = &bad;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_INVALID_ARGUMENT);
    hr_material good = def;
    good.reflectivity = 0.5;
    d.material = &good;
    CHECK(hr_scene_add_object(s, &d, &given) == HR_OK);

    hr_object_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    CHECK(hr_scene_object_info(s, plain, &info) == HR_OK);
    CHECK(memcmp(&info.material, &def, offsetof(hr_material, parameters)) == 0);
    CHECK(info.material.parameter_count == 0);
    CHECK(hr_scene_object_info(s, given, &info) == HR_OK);
    CHECK(info.material.reflectivity == 0.5);
    /* Materials that differ only in one parameter, in a zero's sign, or
     * not at all, given in turn by many objects. */
    enum { OBJECTS = 600, KINDS = 6 };
    double params[KINDS][2];
    hr_material kinds[KINDS];
    for (int k = 0; k < KINDS; k++) {
        kinds[k] = def;
        kinds[k].texture = -1;
        kinds[k].parameter_count = k < 4 ? 2 : 0;
        params[k][0] = 1.0, params[k][1] = k < 2 ? 0.5 : 0.25;
        kinds[k].parameters = k < 4 ? params[k] : NULL;
        kinds[k].reflectivity = k == 3 ? -0.0 : 0.0;
        kinds[k].ambient.r = k == 5 ? 0.3 : def.ambient.r;
    }
    int64_t first = -1;
    for (int i = 0; i < OBJECTS; i++) {
        d.material = &kinds[i % KINDS];
        int64_t at = -1;
        CHECK(hr_scene_add_object(s, &d, &at) == HR_OK);
        if (i == 0) first = at;
    }
    for (int k = 0; k < KINDS; k++) params[k][0] = params[k][1] = -7.0; /* the caller's arrays reused */
    int wrong = 0;
    for (int i = 0; i < OBJECTS; i++) {
        CHECK(hr_scene_object_info(s, first + i, &info) == HR_OK);
        const int k = i % KINDS;
        const hr_material *m = &info.material;
        wrong += m->texture != -1 || m->parameter_count != (k < 4 ? 2 : 0) || signbit(m->reflectivity) != (k == 3) ||
                 m->ambient.r != (k == 5 ? 0.3 : def.ambient.r);
        if (k < 4)
            wrong += !m->parameters || m->parameters[0] != 1.0 || m->parameters[1] != (k < 2 ? 0.5 : 0.25);
        else
            wrong += m->parameters != NULL;
    }
    CHECK_MSG(wrong == 0, "%d objects read back a material other than the one they were given", wrong);
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
    return hr_test_end();
}
