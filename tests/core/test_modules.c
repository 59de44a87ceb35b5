/* The module loader: loading by path, refusals naming the module's path,
 * parameter checks naming the parameter, an older (shorter) class table,
 * directory scanning, and classes registered in process. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, symlink */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <hitray/hitray.h>

#include "hr_test.h"

#define PROBE HR_TEST_MODULE_DIR "/probe.so"

static int contains(const char *hay, const char *needle)
{
    int ok = strstr(hay, needle) != NULL;
    if (!ok) fprintf(stderr, "  message: %s\n  lacks: %s\n", hay, needle);
    return ok;
}

static hr_status add_probe(hr_context *ctx, hr_scene *s, const hr_param *p, int32_t n)
{
    (void)ctx;
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "probeSphere";
    d.params = p;
    d.param_count = n;
    return hr_scene_add_object(s, &d, NULL);
}

static void test_load_and_params(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_load_module(ctx, PROBE));
    const hr_shape_class *cls;
    const char *path;
    CHECK_OK(hr_context_find_shape_class(ctx, "probeSphere", &cls, &path));
    CHECK(strcmp(path, PROBE) == 0);

    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_param radius = {.name = "radius", .type = HR_PARAM_NUMBER, .number = 2.0, .string = NULL, .object = 0};
    CHECK_OK(add_probe(ctx, s, &radius, 1));

    hr_param bogus = {.name = "bogus", .type = HR_PARAM_NUMBER, .number = 1.0, .string = NULL, .object = 0};
    CHECK(add_probe(ctx, s, &bogus, 1) == HR_ERROR_PARAMETER);
    CHECK(contains(hr_context_last_error(ctx), "has no parameter 'bogus'"));
    CHECK(contains(hr_context_last_error(ctx), "radius, refuse, label"));
    CHECK(contains(hr_context_last_error(ctx), PROBE));

    hr_param big = {.name = "radius", .type = HR_PARAM_NUMBER, .number = 1000.0, .string = NULL, .object = 0};
    CHECK(add_probe(ctx, s, &big, 1) == HR_ERROR_PARAMETER);
    CHECK(contains(hr_context_last_error(ctx), "parameter 'radius' = 1000 is outside [1e-06, 100]"));

    hr_param nan_radius = {.name = "radius", .type = HR_PARAM_NUMBER, .number = NAN, .string = NULL, .object = 0};
    CHECK(add_probe(ctx, s, &nan_radius, 1) == HR_ERROR_PARAMETER);
    CHECK(contains(hr_context_last_error(ctx), "finite"));

    hr_param as_string = {.name = "radius", .type = HR_PARAM_STRING, .number = 0, .string = "two", .object = 0};
    CHECK(add_probe(ctx, s, &as_string, 1) == HR_ERROR_PARAMETER);
    CHECK(contains(hr_context_last_error(ctx), "parameter 'radius' must be a number, not a string"));

    hr_param twice[2] = {radius, radius};
    CHECK(add_probe(ctx, s, twice, 2) == HR_ERROR_PARAMETER);
    CHECK(contains(hr_context_last_error(ctx), "given twice"));

    hr_param refuse = {.name = "refuse", .type = HR_PARAM_NUMBER, .number = 1.0, .string = NULL, .object = 0};
    CHECK(add_probe(ctx, s, &refuse, 1) == HR_ERROR_PARAMETER);
    CHECK(contains(hr_context_last_error(ctx), "shape 'probeSphere' (module '" PROBE "')"));
    CHECK(contains(hr_context_last_error(ctx), "parameter 'refuse' is 1"));

    /* Only the one good object went in; it works. */
    CHECK(hr_scene_object_count(s) == 1);
    CHECK_OK(hr_scene_commit(s));
    hr_ray ray = {{0, 0, -10}, {0, 0, 1}};
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &ray, 0, INFINITY, &h, &found));
    CHECK(found == 1);
    CHECK_NEAR(h.t, 8.0, 1e-12);
    CHECK(h.entering == 1);

    /* A committed scene refuses edits. */
    CHECK(add_probe(ctx, s, &radius, 1) == HR_ERROR_STATE);
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
}

