/* The mesh's own BVH: binned SAH over triangle centroids, built top-down
 * with an explicit stack (no recursion, whatever the input), in O(n log n):
 * each level looks at each triangle a constant number of times, and the
 * depth is bounded. Below MESH_BVH_SAH_DEPTH levels, or when the centroids
 * of a node coincide, a node is split at the median instead, which halves
 * it: a pathological file (a million triangles stacked on one point) still
 * gives a tree no deeper than MESH_BVH_MAX_DEPTH.
 *
 * Nodes are laid out depth first (left child next to its parent), and the
 * triangles are put in leaf order, so a leaf is a run of the corner array. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "mesh.h"

#define BINS 16
/* The cost of visiting a node, in triangle tests (the SAH's constant). A
 * box test is cheaper than the watertight test, but each node costs 32
 * bytes: at 4, leaves hold about 4 triangles and the nodes take about 11
 * bytes a triangle (a third of what 1 gives) for a few percent more work
 * per ray. */
#define TRAVERSAL_COST 4.0

/* Float bounds of a double: rounded down (up), so the float box contains
 * the double one; beyond float's range, the widest box. */
static float float_down(double x)
{
    if (x > FLT_MAX) return FLT_MAX;
    if (x < -FLT_MAX) return -INFINITY;
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float float_up(double x)
{
    if (x < -FLT_MAX) return -FLT_MAX;
    if (x > FLT_MAX) return INFINITY;
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

typedef struct box {
    float lo[3], hi[3];
} box;

static void box_empty(box *b)
{
    for (int a = 0; a < 3; a++) b->lo[a] = INFINITY, b->hi[a] = -INFINITY;
}

static void box_grow(box *b, const box *o)
{
    for (int a = 0; a < 3; a++) {
        if (o->lo[a] < b->lo[a]) b->lo[a] = o->lo[a];
        if (o->hi[a] > b->hi[a]) b->hi[a] = o->hi[a];
    }
}

/* Half the surface area, in double (infinite boxes give infinity, which
 * only makes the SAH prefer median-like splits there). */
static double box_half_area(const box *b)
{
    double dx = (double)b->hi[0] - b->lo[0], dy = (double)b->hi[1] - b->lo[1],
           dz = (double)b->hi[2] - b->lo[2];
    if (!(dx >= 0)) return 0.0;
    return dx * dy + dy * dz + dz * dx;
}

typedef struct task {
    uint32_t begin, end; /* range of `order` */
    uint32_t parent;     /* node whose `index` names this right child */
    int32_t depth;
    int32_t is_right;
} task;

typedef struct builder {
    const mesh *m;
    box *boxes;        /* per triangle, float, conservative */
    float *centroids;  /* 3 per triangle: the box centre */
    uint32_t *order;   /* triangle numbers in leaf order */
    mesh_bvh_node *nodes;
    uint32_t node_count;
} builder;

static void triangle_box(const mesh *m, uint32_t t, box *out)
{
    const uint32_t *c = m->corners + 3 * (size_t)t;
    for (int a = 0; a < 3; a++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int k = 0; k < 3; k++) {
            const hr_vec3 *v = &m->vertices[c[k]];
            double x = a == 0 ? v->x : a == 1 ? v->y : v->z;
            if (x < lo) lo = x;
            if (x > hi) hi = x;
        }
        out->lo[a] = float_down(lo);
        out->hi[a] = float_up(hi);
    }
}

/* Rearranges order[begin, end) so that the items whose centroid on `axis`
 * is below the k-th smallest come first: iterative quickselect (Hoare
 * partition around the middle element), O(n) on average, no recursion. */
static void select_median(builder *b, uint32_t begin, uint32_t end, int axis, uint32_t k)
{
    uint32_t *o = b->order;
    const float *c = b->centroids;
    uint32_t lo = begin, hi = end - 1;
    while (lo < hi) {
        float pivot = c[3 * (size_t)o[lo + (hi - lo) / 2] + axis];
        uint32_t i = lo, j = hi;
        while (i <= j) {
            while (c[3 * (size_t)o[i] + axis] < pivot) i++;
            while (c[3 * (size_t)o[j] + axis] > pivot) j--;
            if (i <= j) {
                uint32_t t = o[i];
                o[i] = o[j], o[j] = t;
                i++;
                if (j == 0) break;
                j--;
            }
        }
        if (k <= j) hi = j;
        else if (k >= i) lo = i;
        else return;
    }
}

/* Chooses how to split order[begin, end) with the binned SAH; returns the
 * split position (begin < split < end), or 0 for a leaf. */
static uint32_t split_node(builder *b, const task *t, const box *bounds)
{
    const uint32_t n = t->end - t->begin;
    if (n <= 2) return 0;
    float cmin[3] = {INFINITY, INFINITY, INFINITY}, cmax[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = t->begin; i < t->end; i++) {
        const float *c = b->centroids + 3 * (size_t)b->order[i];
        for (int a = 0; a < 3; a++) {
            if (c[a] < cmin[a]) cmin[a] = c[a];
            if (c[a] > cmax[a]) cmax[a] = c[a];
        }
    }
    int widest = 0;
    double widest_extent = -1.0;
    for (int a = 0; a < 3; a++) {
        double e = (double)cmax[a] - cmin[a];
        if (e > widest_extent) widest_extent = e, widest = a;
    }
    int median = t->depth >= MESH_BVH_SAH_DEPTH || !(widest_extent > 0.0) ||
                 !isfinite(widest_extent);
    int best_axis = -1, best_bin = 0;
    double best_cost = INFINITY;
    if (!median) {
        for (int a = 0; a < 3; a++) {
            double extent = (double)cmax[a] - cmin[a];
            if (!(extent > 0.0)) continue;
            box bin_box[BINS];
            uint32_t bin_count[BINS] = {0};
            for (int k = 0; k < BINS; k++) box_empty(&bin_box[k]);
            const double scale = BINS * (1.0 - 1e-9) / extent;
            for (uint32_t i = t->begin; i < t->end; i++) {
                uint32_t tri = b->order[i];
                int k = (int)(((double)b->centroids[3 * (size_t)tri + a] - cmin[a]) * scale);
                k = k < 0 ? 0 : k >= BINS ? BINS - 1 : k;
                bin_count[k]++;
                box_grow(&bin_box[k], &b->boxes[tri]);
            }
            /* Areas and counts to the right of each boundary, then a sweep
             * from the left. */
            double right_area[BINS];
            uint32_t right_count[BINS];
            box acc;
            box_empty(&acc);
            uint32_t count = 0;
            for (int k = BINS - 1; k > 0; k--) {
                box_grow(&acc, &bin_box[k]);
                count += bin_count[k];
                right_area[k] = box_half_area(&acc);
                right_count[k] = count;
            }
            box_empty(&acc);
            count = 0;
            for (int k = 0; k < BINS - 1; k++) {
                box_grow(&acc, &bin_box[k]);
                count += bin_count[k];
                if (count == 0 || right_count[k + 1] == 0) continue;
                double cost = count * box_half_area(&acc) + right_count[k + 1] * right_area[k + 1];
                if (cost < best_cost) best_cost = cost, best_axis = a, best_bin = k;
            }
        }
        if (best_axis < 0) median = 1;
    }
    if (!median) {
        /* Split when a node visit plus the children's expected tests cost
         * less than testing the whole node. */
        const double area = box_half_area(bounds);
        const double split_cost = area > 0 && isfinite(area) ? TRAVERSAL_COST + best_cost / area : 0.0;
        if (split_cost >= n && n <= MESH_BVH_MAX_LEAF) return 0;
        const int a = best_axis;
        const double scale = BINS * (1.0 - 1e-9) / ((double)cmax[a] - cmin[a]);
        uint32_t i = t->begin, j = t->end;
        while (i < j) {
            uint32_t tri = b->order[i];
            int k = (int)(((double)b->centroids[3 * (size_t)tri + a] - cmin[a]) * scale);
            k = k < 0 ? 0 : k >= BINS ? BINS - 1 : k;
            if (k <= best_bin) {
                i++;
            } else {
                b->order[i] = b->order[--j];
                b->order[j] = tri;
            }
        }
        if (i > t->begin && i < t->end) return i;
    }
    if (n <= MESH_BVH_MAX_LEAF) return 0;
    const uint32_t mid = t->begin + n / 2;
    if (widest_extent > 0.0) select_median(b, t->begin, t->end, widest, mid);
    return mid;
}

static uint32_t centroid_axis_of(const box *bounds)
{
    uint32_t axis = 0;
    double widest = -1.0;
    for (int a = 0; a < 3; a++) {
        double e = (double)bounds->hi[a] - bounds->lo[a];
        if (e > widest) widest = e, axis = (uint32_t)a;
    }
    return axis;
}

static void build_nodes(builder *b)
{
    const mesh *m = b->m;
    task stack[MESH_BVH_MAX_DEPTH + 4];
    int top = 0;
    stack[top++] = (task){0, m->triangle_count, 0, 0, 0};
    while (top > 0) {
        task t = stack[--top];
        const uint32_t self = b->node_count++;
        if (t.is_right) b->nodes[t.parent].index = self;
        box bounds;
        box_empty(&bounds);
        for (uint32_t i = t.begin; i < t.end; i++) box_grow(&bounds, &b->boxes[b->order[i]]);
        mesh_bvh_node *node = &b->nodes[self];
        for (int a = 0; a < 3; a++) {
            node->lo[a] = nextafterf(bounds.lo[a], -INFINITY);
            node->hi[a] = nextafterf(bounds.hi[a], INFINITY);
        }
        uint32_t split = split_node(b, &t, &bounds);
        if (split == 0) {
            node->index = t.begin;
            node->count = (uint16_t)(t.end - t.begin);
            node->axis = 0;
            continue;
        }
        node->count = 0;
        node->axis = (uint16_t)centroid_axis_of(&bounds);
        /* The split axis orders traversal; the widest extent is a good
         * stand-in whichever axis the SAH picked. */
        stack[top++] = (task){split, t.end, self, t.depth + 1, 1};
        stack[top++] = (task){t.begin, split, self, t.depth + 1, 0};
    }
}

hr_status mesh_bvh_build(mesh *m)
{
    const hr_host *host = m->host;
    const size_t n = m->triangle_count;
    builder b;
    memset(&b, 0, sizeof b);
    b.m = m;
    b.boxes = host->alloc(n * sizeof *b.boxes);
    b.centroids = host->alloc(3 * n * sizeof *b.centroids);
    b.order = host->alloc(n * sizeof *b.order);
    b.nodes = host->alloc((2 * n - 1) * sizeof *b.nodes);
    uint32_t *corners = host->alloc(3 * n * sizeof *corners);
    uint32_t *corner_normals = m->corner_normals ? host->alloc(3 * n * sizeof *corner_normals) : NULL;
    hr_status st = HR_OK;
    if (!b.boxes || !b.centroids || !b.order || !b.nodes || !corners ||
        (m->corner_normals && !corner_normals)) {
        st = HR_ERROR_OUT_OF_MEMORY;
        goto done;
    }
    for (uint32_t t = 0; t < n; t++) {
        triangle_box(m, t, &b.boxes[t]);
        for (int a = 0; a < 3; a++) {
            /* A box past float's range has infinite sides: keep its centre
             * finite so that binning and selection compare numbers. */
            float c = 0.5f * b.boxes[t].lo[a] + 0.5f * b.boxes[t].hi[a];
            if (isnan(c)) c = 0.0f;
            b.centroids[3 * (size_t)t + a] = fmaxf(-FLT_MAX, fminf(FLT_MAX, c));
        }
        b.order[t] = t;
    }
    build_nodes(&b);
    /* Triangles in leaf order; the nodes trimmed to what was used. */
    for (size_t i = 0; i < n; i++) {
        memcpy(corners + 3 * i, m->corners + 3 * (size_t)b.order[i], 3 * sizeof *corners);
        if (corner_normals)
            memcpy(corner_normals + 3 * i, m->corner_normals + 3 * (size_t)b.order[i],
                   3 * sizeof *corner_normals);
    }
    host->free(m->corners);
    m->corners = corners;
    corners = NULL;
    if (corner_normals) {
        host->free(m->corner_normals);
        m->corner_normals = corner_normals;
        corner_normals = NULL;
    }
    m->nodes = host->alloc(b.node_count * sizeof *m->nodes);
    if (!m->nodes) {
        st = HR_ERROR_OUT_OF_MEMORY;
        goto done;
    }
    memcpy(m->nodes, b.nodes, b.node_count * sizeof *m->nodes);
    m->node_count = b.node_count;
    /* The object's bounds, exact: those of the corners of its triangles. */
    hr_vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * n; i++) {
        const hr_vec3 v = m->vertices[m->corners[i]];
        lo.x = fmin(lo.x, v.x), lo.y = fmin(lo.y, v.y), lo.z = fmin(lo.z, v.z);
        hi.x = fmax(hi.x, v.x), hi.y = fmax(hi.y, v.y), hi.z = fmax(hi.z, v.z);
    }
    m->bounds.lo = lo;
    m->bounds.hi = hi;
done:
    host->free(b.boxes);
    host->free(b.centroids);
    host->free(b.order);
    host->free(b.nodes);
    host->free(corners);
    host->free(corner_normals);
    return st;
}
