/* accel_bvh4_build against a straightforward reference build kept here: the
 * binned SAH as docs/acceleration.md states it (every bin set up and swept on
 * every axis of every node, each child's bounds gathered the plain way where
 * the split did not make them), then the same collapse to four children.
 * The library's build skips work this one does (empty bins, recomputation),
 * never a decision, so the two must give the same tree: byte for byte the
 * same nodes, the same item order, depth and extent. Inputs: random boxes of
 * many sizes, clusters, equal centroids, boxes on a lattice (many exactly
 * equal costs, so ties must break the same way), a subnormal spread,
 * infinite and huge boxes, geometric spacing (the SAH depth limit), every
 * leaf size and a few traversal costs. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh4.h"
#include "hr_test.h"

#define REF_BINS 16

typedef struct ref_node {
    hr_bounds box;
    uint32_t first, count; /* count 0: inner, children first and first + 1 */
} ref_node;

typedef struct ref_builder {
    ref_node *nodes;
    uint32_t node_count;
    uint32_t *items;
    const hr_bounds *boxes;
    double *centroids;
    uint32_t max_leaf;
    double traversal_cost;
} ref_builder;

static hr_bounds ref_empty(void)
{
    return (hr_bounds){{DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, -DBL_MAX, -DBL_MAX}};
}

static double ref_min(double acc, double v) { return v < acc ? v : acc; }
static double ref_max(double acc, double v) { return v > acc ? v : acc; }

static void ref_grow(hr_bounds *b, const hr_bounds *o)
{
    b->lo.x = ref_min(b->lo.x, o->lo.x), b->lo.y = ref_min(b->lo.y, o->lo.y);
    b->lo.z = ref_min(b->lo.z, o->lo.z);
    b->hi.x = ref_max(b->hi.x, o->hi.x), b->hi.y = ref_max(b->hi.y, o->hi.y);
    b->hi.z = ref_max(b->hi.z, o->hi.z);
}

static void ref_grow_point(hr_bounds *b, const double c[3])
{
    const hr_bounds p = {{c[0], c[1], c[2]}, {c[0], c[1], c[2]}};
    ref_grow(b, &p);
}

