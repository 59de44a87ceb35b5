/* The 8-wide BVH (accel/bvh8.h) on its own, where the CPU has AVX2:
 * - the collapse: every item in exactly one leaf, each a leaf of the 4-wide
 *   tree (the same run of items), every child box containing the items
 *   below it, empty slots empty, no more nodes than the 4-wide tree has;
 *   no tree made for no items;
 * - both walks (nearest first, and in any order) are conservative: with
 *   tmax fixed, every box the ray meets
 *   within [tmin, tmax] by an exact slab test (in __float128) has its leaf
 *   visited, for random and hard rays (axis-parallel, tiny direction
 *   components, origins on slab planes, negative tmin, far origins, boxes
 *   near float's range where nothing is culled, rays touching a face or
 *   an edge exactly);
 * - with a callback that lowers tmax to the exact entry of each box it
 *   meets (a nearest-hit search, ties of many boxes at one entry
 *   included), the 8-wide walk's answer is the 4-wide walk's and the brute
 *   force's, bit for bit. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ACCEL_TEST_SEED 0x2545f4914f6cdd1dull
#include "accel_test_rays.h"
#include "bvh8.h"
#include "hr_test.h"

typedef struct search {
    const accel_bvh4 *bvh;
    const hr_bounds *boxes;
    const hr_ray *ray;
    double tmin, *tmax;
    int lower; /* 0: tmax stays (conservative check), 1: nearest entry */
    char *visited;
    long leaves;
} search;

static int leaf_cb(void *user, uint32_t first, uint32_t count)
{
    search *s = user;
    s->leaves++;
    for (uint32_t i = first; i < first + count; i++) {
        const uint32_t item = s->bvh->items[i];
        s->visited[item] = 1;
        if (!s->lower) continue;
        double e = quad_entry(s->ray, &s->boxes[item], s->tmin, *s->tmax);
        if (e == e && e < *s->tmax) *s->tmax = e;
    }
    return ACCEL_WALK_GO_ON;
}

/* Each item below slot k of n (a node of the 8-wide tree) in the box of
 * slot k; counts the leaves' items into seen. */
static int subtree_ok(const accel_bvh8 *b8, const accel_bvh4 *b4, const hr_bounds *boxes, const accel_bvh8_node *n,
                      int k, const accel_bvh8_node *outer, int outer_k, char *seen, int depth)
{
    if (depth > ACCEL_BVH_MAX_DEPTH) return 0;
    if (n->count[k] > 0) {
        int ok = n->ref[k] + n->count[k] <= b4->item_count;
        for (uint32_t i = n->ref[k]; ok && i < n->ref[k] + n->count[k]; i++) {
            const hr_bounds *b = &boxes[b4->items[i]];
            ok &= outer->lo[0][outer_k] <= b->lo.x && outer->lo[1][outer_k] <= b->lo.y &&
                  outer->lo[2][outer_k] <= b->lo.z && outer->hi[0][outer_k] >= b->hi.x &&
                  outer->hi[1][outer_k] >= b->hi.y && outer->hi[2][outer_k] >= b->hi.z;
            if (seen && outer == n) seen[b4->items[i]]++;
        }
        return ok;
    }
    if (n->ref[k] == ACCEL_BVH4_EMPTY)
        return n == outer ? n->lo[0][k] == INFINITY && n->hi[0][k] == -INFINITY : 1;
    if (n->ref[k] >= b8->node_count) return 0;
    const accel_bvh8_node *c = &b8->nodes[n->ref[k]];
    int ok = 1;
    for (int j = 0; j < 8; j++) ok &= subtree_ok(b8, b4, boxes, c, j, outer, outer_k, NULL, depth + 1);
    return ok;
}

/* The 4-wide tree's leaves, as (first, count) pairs marked in leaf_at. */
static void mark_leaves4(const accel_bvh4 *b4, uint32_t *leaf_at)
{
    for (uint32_t j = 0; j < b4->node_count; j++)
        for (int k = 0; k < 4; k++)
            if (b4->nodes[j].count[k] > 0) leaf_at[b4->nodes[j].ref[k]] = b4->nodes[j].count[k];
}

