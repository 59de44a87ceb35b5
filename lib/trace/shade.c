/* Hill's shade(): the colour seen along a ray.
 *
 *   colour = emissive + ambient * globalAmbient
 *          + sum over lights not in shadow of
 *              light * (diffuse * max(0, s.m) + specular * max(0, h.m)^exponent)
 *          + reflectivity * shade(reflected ray)     if reflectivity >= minReflectivity
 *          + transparency * shade(transmitted ray)   if transparency >= minTransparency
 *
 * m is the unit normal turned to face the incoming ray, s the unit vector to
 * the light, h the half-way vector between s and the direction to the eye.
 * Where the material's specularFraction f is above 0 the specular term is
 * Cook-Torrance's instead (lib/trace/cook_torrance.h), and the lit part of each
 * light is light * ((1 - f) diffuse (s.m) + f specular R_s (s.m)), Hill's
 * mix; a texture multiplies the ambient and diffuse colours first. A
 * light behind the surface (s.m <= 0) adds nothing, diffuse or specular, and
 * casts no shadow ray. Shadows are Hill's: any object between the point and
 * the light blocks it completely. Each term is skipped unless the material
 * calls for it (flags worked out at commit), so an effect the scene lacks
 * costs no ray: a purely emissive object runs no light loop, a light that
 * is behind the surface or whose colour the material cannot reflect casts
 * no shadow ray.
 *
 * The contribution cut-off (hr_render_options.min_weight) weighs each path:
 * a bounce adds reflectivity (or transparency) times the colour it brings
 * back, so a ray's weight is the product of those coefficients along its
 * path, and one below its allowance is not traced. The ray budget
 * (hr_render_options.ray_budget) bounds the work of a camera ray: each ray
 * carries the rays its subtree may cast (itself included), spends one on
 * itself and one on each shadow ray, and gives the rest to its bounces: the
 * reflected ray half of it where a transmitted one follows, the transmitted
 * ray all that the reflected subtree left. A ray is traced only where its
 * share covers it and a shadow ray to every light, so no sample casts more
 * than its budget; the shares follow the one order shade traces in, so a
 * pixel's rays are the same whatever the threads. */
#include <math.h>

#include "trace/cook_torrance.h"
#include "scene/material_analysis.h"
#include "trace/ray_diff.h"
#include "trace/spawn.h"
#include "trace/trace_context.h"
#include "texture/texture.h"
#include "geometry/vec.h"

/* Cook-Torrance's specular term of one light, weighted by the fraction as
 * Hill mixes it with the diffuse, (1 - f) R_d + f R_s (the diffuse's share
 * is taken in shading_material). */
static hr_color cook_torrance_term(const hr_material *mat, hr_vec3 m, hr_vec3 sdir, hr_vec3 to_eye)
{
    double r = hri_cook_torrance(m, sdir, to_eye, mat->surface_roughness, 1.0 / mat->speed_of_light);
    return rgb_scale(mat->specular, mat->specular_fraction * r);
}

/* The light loop; `cook` (a constant in each caller below) picks the
 * specular term, so each caller compiles to a loop of its own and Phong's
 * is the same code it was before Cook-Torrance. */
static inline __attribute__((always_inline)) hr_color
light_loop(hr_trace_ctx *tc, const hr_object *o, const hr_material *mat, hr_vec3 origin, hr_vec3 m,
           hr_vec3 to_eye, uint32_t flags, const int cook)
{
    const hr_scene *s = tc->scene;
    hr_color sum = rgb(0, 0, 0);
    for (int32_t i = 0; i < s->light_count; i++) {
        const hr_light *L = &s->lights[i];
        if ((flags & HR_MAT_INERT_LIGHT) && !tc->force_all_effects && hri_light_adds_nothing(L, mat, flags))
            continue;
        hr_vec3 to_light = v3_sub(L->position, origin);
        hr_vec3 sdir = v3_normalize(to_light);
        double lambert = v3_dot(sdir, m);
        if (!(lambert > 0.0) && !tc->force_all_effects) continue;
        if (s->effects & HR_EFFECT_SHADOWS || tc->force_all_effects) {
            hr_ray shadow = {origin, to_light};
            tc->rays_shadow++;
            tc->effects_ran |= HR_EFFECT_SHADOWS;
            /* The light sits at t = 1 along this ray. */
            if (hri_scene_trace_shadow(tc, &shadow, 0.0, 1.0, i)) continue;
        }
        if (!(lambert > 0.0)) continue;
        hr_color c = rgb(0, 0, 0);
        if (flags & HR_MAT_DIFFUSE) {
            c = rgb_scale(mat->diffuse, lambert);
            tc->effects_ran |= HR_EFFECT_DIFFUSE;
        }
        if (flags & HR_MAT_SPECULAR) {
            if (cook) {
                c = rgb_add(c, cook_torrance_term(mat, m, sdir, to_eye));
            } else {
                hr_vec3 half = v3_normalize(v3_add(sdir, to_eye));
                double phong = v3_dot(half, m);
                /* At or below the cut-off pow would give exactly 0 (scene/material_analysis.h). */
                if (phong > o->specular_cutoff)
                    c = rgb_add(c, rgb_scale(mat->specular, pow(phong, mat->specular_exponent)));
            }
            tc->effects_ran |= HR_EFFECT_SPECULAR;
        }
        sum = rgb_add(sum, rgb_mul(L->color, c));
    }
    return sum;
}

