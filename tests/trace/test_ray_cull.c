/* The culls of lib/trace/ray_cull.h must never drop a hit.
 *
 * The box around a scene's BVH (box_misses on cull_box_widened): on
 * 2,000,000 random rays against random boxes (thin ones, flat ones, far
 * ones), a culled ray must not meet the box as given within its window,
 * decided in long double; rays start inside, outside and on faces (where a
 * parallel ray's distance is 0 / 0), run parallel to faces (+0 and -0) or
 * nearly, and have windows ending on a face's own t. On all of them, and on
 * the box before widening, the SSE2 test (box_misses_sse2) must answer as
 * the scalar one (shape_box_misses).
 *
 * A shadow ray passes an unbounded object (a plane) without tracing it when
 * unbounded_misses says, from the object's object-space bounds, that the ray
 * has no hit in its window: on 3,000,000 random rays through randomly placed
 * objects (a plane z = 0, a half-space's face, a slab and a slab crossed
 * with another), any culled ray must have no hit on any plane inside the
 * bounds (their faces included), computed as object_trace and the plane
 * compute it: the ray into object space, its direction rescaled by a power
 * of two when too long or too short, t = (c - o_z) / d_z and the window
 * test on both sides of the rescaling. The rays are made to find the edges:
 * origins on the plane (as a shadow ray spawned from it), windows ending on
 * the plane's own t or the next double, directions parallel to it, with a
 * tiny component along it, or very long or short, and exact rotations. And
 * the cull must be worth having: most rays of the set are culled. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <hitray/transform.h>

#include "hr_test.h"
#include "trace/ray_cull.h"

static uint64_t state = 0x9e3779b97f4a7c15ull;

static double uniform(void)
{
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return (double)((state * 2685821657736338717ull) >> 11) * 0x1p-53;
}

static double symmetric(double size) { return (2.0 * uniform() - 1.0) * size; }

/* Whether the plane x_axis = c of an object (inverse `inv`) has a hit in
 * (tmin, tmax), as object_trace and the plane shape would find it. */
static int plane_hit(const hr_object *o, int axis, double c, const hr_ray *ray, double tmin,
                     double tmax, hr_vec3 *at)
{
    hr_vec3 org = o->identity ? ray->origin : hri_xform_point(o->inv, ray->origin);
    hr_vec3 dir = o->identity ? ray->dir : hri_xform_vector(o->inv, ray->dir);
    const int t_exp = v3_rescale_exponent(dir);
    double lo = tmin, hi = tmax;
    if (t_exp) {
        dir = v3_ldexp(dir, -t_exp);
        lo = ldexp(tmin, t_exp);
        hi = ldexp(tmax, t_exp);
    }
    const double ok = (&org.x)[axis], dk = (&dir.x)[axis];
    if (dk == 0.0) return 0; /* parallel: the plane reports nothing */
    double t = (c - ok) / dk;
    if (!(t > lo && t < hi)) return 0;
    *at = (hr_vec3){org.x + t * dir.x, org.y + t * dir.y, org.z + t * dir.z};
    if (t_exp) {
        t = ldexp(t, -t_exp);
        if (!(t > tmin && t < tmax && isfinite(t))) return 0;
    }
    return 1;
}

static void random_transform(hr_transform *t, int kind)
{
    hr_transform_identity(t);
    if (kind == 0) return;
    if (kind == 1) { /* Hill's floor: an exact quarter turn */
        CHECK(hr_transform_rotate(t, -90, 1, 0, 0) == HR_OK);
        return;
    }
    hr_transform r;
    hr_transform_identity(&r);
    hr_transform_translate(&r, symmetric(5), symmetric(5), symmetric(5));
    hr_transform_compose(t, &r);
    hr_transform_identity(&r);
    CHECK(hr_transform_rotate(&r, symmetric(180), symmetric(1), symmetric(1), 0.1 + uniform()) ==
          HR_OK);
    hr_transform_compose(t, &r);
    if (kind == 3) {
        hr_transform_identity(&r);
        const double big = uniform() < 0.5 ? 0x1p-230 : 0x1p230;
        CHECK(hr_transform_scale(&r, 0.5 + uniform(), uniform() < 0.3 ? big : 1.0, 0.3 + uniform()) ==
              HR_OK);
        hr_transform_compose(t, &r);
    }
}