static void test_refusals(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    const char *wrong = HR_TEST_MODULE_DIR "/wrong_abi.so";
    CHECK(hr_context_load_module(ctx, wrong) == HR_ERROR_MODULE);
    CHECK(contains(hr_context_last_error(ctx), wrong));
    CHECK(contains(hr_context_last_error(ctx), "shape ABI version 99"));
    CHECK(contains(hr_context_last_error(ctx), "provides version 1"));

    const char *no_entry = HR_TEST_MODULE_DIR "/no_entry.so";
    CHECK(hr_context_load_module(ctx, no_entry) == HR_ERROR_MODULE);
    CHECK(contains(hr_context_last_error(ctx), no_entry));
    CHECK(contains(hr_context_last_error(ctx), "no entry point 'hr_shape_module'"));

    const char *missing = HR_TEST_MODULE_DIR "/does_not_exist.so";
    CHECK(hr_context_load_module(ctx, missing) == HR_ERROR_MODULE);
    CHECK(contains(hr_context_last_error(ctx), missing));

    const hr_shape_class *cls;
    CHECK(hr_context_find_shape_class(ctx, "noSuchShape", &cls, NULL) == HR_ERROR_MODULE);
    CHECK(contains(hr_context_last_error(ctx), "no shape module provides 'noSuchShape'"));
    CHECK(contains(hr_context_last_error(ctx), "searched:"));
    hr_context_destroy(ctx);
}

/* The metadata a module gives (hr_module_info.version, author, url) is
 * listed as given, NULL as ""; an info too short to hold it has none. */
static void check_metadata(const hr_module_entry *e)
{
    if (strcmp(e->name, "probe") == 0) {
        CHECK(strcmp(e->version, "1.2.3") == 0);
        CHECK(strcmp(e->author, "the probe's author") == 0);
        CHECK(strcmp(e->url, "") == 0);
    } else if (strcmp(e->name, "old_abi_layout") == 0) {
        CHECK(strcmp(e->version, "") == 0 && strcmp(e->author, "") == 0);
    } else if (strcmp(e->name, "cube") == 0) {
        char version[32];
        snprintf(version, sizeof version, "%d.%d.%d", HR_VERSION_MAJOR, HR_VERSION_MINOR,
                 HR_VERSION_PATCH);
        CHECK(strcmp(e->version, version) == 0 && *e->author);
    }
}

/* Scanning a directory: good modules usable, refused ones listed with why. */
static void test_scan(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_add_shape_dir(ctx, HR_TEST_MODULE_DIR));
    const hr_shape_class *cls;
    const char *path;
    CHECK_OK(hr_context_find_shape_class(ctx, "probeSphere", &cls, &path));
    CHECK(strcmp(path, PROBE) == 0);
    int32_t n = hr_context_module_count(ctx);
    int refused = 0, loaded = 0;
    for (int32_t i = 0; i < n; i++) {
        hr_module_entry e = {0};
        e.struct_size = sizeof e;
        CHECK_OK(hr_context_module(ctx, i, &e));
        if (e.loaded) {
            loaded++;
            check_metadata(&e);
        } else {
            refused++;
            CHECK(strstr(e.error, e.path) != NULL);
        }
    }
    CHECK(refused == 2); /* wrong_abi, no_entry */
    CHECK(loaded >= 2);  /* probe, old_abi_layout (+ the built-in shapes) */
    /* A missing class now names the refused modules too. */
    CHECK(hr_context_find_shape_class(ctx, "noSuchShape", &cls, NULL) == HR_ERROR_MODULE);
    CHECK(contains(hr_context_last_error(ctx), "wrong_abi.so"));
    hr_context_destroy(ctx);
}

/* A directory every user may write to is searched, but nothing in it is
 * loaded: its modules are listed as refused, saying why (issue 16). */
static void test_world_writable_dir(void)
{
    char dir[] = "/tmp/hitray_ww_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char link[128];
    snprintf(link, sizeof link, "%s/probe.so", dir);
    CHECK(symlink(PROBE, link) == 0);
    CHECK(chmod(dir, 0777) == 0);
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_add_shape_dir(ctx, dir));
    const hr_shape_class *cls;
    CHECK(hr_context_find_shape_class(ctx, "probeSphere", &cls, NULL) == HR_ERROR_MODULE);
    CHECK(contains(hr_context_last_error(ctx), "writable by every user"));
    int found = 0;
    for (int32_t i = 0; i < hr_context_module_count(ctx); i++) {
        hr_module_entry e = {0};
        e.struct_size = sizeof e;
        CHECK_OK(hr_context_module(ctx, i, &e));
        if (strcmp(e.path, link) != 0) continue;
        found = 1;
        CHECK(!e.loaded && contains(e.error, "is writable by every user"));
    }
    CHECK(found);
    hr_context_destroy(ctx);
    /* Writable by its owner only, the same directory is searched as usual. */
    CHECK(chmod(dir, 0755) == 0);
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_add_shape_dir(ctx, dir));
    CHECK_OK(hr_context_find_shape_class(ctx, "probeSphere", &cls, NULL));
    hr_context_destroy(ctx);
    remove(link);
    rmdir(dir);
}

