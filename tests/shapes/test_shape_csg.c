/* The CSG module (shapes/csg): union, intersection and difference through
 * the harness's host, whose trace_child traces harness shapes placed by an
 * offset and a scale (module_harness.h).
 *
 * - The truth table of entering/exiting for the three operations over two
 *   unit spheres centred at z = 0 and z = 0.5, along z from outside, from
 *   inside both and the other way; times exact in closed form.
 * - A difference whose hole shows the inside of the subtracted sphere: the
 *   hit is the small sphere's, with its normal flipped towards the viewer.
 * - Coincident faces (cubes sharing a face, with exact and inexact
 *   placements), tangent rays and rays starting on a boundary: the
 *   documented answers, the same from hit, first_hit and any_hit.
 * - Three levels of nesting and random rays against a brute-force
 *   classification in long double: every leaf's roots sorted, the tree
 *   evaluated at the midpoints between them; over random intervals, exactly
 *   the whole ray's hits that lie inside them.
 * - More hits than HR_MIN_HIT_CAPACITY, open children refused by name,
 *   bounds, an unbounded solid child. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"
#include "module_harness.h"
#include "random_rays.h"

static harness_module csg_module;
static const hr_shape_class *union_cls, *intersection_cls, *difference_cls;
static harness_shape sphere, cube, plane;

/* --- Tracing with the contract checked ----------------------------------------- */

#define EARLIER 2
#define MAX_RESULT 256

typedef struct result {
    hr_hit hits[MAX_RESULT];
    int count;
} result;

/* Calls the class's hit function for `mode` with exactly the promised free
 * space (so AddressSanitizer sees a write past it), then checks: HR_OK, the
 * earlier hits untouched, t strictly inside (tmin, tmax) and strictly
 * increasing, finite fields, a non-zero normal, entering flags alternating
 * (a boolean of solids is a solid), at most one hit from a fast path. */
static void trace(const harness_shape *s, hr_ray ray, double tmin, double tmax, int32_t mode,
                  result *r)
{
    hr_intersection list;
    list.capacity = EARLIER + HR_MIN_HIT_CAPACITY;
    list.hits = calloc((size_t)list.capacity, sizeof *list.hits);
    list.count = EARLIER;
    for (int i = 0; i < EARLIER; i++) list.hits[i].t = -1.0 - i;
    hr_hit_args args;
    memset(&args, 0, sizeof args);
    args.shape = s->shape;
    args.ray = ray;
    args.tmin = tmin;
    args.tmax = tmax;
    args.out = &list;
    hr_hit_fn fn = mode == HARNESS_ALL ? s->cls->hit : mode == HARNESS_FIRST ? s->cls->first_hit
                                                                             : s->cls->any_hit;
    CHECK_OK(fn(&args));
    r->count = list.count - EARLIER;
    CHECK_MSG(r->count >= 0 && r->count <= MAX_RESULT, "count %d", r->count);
    if (r->count < 0) r->count = 0;
    if (r->count > MAX_RESULT) r->count = MAX_RESULT;
    CHECK(mode == HARNESS_ALL || r->count <= 1);
    for (int i = 0; i < EARLIER; i++) CHECK(list.hits[i].t == -1.0 - i);
    memcpy(r->hits, list.hits + EARLIER, (size_t)r->count * sizeof *r->hits);
    free(list.hits);
    for (int i = 0; i < r->count; i++) {
        const hr_hit *h = &r->hits[i];
        CHECK_MSG(h->t > tmin && h->t < tmax, "hit %d at t = %.17g outside (%g, %g)", i, h->t,
                  tmin, tmax);
        CHECK_MSG(i == 0 || h[-1].t < h->t, "hits %d, %d not strictly increasing", i - 1, i);
        CHECK(isfinite(h->point.x) && isfinite(h->point.y) && isfinite(h->point.z) &&
              isfinite(h->normal.x) && isfinite(h->normal.y) && isfinite(h->normal.z) &&
              isfinite(h->error));
        CHECK(h->normal.x != 0 || h->normal.y != 0 || h->normal.z != 0);
        if (mode == HARNESS_ALL && i > 0)
            CHECK_MSG(h->entering != h[-1].entering, "hits %d, %d do not alternate", i - 1, i);
    }
}

/* hit over (tmin, tmax), and first_hit and any_hit agreeing with it. */
static void trace_all(const harness_shape *s, hr_ray ray, double tmin, double tmax, result *r)
{
    trace(s, ray, tmin, tmax, HARNESS_ALL, r);
    result first, any;
    trace(s, ray, tmin, tmax, HARNESS_FIRST, &first);
    trace(s, ray, tmin, tmax, HARNESS_ANY, &any);
    CHECK_MSG(first.count == (r->count > 0), "first_hit found %d, hit %d", first.count, r->count);
    CHECK_MSG(any.count == (r->count > 0), "any_hit found %d, hit %d", any.count, r->count);
    if (first.count == 1 && r->count > 0)
        CHECK(memcmp(&first.hits[0], &r->hits[0], sizeof(hr_hit)) == 0);
    if (any.count == 1 && r->count > 0) CHECK(any.hits[0].t > tmin && any.hits[0].t < tmax);
}

