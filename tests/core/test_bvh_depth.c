/* The BVH's depth bound, on the builder itself (lib/bvh.c is compiled into
 * this test): the traversal stack is sized from HR_BVH_MAX_DEPTH, so no input
 * may build a deeper tree. Geometric spacing is SAH's worst case: it peels
 * one box off per level. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bvh.h"
#include "hr_test.h"

static int32_t depth_of(const hr_bvh *bvh, int32_t node)
{
    const hr_bvh_node *n = &bvh->nodes[node];
    if (n->count > 0) return 1;
    int32_t l = depth_of(bvh, n->first), r = depth_of(bvh, n->first + 1);
    return 1 + (l > r ? l : r);
}

/* Every item appears in exactly one leaf. */
static int covers_all(const hr_bvh *bvh, int32_t count)
{
    char *seen = calloc((size_t)count, 1);
    int ok = seen != NULL && bvh->item_count == count;
    for (int32_t i = 0; ok && i < bvh->node_count; i++) {
        const hr_bvh_node *n = &bvh->nodes[i];
        for (int32_t k = 0; k < n->count; k++) ok &= !seen[bvh->items[n->first + k]]++;
    }
    for (int32_t i = 0; ok && i < count; i++) ok &= seen[i] == 1;
    free(seen);
    return ok;
}

int main(void)
{
    enum { N = 20000 };
    hr_bounds *boxes = malloc(N * sizeof *boxes);
    /* Boxes (spheres' bounds) at x = 1.5^i with size 0.3 x: binned SAH puts
     * all but the largest few in the lowest bin, level after level. */
    enum { GEOMETRIC = 1500 };
    double x = 1;
    for (int i = 0; i < GEOMETRIC; i++, x *= 1.5)
        boxes[i] = (hr_bounds){{x - 0.3 * x, -0.3 * x, -0.3 * x}, {x + 0.3 * x, 0.3 * x, 0.3 * x}};
    hr_bvh bvh;
    CHECK(hr_bvh_build(&bvh, boxes, GEOMETRIC));
    int32_t d = depth_of(&bvh, 0);
    fprintf(stderr, "geometric spacing: depth %d (bound %d)\n", (int)d, HR_BVH_MAX_DEPTH);
    CHECK_MSG(d <= HR_BVH_MAX_DEPTH, "geometric: depth %d > %d", (int)d, HR_BVH_MAX_DEPTH);
    CHECK(covers_all(&bvh, GEOMETRIC));
    hr_bvh_release(&bvh);

    /* Boxes near the ends of the double range: centroids must not overflow. */
    for (int i = 0; i < 64; i++) {
        double s = i % 2 ? 1.0 : -1.0;
        boxes[i] = (hr_bounds){{s * 1e308, i, 0}, {s * 1.7e308, i + 1.0, 1}};
    }
    CHECK(hr_bvh_build(&bvh, boxes, 64));
    CHECK(covers_all(&bvh, 64));
    hr_bvh_release(&bvh);

    /* A subnormal spread of centroids: no binning scale exists. */
    for (int i = 0; i < 64; i++) boxes[i] = (hr_bounds){{i * 1e-320, 0, 0}, {i * 1e-320, 0, 0}};
    CHECK(hr_bvh_build(&bvh, boxes, 64));
    CHECK(covers_all(&bvh, 64));
    CHECK(depth_of(&bvh, 0) <= HR_BVH_MAX_DEPTH);
    hr_bvh_release(&bvh);
    free(boxes);
    return hr_test_end();
}
