/* The sphere's and the cylinder wall's ray equations: the textbook quadratic
 * (Hill, ch. 12: b^2 - a c and (-b +- sqrt) / a, written here as the
 * baseline being compared against) and the modules' stable forms
 * (shapes/sphere/sphere.c, shapes/cylinder/tapered_cylinder.c: Lagrange's
 * identity for the discriminant, compensated sums, the stable root pair),
 * called through the shape module ABI as the library calls them: libhitray
 * finds and loads the module (hr_context_find_shape_class), and the shape
 * is made by its class's create with the defaults of its parameters.
 *
 *   build/bench/accuracy/quadric_forms [--rays=N] [--repeats=N]
 *
 * For each shape (sphere; cylinder, wall only) and each distance 10, 1e2,
 * ..., 1e6 it draws N rays from that far aimed at random points of the
 * shape's bounds (tests/reference/random_rays.c, fixed seed) and prints, per
 * form, one JSON line:
 * - ns: nanoseconds per call over the whole set, the best of `repeats`
 *   passes (a busy machine only slows passes down). The module's figure
 *   covers the call through the ABI and the hit records it fills (point,
 *   normal, error bound), the textbook's only the roots: the difference is
 *   an upper bound on what the stable forms cost;
 * - |t error| against roots computed in __float128 (tests/shapes/
 *   quad_reference.c), over the rays where the form and the reference agree
 *   on the count of wall crossings: worst and 99th percentile, relative to
 *   |t| and in units of u * condition (the error a backward-stable
 *   computation may make);
 * - missed and spurious crossings against the reference, split into rays
 *   clear of any tangency or rim (reference margin > 1e-12) and the rest,
 *   as bench/programs/torus_solvers.c does.
 * It exits non-zero if a module broke the hit contract (a count past the
 * list's room, hits out of order or not finite). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

#include "bench_util.h"
#include "quad_reference.h"
#include "random_rays.h"

#define CLEAR_MARGIN 1e-12
#define SURFACE_WALL 0 /* the tapered cylinder's wall; the sphere's only surface */
#define MAX_HITS 8

/* One shape made by a class that libhitray loaded. */
typedef struct module_shape {
    const hr_shape_class *cls;
    void *shape;
} module_shape;

static int contract_broken;

/* The host services a sphere's or a cylinder's create and hit use: memory
 * for the shape (neither reserves room or traces a child). */
static void *host_alloc(size_t size) { return calloc(1, size); }
static const hr_host host = {
    .struct_size = sizeof(hr_host), .abi_version = HR_SHAPE_ABI_VERSION, .alloc = host_alloc, .free = free};

/* The class `name` as libhitray finds it, made with its defaults. */
static int shape_open(hr_context *ctx, const char *name, module_shape *out)
{
    out->shape = NULL;
    if (hr_context_find_shape_class(ctx, name, &out->cls, NULL) != HR_OK) {
        fprintf(stderr, "quadric_forms: %s\n", hr_context_last_error(ctx));
        return 0;
    }
    hr_param params[16];
    if (out->cls->param_count > 16) return 0;
    memset(params, 0, sizeof params);
    for (int32_t i = 0; i < out->cls->param_count; i++) {
        params[i].name = out->cls->params[i].name;
        params[i].type = out->cls->params[i].type;
        params[i].number = out->cls->params[i].default_number;
        params[i].string = "";
        params[i].object = -1;
    }
    const void *objects[16] = {NULL};
    char error[256] = "";
    hr_create_args args = {.struct_size = sizeof args, .param_count = out->cls->param_count, .params = params,
                           .objects = objects, .host = &host, .error = error, .error_size = sizeof error,
                           .base_dir = ""};
    if (out->cls->create(&args, &out->shape) != HR_OK || !out->shape) {
        fprintf(stderr, "quadric_forms: create %s: %s\n", name, error);
        return 0;
    }
    return 1;
}

static void shape_close(module_shape *s)
{
    if (s->shape) s->cls->destroy(s->shape);
    s->shape = NULL;
}

/* A hit call's arguments for every hit over (0, inf) into `list`, as the
 * library asks for them (the ray to be set). */
static hr_hit_args every_hit(const module_shape *s, hr_intersection *list)
{
    hr_hit_args args;
    memset(&args, 0, sizeof args);
    args.shape = s->shape;
    args.tmin = 0.0;
    args.tmax = INFINITY;
    args.out = list;
    args.struct_size = (uint32_t)sizeof args;
    return args;
}

