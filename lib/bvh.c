/* A BVH over boxes, built top-down with the surface area heuristic over
 * binned centroids (16 bins per axis), stored as a flat array with the two
 * children of an inner node side by side. */
#include "bvh.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BINS 16
#define MAX_LEAF 4
/* Relative cost of visiting a node against testing one object. */
#define TRAVERSAL_COST 0.5

static hr_bounds empty_box(void)
{
    hr_bounds b = {{DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, -DBL_MAX, -DBL_MAX}};
    return b;
}

/* fmin/fmax without the libm call (they are most of the build's time): a
 * NaN in `o` leaves the running box as it was, as fmin/fmax would. */
static inline double lower(double acc, double v) { return v < acc ? v : acc; }
static inline double higher(double acc, double v) { return v > acc ? v : acc; }

static void grow(hr_bounds *b, const hr_bounds *o)
{
    b->lo.x = lower(b->lo.x, o->lo.x), b->lo.y = lower(b->lo.y, o->lo.y);
    b->lo.z = lower(b->lo.z, o->lo.z);
    b->hi.x = higher(b->hi.x, o->hi.x), b->hi.y = higher(b->hi.y, o->hi.y);
    b->hi.z = higher(b->hi.z, o->hi.z);
}

static double area(const hr_bounds *b)
{
    double dx = b->hi.x - b->lo.x, dy = b->hi.y - b->lo.y, dz = b->hi.z - b->lo.z;
    if (dx < 0 || dy < 0 || dz < 0) return 0.0;
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

static double axis_of(const hr_vec3 *v, int axis) { return axis == 0 ? v->x : axis == 1 ? v->y : v->z; }

/* Halves first: lo + hi overflows for boxes near +-DBL_MAX. */
static double centroid(const hr_bounds *b, int axis)
{
    return 0.5 * axis_of(&b->lo, axis) + 0.5 * axis_of(&b->hi, axis);
}

typedef struct builder {
    hr_bvh *bvh;
    const hr_bounds *boxes;
    int32_t node_cap;
} builder;

static int32_t new_node(builder *b)
{
    if (b->bvh->node_count == b->node_cap) return -1; /* capacity is 2n-1: never hit */
    return b->bvh->node_count++;
}

/* Bin index of a centroid along an axis of the centroid bounds. */
static int bin_of(double c, double lo, double scale)
{
    int i = (int)((c - lo) * scale);
    return i < 0 ? 0 : i >= BINS ? BINS - 1 : i;
}

static void build(builder *b, int32_t node, int32_t first, int32_t count, int32_t depth)
{
    hr_bvh *bvh = b->bvh;
    int32_t *items = bvh->items;
    hr_bounds box = empty_box(), cbox = empty_box();
    for (int32_t i = first; i < first + count; i++) {
        const hr_bounds *ib = &b->boxes[items[i]];
        grow(&box, ib);
        hr_vec3 c = {centroid(ib, 0), centroid(ib, 1), centroid(ib, 2)};
        hr_bounds cb = {c, c};
        grow(&cbox, &cb);
    }
    bvh->nodes[node].box = box;
    bvh->nodes[node].first = first;
    bvh->nodes[node].count = count;
    if (count <= 1) return;

    /* Best split over the three axes by binned SAH. */
    double best_cost = DBL_MAX;
    int best_axis = -1, best_split = 0;
    for (int axis = 0; axis < 3; axis++) {
        double lo = axis_of(&cbox.lo, axis), hi = axis_of(&cbox.hi, axis);
        double scale = BINS / (hi - lo);
        /* A subnormal spread gives an infinite scale: no binning possible. */
        if (!(hi > lo) || !isfinite(scale)) continue;
        hr_bounds bin_box[BINS];
        int32_t bin_count[BINS] = {0};
        for (int k = 0; k < BINS; k++) bin_box[k] = empty_box();
        for (int32_t i = first; i < first + count; i++) {
            const hr_bounds *ib = &b->boxes[items[i]];
            int k = bin_of(centroid(ib, axis), lo, scale);
            bin_count[k]++;
            grow(&bin_box[k], ib);
        }
        double right_area[BINS];
        int32_t right_count[BINS];
        hr_bounds acc = empty_box();
        int32_t n = 0;
        for (int k = BINS - 1; k > 0; k--) {
            grow(&acc, &bin_box[k]);
            n += bin_count[k];
            right_area[k] = area(&acc);
            right_count[k] = n;
        }
        acc = empty_box();
        n = 0;
        for (int k = 0; k < BINS - 1; k++) {
            grow(&acc, &bin_box[k]);
            n += bin_count[k];
            if (n == 0 || right_count[k + 1] == 0) continue;
            double cost = area(&acc) * n + right_area[k + 1] * right_count[k + 1];
            if (cost < best_cost) best_cost = cost, best_axis = axis, best_split = k;
        }
    }
    double parent_area = area(&box);
    double leaf_cost = (double)count;
    double split_cost = parent_area > 0 ? TRAVERSAL_COST + best_cost / parent_area : DBL_MAX;
    int32_t mid;
    if (best_axis < 0 || depth >= HR_BVH_SAH_DEPTH) {
        /* All centroids coincide, or SAH has gone deep (geometric spacing
         * can make it split one item off at a time): halve the range, which
         * bounds the rest of the tree to log2(count) levels, so the whole
         * tree stays within HR_BVH_MAX_DEPTH. */
        if (count <= MAX_LEAF && best_axis < 0) return;
        if (count <= 1) return;
        mid = first + count / 2;
    } else {
        if (count <= MAX_LEAF && leaf_cost <= split_cost) return;
        double lo = axis_of(&cbox.lo, best_axis), hi = axis_of(&cbox.hi, best_axis);
        double scale = BINS / (hi - lo);
        int32_t i = first, j = first + count - 1;
        while (i <= j) {
            if (bin_of(centroid(&b->boxes[items[i]], best_axis), lo, scale) <= best_split) {
                i++;
            } else {
                int32_t t = items[i];
                items[i] = items[j];
                items[j--] = t;
            }
        }
        mid = i;
        if (mid == first || mid == first + count) mid = first + count / 2;
    }
    int32_t left = new_node(b), right = new_node(b);
    if (left < 0 || right < 0) return;
    bvh->nodes[node].first = left;
    bvh->nodes[node].count = 0;
    build(b, left, first, mid - first, depth + 1);
    build(b, right, mid, first + count - mid, depth + 1);
}

int hr_bvh_build(hr_bvh *bvh, const hr_bounds *boxes, int32_t count)
{
    memset(bvh, 0, sizeof *bvh);
    if (count <= 0) return 1;
    builder b = {bvh, boxes, 2 * count - 1};
    bvh->nodes = malloc((size_t)b.node_cap * sizeof *bvh->nodes);
    bvh->items = malloc((size_t)count * sizeof *bvh->items);
    if (!bvh->nodes || !bvh->items) {
        hr_bvh_release(bvh);
        return 0;
    }
    for (int32_t i = 0; i < count; i++) bvh->items[i] = i;
    bvh->item_count = count;
    bvh->node_count = 1;
    build(&b, 0, 0, count, 0);
    if (bvh->node_count > 1) {
        size_t n_pairs = (size_t)(bvh->node_count - 1) / 2;
        bvh->pairs = malloc(n_pairs * HR_BVH_PAIR * sizeof *bvh->pairs);
        if (!bvh->pairs) {
            hr_bvh_release(bvh);
            return 0;
        }
        for (size_t k = 0; k < n_pairs; k++) {
            const hr_bounds *l = &bvh->nodes[2 * k + 1].box, *r = &bvh->nodes[2 * k + 2].box;
            const double v[HR_BVH_PAIR] = {l->lo.x, r->lo.x, l->lo.y, r->lo.y, l->lo.z, r->lo.z,
                                           l->hi.x, r->hi.x, l->hi.y, r->hi.y, l->hi.z, r->hi.z};
            memcpy(bvh->pairs + k * HR_BVH_PAIR, v, sizeof v);
        }
    }
    return 1;
}

void hr_bvh_release(hr_bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->items);
    free(bvh->pairs);
    memset(bvh, 0, sizeof *bvh);
}
