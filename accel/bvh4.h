/* A 4-wide bounding volume hierarchy with float child boxes, walked four
 * boxes per SSE step: the acceleration structure of the scene (lib/) and of
 * the mesh module, one piece of code for both.
 *
 * Built over double boxes by a binned SAH (accel/bvh4_build.c): a binary
 * tree first, collapsed to four children a node by pulling up the largest
 * grandchildren. Each child box is rounded outward to float, so it contains
 * the double box it came from.
 *
 * The traversal is conservative: it may visit a box the ray misses, never
 * skip one the ray meets within [tmin, tmax]. Why that holds in float (the
 * argument accel_ray4_init_as and accel_bvh4_test rely on):
 * - the ray's direction is scaled by a power of two so its largest
 *   component is in [1, 2): exact, and t along it is t * 2^scale_exp;
 * - the origin is rounded up and down to float, and each slab distance uses
 *   the rounding that makes the near distance smaller and the far one
 *   larger, so the origin's rounding can only widen the interval;
 * - 1/d is rounded once in double and once to float, (b - o) once and the
 *   product once: four roundings of at most 2^-24 relative each, so every
 *   slab distance is within 4 * 2^-24 of its exact value (subnormal results
 *   aside, which are off by at most 2^-149 absolute). The entry distance
 *   (a max of such values and tmin) and the exit distance (a min) are then
 *   moved outward by 2^-20 relative and 2^-149 absolute, far more than
 *   those errors;
 * - a direction component so small that 1/d would pass 2^40 (below 2^-40
 *   of the largest) gives NaN slab distances, which the max/min ignore:
 *   that axis culls nothing, which is conservative. With boxes and origin
 *   within 2^64 of zero (else the walk culls nothing at all) no slab
 *   distance can overflow float (ACCEL_CULL_RANGE). An exactly zero
 *   component gives +-inf distances (or NaN for an origin exactly on the
 *   slab plane, again ignored), the textbook treatment of a parallel ray;
 * - tmin is rounded down and tmax up to float (after scaling), tmax then
 *   clamped to FLT_MAX: an entry beyond it is +inf, which holds no hit;
 * - the SSE2 and AVX2 walks compute the same slab distances but for the
 *   sign of a zero (accel_bvh4_test_as), so the same entries, the same
 *   boxes met, the same leaves in the same order, on every CPU;
 * - accel_ray4_init_common is accel_ray4_init_any's arithmetic, lane by
 *   lane, for the rays it accepts (test_bvh4_ray_init: bit for bit).
 * So a box is skipped only when the exact ray misses it; the hits a walk
 * finds are the shapes' own, in double, and do not depend on the walk. */
#ifndef HITRAY_ACCEL_BVH4_H
#define HITRAY_ACCEL_BVH4_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <hitray/common.h>
#include <hitray/shape_kit_box.h>
#include <hitray/shape_kit_cpu.h>
#include <hitray/shape_kit_math.h>

#include "float_bounds.h"

/* SAH splits down to this depth of the binary tree, halving below it; with
 * at most ACCEL_BVH4_MAX_ITEMS items the tree is at most
 * ACCEL_BVH_MAX_DEPTH levels deep, and so is the 4-wide one. */
#define ACCEL_BVH_SAH_DEPTH 64
#define ACCEL_BVH_MAX_DEPTH (ACCEL_BVH_SAH_DEPTH + 32)
#define ACCEL_BVH4_MAX_ITEMS ((uint32_t)INT32_MAX)
/* A walk pushes at most three children per level it descends. */
#define ACCEL_BVH4_STACK (3 * ACCEL_BVH_MAX_DEPTH + 4)

/* A slot with no child: its box is empty (lo = +inf, hi = -inf). */
#define ACCEL_BVH4_EMPTY UINT32_MAX

/* One node: four child boxes, by axis then child (lo[a][k] is child k's
 * lower bound on axis a), and what each child is. 128 bytes. */
typedef struct accel_bvh4_node {
    float lo[3][4], hi[3][4];
    /* count[k] > 0: a leaf of items ref[k] .. ref[k] + count[k] - 1;
     * count[k] == 0: an inner child, node ref[k] (ACCEL_BVH4_EMPTY: none). */
    uint32_t ref[4];
    uint32_t count[4];
} accel_bvh4_node;

typedef struct accel_bvh4 {
    accel_bvh4_node *nodes; /* node 0 is the root; NULL when there are no items */
    uint32_t node_count;
    /* The input index of each item, in leaf order: a leaf's items are a run
     * of this array, so a caller may lay its own data out in this order. */
    uint32_t *items;
    uint32_t item_count;
    uint32_t depth; /* levels of nodes (1: the root alone) */
    /* The largest |coordinate| of any item's box (+inf if one is not
     * finite): a walk culls only where it and the ray's origin are within
     * ACCEL_CULL_RANGE (accel_bvh4_walk). */
    double extent;
    /* The largest |origin coordinate| a walk takes as it comes: beyond
     * it the origin is far (accel_origin_far). ACCEL_CULL_RANGE, or less
     * for a tree built with move_far_origins. */
    double origin_reach;
    void (*free_fn)(void *ptr);
} accel_bvh4;

typedef struct accel_bvh4_options {
    /* Leaves hold at most this many items (1 .. 16). */
    uint32_t max_leaf;
    /* Cost of visiting a node against testing one item, for the SAH. */
    double traversal_cost;
    /* Zero-filling allocator and its free (both NULL: calloc and free), so
     * a module can allocate through its host. */
    void *(*alloc)(size_t size);
    void (*free)(void *ptr);
    /* The most threads the build may run on, the caller's included (0 or
     * 1: the caller's alone). Subtrees of at least
     * ACCEL_BVH4_PARALLEL_ITEMS items are then built side by side; the
     * tree is the same, byte for byte, for any number. */
    uint32_t threads;
    /* 1: a walk from an origin beyond ACCEL_FAR_ORIGIN times the boxes'
     * size moves it up to them (accel_origin_far). For a caller whose every
     * query of the items walks the tree (a mesh's triangles), so that all
     * see the same moved line; not for a scene, whose all-hits query
     * traces each object without its box, on the object's own copy of the
     * ray, which carries the transform's rounding of a far origin (1e-4
     * to 2e3 for origins 1e12 to 2^64 away): the unmoved walk's float
     * bracket of the origin covers that rounding, the moved one's does
     * not, and the first hit would no longer be the first of all hits
     * (test_first_hit_paths). */
    int move_far_origins;
} accel_bvh4_options;

/* The fewest items in a subtree the build hands to a thread of its own:
 * below, starting a thread costs more than it saves. */
#define ACCEL_BVH4_PARALLEL_ITEMS 4096u

/* Build over `count` boxes (NaN-free; infinite extents are allowed).
 * Returns 0 on success, -1 when out of memory, -2 when count exceeds
 * ACCEL_BVH4_MAX_ITEMS. */
int accel_bvh4_build(accel_bvh4 *bvh, const hr_bounds *boxes, uint32_t count,
                     const accel_bvh4_options *options);
/* Frees what build allocated (with the options' free); safe on a zeroed or
 * released tree. */
void accel_bvh4_release(accel_bvh4 *bvh);

/* Forced inline where a constant argument (the walk's order) or a value
 * kept in registers (the prepared ray) is what makes the code lean. */
#if defined(__GNUC__)
#define ACCEL_ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define ACCEL_ALWAYS_INLINE static inline
#endif

/* --- Walking ------------------------------------------------------------- */