/* --- Building booleans ------------------------------------------------------------- */

static harness_child place(const harness_shape *s, double x, double y, double z, double scale,
                           int64_t object)
{
    harness_child c = {s, harness_vec(x, y, z), scale, object};
    return c;
}

static harness_shape boolean(const hr_shape_class *cls, const harness_child *a,
                             const harness_child *b)
{
    harness_shape s;
    memset(&s, 0, sizeof s);
    s.cls = cls;
    const char *names[] = {"a", "b"};
    const harness_child *children[] = {a, b};
    char error[256];
    hr_status st = harness_create_composite(cls, names, children, 2, &s.shape, error, sizeof error);
    CHECK_MSG(st == HR_OK && s.shape, "create %s: %d %s", cls->name, (int)st, error);
    return s;
}

static void destroy(harness_shape *s)
{
    if (s->shape) s->cls->destroy(s->shape);
    s->shape = NULL;
}

/* --- Expected hits ------------------------------------------------------------------ */

typedef struct expected {
    double t;
    int64_t object;
    int entering;
    double nz; /* the unit normal's z (rays along z meet the spheres where
                  the normal is +-z); NAN: not checked */
} expected;

static void expect(const char *what, const result *r, const expected *e, int n)
{
    CHECK_MSG(r->count == n, "%s: %d hits, expected %d", what, r->count, n);
    for (int i = 0; i < n && i < r->count; i++) {
        const hr_hit *h = &r->hits[i];
        /* Exact in closed form; the sphere's stable roots are within a few ulps. */
        CHECK_MSG(hr_test_ulps(h->t, e[i].t) <= 4, "%s hit %d: t = %.17g, expected %.17g", what,
                  i, h->t, e[i].t);
        CHECK_MSG(h->object == e[i].object, "%s hit %d: object %lld, expected %lld", what, i,
                  (long long)h->object, (long long)e[i].object);
        CHECK_MSG(h->entering == e[i].entering, "%s hit %d: entering %d", what, i,
                  (int)h->entering);
        const double len = sqrt(h->normal.x * h->normal.x + h->normal.y * h->normal.y +
                                h->normal.z * h->normal.z);
        /* On the z axis the spheres' normals are exactly +-z. */
        CHECK_MSG(isnan(e[i].nz) || fabs(h->normal.z / len - e[i].nz) <= 1e-15,
                  "%s hit %d: normal (%g, %g, %g), expected z %g", what, i, h->normal.x,
                  h->normal.y, h->normal.z, e[i].nz);
    }
}

/* --- The truth table ---------------------------------------------------------------- */

static void test_truth_table(void)
{
    /* A: unit sphere at z = 0 (object 10); B: unit sphere at z = 0.5 (object 11). */
    harness_child a = place(&sphere, 0, 0, 0, 1, 10), b = place(&sphere, 0, 0, 0.5, 1, 11);
    harness_shape u = boolean(union_cls, &a, &b), in = boolean(intersection_cls, &a, &b);
    harness_shape ab = boolean(difference_cls, &a, &b), ba = boolean(difference_cls, &b, &a);
    result r;

    /* Up the z axis from z = -5: A spans t in [4, 6], B [4.5, 6.5]. */
    const hr_ray up = harness_ray(0, 0, -5, 0, 0, 1);
    trace_all(&u, up, 0, INFINITY, &r);
    expect("union, up", &r, (expected[]){{4, 10, 1, -1}, {6.5, 11, 0, 1}}, 2);
    trace_all(&in, up, 0, INFINITY, &r);
    expect("intersection, up", &r, (expected[]){{4.5, 11, 1, -1}, {6, 10, 0, 1}}, 2);
    /* A - B: leaves where it enters B; B's normal there (-z) is flipped. */
    trace_all(&ab, up, 0, INFINITY, &r);
    expect("A - B, up", &r, (expected[]){{4, 10, 1, -1}, {4.5, 11, 0, 1}}, 2);
    /* B - A: enters where it leaves A; A's normal (+z) is flipped. */
    trace_all(&ba, up, 0, INFINITY, &r);
    expect("B - A, up", &r, (expected[]){{6, 10, 1, -1}, {6.5, 11, 0, 1}}, 2);

    /* Down the z axis from z = 5: A spans [4, 6], B [3.5, 5.5]. */
    const hr_ray down = harness_ray(0, 0, 5, 0, 0, -1);
    trace_all(&u, down, 0, INFINITY, &r);
    expect("union, down", &r, (expected[]){{3.5, 11, 1, 1}, {6, 10, 0, -1}}, 2);
    trace_all(&in, down, 0, INFINITY, &r);
    expect("intersection, down", &r, (expected[]){{4, 10, 1, 1}, {5.5, 11, 0, -1}}, 2);
    trace_all(&ab, down, 0, INFINITY, &r);
    expect("A - B, down", &r, (expected[]){{5.5, 11, 1, 1}, {6, 10, 0, -1}}, 2);
    trace_all(&ba, down, 0, INFINITY, &r);
    expect("B - A, down", &r, (expected[]){{3.5, 11, 1, 1}, {4, 10, 0, -1}}, 2);

    /* From z = 0.25, inside both, going up: A left at t = 0.75, B at 1.25. */
    const hr_ray inside = harness_ray(0, 0, 0.25, 0, 0, 1);
    trace_all(&u, inside, 0, INFINITY, &r);
    expect("union, from inside", &r, (expected[]){{1.25, 11, 0, 1}}, 1);
    trace_all(&in, inside, 0, INFINITY, &r);
    expect("intersection, from inside", &r, (expected[]){{0.75, 10, 0, 1}}, 1);
    trace_all(&ab, inside, 0, INFINITY, &r);
    expect("A - B, from inside", &r, NULL, 0);
    trace_all(&ba, inside, 0, INFINITY, &r);
    expect("B - A, from inside", &r, (expected[]){{0.75, 10, 1, -1}, {1.25, 11, 0, 1}}, 2);

    /* A finite interval shows the part of the whole answer inside it. */
    trace_all(&u, up, 4.25, 6.25, &r);
    expect("union over (4.25, 6.25)", &r, NULL, 0);
    trace_all(&u, up, 0, 5, &r);
    expect("union over (0, 5)", &r, (expected[]){{4, 10, 1, -1}}, 1);
    trace_all(&ab, up, 4.25, 100, &r);
    expect("A - B over (4.25, 100)", &r, (expected[]){{4.5, 11, 0, 1}}, 1);
    trace_all(&in, up, 5, 100, &r);
    expect("intersection over (5, 100)", &r, (expected[]){{6, 10, 0, 1}}, 1);

    /* A ray that misses both. */
    trace_all(&u, harness_ray(3, 0, -5, 0, 0, 1), 0, INFINITY, &r);
    expect("union, miss", &r, NULL, 0);
    destroy(&u), destroy(&in), destroy(&ab), destroy(&ba);
}

