/* The 4-wide BVH on its own (accel/, linked in as a static library, so the
 * test can look at the tree):
 * - the build: every item in exactly one leaf, leaves within max_leaf, the
 *   depth within ACCEL_BVH_MAX_DEPTH (the walk's stack is sized from it) on
 *   SAH's worst case, every float child box containing the double boxes of
 *   everything below it, and no overflow or NaN near the ends of the range;
 * - the walks for SSE2 and AVX2 (accel_bvh4_walk_core, _avx2): the same
 *   leaves in the same order, with a callback that lowers tmax as hits do;
 * - the walk (nearest first, and in slot order): conservative. For random and hard rays (axis-parallel, tiny
 *   direction components, origins on slab planes, far origins, origins
 *   beyond float's range, rays that just touch a box's face or edge) every
 *   box that the ray meets within [tmin, tmax] by an exact slab test must
 *   have its leaf visited. The exact test is done in __float128: the
 *   inputs are doubles, and (b - o) / d to 113 bits decides every case
 *   whose answer is not a tie within 2^-100, so the rays that touch a box
 *   are built to touch it exactly (t_enter == t_exit in the reference);
 * - accel_bvh4_root_missed_on: never says a walk meets no root child when
 *   a walk (either order, either ISA) visits a leaf, on flat trees and
 *   rays that start beside them, a rounding away or more, and run away,
 *   along or into them, with directions and origins around its limits. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ACCEL_TEST_SEED 0x9e3779b97f4a7c15ull
#include "accel_test_rays.h"
#include "bvh4.h"
#include "hr_test.h"

/* --- the build ------------------------------------------------------------ */

static uint32_t depth_below(const accel_bvh4 *bvh, uint32_t node)
{
    const accel_bvh4_node *n = &bvh->nodes[node];
    uint32_t deepest = 0;
    for (int k = 0; k < 4; k++) {
        if (n->count[k] > 0 || n->ref[k] == ACCEL_BVH4_EMPTY) continue;
        uint32_t d = depth_below(bvh, n->ref[k]);
        if (d > deepest) deepest = d;
    }
    return 1 + deepest;
}

static int box_holds(const accel_bvh4_node *n, int k, const hr_bounds *b)
{
    return n->lo[0][k] <= b->lo.x && n->lo[1][k] <= b->lo.y && n->lo[2][k] <= b->lo.z &&
           n->hi[0][k] >= b->hi.x && n->hi[1][k] >= b->hi.y && n->hi[2][k] >= b->hi.z;
}

/* Every item below slot k of n lies inside slot outer_k of outer. */
static int items_within(const accel_bvh4 *bvh, const hr_bounds *boxes, const accel_bvh4_node *n,
                        int k, const accel_bvh4_node *outer, int outer_k)
{
    if (n->count[k] > 0) {
        int ok = 1;
        for (uint32_t i = n->ref[k]; i < n->ref[k] + n->count[k]; i++)
            ok &= box_holds(outer, outer_k, &boxes[bvh->items[i]]);
        return ok;
    }
    if (n->ref[k] == ACCEL_BVH4_EMPTY) return 1;
    const accel_bvh4_node *c = &bvh->nodes[n->ref[k]];
    int ok = 1;
    for (int j = 0; j < 4; j++) ok &= items_within(bvh, boxes, c, j, outer, outer_k);
    return ok;
}

/* Each item in exactly one leaf of at most max_leaf items, and inside the
 * box of every slot above it. */
static int tree_ok(const accel_bvh4 *bvh, const hr_bounds *boxes, uint32_t count, uint32_t max_leaf)
{
    int ok = bvh->item_count == count;
    char *seen = calloc(count, 1);
    if (!seen) return 0;
    for (uint32_t nidx = 0; nidx < bvh->node_count; nidx++) {
        const accel_bvh4_node *n = &bvh->nodes[nidx];
        for (int k = 0; k < 4; k++) {
            ok &= items_within(bvh, boxes, n, k, n, k);
            if (n->count[k] == 0) continue;
            ok &= n->count[k] <= max_leaf;
            for (uint32_t i = n->ref[k]; i < n->ref[k] + n->count[k]; i++) ok &= !seen[bvh->items[i]]++;
        }
    }
    for (uint32_t i = 0; i < count; i++) ok &= seen[i] == 1;
    free(seen);
    return ok;
}