/* A ray prepared for accel_bvh4_test. */
typedef struct accel_ray4 {
#if defined(__SSE2__)
    __m128 o_near[3], o_far[3], inv_near[3], inv_far[3];
#else
    float o_near[3], o_far[3], inv_near[3], inv_far[3];
#endif
    /* Byte offsets in a node of the plane each axis meets first and last. */
    size_t near_at[3], far_at[3];
    /* The walk's t is (t - t_offset) * t_scale: t_scale for the
     * direction's scaling, t_offset (tmin when negative, else 0) so that
     * the walk's interval starts at 0 or later, which the slack's
     * direction needs. tmin_offset is t_offset but for a far origin
     * (accel_ray4_init_far), whose move along the line is known within a
     * rounding of its size: t_offset then lies that far below it, and
     * tmin_offset that far above, so the walk's interval holds the
     * caller's. */
    double t_scale, t_offset, tmin_offset;
    int cull; /* 0: no usable interval, every leaf is visited */
} accel_ray4;

/* Float's range bounds where culling is exact: a slab distance beyond it
 * overflows to an infinity, and an entry of +inf reads as a miss. So a
 * walk culls only when the boxes and the origin (moved back to a negative
 * tmin) lie within 2^64 of the origin of coordinates and 1/d is at most 2^40 (a smaller component
 * culls nothing on its axis): every distance is then below 2^65 * 2^40
 * (or infinite from a zero component), far inside float's 2^128. Beyond,
 * the walk visits every leaf: slow, and exact. */
#define ACCEL_CULL_RANGE 0x1p64
#define ACCEL_INV_MAX 0x1p40

/* Relative slack on every slab distance, folded into 1/d: the shape kit's
 * (SHAPE_SLAB_SLACK), far more than the five roundings of 2^-24 it covers
 * (see the top of this file). */
#define ACCEL_SLACK SHAPE_SLAB_SLACK
/* Absolute slack on the entry and exit distances: the error of a subnormal
 * float result. */
#define ACCEL_TINY 0x1p-149f

/* For a walk over [tmin, ...]: any ray, any tmin. */
static inline void accel_ray4_init_any(accel_ray4 *r, const hr_ray *ray, double tmin)
{
    const double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    /* A negative tmin moves the origin back to where the interval starts;
     * the moved origin is bracketed with the error of that product and sum
     * (gamma(2) of the terms' magnitudes). */
    r->t_offset = tmin < 0 ? tmin : 0.0;
    /* An infinite tmin, or one so far back that the moved origin is not
     * finite, leaves no interval to cull by, and neither does a ray that is
     * not finite (0 * inf): the walk then visits every leaf
     * (accel_bvh4_walk), which is slow but exact. */
    r->cull = isfinite(tmin) && isfinite(ray->origin.x + r->t_offset * ray->dir.x) &&
              isfinite(ray->origin.y + r->t_offset * ray->dir.y) &&
              isfinite(ray->origin.z + r->t_offset * ray->dir.z);
    if (!r->cull) r->t_offset = 0.0;
    r->tmin_offset = r->t_offset;
    const double o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    double big = fabs(d[0]);
    if (fabs(d[1]) > big) big = fabs(d[1]);
    if (fabs(d[2]) > big) big = fabs(d[2]);
    /* A direction far from unit length is scaled by a power of two, exactly,
     * so 1/d of its largest component stays well inside float's range: by
     * 2^(1-e), where 2^(e-1) is the power of two at or below the largest
     * |component| (read off its exponent bits), and t along the scaled
     * direction is t * 2^(e-1). Zero, subnormal and non-finite directions
     * are left as they are, which only makes their walk cull less. */
    double down = 1.0;
    r->t_scale = 1.0;
    if (!(big >= 0x1p-60 && big <= 0x1p60)) {
        uint64_t bits;
        memcpy(&bits, &big, sizeof bits);
        int biased = (int)(bits >> 52); /* big >= 0: no sign bit */
        if (biased >= 1 && biased <= 2046) {
            /* 2^(1023 - biased); for the largest binade that is 2^-1023,
             * a subnormal (still exact as a factor: the product is in
             * [1, 2)). */
            uint64_t down_bits = biased < 2046 ? (uint64_t)(2046 - biased) << 52 : 1ull << 51;
            uint64_t up_bits = (uint64_t)biased << 52;
            memcpy(&down, &down_bits, sizeof down);
            memcpy(&r->t_scale, &up_bits, sizeof r->t_scale);
        }
    }
    /* Whether some axis has a usable 1/d: the test's "an entry of +inf is a
     * miss" (accel_bvh4_test) needs one. A direction whose largest
     * component is subnormal has none (every 1/d overflows), and would
     * otherwise meet every box, empty slots included. */
    int usable = 0;
    for (int a = 0; a < 3; a++) {
        double da = d[a] * down;
        int neg = signbit(da) != 0;
        /* 1/0 is inf of the zero's sign: the parallel ray's slab test. A
         * 1/d beyond ACCEL_INV_MAX: NaN, so the axis culls nothing. */
        double i = 1.0 / da;
        float inv_near = (float)(i * (1.0 - ACCEL_SLACK)), inv_far = (float)(i * (1.0 + ACCEL_SLACK));
        if (!(fabs(i) <= ACCEL_INV_MAX) && da != 0) inv_near = inv_far = NAN;
        usable |= fabs(i) <= ACCEL_INV_MAX;
        float up, dn;
        if (r->t_offset == 0) {
            accel_float_bracket(o[a], &dn, &up);
            if (!(fabs(o[a]) <= ACCEL_CULL_RANGE)) r->cull = 0;
        } else {
            double moved = o[a] + r->t_offset * d[a];
            if (!(fabs(moved) <= ACCEL_CULL_RANGE)) r->cull = 0;
            double err = (fabs(o[a]) + fabs(r->t_offset * d[a])) * 0x1p-50;
            dn = accel_float_at_most(moved - err);
            up = accel_float_at_least(moved + err);
        }
        float on = neg ? dn : up, of = neg ? up : dn;
        size_t lo_at = offsetof(accel_bvh4_node, lo) + (size_t)a * 4 * sizeof(float);
        size_t hi_at = offsetof(accel_bvh4_node, hi) + (size_t)a * 4 * sizeof(float);
        r->near_at[a] = neg ? hi_at : lo_at;
        r->far_at[a] = neg ? lo_at : hi_at;
#if defined(__SSE2__)
        r->o_near[a] = _mm_set1_ps(on);
        r->o_far[a] = _mm_set1_ps(of);
        r->inv_near[a] = _mm_set1_ps(inv_near);
        r->inv_far[a] = _mm_set1_ps(inv_far);
#else
        r->o_near[a] = on;
        r->o_far[a] = of;
        r->inv_near[a] = inv_near;
        r->inv_far[a] = inv_far;
#endif
    }
    if (!usable) r->cull = 0;
}

#if defined(__SSE2__)
/* A prepared ray for the flipped node test (accel_bvh4_test_as): its
 * inverses negated, NaN lanes included (a sign flip, exact). */
static inline void accel_ray4_flip(accel_ray4 *r)
{
    const __m128 sign = _mm_set1_ps(-0.0f);
    for (int a = 0; a < 3; a++) {
        r->inv_near[a] = _mm_xor_ps(r->inv_near[a], sign);
        r->inv_far[a] = _mm_xor_ps(r->inv_far[a], sign);
    }
}
#endif

#if defined(__SSE2__)
/* The same preparation, bit for bit, for the common ray, three axes at a
 * time: tmin finite and not negative (so t_offset is 0), every direction
 * component at most 2^39 in size and one at least 2^-39 (so no scaling,
 * t_scale 1, and that one's 1/d is usable), every origin component within
 * ACCEL_CULL_RANGE (so float's range needs no clamp). Returns 0, having
 * written nothing, for any other ray. The arithmetic is
 * accel_ray4_init_any's, operation for operation, in SSE2 lanes that round
 * as the scalar operations do; tests/accel/test_bvh4_ray_init.c compares
 * the two on rays around every one of these limits.
 *
 * flipped (a constant): the inverses come out negated, as accel_ray4_flip
 * makes them, bit for bit: -1/d is -(1/d), and a product and a conversion
 * round a negated value to the negated result; NaN lanes get NaN with its
 * sign flipped. One division by -1 instead of six xors after the stores. */