static long slots_used, nodes8;

static int tree_ok(const accel_bvh8 *b8, const accel_bvh4 *b4, const hr_bounds *boxes, uint32_t count)
{
    char *seen = calloc(count, 1);
    uint32_t *leaf_at = calloc(count, sizeof *leaf_at);
    int ok = seen && leaf_at && b8->node_count >= 1 && b8->node_count <= b4->node_count;
    nodes8 += b8->node_count;
    if (!ok) goto out;
    mark_leaves4(b4, leaf_at);
    for (uint32_t j = 0; j < b8->node_count; j++) {
        const accel_bvh8_node *n = &b8->nodes[j];
        for (int k = 0; k < 8; k++) {
            ok &= subtree_ok(b8, b4, boxes, n, k, n, k, seen, 0);
            slots_used += n->count[k] > 0 || n->ref[k] != ACCEL_BVH4_EMPTY;
            if (n->count[k] > 0) ok &= n->ref[k] < count && leaf_at[n->ref[k]] == n->count[k];
        }
    }
    for (uint32_t i = 0; i < count; i++) ok &= seen[i] == 1;
out:
    free(seen);
    free(leaf_at);
    return ok;
}

static long rays, met, missed, nearest_differ, brute_differ, leaves8, leaves4;

static void check_ray(const accel_bvh8 *b8, const accel_bvh4 *b4, const hr_bounds *boxes, uint32_t n,
                      const hr_ray *ray, double tmin, double tmax, char *visited)
{
    rays++;
    /* Conservative: tmax fixed. */
    memset(visited, 0, n);
    double t = tmax;
    search s = {b4, boxes, ray, tmin, &t, 0, visited, 0};
    accel_bvh8_walk(b8, b4, ray, tmin, &t, leaf_cb, &s);
    char *visited_any = visited + n;
    memset(visited_any, 0, n);
    double t_any = tmax;
    search s_any = {b4, boxes, ray, tmin, &t_any, 0, visited_any, 0};
    accel_bvh8_walk_any(b8, b4, ray, tmin, &t_any, leaf_cb, &s_any);
    double brute = tmax;
    for (uint32_t i = 0; i < n; i++) {
        double e = quad_entry(ray, &boxes[i], tmin, tmax);
        if (e == e) {
            met++;
            missed += !visited[i] + !visited_any[i];
            if (e < brute) brute = e;
        }
    }
    /* The nearest entry, by each walk. */
    double t8 = tmax, t4 = tmax;
    search s8 = {b4, boxes, ray, tmin, &t8, 1, visited, 0}, s4 = {b4, boxes, ray, tmin, &t4, 1, visited, 0};
    accel_bvh8_walk(b8, b4, ray, tmin, &t8, leaf_cb, &s8);
    accel_bvh4_walk(b4, ray, tmin, &t4, leaf_cb, &s4);
    leaves8 += s8.leaves, leaves4 += s4.leaves;
    nearest_differ += memcmp(&t8, &t4, sizeof t8) != 0;
    brute_differ += memcmp(&t8, &brute, sizeof t8) != 0;
}

