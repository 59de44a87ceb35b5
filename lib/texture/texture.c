/* An object's texture: checked when the object is added, placed at commit,
 * looked up at each of its hits that shade sees (lib/texture/texture.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "util/strutil.h"
#include "util/solid_textures.h"
#include "texture/texture.h"
#include "geometry/transform_inline.h"
#include "geometry/vec.h"

/* Every parameter of `kind`: the material's, checked, then the defaults. */
static hr_status fill_params(hr_context *ctx, const hr_material *m, const hr_shape_class *cls,
                             const hr_texture_kind *kind, double *out)
{
    if (m->parameter_count > kind->param_count)
        return hri_error(ctx, HR_ERROR_PARAMETER,
                        "shape '%s': texture %d (%s) takes at most %d parameters, not %d",
                        cls->name, (int)m->texture, kind->name, (int)kind->param_count,
                        (int)m->parameter_count);
    for (int32_t i = 0; i < kind->param_count; i++) {
        const hr_texture_param *p = &kind->params[i];
        const double v = i < m->parameter_count ? m->parameters[i] : p->default_value;
        const char *why = NULL;
        char range[96] = "";
        char lo[HR_SHORTEST_BYTES], hi[HR_SHORTEST_BYTES], value[HR_SHORTEST_BYTES];
        if (p->kind == HR_TEXTURE_PARAM_POSITIVE)
            snprintf(range, sizeof range, " (at most %s)", hri_shortest(p->max, hi));
        else
            snprintf(range, sizeof range, " (within [%s, %s])", hri_shortest(p->min, lo), hri_shortest(p->max, hi));
        if (!isfinite(v)) why = "must be finite";
        else if (p->kind == HR_TEXTURE_PARAM_POSITIVE && !(v > 0.0)) why = "must be positive", range[0] = '\0';
        else if (!(v >= p->min && v <= p->max)) why = "is out of range";
        else if (p->kind == HR_TEXTURE_PARAM_WHOLE && v != floor(v)) why = "must be a whole number";
        if (why)
            return hri_error(ctx, HR_ERROR_PARAMETER,
                            "shape '%s': texture %d (%s): parameter %d (%s) is %s and %s%s",
                            cls->name, (int)m->texture, kind->name, (int)i + 1, p->name,
                            hri_shortest(v, value), why,
                            range);
        out[i] = v;
    }
    return HR_OK;
}


hr_status hri_texture_bind(hr_context *ctx, const hr_material *m, const hr_shape_class *cls,
                          const void *shape, const char *module_path, const hr_pixmap_set *pixmaps,
                          hr_texture **out)
{
    const int32_t id = m->texture;
    *out = NULL;
    /* A composite's hits carry its leaves' materials: its own is unused. */
    if (id == 0 || (cls->flags & HR_SHAPE_COMPOSITE)) return HR_OK;
    const hr_texture_kind *kind = id < 0 ? hri_solid_texture_find(id) : &hri_image_texture_kind;
    const hr_pixmap *pixmap = NULL;
    if (!kind) {
        char known[256];
        hri_solid_texture_list(known, sizeof known);
        return hri_error(ctx, HR_ERROR_PARAMETER, "shape '%s': there is no solid texture %d (there are %s)",
                        cls->name, (int)id, known);
    }
    if (id > 0) {
        const int has_entry = HR_CLASS_HAS(cls, surface_uv) && cls->surface_uv;
        if (!has_entry || cls->surface_uv(shape, NULL, NULL) != 1)
            return hri_error(ctx, HR_ERROR_PARAMETER,
                            "shape '%s' (module '%s') gives no (u, v) on %s, so it cannot carry "
                            "image texture %d",
                            cls->name, module_path,
                            has_entry ? "this object's surface (its data has none: a mesh file "
                                        "without texture coordinates, say)"
                                      : "its surface",
                            (int)id);
        if (!(pixmap = hri_pixmap_find(pixmaps, id)))
            return hri_error(ctx, HR_ERROR_PARAMETER,
                            "shape '%s': image texture %d needs pixmap %d, which is not made "
                            "(makePixmap %d FILE before the object)",
                            cls->name, (int)id, (int)id, (int)id);
    }
    double params[HR_TEXTURE_MAX_PARAMS];
    hr_status st = fill_params(ctx, m, cls, kind, params);
    if (st) return st;
    if (id > 0 && (params[HR_IMAGE_PARAM_UMIN] == params[HR_IMAGE_PARAM_UMAX] ||
                   params[HR_IMAGE_PARAM_VMIN] == params[HR_IMAGE_PARAM_VMAX] ||
                   !isfinite(params[HR_IMAGE_PARAM_UMAX] - params[HR_IMAGE_PARAM_UMIN]) ||
                   !isfinite(params[HR_IMAGE_PARAM_VMAX] - params[HR_IMAGE_PARAM_VMIN])))
        return hri_error(ctx, HR_ERROR_PARAMETER,
                        "shape '%s': image texture %d: the (u, v) range [%g, %g] x [%g, %g] must "
                        "not be empty (u min != u max, v min != v max)",
                        cls->name, (int)id, params[0], params[1], params[2], params[3]);
    hr_texture *t = calloc(1, sizeof *t);
    if (!t) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    t->kind = kind;
    t->pixmap = pixmap;
    memcpy(t->params, params, (size_t)kind->param_count * sizeof *params);
    *out = t;
    return HR_OK;
}

