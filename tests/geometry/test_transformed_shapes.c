/* Every built-in shape under a rotation, a non-uniform scale and a
 * translation: Hill's rule that the ray goes into object space through M^-1
 * unnormalised, so t is the same in both spaces, and that normals come back
 * through the transpose of M^-1. For random rays, the world hits of the
 * transformed object must be the object-space hits of the untransformed one
 * for the object-space ray: the same count, t, entering flags and surfaces;
 * the point M p; the normal M^-T n, normalised. The reference transforms are
 * done here in long double.
 * Tolerances: the host computes the object-space ray and the world point
 * with one 3x4 product each (a few ulps of |M| |p| + |translation|, ~1e-14
 * here), so t agrees to 1e-12 relative and points to 1e-12 (10 + |p|)
 * (scene size ~10; the unbounded plane is met far away); unit normals to 1e-9, as the shapes' own normals carry ~1e-15
 * relative error amplified by the scale ratio (8) and a possible near-grazing
 * renormalisation. */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *ctx;

static hr_scene *one_object(const char *shape, const hr_param *p, int32_t np, const hr_transform *t)
{
    hr_scene *s;
    hr_scene_create(ctx, &s);
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = shape;
    d.params = p;
    d.param_count = np;
    d.transform = t ? t->m : NULL;
    d.inverse = t ? t->inv : NULL;
    CHECK_MSG(hr_scene_add_object(s, &d, NULL) == HR_OK, "%s: %s", shape, hr_context_last_error(ctx));
    CHECK_OK(hr_scene_commit(s));
    return s;
}