static double random_component(void)
{
    const double u = uniform();
    if (u < 0.05) return 0.0;
    if (u < 0.10) return symmetric(0x1p-205);
    if (u < 0.15) return symmetric(0x1p210);
    return symmetric(1.0);
}

/* Whether o + t d, t in (tmin, tmax), meets the closed box b: slab by slab
 * in long double (64 bits of mantissa), far finer than the cull's margins. */
static int box_met(const hr_bounds *b, const hr_ray *r, double tmin, double tmax)
{
    const double *lo = &b->lo.x, *hi = &b->hi.x, *o = &r->origin.x, *d = &r->dir.x;
    long double a = -INFINITY, z = INFINITY;
    for (int k = 0; k < 3; k++) {
        if (d[k] == 0.0) {
            if (o[k] < lo[k] || o[k] > hi[k]) return 0;
            continue;
        }
        long double t0 = ((long double)lo[k] - o[k]) / d[k], t1 = ((long double)hi[k] - o[k]) / d[k];
        if (t0 > t1) {
            const long double w = t0;
            t0 = t1, t1 = w;
        }
        if (t0 > a) a = t0;
        if (t1 < z) z = t1;
    }
    return a <= z && a < tmax && z > tmin;
}

static void box_cull_keeps_every_box(void)
{
    long rays = 0, culled = 0, wrong = 0, differ = 0;
    for (int scene = 0; scene < 1000; scene++) {
        const double far = scene % 3 == 0 ? 1e6 : 1.0, size = scene % 5 == 0 ? 1e-9 : 1.0 + 3 * uniform();
        hr_bounds box;
        box.lo = (hr_vec3){symmetric(5 * far), symmetric(5 * far), symmetric(5 * far)};
        box.hi = (hr_vec3){box.lo.x + size * uniform(), box.lo.y + size * uniform(),
                           box.lo.z + (scene % 7 == 0 ? 0.0 : size * uniform())};
        const hr_bounds widened = cull_box_widened(box);
        for (int i = 0; i < 2000; i++, rays++) {
            hr_ray r;
            const double how = uniform();
            const hr_vec3 inside = {box.lo.x + uniform() * (box.hi.x - box.lo.x),
                                    box.lo.y + uniform() * (box.hi.y - box.lo.y),
                                    box.lo.z + uniform() * (box.hi.z - box.lo.z)};
            if (how < 0.3) { /* on a face, or just off it */
                r.origin = inside;
                const int k = (int)(uniform() * 3);
                (&r.origin.x)[k] = uniform() < 0.5 ? (&box.lo.x)[k] : (&box.hi.x)[k];
                if (uniform() < 0.5) (&r.origin.x)[k] += symmetric(1e-12 * far);
            } else if (how < 0.4) {
                r.origin = inside;
            } else {
                r.origin = (hr_vec3){inside.x + symmetric(10 * far), inside.y + symmetric(10 * far),
                                     inside.z + symmetric(10 * far)};
            }
            /* Aimed at the box's inside most of the time, so it is met or
             * nearly met; some components zero (of either sign) or tiny. */
            const hr_vec3 target = {box.lo.x + uniform() * (box.hi.x - box.lo.x),
                                    box.lo.y + uniform() * (box.hi.y - box.lo.y),
                                    box.lo.z + uniform() * (box.hi.z - box.lo.z)};
            r.dir = uniform() < 0.7 ? (hr_vec3){target.x - r.origin.x, target.y - r.origin.y,
                                                target.z - r.origin.z}
                                    : (hr_vec3){symmetric(1), symmetric(1), symmetric(1)};
            for (int k = 0; k < 3; k++) {
                const double u = uniform();
                if (u < 0.05) (&r.dir.x)[k] = 0.0;
                else if (u < 0.1) (&r.dir.x)[k] = -0.0;
                else if (u < 0.13) (&r.dir.x)[k] = symmetric(1e-300);
            }
            if (r.dir.x == 0 && r.dir.y == 0 && r.dir.z == 0) r.dir.x = 1.0;
            double tmin = uniform() < 0.5 ? 0.0 : symmetric(1e-3), tmax = INFINITY;
            const double pick = uniform();
            if (pick < 0.4) { /* the window ends on a face's own t */
                const int k = (int)(uniform() * 3);
                const double dk = (&r.dir.x)[k];
                if (dk != 0.0) {
                    const double face = uniform() < 0.5 ? (&box.lo.x)[k] : (&box.hi.x)[k];
                    const double t = (face - (&r.origin.x)[k]) / dk, step = uniform();
                    const double end = step < 0.4 ? t : step < 0.7 ? nextafter(t, INFINITY) : nextafter(t, -INFINITY);
                    if (uniform() < 0.5) tmax = end;
                    else tmin = end;
                }
            } else if (pick < 0.6) {
                tmax = uniform() * 2;
            }
            if (!(tmin <= tmax)) continue;
            /* The SSE2 lanes and the scalar reference agree, ray by ray. */
            differ += box_misses_sse2(&widened, &r, tmin, tmax) != shape_box_misses(&widened, &r, tmin, tmax);
            differ += box_misses_sse2(&box, &r, tmin, tmax) != shape_box_misses(&box, &r, tmin, tmax);
            if (!box_misses(&widened, &r, tmin, tmax)) continue;
            culled++;
            if (box_met(&box, &r, tmin, tmax)) {
                if (wrong < 5)
                    fprintf(stderr, "box culled but met: scene %d ray %d o (%a %a %a) d (%a %a %a) (%a, %a)\n",
                            scene, i, r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, tmin,
                            tmax);
                wrong++;
            }
        }
    }
    fprintf(stderr, "boxes: %ld rays, %ld culled, %ld culled but met, %ld where the SSE2 and scalar tests differ\n",
            rays, culled, wrong, differ);
    CHECK_MSG(wrong == 0, "%ld culled rays met the box", wrong);
    CHECK_MSG(differ == 0, "%ld answers of box_misses_sse2 differ from shape_box_misses", differ);
    CHECK(culled > rays / 5);
}

