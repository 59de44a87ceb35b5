/* A packet of up to eight rays walking a 4-wide BVH together (accel/bvh4.h):
 * one box against eight rays per AVX step, one stack and one visit of each
 * node for the packet, each leaf handed over with the lanes (rays) that
 * meet its box. For coherent rays (a camera's neighbouring pixels), which
 * meet mostly the same nodes.
 *
 * Each lane's slab test is accel_bvh4_test_at's, operation for operation,
 * on the values accel_ray4_init_common_as prepared for that ray (unflipped):
 * the same entry and the same verdict for each box as that ray's own walk
 * would compute with the same tmax. So the walk is conservative for every
 * lane by the argument at the top of bvh4.h: a lane is left out of a box
 * only when its exact ray misses the box within [tmin, tmax]. The order in
 * which leaves come is the packet's (nearest first by the least entry of
 * its lanes), not each ray's own: a caller whose answer could depend on the
 * order (a tie in t) must find that out itself.
 *
 * Only rays that accel_ray4_init_common_as takes, with one octant of
 * directions for the whole packet (the planes each axis meets first are
 * then the same), in a tree whose extent is within ACCEL_CULL_RANGE: the
 * caller walks any other ray alone. x86-64 with AVX2, chosen at run time
 * (accel_walk_avx2_usable); no FMA, as in bvh4.h. */
#ifndef HITRAY_ACCEL_BVH4_PACKET_H
#define HITRAY_ACCEL_BVH4_PACKET_H

#include "bvh4.h"

#if ACCEL_WALK_AVX2
#include <immintrin.h>
#define ACCEL_PACKET_WALK 1
#define ACCEL_PACKET 8

/* A packet prepared for the walk; the caller lowers tmax[k] (in the walk's
 * float t, accel_ray4_tmax) as lane k finds nearer hits. */
typedef struct accel_packet8 {
    __m256 o_near[3], o_far[3], inv_near[3], inv_far[3];
    __m256 tmin;
    float tmax[ACCEL_PACKET];
    unsigned lanes; /* bit k: lane k holds a ray */
} accel_packet8;

/* Up to eight rays, by component (ox[k] is ray k's origin.x, ...), as a
 * packet's preparation reads them; lanes past the rays hold copies of ray
 * 0, so every lane computes finite values. */
typedef struct accel_rays8 {
    double o[3][ACCEL_PACKET], d[3][ACCEL_PACKET];
} accel_rays8;

/* The lanes of `r` that accel_ray4_init_common_as takes (for tmin finite
 * and not negative, which the caller checks once): every direction
 * component at most 2^39 in size and one at least 2^-39, every origin
 * component within ACCEL_CULL_RANGE; and each lane's octant (bit a:
 * component a's sign bit), four bits a lane in *octants. */
__attribute__((target("avx2"))) static inline unsigned accel_rays8_common(const accel_rays8 *r, uint32_t *octants)
{
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
    const __m256d d_most = _mm256_set1_pd(0x1p39), d_least = _mm256_set1_pd(0x1p-39);
    const __m256d o_most = _mm256_set1_pd(ACCEL_CULL_RANGE);
    unsigned ok = 0;
    uint32_t oct = 0;
    for (int h = 0; h < 2; h++) {
        __m256d within = _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), large = _mm256_setzero_pd();
        unsigned sign[3];
        for (int a = 0; a < 3; a++) {
            const __m256d d = _mm256_loadu_pd(&r->d[a][4 * h]), o = _mm256_loadu_pd(&r->o[a][4 * h]);
            const __m256d ad = _mm256_and_pd(d, abs_mask);
            within = _mm256_and_pd(within, _mm256_and_pd(_mm256_cmp_pd(ad, d_most, _CMP_LE_OQ),
                                                         _mm256_cmp_pd(_mm256_and_pd(o, abs_mask), o_most, _CMP_LE_OQ)));
            large = _mm256_or_pd(large, _mm256_cmp_pd(ad, d_least, _CMP_GE_OQ));
            sign[a] = (unsigned)_mm256_movemask_pd(d);
        }
        ok |= (unsigned)_mm256_movemask_pd(_mm256_and_pd(within, large)) << (4 * h);
        for (int k = 0; k < 4; k++)
            oct |= ((sign[0] >> k & 1) | (sign[1] >> k & 1) << 1 | (sign[2] >> k & 1) << 2) << (4 * (4 * h + k));
    }
    *octants = oct;
    return ok;
}

/* The packet of the rays in `r` (lanes `lanes`, all of one octant, each
 * one accel_rays8_common takes), each lane what accel_ray4_init_common_as
 * (unflipped) computes for its ray, operation for operation: 1/d in double
 * scaled by 1 -+ ACCEL_SLACK and rounded to float, NaN where |1/d| passes
 * ACCEL_INV_MAX for a non-zero d; the origin rounded to float and stepped
 * down and up by |f| 2^-23 + 2^-149, the near one the side the direction
 * points away from. tmin and tmax are in the walk's t (accel_ray4_tmin,
 * _tmax; a lane not in `lanes` gets tmax -inf and meets no box). */