static double ref_area(const hr_bounds *b)
{
    double dx = b->hi.x - b->lo.x, dy = b->hi.y - b->lo.y, dz = b->hi.z - b->lo.z;
    if (dx < 0 || dy < 0 || dz < 0) return 0.0;
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

static double ref_axis(const hr_vec3 *v, int axis) { return axis == 0 ? v->x : axis == 1 ? v->y : v->z; }

static int ref_bin(double c, double lo, double scale)
{
    const double x = (c - lo) * scale;
    return x >= 0.0 ? (x < REF_BINS ? (int)x : REF_BINS - 1) : 0;
}

static void ref_gather(const ref_builder *b, uint32_t first, uint32_t count, hr_bounds *box,
                       hr_bounds *cbox)
{
    *box = ref_empty(), *cbox = ref_empty();
    for (uint32_t i = first; i < first + count; i++) {
        ref_grow(box, &b->boxes[b->items[i]]);
        ref_grow_point(cbox, b->centroids + 3 * (size_t)b->items[i]);
    }
}

/* Node `node` over items[first, first + count), whose boxes' union is box.
 * Where the binned split divides the items, each child's box is the union
 * of its side's bins (in bin order), as the sweep made it. */
static void ref_build_binary(ref_builder *b, uint32_t node, uint32_t first, uint32_t count,
                             uint32_t depth, const hr_bounds *box)
{
    hr_bounds unused, cbox;
    ref_gather(b, first, count, &unused, &cbox);
    b->nodes[node] = (ref_node){*box, first, count};
    if (count <= 1) return;
    double lo[3], scale[3];
    int binned[3];
    for (int a = 0; a < 3; a++) {
        double l = ref_axis(&cbox.lo, a), h = ref_axis(&cbox.hi, a);
        lo[a] = l, scale[a] = REF_BINS / (h - l);
        binned[a] = h > l && isfinite(scale[a]);
    }
    double best_cost = DBL_MAX;
    int best_axis = -1, best_split = 0;
    hr_bounds best_left = ref_empty(), best_right = ref_empty();
    for (int a = 0; a < 3; a++) {
        if (!binned[a]) continue;
        hr_bounds bins[REF_BINS], right_box[REF_BINS];
        uint32_t counts[REF_BINS] = {0};
        for (int k = 0; k < REF_BINS; k++) bins[k] = ref_empty();
        for (uint32_t i = first; i < first + count; i++) {
            int k = ref_bin(b->centroids[3 * (size_t)b->items[i] + a], lo[a], scale[a]);
            counts[k]++;
            ref_grow(&bins[k], &b->boxes[b->items[i]]);
        }
        /* Right of boundary k: bins k .. 15; an empty bin adds nothing. */
        double right_area[REF_BINS];
        uint32_t right_count[REF_BINS];
        hr_bounds acc = ref_empty();
        double acc_area = 0.0;
        uint32_t n = 0;
        for (int k = REF_BINS - 1; k > 0; k--) {
            if (counts[k]) ref_grow(&acc, &bins[k]), n += counts[k], acc_area = ref_area(&acc);
            right_box[k] = acc, right_area[k] = acc_area, right_count[k] = n;
        }
        acc = ref_empty(), n = 0;
        for (int k = 0; k < REF_BINS - 1; k++) {
            if (!counts[k]) continue;
            ref_grow(&acc, &bins[k]);
            n += counts[k];
            if (right_count[k + 1] == 0) break;
            double cost = ref_area(&acc) * n + right_area[k + 1] * right_count[k + 1];
            if (cost < best_cost) {
                best_cost = cost, best_axis = a, best_split = k;
                best_left = acc, best_right = right_box[k + 1];
            }
        }
    }
    double parent_area = ref_area(box);
    double split_cost = parent_area > 0 ? b->traversal_cost + best_cost / parent_area : DBL_MAX;
    uint32_t mid;
    int from_bins = 0;
    if (best_axis < 0 || depth >= ACCEL_BVH_SAH_DEPTH) {
        if (count <= b->max_leaf && best_axis < 0) return;
        mid = first + count / 2;
    } else {
        if (count <= b->max_leaf && (double)count <= split_cost) return;
        uint32_t i = first, j = first + count;
        while (i < j) {
            const double c = b->centroids[3 * (size_t)b->items[i] + best_axis];
            if (ref_bin(c, lo[best_axis], scale[best_axis]) <= best_split) {
                i++;
            } else {
                uint32_t t = b->items[i];
                b->items[i] = b->items[--j];
                b->items[j] = t;
            }
        }
        from_bins = i > first && i < first + count;
        mid = from_bins ? i : first + count / 2;
    }
    hr_bounds left_box = best_left, right_box = best_right;
    if (!from_bins) {
        ref_gather(b, first, mid - first, &left_box, &unused);
        ref_gather(b, mid, first + count - mid, &right_box, &unused);
    }
    uint32_t left = b->node_count;
    b->node_count += 2;
    b->nodes[node].first = left;
    b->nodes[node].count = 0;
    ref_build_binary(b, left, first, mid - first, depth + 1, &left_box);
    ref_build_binary(b, left + 1, mid, first + count - mid, depth + 1, &right_box);
}

static void ref_set_slot(accel_bvh4_node *n, int k, const ref_node *kid, uint32_t ref)
{
    const hr_bounds *b = &kid->box;
    const double lo[3] = {b->lo.x, b->lo.y, b->lo.z}, hi[3] = {b->hi.x, b->hi.y, b->hi.z};
    for (int a = 0; a < 3; a++) n->lo[a][k] = accel_float_down(lo[a]), n->hi[a][k] = accel_float_up(hi[a]);
    n->ref[k] = ref;
    n->count[k] = kid->count;
}

static void ref_clear_slot(accel_bvh4_node *n, int k)
{
    for (int a = 0; a < 3; a++) n->lo[a][k] = INFINITY, n->hi[a][k] = -INFINITY;
    n->ref[k] = ACCEL_BVH4_EMPTY;
    n->count[k] = 0;
}

typedef struct ref_collapser {
    const ref_node *bin;
    accel_bvh4_node *nodes;
    uint32_t node_count, depth;
} ref_collapser;

static void ref_collapse(ref_collapser *c, uint32_t out, uint32_t b, uint32_t depth)
{
    if (depth > c->depth) c->depth = depth;
    uint32_t kids[4] = {c->bin[b].first, c->bin[b].first + 1, 0, 0};
    int n = 2;
    while (n < 4) {
        int widest = -1;
        double widest_area = -1.0;
        for (int k = 0; k < n; k++) {
            double a = ref_area(&c->bin[kids[k]].box);
            if (c->bin[kids[k]].count == 0 && a > widest_area) widest = k, widest_area = a;
        }
        if (widest < 0) break;
        uint32_t first = c->bin[kids[widest]].first;
        kids[widest] = first;
        kids[n++] = first + 1;
    }
    for (int k = 0; k < 4; k++) {
        if (k >= n) {
            ref_clear_slot(&c->nodes[out], k);
        } else if (c->bin[kids[k]].count > 0) {
            ref_set_slot(&c->nodes[out], k, &c->bin[kids[k]], c->bin[kids[k]].first);
        } else {
            uint32_t child = c->node_count++;
            ref_set_slot(&c->nodes[out], k, &c->bin[kids[k]], child);
            ref_collapse(c, child, kids[k], depth + 1);
        }
    }
}

/* The reference's tree in the library's form (count > 0). */
static void ref_build(accel_bvh4 *out, const hr_bounds *boxes, uint32_t count, uint32_t max_leaf,
                      double traversal_cost)
{
    ref_builder b = {calloc(2 * (size_t)count, sizeof(ref_node)), 1, malloc(count * sizeof(uint32_t)),
                     boxes, malloc(3 * (size_t)count * sizeof(double)), max_leaf, traversal_cost};
    for (uint32_t i = 0; i < count; i++) {
        b.items[i] = i;
        b.centroids[3 * i] = 0.5 * boxes[i].lo.x + 0.5 * boxes[i].hi.x;
        b.centroids[3 * i + 1] = 0.5 * boxes[i].lo.y + 0.5 * boxes[i].hi.y;
        b.centroids[3 * i + 2] = 0.5 * boxes[i].lo.z + 0.5 * boxes[i].hi.z;
    }
    hr_bounds root, unused;
    ref_gather(&b, 0, count, &root, &unused);
    ref_build_binary(&b, 0, 0, count, 0, &root);
    ref_collapser c = {b.nodes, calloc(2 * (size_t)count, sizeof(accel_bvh4_node)), 1, 1};
    if (b.nodes[0].count > 0) {
        ref_set_slot(&c.nodes[0], 0, &b.nodes[0], 0);
        for (int k = 1; k < 4; k++) ref_clear_slot(&c.nodes[0], k);
    } else {
        ref_collapse(&c, 0, 0, 1);
    }
    memset(out, 0, sizeof *out);
    out->nodes = c.nodes;
    out->node_count = c.node_count;
    out->items = b.items;
    out->item_count = count;
    out->depth = c.depth;
    for (uint32_t i = 0; i < count; i++) {
        const double v[6] = {boxes[i].lo.x, boxes[i].lo.y, boxes[i].lo.z,
                             boxes[i].hi.x, boxes[i].hi.y, boxes[i].hi.z};
        for (int k = 0; k < 6; k++)
            if (!(fabs(v[k]) <= out->extent)) out->extent = isnan(v[k]) ? INFINITY : fabs(v[k]);
    }
    free(b.nodes);
    free(b.centroids);
}

/* --- inputs ---------------------------------------------------------------- */

static uint64_t rng_state = 0x2545f4914f6cdd1dull;
static double uniform(void) /* [0, 1) */
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * 0x1p-53;
}
static double between(double a, double b) { return a + (b - a) * uniform(); }
static hr_bounds cube(double x, double y, double z, double r)
{
    return (hr_bounds){{x - r, y - r, z - r}, {x + r, y + r, z + r}};
}

