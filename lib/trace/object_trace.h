/* Internal: tracing one object through its transform (Hill: the ray goes
 * into object space through M^-1 unnormalised, so t is the same in both
 * spaces; normals come back through the transpose of M^-1), as an
 * always-inline body. hri_object_trace (trace.c) is its out-of-line copy; the
 * scene walk and the host's child trace inline it, so that each gets a copy
 * specialised to its mode and pays no call per object and ray. */
#ifndef HITRAY_LIB_TRACE_OBJECT_TRACE_H
#define HITRAY_LIB_TRACE_OBJECT_TRACE_H

#include <math.h>

#include "trace/trace_context.h"
#include "geometry/transform_inline.h"
#include "geometry/vec.h"

/* hri_intersection_reserve for a list tracing may be handed: the one list
 * whose storage is borrowed from a caller's stack (tc->borrowed) moves to
 * the heap when it must grow, every other list is realloc'd (trace.c). */
hr_status hri_trace_list_reserve(hr_trace_ctx *tc, hr_intersection *list, int32_t capacity);

/* Order by t; equal t by object then surface, so sorting is deterministic. */
static inline int hit_before(const hr_hit *a, const hr_hit *b)
{
    if (a->t != b->t) return a->t < b->t;
    if (a->object != b->object) return a->object < b->object;
    return a->surface < b->surface;
}

/* Whether a hit's t, found in the window (tmin, tmax) of a ray whose
 * direction was scaled by 2^-t_exp, is inside it, and then inside the
 * caller's (ray_tmin, ray_tmax) once scaled back (*t is then the caller's).
 * Scaling back may overflow to infinity or round onto an end of the window
 * (the scaled window's ends were rounded too): the hit must be inside the
 * caller's window, checked on the t it will be given. */
static inline __attribute__((always_inline)) int hit_t_in_window(double *t, double tmin, double tmax, int t_exp,
                                                                 double ray_tmin, double ray_tmax)
{
    if (!(*t > tmin && *t < tmax)) return 0;
    if (!t_exp) return 1;
    *t = ldexp(*t, -t_exp);
    return *t > ray_tmin && *t < ray_tmax && isfinite(*t);
}

/* One hit a class gave, whose t is already checked against the window,
 * taken to the parent's space in place (object_trace): 0 when the host's
 * contract drops it. */
static inline __attribute__((always_inline)) int hit_to_parent(const hr_trace_ctx *tc, const hr_object *obj,
                                                               int composite, int unit_normals, hr_hit *h)
{
    /* A non-finite point or normal stays non-finite through the
     * transform (each row has a term in every coordinate, and inf * 0 is
     * NaN) and through v3_unit_exponent, so a transformed object's hit
     * is dropped for it by the test after the transform; only a
     * non-finite error could vanish there (a NaN row loses the max), so
     * that is the one value tested first. An untransformed object's hit
     * is tested whole, here. */
    if (obj->identity ? !v3_pair_is_finite(h->point, h->normal, h->error) : !(h->error - h->error == 0.0))
        return 0;
    /* A composite's hit names its leaf; one naming no object of the scene
     * is taken as the composite's own, so shading never indexes past the
     * object list. Any other shape leaves `object` unset: it is not read
     * (not even by a branch the compiler may merge, which memcheck flags). */
    if (!composite) h->object = obj->index;
    else if (h->object < 0 || h->object >= tc->scene->object_count) h->object = obj->index;
    /* Normals may have any non-zero length: bring them to a safe scale
     * (exactly, by a power of two) before and after the transform, so
     * neither M^-T nor normalising overflows or underflows. */
    hr_vec3 normal = v3_unit_exponent(h->normal);
    if (!obj->identity) {
        /* hri_xform_error_as gives the full bound's bits for a finite
         * point; a hit whose point is not finite is dropped below. */
        const double error = hri_xform_error_as(obj->m, &obj->m_error, obj->diagonal, h->point, h->error);
        hr_vec3 point, n;
        /* Where the one-term forms of a diagonal transform hold, the point
         * and the normal are finite (and the normal stays so, rescaled):
         * only the error is left to test. */
        const int one_term = obj->diagonal && hri_xform_point_diagonal(obj->m, h->point, &point) &&
                             hri_xform_normal_diagonal(obj->inv, normal, &n);
        if (!one_term) {
            point = hri_xform_point_as(obj->m, obj->diagonal, h->point);
            n = hri_xform_normal_as(obj->inv, obj->diagonal, normal);
        }
        normal = v3_unit_exponent(n);
        if (one_term ? !(error - error == 0.0) : !v3_pair_is_finite(point, normal, error)) return 0;
        h->point = point;
        h->error = error;
    }
    h->normal = unit_normals ? v3_normalize(normal) : normal;
    return 1;
}