static void test_build(void)
{
    enum { N = 20000 };
    hr_bounds *boxes = malloc(N * sizeof *boxes);
    const accel_bvh4_options opt = {.max_leaf = 4, .traversal_cost = 0.5};
    accel_bvh4 bvh;

    /* Boxes at x = 1.5^i with size 0.3 x: binned SAH puts all but the
     * largest few in the lowest bin, level after level. */
    enum { GEOMETRIC = 1500 };
    double x = 1;
    for (int i = 0; i < GEOMETRIC; i++, x *= 1.5)
        boxes[i] = (hr_bounds){{x - 0.3 * x, -0.3 * x, -0.3 * x}, {x + 0.3 * x, 0.3 * x, 0.3 * x}};
    CHECK(accel_bvh4_build(&bvh, boxes, GEOMETRIC, &opt) == 0);
    uint32_t d = depth_below(&bvh, 0);
    fprintf(stderr, "geometric spacing: depth %u (bound %d)\n", (unsigned)d, ACCEL_BVH_MAX_DEPTH);
    CHECK_MSG(d <= ACCEL_BVH_MAX_DEPTH && d == bvh.depth, "geometric: depth %u (recorded %u)",
              (unsigned)d, (unsigned)bvh.depth);
    CHECK(tree_ok(&bvh, boxes, GEOMETRIC, opt.max_leaf));
    accel_bvh4_release(&bvh);

    /* Random boxes of many sizes: the usual case, with leaves of 1 and 8. */
    for (int i = 0; i < N; i++) {
        double cx = between(-100, 100), cy = between(-100, 100), cz = between(-100, 100);
        double r = pow(10.0, between(-6, 1));
        boxes[i] = (hr_bounds){{cx - r, cy - r, cz - r}, {cx + r, cy + r, cz + r}};
    }
    for (uint32_t leaf = 1; leaf <= 8; leaf *= 8) {
        const accel_bvh4_options o = {.max_leaf = leaf, .traversal_cost = 1.0};
        CHECK(accel_bvh4_build(&bvh, boxes, N, &o) == 0);
        CHECK(tree_ok(&bvh, boxes, N, leaf));
        CHECK(bvh.depth == depth_below(&bvh, 0));
        accel_bvh4_release(&bvh);
    }

    /* Boxes near the ends of the double range: centroids must not overflow,
     * and their float boxes reach to infinity. */
    for (int i = 0; i < 64; i++) {
        double s = i % 2 ? 1.0 : -1.0;
        boxes[i] = (hr_bounds){{s * 1e308, i, 0}, {s * 1.7e308, i + 1.0, 1}};
    }
    CHECK(accel_bvh4_build(&bvh, boxes, 64, &opt) == 0);
    CHECK(tree_ok(&bvh, boxes, 64, opt.max_leaf));
    accel_bvh4_release(&bvh);

    /* A subnormal spread of centroids (no binning scale), and all at one
     * point: halving keeps the depth bounded. */
    for (int i = 0; i < 64; i++) boxes[i] = (hr_bounds){{i * 1e-320, 0, 0}, {i * 1e-320, 0, 0}};
    CHECK(accel_bvh4_build(&bvh, boxes, 64, &opt) == 0);
    CHECK(tree_ok(&bvh, boxes, 64, opt.max_leaf));
    accel_bvh4_release(&bvh);
    for (int i = 0; i < N; i++) boxes[i] = (hr_bounds){{1, 2, 3}, {1, 2, 3}};
    CHECK(accel_bvh4_build(&bvh, boxes, N, &opt) == 0);
    CHECK(tree_ok(&bvh, boxes, N, opt.max_leaf));
    CHECK(depth_below(&bvh, 0) <= ACCEL_BVH_MAX_DEPTH);
    accel_bvh4_release(&bvh);

    /* One box: a root with a single leaf slot; none: no nodes. */
    CHECK(accel_bvh4_build(&bvh, boxes, 1, &opt) == 0);
    CHECK(bvh.node_count == 1 && bvh.nodes[0].count[0] == 1 && bvh.nodes[0].ref[1] == ACCEL_BVH4_EMPTY);
    accel_bvh4_release(&bvh);
    CHECK(accel_bvh4_build(&bvh, boxes, 0, &opt) == 0);
    CHECK(bvh.nodes == NULL && bvh.node_count == 0);
    accel_bvh4_release(&bvh);
    free(boxes);
}

/* --- the walk ------------------------------------------------------------- */

typedef struct walk_record {
    char *visited; /* per item */
    const accel_bvh4 *bvh;
} walk_record;

static int record_leaf(void *user, uint32_t first, uint32_t count)
{
    walk_record *w = user;
    for (uint32_t i = first; i < first + count; i++) w->visited[w->bvh->items[i]] = 1;
    return ACCEL_WALK_GO_ON;
}

static long met_total; /* box meetings by the exact test, over every walk */

