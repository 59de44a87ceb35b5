/* Every built-in shape module loads, declares the ABI it was built for, and
 * describes complete classes: a full vtable (create, destroy, bounds, hit,
 * first_hit, any_hit), the right flags, surface counts and parameters; every
 * class creates and destroys a shape (LeakSanitizer, in the sanitizer build,
 * sees any leak) and reports the bounds of its generic shape. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"
#include "module_harness.h"

typedef struct expected_class {
    const char *module;
    const char *name;
    int32_t flags;
    int32_t surface_count;
    int32_t param_count;
    hr_bounds bounds; /* with default parameters */
} expected_class;

static const expected_class expected[] = {
    {"sphere", "sphere", HR_SHAPE_CLOSED, 1, 0, {{-1, -1, -1}, {1, 1, 1}}},
    {"plane", "plane", 0, 1, 0, {{-INFINITY, -INFINITY, 0}, {INFINITY, INFINITY, 0}}},
    {"square", "square", 0, 1, 0, {{-1, -1, 0}, {1, 1, 0}}},
    {"cube", "cube", HR_SHAPE_CLOSED, 6, 0, {{-1, -1, -1}, {1, 1, 1}}},
    {"cylinder", "taperedCylinder", HR_SHAPE_CLOSED, 3, 1, {{-1, -1, 0}, {1, 1, 1}}},
    {"cylinder", "cylinder", HR_SHAPE_CLOSED, 3, 0, {{-1, -1, 0}, {1, 1, 1}}},
    {"cylinder", "cone", HR_SHAPE_CLOSED, 3, 0, {{-1, -1, 0}, {1, 1, 1}}},
    /* The open wall: no solid, one surface, the same s. */
    {"cylinder", "openTaperedCylinder", 0, 1, 1, {{-1, -1, 0}, {1, 1, 1}}},
    /* Hill's tube: wall, base, cap, inner; s and t. */
    {"cylinder", "taperedTube", HR_SHAPE_CLOSED, 4, 2, {{-1, -1, 0}, {1, 1, 1}}},
    {"torus", "torus", HR_SHAPE_CLOSED | HR_SHAPE_SDL_BARE, 1, 2, {{-1.2, -1.2, -0.2}, {1.2, 1.2, 0.2}}},
};
#define EXPECTED_COUNT (int)(sizeof expected / sizeof expected[0])

static int same_bounds(const hr_bounds *a, const hr_bounds *b)
{
    return a->lo.x == b->lo.x && a->lo.y == b->lo.y && a->lo.z == b->lo.z &&
           a->hi.x == b->hi.x && a->hi.y == b->hi.y && a->hi.z == b->hi.z;
}

static void test_module_info(const char *stem, int class_count)
{
    harness_module module;
    if (!harness_load(stem, &module)) return;
    const hr_module_info *info = module.info;
    CHECK(info->struct_size == sizeof(hr_module_info));
    CHECK(info->abi_version == HR_SHAPE_ABI_VERSION);
    CHECK(info->name && strcmp(info->name, stem) == 0);
    CHECK(info->description && info->description[0]);
    CHECK_MSG(info->class_count == class_count, "%s: %d classes", stem, (int)info->class_count);
    for (int32_t i = 0; i < info->class_count; i++) {
        const hr_shape_class *c = info->classes[i];
        CHECK(c != NULL);
        if (!c) continue;
        CHECK_MSG(c->struct_size == sizeof(hr_shape_class), "%s: struct_size", c->name);
        CHECK_MSG(c->name && c->help && c->help[0], "%s: name and help", stem);
        CHECK_MSG(c->create && c->destroy && c->bounds && c->hit && c->first_hit && c->any_hit,
                  "%s: incomplete vtable", c->name);
        CHECK(c->param_count == 0 || c->params != NULL);
        /* Every surface named (a composite has none of its own). */
        CHECK_MSG(c->surface_count == 0 || c->surface_names != NULL, "%s: surface_names", c->name);
        for (int32_t k = 0; k < c->surface_count && c->surface_names; k++)
            CHECK_MSG(c->surface_names[k] && c->surface_names[k][0], "%s: surface %d unnamed",
                      c->name, (int)k);
    }
    /* The built-ins' version is the project's and they name their author. */
    char version[32];
    snprintf(version, sizeof version, "%d.%d.%d", HR_VERSION_MAJOR, HR_VERSION_MINOR,
             HR_VERSION_PATCH);
    CHECK_MSG(info->version && strcmp(info->version, version) == 0, "%s: version", stem);
    CHECK_MSG(info->author && info->author[0], "%s: author", stem);
    /* The same table on a second call: no state behind the entry point. */
    harness_module again;
    if (harness_load(stem, &again)) {
        CHECK(again.info == info);
        harness_unload(&again);
    }
    harness_unload(&module);
}

/* hr_hit.surface of the cube and the tapered cylinder, by name. */
static void test_surface_names(void)
{
    static const char *const cube[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    static const char *const tapered[] = {"wall", "base", "cap"};
    harness_shape s;
    if (harness_open(&s, "cube", "cube", NAN))
        for (int k = 0; k < 6; k++) CHECK(strcmp(s.cls->surface_names[k], cube[k]) == 0);
    harness_close(&s);
    if (harness_open(&s, "cylinder", "taperedCylinder", NAN))
        for (int k = 0; k < 3; k++) CHECK(strcmp(s.cls->surface_names[k], tapered[k]) == 0);
    harness_close(&s);
}

static void test_class(const expected_class *e)
{
    harness_shape s;
    if (!harness_open(&s, e->module, e->name, NAN)) {
        harness_close(&s);
        return;
    }
    CHECK_MSG(s.cls->flags == e->flags, "%s: flags %d", e->name, (int)s.cls->flags);
    CHECK_MSG(s.cls->surface_count == e->surface_count, "%s: surface_count %d", e->name,
              (int)s.cls->surface_count);
    CHECK_MSG(s.cls->param_count == e->param_count, "%s: param_count %d", e->name,
              (int)s.cls->param_count);
    hr_bounds b;
    s.cls->bounds(s.shape, &b);
    CHECK_MSG(same_bounds(&b, &e->bounds), "%s: bounds (%g %g %g) (%g %g %g)", e->name, b.lo.x,
              b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
    harness_close(&s);
}

/* taperedCylinder's one parameter: s, a number, optional, default 1, range
 * [0, 1e6] (the host checks the range from this). */
static void test_tapered_parameter(void)
{
    harness_module module;
    if (!harness_load("cylinder", &module)) return;
    const hr_shape_class *c = harness_find_class(&module, "taperedCylinder");
    CHECK(c && c->param_count == 1);
    if (c && c->param_count == 1) {
        const hr_param_spec *p = &c->params[0];
        CHECK(strcmp(p->name, "s") == 0);
        CHECK(p->type == HR_PARAM_NUMBER);
        CHECK(p->required == 0);
        CHECK(p->default_number == 1.0);
        CHECK(p->min == 0.0 && p->max == 1e6);
        CHECK(p->help && p->help[0]);
    }
    harness_unload(&module);
}

int main(void)
{
    test_surface_names();
    test_module_info("sphere", 1);
    test_module_info("plane", 1);
    test_module_info("square", 1);
    test_module_info("cube", 1);
    test_module_info("cylinder", 5);
    test_module_info("torus", 1);
    for (int i = 0; i < EXPECTED_COUNT; i++) test_class(&expected[i]);
    test_tapered_parameter();
    return hr_test_end();
}