ACCEL_ALWAYS_INLINE int accel_ray4_init_common_within(accel_ray4 *r, const hr_ray *ray, double tmin,
                                                      int flipped, double origin_reach)
{
    /* Lanes x, y in one double vector, z in another (its upper lane 0). */
    const __m128d dxy = _mm_loadu_pd(&ray->dir.x), dz = _mm_load_sd(&ray->dir.z);
    const __m128d oxy = _mm_loadu_pd(&ray->origin.x), oz = _mm_load_sd(&ray->origin.z);
    const __m128d abs_mask = _mm_castsi128_pd(_mm_set1_epi64x(INT64_MAX));
    const __m128d adxy = _mm_and_pd(dxy, abs_mask), adz = _mm_and_pd(dz, abs_mask);
    /* Every lane within its limits (NaN fails every compare; z's upper
     * lane, 0, passes), and some direction component large enough. */
    const __m128d d_most = _mm_set1_pd(0x1p39), d_least = _mm_set1_pd(0x1p-39);
    const __m128d o_most = _mm_set1_pd(origin_reach);
    const __m128d within =
        _mm_and_pd(_mm_and_pd(_mm_cmple_pd(adxy, d_most), _mm_cmple_pd(_mm_and_pd(oxy, abs_mask), o_most)),
                   _mm_and_pd(_mm_cmple_pd(adz, d_most), _mm_cmple_pd(_mm_and_pd(oz, abs_mask), o_most)));
    const __m128d large = _mm_or_pd(_mm_cmpge_pd(adxy, d_least), _mm_cmpge_pd(adz, d_least));
    /* One branch for the four conditions: & on their int values. */
    if (!((int)(tmin >= 0) & (int)(tmin < INFINITY) & (int)(_mm_movemask_pd(within) == 3) &
          (int)(_mm_movemask_pd(large) != 0)))
        return 0;
    const __m128d one = _mm_set1_pd(flipped ? -1.0 : 1.0), zero = _mm_setzero_pd();
    const __m128d ixy = _mm_div_pd(one, dxy), iz = _mm_div_sd(one, dz);
    /* Where 1/d passes ACCEL_INV_MAX for a non-zero d: NaN, as a mask of
     * float lanes x, y, z (each double mask's low half). */
    const __m128d inv_max = _mm_set1_pd(ACCEL_INV_MAX);
    const __m128d nan_xy = _mm_and_pd(_mm_cmpnle_pd(_mm_and_pd(ixy, abs_mask), inv_max), _mm_cmpneq_pd(dxy, zero));
    const __m128d nan_z = _mm_and_pd(_mm_cmpnle_pd(_mm_and_pd(iz, abs_mask), inv_max), _mm_cmpneq_pd(dz, zero));
    const __m128 nan_lanes = _mm_shuffle_ps(_mm_castpd_ps(nan_xy), _mm_castpd_ps(nan_z), _MM_SHUFFLE(2, 0, 2, 0));
    const __m128d near_scale = _mm_set1_pd(1.0 - ACCEL_SLACK), far_scale = _mm_set1_pd(1.0 + ACCEL_SLACK);
    const __m128 nan4 = _mm_set1_ps(flipped ? -NAN : NAN);
#define ACCEL_LANES3(xy, z) _mm_movelh_ps(_mm_cvtpd_ps(xy), _mm_cvtpd_ps(z))
    __m128 inv_near = ACCEL_LANES3(_mm_mul_pd(ixy, near_scale), _mm_mul_pd(iz, near_scale));
    __m128 inv_far = ACCEL_LANES3(_mm_mul_pd(ixy, far_scale), _mm_mul_pd(iz, far_scale));
    inv_near = _mm_or_ps(_mm_andnot_ps(nan_lanes, inv_near), _mm_and_ps(nan_lanes, nan4));
    inv_far = _mm_or_ps(_mm_andnot_ps(nan_lanes, inv_far), _mm_and_ps(nan_lanes, nan4));
    /* accel_float_bracket, without its clamp (the origin is within
     * float's range here). */
    const __m128 f = ACCEL_LANES3(oxy, oz);
    const __m128 step = _mm_add_ps(_mm_mul_ps(_mm_and_ps(f, _mm_castsi128_ps(_mm_set1_epi32(INT32_MAX))),
                                              _mm_set1_ps(0x1p-23f)),
                                   _mm_set1_ps(0x1p-149f));
    const __m128 dn = _mm_sub_ps(f, step), up = _mm_add_ps(f, step);
    /* The direction's signs, as lanes and bits (float keeps the sign of
     * every double, a zero's included). */
    const __m128 df = ACCEL_LANES3(dxy, dz);
#undef ACCEL_LANES3
    const __m128 neg = _mm_castsi128_ps(_mm_srai_epi32(_mm_castps_si128(df), 31));
    const __m128 on = _mm_or_ps(_mm_and_ps(neg, dn), _mm_andnot_ps(neg, up));
    const __m128 of = _mm_or_ps(_mm_and_ps(neg, up), _mm_andnot_ps(neg, dn));
    /* Each axis's plane offsets in a node: lo's and hi's rows swapped where
     * the direction is negative, as integer lanes (one and, an add and a
     * subtract for the three axes; each offset is below 2^16, so one
     * 16-bit extract reads it). */
    const int lo_at = (int)offsetof(accel_bvh4_node, lo), hi_at = (int)offsetof(accel_bvh4_node, hi);
    const int row = 4 * (int)sizeof(float);
    const __m128i swap = _mm_and_si128(_mm_castps_si128(neg), _mm_set1_epi32(hi_at - lo_at));
    const __m128i near_at = _mm_add_epi32(_mm_setr_epi32(lo_at, lo_at + row, lo_at + 2 * row, 0), swap);
    const __m128i far_at = _mm_sub_epi32(_mm_setr_epi32(hi_at, hi_at + row, hi_at + 2 * row, 0), swap);
#define ACCEL_AXIS(a, lanes)                                                                   \
    do {                                                                                       \
        r->near_at[a] = (size_t)_mm_extract_epi16(near_at, 2 * (a));                           \
        r->far_at[a] = (size_t)_mm_extract_epi16(far_at, 2 * (a));                             \
        r->o_near[a] = _mm_shuffle_ps(on, on, lanes);                                          \
        r->o_far[a] = _mm_shuffle_ps(of, of, lanes);                                           \
        r->inv_near[a] = _mm_shuffle_ps(inv_near, inv_near, lanes);                            \
        r->inv_far[a] = _mm_shuffle_ps(inv_far, inv_far, lanes);                               \
    } while (0)
    ACCEL_AXIS(0, _MM_SHUFFLE(0, 0, 0, 0));
    ACCEL_AXIS(1, _MM_SHUFFLE(1, 1, 1, 1));
    ACCEL_AXIS(2, _MM_SHUFFLE(2, 2, 2, 2));
#undef ACCEL_AXIS
    r->t_scale = 1.0;
    r->t_offset = r->tmin_offset = 0.0;
    r->cull = 1;
    return 1;
}
/* With origins within ACCEL_CULL_RANGE; a walk takes those within its
 * tree's origin_reach (accel_ray4_init_common_within). */
ACCEL_ALWAYS_INLINE int accel_ray4_init_common_as(accel_ray4 *r, const hr_ray *ray, double tmin, int flipped)
{
    return accel_ray4_init_common_within(r, ray, tmin, flipped, ACCEL_CULL_RANGE);
}
ACCEL_ALWAYS_INLINE int accel_ray4_init_common(accel_ray4 *r, const hr_ray *ray, double tmin)
{
    return accel_ray4_init_common_as(r, ray, tmin, 0);
}
#endif

