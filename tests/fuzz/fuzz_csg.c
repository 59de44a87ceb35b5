/* Fuzz harness: CSG trees (shapes/csg) built from the input through the
 * library, as a program builds them: leaves added with hr_scene_add_object,
 * each under its own translate-and-scale transform, then booleans whose
 * HR_PARAM_OBJECT parameters `a` and `b` name them, nested up to
 * MAX_DEPTH. The leaves are the built-in solids whose inside the harness
 * can tell exactly (sphere, cube, cylinder, cone, taperedCylinder, torus,
 * octahedron), and now and then an open surface (plane, square), which the
 * boolean must refuse with HR_ERROR_PARAMETER and a message.
 *
 * Offsets and scales are mostly multiples of 1/8 (but the octahedron's, see
 * add_leaf), so faces coincide and rays run along them and through edges
 * often: the cases csg_combine.c groups by error bound. Each committed
 * scene is traced along rays from the input with Hill's queries, checking:
 * - hr_scene_all_hits: hits finite, strictly inside (tmin, tmax), sorted,
 *   entering and exiting alternately (the result is a solid), entered
 *   first when the ray starts outside and left last (every leaf is
 *   bounded);
 * - hr_scene_first_hit: the first of all hits;
 * - over a sub-interval (t1, t2) of the ray whose ends lie in gaps between
 *   hits (gaps wider than rounding), exactly the whole ray's hits that lie
 *   inside it (docs/csg.md promises it: operands are traced past tmax);
 * - against a brute-force classification: at sample points along the ray
 *   (the midpoints between result hits, and a regular grid of t), the
 *   tree's inside/outside, evaluated in long double from each leaf's own
 *   distance-like implicit function, must match what the hits say, wherever
 *   the point is clearly (CLEARANCE) inside or outside. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "fuzz_input.h"

#define MAX_DEPTH 6
#define MAX_NODES 64
/* Distance (leaf units, scales are >= 1/4) from every leaf surface beyond
 * which a point's side is certain: far above the rounding of the hits and
 * of the implicit functions, far below any feature size the input makes. */
#define CLEARANCE 1e-6L
#define GRID_SAMPLES 48

enum { LEAF_SPHERE, LEAF_CUBE, LEAF_CYLINDER, LEAF_CONE, LEAF_TAPERED, LEAF_TORUS,
       LEAF_OCTAHEDRON, LEAF_PLANE, LEAF_SQUARE, LEAF_COUNT };
static const char *const leaf_names[LEAF_COUNT] = {
    "sphere", "cube", "cylinder", "cone", "taperedCylinder", "torus", "octahedron", "plane",
    "square"};
static const char *const op_names[3] = {"union", "intersection", "difference"};

typedef struct node {
    int op;           /* -1: a leaf; else 0 union, 1 intersection, 2 difference */
    int a, b;         /* children (node indices) */
    int leaf;         /* LEAF_* */
    double param;     /* s or tube */
    double offset[3], scale[3];
    int64_t index;    /* the object in the scene */
} node;

typedef struct tree {
    node nodes[MAX_NODES];
    int count;
    hr_scene *scene;
    int refused; /* a boolean refused an operand (as it must an open one) */
} tree;

static hr_context *ctx;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    if (hr_context_create(&ctx) != HR_OK) fuzz_fail("csg: no context");
    hr_context_module_count(ctx); /* every module loaded before fuzzing starts */
    return 0;
}

/* Mostly multiples of 1/8 in [lo, hi] (coincidences), sometimes any. */
static double grid_or_any(fuzz_input *in, double lo, double hi)
{
    if (fuzz_choice(in, 4) == 0) return fuzz_double_in(in, lo, hi);
    const double steps = (hi - lo) * 8;
    return lo + fuzz_choice(in, (unsigned)steps + 1) / 8.0;
}

