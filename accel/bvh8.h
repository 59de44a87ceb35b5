/* An 8-wide BVH for AVX2 CPUs, collapsed from the 4-wide one (accel/bvh4.h)
 * with the same leaves, and walked eight float boxes a step. Its boxes are
 * the 4-wide tree's, copied, and each is tested with the 4-wide walk's flipped arithmetic
 * (accel_bvh4_test_at: the same operations, lane for lane, in 256-bit
 * registers), so the walk is exactly as conservative as the 4-wide one:
 * it meets a box whenever that walk would. It may visit leaves in another
 * order; callers that need the 4-wide walk's order must not use it. */
#ifndef HITRAY_ACCEL_BVH8_H
#define HITRAY_ACCEL_BVH8_H

#include "bvh4.h"

#if ACCEL_WALK_AVX2
#include <immintrin.h>
#endif

/* Eight child boxes by axis then child, and what each child is (as in
 * accel_bvh4_node). 256 bytes. */
typedef struct accel_bvh8_node {
    float lo[3][8], hi[3][8];
    uint32_t ref[8];
    uint32_t count[8];
} accel_bvh8_node;

typedef struct accel_bvh8 {
    accel_bvh8_node *nodes; /* NULL: not built */
    uint32_t node_count;
} accel_bvh8;

/* Collapses bvh4 (built) into bvh8, whose leaves are bvh4's (the same runs
 * of bvh4->items). 0, or -1 when out of memory (bvh8 then zeroed); no tree
 * (nodes NULL) for a tree of no items. */
int accel_bvh8_build(accel_bvh8 *bvh8, const accel_bvh4 *bvh4);
void accel_bvh8_release(accel_bvh8 *bvh8);

#if ACCEL_WALK_AVX2
/* Children pushed per level at most, and the stack. */
#define ACCEL_BVH8_STACK (7 * ACCEL_BVH_MAX_DEPTH + 8)

#define ACCEL_BVH8_PLANE_AT(octant, a, near)                                                          \
    ((((octant) >> (a) & 1) == !(near) ? offsetof(accel_bvh8_node, lo) : offsetof(accel_bvh8_node, hi)) + \
     (size_t)(a) * 8 * sizeof(float))

/* The nearest-first walk (accel_bvh4_walk's contract: every leaf the ray
 * may meet before *tmax, read back after each leaf call), for a ray whose
 * direction's sign bits are `octant` (a constant). A ray
 * accel_ray4_init_common_as does not take goes to the 4-wide SSE2 walk. */