/* The leaves a walk visits, in order, with a callback that acts as a
 * scene's would: each leaf's items "hit" where the ray passes nearest their
 * box's centre, lowering *tmax, so the walk's pruning by tmax is exercised. */
typedef struct leaf_log {
    const hr_bounds *boxes;
    const accel_bvh4 *bvh;
    const hr_ray *ray;
    double tmin, *tmax;
    uint32_t first[4096], count[4096], n;
} leaf_log;

static int log_leaf(void *user, uint32_t first, uint32_t count)
{
    leaf_log *w = user;
    if (w->n < 4096) w->first[w->n] = first, w->count[w->n] = count;
    w->n++;
    const hr_vec3 o = w->ray->origin, d = w->ray->dir;
    for (uint32_t i = first; i < first + count; i++) {
        const hr_bounds *b = &w->boxes[w->bvh->items[i]];
        hr_vec3 c = {0.5 * (b->lo.x + b->hi.x), 0.5 * (b->lo.y + b->hi.y), 0.5 * (b->lo.z + b->hi.z)};
        double dd = d.x * d.x + d.y * d.y + d.z * d.z;
        double t = ((c.x - o.x) * d.x + (c.y - o.y) * d.y + (c.z - o.z) * d.z) / dd;
        if (t > w->tmin && t < *w->tmax) *w->tmax = t;
    }
    return ACCEL_WALK_GO_ON;
}

/* The nearest-first order, written plainly: the node test, the children
 * met sorted by entry with an insertion sort (stable: slot order on a
 * tie), stacked farthest first so the nearest is visited next; *tmax read
 * back after every leaf. The walk must visit the same leaves in the same
 * order (it ranks three or four children in lanes instead). Rays the walk
 * does not cull take its own every-leaf walk, and rays whose origin it
 * moves (accel_origin_far) its own walk too. */
static void reference_walk(const accel_bvh4 *bvh, const hr_ray *ray, double tmin, double *tmax,
                           leaf_log *log)
{
    accel_ray4 r;
    accel_ray4_init_as(&r, ray, tmin, 0);
    if (!bvh->nodes || !r.cull || !(bvh->extent <= ACCEL_CULL_RANGE) || accel_origin_far(bvh, ray)) {
        accel_bvh4_walk_core(bvh, ray, tmin, tmax, log_leaf, log, 1, 0);
        return;
    }
    const accel_f4 tmin4 = accel_f4_set(accel_ray4_tmin(&r, tmin));
    float tmax_f = accel_ray4_tmax(&r, *tmax);
    static uint32_t stack_ref[ACCEL_BVH4_STACK], stack_count[ACCEL_BVH4_STACK];
    static float stack_entry[ACCEL_BVH4_STACK];
    uint32_t top = 1;
    stack_ref[0] = 0, stack_count[0] = 0, stack_entry[0] = -INFINITY; /* the root */
    while (top > 0) {
        --top;
        if (stack_entry[top] > tmax_f) continue;
        const uint32_t ref = stack_ref[top], count = stack_count[top];
        if (count > 0) {
            log_leaf(log, ref, count);
            tmax_f = accel_ray4_tmax(&r, *tmax);
            continue;
        }
        const accel_bvh4_node *n = &bvh->nodes[ref];
        float entry[4];
        unsigned mask = accel_bvh4_test(&r, n, tmin4, accel_f4_set(tmax_f), entry);
        uint32_t kid[4], hits = 0;
        for (uint32_t c = 0; c < 4; c++) {
            if (!(mask >> c & 1)) continue;
            uint32_t j = hits++;
            while (j > 0 && entry[kid[j - 1]] > entry[c]) kid[j] = kid[j - 1], j--;
            kid[j] = c;
        }
        for (uint32_t j = hits; j-- > 0;) {
            stack_ref[top] = n->ref[kid[j]], stack_count[top] = n->count[kid[j]];
            stack_entry[top++] = entry[kid[j]];
        }
    }
}

static long walks_ordered, walks_out_of_order;

/* The nearest-first walks (SSE2, and AVX2 where the CPU has it) against
 * reference_walk, leaf by leaf. */
