/* Building the 4-wide BVH: a binary tree by binned SAH over the items'
 * centroids (16 bins per axis), built top-down with the items partitioned
 * in place (so every leaf is a run of `items`), then collapsed to four
 * children a node: starting from a node's two children, the inner child of
 * largest surface area is replaced by its own two until there are four or
 * only leaves. Child boxes are then rounded outward to float.
 *
 * Large subtrees are built on threads of their own (options->threads): a
 * node's right child goes to a new thread, with the right half of the
 * items (a range of `items` no other thread touches) and a range of
 * binary nodes of its own, the one it would have started at had its left
 * sibling's subtree taken the most nodes it can (2 n - 2 below its root).
 * Every decision reads only the node's own items, so the binary tree's
 * nodes and links are the serial build's; only unused slots may lie
 * between the ranges, and the collapse, which follows links, gives the
 * same 4-wide tree. */
#include "bvh4.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#ifdef __SSE2__
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

static hr_bounds empty_box(void)
{
    hr_bounds b = {{DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, -DBL_MAX, -DBL_MAX}};
    return b;
}

/* b <- b grown by o, each bound by fmin/fmax without the libm call (most
 * of the build's time otherwise): lower(acc, v) = v < acc ? v : acc,
 * higher(acc, v) = v > acc ? v : acc. SSE2's minpd(v, acc) is exactly
 * lower(acc, v) (NaN and signed zeros included) and maxpd(v, acc)
 * higher(acc, v): the six doubles lo.x .. hi.z go as three pairs, the middle one
 * (lo.z, hi.x) taking its low lane from the min and its high from the max. */
_Static_assert(sizeof(hr_bounds) == 6 * sizeof(double) && offsetof(hr_bounds, hi) == 3 * sizeof(double),
               "hr_bounds is six doubles, lo then hi");

static inline void grow(hr_bounds *b, const hr_bounds *o)
{
#ifdef __SSE2__
    double *bd = &b->lo.x;
    const double *od = &o->lo.x;
    const __m128d o01 = _mm_loadu_pd(od), o23 = _mm_loadu_pd(od + 2), o45 = _mm_loadu_pd(od + 4);
    const __m128d b01 = _mm_loadu_pd(bd), b23 = _mm_loadu_pd(bd + 2), b45 = _mm_loadu_pd(bd + 4);
    _mm_storeu_pd(bd, _mm_min_pd(o01, b01));
    _mm_storeu_pd(bd + 2, _mm_move_sd(_mm_max_pd(o23, b23), _mm_min_pd(o23, b23)));
    _mm_storeu_pd(bd + 4, _mm_max_pd(o45, b45));
#else
#define lower(acc, v) ((v) < (acc) ? (v) : (acc))
#define higher(acc, v) ((v) > (acc) ? (v) : (acc))
    b->lo.x = lower(b->lo.x, o->lo.x), b->lo.y = lower(b->lo.y, o->lo.y);
    b->lo.z = lower(b->lo.z, o->lo.z);
    b->hi.x = higher(b->hi.x, o->hi.x), b->hi.y = higher(b->hi.y, o->hi.y);
    b->hi.z = higher(b->hi.z, o->hi.z);
#undef lower
#undef higher
#endif
}