/* The image texture's (s, t) in [0, 1)^2 at object-space point p with
 * normal n (world hit `hit`, moved into the object's space). */
static void image_coords(const hr_texture *t, const hr_shape_class *cls, const void *shape, const hr_hit *hit,
                         hr_vec3 p, hr_vec3 n, double st[2])
{
    hr_hit local = *hit;
    local.point = p;
    local.normal = n;
    double uv[2] = {0.0, 0.0};
    cls->surface_uv(shape, &local, uv);
    const double *q = t->params;
    double s = (uv[0] - q[HR_IMAGE_PARAM_UMIN]) / (q[HR_IMAGE_PARAM_UMAX] - q[HR_IMAGE_PARAM_UMIN]);
    double r = (uv[1] - q[HR_IMAGE_PARAM_VMIN]) / (q[HR_IMAGE_PARAM_VMAX] - q[HR_IMAGE_PARAM_VMIN]);
    /* The image repeats: only where (s, r) lies in a tile counts. A class
     * that broke its contract (a non-finite u or v) gets the first texel. */
    s = isfinite(s) ? s - floor(s) : 0.0;
    r = isfinite(r) ? r - floor(r) : 0.0;
    if (!(s < 1.0)) s = 0.0;
    if (!(r < 1.0)) r = 0.0;
    st[0] = s, st[1] = r;
}

/* A solid texture is looked up just inside the surface, past the point's
 * error bound: a face lying on one of its own lattice planes (a floor at
 * z = 0 under a checkerboard) would otherwise fall on either side from one
 * pixel to the next. Near double's range the error bound is infinite:
 * there the point is used as it is, never an infinite or NaN one. */
static hr_vec3 solid_point(const hr_texture *t, const hr_hit *hit, hr_vec3 p, hr_vec3 n)
{
    const double inset = 2.0 * hri_xform_error(t->to_object, hit->point, hit->error);
    hr_vec3 inside = v3_madd(p, v3_normalize(n), -inset);
    return v3_is_finite(inside) ? inside : p;
}

hr_color hri_texture_color(const hr_texture *t, const hr_shape_class *cls, const void *shape,
                          const hr_hit *hit)
{
    hr_vec3 p = hri_xform_point(t->to_object, hit->point);
    hr_vec3 n = hri_xform_normal(t->to_world, hit->normal);
    if (t->kind->solid) return t->kind->solid(t->params, solid_point(t, hit, p, n));
    double st[2];
    image_coords(t, cls, shape, hit, p, n, st);
    return hri_pixmap_sample(t->pixmap, st[0], st[1], t->params[HR_IMAGE_PARAM_NEAREST] != 0.0);
}

