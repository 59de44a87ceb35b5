/* hr_scene_object_info's params: each object's parameters as it was
 * created, one per parameter its class declares, in the class's order,
 * defaults filled in; strings are the scene's own copies (the caller's
 * buffer is gone by the time they are read), operands are object indices,
 * an array keeps its count only. A caller whose struct_size ends before the
 * appended fields gets the fields before and nothing past them. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static int64_t add(hr_scene *s, const char *shape, const hr_param *params, int32_t count)
{
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = shape;
    d.params = params;
    d.param_count = count;
    int64_t index = -1;
    CHECK_MSG(hr_scene_add_object(s, &d, &index) == HR_OK, "add %s: %s", shape,
              hr_context_last_error(hr_scene_context(s)));
    return index;
}

static void test_params(hr_context *ctx)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));

    const int64_t a = add(s, "sphere", NULL, 0);
    const int64_t b = add(s, "cube", NULL, 0);
    hr_param operands[2];
    memset(operands, 0, sizeof operands);
    operands[0].name = "a", operands[0].type = HR_PARAM_OBJECT, operands[0].object = b;
    operands[1].name = "b", operands[1].type = HR_PARAM_OBJECT, operands[1].object = a;
    const int64_t diff = add(s, "difference", operands, 2);

    /* The solver's name in a buffer that is overwritten once the torus is added;
     * the tube is left to its default. */
    char *solver = malloc(16);
    strcpy(solver, "ferrari");
    hr_param torus_param;
    memset(&torus_param, 0, sizeof torus_param);
    torus_param.name = "solver", torus_param.type = HR_PARAM_STRING, torus_param.string = solver;
    const int64_t torus = add(s, "torus", &torus_param, 1);
    memset(solver, 'x', 15);
    free(solver);

    hr_param taper;
    memset(&taper, 0, sizeof taper);
    taper.name = "s", taper.type = HR_PARAM_NUMBER, taper.number = 0.25;
    const int64_t cone = add(s, "taperedCylinder", &taper, 1);

    static const double points[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const double triangles[] = {0, 1, 2};
    hr_param arrays[2];
    memset(arrays, 0, sizeof arrays);
    arrays[0].name = "points", arrays[0].type = HR_PARAM_NUMBERS, arrays[0].numbers = points, arrays[0].count = 9;
    arrays[1].name = "triangles", arrays[1].type = HR_PARAM_NUMBERS;
    arrays[1].numbers = triangles, arrays[1].count = 3;
    const int64_t mesh = add(s, "triangleMesh", arrays, 2);

    hr_object_info o = tb_object_info(s, a);
    CHECK(o.param_count == 0 && o.params == NULL);

    o = tb_object_info(s, diff);
    CHECK(o.param_count == 2);
    if (o.param_count == 2) {
        CHECK(strcmp(o.params[0].name, "a") == 0 && o.params[0].type == HR_PARAM_OBJECT);
        CHECK(o.params[0].object == b);
        CHECK(strcmp(o.params[1].name, "b") == 0 && o.params[1].object == a);
    }

    o = tb_object_info(s, torus);
    CHECK(o.param_count == 2);
    if (o.param_count == 2) {
        CHECK(strcmp(o.params[0].name, "tube") == 0 && o.params[0].type == HR_PARAM_NUMBER);
        CHECK(o.params[0].number == 0.2); /* the class's default */
        CHECK(strcmp(o.params[1].name, "solver") == 0 && o.params[1].type == HR_PARAM_STRING);
        CHECK_MSG(strcmp(o.params[1].string, "ferrari") == 0, "solver '%s'", o.params[1].string);
    }

    o = tb_object_info(s, cone);
    CHECK(o.param_count >= 1 && strcmp(o.params[0].name, "s") == 0 && o.params[0].number == 0.25);

    o = tb_object_info(s, mesh); /* points, triangles, and the normals left out */
    CHECK(o.param_count == 3);
    if (o.param_count == 3) {
        CHECK(o.params[0].type == HR_PARAM_NUMBERS && o.params[0].count == 9 && o.params[0].numbers == NULL);
        CHECK(o.params[1].count == 3 && o.params[1].numbers == NULL);
        CHECK(strcmp(o.params[2].name, "normals") == 0 && o.params[2].count == 0);
    }

    /* A caller of the first layout: nothing written past its struct_size. */
    hr_object_info old;
    memset(&old, 0x5a, sizeof old);
    old.struct_size = (uint32_t)offsetof(hr_object_info, params);
    CHECK_OK(hr_scene_object_info(s, torus, &old));
    CHECK(strcmp(old.shape, "torus") == 0);
    unsigned char past[sizeof old - offsetof(hr_object_info, params)];
    memset(past, 0x5a, sizeof past);
    CHECK(memcmp((const unsigned char *)&old + offsetof(hr_object_info, params), past, sizeof past) == 0);

    /* Still there once committed. */
    CHECK_OK(hr_scene_commit(s));
    o = tb_object_info(s, torus);
    CHECK(o.param_count == 2 && strcmp(o.params[1].string, "ferrari") == 0);
    hr_scene_destroy(s);
}

/* The SDL reader's objects carry theirs too: a mesh's file as written. */
static void test_sdl(hr_context *ctx)
{
    hr_sdl_result r = {0};
    r.struct_size = sizeof r;
    if (hr_sdl_load_string(ctx, "taperedCylinder 0.5\nunion sphere torus 0.3\n", "p.sdl", NULL, &r) != HR_OK) {
        CHECK_MSG(0, "load: %s", hr_context_last_error(ctx));
        return;
    }
    hr_object_info o = tb_object_info(r.scene, 0);
    CHECK(strcmp(o.shape, "taperedCylinder") == 0 && o.param_count >= 1 && o.params[0].number == 0.5);
    o = tb_object_info(r.scene, 2);
    CHECK(strcmp(o.shape, "torus") == 0 && o.params[0].number == 0.3);
    o = tb_object_info(r.scene, 3);
    CHECK(strcmp(o.shape, "union") == 0 && o.param_count == 2 && o.params[0].object == 1 &&
          o.params[1].object == 2);
    hr_scene_destroy(r.scene);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    test_params(ctx);
    test_sdl(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
