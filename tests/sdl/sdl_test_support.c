#include "sdl_test_support.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- stub shapes: no hits, just bounds; enough for the reader ---- */

typedef struct stub {
    hr_bounds bounds;
} stub;

static stub *new_stub(double lo_xy, double hi_xy, double lo_z, double hi_z)
{
    stub *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->bounds.lo = (hr_vec3){lo_xy, lo_xy, lo_z};
    s->bounds.hi = (hr_vec3){hi_xy, hi_xy, hi_z};
    return s;
}

static hr_status stub_box_create(const hr_create_args *a, void **out)
{
    (void)a;
    *out = new_stub(-1, 1, -1, 1);
    return *out ? HR_OK : HR_ERROR_OUT_OF_MEMORY;
}

static hr_status stub_plane_create(const hr_create_args *a, void **out)
{
    (void)a;
    *out = new_stub(-HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL);
    return *out ? HR_OK : HR_ERROR_OUT_OF_MEMORY;
}

/* The bounds show the `s` the reader passed. */
static hr_status stub_taper_create(const hr_create_args *a, void **out)
{
    double s = a->params[0].number;
    double r = s > 1 ? s : 1;
    *out = new_stub(-r, r, 0, 1);
    return *out ? HR_OK : HR_ERROR_OUT_OF_MEMORY;
}

/* Refuses, saying what it was given: tests read file and base_dir back. */
static hr_status stub_mesh_create(const hr_create_args *a, void **out)
{
    snprintf(a->error, a->error_size, "stub mesh: file '%s' in '%s'", a->params[0].string,
             a->base_dir);
    *out = NULL;
    return HR_ERROR_PARAMETER;
}

static void stub_destroy(void *shape) { free(shape); }

static void stub_bounds(const void *shape, hr_bounds *out) { *out = ((const stub *)shape)->bounds; }

static hr_status stub_hit(const hr_hit_args *args)
{
    (void)args;
    return HR_OK;
}

static const hr_param_spec taper_params[] = {
    {"s", HR_PARAM_NUMBER, 0, 1.0, 0.0, HUGE_VAL, "top radius", 0},
};
static const hr_param_spec mesh_params[] = {
    {"file", HR_PARAM_STRING, 1, 0.0, 0.0, 0.0, "mesh file", 0},
};
static const hr_param_spec csg_params[] = {
    {"a", HR_PARAM_OBJECT, 1, 0.0, 0.0, 0.0, "operand A", 0},
    {"b", HR_PARAM_OBJECT, 1, 0.0, 0.0, 0.0, "operand B", 0},
};

#define STUB_CLASS(name_, flags_, params_, count_, create_)                                 \
    {sizeof(hr_shape_class), flags_, name_, "SDL test stub", params_, count_, 1, create_,     \
     stub_destroy, stub_bounds, stub_hit, NULL, NULL, NULL, NULL, NULL, 0}

static const hr_shape_class stub_shapes[] = {
    STUB_CLASS("sphere", HR_SHAPE_CLOSED, NULL, 0, stub_box_create),
    STUB_CLASS("cube", HR_SHAPE_CLOSED, NULL, 0, stub_box_create),
    STUB_CLASS("square", 0, NULL, 0, stub_box_create),
    STUB_CLASS("plane", 0, NULL, 0, stub_plane_create),
    STUB_CLASS("cylinder", HR_SHAPE_CLOSED, NULL, 0, stub_box_create),
    STUB_CLASS("cone", HR_SHAPE_CLOSED, NULL, 0, stub_box_create),
    STUB_CLASS("taperedCylinder", HR_SHAPE_CLOSED, taper_params, 1, stub_taper_create),
};
static const hr_shape_class stub_csg[] = {
    STUB_CLASS("union", HR_SHAPE_CLOSED | HR_SHAPE_COMPOSITE, csg_params, 2, stub_box_create),
    STUB_CLASS("intersection", HR_SHAPE_CLOSED | HR_SHAPE_COMPOSITE, csg_params, 2,
               stub_box_create),
    STUB_CLASS("difference", HR_SHAPE_CLOSED | HR_SHAPE_COMPOSITE, csg_params, 2,
               stub_box_create),
};
static const hr_shape_class stub_mesh = STUB_CLASS("mesh", 0, mesh_params, 1, stub_mesh_create);

static void register_all(hr_context *ctx, const hr_shape_class *classes, size_t count)
{
    for (size_t i = 0; i < count; i++)
        if (hr_context_register_shape_class(ctx, &classes[i], "sdl-test-stub") != HR_OK) {
            fprintf(stderr, "cannot register stub '%s': %s\n", classes[i].name,
                    hr_context_last_error(ctx));
            exit(2);
        }
}