static void compare_order(const accel_bvh4 *bvh, const hr_bounds *boxes, const hr_ray *ray, double tmin,
                          double tmax)
{
    static leaf_log want, got;
    for (int isa = 0; isa < 2; isa++) {
        double tw = tmax, tg = tmax;
        want = (leaf_log){boxes, bvh, ray, tmin, &tw, {0}, {0}, 0};
        got = (leaf_log){boxes, bvh, ray, tmin, &tg, {0}, {0}, 0};
        reference_walk(bvh, ray, tmin, &tw, &want);
        if (isa == 0) {
            accel_bvh4_walk_core(bvh, ray, tmin, &tg, log_leaf, &got, 1, 0);
        } else {
#if ACCEL_WALK_AVX2
            if (!accel_walk_avx2_usable()) return;
            accel_bvh4_walk_avx2(bvh, ray, tmin, &tg, log_leaf, &got);
#else
            return;
#endif
        }
        int same = want.n == got.n && memcmp(&tw, &tg, sizeof tw) == 0;
        uint32_t kept = want.n < 4096 ? want.n : 4096;
        for (uint32_t i = 0; same && i < kept; i++)
            same = want.first[i] == got.first[i] && want.count[i] == got.count[i];
        walks_ordered++;
        walks_out_of_order += !same;
    }
}

static long walks_compared, walks_differing;
/* Walks compared by the octant of their direction (sign bits, a zero's
 * included): the nearest-first AVX2 walk is one copy per octant. */
static long walks_by_octant[8];

/* The AVX2 walk must visit the same leaves in the same order as the SSE2
 * one (accel_bvh4_walk_core), both orders, where the CPU has AVX2. */
static void compare_isas(const accel_bvh4 *bvh, const hr_bounds *boxes, const hr_ray *ray, double tmin,
                         double tmax)
{
#if ACCEL_WALK_AVX2
    if (!accel_walk_avx2_usable()) return;
    static leaf_log a, b;
    for (int ordered = 0; ordered < 2; ordered++) {
        double ta = tmax, tb = tmax;
        a = (leaf_log){boxes, bvh, ray, tmin, &ta, {0}, {0}, 0};
        b = (leaf_log){boxes, bvh, ray, tmin, &tb, {0}, {0}, 0};
        accel_bvh4_walk_core(bvh, ray, tmin, &ta, log_leaf, &a, ordered, 0);
        if (ordered) accel_bvh4_walk_avx2(bvh, ray, tmin, &tb, log_leaf, &b);
        else accel_bvh4_walk_any_avx2(bvh, ray, tmin, &tb, log_leaf, &b);
        int same = a.n == b.n && memcmp(&ta, &tb, sizeof ta) == 0;
        uint32_t kept = a.n < 4096 ? a.n : 4096;
        for (uint32_t i = 0; same && i < kept; i++) same = a.first[i] == b.first[i] && a.count[i] == b.count[i];
        walks_compared++;
        walks_differing += !same;
        walks_by_octant[accel_octant(&ray->dir)] += ordered;
    }
#else
    (void)bvh, (void)boxes, (void)ray, (void)tmin, (void)tmax;
#endif
}

/* Boxes the exact test says the ray meets that a walk did not visit, over
 * both walks: nearest first, and in slot order (shadow rays). */
static long missed_boxes(const accel_bvh4 *bvh, const hr_bounds *boxes, uint32_t n, const hr_ray *ray,
                         double tmin, double tmax, char *visited)
{
    compare_isas(bvh, boxes, ray, tmin, tmax);
    compare_order(bvh, boxes, ray, tmin, tmax);
    char *meets = malloc(n ? n : 1);
    if (!meets) return 1;
    for (uint32_t i = 0; i < n; i++) met_total += meets[i] = (char)quad_meets(ray, &boxes[i], tmin, tmax);
    long missed = 0;
    for (int ordered = 0; ordered < 2; ordered++) {
        memset(visited, 0, n);
        walk_record w = {visited, bvh};
        double t = tmax;
        if (ordered) accel_bvh4_walk(bvh, ray, tmin, &t, record_leaf, &w);
        else accel_bvh4_walk_any(bvh, ray, tmin, &t, record_leaf, &w);
        for (uint32_t i = 0; i < n; i++) missed += meets[i] && !visited[i];
    }
    free(meets);
    return missed;
}