static double area(const hr_bounds *b)
{
    double dx = b->hi.x - b->lo.x, dy = b->hi.y - b->lo.y, dz = b->hi.z - b->lo.z;
    if (dx < 0 || dy < 0 || dz < 0) return 0.0;
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

static inline double axis_of(const hr_vec3 *v, int axis)
{
    return axis == 0 ? v->x : axis == 1 ? v->y : v->z;
}

typedef struct builder {
    bin_node *nodes;
    uint32_t node_count, node_cap;
    uint32_t *items;
    const hr_bounds *boxes;
    double *centroids; /* 3 per input box; halves first: lo + hi overflows near DBL_MAX */
    uint32_t max_leaf;
    double traversal_cost;
    uint32_t threads; /* this subtree's share of options->threads (>= 1) */
    /* One node's bins, used before build_binary recurses: here rather than
     * in its frame, which the recursion would multiply. Between nodes every
     * bin is empty (count 0, box empty_box()): a node empties the ones it
     * filled, so it pays for the bins its items reach, not for all 48. */
    hr_bounds bin_box[3][BINS], right_box[BINS];
    uint32_t bin_count[3][BINS];
} builder;

/* Clamped before the conversion, which is undefined for a value past int's
 * range: an infinite box has an infinite centroid, (c - lo) can then be
 * infinite or NaN (inf - inf, or inf times a zero scale), and those go to
 * the last bin and the first. The same bins as truncating first elsewhere. */
static inline int bin_of(double c, double lo, double scale)
{
    const double x = (c - lo) * scale;
    return x >= 0.0 ? (x < BINS ? (int)x : BINS - 1) : 0;
}

/* The union of items[first, first + count)'s boxes and the bounds of their
 * centroids: the root's, and the halves of a split the bins did not make. */
static void gather(const builder *b, uint32_t first, uint32_t count, hr_bounds *box,
                   hr_bounds *cbox)
{
    *box = empty_box(), *cbox = empty_box();
    for (uint32_t i = first; i < first + count; i++) {
        grow(box, &b->boxes[b->items[i]]);
        const double *c = b->centroids + 3 * (size_t)b->items[i];
        hr_bounds cb = {{c[0], c[1], c[2]}, {c[0], c[1], c[2]}};
        grow(cbox, &cb);
    }
}

static inline void grow_point(hr_bounds *b, const double c[3])
{
    const hr_bounds p = {{c[0], c[1], c[2]}, {c[0], c[1], c[2]}};
    grow(b, &p);
}

static void build_side_by_side(builder *b, uint32_t left, uint32_t first, uint32_t mid, uint32_t right_count,
                               uint32_t depth, const hr_bounds *left_box, const hr_bounds *left_cbox,
                               const hr_bounds *right_box, const hr_bounds *right_cbox);

/* Node `node` over items[first, first + count), whose boxes' union is box
 * and whose centroids' bounds are cbox. One pass bins the items on all
 * three axes; the sweep over the bins gives each side's box of the best
 * split, and the partition gathers each side's centroid bounds, so a
 * child's bounds cost no pass of their own. The sweeps skip empty bins, so
 * the choice is the one a sweep over every boundary makes (below). */
static void build_binary(builder *b, uint32_t node, uint32_t first, uint32_t count, uint32_t depth,
                         const hr_bounds *box, const hr_bounds *cbox)
{
    uint32_t *items = b->items;
    b->nodes[node].box = *box;
    b->nodes[node].first = first;
    b->nodes[node].count = count;
    if (count <= 1) return;

    double lo[3], scale[3];
    int binned[3];
    for (int axis = 0; axis < 3; axis++) {
        double l = axis_of(&cbox->lo, axis), h = axis_of(&cbox->hi, axis);
        lo[axis] = l, scale[axis] = BINS / (h - l);
        /* A subnormal spread gives an infinite scale: no binning possible. */
        binned[axis] = h > l && isfinite(scale[axis]);
    }
    hr_bounds (*bin_box)[BINS] = b->bin_box;
    uint32_t (*bin_count)[BINS] = b->bin_count;
#ifdef __SSE2__
    if (binned[0] && binned[1] && binned[2]) {
        /* The usual node: x and y binned together. maxpd(x, 0) sends
         * negatives and NaN to 0 as bin_of does, minpd(., 15) the rest past
         * the last bin to it, and the truncation is bin_of's. */
        const __m128d lo01 = _mm_loadu_pd(lo), scale01 = _mm_loadu_pd(scale);
        const __m128d zero = _mm_setzero_pd(), last = _mm_set1_pd(BINS - 1);
        for (uint32_t i = first; i < first + count; i++) {
            const double *c = b->centroids + 3 * (size_t)items[i];
            const hr_bounds *ib = &b->boxes[items[i]];
            const __m128d x01 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(c), lo01), scale01);
            const __m128i k01 = _mm_cvttpd_epi32(_mm_min_pd(_mm_max_pd(x01, zero), last));
            const int k0 = _mm_cvtsi128_si32(k01), k1 = _mm_cvtsi128_si32(_mm_srli_si128(k01, 4));
            const int k2 = bin_of(c[2], lo[2], scale[2]);
            bin_count[0][k0]++, bin_count[1][k1]++, bin_count[2][k2]++;
            grow(&bin_box[0][k0], ib);
            grow(&bin_box[1][k1], ib);
            grow(&bin_box[2][k2], ib);
        }
    } else