static uint64_t rng = 0x9E3779B97F4A7C15u;
static double uniform(double lo, double hi)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return lo + (hi - lo) * (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

static void apply_point(const double m[16], const long double p[3], long double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = (long double)m[4 * r] * p[0] + (long double)m[4 * r + 1] * p[1] +
                 (long double)m[4 * r + 2] * p[2] + (long double)m[4 * r + 3];
}

static void check_shape(const char *shape, const hr_param *p, int32_t np)
{
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, 3, -2, 5);
    hr_transform_rotate(&t, 37, 1, 2, -0.5);
    hr_transform_scale(&t, 2, 0.5, 4); /* ratio 8: normals bend */
    hr_transform_rotate(&t, -20, 0, 1, 1);
    hr_scene *world = one_object(shape, p, np, &t);
    hr_scene *object = one_object(shape, p, np, NULL);
    hr_intersection wh, oh;
    hr_intersection_init(&wh);
    hr_intersection_init(&oh);
    int hits = 0;
    for (int i = 0; i < 4000; i++) {
        /* Rays from a box around the object, aimed at points near it. */
        long double o_obj[3] = {uniform(-3, 3), uniform(-3, 3), uniform(-3, 3)};
        long double aim[3] = {uniform(-1.2, 1.2), uniform(-1.2, 1.2), uniform(-0.2, 1.2)};
        long double o_w[3], aim_w[3];
        apply_point(t.m, o_obj, o_w);
        apply_point(t.m, aim, aim_w);
        hr_ray wr = {{(double)o_w[0], (double)o_w[1], (double)o_w[2]},
                     {(double)(aim_w[0] - o_w[0]), (double)(aim_w[1] - o_w[1]), (double)(aim_w[2] - o_w[2])}};
        /* The object-space ray of that world ray, in long double. */
        long double oo[3], od[3];
        for (int r = 0; r < 3; r++) {
            const double *row = t.inv + 4 * r;
            oo[r] = row[0] * (long double)wr.origin.x + row[1] * (long double)wr.origin.y +
                    row[2] * (long double)wr.origin.z + row[3];
            od[r] = row[0] * (long double)wr.dir.x + row[1] * (long double)wr.dir.y +
                    row[2] * (long double)wr.dir.z;
        }
        hr_ray orr = {{(double)oo[0], (double)oo[1], (double)oo[2]}, {(double)od[0], (double)od[1], (double)od[2]}};
        CHECK_OK(hr_scene_all_hits(world, &wr, 0, INFINITY, &wh));
        CHECK_OK(hr_scene_all_hits(object, &orr, 0, INFINITY, &oh));
        if (wh.count != oh.count) {
            /* Only a ray within rounding of an edge or a tangent may differ. */
            int near_edge = 0;
            for (int k = 0; k < oh.count; k++) near_edge |= fabs(oh.hits[k].t - (k ? oh.hits[k - 1].t : 0)) < 1e-9;
            for (int k = 0; k < wh.count; k++) near_edge |= fabs(wh.hits[k].t - (k ? wh.hits[k - 1].t : 0)) < 1e-9;
            CHECK_MSG(near_edge, "%s ray %d: %d world hits, %d object hits", shape, i, (int)wh.count, (int)oh.count);
            continue;
        }
        for (int k = 0; k < wh.count; k++) {
            const hr_hit *w = &wh.hits[k], *h = &oh.hits[k];
            hits++;
            CHECK_MSG(fabs(w->t - h->t) <= 1e-12 * fabs(h->t) + 1e-13, "%s: t %.17g vs %.17g", shape, w->t, h->t);
            CHECK_MSG(w->entering == h->entering && w->surface == h->surface, "%s: flags differ", shape);
            long double hp[3] = {h->point.x, h->point.y, h->point.z}, wp[3];
            apply_point(t.m, hp, wp);
            /* Relative to the point's size: the plane is unbounded, and a
             * grazing ray meets it far away. */
            long double mag = fmaxl(fabsl(wp[0]), fmaxl(fabsl(wp[1]), fabsl(wp[2])));
            long double ptol = 1e-12L * (10 + mag);
            CHECK_MSG(fabsl(wp[0] - w->point.x) < ptol && fabsl(wp[1] - w->point.y) < ptol &&
                          fabsl(wp[2] - w->point.z) < ptol,
                      "%s: point (%.17g %.17g %.17g), expected (%.17Lg %.17Lg %.17Lg)", shape,
                      w->point.x, w->point.y, w->point.z, wp[0], wp[1], wp[2]);
            /* M^-T n, normalised, in long double. */
            long double n[3];
            for (int c = 0; c < 3; c++)
                n[c] = t.inv[c] * (long double)h->normal.x + t.inv[4 + c] * (long double)h->normal.y +
                       t.inv[8 + c] * (long double)h->normal.z;
            long double len = sqrtl(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            CHECK_MSG(fabsl(n[0] / len - w->normal.x) < 1e-9 && fabsl(n[1] / len - w->normal.y) < 1e-9 &&
                          fabsl(n[2] / len - w->normal.z) < 1e-9,
                      "%s: normal (%g %g %g), expected (%Lg %Lg %Lg)", shape, w->normal.x, w->normal.y,
                      w->normal.z, n[0] / len, n[1] / len, n[2] / len);
        }
    }
    /* Enough rays must actually hit for this to mean anything. */
    CHECK_MSG(hits > 500, "%s: only %d hits", shape, hits);
    hr_intersection_release(&wh);
    hr_intersection_release(&oh);
    hr_scene_destroy(world);
    hr_scene_destroy(object);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    const char *plain[] = {"sphere", "cube", "square", "plane", "cylinder", "cone"};
    for (size_t i = 0; i < sizeof plain / sizeof plain[0]; i++) check_shape(plain[i], NULL, 0);
    hr_param s = {.name = "s", .type = HR_PARAM_NUMBER, .number = 0.4, .string = NULL, .object = 0};
    check_shape("taperedCylinder", &s, 1);
    check_shape("torus", NULL, 0);
    hr_param thin = {.name = "tube", .type = HR_PARAM_NUMBER, .number = 0.05, .string = NULL, .object = 0};
    check_shape("torus", &thin, 1);
    hr_context_destroy(ctx);
    return hr_test_end();
}