/* Every hit of the ray, with the contract checked. */
static int shape_hits(const module_shape *s, hr_ray ray, hr_hit hits[MAX_HITS])
{
    hr_intersection list = {hits, 0, MAX_HITS};
    hr_hit_args args = every_hit(s, &list);
    args.ray = ray;
    if (s->cls->hit(&args) != HR_OK || list.count < 0 || list.count > MAX_HITS) {
        contract_broken = 1;
        return 0;
    }
    for (int k = 0; k < list.count; k++)
        if (!(hits[k].t > 0.0 && isfinite(hits[k].t)) || (k && hits[k].t < hits[k - 1].t)) {
            contract_broken = 1;
            return 0;
        }
    return list.count;
}

/* The textbook quadratic for |o + t d|^2 = 1. Returns the roots in t[],
 * sorted. */
__attribute__((noinline)) static int naive_sphere(const hr_ray *ray, double t[2])
{
    const hr_vec3 o = ray->origin, d = ray->dir;
    const double a = d.x * d.x + d.y * d.y + d.z * d.z;
    const double b = o.x * d.x + o.y * d.y + o.z * d.z;
    const double c = o.x * o.x + o.y * o.y + o.z * o.z - 1.0;
    const double disc = b * b - a * c;
    if (disc < 0.0 || a == 0.0) return 0;
    const double root = sqrt(disc);
    t[0] = (-b - root) / a;
    t[1] = (-b + root) / a;
    return 2;
}

/* The textbook quadratic for the wall x^2 + y^2 = 1, 0 <= z <= 1. */
__attribute__((noinline)) static int naive_cylinder_wall(const hr_ray *ray, double t[2])
{
    const hr_vec3 o = ray->origin, d = ray->dir;
    const double a = d.x * d.x + d.y * d.y;
    const double b = o.x * d.x + o.y * d.y;
    const double c = o.x * o.x + o.y * o.y - 1.0;
    const double disc = b * b - a * c;
    if (disc < 0.0 || a == 0.0) return 0;
    const double root = sqrt(disc);
    int n = 0;
    for (int k = 0; k < 2; k++) {
        const double tk = (-b + (k ? root : -root)) / a;
        const double z = o.z + tk * d.z;
        if (z >= 0.0 && z <= 1.0) t[n++] = tk;
    }
    return n;
}

typedef int (*naive_fn)(const hr_ray *ray, double t[2]);

typedef struct shape_case {
    const char *name;     /* the class, as the reference knows it */
    naive_fn naive;
    hr_bounds bounds;
} shape_case;

__attribute__((noinline)) static double time_naive(naive_fn fn, const hr_ray *rays, int count)
{
    volatile int sink = 0;
    double t[2];
    const double start = bench_now_ns();
    for (int i = 0; i < count; i++) sink += fn(&rays[i], t);
    (void)sink;
    return (bench_now_ns() - start) / count;
}

/* The module's hit function (every hit, over (0, inf)) as the host calls
 * it, with the list emptied before each call. */
__attribute__((noinline)) static double time_module(const module_shape *shape,
                                                    const hr_ray *rays, int count)
{
    hr_hit storage[HR_MIN_HIT_CAPACITY];
    hr_intersection list = {storage, 0, HR_MIN_HIT_CAPACITY};
    hr_hit_args args = every_hit(shape, &list);
    volatile int sink = 0;
    const double start = bench_now_ns();
    for (int i = 0; i < count; i++) {
        list.count = 0;
        args.ray = rays[i];
        shape->cls->hit(&args);
        sink += list.count;
    }
    (void)sink;
    return (bench_now_ns() - start) / count;
}

/* The reference's wall crossings with t > 0 (what both forms report). */
static int reference_wall(const ref_trace *r, const ref_hit *out[8])
{
    int n = 0;
    for (int k = 0; k < r->count; k++)
        if (r->hits[k].surface == SURFACE_WALL && r->hits[k].t > 0) out[n++] = &r->hits[k];
    return n;
}

typedef struct tally {
    bench_errors errors;
    int missed_clear, spurious_clear, missed_near, spurious_near;
} tally;