__attribute__((target("avx2"))) ACCEL_ALWAYS_INLINE int
accel_bvh8_walk_octant(const accel_bvh8 *bvh8, const accel_bvh4 *bvh4, const hr_ray *ray, double tmin,
                       double *tmax, int (*leaf)(void *user, uint32_t first, uint32_t count), void *user,
                       int octant, int ordered)
{
    accel_ray4 r4;
    if (!accel_ray4_init_common_as(&r4, ray, tmin, 1) || !(bvh4->extent <= ACCEL_CULL_RANGE))
        return ordered ? accel_bvh4_walk_sse2(bvh4, ray, tmin, tmax, leaf, user)
                       : accel_bvh4_walk_any_sse2(bvh4, ray, tmin, tmax, leaf, user);
    /* Written out (a loop here was kept as one, a dozen instructions a
     * ray). */
#define ACCEL_WIDEN(v) {_mm256_broadcastss_ps(r4.v[0]), _mm256_broadcastss_ps(r4.v[1]), _mm256_broadcastss_ps(r4.v[2])}
    const __m256 o_near[3] = ACCEL_WIDEN(o_near), o_far[3] = ACCEL_WIDEN(o_far);
    const __m256 inv_near[3] = ACCEL_WIDEN(inv_near), inv_far[3] = ACCEL_WIDEN(inv_far);
#undef ACCEL_WIDEN
    const __m256 tmin8 = _mm256_set1_ps(accel_ray4_tmin(&r4, tmin));
    float tmax_f = accel_ray4_tmax(&r4, *tmax);
    __m256 tmax8 = _mm256_set1_ps(tmax_f);
    const __m256 tiny = _mm256_set1_ps(ACCEL_TINY);
    uint32_t stack_ref[ACCEL_BVH8_STACK], stack_count[ACCEL_BVH8_STACK];
    float stack_entry[ACCEL_BVH8_STACK];
    uint32_t top = 0;
    const accel_bvh8_node *const nodes = bvh8->nodes;
    const accel_bvh8_node *n = nodes;
    uint32_t ref, count;
    for (;;) {
        const char *base = (const char *)n;
        __m256 lo = tmin8, hi = tmax8;
#define ACCEL_SLAB8(a)                                                                                   \
    do {                                                                                                 \
        const __m256 bn_ = _mm256_loadu_ps((const float *)(const void *)(base + ACCEL_BVH8_PLANE_AT(octant, a, 1))); \
        const __m256 bf_ = _mm256_loadu_ps((const float *)(const void *)(base + ACCEL_BVH8_PLANE_AT(octant, a, 0))); \
        lo = _mm256_max_ps(_mm256_mul_ps(_mm256_sub_ps(o_near[a], bn_), inv_near[a]), lo);            \
        hi = _mm256_min_ps(_mm256_mul_ps(_mm256_sub_ps(o_far[a], bf_), inv_far[a]), hi);               \
    } while (0)
        ACCEL_SLAB8(0);
        ACCEL_SLAB8(1);
        ACCEL_SLAB8(2);
#undef ACCEL_SLAB8
        lo = _mm256_sub_ps(lo, tiny);
        hi = _mm256_add_ps(hi, tiny);
        unsigned mask = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(lo, hi, _CMP_LE_OQ));
        if (!mask) goto next;
        float entry[8];
        _mm256_storeu_ps(entry, lo);
        uint32_t k = (uint32_t)__builtin_ctz(mask);
        mask &= mask - 1;
        if (mask && !ordered) {
            /* Any order (accel_bvh4_walk_any): stack all but the first. */
            for (unsigned rest = mask; rest; rest &= rest - 1) {
                const uint32_t c = (uint32_t)__builtin_ctz(rest);
                stack_ref[top] = n->ref[c], stack_count[top] = n->count[c];
                stack_entry[top++] = entry[c];
            }
        } else if (mask && !(mask & (mask - 1))) {
            ACCEL_WALK_TWO();
        } else if (mask) {
            /* Three or more: each child's rank by entry (ties by slot),
             * from integer keys: the entry's bits (a negative entry, at
             * most 2^-149 below 0, as 0) with the slot in the low three
             * bits, a child not met above every finite entry. The order
             * only speeds the walk up; any order finds the same hits. */
            const uint32_t met = mask | 1u << k, hits = (uint32_t)__builtin_popcount(met);
            const __m256i slots = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
            const __m256i is_met = _mm256_cmpeq_epi32(
                _mm256_and_si256(_mm256_set1_epi32((int)met), _mm256_sllv_epi32(_mm256_set1_epi32(1), slots)),
                _mm256_sllv_epi32(_mm256_set1_epi32(1), slots));
            __m256i key = _mm256_max_epi32(_mm256_castps_si256(lo), _mm256_setzero_si256());
            key = _mm256_or_si256(_mm256_andnot_si256(_mm256_set1_epi32(7), key), slots);
            key = _mm256_blendv_epi8(_mm256_set1_epi32(INT32_MAX), key, is_met);
            __m256i rank = _mm256_setzero_si256();
#define ACCEL_RANK(s)                                                                                   \
    rank = _mm256_sub_epi32(                                                                            \
        rank, _mm256_cmpgt_epi32(key, _mm256_permutevar8x32_epi32(                                     \
                                          key, _mm256_setr_epi32((s) & 7, (s + 1) & 7, (s + 2) & 7,     \
                                                                 (s + 3) & 7, (s + 4) & 7, (s + 5) & 7, \
                                                                 (s + 6) & 7, (s + 7) & 7))))
            ACCEL_RANK(1);
            ACCEL_RANK(2);
            ACCEL_RANK(3);
            ACCEL_RANK(4);
            ACCEL_RANK(5);
            ACCEL_RANK(6);
            ACCEL_RANK(7);
#undef ACCEL_RANK
            int32_t ranks[8];
            _mm256_storeu_si256((__m256i *)(void *)ranks, rank);
            const uint32_t last = top + hits - 1;
            for (unsigned rest = met; rest; rest &= rest - 1) {
                const uint32_t c = (uint32_t)__builtin_ctz(rest), at = last - (uint32_t)ranks[c];
                stack_ref[at] = n->ref[c], stack_count[at] = n->count[c];
                stack_entry[at] = entry[c];
                k = ranks[c] ? k : c;
            }
            top = last;
        }
        ACCEL_WALK_ON((tmax_f = accel_ray4_tmax(&r4, *tmax), tmax8 = _mm256_set1_ps(tmax_f)));
    }
}