/* --- The hole of a difference -------------------------------------------------------- */

static void test_difference_hole(void)
{
    /* A unit sphere (object 1) minus a sphere of radius 0.5 at z = 1 (object 2). */
    harness_child big = place(&sphere, 0, 0, 0, 1, 1), bite = place(&sphere, 0, 0, 1, 0.5, 2);
    harness_shape d = boolean(difference_cls, &big, &bite);
    result r;
    /* Looking down the axis from z = 5: the top of the big sphere (z = 1) is
     * inside the bite, so the first thing seen is the bottom of the bite at
     * z = 0.5, from inside the bite: its normal (-z) flipped to face the eye. */
    trace_all(&d, harness_ray(0, 0, 5, 0, 0, -1), 0, INFINITY, &r);
    expect("hole", &r, (expected[]){{4.5, 2, 1, 1}, {6, 1, 0, -1}}, 2);
    if (r.count > 0) {
        CHECK_NEAR(r.hits[0].point.z, 0.5, 1e-15);
        /* The flipped normal faces the ray: it is what shading sees. */
        CHECK(r.hits[0].normal.z > 0);
    }
    /* Off the axis, through the rim of the hole: the bite's surface at
     * x = 0.3 is at z = 1 - sqrt(0.25 - 0.09) = 0.6; the big sphere's top at
     * sqrt(1 - 0.09), inside the bite (its z < 1 + 0.4). */
    trace_all(&d, harness_ray(0.3, 0, 5, 0, 0, -1), 0, INFINITY, &r);
    CHECK(r.count == 2);
    if (r.count == 2) {
        CHECK_MSG(fabs(r.hits[0].t - 4.4) <= 1e-14, "rim t = %.17g", r.hits[0].t);
        CHECK(r.hits[0].object == 2 && r.hits[0].entering == 1);
        /* The bite's outward normal there is (0.3, 0, -0.4)/0.5; flipped. */
        const hr_vec3 n = r.hits[0].normal;
        const double len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
        CHECK(fabs(n.x / len + 0.6) <= 1e-14 && fabs(n.z / len - 0.8) <= 1e-14);
    }
    destroy(&d);
}

/* --- Coincident faces, tangents, boundaries -------------------------------------------- */

