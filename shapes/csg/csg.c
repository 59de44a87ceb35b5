/* CSG booleans of Hill's chapter 12: `union`, `intersection` and
 * `difference` (a minus b) of two objects, nested to any depth.
 *
 * A boolean is a module like any shape. It knows its operands only as the
 * child handles the host gave to create (parameters `a` and `b` of type
 * HR_PARAM_OBJECT) and traces them only through hr_host.trace_child, so any
 * solid a user's module adds works inside a boolean, and so does another
 * boolean. Each operand keeps its own transform and material: the host
 * carries the ray through the operand's transform, and every hit names the
 * leaf object whose surface it is. The boolean node has neither a material
 * nor (in SDL) a transform of its own.
 *
 * Operands must be solids (class flag HR_SHAPE_CLOSED): inside and outside
 * must mean something. An open surface (plane, square, a user's disk) is
 * refused at create with a message naming the parameter.
 *
 * Hit: both operands are traced over (tmin, +infinity), every hit, into the
 * caller's own list (no scratch list, so nesting depth costs no host
 * resource but stack), and csg_combine.c walks the two lists together; see
 * csg_combine.h for the walk, coincident faces, tangents and which hit
 * speaks for a group. Tracing past tmax is what makes an answer over
 * (tmin, tmax) the part of the answer over the whole ray that lies in
 * (tmin, tmax): a shadow ray sees exactly the hits a camera ray would.
 *
 * State at tmin: an operand's first hit after tmin is exiting exactly when
 * the ray starts inside it. A ray that starts on a boundary (t = tmin on a
 * surface) is therefore classified by where it goes next, for each operand
 * by that operand's own arithmetic; the hit at tmin itself is never
 * reported (hits are strictly inside (tmin, tmax)). An operand with no hit
 * at all is outside when it is bounded (a ray inside a bounded solid must
 * leave it); for an unbounded solid the host is asked along the six axis
 * directions from the ray's start, and the first hit found decides.
 *
 * Fast paths. The first hit is the walk stopped at its first hit: an
 * operand's own first hit is not enough (the ray may start inside the
 * other operand, or a tangent group may cancel), so operands are traced in
 * full. The any hit (shadow rays) is the first hit. Asking the leaf
 * operands for any hit in (tmin, tmax) first, to answer no without the walk
 * when neither has one, costs more than it saves: a built-in solid's any
 * hit costs about what its every hit does, and wherever an operand has a
 * hit the question only repeats its trace (measured on torus_csg.sdl,
 * scenes/csg.sdl and a union of a cube and a torus). In every mode, b is
 * not traced at all when the ray is never inside a and the result lies
 * within a (intersection, difference), and an operand whose box the ray
 * misses is not traced (see trace_operand).
 *
 * No limit on the number of hits: the list grows through hr_host.reserve.
 *
 * Bounds (in the boolean's object space, from hr_host.child_bounds): a union
 * the box around both boxes, an intersection their overlap, a difference the
 * box of a. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/shape_kit.h>
#include <hitray/shape_module.h>

#include "../common/shape_builtin.h"
#include "csg_combine.h"

typedef struct csg_shape {
    const hr_host *host;
    const void *a, *b;                /* child handles for trace_child */
    int32_t op;                       /* CSG_* */
    hr_bounds a_box, b_box;           /* operands' bounds, fixed once made */
    int32_t a_box_finite, b_box_finite;
} csg_shape;

/* --- Create and destroy ------------------------------------------------------ */

static int bounds_finite(const hr_bounds *b)
{
    return isfinite(b->lo.x) && isfinite(b->lo.y) && isfinite(b->lo.z) && isfinite(b->hi.x) &&
           isfinite(b->hi.y) && isfinite(b->hi.z);
}

/* The child given as parameter `name`, checked to be a solid. */
static hr_status find_operand(const hr_create_args *args, const char *name, const void **out)
{
    const hr_param *p = shape_param(args, name);
    *out = p && p->type == HR_PARAM_OBJECT && args->objects ? args->objects[p - args->params] : NULL;
    if (!*out) {
        snprintf(args->error, args->error_size, "parameter '%s' must name an object", name);
        return HR_ERROR_PARAMETER;
    }
    /* A host from before child_class cannot say; its children are traced
     * as solids. */
    if (!HR_HOST_HAS(args->host, child_class) || !args->host->child_class) return HR_OK;
    const hr_shape_class *cls = args->host->child_class(*out);
    if (cls && !(cls->flags & HR_SHAPE_CLOSED)) {
        snprintf(args->error, args->error_size,
                 "parameter '%s' is a '%s', which is not a solid (its class lacks "
                 "HR_SHAPE_CLOSED): a boolean needs an inside and an outside; use a solid "
                 "such as a cube or a sphere",
                 name, cls->name ? cls->name : "?");
        return HR_ERROR_PARAMETER;
    }
    return HR_OK;
}