/* For a walk over [tmin, ...], with the node test flipped or not
 * (accel_bvh4_test_as; flipped only where SSE2 is). */
ACCEL_ALWAYS_INLINE void accel_ray4_init_as(accel_ray4 *r, const hr_ray *ray, double tmin, int flipped)
{
#if defined(__SSE2__)
    if (accel_ray4_init_common_as(r, ray, tmin, flipped)) return;
    /* The general form writes a copy of its own: *r's address then never
     * leaves the caller, whose compiler may keep the common ray's fields
     * in registers instead of storing and reloading them. */
    accel_ray4 any;
    accel_ray4_init_any(&any, ray, tmin);
    if (flipped) accel_ray4_flip(&any);
    *r = any;
#else
    (void)flipped;
    accel_ray4_init_any(r, ray, tmin);
#endif
}

/* The float bounds of a ray's interval, in the walk's t. The upper one is
 * at most the largest float (NaN stays NaN): the test's "an entry of +inf
 * is a miss" then comes free with "the entry is below the exit", since an
 * entry at or below FLT_MAX is finite (accel_bvh4_test). An exit clamped
 * so culls exactly what +inf did: every entry the test passes is finite. */
static inline float accel_ray4_tmin(const accel_ray4 *r, double tmin)
{
    return accel_float_at_most((tmin - r->tmin_offset) * r->t_scale);
}
static inline float accel_ray4_tmax(const accel_ray4 *r, double tmax)
{
    float t = accel_float_at_least((tmax - r->t_offset) * r->t_scale);
    return t > FLT_MAX ? FLT_MAX : t;
}

/* Which of a node's four children the ray may meet within [tmin, tmax]
 * (floats from accel_ray4_tmin/_tmax, tmin >= 0 by construction): bit k
 * for child k, with a lower bound of where it enters in entry[k]. With the
 * interval at t >= 0, only positive slab distances can decide a test, and
 * for those the slack in inv_near (inv_far) makes the entry smaller (the
 * exit larger); a negative distance stays negative. (A far origin's walk,
 * accel_ray4_init_far, may have tmin < 0, with every box wholly ahead of
 * its moved origin: for a box ahead the same argument holds.)
 *
 * An entry of +inf is a miss: no hit lies there. The test needs no compare
 * of its own for it: the exit is at most tmax + 2^-149, which is at most
 * FLT_MAX (accel_ray4_tmax; rounding is monotone and FLT_MAX + 2^-149
 * rounds to FLT_MAX), so "entry <= exit" already says "entry < +inf".
 * Clamping tmax there gives the same mask, bit for bit, as testing
 * "entry < +inf" beside an unclamped exit: fl(min(h, FLT_MAX) + 2^-149)
 * is min(fl(h + 2^-149), FLT_MAX) for every h. That is also what keeps an
 * empty slot (lo = +inf, hi = -inf) from ever being met, with no test of
 * its own: along the direction's largest component 1/d is finite, and of
 * that axis's two slab distances at least one is an infinity on the
 * missing side (+inf entering or -inf leaving); the other may be NaN
 * (inf - inf, an origin beyond float's range), which the max/min ignore,
 * but both cannot be, since the origin cannot be beyond both ends. */
#if defined(__SSE2__)
typedef __m128 accel_f4; /* a float in every lane, for the four boxes at once */
static inline accel_f4 accel_f4_set(float x) { return _mm_set1_ps(x); }
#else
typedef float accel_f4;
static inline accel_f4 accel_f4_set(float x) { return x; }
#endif

/* flipped: r's inverses are negated (accel_bvh4_walk_core) and each slab
 * distance is taken as (o - b) * -(1/d) rather than (b - o) * (1/d). That
 * is the same value, since rounding is symmetric, but for the sign of a
 * zero, which no compare sees and the entry's and exit's 2^-149 steps
 * below erase (-0 - 2^-149 and +0 - 2^-149 are both -2^-149): the same
 * mask and entries, bit for bit. With AVX's three-operand form it reads
 * the box straight from memory, a load and a copy fewer per slab. */
/* The byte offset of axis a's near (far: !near) plane in a node for a ray
 * whose direction's sign bits are `octant` (bit a: component a negative),
 * as accel_ray4_init_as sets near_at and far_at. */
#define ACCEL_PLANE_AT(octant, a, near)                                                  \
    ((((octant) >> (a) & 1) == !(near) ? offsetof(accel_bvh4_node, lo)                   \
                                       : offsetof(accel_bvh4_node, hi)) +                \
     (size_t)(a) * 4 * sizeof(float))

/* octant: -1, the planes as r->near_at and r->far_at give them; 0 .. 7 (a
 * constant, which must be the ray's: accel_bvh4_walk_avx2), the same
 * offsets as constants, so that a walk keeps none of them in registers. */
ACCEL_ALWAYS_INLINE unsigned accel_bvh4_test_at(const accel_ray4 *r, const accel_bvh4_node *n,
                                                accel_f4 tmin, accel_f4 tmax, float entry[4],
                                                int flipped, int octant)
{
    const char *base = (const char *)n;
#if defined(__SSE2__)
    __m128 lo = tmin, hi = tmax;
    /* Written out axis by axis (a loop kept its counter and reloaded the
     * offsets every node). max(x, acc) is x > acc ? x : acc: a NaN x leaves
     * acc as it was. */
#define ACCEL_NEAR_AT(a) (octant < 0 ? r->near_at[a] : ACCEL_PLANE_AT(octant, a, 1))
#define ACCEL_FAR_AT(a) (octant < 0 ? r->far_at[a] : ACCEL_PLANE_AT(octant, a, 0))
#define ACCEL_SLAB(a)                                                                   \
    do {                                                                                \
        const __m128 bn_ = _mm_loadu_ps((const float *)(const void *)(base + ACCEL_NEAR_AT(a))); \
        const __m128 bf_ = _mm_loadu_ps((const float *)(const void *)(base + ACCEL_FAR_AT(a)));  \
        const __m128 dn_ = flipped ? _mm_sub_ps(r->o_near[a], bn_) : _mm_sub_ps(bn_, r->o_near[a]); \
        const __m128 df_ = flipped ? _mm_sub_ps(r->o_far[a], bf_) : _mm_sub_ps(bf_, r->o_far[a]);   \
        lo = _mm_max_ps(_mm_mul_ps(dn_, r->inv_near[a]), lo);                            \
        hi = _mm_min_ps(_mm_mul_ps(df_, r->inv_far[a]), hi);                             \
    } while (0)
    ACCEL_SLAB(0);
    ACCEL_SLAB(1);
    ACCEL_SLAB(2);
#undef ACCEL_SLAB
#undef ACCEL_NEAR_AT
#undef ACCEL_FAR_AT
    const __m128 tiny = _mm_set1_ps(ACCEL_TINY);
    lo = _mm_sub_ps(lo, tiny);
    hi = _mm_add_ps(hi, tiny);
    _mm_storeu_ps(entry, lo);
    return (unsigned)_mm_movemask_ps(_mm_cmple_ps(lo, hi));
#else
    unsigned mask = 0;
    for (int k = 0; k < 4; k++) {
        float lo = tmin, hi = tmax;
        for (int a = 0; a < 3; a++) {
            const float *bn = (const float *)(const void *)(base + r->near_at[a]);
            const float *bf = (const float *)(const void *)(base + r->far_at[a]);
            float tn = (bn[k] - r->o_near[a]) * r->inv_near[a];
            float tf = (bf[k] - r->o_far[a]) * r->inv_far[a];
            lo = tn > lo ? tn : lo;
            hi = tf < hi ? tf : hi;
        }
        lo -= ACCEL_TINY;
        hi += ACCEL_TINY;
        entry[k] = lo;
        if (lo <= hi) mask |= 1u << k;
    }
    (void)flipped, (void)octant; /* the lane-by-lane form has no use for them */
    return mask;
#endif
}
ACCEL_ALWAYS_INLINE unsigned accel_bvh4_test_as(const accel_ray4 *r, const accel_bvh4_node *n,
                                                accel_f4 tmin, accel_f4 tmax, float entry[4],
                                                int flipped)
{
    return accel_bvh4_test_at(r, n, tmin, tmax, entry, flipped, -1);
}
static inline unsigned accel_bvh4_test(const accel_ray4 *r, const accel_bvh4_node *n,
                                       accel_f4 tmin, accel_f4 tmax, float entry[4])
{
    return accel_bvh4_test_as(r, n, tmin, tmax, entry, 0);
}