static void test_coincident_faces(void)
{
    /* Cube A = [-1, 1]^3 (object 1); B = [1, 3] x [-1, 1]^2 shares A's +x face
     * (object 2); C = [1/3, 1] x [-1/3, 1/3]^2, placed by an inexact scale,
     * shares it from inside A (object 3). */
    harness_child a = place(&cube, 0, 0, 0, 1, 1), b = place(&cube, 2, 0, 0, 1, 2);
    harness_child c = place(&cube, 2.0 / 3.0, 0, 0, 1.0 / 3.0, 3);
    harness_shape u = boolean(union_cls, &a, &b), in = boolean(intersection_cls, &a, &b);
    harness_shape ab = boolean(difference_cls, &a, &b), ac = boolean(difference_cls, &a, &c);
    harness_shape ca = boolean(difference_cls, &c, &a);
    ray_rng rng;
    rng_seed(&rng, 7);
    for (int k = 0; k < 2000; k++) {
        /* Along +x at varied heights and slopes, so the shared face's two
         * times round differently from ray to ray. */
        /* |y| stays below 0.2 + 12 * 0.005 = 0.26 over x in [-9, 3]: within
         * C's 1/3, so every ray runs through the shared faces. */
        const double y = rng_uniform(&rng, -0.2, 0.2), z = rng_uniform(&rng, -0.2, 0.2);
        const double ox = rng_uniform(&rng, -9, -2);
        const double dy = rng_uniform(&rng, -0.005, 0.005), dx = rng_uniform(&rng, 0.3, 3);
        const hr_ray ray = harness_ray(ox, y, z, dx, dy * dx, 0);
        result r;
        /* Touching cubes are one solid: in at x = -1, out at x = 3, no face
         * between. */
        trace_all(&u, ray, 0, INFINITY, &r);
        CHECK_MSG(r.count == 2 && r.hits[0].object == 1 && r.hits[1].object == 2,
                  "ray %d: touching union has %d hits", k, r.count);
        /* Their intersection is a face with no volume: empty. */
        trace_all(&in, ray, 0, INFINITY, &r);
        CHECK_MSG(r.count == 0, "ray %d: touching intersection has %d hits", k, r.count);
        /* A - B is A: the shared face is A's own exit (surface 0, +x). */
        trace_all(&ab, ray, 0, INFINITY, &r);
        CHECK_MSG(r.count == 2 && r.hits[1].object == 1 && r.hits[1].surface == 0 &&
                      r.hits[1].entering == 0 && r.hits[1].normal.x > 0,
                  "ray %d: A - B has %d hits", k, r.count);
        /* A - C: in at x = -1, out at C's near face x = 1/3 (C's -x face,
         * flipped to +x); at x = 1 both are left together: nothing. */
        trace_all(&ac, ray, 0, INFINITY, &r);
        CHECK_MSG(r.count == 2 && r.hits[1].object == 3 && r.hits[1].surface == 1 &&
                      r.hits[1].normal.x > 0,
                  "ray %d: A - C has %d hits", k, r.count);
        if (r.count == 2) CHECK_NEAR(r.hits[1].point.x, 1.0 / 3.0, 1e-14);
        /* C - A is empty whatever the rounding at x = 1. */
        trace_all(&ca, ray, 0, INFINITY, &r);
        CHECK_MSG(r.count == 0, "ray %d: C - A has %d hits", k, r.count);
    }
    destroy(&u), destroy(&in), destroy(&ab), destroy(&ac), destroy(&ca);
}

static void test_tangent_and_boundary(void)
{
    harness_child a = place(&sphere, 0, 0, 0, 1, 1), far = place(&sphere, 5, 0, 0, 1, 2);
    harness_child b = place(&sphere, 0, 0, 0.5, 1, 3);
    harness_shape u = boolean(union_cls, &a, &far), ub = boolean(union_cls, &a, &b);
    result r;
    /* Tangent to A at (1, 0, 0): the sphere reports a zero-length visit,
     * which a boolean drops (regularised), every time and in every mode. */
    for (int k = 0; k < 3; k++) {
        trace_all(&u, harness_ray(1, 0, -5, 0, 0, 1), 0, INFINITY, &r);
        expect("tangent", &r, NULL, 0);
    }
    /* Starting exactly on A's surface at z = -1: the hit at t = 0 is not
     * reported; going up, the ray is inside A (A's next hit is its exit), so
     * the union is left only at B's top, z = 1.5. */
    trace_all(&ub, harness_ray(0, 0, -1, 0, 0, 1), 0, INFINITY, &r);
    expect("from the boundary, in", &r, (expected[]){{2.5, 3, 0, 1}}, 1);
    /* Going down from there: outside both, nothing. */
    trace_all(&ub, harness_ray(0, 0, -1, 0, 0, -1), 0, INFINITY, &r);
    expect("from the boundary, out", &r, NULL, 0);
    /* On B's top going up: nothing, whatever the rounding of B's root. */
    trace_all(&ub, harness_ray(0, 0, 1.5, 0, 0, 1), 0, INFINITY, &r);
    expect("from the top, out", &r, NULL, 0);
    destroy(&u), destroy(&ub);
}

/* --- Many hits --------------------------------------------------------------------------- */

