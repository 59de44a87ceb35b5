/* Internal: a bounding volume hierarchy over boxes (binned SAH build). */
#ifndef HITRAY_LIB_BVH_H
#define HITRAY_LIB_BVH_H

#include <hitray/common.h>

/* SAH splits down to this depth, halving below it; with at most 2^31 items
 * the tree is at most HR_BVH_MAX_DEPTH levels deep, which sizes the
 * traversal stack (two entries per level). */
#define HR_BVH_SAH_DEPTH 64
#define HR_BVH_MAX_DEPTH (HR_BVH_SAH_DEPTH + 32)

typedef struct hr_bvh_node {
    hr_bounds box;
    int32_t first; /* leaf: first item in `items`; inner: index of left child */
    int32_t count; /* leaf: number of items (> 0); inner: 0 (right = left + 1) */
} hr_bvh_node;

typedef struct hr_bvh {
    hr_bvh_node *nodes;
    int32_t node_count;
    int32_t *items; /* item indices, leaf ranges point into this */
    int32_t item_count;
} hr_bvh;

/* Build over `count` boxes; returns 0 if out of memory. */
int hr_bvh_build(hr_bvh *bvh, const hr_bounds *boxes, int32_t count);
void hr_bvh_release(hr_bvh *bvh);

/* Precomputed ray data for the slab test. */
typedef struct hr_bvh_ray {
    double o[3], inv_d[3];
    int neg[3];
} hr_bvh_ray;
void hr_bvh_ray_init(hr_bvh_ray *r, const hr_ray *ray);
/* Entry distance of the ray into the box within [tmin, tmax], or 0 if missed. */
int hr_bvh_ray_box(const hr_bvh_ray *r, const hr_bounds *b, double tmin, double tmax,
                   double *t_enter);

#endif
