/* Shape classes that break the contract of shape_module.h (hits out of
 * order, outside (tmin, tmax), NaN, more hits than the room they were given,
 * a composite naming an object that does not exist, normals of extreme
 * length). The host says it enforces the contract instead of trusting it:
 * whatever such a class returns, the scene queries must stay in bounds, keep
 * their own promises (nearest hit, unit normals, finite values) or report
 * an error. Registered in process, so no module file is needed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "scene_builder.h"

static hr_context *ctx;

/* What a rogue instance does wrong. */
#define ROGUE_UNSORTED 1       /* hits at t = 3 then t = 1 */
#define ROGUE_OUT_OF_RANGE 2   /* a hit before tmin, then one at t = 2 */
#define ROGUE_ANY_BEYOND 3     /* no hits, but any_hit reports t > tmax */
#define ROGUE_ANY_NAN 4        /* no hits, but any_hit reports t = NaN */
#define ROGUE_OVERFLOW 6       /* claims more hits than the list can hold */
#define ROGUE_TINY_NORMAL 7    /* a hit at t = 2 with normal (0, 0, 1e-200) */
#define ROGUE_HUGE_NORMAL 8    /* a hit at t = 2 with normal (0, 0, 1e300) */
#define ROGUE_SHRINK 9         /* lowers out->count below where it started */
/* ROGUE_BAD_FIELD + 3 field + kind: a hit at t = 1 whose field (0-2: point,
 * 3-5: normal, 6: error) is +inf, -inf or NaN (kind 0, 1, 2), then a good
 * hit at t = 2. ROGUE_FAR_POINT: a hit at t = 1 whose point is finite but
 * overflows under a large transform, then the good hit. */
#define ROGUE_BAD_FIELD 100
#define ROGUE_FAR_POINT 130
/* One hit alone at t = 1 (the host's path for a single first hit), with a
 * normal that has no zero coordinate, whose point (ROGUE_FAR_POINT_ALONE)
 * or error (ROGUE_FAR_ERROR_ALONE) is finite but overflows under a large
 * transform. */
#define ROGUE_FAR_POINT_ALONE 131
#define ROGUE_FAR_ERROR_ALONE 132

typedef struct rogue {
    int mode;
} rogue;

static const hr_param_spec rogue_params[] = {
    {"mode", HR_PARAM_NUMBER, 1, 0, 0, 200, "which rule to break", 0},
};

static hr_status rogue_create(const hr_create_args *a, void **out)
{
    rogue *r = a->host->alloc(sizeof *r);
    if (!r) return HR_ERROR_OUT_OF_MEMORY;
    r->mode = (int)a->params[0].number;
    *out = r;
    return HR_OK;
}

static void rogue_destroy(void *shape) { free(shape); }

static void unbounded(const void *shape, hr_bounds *b)
{
    (void)shape;
    b->lo = (hr_vec3){-INFINITY, -INFINITY, -INFINITY};
    b->hi = (hr_vec3){INFINITY, INFINITY, INFINITY};
}

static void put(const hr_hit_args *a, double t, hr_vec3 normal)
{
    hr_hit *h = &a->out->hits[a->out->count++];
    memset(h, 0, sizeof *h);
    h->t = t;
    h->point = (hr_vec3){a->ray.origin.x + t * a->ray.dir.x, a->ray.origin.y + t * a->ray.dir.y,
                         a->ray.origin.z + t * a->ray.dir.z};
    h->normal = normal;
    h->entering = 1;
}