static hr_status csg_create(const hr_create_args *args, int32_t op, void **out_shape)
{
    *out_shape = NULL;
    const void *a, *b;
    hr_status st = find_operand(args, "a", &a);
    if (st == HR_OK) st = find_operand(args, "b", &b);
    if (st) return st;
    csg_shape *shape = args->host->alloc(sizeof *shape);
    if (!shape) return HR_ERROR_OUT_OF_MEMORY;
    shape->host = args->host;
    shape->a = a;
    shape->b = b;
    shape->op = op;
    args->host->child_bounds(a, &shape->a_box);
    args->host->child_bounds(b, &shape->b_box);
    shape->a_box_finite = bounds_finite(&shape->a_box);
    shape->b_box_finite = bounds_finite(&shape->b_box);
    *out_shape = shape;
    return HR_OK;
}

static hr_status union_create(const hr_create_args *args, void **out)
{
    return csg_create(args, CSG_UNION, out);
}

static hr_status intersection_create(const hr_create_args *args, void **out)
{
    return csg_create(args, CSG_INTERSECTION, out);
}

static hr_status difference_create(const hr_create_args *args, void **out)
{
    return csg_create(args, CSG_DIFFERENCE, out);
}

static void csg_destroy(void *shape)
{
    if (!shape) return;
    const hr_host *host = ((csg_shape *)shape)->host;
    host->free(shape);
}

/* --- Bounds ------------------------------------------------------------------- */

static void csg_bounds(const void *shape_ptr, hr_bounds *out)
{
    const csg_shape *shape = shape_ptr;
    const hr_bounds a = shape->a_box, b = shape->b_box;
    if (shape->op == CSG_DIFFERENCE) {
        *out = a;
        return;
    }
    double *lo = &out->lo.x, *hi = &out->hi.x;
    const double *alo = &a.lo.x, *ahi = &a.hi.x, *blo = &b.lo.x, *bhi = &b.hi.x;
    for (int i = 0; i < 3; i++) {
        if (shape->op == CSG_UNION) {
            lo[i] = fmin(alo[i], blo[i]);
            hi[i] = fmax(ahi[i], bhi[i]);
        } else {
            lo[i] = fmax(alo[i], blo[i]);
            hi[i] = fmin(ahi[i], bhi[i]);
        }
    }
    /* Boxes that do not overlap: the intersection is empty and has no hit;
     * a point box (between the two) keeps the bounds well formed. */
    for (int i = 0; i < 3; i++)
        if (!(lo[i] <= hi[i])) lo[i] = hi[i] = 0.5 * lo[i] + 0.5 * hi[i];
}

/* --- Hits --------------------------------------------------------------------- */

/* Whether `p` is inside an unbounded child that the ray never crosses: the
 * first hit along an axis direction from p tells (exiting: inside). None in
 * any of the six: outside. The probe hits are dropped from `out`. */