int main(void)
{
    box_cull_keeps_every_box();
    /* Bounds: the plane, a half-space's face, a slab, a slab by a slab. */
    const hr_bounds shapes[4] = {
        {{-INFINITY, -INFINITY, 0.0}, {INFINITY, INFINITY, 0.0}},
        {{-INFINITY, -INFINITY, -INFINITY}, {INFINITY, INFINITY, 0.25}},
        {{-INFINITY, -INFINITY, -0.5}, {INFINITY, INFINITY, 0.75}},
        {{-1.0, -INFINITY, -0.5}, {2.0, INFINITY, 0.5}},
    };
    long rays = 0, culled = 0, wrong = 0;
    for (int scene = 0; scene < 1500; scene++) {
        hr_object o;
        memset(&o, 0, sizeof o);
        hr_transform t;
        random_transform(&t, scene % 4);
        memcpy(o.m, t.m, sizeof o.m);
        memcpy(o.inv, t.inv, sizeof o.inv);
        o.identity = scene % 4 == 0;
        o.local_bounds = shapes[(scene / 4) % 4];
        unbounded_cull_prepare(&o);
        CHECK(o.slab_axes == ((scene / 4) % 4 == 3 ? 5u : 4u));
        for (int i = 0; i < 2000; i++, rays++) {
            hr_ray ray;
            /* A point of the plane z = lo (or hi) in world space, moved off
             * it a little or not at all, or anywhere. */
            const double *lo = &o.local_bounds.lo.x, *hi = &o.local_bounds.hi.x;
            const double face = isfinite(lo[2]) && uniform() < 0.5 ? lo[2] : hi[2];
            const hr_vec3 on = hri_xform_point(o.m, (hr_vec3){symmetric(20), symmetric(20), face});
            const double how = uniform();
            ray.origin = how < 0.4 ? on
                         : how < 0.7 ? (hr_vec3){on.x + symmetric(1e-12), on.y + symmetric(1e-12),
                                                 on.z + symmetric(1e-12)}
                                     : (hr_vec3){symmetric(30), symmetric(30), symmetric(30)};
            ray.dir = (hr_vec3){random_component(), random_component(), random_component()};
            if (uniform() < 0.1) { /* parallel to the plane in object space, or nearly */
                hr_vec3 d = hri_xform_vector(o.m, (hr_vec3){symmetric(1), symmetric(1),
                                                            uniform() < 0.5 ? 0.0 : symmetric(1e-300)});
                ray.dir = d;
            }
            if (ray.dir.x == 0 && ray.dir.y == 0 && ray.dir.z == 0) ray.dir.y = 1.0;
            double tmin = uniform() < 0.5 ? 0.0 : symmetric(1e-9), tmax = INFINITY;
            const double pick = uniform();
            if (pick < 0.5) {
                /* The window ends at (or just around) the face's own t. */
                hr_vec3 org = hri_xform_point(o.inv, ray.origin), dir = hri_xform_vector(o.inv, ray.dir);
                const double tf = dir.z != 0.0 ? (face - org.z) / dir.z : 1.0;
                const double choice = uniform();
                tmax = choice < 0.3 ? tf : choice < 0.6 ? nextafter(tf, INFINITY) : nextafter(tf, -INFINITY);
                if (uniform() < 0.3) tmin = tmax < 0 ? tmax : tmin, tmax = tmax < 0 ? 0.0 : tmax;
            } else if (pick < 0.7) {
                tmax = uniform() * 50;
            }
            if (!(tmin <= tmax) || isnan(tmax)) continue;
            if (!unbounded_misses(&o, &ray, tmin, tmax)) continue;
            culled++;
            /* Culled: no plane inside the bounds may have a hit. */
            int hit = 0;
            for (uint32_t axes = o.slab_axes; axes; axes &= axes - 1) {
                const int k = __builtin_ctz(axes);
                const double cs[3] = {lo[k], hi[k], isfinite(lo[k]) && isfinite(hi[k]) ? 0.5 * (lo[k] + hi[k]) : hi[k]};
                for (int j = 0; j < 3; j++) {
                    if (!isfinite(cs[j])) continue;
                    /* The part of the plane inside the other slab (a face
                     * of the box, or a section of it) is inside the bounds;
                     * a point within 1e-12 of the other slab's faces is
                     * left out: a ray nearly parallel to them, as this set
                     * has, crosses them where rounding says, so whether
                     * such a point is inside is not the ray's to tell. */
                    hr_vec3 at;
                    if (!plane_hit(&o, k, cs[j], &ray, tmin, tmax, &at)) continue;
                    const int other = k == 0 ? 2 : 0;
                    const double x = (&at.x)[other];
                    hit |= !(o.slab_axes >> other & 1) ||
                           (x >= lo[other] + 1e-12 && x <= hi[other] - 1e-12);
                }
            }
            if (hit) {
                if (wrong < 5)
                    fprintf(stderr, "culled with a hit: scene %d ray %d o (%a %a %a) d (%a %a %a) (%a, %a)\n",
                            scene, i, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y,
                            ray.dir.z, tmin, tmax);
                wrong++;
            }
        }
    }
    fprintf(stderr, "planes: %ld rays, %ld culled, %ld culled with a hit\n", rays, culled, wrong);
    CHECK_MSG(wrong == 0, "%ld culled rays had a hit", wrong);
    CHECK(culled > rays / 4);
    return hr_test_end();
}
