/* Internal: a bounding volume hierarchy over boxes (binned SAH build). */
#ifndef HITRAY_LIB_BVH_H
#define HITRAY_LIB_BVH_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
    /* The boxes of each pair of children again, side by side per number, for
     * the two-at-once test: the children of the inner node whose `first` is
     * f (always odd: children are made in pairs after the root) are at
     * pairs + HR_BVH_PAIR * (f - 1) / 2, as lo.x of left and right, lo.y of
     * both, ..., hi.z of both. NULL when the tree is a single leaf. */
    double *pairs;
} hr_bvh;

#define HR_BVH_PAIR 12

/* Build over `count` boxes; returns 0 if out of memory. */
int hr_bvh_build(hr_bvh *bvh, const hr_bounds *boxes, int32_t count);
void hr_bvh_release(hr_bvh *bvh);

/* Precomputed ray data for the slab test: the origin, 1/d, and for each axis
 * which of the box's six numbers (lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, in
 * hr_bounds order) the ray meets first, so the test has no branch on the
 * direction's sign. */
typedef struct hr_bvh_ray {
    double o[3], inv_d[3];
    int near_i[3], far_i[3];
#if defined(__SSE2__)
    __m128d o2[3], inv_d2[3]; /* o and 1/d in both lanes, for the pair test */
#endif
} hr_bvh_ray;
/* Inline, so the ray data stays in registers during traversal: a call
 * would let the ray's copy escape and be reloaded after every object test. */
static inline void hr_bvh_ray_init(hr_bvh_ray *r, const hr_ray *ray)
{
    double o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    for (int a = 0; a < 3; a++) {
        r->o[a] = o[a];
        r->inv_d[a] = 1.0 / d[a]; /* +-inf for a zero component: see hr_bvh_ray_box */
        int neg = signbit(d[a]) != 0;
        r->near_i[a] = neg ? a + 3 : a; /* a negative direction meets hi first */
        r->far_i[a] = neg ? a : a + 3;
#if defined(__SSE2__)
        r->o2[a] = _mm_set1_pd(r->o[a]);
        r->inv_d2[a] = _mm_set1_pd(r->inv_d[a]);
#endif
    }
}

/* Slab test, inline: it is most of what tracing a big scene costs. A zero
 * direction component gives infinite slab distances; the only NaN case
 * (origin exactly on a slab plane, 0 * inf) must read as "the ray runs inside
 * that slab", and the comparisons below are written so a NaN leaves the
 * running bound as it was: exactly that. The far distance is widened by
 * 1 + 2*gamma(3) (pbrt) so rounding never loses a box the ray touches. */
#define HR_BVH_WIDEN ((1.0 + 2.0 * (3.0 * DBL_EPSILON * 0.5) / (1.0 - 3.0 * DBL_EPSILON * 0.5)) - 1.0)

/* Entry distance of the ray into the box within [tmin, tmax], or 0 if missed. */
static inline int hr_bvh_ray_box(const hr_bvh_ray *r, const hr_bounds *b, double tmin,
                                 double tmax, double *t_enter)
{
    const double *v = (const double *)(const void *)b; /* lo.x lo.y lo.z hi.x hi.y hi.z */
#define HR_BVH_SLAB(a)                                                         \
    do {                                                                       \
        double near_ = (v[r->near_i[a]] - r->o[a]) * r->inv_d[a];              \
        double far_ = (v[r->far_i[a]] - r->o[a]) * r->inv_d[a];                \
        far_ += fabs(far_) * HR_BVH_WIDEN;                                     \
        if (near_ > tmin) tmin = near_;                                        \
        if (far_ < tmax) tmax = far_;                                          \
    } while (0)
    HR_BVH_SLAB(0);
    HR_BVH_SLAB(1);
    HR_BVH_SLAB(2);
#undef HR_BVH_SLAB
    if (!(tmin <= tmax)) return 0;
    *t_enter = tmin;
    return 1;
}

/* The two children of an inner node at once (the node's `first`): returns
 * bit 0 if the ray meets the left child, bit 1 if it meets the right one, with the entry distances in t[0], t[1].
 * Lane by lane the same operations as hr_bvh_ray_box, in the same order, so
 * the same answers: SSE2's max(a, b) is a > b ? a : b and min(a, b) is
 * a < b ? a : b, which keep the running bound on a NaN exactly as the scalar
 * comparisons do; fabs is clearing the sign bit. Without SSE2: the scalar
 * test twice. */
static inline int hr_bvh_ray_box2(const hr_bvh_ray *r, const hr_bvh *bvh, int32_t first,
                                  double tmin, double tmax, double t[2])
{
#if defined(__SSE2__)
    /* first is odd: HR_BVH_PAIR * (first - 1) / 2 without the division */
    const double *p = bvh->pairs + (size_t)(HR_BVH_PAIR / 2) * (size_t)(first - 1);
    const __m128d widen = _mm_set1_pd(HR_BVH_WIDEN), sign = _mm_set1_pd(-0.0);
    __m128d lo = _mm_set1_pd(tmin), hi = _mm_set1_pd(tmax);
#define HR_BVH_SLAB2(k)                                                        \
    do {                                                                       \
        const __m128d o_ = r->o2[k], inv_ = r->inv_d2[k];                      \
        __m128d near_ = _mm_loadu_pd(p + 2 * r->near_i[k]);                    \
        __m128d far_ = _mm_loadu_pd(p + 2 * r->far_i[k]);                      \
        near_ = _mm_mul_pd(_mm_sub_pd(near_, o_), inv_);                       \
        far_ = _mm_mul_pd(_mm_sub_pd(far_, o_), inv_);                         \
        far_ = _mm_add_pd(far_, _mm_mul_pd(_mm_andnot_pd(sign, far_), widen)); \
        lo = _mm_max_pd(near_, lo);                                            \
        hi = _mm_min_pd(far_, hi);                                             \
    } while (0)
    HR_BVH_SLAB2(0);
    HR_BVH_SLAB2(1);
    HR_BVH_SLAB2(2);
#undef HR_BVH_SLAB2
    _mm_storeu_pd(t, lo);
    return _mm_movemask_pd(_mm_cmple_pd(lo, hi));
#else
    return hr_bvh_ray_box(r, &bvh->nodes[first].box, tmin, tmax, &t[0]) |
           hr_bvh_ray_box(r, &bvh->nodes[first + 1].box, tmin, tmax, &t[1]) << 1;
#endif
}

/* hr_bvh_ray_box reads a box as six doubles in a row. */
_Static_assert(offsetof(hr_bounds, hi) == 3 * sizeof(double) &&
                   offsetof(hr_vec3, z) == 2 * sizeof(double) &&
                   sizeof(hr_bounds) == 6 * sizeof(double),
               "hr_bounds is six doubles");

#endif
