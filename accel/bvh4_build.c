/* Building the 4-wide BVH: a binary tree by binned SAH over the items'
 * centroids (16 bins per axis), built top-down with the items partitioned
 * in place (so every leaf is a run of `items`), then collapsed to four
 * children a node: starting from a node's two children, the inner child of
 * largest surface area is replaced by its own two until there are four or
 * only leaves. Child boxes are then rounded outward to float. */
#include "bvh4.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#define BINS 16

static void *default_alloc(size_t size) { return calloc(1, size ? size : 1); }

/* --- The binary tree ------------------------------------------------------ */

typedef struct bin_node {
    hr_bounds box;
    uint32_t first; /* leaf: first item; inner: left child (right = left + 1) */
    uint32_t count; /* leaf: number of items (> 0); inner: 0 */
} bin_node;

/* A box as six numbers to take minima of: lo.x, lo.y, lo.z, -hi.x, -hi.y,
 * -hi.z (negation is exact, so min of -hi is -max of hi), so growing a box
 * is three two-lane minima with SSE2. */
typedef struct nbox {
    double v[6];
} nbox;

static nbox nbox_empty(void)
{
    nbox b = {{DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX, DBL_MAX}};
    return b;
}

static nbox nbox_of(const hr_bounds *b)
{
    nbox n = {{b->lo.x, b->lo.y, b->lo.z, -b->hi.x, -b->hi.y, -b->hi.z}};
    return n;
}

static hr_bounds nbox_bounds(const nbox *n)
{
    hr_bounds b = {{n->v[0], n->v[1], n->v[2]}, {-n->v[3], -n->v[4], -n->v[5]}};
    return b;
}

/* Lane by lane v < acc ? v : acc, as SSE2's min(v, acc) is: a NaN in `o`
 * leaves the running box as it was. */
static inline void grow(nbox *b, const nbox *o)
{
#if defined(__SSE2__)
    for (int i = 0; i < 6; i += 2)
        _mm_storeu_pd(b->v + i, _mm_min_pd(_mm_loadu_pd(o->v + i), _mm_loadu_pd(b->v + i)));
#else
    for (int i = 0; i < 6; i++) b->v[i] = o->v[i] < b->v[i] ? o->v[i] : b->v[i];
#endif
}