__attribute__((target("avx2"))) static inline void accel_packet8_init(accel_packet8 *p, const accel_rays8 *r,
                                                                      unsigned lanes, unsigned octant,
                                                                      float tmin, const float tmax[ACCEL_PACKET])
{
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
    const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd(), inv_max = _mm256_set1_pd(ACCEL_INV_MAX);
    const __m256d near_scale = _mm256_set1_pd(1.0 - ACCEL_SLACK), far_scale = _mm256_set1_pd(1.0 + ACCEL_SLACK);
    const __m128 nan4 = _mm_set1_ps(NAN);
    for (int a = 0; a < 3; a++) {
        __m128 in[2], fa[2], on[2], of[2];
        for (int h = 0; h < 2; h++) {
            const __m256d d = _mm256_loadu_pd(&r->d[a][4 * h]), o = _mm256_loadu_pd(&r->o[a][4 * h]);
            const __m256d i = _mm256_div_pd(one, d);
            const __m256d big = _mm256_and_pd(_mm256_cmp_pd(_mm256_and_pd(i, abs_mask), inv_max, _CMP_NLE_UQ),
                                              _mm256_cmp_pd(d, zero, _CMP_NEQ_UQ));
            /* The double mask's lanes as float lanes (their low halves). */
            const __m256 big_f = _mm256_castpd_ps(big);
            const __m128 mask = _mm_shuffle_ps(_mm256_castps256_ps128(big_f), _mm256_extractf128_ps(big_f, 1),
                                               _MM_SHUFFLE(2, 0, 2, 0));
            const __m128 n = _mm256_cvtpd_ps(_mm256_mul_pd(i, near_scale));
            const __m128 f = _mm256_cvtpd_ps(_mm256_mul_pd(i, far_scale));
            in[h] = _mm_or_ps(_mm_andnot_ps(mask, n), _mm_and_ps(mask, nan4));
            fa[h] = _mm_or_ps(_mm_andnot_ps(mask, f), _mm_and_ps(mask, nan4));
            const __m128 of_ = _mm256_cvtpd_ps(o);
            const __m128 step = _mm_add_ps(_mm_mul_ps(_mm_and_ps(of_, _mm_castsi128_ps(_mm_set1_epi32(INT32_MAX))),
                                                      _mm_set1_ps(0x1p-23f)),
                                           _mm_set1_ps(0x1p-149f));
            const __m128 dn = _mm_sub_ps(of_, step), up = _mm_add_ps(of_, step);
            on[h] = octant >> a & 1 ? dn : up;
            of[h] = octant >> a & 1 ? up : dn;
        }
        p->inv_near[a] = _mm256_set_m128(in[1], in[0]);
        p->inv_far[a] = _mm256_set_m128(fa[1], fa[0]);
        p->o_near[a] = _mm256_set_m128(on[1], on[0]);
        p->o_far[a] = _mm256_set_m128(of[1], of[0]);
    }
    p->tmin = _mm256_set1_ps(tmin);
    for (int k = 0; k < ACCEL_PACKET; k++) p->tmax[k] = lanes >> k & 1 ? tmax[k] : -INFINITY;
    p->lanes = lanes;
}

/* Which lanes meet child c of node n, lanes `active` only, and their
 * entries: accel_bvh4_test_at's lane arithmetic with the box broadcast and
 * the rays in the lanes. octant: p->octant, a constant (the planes' offsets
 * then are). */
__attribute__((target("avx2"), always_inline)) static inline unsigned
accel_packet8_test(const accel_packet8 *p, const accel_bvh4_node *n, int c, __m256 tmax, unsigned active,
                   __m256 *entry, unsigned octant)
{
    const char *base = (const char *)n + (size_t)c * sizeof(float);
    __m256 lo = p->tmin, hi = tmax;
    /* Written out axis by axis: a loop kept its counter. */
#define ACCEL_PACKET_SLAB(a)                                                                              \
    do {                                                                                                  \
        const __m256 bn_ = _mm256_broadcast_ss((const float *)(const void *)(base + ACCEL_PLANE_AT(octant, a, 1))); \
        const __m256 bf_ = _mm256_broadcast_ss((const float *)(const void *)(base + ACCEL_PLANE_AT(octant, a, 0))); \
        lo = _mm256_max_ps(_mm256_mul_ps(_mm256_sub_ps(bn_, p->o_near[a]), p->inv_near[a]), lo);          \
        hi = _mm256_min_ps(_mm256_mul_ps(_mm256_sub_ps(bf_, p->o_far[a]), p->inv_far[a]), hi);            \
    } while (0)
    ACCEL_PACKET_SLAB(0);
    ACCEL_PACKET_SLAB(1);
    ACCEL_PACKET_SLAB(2);
#undef ACCEL_PACKET_SLAB
    const __m256 tiny = _mm256_set1_ps(ACCEL_TINY);
    lo = _mm256_sub_ps(lo, tiny);
    hi = _mm256_add_ps(hi, tiny);
    *entry = lo;
    return (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(lo, hi, _CMP_LE_OQ)) & active;
}

