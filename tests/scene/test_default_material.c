/* An object added without a material copies the scene's default material
 * unchecked (lib/scene/scene_objects.c), which is right only because
 * hr_material_default's material passes the checks every given material
 * must: checked here, with a given material still checked (a bad one
 * refused), and an object without one reading back as the default, field
 * for field. */
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
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
    return hr_test_end();
}