/* How many pieces to cut side b of the footprint (a parallelogram of
 * sides a and b) into. Its box is much larger than it where b leans along
 * a's main axis: with a along x and b = (b_x, 0, b_z), the box is
 * (|a_x| + |b_x|) |b_z| for a parallelogram of |a_x| |b_z|, and b cut into
 * n pieces, each with its own box, brings that to (1 + |b_x| / (n |a_x|))
 * times the area. Cut so the excess is at most a quarter, up to FOOTPRINT_CUTS pieces
 * in all (both sides together). */
#define FOOTPRINT_CUTS 8
static int footprint_cuts(hr_vec3 a, hr_vec3 b)
{
    const double ax[3] = {fabs(a.x), fabs(a.y), fabs(a.z)}, bx[3] = {fabs(b.x), fabs(b.y), fabs(b.z)};
    const int main = ax[0] >= ax[1] && ax[0] >= ax[2] ? 0 : ax[1] >= ax[2] ? 1 : 2;
    if (!(ax[main] > 0.0)) return 1;
    const double lean = 4.0 * bx[main] / ax[main];
    return lean < FOOTPRINT_CUTS - 1 ? 1 + (int)lean : FOOTPRINT_CUTS;
}

/* A difference of image coordinates across the tiles' seam: the nearer of
 * the two ways round. */
static double seam_difference(double d) { return d - nearbyint(d); }

hr_color hri_texture_color_filtered(const hr_texture *t, const hr_shape_class *cls, const void *shape,
                                   const hr_hit *hit, hr_vec3 dpdx, hr_vec3 dpdy)
{
    hr_vec3 p = hri_xform_point(t->to_object, hit->point);
    hr_vec3 n = hri_xform_normal(t->to_world, hit->normal);
    const hr_vec3 dqx = hri_xform_vector(t->to_object, dpdx);
    const hr_vec3 dqy = hri_xform_vector(t->to_object, dpdy);
    if (!v3_is_finite(dqx) || !v3_is_finite(dqy)) return hri_texture_color(t, cls, shape, hit);
    if (t->kind->solid) {
        const hr_vec3 q = solid_point(t, hit, p, n);
        if (!t->kind->solid_box) return t->kind->solid(t->params, q);
        /* The box around the pixel's footprint, a parallelogram of sides
         * dq/dx and dq/dy centred on q: where a side leans along the other's
         * axis (a floor's receding lines, off the image's centre), that box
         * is much larger than the parallelogram and blurs what the pixel
         * does not cover, so each side is cut into pieces (footprint_cuts),
         * each piece filtered by its own box. */
        int na = footprint_cuts(dqy, dqx), nb = footprint_cuts(dqx, dqy);
        while (na * nb > FOOTPRINT_CUTS) na > nb ? na-- : nb--;
        const hr_vec3 pa = v3_scale(dqx, 1.0 / na), pb = v3_scale(dqy, 1.0 / nb);
        const hri_footprint_pieces f = {q, pa, pb,
                                        v3(0.5 * (fabs(pa.x) + fabs(pb.x)), 0.5 * (fabs(pa.y) + fabs(pb.y)),
                                           0.5 * (fabs(pa.z) + fabs(pb.z))),
                                        na, nb};
        if (t->kind->solid_footprint) return t->kind->solid_footprint(t->params, &f);
        return hri_footprint_mean(t->kind->solid_box, t->params, &f);
    }
    if (t->params[HR_IMAGE_PARAM_NEAREST] != 0.0) return hri_texture_color(t, cls, shape, hit);
    double st[2], sx[2], sy[2];
    image_coords(t, cls, shape, hit, p, n, st);
    image_coords(t, cls, shape, hit, v3_add(p, dqx), n, sx);
    image_coords(t, cls, shape, hit, v3_add(p, dqy), n, sy);
    const double dst[4] = {seam_difference(sx[0] - st[0]), seam_difference(sx[1] - st[1]),
                           seam_difference(sy[0] - st[0]), seam_difference(sy[1] - st[1])};
    return hri_pixmap_sample_footprint(t->pixmap, st[0], st[1], dst);
}