enum { KINDS = 10 };
static const char *const kind_names[KINDS] = {"random", "clusters", "equal centroids", "lattice",
                                              "subnormal spread", "infinite", "huge",
                                              "geometric", "flat", "signed zeros"};

static void make_boxes(int kind, hr_bounds *boxes, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++) {
        switch (kind) {
        case 0: {
            double r = pow(10.0, between(-6, 1));
            boxes[i] = cube(between(-100, 100), between(-100, 100), between(-100, 100), r);
            break;
        }
        case 1: { /* a few tight clusters far apart */
            double cx = 1000.0 * (double)(i % 5), r = between(1e-4, 1e-2);
            boxes[i] = cube(cx + between(0, 0.01), between(0, 0.01), between(-5, 5), r);
            break;
        }
        case 2: boxes[i] = cube(1, 2, 3, 0.5 + (double)(i % 3)); break;
        case 3: /* unit cubes on a lattice: many equal costs */
            boxes[i] = cube((double)(i % 7), (double)(i / 7 % 7), (double)(i / 49), 0.5);
            break;
        case 4: boxes[i] = cube(0x1p-1070 * (double)(i % 4), 0, 0, 0.0); break;
        case 5: /* a few unbounded boxes (planes) among finite ones */
            boxes[i] = i % 17 == 3 ? (hr_bounds){{-INFINITY, -INFINITY, 0}, {INFINITY, INFINITY, 0}}
                                   : cube(between(-10, 10), between(-10, 10), between(-10, 10), 0.1);
            break;
        case 6: {
            double s = i % 2 ? 1.0 : -1.0;
            boxes[i] = (hr_bounds){{s * between(1e307, 1e308), (double)i, 0},
                                   {s * 1.7e308, (double)i + 1.0, 1}};
            break;
        }
        case 7: {
            double x = pow(1.5, (double)(i % 1500));
            boxes[i] = (hr_bounds){{0.7 * x, -0.3 * x, -0.3 * x}, {1.3 * x, 0.3 * x, 0.3 * x}};
            break;
        }
        case 8: /* zero thickness on one axis, so some areas are equal */
            boxes[i] = (hr_bounds){{between(-1, 1), between(-1, 1), 0},
                                   {between(1, 2), between(1, 2), 0}};
            break;
        default: { /* faces on 0 and -0: a union's zero depends on the order it grows in */
            double z0 = uniform() < 0.5 ? -0.0 : 0.0, z1 = uniform() < 0.5 ? -0.0 : 0.0;
            boxes[i] = (hr_bounds){{z0, between(-1, 0), z1}, {between(0, 1), z1, between(0, 1)}};
            break;
        }
        }
    }
}