/* A t at or before every point of the line p + t d that lies in the cube
 * [-c, c]^3 (at or before where the line enters it): the largest of the
 * near planes' distances, each with two roundings (relative 2^-52), moved
 * back by 2^-48 of itself. Axes with d = 0 bound nothing here. */
static inline double accel_cube_entry(const double p[3], const double d[3], double c)
{
    double t = -INFINITY;
    for (int a = 0; a < 3; a++) {
        if (d[a] == 0.0) continue;
        const double ta = ((d[a] > 0.0 ? -c : c) - p[a]) / d[a];
        if (ta > t) t = ta;
    }
    return t - fabs(t) * 0x1p-48;
}

/* For a ray accel_ray4_init_any leaves with no interval to cull by whose
 * line is finite: an origin beyond ACCEL_CULL_RANGE (a shadow ray from 1e21
 * away toward a light beside a mesh walked every leaf of the mesh: a fuzz
 * input), or tmin = -inf; and for an origin whose float bracket would blur
 * the boxes (accel_origin_far). The boxes lie in the cube |x| <= extent, so the
 * origin can move along the line to just before the cube [-c, c]^3,
 * c = 2 extent + 2^-20, without passing a box: by t1 + t2, two steps
 * toward the cube's entry (accel_cube_entry), the second from where the
 * first arrived, each step's product and sum exact (shape_two_product,
 * shape_two_sum), so the
 * moved origin is known within 2^-50 of its size and of the terms left
 * over, whatever the first distance was; the walk then culls as for a ray
 * from there. Returns 1 with *r prepared (unflipped), 0 where that does
 * not hold (the walk visits every leaf), -1 where the line misses the cube
 * (parallel to an axis, outside its slab): no box is met. The walk's tmin
 * is below 0 where the move passes the caller's tmin; no box lies there. */
static __attribute__((noinline, unused)) int accel_ray4_init_far(accel_ray4 *r, const hr_ray *ray, double tmin,
                                                                 double extent)
{
    const double o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    const double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    if (!(tmin < INFINITY) || !(extent <= ACCEL_CULL_RANGE)) return 0;
    const double c = 2.0 * extent + 0x1p-20;
    for (int a = 0; a < 3; a++) {
        if (!isfinite(o[a]) || !isfinite(d[a])) return 0;
        if (d[a] == 0.0 && !(fabs(o[a]) <= c)) return -1;
    }
    double t1 = accel_cube_entry(o, d, c);
    if (tmin > t1) t1 = tmin;
    if (!isfinite(t1)) return 0;
    double s[3], lo1[3], m1[3];
    for (int a = 0; a < 3; a++) {
        double pe, se;
        const double p = shape_two_product(t1, d[a], &pe);
        s[a] = shape_two_sum(o[a], p, &se);
        lo1[a] = se + pe; /* o + t1 d = s + lo1, within 2^-53 |lo1| */
        m1[a] = s[a] + lo1[a];
    }
    const double t2 = accel_cube_entry(m1, d, c);
    if (!isfinite(t2)) return 0;
    hr_ray moved = *ray;
    double m2[3], err[3];
    for (int a = 0; a < 3; a++) {
        double qe, sum_e;
        const double q = shape_two_product(t2, d[a], &qe);
        const double sum = shape_two_sum(s[a], q, &sum_e);
        m2[a] = sum + ((lo1[a] + sum_e) + qe);
        err[a] = (fabs(m2[a]) + fabs(lo1[a]) + fabs(sum_e) + fabs(qe)) * 0x1p-50 + 0x1p-1060;
        if (!(fabs(m2[a]) + err[a] <= ACCEL_CULL_RANGE)) return 0;
    }
    moved.origin.x = m2[0], moved.origin.y = m2[1], moved.origin.z = m2[2];
    accel_ray4_init_any(r, &moved, 0.0);
    if (!r->cull) return 0;
    for (int a = 0; a < 3; a++) {
        const float dn = accel_float_at_most(m2[a] - err[a]), up = accel_float_at_least(m2[a] + err[a]);
        const int neg = r->near_at[a] == offsetof(accel_bvh4_node, hi) + (size_t)a * 4 * sizeof(float);
#if defined(__SSE2__)
        r->o_near[a] = _mm_set1_ps(neg ? dn : up);
        r->o_far[a] = _mm_set1_ps(neg ? up : dn);
#else
        r->o_near[a] = neg ? dn : up;
        r->o_far[a] = neg ? up : dn;
#endif
    }
    /* The move is t1 + t2, which a double holds within 2^-53 of its size;
     * the walk's t is then (t - t_offset) * t_scale with one more rounding,
     * within 2^-53 of the result, which the node test's slack covers. So
     * both ends move out by 2^-50 of the terms (each of those roundings and
     * this one's, with room): along the line the walk culls no closer than
     * that, across it as closely as from an origin beside the boxes. */
    const double sum = t1 + t2, pad = (fabs(t1) + fabs(t2)) * 0x1p-50;
    r->t_offset = sum - pad;
    r->tmin_offset = sum + pad;
    return 1;
}

/* Whether the ray's origin lies beyond bvh->origin_reach: past
 * ACCEL_CULL_RANGE (the walk cannot cull from it), or, in a tree built
 * with move_far_origins, past ACCEL_FAR_ORIGIN times the cube of
 * accel_ray4_init_far, so far from the boxes that its float bracket, 2^-24
 * of its size, would blur them. The walk then culls from the origin moved
 * up to the cube. Shadow rays from 2^31 to 2^61 away (within
 * ACCEL_CULL_RANGE, so culling by the float bracket), past 104 coincident
 * teapots, walked every leaf of each (a fuzz input). Within 2^12 the blur
 * is under 2^-12 of the cube, and the move would cost more than the
 * leaves the blur lets in. */
#define ACCEL_FAR_ORIGIN 0x1p12

static inline int accel_origin_far(const accel_bvh4 *bvh, const hr_ray *ray)
{
    const double reach = bvh->origin_reach;
    return !(fabs(ray->origin.x) <= reach && fabs(ray->origin.y) <= reach && fabs(ray->origin.z) <= reach);
}

/* What a walk's leaf callback returns. */
#define ACCEL_WALK_GO_ON 0
#define ACCEL_WALK_STOP 1

/* The walk of a ray with no interval to cull by (accel_ray4_init_as): every
 * leaf, in the order the culling walk would take them were every entry
 * -inf (all ties): depth first, the first child of a node first, then the
 * others in slot order (ordered) or, as the unordered walk stacks them,
 * the last first. Out of line: it is rare, and slow anyway. */
