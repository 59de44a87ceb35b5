/* What ABI 1 grew for shape classes: hr_param_spec.flags (an excluded end of
 * a range, "> 0"), read through hr_shape_class.param_spec_size so a class
 * built with the first, 48-byte specs keeps its parameters; and
 * hr_hit_args.struct_size, set by the host. Classes registered in process. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *ctx;

static hr_status plain_create(const hr_create_args *a, void **out)
{
    void *p = a->host->alloc(1);
    if (!p) return HR_ERROR_OUT_OF_MEMORY;
    *out = p;
    return HR_OK;
}

static void plain_destroy(void *shape) { free(shape); }

static void unit_box(const void *shape, hr_bounds *b)
{
    (void)shape;
    b->lo = (hr_vec3){-1, -1, -1};
    b->hi = (hr_vec3){1, 1, 1};
}

/* A hit at t = 1 whose surface id says whether the host's hit arguments
 * carry a struct_size that covers the field (1) or not (0). */
static hr_status size_hit(const hr_hit_args *a)
{
    if (!(a->tmin < 1.0 && 1.0 < a->tmax)) return HR_OK;
    hr_hit *h = &a->out->hits[a->out->count++];
    memset(h, 0, sizeof *h);
    h->t = 1.0;
    h->point = (hr_vec3){a->ray.origin.x + a->ray.dir.x, a->ray.origin.y + a->ray.dir.y,
                         a->ray.origin.z + a->ray.dir.z};
    h->normal = (hr_vec3){0, 0, 1};
    h->surface = HR_HIT_ARGS_HAS(a, struct_size) && a->struct_size == sizeof(hr_hit_args);
    h->entering = 1;
    return HR_OK;
}

static const hr_param_spec open_params[] = {
    {.name = "radius", .type = HR_PARAM_NUMBER, .default_number = 1, .min = 0, .max = 1e6,
     .help = "> 0", .flags = HR_PARAM_MIN_EXCLUSIVE},
    {.name = "share", .type = HR_PARAM_NUMBERS, .min = 0, .max = 1,
     .help = "each in [0, 1)", .flags = HR_PARAM_MAX_EXCLUSIVE},
};

static const hr_shape_class open_class = {
    .struct_size = sizeof(hr_shape_class), .name = "openRange", .help = "exclusive bounds",
    .params = open_params, .param_count = 2, .surface_count = 2, .create = plain_create,
    .destroy = plain_destroy, .bounds = unit_box, .hit = size_hit,
};

/* The first layout of a parameter spec, as a module built before flags
 * declared it: 48 bytes, no flags. */
typedef struct first_spec {
    const char *name;
    int32_t type, required;
    double default_number, min, max;
    const char *help;
} first_spec;

static const first_spec first_params[] = {
    {"a", HR_PARAM_NUMBER, 0, 0.0, 0.0, 10.0, "first"},
    {"b", HR_PARAM_NUMBER, 0, 1.5, 1.0, 2.0, "second"},
};

static hr_shape_class first_class = {
    .name = "firstLayout", .help = "specs of 48 bytes", .param_count = 2, .surface_count = 2,
    .create = plain_create, .destroy = plain_destroy, .bounds = unit_box, .hit = size_hit,
};

/* Adds one object of `shape` with the one parameter `p` to a new scene. */
static hr_status add_param(const char *shape, hr_param p)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = shape;
    d.param_count = 1;
    d.params = &p;
    hr_status st = hr_scene_add_object(s, &d, NULL);
    hr_scene_destroy(s);
    return st;
}

static hr_status add(const char *shape, const char *name, double number)
{
    return add_param(shape, (hr_param){.name = name, .type = HR_PARAM_NUMBER, .number = number});
}

static hr_status add_numbers(const double *v, int64_t n)
{
    return add_param("openRange",
                     (hr_param){.name = "share", .type = HR_PARAM_NUMBERS, .numbers = v, .count = n});
}

static int error_has(const char *text)
{
    const char *e = hr_context_last_error(ctx);
    return e && strstr(e, text);
}

/* An excluded minimum refuses the bound itself (and -0), with a message
 * saying "> 0"; anything above it passes, however small. */
static void exclusive_min(void)
{
    CHECK(add("openRange", "radius", 0.0) == HR_ERROR_PARAMETER);
    CHECK_MSG(error_has("parameter 'radius' = 0 is outside (0, 1e+06]: it must be > 0"), "%s",
              hr_context_last_error(ctx));
    CHECK(add("openRange", "radius", -0.0) == HR_ERROR_PARAMETER);
    CHECK(add("openRange", "radius", 1e-300) == HR_OK);
    CHECK(add("openRange", "radius", 1e6) == HR_OK);
    CHECK(add("openRange", "radius", 1.5e6) == HR_ERROR_PARAMETER);
}

/* An excluded maximum, on the elements of an array. */
static void exclusive_max(void)
{
    const double fine[] = {0.0, 0.5, 0.99999999};
    const double one[] = {0.5, 1.0};
    CHECK(add_numbers(fine, 3) == HR_OK);
    CHECK(add_numbers(one, 2) == HR_ERROR_PARAMETER);
    CHECK_MSG(error_has("element 1 of parameter 'share' = 1 is outside [0, 1): it must be < 1"),
              "%s", hr_context_last_error(ctx));
}

/* A class of the first layout: its second spec is found 48 bytes on, not
 * sizeof(hr_param_spec), and its flags read as 0 (inclusive ends). */
static void first_layout(void)
{
    first_class.struct_size = (uint32_t)offsetof(hr_shape_class, param_spec_size);
    first_class.params = (const hr_param_spec *)(const void *)first_params;
    CHECK_OK(hr_context_register_shape_class(ctx, &first_class, "test_param_flags.c"));
    CHECK(add("firstLayout", "b", 2.0) == HR_OK);
    CHECK(add("firstLayout", "a", 0.0) == HR_OK);
    CHECK(add("firstLayout", "b", 3.0) == HR_ERROR_PARAMETER);
    CHECK_MSG(error_has("parameter 'b' = 3 is outside [1, 2]"), "%s", hr_context_last_error(ctx));
}

/* A flag this host does not know is a malformed class, refused with its
 * name, not guessed at. */
static void unknown_flag(void)
{
    static const hr_param_spec odd[] = {
        {.name = "x", .type = HR_PARAM_NUMBER, .min = 0, .max = 1, .help = "", .flags = 8},
    };
    hr_shape_class c = open_class;
    c.name = "oddFlags";
    c.params = odd;
    c.param_count = 1;
    CHECK(hr_context_register_shape_class(ctx, &c, "test_param_flags.c") == HR_ERROR_MODULE);
    CHECK_MSG(error_has("class 'oddFlags' has a malformed parameter 0"), "%s",
              hr_context_last_error(ctx));
}

/* The host fills in hr_hit_args.struct_size for every hit call. */
static void hit_args_size(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "openRange";
    CHECK_OK(hr_scene_add_object(s, &d, NULL));
    CHECK_OK(hr_scene_commit(s));
    const hr_ray down = {{0, 0, 5}, {0, 0, -1}};
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    CHECK(found == 1);
    CHECK_MSG(h.surface == 1, "the shape saw no struct_size of %zu", sizeof(hr_hit_args));
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_register_shape_class(ctx, &open_class, "test_param_flags.c"));
    exclusive_min();
    exclusive_max();
    first_layout();
    unknown_flag();
    hit_args_size();
    hr_context_destroy(ctx);
    return hr_test_end();
}