static void test_many_hits(void)
{
    /* A chain of 40 unions of spheres spaced 3 apart along z: 80 hits, far
     * more than the HR_MIN_HIT_CAPACITY the host promises. */
    enum { N = 40 };
    harness_child leaves[N];
    harness_shape nodes[N];
    harness_child node_children[N];
    for (int i = 0; i < N; i++) leaves[i] = place(&sphere, 0, 0, 3.0 * i, 1, i);
    /* node i = node i-1 | leaf i, node 0 standing for leaf 0 itself. */
    node_children[0] = leaves[0];
    for (int i = 1; i < N; i++) {
        nodes[i] = boolean(union_cls, &node_children[i - 1], &leaves[i]);
        node_children[i] = place(&nodes[i], 0, 0, 0, 1, -1);
    }
    result r;
    trace_all(&nodes[N - 1], harness_ray(0, 0, -2, 0, 0, 1), 0, INFINITY, &r);
    CHECK_MSG(r.count == 2 * N, "%d hits, expected %d", r.count, 2 * N);
    for (int i = 0; i < N && 2 * i + 1 < r.count; i++) {
        CHECK(r.hits[2 * i].object == i && r.hits[2 * i].entering == 1);
        CHECK(hr_test_ulps(r.hits[2 * i].t, 3.0 * i + 1) <= 4);
        CHECK(hr_test_ulps(r.hits[2 * i + 1].t, 3.0 * i + 3) <= 4);
    }
    for (int i = N - 1; i >= 1; i--) destroy(&nodes[i]);
}

/* --- Brute force: three levels of nesting, random rays ---------------------------------- */

#define LEAF_SPHERE 0
#define LEAF_CUBE 1

typedef struct leaf {
    int kind;
    long double x, y, z, scale;
} leaf;

/* The tree under test, mirrored: ((S0 | S1) & C2) - S3. */
static const leaf brute_leaves[4] = {
    {LEAF_SPHERE, 0, 0, 0, 1},
    {LEAF_SPHERE, 0.6L, 0.2L, 0.3L, 0.75L},
    {LEAF_CUBE, 0.2L, 0, 0.1L, 0.9L},
    {LEAF_SPHERE, -0.5L, 0.4L, 0.2L, 0.5L},
};

static int leaf_contains(const leaf *l, long double px, long double py, long double pz)
{
    const long double x = (px - l->x) / l->scale, y = (py - l->y) / l->scale,
                      z = (pz - l->z) / l->scale;
    if (l->kind == LEAF_SPHERE) return x * x + y * y + z * z < 1.0L;
    return fabsl(x) < 1.0L && fabsl(y) < 1.0L && fabsl(z) < 1.0L;
}

static int tree_contains(long double x, long double y, long double z)
{
    const int s0 = leaf_contains(&brute_leaves[0], x, y, z);
    const int s1 = leaf_contains(&brute_leaves[1], x, y, z);
    const int c2 = leaf_contains(&brute_leaves[2], x, y, z);
    const int s3 = leaf_contains(&brute_leaves[3], x, y, z);
    return ((s0 || s1) && c2) && !s3;
}

typedef struct root {
    long double t;
    int leaf;
} root;

/* The leaf's crossings with t > 0 in long double; returns how many, and
 * sets *fragile for a ray too close to tangent (or to an edge) for the
 * double shapes and this reference to agree on whether it hits. */
static int leaf_roots(const leaf *l, int index, const hr_ray *ray, root *out, int *fragile)
{
    const long double ox = (ray->origin.x - l->x) / l->scale, oy = (ray->origin.y - l->y) / l->scale,
                      oz = (ray->origin.z - l->z) / l->scale;
    const long double dx = ray->dir.x / l->scale, dy = ray->dir.y / l->scale,
                      dz = ray->dir.z / l->scale;
    long double t0, t1;
    if (l->kind == LEAF_SPHERE) {
        const long double a = dx * dx + dy * dy + dz * dz, b = ox * dx + oy * dy + oz * dz,
                          c = ox * ox + oy * oy + oz * oz - 1.0L;
        const long double disc = b * b - a * c;
        if (fabsl(disc) < 1e-6L * a) *fragile = 1;
        if (disc < 0) return 0;
        const long double s = sqrtl(disc);
        t0 = (-b - s) / a;
        t1 = (-b + s) / a;
    } else {
        t0 = -INFINITY;
        t1 = INFINITY;
        const long double o[3] = {ox, oy, oz}, d[3] = {dx, dy, dz};
        for (int k = 0; k < 3; k++) {
            if (d[k] == 0) {
                if (fabsl(o[k]) >= 1.0L) return 0;
                continue;
            }
            long double ta = (-1.0L - o[k]) / d[k], tb = (1.0L - o[k]) / d[k];
            if (ta > tb) {
                const long double tmp = ta;
                ta = tb, tb = tmp;
            }
            if (ta > t0) t0 = ta;
            if (tb < t1) t1 = tb;
        }
        if (fabsl(t1 - t0) < 1e-6L) *fragile = 1;
        if (!(t0 <= t1)) return 0;
    }
    int n = 0;
    if (t0 > 0) out[n++] = (root){t0, index};
    if (t1 > 0) out[n++] = (root){t1, index};
    return n;
}

static int compare_roots(const void *x, const void *y)
{
    const root *a = x, *b = y;
    return a->t < b->t ? -1 : a->t > b->t ? 1 : 0;
}