static int accel_bvh4_walk_every(const accel_bvh4 *bvh,
                                 int (*leaf)(void *user, uint32_t first, uint32_t count),
                                 void *user, int ordered)
{
    uint32_t stack_ref[ACCEL_BVH4_STACK], stack_count[ACCEL_BVH4_STACK];
    uint32_t top = 0;
    uint32_t ref = 0, count = 0; /* the root, an inner node */
    for (;;) {
        if (count > 0) {
            if (leaf(user, ref, count) == ACCEL_WALK_STOP) return ACCEL_WALK_STOP;
        } else {
            const accel_bvh4_node *n = &bvh->nodes[ref];
            unsigned mask = 0;
            for (uint32_t k = 0; k < 4; k++)
                mask |= (uint32_t)(n->count[k] > 0 || n->ref[k] != ACCEL_BVH4_EMPTY) << k;
            if (mask) {
                uint32_t k = (uint32_t)__builtin_ctz(mask);
                mask &= mask - 1;
                for (uint32_t j = 0; j < 4; j++) {
                    uint32_t c = ordered ? 3 - j : j;
                    if (!(mask >> c & 1)) continue;
                    stack_ref[top] = n->ref[c], stack_count[top++] = n->count[c];
                }
                ref = n->ref[k], count = n->count[k];
                continue;
            }
        }
        if (top == 0) return ACCEL_WALK_GO_ON;
        --top;
        ref = stack_ref[top], count = stack_count[top];
    }
}

typedef int (*accel_walk_fn)(const accel_bvh4 *bvh, const hr_ray *ray, double tmin, double *tmax,
                             int (*leaf)(void *user, uint32_t first, uint32_t count), void *user);

/* In a nearest-first walk (this one's and the 8-wide one's), of two
 * children met, k and the one left in mask: go on with the nearer (k) and
 * stack the farther (the later slot, c, on a tie, as the sort of three or
 * more does). */
#define ACCEL_WALK_TWO()                                                                           \
    do {                                                                                           \
        uint32_t c = (uint32_t)__builtin_ctz(mask);                                                \
        if (entry[c] < entry[k]) {                                                                 \
            const uint32_t t = c;                                                                  \
            c = k, k = t;                                                                          \
        }                                                                                          \
        stack_ref[top] = n->ref[c], stack_count[top] = n->count[c];                                \
        stack_entry[top++] = entry[c];                                                             \
    } while (0)

/* The end of a nearest-first walk's loop (this one's and the 8-wide one's,
 * accel/bvh8.h), once it has chosen child k of node n to go on with: into
 * it if it is an inner node, else its leaf, then the next stacked child
 * that may still hold something nearer than the best hit, which may have
 * come nearer since it was pushed. `reload` is run when a leaf lowered
 * *tmax, to take the new value (tmax_f, and the walk's vector of it). */
#define ACCEL_WALK_ON(reload)                                                                      \
    ref = n->ref[k], count = n->count[k];                                                          \
    if (count == 0) {                                                                              \
        n = nodes + ref;                                                                           \
        continue;                                                                                  \
    }                                                                                              \
    leaf:;                                                                                         \
    {                                                                                              \
        const double before = *tmax;                                                               \
        if (leaf(user, ref, count) == ACCEL_WALK_STOP) return ACCEL_WALK_STOP;                    \
        if (*tmax != before) reload;                                                               \
    }                                                                                              \
    next:                                                                                          \
    do {                                                                                           \
        if (top == 0) return ACCEL_WALK_GO_ON;                                                     \
        --top;                                                                                     \
    } while (stack_entry[top] > tmax_f);                                                           \
    ref = stack_ref[top], count = stack_count[top];                                                \
    if (count > 0) goto leaf;                                                                      \
    n = nodes + ref

/* The walk of accel_bvh4_walk (ordered: nearest entry first, the earlier
 * slot on a tie) and of accel_bvh4_walk_any (children in slot order), with
 * the node test flipped or not (accel_bvh4_test_as). */
ACCEL_ALWAYS_INLINE int accel_bvh4_walk_octant(const accel_bvh4 *bvh, const hr_ray *ray, double tmin,
                                               double *tmax,
                                               int (*leaf)(void *user, uint32_t first, uint32_t count),
                                               void *user, int ordered, int flipped, int octant,
                                               accel_walk_fn uncommon)
{
    if (!bvh->nodes) return ACCEL_WALK_GO_ON;
    accel_ray4 r;
#if defined(__SSE2__)
    /* uncommon (a constant): the walk for any ray accel_ray4_init_common_as
     * does not take, so that this one knows t_offset 0, t_scale 1 and cull
     * 1 as constants (fewer values live, less to work out per ray). */
    if (uncommon) {
        if (!accel_ray4_init_common_within(&r, ray, tmin, flipped, bvh->origin_reach))
            return uncommon(bvh, ray, tmin, tmax, leaf, user);
    } else {
        accel_ray4_init_as(&r, ray, tmin, flipped);
    }
#else
    (void)uncommon;
    accel_ray4_init_as(&r, ray, tmin, flipped);
#endif
    if (!(bvh->extent <= ACCEL_CULL_RANGE)) r.cull = 0; /* the origin: accel_ray4_init_as */
    /* A far origin is moved by the unflipped (SSE2) walks alone: the AVX2
     * walks hand them every such ray (uncommon), and stay free of the
     * check (in them GCC moved a double between registers with a
     * VEX-encoded movq that valgrind 3.19 cannot decode, and memcheck
     * runs every walk). */
    if (!r.cull || (!flipped && accel_origin_far(bvh, ray))) {
        /* Into a copy: r's address stays in this function (see
         * accel_ray4_init_as). A far origin that cannot be moved keeps
         * the float bracket's culling. */
        accel_ray4 moved;
        const int far = accel_ray4_init_far(&moved, ray, tmin, bvh->extent);
        if (far < 0) return ACCEL_WALK_GO_ON;
        if (!far && !r.cull) return accel_bvh4_walk_every(bvh, leaf, user, ordered);
        if (far) {
#if defined(__SSE2__)
            if (flipped) accel_ray4_flip(&moved);
#endif
            r = moved;
        }
    }
    const accel_f4 tmin4 = accel_f4_set(accel_ray4_tmin(&r, tmin));
    float tmax_f = accel_ray4_tmax(&r, *tmax);
    accel_f4 tmax4 = accel_f4_set(tmax_f);
    uint32_t stack_ref[ACCEL_BVH4_STACK], stack_count[ACCEL_BVH4_STACK];
    float stack_entry[ACCEL_BVH4_STACK];
    uint32_t top = 0;
    const accel_bvh4_node *const nodes = bvh->nodes;
    const accel_bvh4_node *n = nodes; /* the root, an inner node */
    uint32_t ref, count;
    for (;;) {
        float entry[4];
        unsigned mask = accel_bvh4_test_at(&r, n, tmin4, tmax4, entry, flipped, octant);
        if (!mask) goto next;
        uint32_t k = (uint32_t)__builtin_ctz(mask);
        mask &= mask - 1;
        if (mask && !ordered) {
            /* Two or more, any order: stack all but the first. */
            for (unsigned rest = mask; rest; rest &= rest - 1) {
                uint32_t c = (uint32_t)__builtin_ctz(rest);
                stack_ref[top] = n->ref[c], stack_count[top] = n->count[c];
                stack_entry[top++] = entry[c];
            }
        } else if (mask && !(mask & (mask - 1))) {
            /* Exactly two (the most common case). */
            ACCEL_WALK_TWO();
        } else if (mask) {
#if defined(__SSE2__)
            /* Three or four: stack all but the nearest, farthest first, in
             * the order of a stable sort by entry (slot order on a tie), as
             * the insertion sort below gives it. Each child's place is its
             * rank: the children met that enter before it, or at the same
             * entry from an earlier slot (entries of children met are
             * never NaN, tmin being finite: accel_bvh4_test_at), counted
             * for the four lanes at once against the entries rotated by
             * one, two and three slots; a child not met enters at +inf
             * and so counts for none. Rank r goes to top + hits - 1 - r;
             * rank 0, the nearest, to the slot above the new top, which
             * is scratch (the stack has 4 slots beyond the 3 a level). */
            const uint32_t met = mask | 1u << k, hits = (uint32_t)__builtin_popcount(met);
            const __m128i slot_bits = _mm_setr_epi32(1, 2, 4, 8);
            const __m128 is_met = _mm_castsi128_ps(
                _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)met), slot_bits), slot_bits));
            const __m128 e = _mm_or_ps(_mm_and_ps(is_met, _mm_loadu_ps(entry)),
                                       _mm_andnot_ps(is_met, _mm_set1_ps(INFINITY)));
            /* Lane c of a rotation by s holds slot (c + s) % 4, an earlier
             * slot exactly in lanes c >= 4 - s. */