static double area(const nbox *b)
{
    double dx = -b->v[3] - b->v[0], dy = -b->v[4] - b->v[1], dz = -b->v[5] - b->v[2];
    if (dx < 0 || dy < 0 || dz < 0) return 0.0;
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

static double bounds_area(const hr_bounds *b)
{
    const nbox n = nbox_of(b);
    return area(&n);
}

typedef struct builder {
    bin_node *nodes;
    uint32_t node_count, node_cap;
    uint32_t *items;
    const nbox *boxes;
    double *centroids; /* 3 per input box; halves first: lo + hi overflows near DBL_MAX */
    uint32_t max_leaf;
    double traversal_cost;
} builder;

static inline int bin_of(double c, double lo, double scale)
{
    int i = (int)((c - lo) * scale);
    return i < 0 ? 0 : i >= BINS ? BINS - 1 : i;
}

static void build_binary(builder *b, uint32_t node, uint32_t first, uint32_t count, uint32_t depth)
{
    uint32_t *items = b->items;
    nbox box = nbox_empty(), cbox = nbox_empty();
    for (uint32_t i = first; i < first + count; i++) {
        grow(&box, &b->boxes[items[i]]);
        const double *c = b->centroids + 3 * (size_t)items[i];
        nbox cb = {{c[0], c[1], c[2], -c[0], -c[1], -c[2]}};
        grow(&cbox, &cb);
    }
    b->nodes[node].box = nbox_bounds(&box);
    b->nodes[node].first = first;
    b->nodes[node].count = count;
    if (count <= 1) return;

    /* Bin on every axis whose centroids spread (a subnormal spread gives an
     * infinite scale: no binning possible there), in one pass. */
    double lo[3], scale[3];
    int binned[3], any = 0;
    for (int axis = 0; axis < 3; axis++) {
        lo[axis] = cbox.v[axis];
        const double hi = -cbox.v[axis + 3];
        scale[axis] = BINS / (hi - lo[axis]);
        binned[axis] = hi > lo[axis] && isfinite(scale[axis]);
        any |= binned[axis];
    }
    nbox bin_box[3][BINS];
    uint32_t bin_count[3][BINS] = {{0}};
    if (any) {
        for (int axis = 0; axis < 3; axis++)
            for (int k = 0; k < BINS; k++) bin_box[axis][k] = nbox_empty();
        for (uint32_t i = first; i < first + count; i++) {
            const double *c = b->centroids + 3 * (size_t)items[i];
            const nbox *ib = &b->boxes[items[i]];
            for (int axis = 0; axis < 3; axis++) {
                if (!binned[axis]) continue;
                int k = bin_of(c[axis], lo[axis], scale[axis]);
                bin_count[axis][k]++;
                grow(&bin_box[axis][k], ib);
            }
        }
    }
    double best_cost = DBL_MAX;
    int best_axis = -1, best_split = 0;
    for (int axis = 0; axis < 3; axis++) {
        if (!binned[axis]) continue;
        double right_area[BINS];
        uint32_t right_count[BINS];
        nbox acc = nbox_empty();
        uint32_t n = 0;
        for (int k = BINS - 1; k > 0; k--) {
            grow(&acc, &bin_box[axis][k]);
            n += bin_count[axis][k];
            right_area[k] = area(&acc);
            right_count[k] = n;
        }
        acc = nbox_empty();
        n = 0;
        for (int k = 0; k < BINS - 1; k++) {
            grow(&acc, &bin_box[axis][k]);
            n += bin_count[axis][k];
            if (n == 0 || right_count[k + 1] == 0) continue;
            double cost = area(&acc) * n + right_area[k + 1] * right_count[k + 1];
            if (cost < best_cost) best_cost = cost, best_axis = axis, best_split = k;
        }
    }
    double parent_area = area(&box);
    double split_cost = parent_area > 0 ? b->traversal_cost + best_cost / parent_area : DBL_MAX;
    uint32_t mid;
    if (best_axis < 0 || depth >= ACCEL_BVH_SAH_DEPTH) {
        /* All centroids coincide, or SAH has gone deep (geometric spacing
         * can make it peel one item off per level): halve the range, which
         * bounds the rest of the tree to log2(count) levels, so the whole
         * tree stays within ACCEL_BVH_MAX_DEPTH. */
        if (count <= b->max_leaf && best_axis < 0) return;
        mid = first + count / 2;
    } else {
        if (count <= b->max_leaf && (double)count <= split_cost) return;
        const double axis_lo = lo[best_axis], axis_scale = scale[best_axis];
        uint32_t i = first, j = first + count; /* [i, j) not yet placed */
        while (i < j) {
            if (bin_of(b->centroids[3 * (size_t)items[i] + (size_t)best_axis], axis_lo, axis_scale) <=
                best_split) {
                i++;
            } else {
                uint32_t t = items[i];
                items[i] = items[--j];
                items[j] = t;
            }
        }
        mid = i;
        if (mid == first || mid == first + count) mid = first + count / 2;
    }
    /* Capacity is 2 count - 1 nodes: a binary tree with count leaves at most. */
    uint32_t left = b->node_count;
    b->node_count += 2;
    b->nodes[node].first = left;
    b->nodes[node].count = 0;
    build_binary(b, left, first, mid - first, depth + 1);
    build_binary(b, left + 1, mid, first + count - mid, depth + 1);
}

/* --- Collapsing to four children ------------------------------------------ */

typedef struct collapser {
    const bin_node *bin;
    accel_bvh4_node *nodes;
    uint32_t node_count;
    uint32_t depth;
} collapser;

static void set_slot(accel_bvh4_node *n, int k, const hr_bounds *b, uint32_t ref, uint32_t count)
{
    const double lo[3] = {b->lo.x, b->lo.y, b->lo.z}, hi[3] = {b->hi.x, b->hi.y, b->hi.z};
    for (int a = 0; a < 3; a++) {
        n->lo[a][k] = accel_float_down(lo[a]);
        n->hi[a][k] = accel_float_up(hi[a]);
    }
    n->ref[k] = ref;
    n->count[k] = count;
}

static void clear_slot(accel_bvh4_node *n, int k)
{
    for (int a = 0; a < 3; a++) n->lo[a][k] = INFINITY, n->hi[a][k] = -INFINITY;
    n->ref[k] = ACCEL_BVH4_EMPTY;
    n->count[k] = 0;
}

/* Makes the 4-wide node `out` for binary inner node `b`. */
static void collapse(collapser *c, uint32_t out, uint32_t b, uint32_t depth)
{
    if (depth > c->depth) c->depth = depth;
    uint32_t kids[4] = {c->bin[b].first, c->bin[b].first + 1, 0, 0};
    int n = 2;
    while (n < 4) {
        int widest = -1;
        double widest_area = -1.0;
        for (int k = 0; k < n; k++) {
            const bin_node *kid = &c->bin[kids[k]];
            double a = bounds_area(&kid->box);
            if (kid->count == 0 && a > widest_area) widest = k, widest_area = a;
        }
        if (widest < 0) break;
        uint32_t first = c->bin[kids[widest]].first;
        kids[widest] = first;
        kids[n++] = first + 1;
    }
    accel_bvh4_node *node = &c->nodes[out];
    for (int k = 0; k < 4; k++) {
        if (k >= n) {
            clear_slot(node, k);
            continue;
        }
        const bin_node *kid = &c->bin[kids[k]];
        if (kid->count > 0) {
            set_slot(node, k, &kid->box, kid->first, kid->count);
        } else {
            uint32_t child = c->node_count++;
            set_slot(&c->nodes[out], k, &kid->box, child, 0);
            collapse(c, child, kids[k], depth + 1);
        }
    }
}

int accel_bvh4_build(accel_bvh4 *bvh, const hr_bounds *boxes, uint32_t count,
                     const accel_bvh4_options *options)
{
    void *(*alloc)(size_t) = options->alloc ? options->alloc : default_alloc;
    void (*dealloc)(void *) = options->free ? options->free : free;
    memset(bvh, 0, sizeof *bvh);
    bvh->free_fn = dealloc;
    if (count == 0) return 0;
    if (count > ACCEL_BVH4_MAX_ITEMS) return -2;
    builder b = {0};
    b.max_leaf = options->max_leaf < 1 ? 1 : options->max_leaf > 16 ? 16 : options->max_leaf;
    b.traversal_cost = options->traversal_cost;
    b.node_cap = 2 * count - 1;
    b.nodes = alloc((size_t)b.node_cap * sizeof *b.nodes);
    b.items = alloc((size_t)count * sizeof *b.items);
    b.centroids = alloc((size_t)count * 3 * sizeof *b.centroids);
    nbox *nboxes = alloc((size_t)count * sizeof *nboxes);
    b.boxes = nboxes;
    if (!b.nodes || !b.items || !b.centroids || !nboxes) goto out_of_memory;
    for (uint32_t i = 0; i < count; i++) {
        const hr_bounds *ib = &boxes[i];
        nboxes[i] = nbox_of(ib);
        double *c = b.centroids + 3 * (size_t)i;
        c[0] = 0.5 * ib->lo.x + 0.5 * ib->hi.x;
        c[1] = 0.5 * ib->lo.y + 0.5 * ib->hi.y;
        c[2] = 0.5 * ib->lo.z + 0.5 * ib->hi.z;
        b.items[i] = i;
    }
    b.node_count = 1;
    build_binary(&b, 0, 0, count, 0);
    dealloc(b.centroids);
    b.centroids = NULL;
    dealloc(nboxes);
    nboxes = NULL;

    /* Each 4-wide node stands for at least one binary inner node; the root
     * exists even when the binary root is a leaf. */
    uint32_t inner = 0;
    for (uint32_t i = 0; i < b.node_count; i++) inner += b.nodes[i].count == 0;
    collapser c = {b.nodes, alloc((size_t)(inner ? inner : 1) * sizeof(accel_bvh4_node)), 1, 1};
    if (!c.nodes) goto out_of_memory;
    if (b.nodes[0].count > 0) {
        set_slot(&c.nodes[0], 0, &b.nodes[0].box, 0, b.nodes[0].count);
        for (int k = 1; k < 4; k++) clear_slot(&c.nodes[0], k);
    } else {
        collapse(&c, 0, 0, 1);
    }
    dealloc(b.nodes);
    bvh->nodes = c.nodes;
    bvh->node_count = c.node_count;
    bvh->items = b.items;
    bvh->item_count = count;
    bvh->depth = c.depth;
    return 0;

out_of_memory:
    dealloc(nboxes);
    dealloc(b.nodes);
    dealloc(b.items);
    dealloc(b.centroids);
    return -1;
}

void accel_bvh4_release(accel_bvh4 *bvh)
{
    void (*dealloc)(void *) = bvh->free_fn ? bvh->free_fn : free;
    dealloc(bvh->nodes);
    dealloc(bvh->items);
    memset(bvh, 0, sizeof *bvh);
}