static int same_tree(const accel_bvh4 *a, const accel_bvh4 *b)
{
    return a->node_count == b->node_count && a->item_count == b->item_count &&
           a->depth == b->depth && a->extent == b->extent &&
           memcmp(a->nodes, b->nodes, a->node_count * sizeof *a->nodes) == 0 &&
           memcmp(a->items, b->items, a->item_count * sizeof *a->items) == 0;
}

int main(void)
{
    static const uint32_t sizes[] = {1, 2, 3, 5, 8, 17, 64, 100, 333, 1000, 4096};
    static const double costs[] = {0.5, 1.0, 0.125};
    enum { N = 20000 };
    hr_bounds *boxes = malloc(N * sizeof *boxes);
    long builds = 0, differing = 0;
    for (int kind = 0; kind < KINDS; kind++) {
        long kind_differing = 0;
        for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
            for (uint32_t leaf = 1; leaf <= 16; leaf = leaf < 4 ? leaf + 1 : leaf * 2)
                for (int rep = 0; rep < 2; rep++) {
                    const uint32_t n = sizes[s];
                    const double cost = costs[(s + leaf + (uint32_t)rep) % 3];
                    make_boxes(kind, boxes, n);
                    const accel_bvh4_options o = {.max_leaf = leaf, .traversal_cost = cost};
                    accel_bvh4 got, want;
                    CHECK(accel_bvh4_build(&got, boxes, n, &o) == 0);
                    ref_build(&want, boxes, n, leaf, cost);
                    int same = same_tree(&got, &want);
                    CHECK_MSG(same, "%s, %u boxes, max_leaf %u, cost %g: tree differs from the reference",
                              kind_names[kind], (unsigned)n, (unsigned)leaf, cost);
                    builds++, kind_differing += !same;
                    accel_bvh4_release(&got);
                    free(want.nodes);
                    free(want.items);
                }
        differing += kind_differing;
        fprintf(stderr, "%s: %ld differing\n", kind_names[kind], kind_differing);
    }
    /* Large random sets, where most of the build's time is, built on one
     * thread and on several (subtrees of ACCEL_BVH4_PARALLEL_ITEMS items or
     * more side by side, two to four of them, an odd share too): the same
     * tree either way. */
    for (int rep = 0; rep < 6; rep++) {
        make_boxes(rep % 3 == 2 ? 3 : 0, boxes, N);
        const accel_bvh4_options o = {.max_leaf = rep % 3 ? 4u : 1u, .traversal_cost = 1.0,
                                      .threads = rep < 3 ? 1u : (uint32_t)rep - 1u};
        accel_bvh4 got, want;
        CHECK(accel_bvh4_build(&got, boxes, N, &o) == 0);
        ref_build(&want, boxes, N, o.max_leaf, 1.0);
        CHECK_MSG(same_tree(&got, &want), "%d large boxes, rep %d: tree differs", N, rep);
        builds++, differing += !same_tree(&got, &want);
        accel_bvh4_release(&got);
        free(want.nodes);
        free(want.items);
    }
    fprintf(stderr, "%ld builds compared with the reference, %ld differing\n", builds, differing);
    CHECK(builds > 1000);
    free(boxes);
    return hr_test_end();
}