static int add_leaf(fuzz_input *in, tree *t, node *n)
{
    n->op = -1;
    n->leaf = (int)fuzz_choice(in, LEAF_COUNT);
    /* Open surfaces rarely: each one ends the tree. */
    if (n->leaf >= LEAF_PLANE && fuzz_choice(in, 4) != 0) n->leaf = LEAF_SPHERE;
    hr_param param = {.name = NULL, .type = HR_PARAM_NUMBER, .number = 0.0, .string = NULL, .object = 0};
    if (n->leaf == LEAF_TAPERED) {
        param.name = "s";
        n->param = param.number = grid_or_any(in, 0.0, 3.0);
    } else if (n->leaf == LEAF_TORUS) {
        param.name = "tube";
        n->param = param.number = 0.125 + grid_or_any(in, 0.0, 0.75);
    }
    /* The octahedron off the grid: its faces x +- y +- z = 1 then never
     * hold a grid ray, not even within rounding. A ray that lies within
     * rounding of a face's plane crosses that face's triangle seen nearly
     * edge on, whose t error bound (mesh_t_error) is then larger than t
     * itself: the mesh refuses the crossing as maybe lying before tmin,
     * keeps its pair, and the boolean above it is left inside for ever.
     * That limit is the mesh module's, not the booleans'. */
    const int grid = n->leaf != LEAF_OCTAHEDRON;
    for (int k = 0; k < 3; k++)
        n->offset[k] = grid ? grid_or_any(in, -2.0, 2.0) : fuzz_double_in(in, -2.0, 2.0);
    for (int k = 0; k < 3; k++)
        n->scale[k] = 0.25 + (grid ? grid_or_any(in, 0.0, 1.75) : fuzz_double_in(in, 0.0, 1.75));
    const double m[16] = {n->scale[0], 0, 0, n->offset[0], 0, n->scale[1], 0, n->offset[1],
                          0, 0, n->scale[2], n->offset[2], 0, 0, 0, 1};
    hr_object_desc desc = {.struct_size = sizeof desc};
    desc.shape = leaf_names[n->leaf];
    desc.params = param.name ? &param : NULL;
    desc.param_count = param.name ? 1 : 0;
    desc.transform = m;
    const hr_status st = hr_scene_add_object(t->scene, &desc, &n->index);
    if (st) fuzz_fail("csg: adding a %s failed: %s", desc.shape, hr_context_last_error(ctx));
    return 1;
}

/* Builds a node from the input; returns its index, -1 when the tree ended
 * (a refused operand). `root` forces a boolean. */
static int build(fuzz_input *in, tree *t, int depth, int root)
{
    if (t->count >= MAX_NODES) fuzz_fail("csg: the tree outgrew its %d nodes", MAX_NODES);
    const int me = t->count++;
    node *n = &t->nodes[me];
    const unsigned kind = fuzz_choice(in, 5);
    /* A boolean needs two more nodes, and each of the at most MAX_DEPTH
     * booleans above it still one for its second operand. */
    if (!root && (depth >= MAX_DEPTH || t->count + 2 + MAX_DEPTH > MAX_NODES || kind >= 3))
        return add_leaf(in, t, n) ? me : -1;
    n->op = (int)(kind % 3);
    const int a = build(in, t, depth + 1, 0);
    if (a < 0) return -1;
    const int b = build(in, t, depth + 1, 0);
    if (b < 0) return -1;
    n = &t->nodes[me];
    n->a = a;
    n->b = b;
    const hr_param params[2] = {{.name = "a", .type = HR_PARAM_OBJECT, .number = 0.0, .string = NULL, .object = t->nodes[a].index},
                                {.name = "b", .type = HR_PARAM_OBJECT, .number = 0.0, .string = NULL, .object = t->nodes[b].index}};
    hr_object_desc desc = {.struct_size = sizeof desc};
    desc.shape = op_names[n->op];
    desc.params = params;
    desc.param_count = 2;
    const hr_status st = hr_scene_add_object(t->scene, &desc, &n->index);
    const int open = (t->nodes[a].op < 0 && t->nodes[a].leaf >= LEAF_PLANE) ||
                     (t->nodes[b].op < 0 && t->nodes[b].leaf >= LEAF_PLANE);
    if (st == HR_OK && open) fuzz_fail("csg: a %s of an open surface was accepted", desc.shape);
    if (st == HR_OK) return me;
    if (!open) fuzz_fail("csg: a %s was refused: %s", desc.shape, hr_context_last_error(ctx));
    if (st != HR_ERROR_PARAMETER || !strstr(hr_context_last_error(ctx), "not a solid"))
        fuzz_fail("csg: an open operand refused with status %d: %s", (int)st,
                  hr_context_last_error(ctx));
    t->refused = 1;
    return -1;
}