#endif
    if (binned[0] || binned[1] || binned[2]) {
        for (uint32_t i = first; i < first + count; i++) {
            const double *c = b->centroids + 3 * (size_t)items[i];
            const hr_bounds *ib = &b->boxes[items[i]];
            for (int axis = 0; axis < 3; axis++) {
                if (!binned[axis]) continue;
                int k = bin_of(c[axis], lo[axis], scale[axis]);
                bin_count[axis][k]++;
                grow(&bin_box[axis][k], ib);
            }
        }
    }
    /* The sweeps visit only the filled bins (filled[0 .. m), in bin order):
     * an empty bin's boundary splits the items as the one before it does,
     * at the same cost, and adds nothing to a side's box. */
    double best_cost = DBL_MAX;
    int best_axis = -1, best_split = 0;
    hr_bounds best_left = empty_box(), best_right = empty_box();
    uint8_t filled[3][BINS];
    int filled_count[3] = {0, 0, 0};
    for (int axis = 0; axis < 3; axis++) {
        if (!binned[axis]) continue;
        const hr_bounds *bins = bin_box[axis];
        const uint32_t *counts = bin_count[axis];
        uint8_t *f = filled[axis];
        int m = 0;
        for (int k = 0; k < BINS; k++)
            if (counts[k]) f[m++] = (uint8_t)k;
        filled_count[axis] = m;
        /* right_*[j]: the union of filled bins j .. m - 1. */
        hr_bounds *right_box = b->right_box;
        double right_area[BINS];
        uint32_t right_count[BINS];
        hr_bounds acc = empty_box();
        uint32_t n = 0;
        for (int j = m - 1; j > 0; j--) {
            grow(&acc, &bins[f[j]]);
            n += counts[f[j]];
            right_box[j] = acc;
            right_area[j] = area(&acc);
            right_count[j] = n;
        }
        acc = empty_box();
        n = 0;
        for (int j = 0; j + 1 < m; j++) {
            grow(&acc, &bins[f[j]]);
            n += counts[f[j]];
            double cost = area(&acc) * n + right_area[j + 1] * right_count[j + 1];
            if (cost < best_cost) {
                best_cost = cost, best_axis = axis, best_split = f[j];
                best_left = acc, best_right = right_box[j + 1];
            }
        }
    }
    for (int axis = 0; axis < 3; axis++)
        for (int j = 0; j < filled_count[axis]; j++) {
            bin_count[axis][filled[axis][j]] = 0;
            bin_box[axis][filled[axis][j]] = empty_box();
        }
    double parent_area = area(box);
    double split_cost = parent_area > 0 ? b->traversal_cost + best_cost / parent_area : DBL_MAX;
    uint32_t mid;
    hr_bounds left_box, right_box, left_cbox = empty_box(), right_cbox = empty_box();
    int gathered = 0;
    if (best_axis < 0 || depth >= ACCEL_BVH_SAH_DEPTH) {
        /* All centroids coincide, or SAH has gone deep (geometric spacing
         * can make it peel one item off per level): halve the range, which
         * bounds the rest of the tree to log2(count) levels, so the whole
         * tree stays within ACCEL_BVH_MAX_DEPTH. */
        if (count <= b->max_leaf && best_axis < 0) return;
        mid = first + count / 2;
    } else {
        if (count <= b->max_leaf && (double)count <= split_cost) return;
        const int axis = best_axis;
        uint32_t i = first, j = first + count; /* [i, j) not yet placed */
        while (i < j) {
            const double *c = b->centroids + 3 * (size_t)items[i];
            if (bin_of(c[axis], lo[axis], scale[axis]) <= best_split) {
                grow_point(&left_cbox, c);
                i++;
            } else {
                grow_point(&right_cbox, c);
                uint32_t t = items[i];
                items[i] = items[--j];
                items[j] = t;
            }
        }
        mid = i;
        gathered = mid > first && mid < first + count;
        if (!gathered) mid = first + count / 2;
        left_box = best_left, right_box = best_right;
    }
    if (!gathered) {
        gather(b, first, mid - first, &left_box, &left_cbox);
        gather(b, mid, first + count - mid, &right_box, &right_cbox);
    }
    /* Capacity is 2 count - 1 nodes: a binary tree with count leaves at most. */
    uint32_t left = b->node_count;
    b->node_count += 2;
    b->nodes[node].first = left;
    b->nodes[node].count = 0;
    const uint32_t right_count = first + count - mid;
    if (b->threads > 1 && right_count >= ACCEL_BVH4_PARALLEL_ITEMS && mid - first >= ACCEL_BVH4_PARALLEL_ITEMS) {
        build_side_by_side(b, left, first, mid, right_count, depth + 1, &left_box, &left_cbox, &right_box,
                           &right_cbox);
        return;
    }
    build_binary(b, left, first, mid - first, depth + 1, &left_box, &left_cbox);
    build_binary(b, left + 1, mid, right_count, depth + 1, &right_box, &right_cbox);
}

/* A right subtree built on a thread of its own (build_side_by_side). */
typedef struct side_job {
    builder b; /* its own bins and node range */
    uint32_t node, first, count, depth;
    hr_bounds box, cbox;
} side_job;