/* In shade's own code (both its copies), as the light loop of nearly every
 * hit. */
static inline __attribute__((always_inline)) hr_color
direct_light(hr_trace_ctx *tc, const hr_object *o, const hr_material *mat, hr_vec3 origin, hr_vec3 m,
             hr_vec3 to_eye, uint32_t flags)
{
    return light_loop(tc, o, mat, origin, m, to_eye, flags, 0);
}

static __attribute__((noinline)) hr_color direct_light_cook_torrance(hr_trace_ctx *tc, const hr_object *o,
                                                                     const hr_material *mat, hr_vec3 origin,
                                                                     hr_vec3 m, hr_vec3 to_eye, uint32_t flags)
{
    return light_loop(tc, o, mat, origin, m, to_eye, flags, 1);
}

/* What a ray carries down its path: its weight, the cut-off's allowance
 * and the rays its subtree may cast (INFINITY: no budget). */
typedef struct path {
    double weight, allowance, rays;
} path;

/* Every ray a context has cast below its camera rays. */
static inline uint64_t rays_cast(const hr_trace_ctx *tc)
{
    return tc->rays_shadow + tc->rays_reflected + tc->rays_refracted;
}

/* Whether a bounce of path `p` is traced. A forced bounce (one only
 * HR_EFFECTS_ALL traces, weight 0 throughout its subtree) passes the
 * cut-off: it contributes nothing either way, and it is there to be run;
 * the budget bounds it like any other (where `budgeted`: elsewhere no
 * bounce can reach it). */
static inline int worth_tracing(hr_trace_ctx *tc, path p, int forced, const int budgeted)
{
    if (!forced && p.weight < p.allowance) {
        tc->rays_cut++;
        return 0;
    }
    if (budgeted && !(p.rays >= 1.0 + (double)tc->scene->light_count)) {
        tc->rays_over_budget++;
        return 0;
    }
    return 1;
}

/* shade in three copies: one that keeps the ray budget's accounts, one for
 * the rays whose trees cannot reach the budget (a scene's usual depth and
 * lights: tc->budget_free_levels), which pays nothing for it, and one for
 * rays that carry differentials (a textured scene, lib/trace/ray_diff.h),
 * which keeps the budget's accounts too. A ray's bounces have fewer levels
 * below them than it has, so they stay in the copy it is in. The path goes
 * in registers: its parts as arguments. */
static hr_color shade_budgeted(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth,
                               double weight, double allowance, double rays, int forced);
static hr_color shade_unbudgeted(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth,
                                 double weight, double allowance, int forced);
static hr_color shade_diff(hr_trace_ctx *tc, const hr_ray *ray, const hr_ray_diff *rd, int32_t depth,
                           int32_t max_depth, path p, int forced);

static inline hr_color bounce(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth, path p,
                              int forced, const int budgeted)
{
    return budgeted ? shade_budgeted(tc, ray, depth, max_depth, p.weight, p.allowance, p.rays, forced)
                    : shade_unbudgeted(tc, ray, depth, max_depth, p.weight, p.allowance, forced);
}

hr_color hri_shade_ray(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth)
{
    if (max_depth - depth <= tc->budget_free_levels)
        return shade_unbudgeted(tc, ray, depth, max_depth, 1.0, tc->min_weight, 0);
    return shade_budgeted(tc, ray, depth, max_depth, 1.0, tc->min_weight, tc->ray_budget, 0);
}

hr_color hri_shade_ray_unbudgeted(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth, int32_t max_depth)
{
    return shade_unbudgeted(tc, ray, depth, max_depth, 1.0, tc->min_weight, 0);
}