#define ACCEL_WALK8_OCTANT(o)                                                                          \
    __attribute__((target("avx2"), noinline, unused)) static int accel_bvh8_walk_##o(                 \
        const accel_bvh8 *bvh8, const accel_bvh4 *bvh4, const hr_ray *ray, double tmin, double *tmax, \
        int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)                          \
    {                                                                                                 \
        return accel_bvh8_walk_octant(bvh8, bvh4, ray, tmin, tmax, leaf, user, o, 1);                 \
    }                                                                                                 \
    __attribute__((target("avx2"), noinline, unused)) static int accel_bvh8_walk_any_##o(             \
        const accel_bvh8 *bvh8, const accel_bvh4 *bvh4, const hr_ray *ray, double tmin, double *tmax, \
        int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)                          \
    {                                                                                                 \
        return accel_bvh8_walk_octant(bvh8, bvh4, ray, tmin, tmax, leaf, user, o, 0);                 \
    }
ACCEL_WALK8_OCTANT(0)
ACCEL_WALK8_OCTANT(1)
ACCEL_WALK8_OCTANT(2)
ACCEL_WALK8_OCTANT(3)
ACCEL_WALK8_OCTANT(4)
ACCEL_WALK8_OCTANT(5)
ACCEL_WALK8_OCTANT(6)
ACCEL_WALK8_OCTANT(7)
#undef ACCEL_WALK8_OCTANT
#endif

/* Whether accel_bvh8_walk would walk an 8-wide tree on this CPU: build
 * one only then. */
static inline int accel_bvh8_usable(void)
{
#if ACCEL_WALK_AVX2
    return accel_walk_avx2_usable();
#else
    return 0;
#endif
}

/* The walks over bvh8 where it is built and AVX2 may be used, else over
 * bvh4 (which bvh8 was collapsed from): nearest first (accel_bvh4_walk's
 * contract) or in any order (accel_bvh4_walk_any's). */
#if ACCEL_WALK_AVX2
#define ACCEL_BVH8_BY_OCTANT(walk)                                                                 \
    switch (accel_octant(&ray->dir)) {                                                             \
    case 0: return walk##0(bvh8, bvh4, ray, tmin, tmax, leaf, user);                               \
    case 1: return walk##1(bvh8, bvh4, ray, tmin, tmax, leaf, user);                               \
    case 2: return walk##2(bvh8, bvh4, ray, tmin, tmax, leaf, user);                               \
    case 3: return walk##3(bvh8, bvh4, ray, tmin, tmax, leaf, user);                               \
    case 4: return walk##4(bvh8, bvh4, ray, tmin, tmax, leaf, user);                               \
    case 5: return walk##5(bvh8, bvh4, ray, tmin, tmax, leaf, user);                               \
    case 6: return walk##6(bvh8, bvh4, ray, tmin, tmax, leaf, user);                               \
    default: return walk##7(bvh8, bvh4, ray, tmin, tmax, leaf, user);                              \
    }
#endif
static inline int accel_bvh8_walk(const accel_bvh8 *bvh8, const accel_bvh4 *bvh4, const hr_ray *ray,
                                  double tmin, double *tmax,
                                  int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)
{
#if ACCEL_WALK_AVX2
    if (bvh8->nodes && accel_walk_avx2_usable()) ACCEL_BVH8_BY_OCTANT(accel_bvh8_walk_)
#endif
    (void)bvh8;
    return accel_bvh4_walk(bvh4, ray, tmin, tmax, leaf, user);
}
static inline int accel_bvh8_walk_any(const accel_bvh8 *bvh8, const accel_bvh4 *bvh4, const hr_ray *ray,
                                      double tmin, double *tmax,
                                      int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)
{
#if ACCEL_WALK_AVX2
    if (bvh8->nodes && accel_walk_avx2_usable()) ACCEL_BVH8_BY_OCTANT(accel_bvh8_walk_any_)
#endif
    (void)bvh8;
    return accel_bvh4_walk_any(bvh4, ray, tmin, tmax, leaf, user);
}

#endif