static void test_walk(void)
{
    enum { N = 3000 };
    hr_bounds *boxes = malloc(N * sizeof *boxes);
    char *visited = malloc(2 * N); /* by the nearest-first walk, then by the walk in any order */
    CHECK(boxes && visited);
    const double scales[] = {1e-6, 1.0, 1e6, 0x1p60, 0x1p124};
    for (int s = 0; s < 5; s++) {
        const double L = scales[s];
        for (uint32_t count = 1; count <= N; count = count < 20 ? count + 1 : count * 4) {
            for (uint32_t i = 0; i < count; i++) {
                double cx = between(-L, L), cy = between(-L, L), cz = between(-L, L);
                double r = L * pow(10.0, between(-5, -0.5));
                /* Every fifth box a copy of an earlier one: ties at one entry. */
                if (i % 5 == 4) boxes[i] = boxes[i / 2];
                else boxes[i] = (hr_bounds){{cx - r, cy - r * 0.5, cz - r * 2}, {cx + r, cy + r * 0.7, cz + r}};
            }
            for (uint32_t max_leaf = 1; max_leaf <= 4; max_leaf += 3) {
                const accel_bvh4_options opt = {.max_leaf = max_leaf, .traversal_cost = 0.5};
                accel_bvh4 b4;
                accel_bvh8 b8;
                CHECK(accel_bvh4_build(&b4, boxes, count, &opt) == 0);
                CHECK(accel_bvh8_build(&b8, &b4) == 0);
                CHECK_MSG(tree_ok(&b8, &b4, boxes, count), "the 8-wide tree of %u boxes at scale %g", count, L);
                const int per = s < 4 ? (count < 20 ? 40 : 600) : 60;
                for (int k = 0; k < per; k++) {
                    const hr_bounds *aim = &boxes[(uint32_t)k * 7919u % count];
                    hr_vec3 target = {between(aim->lo.x, aim->hi.x), between(aim->lo.y, aim->hi.y),
                                      between(aim->lo.z, aim->hi.z)};
                    hr_ray ray = {{between(-2 * L, 2 * L), between(-2 * L, 2 * L), between(-2 * L, 2 * L)}, {0, 0, 0}};
                    const int kind = k % 6;
                    if (kind == 1) ray.origin.x = target.x;
                    if (kind == 2) ray.origin.y = target.y, ray.origin.z = target.z;
                    ray.dir = (hr_vec3){target.x - ray.origin.x, target.y - ray.origin.y, target.z - ray.origin.z};
                    if (kind == 3) ray.dir.x *= 1e-40;
                    if (kind == 4) ray.origin.x = boxes[(uint32_t)k % count].lo.x;
                    if (kind == 5 && k % 12 < 6) ray.dir = random_dir();
                    if (kind == 5 && k % 12 >= 6) { /* touching a face or edge exactly */
                        const hr_bounds *b = &boxes[(uint32_t)k % count];
                        hr_vec3 touch = {b->hi.x, between(b->lo.y, b->hi.y), k % 24 < 12 ? b->lo.z : b->hi.z};
                        ray.dir = (hr_vec3){0, between(-1, 1), between(-1, 1)};
                        ray.origin = (hr_vec3){touch.x, touch.y - ray.dir.y, touch.z - ray.dir.z};
                    }
                    const double tmin = k % 3 == 0 ? 0.0 : k % 3 == 1 ? between(0, 0.5) : -between(0, 2);
                    const double tmax = k % 4 == 0 ? INFINITY : between(0.5, 4);
                    check_ray(&b8, &b4, boxes, count, &ray, tmin, tmax, visited);
                }
                accel_bvh8_release(&b8);
                CHECK(b8.nodes == NULL);
                accel_bvh4_release(&b4);
            }
        }
    }
    /* No tree: nothing visited. */
    accel_bvh4 b4;
    accel_bvh8 b8;
    memset(&b8, 0xff, sizeof b8);
    CHECK(accel_bvh4_build(&b4, boxes, 0, &(accel_bvh4_options){.max_leaf = 1}) == 0);
    CHECK(accel_bvh8_build(&b8, &b4) == 0 && b8.nodes == NULL && b8.node_count == 0);
    fprintf(stderr, "bvh8: %ld rays, %ld box meetings, %ld missed; nearest entry: %ld differ from the 4-wide walk, "
                    "%ld from the brute force; leaves visited %ld (4-wide %ld)\n",
            rays, met, missed, nearest_differ, brute_differ, leaves8, leaves4);
    fprintf(stderr, "bvh8: %ld nodes, %.2f children a node\n", nodes8, (double)slots_used / (double)nodes8);
    CHECK(rays > 20000 && met > 40000);
    CHECK_MSG(missed == 0, "the 8-wide walk skipped %ld boxes the exact test says the ray meets", missed);
    CHECK(nearest_differ == 0 && brute_differ == 0);
    free(boxes);
    free(visited);
}

int main(void)
{
    if (!accel_bvh8_usable()) {
        fprintf(stderr, "bvh8: this CPU has no AVX2 (or HITRAY_CPU takes it away): nothing to test\n");
        return 0;
    }
    test_walk();
    return hr_test_end();
}