static void test_nested_brute_force(void)
{
    harness_child l0 = place(&sphere, 0, 0, 0, 1, 0), l1 = place(&sphere, 0.6, 0.2, 0.3, 0.75, 1);
    harness_child l2 = place(&cube, 0.2, 0, 0.1, 0.9, 2), l3 = place(&sphere, -0.5, 0.4, 0.2, 0.5, 3);
    harness_shape level1 = boolean(union_cls, &l0, &l1);
    harness_child c1 = place(&level1, 0, 0, 0, 1, -1);
    harness_shape level2 = boolean(intersection_cls, &c1, &l2);
    harness_child c2 = place(&level2, 0, 0, 0, 1, -1);
    harness_shape level3 = boolean(difference_cls, &c2, &l3);

    ray_rng rng;
    rng_seed(&rng, 2024);
    int compared = 0, with_hits = 0, intervals = 0;
    for (int k = 0; k < 20000; k++) {
        const hr_vec3 o = harness_vec(rng_uniform(&rng, -3, 3), rng_uniform(&rng, -3, 3),
                                      rng_uniform(&rng, -3, 3));
        const hr_vec3 target = harness_vec(rng_uniform(&rng, -1.2, 1.2),
                                           rng_uniform(&rng, -1.2, 1.2),
                                           rng_uniform(&rng, -1.2, 1.2));
        const hr_ray ray = harness_ray(o.x, o.y, o.z, target.x - o.x, target.y - o.y,
                                       target.z - o.z);
        root roots[8];
        int n = 0, fragile = 0;
        for (int i = 0; i < 4; i++) n += leaf_roots(&brute_leaves[i], i, &ray, roots + n, &fragile);
        qsort(roots, (size_t)n, sizeof *roots, compare_roots);
        /* Roots closer than this (relative) are coincidences the double
         * shapes may order either way: skip such rays (about 1 in 1000). */
        for (int i = 0; i + 1 < n; i++)
            if (roots[i + 1].t - roots[i].t < 1e-9L * (1 + roots[i].t)) fragile = 1;
        if (n > 0 && roots[0].t < 1e-9L) fragile = 1;
        if (fragile) continue;
        /* The reference: the tree's state on each side of each root. */
        expected want[8];
        int nwant = 0;
        long double before = 0;
        for (int i = 0; i < n; i++) {
            const long double after = i + 1 < n ? roots[i + 1].t : roots[i].t + 1;
            const long double m0 = 0.5L * (before + roots[i].t), m1 = 0.5L * (roots[i].t + after);
            const int in0 = tree_contains(o.x + m0 * ray.dir.x, o.y + m0 * ray.dir.y,
                                          o.z + m0 * ray.dir.z);
            const int in1 = tree_contains(o.x + m1 * ray.dir.x, o.y + m1 * ray.dir.y,
                                          o.z + m1 * ray.dir.z);
            if (in0 != in1) want[nwant++] = (expected){(double)roots[i].t, roots[i].leaf, in1, 0};
            before = roots[i].t;
        }
        result r;
        trace_all(&level3, ray, 0, INFINITY, &r);
        compared++;
        with_hits += nwant > 0;
        CHECK_MSG(r.count == nwant, "ray %d: %d hits, reference %d", k, r.count, nwant);
        for (int i = 0; i < nwant && i < r.count; i++) {
            const hr_hit *h = &r.hits[i];
            /* The shapes' roots are good to a few ulps relative to the
             * ray's scale (|o| + t |d| <= about 20 here): 1e-12 is loose. */
            CHECK_MSG(fabs(h->t - want[i].t) <= 1e-12 * (1 + fabs(want[i].t)),
                      "ray %d hit %d: t %.17g, reference %.17g", k, i, h->t, want[i].t);
            CHECK_MSG(h->object == want[i].object && h->entering == want[i].entering,
                      "ray %d hit %d: object %lld entering %d, reference %lld %d", k, i,
                      (long long)h->object, (int)h->entering, (long long)want[i].object,
                      want[i].entering);
            /* The normal points out of the result: along the ray when
             * leaving, against it when entering. */
            const double along = h->normal.x * ray.dir.x + h->normal.y * ray.dir.y +
                                 h->normal.z * ray.dir.z;
            CHECK_MSG(h->entering ? along < 0 : along > 0, "ray %d hit %d: normal faces the wrong way",
                      k, i);
        }
        /* Over a random interval: exactly the whole ray's hits inside it
         * (an interval end near a root could see a different rounding of
         * the same crossing: such intervals are skipped). */
        double tmin, tmax;
        random_interval(&rng, &tmin, &tmax);
        if (tmin < 0) tmin = -tmin;
        int near_end = 0;
        for (int i = 0; i < n; i++)
            near_end |= fabsl(roots[i].t - tmin) < 1e-9L || fabsl(roots[i].t - tmax) < 1e-9L;
        if (tmin >= tmax || near_end) continue;
        result part;
        trace_all(&level3, ray, tmin, tmax, &part);
        int inside_count = 0;
        for (int i = 0; i < r.count; i++) {
            if (!(r.hits[i].t > tmin && r.hits[i].t < tmax)) continue;
            CHECK_MSG(inside_count < part.count &&
                          memcmp(&r.hits[i], &part.hits[inside_count], sizeof(hr_hit)) == 0,
                      "ray %d over (%g, %g): hit %d differs from the whole ray's", k, tmin, tmax,
                      inside_count);
            inside_count++;
        }
        CHECK_MSG(part.count == inside_count, "ray %d over (%g, %g): %d hits, the whole ray %d", k,
                  tmin, tmax, part.count, inside_count);
        intervals++;
    }
    /* The rays must exercise the tree, not just miss it. */
    CHECK_MSG(compared > 19000 && with_hits > 5000 && intervals > 15000,
              "compared %d rays, %d with hits, %d over intervals", compared, with_hits, intervals);
    destroy(&level3), destroy(&level2), destroy(&level1);
}