/* A module with a short class table (no first_hit/any_hit fields, garbage
 * after its declared size) works for every query, shadows included. */
static void test_old_layout(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_load_module(ctx, HR_TEST_MODULE_DIR "/old_abi_layout.so"));
    const hr_shape_class *cls;
    CHECK_OK(hr_context_find_shape_class(ctx, "oldSlab", &cls, NULL));
    CHECK(cls->first_hit == NULL && cls->any_hit == NULL);
    CHECK(cls->struct_size == sizeof(hr_shape_class));
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "oldSlab";
    CHECK_OK(hr_scene_add_object(s, &d, NULL));
    hr_light l = {sizeof l, 0, {0, 0, 10}, {1, 1, 1}};
    CHECK_OK(hr_scene_add_light(s, &l));
    CHECK_OK(hr_scene_commit(s));
    hr_ray ray = {{0, 0, 5}, {0, 0, -1}};
    hr_hit h;
    int32_t found;
    CHECK_OK(hr_scene_first_hit(s, &ray, 0, INFINITY, &h, &found));
    CHECK(found == 1);
    CHECK_NEAR(h.t, 4.0, 0.0);
    hr_color c;
    CHECK_OK(hr_scene_shade(s, &ray, -1, &c)); /* shadow ray: any-hit fallback */
    CHECK(c.r > 0.5);
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
}

/* A class that lives in this program, registered without a module file. */
static hr_status mem_create(const hr_create_args *a, void **out)
{
    (void)a;
    static int token;
    *out = &token;
    return HR_OK;
}
static void mem_destroy(void *p) { (void)p; }
static void mem_bounds(const void *p, hr_bounds *b)
{
    (void)p;
    *b = (hr_bounds){{-1, -1, -1}, {1, 1, 1}};
}
static hr_status mem_hit(const hr_hit_args *a)
{
    if (a->ray.dir.z == 0) return HR_OK;
    double t = -a->ray.origin.z / a->ray.dir.z;
    if (!(t > a->tmin && t < a->tmax)) return HR_OK;
    hr_hit *h = &a->out->hits[a->out->count++];
    memset(h, 0, sizeof *h);
    h->t = t;
    h->point = (hr_vec3){a->ray.origin.x + t * a->ray.dir.x, a->ray.origin.y + t * a->ray.dir.y, 0};
    h->normal = (hr_vec3){0, 0, 1};
    h->entering = a->ray.dir.z < 0;
    return HR_OK;
}

static void test_registered(void)
{
    static const hr_shape_class cls = {sizeof(hr_shape_class), 0, "memDisc", "in-process test",
                                       NULL, 0, 1, mem_create, mem_destroy, mem_bounds, mem_hit,
                                       NULL, NULL, NULL, NULL, NULL, 0};
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_register_shape_class(ctx, &cls, "test_modules.c"));
    const hr_shape_class *found_cls;
    const char *origin;
    CHECK_OK(hr_context_find_shape_class(ctx, "memDisc", &found_cls, &origin));
    CHECK(strcmp(origin, "test_modules.c") == 0);
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "memDisc";
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, 0, 0, 3);
    d.transform = t.m;
    CHECK_OK(hr_scene_add_object(s, &d, NULL));
    CHECK_OK(hr_scene_commit(s));
    hr_ray ray = {{0.5, 0, 10}, {0, 0, -2}};
    hr_hit h;
    int32_t found;
    CHECK_OK(hr_scene_first_hit(s, &ray, 0, INFINITY, &h, &found));
    CHECK(found && h.t == 3.5 && h.point.z == 3.0);
    hr_scene_destroy(s);
    hr_context_destroy(ctx);
}

int main(void)
{
    test_load_and_params();
    test_refusals();
    test_scan();
    test_world_writable_dir();
    test_old_layout();
    test_registered();
    return hr_test_end();
}