/* hri_object_trace's body, inline so that the scene walk (visit_object in
 * trace.c) and a composite's every-hit child trace (host_trace_child in
 * host_services.c) get copies specialised to their modes. */
static inline __attribute__((always_inline)) hr_status
object_trace(hr_trace_ctx *tc, const hr_object *obj, const hr_ray *ray, double tmin, double tmax,
             int32_t mode, int unit_normals, hr_intersection *out)
{
    const hr_shape_class *cls = obj->cls;
    hr_status st;
    if (out->capacity - out->count < HR_MIN_HIT_CAPACITY &&
        (st = hri_trace_list_reserve(tc, out, out->count + HR_MIN_HIT_CAPACITY)))
        return tc->status = st;
    hr_hit_args args;
    args.shape = obj->shape;
    if (obj->identity) {
        args.ray = *ray;
    } else {
        args.ray.origin = hri_xform_point_as(obj->inv, obj->diagonal, ray->origin);
        args.ray.dir = hri_xform_vector_as(obj->inv, obj->diagonal, ray->dir);
    }
    /* A direction whose squared length would under- or overflow (a sphere
     * scaled by 1e-300, a ray into an object scaled by 1e160) is brought near
     * unit length by a power of two, 2^-e, and t scaled by 2^e: exact both
     * ways, so every shape sees a well-scaled ray and no shape needs its own
     * guard. Normal rays skip this with one comparison. */
    int t_exp = v3_rescale_exponent(args.ray.dir);
    const double ray_tmin = tmin, ray_tmax = tmax; /* the caller's window */
    if (t_exp) {
        args.ray.dir = v3_ldexp(args.ray.dir, -t_exp);
        tmin = ldexp(tmin, t_exp);
        tmax = ldexp(tmax, t_exp);
    }
    args.tmin = tmin;
    args.tmax = tmax;
    args.out = out;
    args.call = tc;
    args.struct_size = (uint32_t)sizeof args;
    hr_hit_fn fn = cls->hit;
    if (mode == HR_TRACE_FIRST && cls->first_hit) fn = cls->first_hit;
    if (mode == HR_TRACE_ANY) fn = cls->any_hit ? cls->any_hit : cls->first_hit ? cls->first_hit : cls->hit;
    int32_t start = out->count;
    if ((st = fn(&args))) {
        out->count = start;
        return tc->status = st;
    }
    /* A count below where it started, or beyond the room the list has, means
     * the class wrote where it had no room or dropped hits that were not its
     * own: nothing it returned can be trusted, and reading on would leave
     * the list. */
    if (out->count < start || out->count > out->capacity) {
        out->count = start;
        return tc->status = HR_ERROR_MODULE;
    }
    int composite = (cls->flags & HR_SHAPE_COMPOSITE) != 0;
    /* The host enforces the contract instead of trusting it: a hit outside
     * (tmin, tmax) or with a non-finite field is dropped, before a first
     * or any hit is chosen, so a bad hit cannot hide a good one. Any-hit
     * answers carry only t. */
    if (mode == HR_TRACE_FIRST && out->count == start + 1) {
        /* A first hit, as classes give it: the one hit, in place. */
        hr_hit *h = &out->hits[start];
        const int keep = hit_t_in_window(&h->t, tmin, tmax, t_exp, ray_tmin, ray_tmax) &&
                         hit_to_parent(tc, obj, composite, unit_normals, h);
        out->count = start + keep;
        return HR_OK;
    }
    int32_t kept = start;
    for (int32_t i = start; i < out->count; i++) {
        hr_hit h = out->hits[i];
        if (!hit_t_in_window(&h.t, tmin, tmax, t_exp, ray_tmin, ray_tmax)) continue;
        if (mode == HR_TRACE_ANY) {
            out->hits[start] = h;
            out->count = start + 1;
            return HR_OK;
        }
        if (!hit_to_parent(tc, obj, composite, unit_normals, &h)) continue;
        out->hits[kept++] = h;
    }
    out->count = kept;
    if (mode == HR_TRACE_FIRST && kept > start + 1) {
        /* The nearest, whatever order the class listed its hits in. */
        int32_t best = start;
        for (int32_t i = start + 1; i < kept; i++)
            if (hit_before(&out->hits[i], &out->hits[best])) best = i;
        out->hits[start] = out->hits[best];
        out->count = start + 1;
    }
    return HR_OK;
}

#endif
