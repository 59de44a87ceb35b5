/* Tracing a batch of rays for their first hits (batch_trace.h): rays side by
 * side in packets of eight that walk the BVH together (accel/bvh4_packet.h),
 * each ray still getting its exact double hit from the shapes; any ray a
 * packet cannot take alone, by the single query's walk (trace.c).
 *
 * Why a packet's answer is the single query's, bit for bit. The packet
 * walk is conservative for every lane, and the host tests each object a
 * lane meets with that ray exactly as the single walk does (object_trace),
 * so each ray ends with the least t of all its objects' hits in (tmin,
 * tmax), the BVH's and then the unbounded objects', as the single walk
 * does. Only which object holds that t can depend on the order objects are
 * tested in, and only when two of them hold it exactly (a tie): the single
 * query's rule for ties is then its own. So each lane also notes a tie:
 * once it has a hit at t, it asks every later object for hits up to and
 * including t (the window's end moved one step up), and an object that
 * answers t exactly is a tie. A ray with a tie is traced again alone, by
 * the single query (a handful in a picture; none in most). Without one the
 * nearest hit is one object's, whatever the order, and that object's hit
 * is what it answers for any window that holds it (the host's contract
 * with shapes, which the single walk relies on too: trace.c). The rays the
 * single query culls by the box around the BVH's objects (box_misses) are
 * culled here too, and so have the same (no) BVH hits. */
#include <math.h>

#include "trace/batch_trace.h"
#include "trace/object_trace.h"
#include "trace/ray_cull.h"
#include "bvh4_packet.h"

#if ACCEL_PACKET_WALK
/* What each lane of a packet has found so far. */
typedef struct packet_state {
    hr_trace_ctx *tc;
    const hr_ray *rays;     /* the packet's: lane k is rays[k] */
    double tmin;
    double best[ACCEL_PACKET];
    hr_hit *hits;
    int32_t *found;
    unsigned tie; /* lanes to trace again alone: their best t is two
                     objects' (a tie), or the box cull is against them */
    int64_t failed; /* the first ray a shape failed on, or -1 */
    hr_intersection *tmp;
    accel_packet8 *p;
    accel_ray4 unit; /* t_offset 0, t_scale 1: every packet ray's (accel_ray4_tmax) */
} packet_state;

/* Object o against lane k's ray: a nearer hit becomes its best (and ends
 * its tie); one exactly at its best is a tie. Returns 1 when the best
 * came nearer. */
static inline __attribute__((always_inline)) int visit_lane(packet_state *ps, int k, const hr_object *o)
{
    const int i = k;
    const double best = ps->best[k];
    /* With a hit at best, the window holds best too (ties); without one,
     * it is the caller's, open at tmax. */
    const double end = ps->found[i] ? nextafter(best, INFINITY) : best;
    ps->tmp->count = 0;
    if (object_trace(ps->tc, o, &ps->rays[i], ps->tmin, end, HR_TRACE_FIRST, 1, ps->tmp) != HR_OK) {
        if (ps->failed < 0) ps->failed = i;
        return 0;
    }
    if (ps->tmp->count == 0) return 0;
    const hr_hit *h = &ps->tmp->hits[0];
    if (h->t == best) {
        ps->tie |= 1u << k;
        return 0;
    }
    ps->tie &= ~(1u << k);
    ps->best[k] = h->t;
    ps->hits[i] = *h;
    ps->found[i] = 1;
    return 1;
}

/* A leaf: each of its objects against each lane that meets its box. */
static inline __attribute__((always_inline)) void visit_leaf(void *user, uint32_t first, uint32_t count,
                                                             unsigned lanes)
{
    packet_state *ps = user;
    const hr_object *const *objects = ps->tc->scene->leaf_objects + first;
    for (uint32_t j = 0; j < count; j++)
        for (unsigned rest = lanes; rest; rest &= rest - 1) {
            const int k = __builtin_ctz(rest);
            if (visit_lane(ps, k, objects[j])) ps->p->tmax[k] = accel_ray4_tmax(&ps->unit, ps->best[k]);
        }
}