static hr_status rogue_hit(const hr_hit_args *a)
{
    const rogue *r = a->shape;
    hr_vec3 up = {0, 0, 1}, tilted = {0.5, 0.5, 1};
    switch (r->mode) {
    case ROGUE_UNSORTED:
        put(a, 3, up);
        put(a, 1, up);
        break;
    case ROGUE_OUT_OF_RANGE:
        put(a, a->tmin - 1, up);
        put(a, 2, up);
        break;
    case ROGUE_OVERFLOW:
        /* Writes nothing, but says it wrote far past the capacity. */
        a->out->count = a->out->capacity + 100;
        break;
    case ROGUE_TINY_NORMAL: put(a, 2, (hr_vec3){0, 0, 1e-200}); break;
    case ROGUE_HUGE_NORMAL: put(a, 2, (hr_vec3){0, 0, 1e300}); break;
    case ROGUE_SHRINK: a->out->count = -5; break;
    case ROGUE_FAR_POINT:
        put(a, 1, up);
        a->out->hits[a->out->count - 1].point.x = 1e300;
        put(a, 2, up);
        break;
    case ROGUE_FAR_POINT_ALONE:
        put(a, 1, tilted);
        a->out->hits[a->out->count - 1].point.x = 1e300;
        break;
    case ROGUE_FAR_ERROR_ALONE:
        put(a, 1, tilted);
        a->out->hits[a->out->count - 1].error = 1e300;
        break;
    default:
        if (r->mode >= ROGUE_BAD_FIELD && r->mode < ROGUE_BAD_FIELD + 21) {
            const int field = (r->mode - ROGUE_BAD_FIELD) / 3, kind = (r->mode - ROGUE_BAD_FIELD) % 3;
            const double bad = kind == 0 ? INFINITY : kind == 1 ? -INFINITY : NAN;
            put(a, 1, up);
            hr_hit *h = &a->out->hits[a->out->count - 1];
            double *fields[7] = {&h->point.x,  &h->point.y,  &h->point.z, &h->normal.x,
                                 &h->normal.y, &h->normal.z, &h->error};
            *fields[field] = bad;
            put(a, 2, up);
        }
        break;
    }
    return HR_OK;
}

static hr_status rogue_any(const hr_hit_args *a)
{
    const rogue *r = a->shape;
    if (r->mode == ROGUE_ANY_BEYOND) put(a, a->tmax + 1, (hr_vec3){0, 0, 1});
    else if (r->mode == ROGUE_ANY_NAN) put(a, NAN, (hr_vec3){0, 0, 1});
    else return rogue_hit(a);
    return HR_OK;
}

static const hr_shape_class rogue_class = {
    sizeof(hr_shape_class), 0, "rogue", "breaks the shape contract on purpose",
    rogue_params, 1, 1, rogue_create, rogue_destroy, unbounded, rogue_hit, NULL, rogue_any, NULL, NULL, NULL, 0
};

/* A composite that makes a hit of its own and leaves `object` naming no
 * object of the scene (the contract says modules leave it alone). */
static hr_status composite_create(const hr_create_args *a, void **out)
{
    *out = a->host->alloc(1);
    return *out ? HR_OK : HR_ERROR_OUT_OF_MEMORY;
}

static hr_status composite_hit(const hr_hit_args *a)
{
    put(a, 2, (hr_vec3){0, 0, 1});
    a->out->hits[a->out->count - 1].object = (int64_t)1 << 40;
    return HR_OK;
}

static const hr_shape_class composite_class = {
    sizeof(hr_shape_class), HR_SHAPE_COMPOSITE, "rogueComposite", "names a leaf that is not there",
    NULL, 0, 1, composite_create, rogue_destroy, unbounded, composite_hit, NULL, NULL, NULL, NULL, NULL, 0
};

static hr_scene *rogue_scene(int mode, const hr_transform *t)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_param p = {.name = "mode", .type = HR_PARAM_NUMBER, .number = mode, .string = NULL, .object = 0};
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "rogue";
    d.param_count = 1;
    d.params = &p;
    d.transform = t ? t->m : NULL;
    d.inverse = t ? t->inv : NULL;
    CHECK_OK(hr_scene_add_object(s, &d, NULL));
    return s;
}

static const hr_ray down = {{0, 0, 5}, {0, 0, -1}};

/* getFirstHit is the nearest hit even when the class lists hits out of
 * order (it has no first_hit, so the host asks `hit` for everything). */
static void unsorted_hits(void)
{
    hr_scene *s = rogue_scene(ROGUE_UNSORTED, NULL);
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    CHECK(found == 1);
    CHECK_MSG(h.t == 1.0, "first hit at t = %g, expected 1", h.t);
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &down, 0, INFINITY, &all));
    CHECK(all.count == 2 && all.hits[0].t == 1.0 && all.hits[1].t == 3.0);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* A hit before tmin is dropped, and the valid hit after it still counts. */