static void test_walk(void)
{
    enum { N = 2000 };
    hr_bounds *boxes = malloc(N * sizeof *boxes);
    char *visited = malloc(N);
    const accel_bvh4_options opt = {.max_leaf = 2, .traversal_cost = 0.5};
    accel_bvh4 bvh;
    long missed = 0, rays = 0;

    /* Boxes at several scales and distances; box coordinates that are not
     * floats, so rounding to float matters. */
    /* From small to the edge of where the walk culls (2^60) and beyond it
     * (2^124, 2^126: near float's range, where it must visit every leaf). */
    const double scales[] = {1e-6, 1.0, 1e6, 0x1p60, 0x1p124, 0x1p126};
    for (int s = 0; s < 6; s++) {
        double L = scales[s];
        for (int i = 0; i < N; i++) {
            double cx = between(-L, L), cy = between(-L, L), cz = between(-L, L);
            double r = L * pow(10.0, between(-7, -0.5));
            boxes[i] = (hr_bounds){{cx - r, cy - r * 0.5, cz - r * 2}, {cx + r, cy + r * 0.7, cz + r}};
        }
        CHECK(accel_bvh4_build(&bvh, boxes, N, &opt) == 0);
        for (int k = 0; k < (s < 4 ? 3000 : 300); k++) {
            /* Aimed at a point of a random box, so rays meet many boxes. */
            const hr_bounds *aim = &boxes[(k * 7919) % N];
            hr_vec3 target = {between(aim->lo.x, aim->hi.x), between(aim->lo.y, aim->hi.y),
                              between(aim->lo.z, aim->hi.z)};
            hr_ray ray = {{between(-2 * L, 2 * L), between(-2 * L, 2 * L), between(-2 * L, 2 * L)}, {0, 0, 0}};
            int kind = k % 6;
            if (kind == 1) ray.origin.x = target.x;                      /* parallel to a slab */
            if (kind == 2) ray.origin.y = target.y, ray.origin.z = target.z; /* along an axis */
            ray.dir = (hr_vec3){target.x - ray.origin.x, target.y - ray.origin.y, target.z - ray.origin.z};
            if (kind == 3) ray.dir.x *= 1e-40;                           /* 1/d overflows float */
            if (kind == 4) ray.origin.x = boxes[k % N].lo.x;             /* on a slab plane */
            if (kind == 5) {                                    /* touching a face or edge */
                const hr_bounds *b = &boxes[k % N];
                hr_vec3 touch = {b->hi.x, between(b->lo.y, b->hi.y), k % 12 < 6 ? b->lo.z : b->hi.z};
                ray.dir = (hr_vec3){0, between(-1, 1), between(-1, 1)};
                ray.origin = (hr_vec3){touch.x, touch.y - ray.dir.y, touch.z - ray.dir.z};
            }
            double tmin = k % 3 == 0 ? 0.0 : k % 3 == 1 ? between(0, 0.5) : -between(0, 2), tmax = k % 4 == 0 ? INFINITY : between(0.5, 4);
            missed += missed_boxes(&bvh, boxes, N, &ray, tmin, tmax, visited);
            rays++;
        }
        accel_bvh4_release(&bvh);
    }

    /* The far-origin walks twice: on a tree built with move_far_origins
     * (a mesh's), which must cull from far origins, and on one without (a
     * scene's), which must stay conservative. */
    for (int move = 0; move < 2; move++) {
        accel_bvh4_options far_opt = opt;
        far_opt.move_far_origins = move;
        /* Far origins: beyond float's range, and far enough that float
         * rounding of the origin is many box sizes. */
        for (int i = 0; i < N; i++) {
            double cx = between(-1, 1), cy = between(-1, 1), cz = between(-1, 1);
            boxes[i] = (hr_bounds){{cx - 1e-3, cy - 1e-3, cz - 1e-3}, {cx + 1e-3, cy + 1e-3, cz + 1e-3}};
        }
        CHECK(accel_bvh4_build(&bvh, boxes, N, &far_opt) == 0);
        const double far[] = {1e7, 1e30, 1e200};
        for (int f = 0; f < 3; f++) {
            for (int k = 0; k < 1000; k++) {
                const hr_bounds *b = &boxes[k % N];
                hr_vec3 target = {0.5 * (b->lo.x + b->hi.x), 0.5 * (b->lo.y + b->hi.y), 0.5 * (b->lo.z + b->hi.z)};
                hr_vec3 from = random_dir();
                hr_ray ray = {{target.x + from.x * far[f], target.y + from.y * far[f], target.z + from.z * far[f]},
                              {-from.x, -from.y, -from.z}};
                missed += missed_boxes(&bvh, boxes, N, &ray, 0, INFINITY, visited);
                rays++;
            }
        }
        /* Far origins, which the walk moves along the line to just before the
         * boxes (accel_ray4_init_far): past ACCEL_CULL_RANGE, and within it but
         * so far that the float bracket of the origin blurs the boxes
         * (accel_origin_far: 2^31 to 2^61, where shadow rays from far planes
         * met coincident teapots); directions unit and as long as the distance
         * (a shadow ray's, to its light), some along an axis, some from beside
         * the boxes' slab, intervals from 0 and from -inf. Conservative, and
         * culling: a walk that visits every leaf, as these did before, visits
         * all 2,000 items; one that culls, those near the line. */
        const double beyond[] = {0x1p31, 0x1p45, 0x1p61, 0x1p65, 1e21, 1e25, 1e30};
        long far_visited = 0, far_walks = 0;
        for (int f = 0; f < 7; f++) {
            for (int k = 0; k < 500; k++) {
                const hr_bounds *b = &boxes[(k * 7919) % N];
                hr_vec3 target = {0.5 * (b->lo.x + b->hi.x), 0.5 * (b->lo.y + b->hi.y), 0.5 * (b->lo.z + b->hi.z)};
                hr_vec3 from = random_dir();
                if (k % 5 == 0) from = k % 3 == 0 ? (hr_vec3){-1, 0, 0} : k % 3 == 1 ? (hr_vec3){0, 1, 0} : (hr_vec3){0, 0, -1};
                if (k % 10 == 5) target.y = 3.0; /* beside every box's slab */
                const double scale = k % 2 ? 1.0 : beyond[f];
                hr_ray ray = {{target.x + from.x * beyond[f], target.y + from.y * beyond[f],
                               target.z + from.z * beyond[f]},
                              {-from.x * scale, -from.y * scale, -from.z * scale}};
                const double tmin = k % 4 == 3 ? -INFINITY : 0.0;
                missed += missed_boxes(&bvh, boxes, N, &ray, tmin, INFINITY, visited);
                rays++;
                memset(visited, 0, N);
                walk_record w = {visited, &bvh};
                double t = INFINITY;
                accel_bvh4_walk_any(&bvh, &ray, tmin, &t, record_leaf, &w);
                for (uint32_t i = 0; i < N; i++) far_visited += visited[i];
                far_walks++;
            }
        }
        if (!move) {
            accel_bvh4_release(&bvh);
            continue;
        }
        fprintf(stderr, "walk: far origins: %ld walks, %.1f items visited a walk of %d\n", far_walks,
                (double)far_visited / (double)far_walks, N);
        CHECK_MSG(far_visited < far_walks * (N / 20), "far origins visit %ld items in %ld walks", far_visited,
                  far_walks);
    }

    /* No finite interval to cull by (tmin -inf, or so far back that the
     * moved origin overflows), and directions in the largest binade. */
    for (int k = 0; k < 300; k++) {
        hr_ray ray = {{between(-1, 1), between(-1, 1), between(-1, 1)}, random_dir()};
        double tmin = k % 3 == 0 ? -INFINITY : k % 3 == 1 ? -1e308 : 0.0;
        if (k % 3 == 1) ray.dir.x = 1e10;
        if (k % 3 == 2) ray.dir = (hr_vec3){1.5e308 * ray.dir.x, -1.7e308, 0.5e308 * ray.dir.z};
        missed += missed_boxes(&bvh, boxes, N, &ray, tmin, INFINITY, visited);
        rays++;
    }

    accel_bvh4_release(&bvh);

    /* Trees of one to three boxes have empty slots, which no ray may enter
     * (the walk would read a node that is not there): origins beyond
     * float's range on every side, with tmax infinite. */
    for (uint32_t count = 1; count <= 3; count++) {
        CHECK(accel_bvh4_build(&bvh, boxes, count, &opt) == 0);
        for (int k = 0; k < 600; k++) {
            const double big = k % 3 == 0 ? 1e39 : k % 3 == 1 ? 1e200 : 3.5e38;
            hr_vec3 from = random_dir();
            hr_ray ray = {{from.x * big, from.y * big, from.z * big}, random_dir()};
            if (k % 2) ray.dir = (hr_vec3){-from.x, -from.y, -from.z};
            missed += missed_boxes(&bvh, boxes, count, &ray, 0, INFINITY, visited);
            rays++;
        }
        accel_bvh4_release(&bvh);
    }
    fprintf(stderr, "walk: %ld rays, %ld box meetings, %ld missed\n", rays, met_total, missed);
    fprintf(stderr, "walk: nearest first against the plain order: %ld walks, %ld with other leaves or order\n",
            walks_ordered, walks_out_of_order);
    /* One walk per ray for each walk this CPU runs (SSE2, and AVX2 where
     * it has it): HITRAY_CPU=sse2 leaves one. */
    CHECK(walks_ordered > 15000 && walks_out_of_order == 0);
    CHECK_MSG(missed == 0, "the walk skipped %ld boxes the exact test says the ray meets", missed);
    CHECK(met_total > 20000);
#if ACCEL_WALK_AVX2
    if (accel_walk_avx2_usable()) {
        fprintf(stderr, "walk: AVX2 against SSE2: %ld walks, %ld with other leaves or order\n", walks_compared,
                walks_differing);
        CHECK(walks_compared > 20000 && walks_differing == 0);
    } else {
        fprintf(stderr, "walk: no AVX2 on this CPU, only the SSE2 walk checked\n");
    }
#endif
    free(boxes);
    free(visited);
}


