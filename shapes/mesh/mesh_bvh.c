/* The mesh's own BVH: binned SAH over triangle centroids, built top-down
 * with an explicit stack (no recursion, whatever the input), in O(n log n):
 * each level looks at each triangle a constant number of times, and the
 * depth is bounded. Below MESH_BVH_SAH_DEPTH levels, or when the centroids
 * of a node coincide, a node is split at the median instead, which halves
 * it: a pathological file (a million triangles stacked on one point) still
 * gives a tree no deeper than MESH_BVH_MAX_DEPTH.
 *
 * The build works on one array of items (a triangle's box, its centre and
 * its number, 40 bytes) that it partitions in place, so each level reads
 * the array front to back. A node costs two passes over its items: one
 * bins them on all three axes at once, one partitions them and gathers the
 * bounds of each side's centres; the boxes of the two sides come from the
 * bins (a union of float boxes is exact), so no pass is spent on bounds.
 *
 * Nodes are laid out depth first (left child next to its parent), each
 * interior node holding its two children's boxes (mesh.h), and the
 * triangles are put in leaf order, so a leaf is a run of the corner array. */
#include <float.h>
#include <math.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "mesh.h"

#define BINS 16
/* The cost of visiting a node, in triangle tests (the SAH's constant). A
 * box test is cheaper than the watertight test, but each node costs 32
 * bytes: at 4, leaves hold about 4 triangles and the nodes take about 11
 * bytes a triangle (a third of what 1 gives) for a few percent more work
 * per ray. */
#define TRAVERSAL_COST 4.0

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

/* x, y, z and a fourth lane kept at 0, so that the binning loads a box
 * as two SSE vectors. */
typedef struct box {
    float lo[4], hi[4];
} box;

static void box_empty(box *b)
{
    for (int a = 0; a < 3; a++) b->lo[a] = INFINITY, b->hi[a] = -INFINITY;
    b->lo[3] = b->hi[3] = 0.0f;
}

/* Written as selections, not conditional stores, so that they compile to
 * min and max instructions without branches. */
static float min_f(float a, float b)
{
    return a < b ? a : b;
}

static float max_f(float a, float b)
{
    return a > b ? a : b;
}