hr_context *sdl_test_context(int stubs)
{
    hr_context *ctx = NULL;
    if (hr_context_create(&ctx) != HR_OK) {
        fprintf(stderr, "cannot create a context\n");
        exit(2);
    }
    if (stubs & SDL_STUB_SHAPES) register_all(ctx, stub_shapes, sizeof stub_shapes / sizeof stub_shapes[0]);
    if (stubs & SDL_STUB_CSG) register_all(ctx, stub_csg, sizeof stub_csg / sizeof stub_csg[0]);
    if (stubs & SDL_STUB_MESH) register_all(ctx, &stub_mesh, 1);
    return ctx;
}

int sdl_test_has_class(hr_context *ctx, const char *name)
{
    const hr_shape_class *cls;
    return hr_context_find_shape_class(ctx, name, &cls, NULL) == HR_OK;
}

/* ---- loading ---- */

hr_scene *sdl_test_load_at(const char *file, int line, hr_context *ctx, const char *text,
                           hr_sdl_result *result)
{
    memset(result, 0, sizeof *result);
    result->struct_size = sizeof *result;
    hr_status st = hr_sdl_load_string(ctx, text, SDL_TEST_NAME, NULL, result);
    hr_test_checks++;
    if (st != HR_OK || !result->scene) {
        hr_test_fail(file, line, "loading failed (%d): %s\n--- text:\n%.400s", (int)st,
                     hr_context_last_error(ctx), text);
        if (result->scene) hr_scene_destroy(result->scene);
        result->scene = NULL;
    }
    return result->scene;
}

void sdl_test_expect_error_at(const char *file, int line, hr_context *ctx, const char *text,
                              hr_status status, int err_line, int err_col, ...)
{
    hr_sdl_result result;
    memset(&result, 0, sizeof result);
    result.struct_size = sizeof result;
    result.has_camera = 7; /* must be reset */
    hr_status st = hr_sdl_load_string(ctx, text, SDL_TEST_NAME, NULL, &result);
    const char *message = hr_context_last_error(ctx);
    hr_test_checks++;
    if (st != status)
        hr_test_fail(file, line, "status %d, expected %d; message: %s", (int)st, (int)status,
                     message);
    hr_test_checks++;
    if (result.scene || result.has_camera != 0) {
        hr_test_fail(file, line, "a failed load returned a scene or has_camera");
        if (result.scene) hr_scene_destroy(result.scene);
    }
    char place[64];
    snprintf(place, sizeof place, "%s:%d:%d: ", SDL_TEST_NAME, err_line, err_col);
    hr_test_checks++;
    if (strncmp(message, place, strlen(place)) != 0)
        hr_test_fail(file, line, "message does not start with '%s': %s", place, message);

    hr_error_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    hr_test_checks++;
    if (hr_context_last_error_info(ctx, &info) != HR_OK || info.status != status ||
        info.line != err_line || info.column != err_col || strcmp(info.file, SDL_TEST_NAME) != 0)
        hr_test_fail(file, line, "error info: status %d, %s:%d:%d; expected %d, %s:%d:%d",
                     (int)info.status, info.file ? info.file : "(null)", (int)info.line,
                     (int)info.column, (int)status, SDL_TEST_NAME, err_line, err_col);

    va_list ap;
    va_start(ap, err_col);
    for (const char *want = va_arg(ap, const char *); want; want = va_arg(ap, const char *)) {
        hr_test_checks++;
        if (!strstr(message, want))
            hr_test_fail(file, line, "message lacks \"%s\": %s", want, message);
    }
    va_end(ap);
}

hr_object_info sdl_test_object(const hr_scene *scene, int64_t index)
{
    hr_object_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    if (hr_scene_object_info(scene, index, &info) != HR_OK) {
        memset(&info, 0, sizeof info);
        info.shape = "(no such object)";
    }
    return info;
}

void sdl_test_check_matrix_at(const char *file, int line, const double got[16],
                              const double want[16], double tol, const char *what)
{
    for (int i = 0; i < 16; i++) {
        hr_test_checks++;
        if (!(fabs(got[i] - want[i]) <= tol))
            hr_test_fail(file, line, "%s[%d][%d] = %.17g, expected %.17g", what, i / 4, i % 4,
                         got[i], want[i]);
    }
}

double sdl_test_seconds(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