#define ACCEL_BEFORE(rot, earlier)                                                                  \
    _mm_castps_si128(_mm_or_ps(_mm_cmplt_ps(rot, e),                                                \
                               _mm_and_ps(_mm_cmpeq_ps(rot, e), _mm_castsi128_ps(earlier))))
            __m128i rank = ACCEL_BEFORE(_mm_shuffle_ps(e, e, _MM_SHUFFLE(0, 3, 2, 1)), _mm_setr_epi32(0, 0, 0, -1));
            rank = _mm_add_epi32(rank, ACCEL_BEFORE(_mm_shuffle_ps(e, e, _MM_SHUFFLE(1, 0, 3, 2)),
                                                    _mm_setr_epi32(0, 0, -1, -1)));
            rank = _mm_add_epi32(rank, ACCEL_BEFORE(_mm_shuffle_ps(e, e, _MM_SHUFFLE(2, 1, 0, 3)),
                                                    _mm_setr_epi32(0, -1, -1, -1)));
#undef ACCEL_BEFORE
            int32_t minus_rank[4]; /* each lane counted -1 per child before it */
            _mm_storeu_si128((__m128i *)(void *)minus_rank, rank);
            const uint32_t last = top + hits - 1;
            for (unsigned rest = met; rest; rest &= rest - 1) {
                const uint32_t c = (uint32_t)__builtin_ctz(rest), at = last + (uint32_t)minus_rank[c];
                stack_ref[at] = n->ref[c], stack_count[at] = n->count[c];
                stack_entry[at] = entry[c];
                k = minus_rank[c] ? k : c;
            }
            top = last;
#else
            /* Three or four: stack all but the nearest, farthest first (an
             * insertion sort, by entry, stable: slot order on a tie). */
            uint32_t kid[4], hits = 1;
            float at[4];
            kid[0] = k, at[0] = entry[k];
            while (mask) {
                uint32_t c = (uint32_t)__builtin_ctz(mask), j = hits++;
                mask &= mask - 1;
                while (j > 0 && at[j - 1] > entry[c]) kid[j] = kid[j - 1], at[j] = at[j - 1], j--;
                kid[j] = c, at[j] = entry[c];
            }
            for (uint32_t j = hits - 1; j > 0; j--) {
                stack_ref[top] = n->ref[kid[j]], stack_count[top] = n->count[kid[j]];
                stack_entry[top++] = at[j];
            }
            k = kid[0];
#endif
        }
        ACCEL_WALK_ON((tmax_f = accel_ray4_tmax(&r, *tmax), tmax4 = accel_f4_set(tmax_f)));
    }
}

ACCEL_ALWAYS_INLINE int accel_bvh4_walk_core(const accel_bvh4 *bvh, const hr_ray *ray, double tmin,
                                             double *tmax,
                                             int (*leaf)(void *user, uint32_t first, uint32_t count),
                                             void *user, int ordered, int flipped)
{
    return accel_bvh4_walk_octant(bvh, ray, tmin, tmax, leaf, user, ordered, flipped, -1, NULL);
}

/* The same walks compiled for AVX2 CPUs, chosen at run time (the build
 * stays baseline x86-64): the node test flipped, so that each slab reads
 * its box as a memory operand of a three-operand subtract. No FMA: a fused
 * (b - o) * (1/d) would round once where the argument at the top counts
 * two, and would move entries, so the order leaves are visited in. The
 * same leaves in the same order as the SSE2 walk, entries bit for bit
 * (accel_bvh4_test_as); test_bvh4 compares the two leaf by leaf. */
#if defined(__SSE2__) && defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define ACCEL_WALK_AVX2 1
/* The SSE2 walks out of line as well: choosing between the two is then a
 * test and a tail call, with no stack frame of its own to set up on every
 * walk (inlined, the SSE2 walk's frame was built before the test). */
__attribute__((noinline, unused)) static int
accel_bvh4_walk_sse2(const accel_bvh4 *bvh, const hr_ray *ray, double tmin, double *tmax,
                     int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)
{
    return accel_bvh4_walk_core(bvh, ray, tmin, tmax, leaf, user, 1, 0);
}
__attribute__((noinline, unused)) static int
accel_bvh4_walk_any_sse2(const accel_bvh4 *bvh, const hr_ray *ray, double tmin, double *tmax,
                         int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)
{
    return accel_bvh4_walk_core(bvh, ray, tmin, tmax, leaf, user, 0, 0);
}
/* The nearest-first walk, the first-hit query's, once for each octant of
 * directions, its plane offsets constants: six offsets kept in registers
 * across the walk left too few for the rest, and four were reloaded from
 * the stack on every node. The octant is the
 * direction's sign bits, as accel_ray4_init_as reads them for near_at and
 * far_at: whenever the walk culls, the direction is finite and its scaling
 * is by a positive power of two, which keeps every sign (a zero's too).
 * Each copy takes only the common ray (accel_ray4_init_common_as) and
 * hands any other to the SSE2 walk, which visits the same leaves in the
 * same order: it is rare, and the copies then keep fewer values live. */
#define ACCEL_WALK_AVX2_OCTANT(o)                                                                 \
    __attribute__((target("avx2"), noinline, unused)) static int accel_bvh4_walk_avx2_##o(          \
        const accel_bvh4 *bvh, const hr_ray *ray, double tmin, double *tmax,                       \
        int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)                       \
    {                                                                                              \
        return accel_bvh4_walk_octant(bvh, ray, tmin, tmax, leaf, user, 1, 1, o,                   \
                                      accel_bvh4_walk_sse2);                                       \
    }
ACCEL_WALK_AVX2_OCTANT(0)
ACCEL_WALK_AVX2_OCTANT(1)
ACCEL_WALK_AVX2_OCTANT(2)
ACCEL_WALK_AVX2_OCTANT(3)
ACCEL_WALK_AVX2_OCTANT(4)
ACCEL_WALK_AVX2_OCTANT(5)
ACCEL_WALK_AVX2_OCTANT(6)
ACCEL_WALK_AVX2_OCTANT(7)
#undef ACCEL_WALK_AVX2_OCTANT
/* The octant of a direction: bit a set where component a's sign bit is
 * (two sign-bit reads; the z lane's load leaves its upper lane +0). */
static inline unsigned accel_octant(const hr_vec3 *d)
{
    return (unsigned)_mm_movemask_pd(_mm_loadu_pd(&d->x)) | (unsigned)_mm_movemask_pd(_mm_load_sd(&d->z)) << 2;
}
static inline int accel_bvh4_walk_avx2(const accel_bvh4 *bvh, const hr_ray *ray, double tmin,
                                       double *tmax,
                                       int (*leaf)(void *user, uint32_t first, uint32_t count),
                                       void *user)
{
    /* Direct calls, not a table: each copy is then specialised to its one
     * caller's callback (inlined into it), as the single walk was. */
    switch (accel_octant(&ray->dir)) {
    case 0: return accel_bvh4_walk_avx2_0(bvh, ray, tmin, tmax, leaf, user);
    case 1: return accel_bvh4_walk_avx2_1(bvh, ray, tmin, tmax, leaf, user);
    case 2: return accel_bvh4_walk_avx2_2(bvh, ray, tmin, tmax, leaf, user);
    case 3: return accel_bvh4_walk_avx2_3(bvh, ray, tmin, tmax, leaf, user);
    case 4: return accel_bvh4_walk_avx2_4(bvh, ray, tmin, tmax, leaf, user);
    case 5: return accel_bvh4_walk_avx2_5(bvh, ray, tmin, tmax, leaf, user);
    case 6: return accel_bvh4_walk_avx2_6(bvh, ray, tmin, tmax, leaf, user);
    default: return accel_bvh4_walk_avx2_7(bvh, ray, tmin, tmax, leaf, user);
    }
}
/* The any-order walk takes the common ray alone too, and hands any other
 * to the SSE2 walk (which moves far origins up to the boxes). */