/* --- Refusals, bounds, an unbounded solid ----------------------------------------------- */

static void test_refusals(void)
{
    harness_child s = place(&sphere, 0, 0, 0, 1, 0), p = place(&plane, 0, 0, 0, 1, 1);
    const char *names[] = {"a", "b"};
    const harness_child *open_b[] = {&s, &p};
    void *shape = NULL;
    char error[256];
    hr_status st = harness_create_composite(union_cls, names, open_b, 2, &shape, error, sizeof error);
    CHECK(st == HR_ERROR_PARAMETER && shape == NULL);
    CHECK_MSG(strstr(error, "parameter 'b'") && strstr(error, "'plane'") && strstr(error, "solid"),
              "message: %s", error);
    const harness_child *missing[] = {&s};
    st = harness_create_composite(difference_cls, names, missing, 1, &shape, error, sizeof error);
    CHECK(st == HR_ERROR_PARAMETER && shape == NULL);
    CHECK_MSG(strstr(error, "parameter 'b'"), "message: %s", error);
}

/* A host from before hr_host.child_class (a smaller struct_size): the
 * module must not read past it, and then takes its operands as solids. */
static void test_older_host(void)
{
    hr_host old = *harness_host();
    old.struct_size = (uint32_t)offsetof(hr_host, child_class);
    old.child_class = NULL; /* reading it would crash */
    harness_child s = place(&sphere, 0, 0, 0, 1, 0), c = place(&cube, 0, 0, 0, 0.5, 1);
    hr_param params[2];
    memset(params, 0, sizeof params);
    params[0].name = "a", params[0].type = HR_PARAM_OBJECT, params[0].object = 0;
    params[1].name = "b", params[1].type = HR_PARAM_OBJECT, params[1].object = 1;
    const void *objects[2] = {&s, &c};
    char error[128] = "";
    hr_create_args args;
    memset(&args, 0, sizeof args);
    args.struct_size = sizeof args;
    args.param_count = 2;
    args.params = params;
    args.objects = objects;
    args.host = &old;
    args.error = error;
    args.error_size = sizeof error;
    args.base_dir = "";
    harness_shape d;
    memset(&d, 0, sizeof d);
    d.cls = difference_cls;
    CHECK_MSG(difference_cls->create(&args, &d.shape) == HR_OK && d.shape, "create: %s", error);
    if (!d.shape) return;
    /* Sphere minus the cube of half-size 0.5, along z from -5. */
    result r;
    trace_all(&d, harness_ray(0, 0, -5, 0, 0, 1), 0, INFINITY, &r);
    expect("older host", &r,
           (expected[]){{4, 0, 1, -1}, {4.5, 1, 0, 1}, {5.5, 1, 1, -1}, {6, 0, 0, 1}}, 4);
    destroy(&d);
}