hr_color hri_shade_ray_diff(hr_trace_ctx *tc, const hr_ray *ray, const hr_ray_diff *rd, int32_t depth,
                            int32_t max_depth)
{
    path p = {1.0, tc->min_weight, tc->ray_budget > 0.0 ? tc->ray_budget : INFINITY};
    return shade_diff(tc, ray, rd, depth, max_depth, p, 0);
}

/* How the facing normal m turns along the footprint of hit h, for the
 * bounces' differentials: the surface's own normal a fraction NEAR of the
 * footprint away, found by tracing the ray offset by NEAR of each
 * differential (shapes give no curvature; a plane gives 0 exactly). An
 * offset ray that leaves the surface (a silhouette, another object, a far
 * part of the same one) leaves that derivative 0, a plane's. Only textured
 * scenes trace these; they count in no statistic and change no shadow
 * cache, so a pixel's rays are the same whatever the threads. */
#define NEAR 0.0625
static __attribute__((noinline)) void normal_derivatives(hr_trace_ctx *tc, const hr_ray *ray,
                                                         const hr_ray_diff *rd, const hr_hit *h,
                                                         hr_vec3 dir, hr_vec3 m, hr_vec3 dpdx,
                                                         hr_vec3 dpdy, hr_vec3 *dmdx, hr_vec3 *dmdy)
{
    const hr_vec3 dos[2] = {rd->dodx, rd->dody}, dds[2] = {rd->dddx, rd->dddy}, dps[2] = {dpdx, dpdy};
    hr_vec3 *out[2] = {dmdx, dmdy};
    const double sign = v3_dot(h->normal, m) > 0.0 ? 1.0 : -1.0;
    for (int i = 0; i < 2; i++) {
        *out[i] = v3(0.0, 0.0, 0.0);
        hr_ray r = {v3_madd(ray->origin, dos[i], NEAR), v3_madd(dir, dds[i], NEAR)};
        hr_hit near;
        if (!hri_scene_trace_first(tc, &r, 0.0, INFINITY, &near)) continue;
        /* The same surface, where the footprint says the hit moved. */
        const hr_vec3 expect = v3_madd(h->point, dps[i], NEAR);
        const double slack = 0.5 * NEAR * v3_length(dps[i]) + 4.0 * (h->error + near.error);
        if (near.object != h->object || near.surface != h->surface ||
            !(v3_length(v3_sub(near.point, expect)) <= slack))
            continue;
        *out[i] = v3_scale(v3_sub(v3_scale(near.normal, sign), m), 1.0 / NEAR);
    }
}
#undef NEAR

/* The material shading uses at hit h of an object whose material is
 * textured or Cook-Torrance's (HR_MAT_ADJUSTED): a copy in `buf` whose
 * ambient and diffuse colours are multiplied by the texture's (where the
 * texture has a term to modulate) and whose diffuse gives the specular
 * its fraction, (1 - f). Out of line, so shade's own code is the same for
 * every other object. `footprint` (dp/dx, dp/dy; NULL: none) filters the
 * texture over the pixel's extent on the surface. */
static __attribute__((noinline)) const hr_material *
shading_material(hr_trace_ctx *tc, const hr_object *o, const hr_hit *h, const hr_vec3 *footprint,
                 uint32_t flags, hr_material *buf)
{
    *buf = *o->material;
    if (o->texture && (flags & (HR_MAT_AMBIENT | HR_MAT_DIFFUSE))) {
        hr_color t = footprint ? hri_texture_color_filtered(o->texture, o->cls, o->shape, h, footprint[0],
                                                            footprint[1])
                               : hri_texture_color(o->texture, o->cls, o->shape, h);
        buf->ambient = rgb_mul(buf->ambient, t);
        buf->diffuse = rgb_mul(buf->diffuse, t);
        tc->effects_ran |= HR_EFFECT_TEXTURE;
    }
    if (flags & HR_MAT_COOK_TORRANCE) buf->diffuse = rgb_scale(buf->diffuse, 1.0 - buf->specular_fraction);
    return buf;
}

/* shade's body, for the three copies below: `diff` (a constant in each)
 * says whether the ray carries differentials (rd), so the shading of a scene
 * without textures is the code it was, and a textured scene's filters each
 * texture by its hit's footprint; `budgeted` whether it keeps the ray
 * budget's accounts. */