static void out_of_range_first(void)
{
    hr_scene *s = rogue_scene(ROGUE_OUT_OF_RANGE, NULL);
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    CHECK_MSG(found == 1 && h.t == 2.0, "found %d at t = %g, expected the hit at t = 2",
              (int)found, found ? h.t : NAN);
    hr_scene_destroy(s);
}

/* A shadow ray is blocked only by a hit strictly between the point and the
 * light: an any_hit answer beyond the light or NaN blocks nothing. */
static void any_hit_outside(int mode)
{
    hr_scene *s = rogue_scene(mode, NULL);
    hr_material white = tb_black();
    white.diffuse = (hr_color){1, 1, 1};
    CHECK(tb_add(s, "sphere", &white, NULL) >= 0);
    tb_light(s, 0, 0, 10, 1, 1, 1);
    tb_dark_globals(s, 0);
    CHECK_OK(hr_scene_commit(s));
    hr_color c;
    CHECK_OK(hr_scene_shade(s, &down, -1, &c));
    /* The sphere's top faces the light head on: diffuse 1 * light 1. */
    CHECK_MSG(fabs(c.r - 1.0) < 1e-9, "mode %d: colour %g, expected 1 (lit)", mode, c.r);
    hr_scene_destroy(s);
}

/* More hits than the room given (without host->reserve): the host reports
 * the module's failure instead of reading past the list. */
static void overflowing_count(int mode)
{
    hr_scene *s = rogue_scene(mode, NULL);
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    int32_t found = 0;
    hr_status st = hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found);
    CHECK_MSG(st != HR_OK && found == 0, "mode %d: first hit returned %d, found %d", mode, (int)st,
              (int)found);
    hr_intersection all;
    hr_intersection_init(&all);
    st = hr_scene_all_hits(s, &down, 0, INFINITY, &all);
    CHECK_MSG(st != HR_OK && all.count == 0, "mode %d: all hits returned %d, count %d", mode,
              (int)st, (int)all.count);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* Normals of any non-zero length are allowed from a shape; the world normal
 * of a hit is unit length and finite, through any transform. */
static void extreme_normals(void)
{
    hr_scene *s = rogue_scene(ROGUE_TINY_NORMAL, NULL);
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    CHECK(found == 1);
    CHECK_MSG(fabs(h.normal.z - 1.0) < 1e-15, "tiny normal came back as (%g %g %g)", h.normal.x,
              h.normal.y, h.normal.z);
    hr_scene_destroy(s);

    /* Squashed along z: M^-T scales the object normal's z by 1e10. */
    hr_transform t;
    hr_transform_identity(&t);
    CHECK_OK(hr_transform_scale(&t, 1, 1, 1e-10));
    s = rogue_scene(ROGUE_HUGE_NORMAL, &t);
    CHECK_OK(hr_scene_commit(s));
    found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    CHECK(found == 1);
    CHECK_MSG(fabs(h.normal.z - 1.0) < 1e-15, "huge normal came back as (%g %g %g)", h.normal.x,
              h.normal.y, h.normal.z);
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &down, 0, INFINITY, &all));
    CHECK(all.count == 1 && fabs(all.hits[0].normal.z - 1.0) < 1e-15);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* A hit with any one non-finite field, in object space or after the
 * transform to the world, is dropped whichever field it is, and the good
 * hit behind it is the answer. */
static void first_and_all_are_the_good_hit(hr_scene *s, const char *what)
{
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    CHECK_MSG(found == 1 && h.t == 2.0, "%s: found %d at t = %g, expected the hit at t = 2", what,
              (int)found, found ? h.t : NAN);
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &down, 0, INFINITY, &all));
    CHECK_MSG(all.count == 1 && all.hits[0].t == 2.0, "%s: all hits gave %d hits", what,
              (int)all.count);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