static void box_grow(box *restrict b, const box *restrict o)
{
    for (int a = 0; a < 3; a++) {
        b->lo[a] = min_f(o->lo[a], b->lo[a]);
        b->hi[a] = max_f(o->hi[a], b->hi[a]);
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

/* A triangle as the build moves it: its conservative float box, the
 * box's centre (kept finite) and its number. */
typedef struct item {
    box b;
    float c[3];
    uint32_t tri; /* read with c as a fourth lane, masked off */
} item;

/* A node still to build: items[begin, end), the union of their boxes and
 * the bounds of their centres. */
typedef struct task {
    uint32_t begin, end;
    uint32_t parent;     /* node whose `index` names this right child */
    int32_t depth;
    int32_t is_right;
    box bounds, centres;
} task;

/* A node as the build makes it, with its own box (pack_nodes moves each
 * box into the parent). */
typedef struct built_node {
    float lo[3], hi[3];
    uint32_t index; /* leaf: first triangle; interior: right child */
    uint16_t count; /* > 0: a leaf */
    uint16_t axis;
} built_node;

typedef struct builder {
    item *items;
    built_node *nodes;
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
    out->lo[3] = out->hi[3] = 0.0f;
}

static void box_add_point(box *restrict b, const float *restrict p)
{
    for (int a = 0; a < 3; a++) {
        b->lo[a] = min_f(p[a], b->lo[a]);
        b->hi[a] = max_f(p[a], b->hi[a]);
    }
}

/* The task's bounds and centres, from its items (the root, and the halves
 * of a median split). */
static void gather_bounds(const builder *b, task *t)
{
    box_empty(&t->bounds);
    box_empty(&t->centres);
    for (uint32_t i = t->begin; i < t->end; i++) {
        box_grow(&t->bounds, &b->items[i].b);
        box_add_point(&t->centres, b->items[i].c);
    }
}

static void sift_by_axis(item *o, int axis, size_t root, size_t n)
{
    for (;;) {
        size_t child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && o[child].c[axis] < o[child + 1].c[axis]) child++;
        if (!(o[root].c[axis] < o[child].c[axis])) return;
        item t = o[root];
        o[root] = o[child], o[child] = t;
        root = child;
    }
}

/* Rearranges items[begin, end) so that the k-th smallest centre on `axis`
 * is at k, smaller ones before it and larger ones after: quickselect
 * (Hoare partition around the middle element), O(n) on average and
 * without recursion; after 64 rounds (an input built against the pivot
 * rule) the range is heapsorted instead, so the worst case is
 * O(n log n). */
static void select_median(builder *b, uint32_t begin, uint32_t end, int axis, uint32_t k)
{
    item *o = b->items;
    uint32_t lo = begin, hi = end - 1;
    for (int round = 0; lo < hi; round++) {
        if (round == 64) {
            const size_t n = (size_t)hi - lo + 1;
            item *r = o + lo;
            for (size_t i = n / 2; i-- > 0;) sift_by_axis(r, axis, i, n);
            for (size_t e = n; e-- > 1;) {
                item t = r[0];
                r[0] = r[e], r[e] = t;
                sift_by_axis(r, axis, 0, e);
            }
            return;
        }
        float pivot = o[lo + (hi - lo) / 2].c[axis];
        uint32_t i = lo, j = hi;
        while (i <= j) {
            while (o[i].c[axis] < pivot) i++;
            while (o[j].c[axis] > pivot) j--;
            if (i <= j) {
                item t = o[i];
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

/* Where a node's centres start on each axis, and the bins per unit
 * length (0 on an axis without extent). */
typedef struct binning {
    float lo[4], scale[4];
} binning;

/* The bins of an item's centre on the three axes: (c - lo) scale in float,
 * clamped to [0, BINS - 1] (a NaN, from an infinite difference times a
 * zero scale, to 0), truncated. Monotone in c, so a bin boundary is a
 * plane; the SSE2 and the scalar forms give the same bins (the same float
 * operations), and the same function bins and partitions. */
static void bins_of(const binning *g, const item *it, int out[4])
{
#if defined(__SSE2__)
    const __m128 lane_mask = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
    const __m128 c = _mm_and_ps(_mm_loadu_ps(it->c), lane_mask);
    __m128 k = _mm_mul_ps(_mm_sub_ps(c, _mm_loadu_ps(g->lo)), _mm_loadu_ps(g->scale));
    k = _mm_min_ps(_mm_max_ps(k, _mm_setzero_ps()), _mm_set1_ps((float)(BINS - 1)));
    _mm_storeu_si128((__m128i *)(void *)out, _mm_cvttps_epi32(k));
#else
    for (int a = 0; a < 3; a++) {
        float k = (it->c[a] - g->lo[a]) * g->scale[a];
        k = k > 0.0f ? k : 0.0f;
        k = k < (float)(BINS - 1) ? k : (float)(BINS - 1);
        out[a] = (int)k;
    }
    out[3] = 0;
#endif
}

typedef struct bin {
    box b;
    uint32_t count;
} bin;

static void bin_add(bin *into, const item *it)
{
    into->count++;
#if defined(__SSE2__)
    _mm_storeu_ps(into->b.lo, _mm_min_ps(_mm_loadu_ps(it->b.lo), _mm_loadu_ps(into->b.lo)));
    _mm_storeu_ps(into->b.hi, _mm_max_ps(_mm_loadu_ps(it->b.hi), _mm_loadu_ps(into->b.hi)));
#else
    box_grow(&into->b, &it->b);
#endif
}

typedef struct split {
    int axis, last_bin; /* left: bins 0..last_bin on axis */
    double cost;        /* count times half area, summed over the sides */
    box left, right;
} split;

/* The best binned SAH split of the task on any axis; cost INFINITY when
 * no axis separates its centres. One pass bins every item on all three
 * axes. */
static split best_split(const builder *b, const task *t, const binning *g)
{
    bin bins[3][BINS];
    for (int a = 0; a < 3; a++)
        for (int k = 0; k < BINS; k++) box_empty(&bins[a][k].b), bins[a][k].count = 0;
    for (uint32_t i = t->begin; i < t->end; i++) {
        const item *it = &b->items[i];
        int k[4];
        bins_of(g, it, k);
        bin_add(&bins[0][k[0]], it);
        bin_add(&bins[1][k[1]], it);
        bin_add(&bins[2][k[2]], it);
    }
    split best = {-1, 0, INFINITY, {{0}, {0}}, {{0}, {0}}};
    for (int a = 0; a < 3; a++) {
        if (!(g->scale[a] > 0.0f)) continue;
        /* Boxes, areas and counts to the right of each boundary, then a
         * sweep from the left. An empty bin changes neither side: its
         * boundary splits the items as the one before it does, at the
         * same cost, so it is not evaluated (most bins of a small node
         * are empty). */
        const bin *row = bins[a];
        box right_box[BINS];
        double right_area[BINS];
        uint32_t right_count[BINS];
        box acc;
        box_empty(&acc);
        double area = 0.0;
        uint32_t count = 0;
        for (int k = BINS - 1; k > 0; k--) {
            if (row[k].count) {
                box_grow(&acc, &row[k].b);
                count += row[k].count;
                area = box_half_area(&acc);
            }
            right_box[k] = acc;
            right_area[k] = area;
            right_count[k] = count;
        }
        box_empty(&acc);
        count = 0;
        for (int k = 0; k < BINS - 1; k++) {
            if (!row[k].count) continue;
            box_grow(&acc, &row[k].b);
            count += row[k].count;
            if (right_count[k + 1] == 0) break;
            double cost = count * box_half_area(&acc) + right_count[k + 1] * right_area[k + 1];
            if (cost < best.cost) {
                best.cost = cost, best.axis = a, best.last_bin = k;
                best.left = acc, best.right = right_box[k + 1];
            }
        }
    }
    return best;
}

/* Splits items[begin, end) of the task into the two children's tasks:
 * returns 0 for a leaf. */
static int split_node(builder *b, const task *t, task *left, task *right)
{
    const uint32_t n = t->end - t->begin;
    if (n <= 2) return 0;
    int widest = 0;
    double widest_extent = -1.0;
    binning g;
    memset(&g, 0, sizeof g);
    for (int a = 0; a < 3; a++) {
        double e = (double)t->centres.hi[a] - t->centres.lo[a];
        if (e > widest_extent) widest_extent = e, widest = a;
        g.lo[a] = t->centres.lo[a];
        g.scale[a] = e > 0.0 && isfinite(e) ? (float)(BINS / e) : 0.0f;
    }
    *left = (task){t->begin, 0, 0, t->depth + 1, 0, {{0}, {0}}, {{0}, {0}}};
    *right = (task){0, t->end, 0, t->depth + 1, 1, {{0}, {0}}, {{0}, {0}}};
    const int median = t->depth >= MESH_BVH_SAH_DEPTH || !(widest_extent > 0.0) ||
                       !isfinite(widest_extent);
    split s = {-1, 0, INFINITY, {{0}, {0}}, {{0}, {0}}};
    if (!median) s = best_split(b, t, &g);
    if (s.axis >= 0) {
        /* Split when a node visit plus the children's expected tests cost
         * less than testing the whole node. */
        const double area = box_half_area(&t->bounds);
        const double split_cost = area > 0 && isfinite(area) ? TRAVERSAL_COST + s.cost / area : 0.0;
        if (split_cost >= n && n <= MESH_BVH_MAX_LEAF) return 0;
        const int a = s.axis;
        box_empty(&left->centres);
        box_empty(&right->centres);
        uint32_t i = t->begin, j = t->end;
        while (i < j) {
            item *it = &b->items[i];
            int k[4];
            bins_of(&g, it, k);
            if (k[a] <= s.last_bin) {
                box_add_point(&left->centres, it->c);
                i++;
            } else {
                box_add_point(&right->centres, it->c);
                const item moved = *it;
                *it = b->items[--j];
                b->items[j] = moved;
            }
        }
        /* Both sides hold items: the sweep only took boundaries with
         * counts on either side. */
        left->end = right->begin = i;
        left->bounds = s.left;
        right->bounds = s.right;
        return 1;
    }
    if (n <= MESH_BVH_MAX_LEAF) return 0;
    const uint32_t mid = t->begin + n / 2;
    if (widest_extent > 0.0) select_median(b, t->begin, t->end, widest, mid);
    left->end = right->begin = mid;
    gather_bounds(b, left);
    gather_bounds(b, right);
    return 1;
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

static void build_nodes(builder *b, uint32_t count)
{
    task stack[MESH_BVH_MAX_DEPTH + 4];
    int top = 0;
    stack[top] = (task){0, count, 0, 0, 0, {{0}, {0}}, {{0}, {0}}};
    gather_bounds(b, &stack[top++]);
    while (top > 0) {
        const task t = stack[--top];
        const uint32_t self = b->node_count++;
        if (t.is_right) b->nodes[t.parent].index = self;
        built_node *node = &b->nodes[self];
        for (int a = 0; a < 3; a++) {
            node->lo[a] = nextafterf(t.bounds.lo[a], -INFINITY);
            node->hi[a] = nextafterf(t.bounds.hi[a], INFINITY);
        }
        task left, right;
        if (!split_node(b, &t, &left, &right)) {
            node->index = t.begin;
            node->count = (uint16_t)(t.end - t.begin);
            node->axis = 0;
            continue;
        }
        node->count = 0;
        /* The split axis orders traversal; the widest extent is a good
         * stand-in whichever axis the SAH picked. */
        node->axis = (uint16_t)centroid_axis_of(&t.bounds);
        right.parent = self;
        stack[top++] = right;
        stack[top++] = left;
    }
}

/* The built tree in the layout the traversal reads: the root's box and
 * kind in the mesh, each interior node holding its children's boxes.
 * Interior nodes keep their depth-first order, so a left child that is a
 * node is still the next one. */
static hr_status pack_nodes(mesh *m, const built_node *built, uint32_t count)
{
    const built_node *root = &built[0];
    memcpy(m->root_lo, root->lo, sizeof m->root_lo);
    memcpy(m->root_hi, root->hi, sizeof m->root_hi);
    m->root_index = root->count ? root->index : 0;
    m->root_count = root->count;
    m->node_count = 0;
    m->nodes = NULL;
    if (root->count) return HR_OK;
    const hr_host *host = m->host;
    uint32_t *rank = host->alloc(count * sizeof *rank);
    uint32_t interior = 0;
    if (!rank) return HR_ERROR_OUT_OF_MEMORY;
    for (uint32_t i = 0; i < count; i++) rank[i] = built[i].count ? 0 : interior++;
    m->nodes = host->alloc(interior * sizeof *m->nodes);
    if (!m->nodes) {
        host->free(rank);
        return HR_ERROR_OUT_OF_MEMORY;
    }
    for (uint32_t i = 0; i < count; i++) {
        if (built[i].count) continue;
        mesh_bvh_node *node = &m->nodes[rank[i]];
        const uint32_t children[2] = {i + 1, built[i].index};
        for (int k = 0; k < 2; k++) {
            const built_node *c = &built[children[k]];
            for (int a = 0; a < 3; a++) node->lo[a][k] = c->lo[a], node->hi[a][k] = c->hi[a];
            node->index[k] = c->count ? c->index : rank[children[k]];
            node->count[k] = c->count;
        }
        node->axis = built[i].axis;
    }
    m->node_count = interior;
    host->free(rank);
    return HR_OK;
}

hr_status mesh_bvh_build(mesh *m)
{
    const hr_host *host = m->host;
    const size_t n = m->triangle_count;
    builder b;
    memset(&b, 0, sizeof b);
    b.items = host->alloc(n * sizeof *b.items);
    b.nodes = host->alloc((2 * n - 1) * sizeof *b.nodes);
    uint32_t *corners = host->alloc(3 * n * sizeof *corners);
    uint32_t *corner_normals = m->corner_normals ? host->alloc(3 * n * sizeof *corner_normals) : NULL;
    hr_status st = HR_OK;
    if (!b.items || !b.nodes || !corners || (m->corner_normals && !corner_normals)) {
        st = HR_ERROR_OUT_OF_MEMORY;
        goto done;
    }
    for (uint32_t t = 0; t < n; t++) {
        item *it = &b.items[t];
        triangle_box(m, t, &it->b);
        for (int a = 0; a < 3; a++) {
            /* A box past float's range has infinite sides: keep its centre
             * finite so that binning and selection compare numbers. */
            float c = 0.5f * it->b.lo[a] + 0.5f * it->b.hi[a];
            if (isnan(c)) c = 0.0f;
            it->c[a] = fmaxf(-FLT_MAX, fminf(FLT_MAX, c));
        }
        it->tri = t;
    }
    build_nodes(&b, (uint32_t)n);
    /* Triangles in leaf order. */
    for (size_t i = 0; i < n; i++) {
        memcpy(corners + 3 * i, m->corners + 3 * (size_t)b.items[i].tri, 3 * sizeof *corners);
        if (corner_normals)
            memcpy(corner_normals + 3 * i, m->corner_normals + 3 * (size_t)b.items[i].tri,
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
    st = pack_nodes(m, b.nodes, b.node_count);
    if (st) goto done;
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
    host->free(b.items);
    host->free(b.nodes);
    host->free(corners);
    host->free(corner_normals);
    return st;
}