/* The packet's walk, its unbounded objects, and the rays with a tie again
 * alone. Returns as hri_trace_first_batch. One copy per octant of
 * directions, as the single walk's (accel/bvh4.h), so that the planes'
 * offsets in a node are constants. */
static inline __attribute__((always_inline)) int64_t finish_packet(packet_state *ps, unsigned lanes,
                                                                   double tmax)
{
    const hr_scene *s = ps->tc->scene;
    for (; lanes && ps->failed < 0; lanes &= lanes - 1) {
        const int k = __builtin_ctz(lanes), i = k;
        /* A hit of the BVH's for a ray the single query would not have
         * walked (the box around the BVH's objects culls it: its hits come
         * only from an object's rounding of the ray): that ray alone. */
        if (ps->found[i] && box_misses(&s->bvh_box, &ps->rays[i], ps->tmin, tmax)) ps->tie |= 1u << k;
        for (int32_t u = 0; u < s->unbounded_count && !(ps->tie >> k & 1); u++) visit_lane(ps, k, s->unbounded[u]);
        if (ps->tie >> k & 1 && ps->failed < 0) {
            ps->found[i] = hri_scene_trace_nearest(ps->tc, &ps->rays[i], ps->tmin, tmax, &ps->hits[i], ps->tmp);
            if (ps->tc->status) ps->failed = i;
        }
    }
    return ps->failed;
}
#define TRACE_PACKET_OCTANT(o)                                                                    \
    __attribute__((target("avx2"), noinline)) static int64_t trace_packet_##o(packet_state *ps,            \
                                                                             unsigned lanes, double tmax) \
    {                                                                                             \
        accel_bvh4_walk_packet8(&ps->tc->scene->bvh, ps->p, visit_leaf, ps, o);                   \
        return finish_packet(ps, lanes, tmax);                                                    \
    }
TRACE_PACKET_OCTANT(0)
TRACE_PACKET_OCTANT(1)
TRACE_PACKET_OCTANT(2)
TRACE_PACKET_OCTANT(3)
TRACE_PACKET_OCTANT(4)
TRACE_PACKET_OCTANT(5)
TRACE_PACKET_OCTANT(6)
TRACE_PACKET_OCTANT(7)
#undef TRACE_PACKET_OCTANT

static int64_t trace_packet(packet_state *ps, unsigned lanes, double tmax, unsigned octant)
{
    switch (octant) {
    case 0: return trace_packet_0(ps, lanes, tmax);
    case 1: return trace_packet_1(ps, lanes, tmax);
    case 2: return trace_packet_2(ps, lanes, tmax);
    case 3: return trace_packet_3(ps, lanes, tmax);
    case 4: return trace_packet_4(ps, lanes, tmax);
    case 5: return trace_packet_5(ps, lanes, tmax);
    case 6: return trace_packet_6(ps, lanes, tmax);
    default: return trace_packet_7(ps, lanes, tmax);
    }
}
#endif

/* Ray i alone, by the single query's walk; returns i when a shape failed. */
static inline int64_t trace_alone(hr_trace_ctx *tc, const hr_ray *rays, int64_t i, double tmin, double tmax,
                                  hr_hit *hits, int32_t *found, hr_intersection *tmp)
{
    found[i] = hri_scene_trace_nearest(tc, &rays[i], tmin, tmax, &hits[i], tmp);
    return tc->status ? i : -1;
}