__attribute__((target("avx2"))) static inline int
accel_bvh4_walk_any_avx2(const accel_bvh4 *bvh, const hr_ray *ray, double tmin, double *tmax,
                         int (*leaf)(void *user, uint32_t first, uint32_t count), void *user)
{
    return accel_bvh4_walk_octant(bvh, ray, tmin, tmax, leaf, user, 0, 1, -1, accel_bvh4_walk_any_sse2);
}
/* A load and a test after the first call (shape_kit_cpu.h). */
static inline int accel_walk_avx2_usable(void) { return shape_cpu_has_avx2(); }
#else
#define ACCEL_WALK_AVX2 0
#endif

/* The walk for this CPU. */
ACCEL_ALWAYS_INLINE int accel_bvh4_walk_as(const accel_bvh4 *bvh, const hr_ray *ray, double tmin,
                                           double *tmax,
                                           int (*leaf)(void *user, uint32_t first, uint32_t count),
                                           void *user, int ordered)
{
#if ACCEL_WALK_AVX2
    if (accel_walk_avx2_usable())
        return ordered ? accel_bvh4_walk_avx2(bvh, ray, tmin, tmax, leaf, user)
                       : accel_bvh4_walk_any_avx2(bvh, ray, tmin, tmax, leaf, user);
    return ordered ? accel_bvh4_walk_sse2(bvh, ray, tmin, tmax, leaf, user)
                   : accel_bvh4_walk_any_sse2(bvh, ray, tmin, tmax, leaf, user);
#else
    return accel_bvh4_walk_core(bvh, ray, tmin, tmax, leaf, user, ordered, 0);
#endif
}

/* Front-to-back walk: calls leaf(user, first, count) for each leaf the ray
 * may meet, nearest entry first, skipping what lies beyond *tmax. The
 * callback may lower *tmax (a nearer hit); the walk reads it after each
 * call. Returns ACCEL_WALK_STOP if a callback did. Inline, so the callback
 * and the ray stay in registers in the caller's loop. */
static inline int accel_bvh4_walk(const accel_bvh4 *bvh, const hr_ray *ray, double tmin,
                                  double *tmax,
                                  int (*leaf)(void *user, uint32_t first, uint32_t count),
                                  void *user)
{
    return accel_bvh4_walk_as(bvh, ray, tmin, tmax, leaf, user, 1);
}

/* The same walk with the children of a node in slot order, for a question
 * whose answer does not depend on the order leaves are asked in (is
 * anything hit at all: shadow rays), where sorting them costs more than it
 * saves. */
static inline int accel_bvh4_walk_any(const accel_bvh4 *bvh, const hr_ray *ray, double tmin,
                                      double *tmax,
                                      int (*leaf)(void *user, uint32_t first, uint32_t count),
                                      void *user)
{
    return accel_bvh4_walk_as(bvh, ray, tmin, tmax, leaf, user, 0);
}

/* The root children's boxes merged on axis a (an empty tree: lo +inf, hi
 * -inf): what accel_bvh4_root_missed_on is given, worked out once. */
static inline void accel_bvh4_root_span(const accel_bvh4 *bvh, int a, float *lo, float *hi)
{
    *lo = INFINITY, *hi = -INFINITY;
    if (!bvh->nodes) return;
    for (int k = 0; k < 4; k++) {
        if (bvh->nodes[0].lo[a][k] < *lo) *lo = bvh->nodes[0].lo[a][k];
        if (bvh->nodes[0].hi[a][k] > *hi) *hi = bvh->nodes[0].hi[a][k];
    }
}

/* Whether a walk from tmin (either walk, any tmax) would meet none of the
 * root's children, and so call no leaf, for the ray's progress along axis
 * a alone; lo and hi are accel_bvh4_root_span's for a. 1 only when that is
 * certain, 0 when it cannot tell (then walk). A few compares where the
 * walk prepares the whole ray first, for a caller whose tree is flat on an
 * axis, so that rays start beside it and run away from it (a ray leaving
 * a floor, in a scene whose BVH gives the floor's object a box a rounding
 * thick, so that the scene's walk asks it). It answers 1 when:
 * - the ray is one accel_ray4_init_common takes (tmin finite and not
 *   negative, |d| <= 2^39 and |o| <= ACCEL_CULL_RANGE on every axis, and
 *   |d[a]| >= 2^-39) and the tree culls (extent within ACCEL_CULL_RANGE),
 *   so the walk tests the root with that preparation, unscaled;
 * - d[a] > 0 and fl(hi - dn) <= -2^-100, dn being the origin's lower float
 *   bracket (accel_float_bracket, which init_common reproduces bit for
 *   bit). Each child's exit distance on a is then fl(fl(h - dn) * inv_far)
 *   (or the same value from the flipped form) for its h <= hi (-inf for an
 *   empty slot), with fl(h - dn) <= -2^-100 by monotone rounding and
 *   inv_far >= 2^-39 (1/d >= 2^-39, and not NaN as 1/d <= 2^39): at most
 *   -2^-139. The exit the test compares is a min that only falls (a NaN
 *   distance leaves it) plus 2^-149; the entry is a max that only rises,
 *   from tmin rounded down (>= -2^-149), less 2^-149, so >= -2^-148, which
 *   is above -2^-139 + 2^-149: no child is met.
 * - or d[a] < 0 the same way round: fl(lo - up) >= 2^-100, inv_far <= -2^-39.
 * test_bvh4 checks it against the walk on random trees and rays. */
static inline int accel_bvh4_root_missed_on(const accel_bvh4 *bvh, const hr_ray *ray, double tmin, int a,
                                            float lo, float hi)
{
    if (!bvh->nodes) return 1; /* the walk returns at once */
#if defined(__SSE2__)
    /* The axis first: most rays the caller asks about run towards the tree
     * and fail here, at a few instructions; then init_common's conditions
     * (as scalar compares: fewer instructions here than its lanes). */
    const hr_vec3 o = ray->origin, d = ray->dir;
    const double oa = a == 0 ? o.x : a == 1 ? o.y : o.z, da = a == 0 ? d.x : a == 1 ? d.y : d.z;
    if (!(fabs(da) >= 0x1p-39)) return 0;
    float dn, up;
    accel_float_bracket(oa, &dn, &up);
    if (!(da > 0 ? hi - dn <= -0x1p-100f : lo - up >= 0x1p-100f)) return 0;
    return tmin >= 0 && tmin < INFINITY && bvh->extent <= ACCEL_CULL_RANGE && fabs(d.x) <= 0x1p39 &&
           fabs(d.y) <= 0x1p39 && fabs(d.z) <= 0x1p39 && fabs(o.x) <= ACCEL_CULL_RANGE &&
           fabs(o.y) <= ACCEL_CULL_RANGE && fabs(o.z) <= ACCEL_CULL_RANGE;
#else
    (void)ray, (void)tmin, (void)a, (void)lo, (void)hi;
    return 0; /* no accel_ray4_init_common to reason from */
#endif
}

#endif