static void check_box(const char *what, const harness_shape *s, double lx, double ly, double lz,
                      double hx, double hy, double hz)
{
    hr_bounds b;
    s->cls->bounds(s->shape, &b);
    CHECK_MSG(b.lo.x == lx && b.lo.y == ly && b.lo.z == lz && b.hi.x == hx && b.hi.y == hy &&
                  b.hi.z == hz,
              "%s: (%g %g %g) - (%g %g %g)", what, b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
}

static void test_bounds(void)
{
    harness_child a = place(&sphere, 0, 0, 0, 1, 0), b = place(&cube, 1, 0, 0.5, 0.5, 1);
    harness_child far = place(&sphere, 5, 0, 0, 1, 2);
    harness_shape u = boolean(union_cls, &a, &b), in = boolean(intersection_cls, &a, &b);
    harness_shape d = boolean(difference_cls, &b, &a), none = boolean(intersection_cls, &a, &far);
    check_box("union", &u, -1, -1, -1, 1.5, 1, 1);
    check_box("intersection", &in, 0.5, -0.5, 0, 1, 0.5, 1);
    check_box("difference", &d, 0.5, -0.5, 0, 1.5, 0.5, 1);
    /* Disjoint: a point box between them (x: lo 4 > hi 1 becomes 2.5). */
    check_box("empty intersection", &none, 2.5, -1, -1, 2.5, 1, 1);
    destroy(&u), destroy(&in), destroy(&d), destroy(&none);
}

/* A closed solid without bounds: the half-space z < 0 (hits like the plane's,
 * but declared a solid). */
static hr_status half_create(const hr_create_args *args, void **out)
{
    *out = args->host->alloc(1);
    return *out ? HR_OK : HR_ERROR_OUT_OF_MEMORY;
}
static void half_destroy(void *shape)
{
    harness_host()->free(shape);
}
static void half_bounds(const void *shape, hr_bounds *b)
{
    (void)shape;
    b->lo = harness_vec(-INFINITY, -INFINITY, -INFINITY);
    b->hi = harness_vec(INFINITY, INFINITY, 0);
}
static hr_status half_hit(const hr_hit_args *args)
{
    const hr_ray *r = &args->ray;
    if (r->dir.z == 0) return HR_OK;
    const double t = -r->origin.z / r->dir.z;
    if (!(t > args->tmin && t < args->tmax)) return HR_OK;
    hr_hit *h = &args->out->hits[args->out->count++];
    h->t = t;
    h->point = harness_vec(r->origin.x + t * r->dir.x, r->origin.y + t * r->dir.y, 0);
    h->normal = harness_vec(0, 0, 1);
    h->error = 4 * DBL_EPSILON * (fabs(h->point.x) + fabs(h->point.y));
    h->surface = 0;
    h->entering = r->dir.z < 0;
    return HR_OK;
}
static const hr_shape_class half_class = {
    sizeof(hr_shape_class), HR_SHAPE_CLOSED, "halfSpace", "z < 0", NULL, 0, 1, half_create,
    half_destroy, half_bounds, half_hit, NULL, NULL, NULL, NULL, NULL, 0};

static void test_unbounded_child(void)
{
    harness_shape half;
    memset(&half, 0, sizeof half);
    half.cls = &half_class;
    char error[64];
    CHECK_OK(harness_create(&half_class, NULL, NULL, 0, &half.shape, error, sizeof error));
    harness_child s = place(&sphere, 0, 0, 0, 1, 0), h = place(&half, 0, 0, 0, 1, 1);
    harness_shape cut = boolean(intersection_cls, &s, &h);
    result r;
    /* Parallel to the boundary, below it: the ray never crosses the
     * half-space's surface, yet is inside it all along. */
    trace_all(&cut, harness_ray(-5, 0, -0.6, 1, 0, 0), 0, INFINITY, &r);
    expect("below the cut", &r, (expected[]){{4.2, 0, 1, NAN}, {5.8, 0, 0, NAN}}, 2);
    /* Above it: outside all along. */
    trace_all(&cut, harness_ray(-5, 0, 0.6, 1, 0, 0), 0, INFINITY, &r);
    expect("above the cut", &r, NULL, 0);
    /* Down through the cut face: in at z = 0 (the half-space's surface). */
    trace_all(&cut, harness_ray(0, 0, 5, 0, 0, -1), 0, INFINITY, &r);
    expect("through the cut", &r, (expected[]){{5, 1, 1, 1}, {6, 0, 0, -1}}, 2);
    destroy(&cut);
    half_destroy(half.shape);
}

static void test_module(void)
{
    CHECK(union_cls && intersection_cls && difference_cls);
    const hr_shape_class *classes[] = {union_cls, intersection_cls, difference_cls};
    for (int i = 0; i < 3; i++) {
        const hr_shape_class *c = classes[i];
        CHECK(c->flags == (HR_SHAPE_CLOSED | HR_SHAPE_COMPOSITE));
        CHECK(c->param_count == 2 && strcmp(c->params[0].name, "a") == 0 &&
              strcmp(c->params[1].name, "b") == 0);
        CHECK(c->params[0].type == HR_PARAM_OBJECT && c->params[1].type == HR_PARAM_OBJECT);
        CHECK(c->params[0].required && c->params[1].required);
        CHECK(c->hit && c->first_hit && c->any_hit);
    }
}

int main(void)
{
    if (!harness_load("csg", &csg_module) || !harness_open(&sphere, "sphere", "sphere", NAN) ||
        !harness_open(&cube, "cube", "cube", NAN) || !harness_open(&plane, "plane", "plane", NAN))
        return hr_test_end();
    union_cls = harness_find_class(&csg_module, "union");
    intersection_cls = harness_find_class(&csg_module, "intersection");
    difference_cls = harness_find_class(&csg_module, "difference");
    test_module();
    if (union_cls && intersection_cls && difference_cls) {
        test_truth_table();
        test_difference_hole();
        test_coincident_faces();
        test_tangent_and_boundary();
        test_many_hits();
        test_nested_brute_force();
        test_refusals();
        test_bounds();
        test_unbounded_child();
        test_older_host();
    }
    harness_close(&sphere);
    harness_close(&cube);
    harness_close(&plane);
    harness_unload(&csg_module);
    return hr_test_end();
}