int64_t hri_trace_first_batch(hr_trace_ctx *tc, const hr_ray *rays, int64_t count, double tmin, double tmax,
                              hr_hit *hits, int32_t *found, hr_intersection *tmp)
{
    int64_t failed = -1, i = 0;
#if ACCEL_PACKET_WALK
    const hr_scene *s = tc->scene;
    /* Packets need the tree to cull (extent), AVX2, and a window that
     * starts at 0 or later (accel_ray4_init_common_as). */
    if (count >= 2 && s->bvh.nodes && s->bvh.extent <= ACCEL_CULL_RANGE && tmin >= 0 && tmin < INFINITY &&
        accel_walk_avx2_usable()) {
        accel_packet8 p;
        packet_state ps = {.tc = tc, .tmin = tmin, .failed = -1, .tmp = tmp, .p = &p};
        ps.unit.t_offset = ps.unit.tmin_offset = 0.0, ps.unit.t_scale = 1.0;
        const float tmin_f = accel_ray4_tmin(&ps.unit, tmin), tmax_f = accel_ray4_tmax(&ps.unit, tmax);
        const float tmax8[ACCEL_PACKET] = {tmax_f, tmax_f, tmax_f, tmax_f, tmax_f, tmax_f, tmax_f, tmax_f};
        for (; i < count && failed < 0; i += ACCEL_PACKET) {
            const int n = count - i < ACCEL_PACKET ? (int)(count - i) : ACCEL_PACKET;
            /* Rays of two octants make no packet (below): the first and
             * the last tell most such apart for a few instructions. */
            if (accel_octant(&rays[i].dir) != accel_octant(&rays[i + n - 1].dir)) {
                for (int k = 0; k < n && failed < 0; k++)
                    failed = trace_alone(tc, rays, i + k, tmin, tmax, hits, found, tmp);
                continue;
            }
            accel_rays8 r;
            for (int k = 0; k < ACCEL_PACKET; k++) {
                const hr_ray *ray = &rays[i + (k < n ? k : 0)];
                r.o[0][k] = ray->origin.x, r.o[1][k] = ray->origin.y, r.o[2][k] = ray->origin.z;
                r.d[0][k] = ray->dir.x, r.d[1][k] = ray->dir.y, r.d[2][k] = ray->dir.z;
            }
            /* A packet when the walk's preparation takes every ray and
             * all run into one octant (a camera's neighbouring pixels, all
             * but where the octant changes); else each ray alone: rays of
             * different octants are seldom coherent enough for a packet
             * to pay (random rays cost 25% more instructions in packets of
             * their octant's few). */
            uint32_t octants;
            const unsigned all = (1u << n) - 1;
            const unsigned ok = accel_rays8_common(&r, &octants) & all;
            const unsigned first = octants & 7;
            unsigned lanes = 0;
            for (int k = 0; k < n; k++)
                if (ok >> k & 1 && (octants >> (4 * k) & 7) == first) lanes |= 1u << k;
            if (lanes != all) lanes = 0;
            for (int k = 0; k < n && failed < 0; k++)
                if (!(lanes >> k & 1)) failed = trace_alone(tc, rays, i + k, tmin, tmax, hits, found, tmp);
            if (!lanes || failed >= 0) continue;
            ps.rays = rays + i, ps.hits = hits + i, ps.found = found + i;
            ps.tie = 0;
            for (int k = 0; k < n; k++) {
                ps.best[k] = tmax;
                if (lanes >> k & 1) found[i + k] = 0;
            }
            accel_packet8_init(&p, &r, lanes, first, tmin_f, tmax8);
            if ((failed = trace_packet(&ps, lanes, tmax, first)) >= 0) failed += i;
        }
        i = count;
    }
#endif
    for (; i < count && failed < 0; i++) failed = trace_alone(tc, rays, i, tmin, tmax, hits, found, tmp);
    /* A shape failed: rays before it may be untraced too (in a packet). */
    if (failed >= 0)
        for (int64_t j = 0; j < count; j++) found[j] = 0;
    return failed;
}

int64_t hri_trace_occluded_batch(hr_trace_ctx *tc, const hr_ray *rays, int64_t count, double tmin, double tmax,
                                 int32_t *hit)
{
    for (int64_t i = 0; i < count; i++) {
        hit[i] = hri_scene_trace_shadow(tc, &rays[i], tmin, tmax, 0);
        if (tc->status) {
            for (int64_t j = i; j < count; j++) hit[j] = 0;
            return i;
        }
    }
    return -1;
}