static uint32_t leaves_walked; /* by count_leaf */

static int count_leaf(void *user, uint32_t first, uint32_t count)
{
    (void)user, (void)first, (void)count;
    leaves_walked++;
    return ACCEL_WALK_GO_ON;
}

/* Leaves visited by every walk of the ray: nearest first and in slot
 * order, SSE2 and (where the CPU has it) AVX2. */
static uint32_t leaves_of_every_walk(const accel_bvh4 *bvh, const hr_ray *ray, double tmin, double tmax)
{
    leaves_walked = 0;
    for (int ordered = 0; ordered < 2; ordered++) {
        double t = tmax;
        accel_bvh4_walk_core(bvh, ray, tmin, &t, count_leaf, NULL, ordered, 0);
#if ACCEL_WALK_AVX2
        t = tmax;
        if (accel_walk_avx2_usable()) {
            if (ordered) accel_bvh4_walk_avx2(bvh, ray, tmin, &t, count_leaf, NULL);
            else accel_bvh4_walk_any_avx2(bvh, ray, tmin, &t, count_leaf, NULL);
        }
#endif
    }
    return leaves_walked;
}

static void test_root_missed(void)
{
    enum { N = 300 };
    hr_bounds *boxes = malloc(N * sizeof *boxes);
    const accel_bvh4_options opt = {.max_leaf = 4, .traversal_cost = 0.5};
    long rays = 0, said_missed = 0, wrong = 0;
    /* Planes at 0, at a double that is no float, far out, and near the
     * ends of the range the walk culls in; trees flat on each axis, and
     * some with thickness. */
    const double planes[] = {0.0, 0.1, -3.3, 1e-30, -1e20, 0x1p63};
    for (int p = 0; p < 6; p++) {
        for (int axis = 0; axis < 3; axis++) {
            for (int thick = 0; thick < 2; thick++) {
                const double c = planes[p], L = fabs(c) > 1 ? fabs(c) : 1.0;
                for (int i = 0; i < N; i++) {
                    double lo[3], hi[3];
                    for (int a = 0; a < 3; a++) {
                        double m = between(-L, L), r = L * between(0.001, 0.1);
                        lo[a] = m - r, hi[a] = m + r;
                    }
                    lo[axis] = hi[axis] = c;
                    if (thick) lo[axis] -= L * between(0, 0.01), hi[axis] += L * between(0, 0.01);
                    boxes[i] = (hr_bounds){{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
                }
                accel_bvh4 bvh;
                CHECK(accel_bvh4_build(&bvh, boxes, N, &opt) == 0);
                float span_lo, span_hi;
                accel_bvh4_root_span(&bvh, axis, &span_lo, &span_hi);
                for (int k = 0; k < 1500; k++) {
                    /* Start a power of two from 2^-160 to 2 (times L) off
                     * the span's side, or on it, above or below. */
                    const int above = k % 2;
                    const double side = above ? span_hi : span_lo;
                    const double off = k % 7 == 0 ? 0.0 : L * ldexp(between(1, 2), -(int)between(0, 161));
                    double o[3] = {between(-1.5 * L, 1.5 * L), between(-1.5 * L, 1.5 * L),
                                   between(-1.5 * L, 1.5 * L)};
                    o[axis] = above ? side + off : side - off;
                    hr_vec3 dv = random_dir();
                    double d[3] = {dv.x, dv.y, dv.z};
                    /* Mostly away from the plane; along it, into it, or
                     * with the component around the helper's 2^-39. */
                    d[axis] = fabs(d[axis]) * (above ? 1 : -1);
                    const int kind = (k / 2) % 8;
                    if (kind == 1) d[axis] = -d[axis];
                    if (kind == 2) d[axis] = 0.0;
                    if (kind == 3) d[axis] = (above ? 1 : -1) * ldexp(1.0, -(int)between(36, 43));
                    if (kind == 4) d[(axis + 1) % 3] = ldexp(1.0, (int)between(37, 41));
                    if (kind == 5) o[(axis + 2) % 3] = ldexp(1.0, (int)between(62, 66));
                    const hr_ray ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
                    const double tmin = k % 5 == 0   ? 0.0
                                        : k % 5 == 1 ? between(0, 1e-3)
                                        : k % 5 == 2 ? -between(0, 1)
                                        : k % 5 == 3 ? ldexp(1.0, -(int)between(100, 160))
                                                     : between(0, 2 * L);
                    const double tmax = k % 3 ? INFINITY : tmin + between(0, 4 * L);
                    const int missed = accel_bvh4_root_missed_on(&bvh, &ray, tmin, axis, span_lo, span_hi);
                    said_missed += missed;
                    if (missed && leaves_of_every_walk(&bvh, &ray, tmin, tmax) > 0) {
                        if (wrong++ < 5)
                            fprintf(stderr, "root_missed_on: wrong for o (%a, %a, %a) d (%a, %a, %a) tmin %a\n",
                                    o[0], o[1], o[2], d[0], d[1], d[2], tmin);
                    }
                    rays++;
                }
                accel_bvh4_release(&bvh);
            }
        }
    }
    /* An empty tree: every ray misses, as the walk visits nothing. */
    accel_bvh4 empty;
    CHECK(accel_bvh4_build(&empty, boxes, 0, &opt) == 0);
    const hr_ray any = {{0, 0, 0}, {0, 0, 1}};
    CHECK(accel_bvh4_root_missed_on(&empty, &any, 0.0, 2, INFINITY, -INFINITY) == 1);
    accel_bvh4_release(&empty);
    fprintf(stderr, "root_missed_on: %ld rays, %ld said missed, %ld of them wrongly\n", rays, said_missed, wrong);
    CHECK(wrong == 0);
    CHECK(said_missed > rays / 20);
    free(boxes);
}

/* Every octant of directions, with each component negative, positive, -0
 * or +0 (a zero's sign picks its planes as a non-zero's does, and so the
 * copy of the AVX2 walk): conservative, and the AVX2 walk the SSE2 one's
 * leaves in the same order. */
static void test_walk_octants(void)
{
    enum { N = 1500 };
    hr_bounds *boxes = malloc(N * sizeof *boxes);
    char *visited = malloc(N);
    const accel_bvh4_options opt = {.max_leaf = 2, .traversal_cost = 0.5};
    accel_bvh4 bvh;
    for (int i = 0; i < N; i++) {
        double cx = between(-1, 1), cy = between(-1, 1), cz = between(-1, 1), r = between(1e-3, 0.1);
        boxes[i] = (hr_bounds){{cx - r, cy - r, cz - r}, {cx + r, cy + r, cz + r}};
    }
    CHECK(accel_bvh4_build(&bvh, boxes, N, &opt) == 0);
    long missed = 0, before[8], compared = walks_compared, differing = walks_differing;
    const long ordered = walks_ordered, out_of_order = walks_out_of_order;
    memcpy(before, walks_by_octant, sizeof before);
    for (int k = 0; k < 4 * 4 * 4 * 40; k++) {
        /* Per axis: 0 negative, 1 positive, 2 -0, 3 +0 (never all zero). */
        const int kind[3] = {k % 4, k / 4 % 4, k / 16 % 4};
        if (kind[0] >= 2 && kind[1] >= 2 && kind[2] >= 2) continue;
        const hr_bounds *aim = &boxes[(k * 7919) % N];
        double o[3] = {between(-1.5, 1.5), between(-1.5, 1.5), between(-1.5, 1.5)}, d[3];
        const double lo[3] = {aim->lo.x, aim->lo.y, aim->lo.z}, hi[3] = {aim->hi.x, aim->hi.y, aim->hi.z};
        for (int a = 0; a < 3; a++) {
            double m = between(0.05, 1);
            d[a] = kind[a] == 0 ? -m : kind[a] == 1 ? m : kind[a] == 2 ? -0.0 : 0.0;
            /* A zero component: the origin within the aimed box's slab on
             * that axis, so the ray still meets boxes. */
            if (kind[a] >= 2) o[a] = between(lo[a], hi[a]);
        }
        hr_ray ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
        double tmin = k % 3 == 0 ? 0.0 : k % 3 == 1 ? between(0, 0.5) : -between(0, 2);
        double tmax = k % 2 ? INFINITY : between(0.5, 4);
        missed += missed_boxes(&bvh, boxes, N, &ray, tmin, tmax, visited);
    }
    accel_bvh4_release(&bvh);
    CHECK_MSG(missed == 0, "the walk skipped %ld boxes the exact test says the ray meets", missed);
    CHECK(walks_ordered > ordered && walks_out_of_order == out_of_order);
#if ACCEL_WALK_AVX2
    if (accel_walk_avx2_usable()) {
        for (int o = 0; o < 8; o++) {
            fprintf(stderr, "walk: octant %d: %ld nearest-first walks compared\n", o, walks_by_octant[o] - before[o]);
            CHECK(walks_by_octant[o] - before[o] >= 250); /* 7 sign patterns, 40 rays each */
        }
        CHECK(walks_compared > compared && walks_differing == differing);
    }
#endif
    free(boxes);
    free(visited);
}

int main(void)
{
    test_build();
    test_walk();
    test_root_missed();
    test_walk_octants();
    return hr_test_end();
}
