/* CSG: from the hits of two solids along a ray to the hits of their union,
 * intersection or difference (Hill's "Intersection" lists of the operands,
 * walked together). Pure arithmetic on hit lists: tracing the operands is
 * csg.c's job.
 *
 * The walk. Each operand is a closed solid (HR_SHAPE_CLOSED), so its hits
 * alternate, and after each hit the ray is inside that operand exactly when
 * the hit is entering. The walk keeps both operands' states, starting from
 * their states at tmin, and takes the hits of both lists in order of t;
 * wherever the combined state (a or b, a and b, a and not b) changes, the
 * result has a hit.
 *
 * Coincident hits are one event. Consecutive hits (of either operand) whose
 * points are within the sum of their error bounds of each other on every
 * axis, or that have the same t, are the same place as far as the operands'
 * arithmetic can tell: they form one group, and the group is applied as a
 * whole. The result gets one hit from a group when its state after the group
 * differs from its state before, and none otherwise. Hence:
 * - a cube minus a cube sharing a face: at the shared face the result leaves
 *   once (or not at all where the face is inside the hole), never a sliver
 *   of zero thickness and never a double hit, whatever the rounding of the
 *   two faces' t;
 * - two solids that touch along a face are one solid in a union (no inner
 *   face), and their intersection along the face is empty;
 * - a zero-length visit (a tangent ray, a ray along an edge, which the
 *   built-in shapes report as entering and leaving at the same t) changes
 *   nothing and gives no hit: booleans are regularised, so a point or a face
 *   with no volume behind it is not part of the result.
 * Which hit speaks for a group: the operand whose state changed across the
 * group (a when both did), and its last hit in the group, which is the one
 * that left it in its final state. Its surface, object and normal are kept;
 * its entering flag is the result's; its normal is negated when it is b's in
 * a difference (the subtracted solid's surface bounds the result from the
 * other side). An operand that changed state always moved the way the result
 * did (a union leaves only when both operands are left, ...), so the normal
 * kept points out of the result.
 * Order at one t: a's hits before b's. With the rules above the outcome is
 * the same for either order; the order only makes the walk deterministic. */
#ifndef HITRAY_CSG_COMBINE_H
#define HITRAY_CSG_COMBINE_H

#include <hitray/shape_module.h>

#define CSG_UNION 0
#define CSG_INTERSECTION 1
#define CSG_DIFFERENCE 2 /* a minus b */

/* One operand's hits, sorted by t, and whether the ray is inside it at the
 * start of the interval. */
typedef struct csg_operand {
    const hr_hit *hits;
    int32_t count;
    int32_t inside;
} csg_operand;

/* Whether a point inside a (a_inside) and b (b_inside) is inside the result. */
int csg_inside(int32_t op, int a_inside, int b_inside);

/* Writes to `out` the result's hits with tmin < t < tmax, at most `limit`
 * of them (1 gives the first hit), and returns how many. `out` has room for
 * min(limit, a.count + b.count) hits and overlaps neither operand. */
int32_t csg_combine(int32_t op, const csg_operand *a, const csg_operand *b, double tmin,
                    double tmax, int32_t limit, hr_hit *out);

#endif