static void tally_ray(tally *y, const ref_trace *r, const double *t, int n)
{
    const ref_hit *want[8];
    const int m = reference_wall(r, want);
    const int clear = r->margin > CLEAR_MARGIN;
    if (n < m) *(clear ? &y->missed_clear : &y->missed_near) += m - n;
    if (n > m) *(clear ? &y->spurious_clear : &y->spurious_near) += n - m;
    if (n != m) return;
    for (int k = 0; k < n; k++)
        bench_errors_add(&y->errors, fabs(ref_to_double((quad)t[k] - want[k]->t)), t[k],
                         ref_to_double(want[k]->condition));
}

static void print_row(const shape_case *sc, const char *form, double distance, int count,
                      int repeats, double ns, tally *y)
{
    const bench_error_summary e = bench_errors_summarise(&y->errors);
    printf("{\"shape\": \"%s\", \"form\": \"%s\", \"distance\": %g, \"rays\": %d, "
           "\"repeats\": %d, \"ns\": %.1f, \"roots\": %d, ",
           sc->name, form, distance, count, repeats, ns, y->errors.count);
    bench_print_error_members(&e);
    printf(", \"missed_clear\": %d, \"spurious_clear\": %d, \"missed_tangent\": %d, "
           "\"spurious_tangent\": %d}\n",
           y->missed_clear, y->spurious_clear, y->missed_near, y->spurious_near);
    fflush(stdout);
}

static void run_case(hr_context *ctx, const shape_case *sc, double distance, int count, int repeats)
{
    module_shape shape;
    if (!shape_open(ctx, sc->name, &shape)) exit(1);
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0x9ad71c) + (uint64_t)log10(distance));
    hr_ray *rays = bench_checked(malloc((size_t)count * sizeof *rays));
    ref_trace *refs = bench_checked(malloc((size_t)count * sizeof *refs));
    const ref_shape ref = ref_shape_of(sc->name, 1.0, NAN);
    for (int i = 0; i < count; i++) {
        rays[i] = random_ray_far(&rng, &sc->bounds, distance);
        ref_trace_ray(ref, rays[i], &refs[i]);
    }

    double ns_naive = INFINITY, ns_module = INFINITY;
    for (int rep = 0; rep < repeats; rep++) {
        ns_naive = fmin(ns_naive, time_naive(sc->naive, rays, count));
        ns_module = fmin(ns_module, time_module(&shape, rays, count));
    }

    tally naive = {0}, stable = {0};
    bench_errors_init(&naive.errors, 2 * count);
    bench_errors_init(&stable.errors, 2 * count);
    for (int i = 0; i < count; i++) {
        double t[MAX_HITS];
        int n = sc->naive(&rays[i], t);
        tally_ray(&naive, &refs[i], t, n);
        hr_hit hits[MAX_HITS];
        const int h = shape_hits(&shape, rays[i], hits);
        n = 0;
        for (int k = 0; k < h; k++)
            if (hits[k].surface == SURFACE_WALL) t[n++] = hits[k].t;
        tally_ray(&stable, &refs[i], t, n);
    }
    print_row(sc, "textbook", distance, count, repeats, ns_naive, &naive);
    print_row(sc, "stable (module)", distance, count, repeats, ns_module, &stable);
    bench_errors_free(&naive.errors);
    bench_errors_free(&stable.errors);
    free(rays);
    free(refs);
    shape_close(&shape);
}

int main(int argc, char **argv)
{
    int count = 20000, repeats = 5;
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (bench_option(argv[i], "--rays", &v)) count = atoi(v);
        else if (bench_option(argv[i], "--repeats", &v)) repeats = atoi(v);
        else count = 0;
    }
    if (count <= 0 || repeats <= 0) {
        fprintf(stderr, "usage: quadric_forms [--rays=N] [--repeats=N]\n");
        return 2;
    }
    static const shape_case cases[] = {
        {"sphere", naive_sphere, {{-1, -1, -1}, {1, 1, 1}}},
        {"cylinder", naive_cylinder_wall, {{-1, -1, 0}, {1, 1, 1}}},
    };
    hr_context *ctx;
    if (hr_context_create(&ctx) != HR_OK) return 1;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
        for (double distance = 10; distance <= 1e6; distance *= 10)
            run_case(ctx, &cases[c], distance, count, repeats);
    hr_context_destroy(ctx);
    if (contract_broken) fprintf(stderr, "quadric_forms: a module broke the hit contract\n");
    return contract_broken;
}