static hr_status probe_inside(const csg_shape *shape, void *call, const void *child, hr_vec3 p,
                              hr_intersection *out, int *inside)
{
    static const double axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                      {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const int32_t start = out->count;
    *inside = 0;
    for (int k = 0; k < 6; k++) {
        const hr_ray probe = {p, {axes[k][0], axes[k][1], axes[k][2]}};
        hr_status st = shape->host->trace_child(call, child, &probe, 0.0, INFINITY,
                                                HR_TRACE_FIRST, out);
        if (st) return st;
        if (out->count > start) {
            *inside = !out->hits[start].entering;
            out->count = start;
            return HR_OK;
        }
    }
    return HR_OK;
}

/* Appends every hit of `child` after tmin to `out` and says whether the ray
 * is inside it at tmin. A bounded child whose box the ray misses has no hit
 * and is outside all along: it is not traced (so a tree of booleans prunes
 * itself like a BVH). The box test is the kit's (shape_box_misses), which
 * never drops a box the ray touches after tmin. */
static hr_status trace_operand(const csg_shape *shape, const hr_hit_args *args, int which_b,
                               int *inside)
{
    hr_intersection *out = args->out;
    const int32_t start = out->count;
    const void *child = which_b ? shape->b : shape->a;
    const int finite = which_b ? shape->b_box_finite : shape->a_box_finite;
    *inside = 0;
    if (finite && shape_box_misses(which_b ? &shape->b_box : &shape->a_box, &args->ray, args->tmin, INFINITY))
        return HR_OK;
    hr_status st = shape->host->trace_child(args->call, child, &args->ray, args->tmin, INFINITY,
                                            HR_TRACE_ALL, out);
    if (st) return st;
    if (out->count > start) {
        *inside = !out->hits[start].entering;
        return HR_OK;
    }
    if (finite) return HR_OK;
    /* Any point of the ray after tmin will do: none crosses the surface. */
    const hr_ray *r = &args->ray;
    hr_vec3 p = r->origin;
    if (isfinite(args->tmin)) {
        const hr_vec3 q = {r->origin.x + args->tmin * r->dir.x, r->origin.y + args->tmin * r->dir.y,
                           r->origin.z + args->tmin * r->dir.z};
        if (isfinite(q.x) && isfinite(q.y) && isfinite(q.z)) p = q;
    }
    return probe_inside(shape, args->call, child, p, out, inside);
}

static hr_status csg_trace(const hr_hit_args *args, int32_t mode)
{
    const csg_shape *shape = args->shape;
    hr_intersection *out = args->out;
    const int32_t start = out->count;
    hr_status st;
    /* The operands' hits go after what the list held: a's, then b's, then
     * the result, which is finally moved down to `start`. */
    csg_operand a, b;
    int inside;
    if ((st = trace_operand(shape, args, 0, &inside))) goto fail;
    a.inside = inside;
    a.count = out->count - start;
    /* An intersection or a difference lies inside a: a ray that never is
     * inside a has no hit, whatever b does. */
    if (shape->op != CSG_UNION && a.count == 0 && !a.inside) return HR_OK;
    if ((st = trace_operand(shape, args, 1, &inside))) goto fail;
    b.inside = inside;
    b.count = out->count - start - a.count;
    const int32_t n = a.count + b.count;
    const int32_t limit = mode == HR_TRACE_ALL ? n : 1;
    if (n > (INT32_MAX - start) / 2) {
        st = HR_ERROR_OUT_OF_MEMORY;
        goto fail;
    }
    if ((st = shape->host->reserve(args->call, out, start + n + limit))) goto fail;
    hr_hit *hits = out->hits; /* after reserve, which may move them */
    a.hits = hits + start;
    b.hits = hits + start + a.count;
    const int32_t m =
        csg_combine(shape->op, &a, &b, args->tmin, args->tmax, limit, hits + start + n);
    memmove(hits + start, hits + start + n, (size_t)m * sizeof *hits);
    out->count = start + m;
    return HR_OK;
fail:
    out->count = start;
    return st;
}

SHAPE_DEFINE_HIT_MODES(csg, csg_trace)

/* --- The module --------------------------------------------------------------- */

/* min > max: no range to check (object parameters have none). */
static const hr_param_spec csg_params[] = {
    {"a", HR_PARAM_OBJECT, 1, 0.0, 1.0, 0.0, "the first solid", 0},
    {"b", HR_PARAM_OBJECT, 1, 0.0, 1.0, 0.0, "the second solid", 0},
};

static const hr_param_spec difference_params[] = {
    {"a", HR_PARAM_OBJECT, 1, 0.0, 1.0, 0.0, "the solid to take from", 0},
    {"b", HR_PARAM_OBJECT, 1, 0.0, 1.0, 0.0, "the solid taken away from a", 0},
};

#define CSG_CLASS(var, class_name, param_specs, create_fn, help_text)                        \
    static const hr_shape_class var = {                                                     \
        .struct_size = sizeof(hr_shape_class),                                              \
        .flags = HR_SHAPE_CLOSED | HR_SHAPE_COMPOSITE,                                      \
        .name = class_name,                                                                 \
        .help = help_text,                                                                  \
        .params = param_specs,                                                              \
        .param_count = 2,                                                                   \
        .surface_count = 0,                                                                 \
        .create = create_fn,                                                                \
        .destroy = csg_destroy,                                                             \
        .bounds = csg_bounds,                                                               \
        .hit = csg_hit,                                                                     \
        .first_hit = csg_first_hit,                                                         \
        .any_hit = csg_any_hit,                                                             \
    }

CSG_CLASS(union_class, "union", csg_params, union_create, "CSG: every point inside a or b");
CSG_CLASS(intersection_class, "intersection", csg_params, intersection_create,
          "CSG: every point inside both a and b");
CSG_CLASS(difference_class, "difference", difference_params, difference_create,
          "CSG: every point inside a and not inside b");

SHAPE_MODULE("csg", "CSG booleans of two solids: union, intersection, difference",
             SHAPE_BUILTIN_METADATA, &union_class, &intersection_class, &difference_class);