/* --- The brute-force classification ----------------------------------------- */

typedef long double real;

static real leaf_clearance(const node *n, const real p[3])
{
    real q[3];
    for (int k = 0; k < 3; k++) q[k] = (p[k] - n->offset[k]) / n->scale[k];
    const real rho = sqrtl(q[0] * q[0] + q[1] * q[1]);
    switch (n->leaf) {
    case LEAF_SPHERE: return sqrtl(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - 1;
    case LEAF_CUBE: return fmaxl(fabsl(q[0]), fmaxl(fabsl(q[1]), fabsl(q[2]))) - 1;
    case LEAF_TORUS: return sqrtl((rho - 1) * (rho - 1) + q[2] * q[2]) - n->param;
    case LEAF_OCTAHEDRON: return (fabsl(q[0]) + fabsl(q[1]) + fabsl(q[2]) - 1) / sqrtl(3);
    default: { /* the tapered family: the slab 0 <= z <= 1 and the wall */
        const real s = n->leaf == LEAF_CYLINDER ? 1 : n->leaf == LEAF_CONE ? 0 : n->param;
        const real k = s - 1;
        const real wall = (rho - (1 + k * q[2])) / sqrtl(1 + k * k);
        return fmaxl(fmaxl(-q[2], q[2] - 1), wall);
    }
    }
}

/* Negative inside, positive outside; its magnitude is at most the
 * distance-like clearance of the leaves that decide. */
static real clearance(const tree *t, int i, const real p[3])
{
    const node *n = &t->nodes[i];
    if (n->op < 0) return leaf_clearance(n, p);
    const real a = clearance(t, n->a, p), b = clearance(t, n->b, p);
    switch (n->op) {
    case 0: return fminl(a, b);
    case 1: return fmaxl(a, b);
    default: return fmaxl(a, -b);
    }
}

/* --- Tracing ------------------------------------------------------------------ */

#define RAY_FMT "csg: ray (%a, %a, %a) + t (%a, %a, %a): "
#define RAY_ARGS(r) (r).origin.x, (r).origin.y, (r).origin.z, (r).dir.x, (r).dir.y, (r).dir.z

static void all_hits(const tree *t, const hr_ray *ray, double tmin, double tmax,
                     hr_intersection *out)
{
    out->count = 0;
    if (hr_scene_all_hits(t->scene, ray, tmin, tmax, out) != HR_OK)
        fuzz_fail(RAY_FMT "all hits failed: %s", RAY_ARGS(*ray), hr_context_last_error(ctx));
    for (int32_t i = 0; i < out->count; i++) {
        const hr_hit *h = &out->hits[i];
        if (!(isfinite(h->t) && isfinite(h->point.x) && isfinite(h->point.y) &&
              isfinite(h->point.z) && isfinite(h->normal.x) && isfinite(h->normal.y) &&
              isfinite(h->normal.z) && isfinite(h->error)))
            fuzz_fail(RAY_FMT "hit %d has a non-finite field", RAY_ARGS(*ray), (int)i);
        if (!(h->t > tmin && h->t < tmax))
            fuzz_fail(RAY_FMT "hit %d at t = %a is outside (%a, %a)", RAY_ARGS(*ray), (int)i,
                      h->t, tmin, tmax);
        if (i > 0 && !(h[-1].t <= h->t))
            fuzz_fail(RAY_FMT "hits %d, %d unsorted", RAY_ARGS(*ray), (int)i - 1, (int)i);
        if (i > 0 && h[-1].entering == h->entering)
            fuzz_fail(RAY_FMT "hits %d, %d at t = %a, %a do not alternate", RAY_ARGS(*ray),
                      (int)i - 1, (int)i, h[-1].t, h->t);
    }
}

/* Whether the hits say the ray is inside at t (not a hit's own t). */
static int inside_at(const hr_intersection *hits, double t)
{
    int32_t after = 0;
    while (after < hits->count && hits->hits[after].t < t) after++;
    if (after > 0) return hits->hits[after - 1].entering != 0;
    return after < hits->count ? hits->hits[after].entering == 0 : 0;
}

static void classify(const tree *t, const hr_ray *ray, const hr_intersection *hits, double at)
{
    const real p[3] = {(real)ray->origin.x + (real)at * ray->dir.x,
                       (real)ray->origin.y + (real)at * ray->dir.y,
                       (real)ray->origin.z + (real)at * ray->dir.z};
    const real c = clearance(t, 0, p);
    if (fabsl(c) <= CLEARANCE) return;
    const int truth = c < 0, said = inside_at(hits, at);
    if (truth != said)
        fuzz_fail(RAY_FMT "at t = %a the point is %s by %.3Lg, the %d hits say %s",
                  RAY_ARGS(*ray), at, truth ? "inside" : "outside", fabsl(c), (int)hits->count,
                  said ? "inside" : "outside");
}

/* A point of the gap (a, b) off the grid the input's values lie on: the
 * midpoint of two grid times is a grid time, where an operand's surface may
 * well be (a ray starting on it is classified by where the operand goes
 * next, docs/csg.md, and may rightly differ from the whole ray there). */
static double between(double a, double b)
{
    return a + (b - a) * 0.41421356237309503;
}

static int wide_gap(const hr_ray *ray, const hr_hit *a, const hr_hit *b)
{
    const double speed = fmax(fabs(ray->dir.x), fmax(fabs(ray->dir.y), fabs(ray->dir.z)));
    return (b->t - a->t) * speed > 1e-9 * (1 + fabs(b->t) * speed);
}

static void check_ray(const tree *t, const hr_ray *ray, fuzz_input *in, hr_intersection *whole,
                      hr_intersection *part)
{
    all_hits(t, ray, 0.0, INFINITY, whole);
    const real o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    const real c0 = clearance(t, 0, o);
    if (whole->count > 0 && fabsl(c0) > CLEARANCE &&
        (whole->hits[0].entering != (c0 > 0) || whole->hits[whole->count - 1].entering))
        fuzz_fail(RAY_FMT "from %s, %d hits: the first %s, the last %s", RAY_ARGS(*ray),
                  c0 > 0 ? "outside" : "inside", (int)whole->count,
                  whole->hits[0].entering ? "entering" : "exiting",
                  whole->hits[whole->count - 1].entering ? "entering" : "exiting");
    hr_hit first;
    int32_t found = 0;
    if (hr_scene_first_hit(t->scene, ray, 0.0, INFINITY, &first, &found) != HR_OK)
        fuzz_fail(RAY_FMT "first hit failed: %s", RAY_ARGS(*ray), hr_context_last_error(ctx));
    if (found != (whole->count > 0) ||
        (found && (first.t != whole->hits[0].t || first.entering != whole->hits[0].entering ||
                   first.object != whole->hits[0].object)))
        fuzz_fail(RAY_FMT "first hit found %d t %a, all hits %d, the first at t %a",
                  RAY_ARGS(*ray), (int)found, found ? first.t : 0.0, (int)whole->count,
                  whole->count ? whole->hits[0].t : 0.0);
    /* Midpoints between hits, and a grid over where the tree can be. */
    for (int32_t i = 0; i + 1 < whole->count; i++)
        classify(t, ray, whole, 0.5 * whole->hits[i].t + 0.5 * whole->hits[i + 1].t);
    if (whole->count > 0) classify(t, ray, whole, whole->hits[whole->count - 1].t * 1.5 + 1);
    const double speed = fmax(fabs(ray->dir.x), fmax(fabs(ray->dir.y), fabs(ray->dir.z)));
    const double reach = 16.0 / speed;
    for (int k = 1; k <= GRID_SAMPLES; k++) classify(t, ray, whole, reach * k / GRID_SAMPLES);
    /* A sub-interval whose ends lie between hits of the whole ray (a point
     * of the gap before hit i1, or 0; of the one after hit i2, or infinity):
     * the hits inside it and no others. Not an end at a hit itself: a ray
     * starting on a boundary is classified by where each operand goes next
     * (docs/csg.md), so where two operands' faces coincide within their
     * error bounds, one of them a rounding after tmin, the result may
     * rightly enter there although the whole ray merged the two. */
    if (whole->count == 0) return;
    const int32_t count = whole->count < 256 ? whole->count : 256;
    const int32_t i1 = (int32_t)fuzz_choice(in, (unsigned)count);
    const int32_t i2 = i1 + (int32_t)fuzz_choice(in, (unsigned)(count - i1));
    /* Only gaps far wider than rounding (1e-9 relative): inside a sliver a
     * few ulps wide, the operands' hits on either side of the end are one
     * coincident group, which an end between them splits. */
    if ((i1 > 0 && !wide_gap(ray, &whole->hits[i1 - 1], &whole->hits[i1])) ||
        (i2 + 1 < count && !wide_gap(ray, &whole->hits[i2], &whole->hits[i2 + 1])))
        return;
    const double t1 = i1 == 0 ? 0.0 : between(whole->hits[i1 - 1].t, whole->hits[i1].t);
    const double t2 =
        i2 + 1 >= count ? INFINITY : between(whole->hits[i2].t, whole->hits[i2 + 1].t);
    all_hits(t, ray, t1, t2, part);
    int32_t expect = 0;
    for (int32_t i = 0; i < whole->count; i++) {
        const hr_hit *h = &whole->hits[i];
        if (!(h->t > t1 && h->t < t2)) continue;
        if (expect >= part->count || part->hits[expect].t != h->t ||
            part->hits[expect].entering != h->entering)
            fuzz_fail(RAY_FMT "over (%a, %a): hit %d of the whole ray at t = %a is not there "
                              "(%d hits there)",
                      RAY_ARGS(*ray), t1, t2, (int)i, h->t, (int)part->count);
        expect++;
    }
    if (expect != part->count)
        fuzz_fail(RAY_FMT "over (%a, %a): %d hits, the whole ray has %d there", RAY_ARGS(*ray),
                  t1, t2, (int)part->count, (int)expect);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in = fuzz_input_make(data, size);
    static tree t; /* large; one input at a time */
    memset(&t, 0, sizeof t);
    if (hr_scene_create(ctx, &t.scene) != HR_OK) fuzz_fail("csg: no scene");
    const int root = build(&in, &t, 0, 1);
    if (root < 0) {
        if (!t.refused) fuzz_fail("csg: the tree ended without a refusal");
        hr_scene_destroy(t.scene);
        return 0;
    }
    if (hr_scene_commit(t.scene) != HR_OK)
        fuzz_fail("csg: commit failed: %s", hr_context_last_error(ctx));
    hr_intersection whole, part;
    hr_intersection_init(&whole);
    hr_intersection_init(&part);
    for (int r = 0; r < 4 && (r == 0 || fuzz_more(&in)); r++) {
        hr_ray ray;
        ray.origin.x = grid_or_any(&in, -4.0, 4.0);
        ray.origin.y = grid_or_any(&in, -4.0, 4.0);
        ray.origin.z = grid_or_any(&in, -4.0, 4.0);
        ray.dir.x = grid_or_any(&in, -1.0, 1.0);
        ray.dir.y = grid_or_any(&in, -1.0, 1.0);
        ray.dir.z = grid_or_any(&in, -1.0, 1.0);
        if (ray.dir.x == 0 && ray.dir.y == 0 && ray.dir.z == 0) ray.dir.z = 1;
        check_ray(&t, &ray, &in, &whole, &part);
    }
    hr_intersection_release(&whole);
    hr_intersection_release(&part);
    hr_scene_destroy(t.scene);
    return 0;
}