static void non_finite_fields(void)
{
    static const char *const names[7] = {"point.x",  "point.y",  "point.z", "normal.x",
                                         "normal.y", "normal.z", "error"};
    static const char *const kinds[3] = {"+inf", "-inf", "NaN"};
    hr_transform scale;
    hr_transform_identity(&scale);
    CHECK_OK(hr_transform_scale(&scale, 2, 2, 2));
    for (int field = 0; field < 7; field++)
        for (int kind = 0; kind < 3; kind++)
            for (int moved = 0; moved < 2; moved++) {
                char what[80];
                snprintf(what, sizeof what, "%s = %s%s", names[field], kinds[kind],
                         moved ? " (scaled)" : "");
                first_and_all_are_the_good_hit(
                    rogue_scene(ROGUE_BAD_FIELD + 3 * field + kind, moved ? &scale : NULL), what);
            }
    /* 1e300 is finite, 1e300 * 1e10 is not: caught after the transform. */
    hr_transform big;
    hr_transform_identity(&big);
    CHECK_OK(hr_transform_scale(&big, 1e10, 1, 1));
    first_and_all_are_the_good_hit(rogue_scene(ROGUE_FAR_POINT, &big), "point overflowing to the world");
    /* The same for a class's only hit, which the host takes to the world in
     * place (a translate and scale, one term a row): dropped, nothing found. */
    static const int alone[2] = {ROGUE_FAR_POINT_ALONE, ROGUE_FAR_ERROR_ALONE};
    /* No zero coordinate in the hit's point or normal, either side of the
     * transform: the one-term forms of a diagonal transform hold for them. */
    const hr_ray aslant = {{0.5, 0.25, 5}, {0, 0, -1}};
    for (int k = 0; k < 2; k++) {
        hr_scene *s = rogue_scene(alone[k], &big);
        CHECK_OK(hr_scene_commit(s));
        hr_hit h;
        int32_t found = 1;
        CHECK_OK(hr_scene_first_hit(s, &aslant, 0, INFINITY, &h, &found));
        CHECK_MSG(found == 0, "%s overflowing to the world alone: found at t = %g", k ? "error" : "point", h.t);
        hr_intersection all;
        hr_intersection_init(&all);
        CHECK_OK(hr_scene_all_hits(s, &aslant, 0, INFINITY, &all));
        CHECK_MSG(all.count == 0, "%s overflowing alone: all hits gave %d", k ? "error" : "point",
                  (int)all.count);
        hr_intersection_release(&all);
        hr_scene_destroy(s);
    }
}

/* A committed scene with no objects: every query answers "nothing". */
static void empty_scene(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    CHECK_OK(hr_scene_commit(s));
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &down, 0, INFINITY, &all));
    CHECK(all.count == 0);
    hr_intersection_release(&all);
    hr_scene_destroy(s);
}

/* A composite's hit naming an object the scene does not have is the
 * composite's own hit: it never indexes past the object list. */
static void composite_bad_leaf(void)
{
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "rogueComposite";
    int64_t index = -1;
    CHECK_OK(hr_scene_add_object(s, &d, &index));
    CHECK_OK(hr_scene_commit(s));
    hr_hit h;
    int32_t found = 0;
    CHECK_OK(hr_scene_first_hit(s, &down, 0, INFINITY, &h, &found));
    CHECK(found == 1);
    CHECK_MSG(h.object == index, "hit names object %lld, the scene has %lld", (long long)h.object,
              (long long)hr_scene_object_count(s));
    hr_intersection all;
    hr_intersection_init(&all);
    CHECK_OK(hr_scene_all_hits(s, &down, 0, INFINITY, &all));
    CHECK(all.count == 1 && all.hits[0].object == index);
    hr_intersection_release(&all);
    /* Shading looks the object up: this must not read past the list. */
    hr_color c;
    CHECK_OK(hr_scene_shade(s, &down, -1, &c));
    CHECK(isfinite(c.r) && isfinite(c.g) && isfinite(c.b));
    hr_scene_destroy(s);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    CHECK_OK(hr_context_register_shape_class(ctx, &rogue_class, "test_rogue_shapes.c"));
    CHECK_OK(hr_context_register_shape_class(ctx, &composite_class, "test_rogue_shapes.c"));
    empty_scene();
    unsorted_hits();
    out_of_range_first();
    any_hit_outside(ROGUE_ANY_BEYOND);
    any_hit_outside(ROGUE_ANY_NAN);
    overflowing_count(ROGUE_OVERFLOW);
    overflowing_count(ROGUE_SHRINK);
    extreme_normals();
    non_finite_fields();
    composite_bad_leaf();
    hr_context_destroy(ctx);
    return hr_test_end();
}
