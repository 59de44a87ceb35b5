/* Shapes a user adds: a class some module (here: registered in process, as a
 * plugin's would be found) provides beyond Hill's list is an SDL object
 * keyword, read like Hill's `taperedCylinder s`: its name, then one argument
 * per parameter in the class's order (a number, a word for a string, a whole
 * object for an object parameter). */
#include <stdio.h>
#include <string.h>

#include "sdl_test_support.h"

/* A stand-in plugin shape: records what create received. */
typedef struct probe {
    double width, height;
    char label[32];
    const hr_host *host;
} probe;

static hr_status probe_create(const hr_create_args *a, void **out)
{
    probe *p = a->host->alloc(sizeof *p);
    if (!p) return HR_ERROR_OUT_OF_MEMORY;
    p->width = a->param_count >= 2 ? a->params[0].number : 1.0;
    p->height = a->param_count >= 2 ? a->params[1].number : 1.0;
    if (a->param_count == 3) snprintf(p->label, sizeof p->label, "%s", a->params[2].string);
    p->host = a->host;
    *out = p;
    return HR_OK;
}
static void probe_destroy(void *shape)
{
    probe *p = shape;
    p->host->free(p);
}
static void probe_bounds(const void *shape, hr_bounds *b)
{
    const probe *p = shape;
    *b = (hr_bounds){{-p->width, -p->width, 0}, {p->width, p->width, p->height}};
}
static hr_status probe_hit(const hr_hit_args *a)
{
    (void)a;
    return HR_OK;
}

static const hr_param_spec probe_params[] = {
    {"width", HR_PARAM_NUMBER, 0, 1.0, 0.0, 100.0, "half width", 0},
    {"height", HR_PARAM_NUMBER, 0, 2.0, 0.0, 100.0, "height", 0},
    {"label", HR_PARAM_STRING, 0, 0.0, 1.0, 0.0, "a word", 0},
};
static const hr_shape_class probe_class = {sizeof(hr_shape_class), HR_SHAPE_CLOSED, "userBlock",
                                           "a user's shape", probe_params, 3, 1, probe_create,
                                           probe_destroy, probe_bounds, probe_hit, NULL, NULL, NULL, NULL, NULL, 0};
/* No parameters at all. */
static const hr_shape_class bare_class = {sizeof(hr_shape_class), HR_SHAPE_CLOSED, "userBare",
                                          "no parameters", NULL, 0, 1, probe_create,
                                          probe_destroy, probe_bounds, probe_hit, NULL, NULL, NULL, NULL, NULL, 0};
/* A composite: its object parameter is an operand, as `union`'s are. */
static const hr_param_spec pair_params[] = {{"a", HR_PARAM_OBJECT, 1, 0, 1, 0, "first", 0}};
static const hr_shape_class pair_class = {sizeof(hr_shape_class), HR_SHAPE_COMPOSITE, "userPair",
                                          "a composite", pair_params, 1, 1, probe_create,
                                          probe_destroy, probe_bounds, probe_hit, NULL, NULL, NULL, NULL, NULL, 0};
/* Array parameters have no SDL form. */
static const hr_param_spec cloud_params[] = {{"points", HR_PARAM_NUMBERS, 1, 0, 0, 1, "x y z each", 0}};
static const hr_shape_class cloud_class = {sizeof(hr_shape_class), 0, "userCloud", "points",
                                           cloud_params, 1, 1, probe_create, probe_destroy,
                                           probe_bounds, probe_hit, NULL, NULL, NULL, NULL, NULL, 0};
/* A class named like a command must not take the command's place. */
static const hr_shape_class light_class = {sizeof(hr_shape_class), 0, "light", "a bad name",
                                           NULL, 0, 1, probe_create, probe_destroy,
                                           probe_bounds, probe_hit, NULL, NULL, NULL, NULL, NULL, 0};

int main(void)
{
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);
    CHECK_OK(hr_context_register_shape_class(ctx, &probe_class, "test_sdl_plugins.c"));
    CHECK_OK(hr_context_register_shape_class(ctx, &bare_class, "test_sdl_plugins.c"));
    CHECK_OK(hr_context_register_shape_class(ctx, &pair_class, "test_sdl_plugins.c"));
    CHECK_OK(hr_context_register_shape_class(ctx, &light_class, "test_sdl_plugins.c"));
    CHECK_OK(hr_context_register_shape_class(ctx, &cloud_class, "test_sdl_plugins.c"));

    /* Parameters in the class's order; material and transform as for any
     * object; the class is usable inside macros and as a CSG operand. */
    hr_sdl_result r;
    hr_scene *s = LOAD_OK(ctx,
                          "diffuse 1 0 0 translate 0 0 5\n"
                          "userBlock 3 4.5 tall\n"
                          "def b { userBare }\n"
                          "use b\n"
                          "light 0 10 0 1 1 1\n",
                          &r);
    if (s) {
        CHECK(hr_scene_object_count(s) == 2);
        CHECK(hr_scene_light_count(s) == 1); /* `light` stayed the command */
        hr_object_info o = sdl_test_object(s, 0);
        CHECK(o.shape && strcmp(o.shape, "userBlock") == 0);
        CHECK(o.material.diffuse.r == 1 && o.material.diffuse.g == 0);
        CHECK(o.transform[11] == 5);
        /* width 3, height 4.5 reached create: bounds x in [-3,3], z in 5+[0,4.5]. */
        CHECK_NEAR(o.world_bounds.lo.x, -3, 1e-12);
        CHECK_NEAR(o.world_bounds.hi.z, 9.5, 1e-12);
        o = sdl_test_object(s, 1);
        CHECK(o.shape && strcmp(o.shape, "userBare") == 0);
        hr_scene_destroy(s);
    }

    /* Arguments missing or of the wrong kind are errors at their place; the
     * host's range check names the parameter at the keyword. */
    EXPECT_ERROR(ctx, "userBlock 3\n", HR_ERROR_SDL, 2, 1, "expected a number after 'userBlock'");
    EXPECT_ERROR(ctx, "userBlock 3 4 {\n", HR_ERROR_SDL, 1, 15, "expected a word for 'label' of 'userBlock'");
    EXPECT_ERROR(ctx, "sphere\nuserBlock 300 1 x\n", HR_ERROR_PARAMETER, 2, 1,
                 "parameter 'width' = 300 is outside [0, 100]");
    EXPECT_ERROR(ctx, "userCloud 1 2 3\n", HR_ERROR_UNSUPPORTED, 1, 1,
                 "takes array parameters ('points'), which SDL cannot give");

    /* An object parameter reads a whole object, state commands before it
     * run; the composite is added after its operand, untransformed. */
    s = LOAD_OK(ctx, "userPair translate 0 0 7 sphere\n", &r);
    if (s) {
        CHECK(hr_scene_object_count(s) == 2);
        hr_object_info o = sdl_test_object(s, 0);
        CHECK(o.shape && strcmp(o.shape, "sphere") == 0 && o.transform[11] == 7);
        o = sdl_test_object(s, 1);
        CHECK(o.shape && strcmp(o.shape, "userPair") == 0 && o.transform[11] == 0);
        hr_scene_destroy(s);
    }
    EXPECT_ERROR(ctx, "userPair\n", HR_ERROR_SDL, 2, 1,
                 "expected an object for operand A of 'userPair' at t.dat:1:1");
    /* A word no module provides is still an unknown keyword, not a module error. */
    EXPECT_ERROR(ctx, "userBlok 1 2 x\n", HR_ERROR_SDL, 1, 1, "unknown keyword 'userBlok'");
    hr_context_destroy(ctx);
    return hr_test_end();
}