static void *build_side(void *arg)
{
    side_job *job = arg;
    build_binary(&job->b, job->node, job->first, job->count, job->depth, &job->box, &job->cbox);
    return NULL;
}

/* The children left (items first .. mid - 1) and left + 1 (mid .. mid +
 * right_count - 1) of a node: the right one on a new thread with half of
 * this subtree's threads, its nodes from where the left one's can no longer
 * reach; the left one here. If no thread can be started, the right one
 * follows here, in the same range. */
static void build_side_by_side(builder *b, uint32_t left, uint32_t first, uint32_t mid, uint32_t right_count,
                               uint32_t depth, const hr_bounds *left_box, const hr_bounds *left_cbox,
                               const hr_bounds *right_box, const hr_bounds *right_cbox)
{
    side_job *job = malloc(sizeof *job);
    if (job) {
        job->b = *b; /* between nodes every bin is empty: the copy's are too */
        job->b.node_count = b->node_count + 2 * (mid - first) - 2;
        job->b.threads = b->threads / 2;
        job->node = left + 1, job->first = mid, job->count = right_count, job->depth = depth;
        job->box = *right_box, job->cbox = *right_cbox;
    }
    pthread_t thread;
    const int started = job && pthread_create(&thread, NULL, build_side, job) == 0;
    b->threads -= started ? b->threads / 2 : 0;
    build_binary(b, left, first, mid - first, depth, left_box, left_cbox);
    if (started) pthread_join(thread, NULL);
    else if (job) build_side(job);
    else build_binary(b, left + 1, mid, right_count, depth, right_box, right_cbox);
    if (job) b->node_count = job->b.node_count; /* past the left's, whose range comes first */
    free(job);
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
            double a = area(&kid->box);
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
    b.boxes = boxes;
    b.max_leaf = options->max_leaf < 1 ? 1 : options->max_leaf > 16 ? 16 : options->max_leaf;
    b.traversal_cost = options->traversal_cost;
    b.threads = options->threads > 1 ? options->threads : 1;
    b.node_cap = 2 * count - 1;
    b.nodes = alloc((size_t)b.node_cap * sizeof *b.nodes);
    b.items = alloc((size_t)count * sizeof *b.items);
    b.centroids = alloc((size_t)count * 3 * sizeof *b.centroids);
    if (!b.nodes || !b.items || !b.centroids) goto out_of_memory;
    for (uint32_t i = 0; i < count; i++) {
        const hr_bounds *ib = &boxes[i];
        double *c = b.centroids + 3 * (size_t)i;
        c[0] = 0.5 * ib->lo.x + 0.5 * ib->hi.x;
        c[1] = 0.5 * ib->lo.y + 0.5 * ib->hi.y;
        c[2] = 0.5 * ib->lo.z + 0.5 * ib->hi.z;
        b.items[i] = i;
    }
    for (int axis = 0; axis < 3; axis++)
        for (int k = 0; k < BINS; k++) b.bin_box[axis][k] = empty_box();
    b.node_count = 1;
    hr_bounds box, cbox;
    gather(&b, 0, count, &box, &cbox);
    build_binary(&b, 0, 0, count, 0, &box, &cbox);
    dealloc(b.centroids);
    b.centroids = NULL;

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
    /* The collapse used fewer nodes than the bound it was given room for
     * (about half): keep only those. */
    if (c.node_count < inner) {
        accel_bvh4_node *exact = alloc((size_t)c.node_count * sizeof *exact);
        if (!exact) {
            dealloc(c.nodes);
            b.nodes = NULL;
            goto out_of_memory;
        }
        memcpy(exact, c.nodes, (size_t)c.node_count * sizeof *exact);
        dealloc(c.nodes);
        c.nodes = exact;
    }
    bvh->nodes = c.nodes;
    bvh->node_count = c.node_count;
    bvh->items = b.items;
    bvh->item_count = count;
    bvh->depth = c.depth;
    bvh->extent = 0.0;
    for (uint32_t i = 0; i < count; i++) {
        const double v[6] = {boxes[i].lo.x, boxes[i].lo.y, boxes[i].lo.z,
                             boxes[i].hi.x, boxes[i].hi.y, boxes[i].hi.z};
        for (int k = 0; k < 6; k++)
            if (!(fabs(v[k]) <= bvh->extent)) bvh->extent = isnan(v[k]) ? INFINITY : fabs(v[k]);
    }
    const double far = ACCEL_FAR_ORIGIN * (2.0 * bvh->extent + 0x1p-20);
    bvh->origin_reach = options->move_far_origins && far < ACCEL_CULL_RANGE ? far : ACCEL_CULL_RANGE;
    return 0;

out_of_memory:
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