static inline __attribute__((always_inline)) hr_color
shade_body(hr_trace_ctx *tc, const hr_ray *ray, const hr_ray_diff *rd, int32_t depth, int32_t max_depth,
           path p, int forced, const int diff, const int budgeted)
{
    const hr_scene *s = tc->scene;
    const uint64_t cast_before = budgeted ? rays_cast(tc) : 0;
    /* A shape failed: the render fails, so the rest of its rays are not
     * traced (a failing shape may be slow to fail: one that renders). */
    if (tc->status) return rgb(0, 0, 0);
    if (tc->cancelled) {
        if (tc->poll && ++tc->shade_calls % HR_POLL_INTERVAL == 0) tc->poll(tc->poll_user);
        /* The image is thrown away: unwind as fast as possible. */
        if (atomic_load_explicit(tc->cancelled, memory_order_relaxed)) return rgb(0, 0, 0);
        if (tc->cancel_flag && __atomic_load_n(tc->cancel_flag, __ATOMIC_RELAXED)) return rgb(0, 0, 0);
    }
    hr_hit h;
    if (!hri_scene_trace_first(tc, ray, 0.0, INFINITY, &h)) return s->globals.background;
    const hr_object *o = s->objects[h.object];
    const hr_material *mat = o->material;
    uint32_t flags = o->mat_flags;
    if (tc->force_all_effects)
        flags |= HR_MAT_EMITS | HR_MAT_AMBIENT | HR_MAT_DIFFUSE | HR_MAT_SPECULAR;
    /* A texture modulates the ambient and diffuse colours (Hill), nothing
     * else; Cook-Torrance takes its fraction from the diffuse. Any other
     * object pays this one test. */
    hr_vec3 dir = v3_normalize(ray->dir);
    hr_vec3 footprint[2];
    if (diff) hri_ray_diff_transfer(rd, dir, h.t * v3_length(ray->dir), h.normal, &footprint[0], &footprint[1]);
    hr_material adjusted;
    if (flags & HR_MAT_ADJUSTED) mat = shading_material(tc, o, &h, diff ? footprint : NULL, flags, &adjusted);

    hr_vec3 to_eye = v3_neg(dir);
    /* Hill's m: the normal on the side the ray arrives from. */
    hr_vec3 m = v3_dot(h.normal, dir) > 0.0 ? v3_neg(h.normal) : h.normal;

    hr_color c = rgb(0, 0, 0);
    if (flags & HR_MAT_EMITS) {
        c = rgb_add(c, mat->emissive);
        tc->effects_ran |= HR_EFFECT_EMISSION;
    }
    if (flags & HR_MAT_AMBIENT) {
        c = rgb_add(c, rgb_mul(mat->ambient, s->globals.global_ambient));
        tc->effects_ran |= HR_EFFECT_AMBIENT;
    }
    /* Where shadow rays and the reflected ray start (both leave on m's
     * side): worked out once, for the first of them that is cast. */
    hr_vec3 origin;
    int have_origin = 0;
    if ((flags & (HR_MAT_DIFFUSE | HR_MAT_SPECULAR)) && s->light_count > 0) {
        origin = hri_hit_spawn_origin(&h, m);
        have_origin = 1;
        c = rgb_add(c, flags & HR_MAT_COOK_TORRANCE
                           ? direct_light_cook_torrance(tc, o, mat, origin, m, to_eye, flags)
                           : direct_light(tc, o, mat, origin, m, to_eye, flags));
    }
    if (depth >= max_depth) return c;

    /* Under HR_EFFECTS_ALL every bounce is traced, weighted by what the
     * material calls for: 0 where it calls for none. c starts at +0 and its
     * terms are finite, so adding 0 * colour leaves every bit of it as it
     * was: the image is the same, only the work differs. */
    double reflect_weight = flags & HR_MAT_REFLECTS ? mat->reflectivity : 0.0;
    double refract_weight = flags & HR_MAT_REFRACTS ? mat->transparency : 0.0;
    /* The allowance is shared among the bounces that carry weight, so
     * HR_EFFECTS_ALL's forced ones change no cut; the budget among all the
     * bounces traced, as each costs rays. */
    int weighted = (reflect_weight > 0.0) + (refract_weight > 0.0);
    if (tc->force_all_effects) flags |= HR_MAT_REFLECTS | HR_MAT_REFRACTS;
    int bounces = ((flags & HR_MAT_REFLECTS) != 0) + ((flags & HR_MAT_REFRACTS) != 0);
    if (bounces == 0) return c;
    double allowance = tc->split_cut_off && weighted == 2 ? 0.5 * p.allowance : p.allowance;
    double rays = budgeted ? (p.rays - 1.0 - (double)(rays_cast(tc) - cast_before)) / bounces : INFINITY;

    double cos_i = -v3_dot(dir, m); /* > 0: angle of incidence */
    hr_vec3 dm[2]; /* m's derivatives (diff), worked out for the first bounce */
    int have_dm = 0;
    path reflected = {p.weight * reflect_weight, allowance, rays};
    if ((flags & HR_MAT_REFLECTS) && worth_tracing(tc, reflected, forced || reflect_weight == 0.0, budgeted)) {
        if (!have_origin) origin = hri_hit_spawn_origin(&h, m);
        have_origin = 1;
        hr_ray r = {origin, v3_madd(dir, m, 2.0 * cos_i)};
        tc->rays_reflected++;
        tc->effects_ran |= HR_EFFECT_REFLECTION;
        hr_color seen;
        if (diff) {
            if (!have_dm) normal_derivatives(tc, ray, rd, &h, dir, m, footprint[0], footprint[1], &dm[0], &dm[1]);
            have_dm = 1;
            hr_ray_diff rr = hri_ray_diff_reflect(rd, dir, m, dm[0], dm[1], footprint[0], footprint[1]);
            seen = shade_diff(tc, &r, &rr, depth + 1, max_depth, reflected, forced || reflect_weight == 0.0);
        } else {
            seen = bounce(tc, &r, depth + 1, max_depth, reflected, forced || reflect_weight == 0.0, budgeted);
        }
        c = rgb_add(c, rgb_scale(seen, reflect_weight));
    }
    /* What the reflected subtree left, all of it. */
    path refracted = {p.weight * refract_weight, allowance,
                      budgeted ? p.rays - 1.0 - (double)(rays_cast(tc) - cast_before) : INFINITY};
    if ((flags & HR_MAT_REFRACTS) && worth_tracing(tc, refracted, forced || refract_weight == 0.0, budgeted)) {
        /* Snell with Hill's speeds: sin(t) = (c2 / c1) sin(i). Entering goes
         * from the surrounding space (speed 1) into the material. */
        double c1 = h.entering ? 1.0 : mat->speed_of_light;
        double c2 = h.entering ? mat->speed_of_light : 1.0;
        double ratio = c2 / c1;
        double cos_t2 = 1.0 - ratio * ratio * (1.0 - cos_i * cos_i);
        hr_ray t;
        if (cos_t2 < 0.0) { /* total internal reflection */
            if (!have_origin) origin = hri_hit_spawn_origin(&h, m);
            have_origin = 1;
            t.origin = origin;
            t.dir = v3_madd(dir, m, 2.0 * cos_i);
            tc->rays_reflected++;
        } else {
            t.origin = hri_hit_spawn_origin(&h, v3_neg(m));
            t.dir = v3_add(v3_scale(dir, ratio), v3_scale(m, ratio * cos_i - sqrt(cos_t2)));
            tc->rays_refracted++;
        }
        tc->effects_ran |= HR_EFFECT_REFRACTION;
        hr_color seen;
        if (diff) {
            if (!have_dm) normal_derivatives(tc, ray, rd, &h, dir, m, footprint[0], footprint[1], &dm[0], &dm[1]);
            have_dm = 1;
            hr_ray_diff tr = cos_t2 < 0.0
                                 ? hri_ray_diff_reflect(rd, dir, m, dm[0], dm[1], footprint[0], footprint[1])
                                 : hri_ray_diff_refract(rd, dir, m, dm[0], dm[1], footprint[0], footprint[1],
                                                        ratio, sqrt(cos_t2));
            seen = shade_diff(tc, &t, &tr, depth + 1, max_depth, refracted, forced || refract_weight == 0.0);
        } else {
            seen = bounce(tc, &t, depth + 1, max_depth, refracted, forced || refract_weight == 0.0, budgeted);
        }
        c = rgb_add(c, rgb_scale(seen, refract_weight));
    }
    return c;
}

static __attribute__((noinline)) hr_color shade_budgeted(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth,
                                                         int32_t max_depth, double weight, double allowance,
                                                         double rays, int forced)
{
    return shade_body(tc, ray, NULL, depth, max_depth, (path){weight, allowance, rays}, forced, 0, 1);
}

static __attribute__((noinline)) hr_color shade_unbudgeted(hr_trace_ctx *tc, const hr_ray *ray, int32_t depth,
                                                           int32_t max_depth, double weight, double allowance,
                                                           int forced)
{
    return shade_body(tc, ray, NULL, depth, max_depth, (path){weight, allowance, INFINITY}, forced, 0, 0);
}

static hr_color shade_diff(hr_trace_ctx *tc, const hr_ray *ray, const hr_ray_diff *rd, int32_t depth,
                           int32_t max_depth, path p, int forced)
{
    return shade_body(tc, ray, rd, depth, max_depth, p, forced, 1, 1);
}