/* The entry of the first lane in `mask` (not empty): the key the walk
 * orders children by (any order is conservative). */
__attribute__((target("avx2"), always_inline)) static inline float accel_packet8_key(__m256 entry,
                                                                                      unsigned mask)
{
    float e[ACCEL_PACKET];
    _mm256_storeu_ps(e, entry);
    return e[__builtin_ctz(mask)];
}

/* The walk: leaf(user, first, count, lanes) for each leaf some lane may
 * meet within its [tmin, tmax], with those lanes; the callback may lower
 * p->tmax[k] of its lanes, read back after each call. Children are taken
 * nearest first by the entry of their first lane; a stacked child is taken
 * with the lanes whose entry is still within their tmax. octant: p->octant,
 * as a constant. */
__attribute__((target("avx2"), always_inline)) static inline void
accel_bvh4_walk_packet8(const accel_bvh4 *bvh, accel_packet8 *p,
                        void (*leaf)(void *user, uint32_t first, uint32_t count, unsigned lanes), void *user,
                        unsigned octant)
{
    if (!bvh->nodes || !p->lanes) return;
    uint32_t stack_ref[ACCEL_BVH4_STACK], stack_count[ACCEL_BVH4_STACK];
    unsigned stack_lanes[ACCEL_BVH4_STACK];
    __m256 stack_entry[ACCEL_BVH4_STACK];
    uint32_t top = 0;
    __m256 tmax = _mm256_loadu_ps(p->tmax);
    const accel_bvh4_node *n = bvh->nodes;
    unsigned active = p->lanes;
    for (;;) {
        /* The children met, nearest first: kid[0] is walked next, the
         * others stacked farthest first. */
        uint32_t kid[4], hits = 0;
        float key[4];
        unsigned kid_lanes[4];
        __m256 kid_entry[4];
        /* Children written out one by one: a loop kept its counter. */
#define ACCEL_PACKET_CHILD(c)                                                                          \
    do {                                                                                               \
        __m256 e_;                                                                                     \
        const unsigned m_ = accel_packet8_test(p, n, c, tmax, active, &e_, octant);                     \
        if (m_) {                                                                                      \
            const float k_ = accel_packet8_key(e_, m_);                                                 \
            uint32_t j_ = hits++;                                                                      \
            while (j_ > 0 && key[j_ - 1] > k_) {                                                       \
                kid[j_] = kid[j_ - 1], key[j_] = key[j_ - 1], kid_lanes[j_] = kid_lanes[j_ - 1];        \
                kid_entry[j_] = kid_entry[j_ - 1];                                                     \
                j_--;                                                                                  \
            }                                                                                          \
            kid[j_] = c, key[j_] = k_, kid_lanes[j_] = m_, kid_entry[j_] = e_;                         \
        }                                                                                              \
    } while (0)
        ACCEL_PACKET_CHILD(0);
        ACCEL_PACKET_CHILD(1);
        ACCEL_PACKET_CHILD(2);
        ACCEL_PACKET_CHILD(3);
#undef ACCEL_PACKET_CHILD
        uint32_t ref = 0, count = 0;
        if (hits) {
            for (uint32_t j = hits - 1; j > 0; j--) {
                stack_ref[top] = n->ref[kid[j]], stack_count[top] = n->count[kid[j]];
                stack_lanes[top] = kid_lanes[j], stack_entry[top++] = kid_entry[j];
            }
            ref = n->ref[kid[0]], count = n->count[kid[0]], active = kid_lanes[0];
            if (count == 0) {
                n = bvh->nodes + ref;
                continue;
            }
        }
        for (;;) {
            if (hits) {
                leaf(user, ref, count, active);
                tmax = _mm256_loadu_ps(p->tmax);
            }
            /* The next stacked child with a lane still within its tmax. */
            hits = 1;
            do {
                if (top == 0) return;
                --top;
                active = stack_lanes[top] &
                         (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(stack_entry[top], tmax, _CMP_LE_OQ));
            } while (!active);
            ref = stack_ref[top], count = stack_count[top];
            if (count == 0) break;
        }
        n = bvh->nodes + ref;
    }
}

#else
#define ACCEL_PACKET_WALK 0
#endif

#endif
