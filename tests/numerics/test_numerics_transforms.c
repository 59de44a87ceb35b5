/* Transformed shapes through the whole library (cases X01-X09 of
 * CATALOG.md): hr_scene_add_object with transforms of scale 1e-4 .. 1e4,
 * uniform and not, rotated, translated up to 1e6, traced by
 * hr_scene_all_hits and compared with the quad-precision reference.
 *
 * Reference: the world ray is carried into object space in __float128
 * through the object's inverse (whose double entries are taken as exact;
 * the scene is given that inverse), then traced by quad_reference.c; Hill's
 * rule keeps t the same in both spaces.
 *
 * Three things are scored per hit, each against its own tolerance:
 * - t: 8 u condition (the module's error on the ray it was given, as in
 *   numerics_family.h) plus the host's rounding of the object-space ray:
 *   each coordinate of M^-1 o is a sum of 3 products and the translation,
 *   within gamma(3) (m_i) with m_i the sum of the magnitudes of its terms
 *   (Higham 3.1), and likewise the direction (n_i); that moves the line's
 *   point at the root by gamma(3) (m_i + |t| n_i), hence the root by
 *   sum_i |g_i| gamma(3) (m_i + |t| n_i) / |g . d| (g the surface's gradient
 *   at the root, d the object-space direction);
 * - the point: mapped back to object space in quad, its distance to the
 *   surface must be within sqrt(3) times the world error box mapped into
 *   object space (per object coordinate sum_j |inv_ij| error);
 * - the normal (the non-uniform scales): the angle between the library's
 *   unit normal and the exact one, M^-T g normalised, g the gradient at the
 *   object-space image of the reported point. The library computes
 *   normalise(M^-T n_o): n_o is within gamma(8) of its direction at the
 *   module's point (the re-projection's bound), which lies within dp of
 *   the image of the world point (the rounding of M p, mapped back), which
 *   turns a curved surface's normal by up to dp (curvature 1 for the unit
 *   quadrics); M^-T adds gamma(3) |M^-T| |n_o|; normalising two roundings.
 *   The tolerance is 2 |M^-T| (dn_o + gamma(3) |n_o|) / |M^-T n_o| +
 *   gamma(4): the first factor is the amplification of a non-uniform
 *   scale (up to its condition number, 1e8 for scales 1e-4 and 1e4). */
#include <math.h>
#include <quadmath.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "numerics_cases.h"
#include "quad_reference.h"
#include "random_rays.h"

#define RAYS 1500
#define SAFE_MARGIN 1e-6

static quad qabs(quad x)
{
    return x < 0 ? -x : x;
}

typedef struct placement {
    const char *cls;
    double scale[3];
    double translate[3];
    double angle;      /* degrees about (1, 2, -0.5) */
    double eye;        /* primary rays start this far (object units) from the centre */
    hr_vec3 centre;    /* object space */
    hr_bounds targets; /* object space, aimed at */
} placement;

/* The outward gradient of the reference surface at object point p. */
static void gradient(ref_shape ref, int surface, const quad p[3], quad g[3])
{
    g[0] = g[1] = g[2] = 0;
    switch (ref.kind) {
    case REF_SPHERE: g[0] = p[0], g[1] = p[1], g[2] = p[2]; break;
    case REF_CUBE: g[surface / 2] = surface % 2 ? -1 : 1; break;
    case REF_TAPERED:
        if (surface == 0) {
            const quad k = (quad)ref.s - 1, w = 1 + k * p[2];
            g[0] = p[0], g[1] = p[1], g[2] = -k * w;
        } else {
            g[2] = surface == 1 ? -1 : 1;
        }
        break;
    default: g[2] = 1; break;
    }
}

static double curvature(ref_shape ref, int surface)
{
    return ref.kind == REF_SPHERE || (ref.kind == REF_TAPERED && surface == 0) ? 1 : 0;
}

static void run_placement(const placement *pl, nc_result *out)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, pl->translate[0], pl->translate[1], pl->translate[2]);
    hr_transform_rotate(&t, pl->angle, 1, 2, -0.5);
    CHECK_OK(hr_transform_scale(&t, pl->scale[0], pl->scale[1], pl->scale[2]));
    hr_scene *scene;
    CHECK_OK(hr_scene_create(ctx, &scene));
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = pl->cls, d.transform = t.m, d.inverse = t.inv;
    CHECK_OK(hr_scene_add_object(scene, &d, NULL));
    CHECK_OK(hr_scene_commit(scene));
    const ref_shape ref = ref_shape_of(pl->cls, NAN, NAN);
    const double *m = t.m, *inv = t.inv;
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0x7a0000) + (uint64_t)pl->angle);
    hr_intersection list;
    hr_intersection_init(&list);
    double worst_t = 0, worst_point = 0, worst_normal = 0;
    int compared = 0, skipped = 0;
    for (int i = 0; i < RAYS; i++) {
        hr_vec3 u = rng_unit_vector(&rng);
        if (ref.kind == REF_PLANE) u.z = fabs(u.z) + (i % 2 ? 1e-6 : 0.3);
        const double ul = sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
        const hr_vec3 from = {pl->centre.x + pl->eye * u.x / ul, pl->centre.y + pl->eye * u.y / ul,
                              pl->centre.z + pl->eye * u.z / ul};
        const hr_vec3 to = {rng_uniform(&rng, pl->targets.lo.x, pl->targets.hi.x),
                            rng_uniform(&rng, pl->targets.lo.y, pl->targets.hi.y),
                            rng_uniform(&rng, pl->targets.lo.z, pl->targets.hi.z)};
        hr_ray wr;
        wr.origin = hr_transform_point(m, from);
        const hr_vec3 wt = hr_transform_point(m, to);
        wr.dir = (hr_vec3){wt.x - wr.origin.x, wt.y - wr.origin.y, wt.z - wr.origin.z};
        const double wo[3] = {wr.origin.x, wr.origin.y, wr.origin.z};
        const double wd[3] = {wr.dir.x, wr.dir.y, wr.dir.z};
        quad o[3], dq[3], mo[3], nd[3];
        for (int r = 0; r < 3; r++) {
            const double *row = inv + 4 * r;
            o[r] = row[3], dq[r] = 0, mo[r] = qabs(row[3]), nd[r] = 0;
            for (int c = 0; c < 3; c++) {
                o[r] += row[c] * (quad)wo[c];
                dq[r] += row[c] * (quad)wd[c];
                mo[r] += qabs(row[c] * (quad)wo[c]);
                nd[r] += qabs(row[c] * (quad)wd[c]);
            }
        }
        ref_trace expect;
        ref_trace_quad_ray(ref, o, dq, &expect);
        CHECK_OK(hr_scene_all_hits(scene, &wr, 0, INFINITY, &list));
        /* Hits behind the origin are not asked for. */
        int first = 0;
        while (first < expect.count && expect.hits[first].t <= 0) first++;
        if (!(expect.margin > SAFE_MARGIN)) {
            skipped++;
            continue;
        }
        compared++;
        const int n = expect.count - first;
        CHECK_MSG(list.count == n, "%s ray %d: %d hits, reference %d", pl->cls, i,
                  (int)list.count, n);
        if (list.count != n) {
            worst_t = INFINITY;
            continue;
        }
        for (int k = 0; k < n; k++) {
            const hr_hit *h = &list.hits[k];
            const ref_hit *r = &expect.hits[first + k];
            const quad p[3] = {o[0] + r->t * dq[0], o[1] + r->t * dq[1], o[2] + r->t * dq[2]};
            quad g[3];
            gradient(ref, r->surface, p, g);
            const quad slope = qabs(g[0] * dq[0] + g[1] * dq[1] + g[2] * dq[2]);
            quad moved = 0;
            for (int c = 0; c < 3; c++)
                moved += qabs(g[c]) * (quad)nc_gamma(3) * (mo[c] + qabs(r->t) * nd[c]);
            const double allowed = 8 * NC_U * ref_to_double(r->condition) +
                                   (slope > 0 ? ref_to_double(moved / slope) : INFINITY);
            const double t_ratio = ref_to_double(qabs((quad)h->t - r->t)) / allowed;
            if (!(t_ratio <= worst_t)) worst_t = t_ratio;
            /* The point, back in object space. */
            quad po[3];
            double box = 0, dp = 0;
            for (int row = 0; row < 3; row++) {
                const double *mr = inv + 4 * row;
                po[row] = mr[3] + mr[0] * (quad)h->point.x + mr[1] * (quad)h->point.y +
                          mr[2] * (quad)h->point.z;
                const double spread = fabs(mr[0]) + fabs(mr[1]) + fabs(mr[2]);
                box = fmax(box, spread * h->error);
                /* Rounding of M p for the module's point (|p| <= 2 here), mapped back. */
                const double *fr = m + 4 * row;
                const double fwd = nc_gamma(3) * (2 * (fabs(fr[0]) + fabs(fr[1]) + fabs(fr[2])) +
                                                  fabs(fr[3]));
                dp = fmax(dp, spread * fwd);
            }
            const hr_vec3 pd = {(double)po[0], (double)po[1], (double)po[2]};
            const double distance = ref_surface_distance(ref, h->surface, pd);
            const double point_ratio = distance / (sqrt(3.0) * box);
            if (!(point_ratio <= worst_point)) worst_point = point_ratio;
            /* The normal. */
            quad gn[3];
            gradient(ref, h->surface, po, gn);
            const quad gl = sqrtq(gn[0] * gn[0] + gn[1] * gn[1] + gn[2] * gn[2]);
            quad nw[3], spread = 0;
            for (int row = 0; row < 3; row++) {
                /* (M^-T g)_row = sum_c inv[c][row] g_c */
                nw[row] = 0;
                quad a = 0;
                for (int c = 0; c < 3; c++) {
                    nw[row] += inv[4 * c + row] * gn[c] / gl;
                    a += qabs((quad)inv[4 * c + row]) *
                         ((quad)(nc_gamma(8) + curvature(ref, h->surface) * dp) +
                          (quad)nc_gamma(3) * qabs(gn[c] / gl));
                }
                spread += a * a;
            }
            const quad nl = sqrtq(nw[0] * nw[0] + nw[1] * nw[1] + nw[2] * nw[2]);
            const quad ex = nw[0] / nl - h->normal.x, ey = nw[1] / nl - h->normal.y,
                       ez = nw[2] / nl - h->normal.z;
            const double angle = ref_to_double(sqrtq(ex * ex + ey * ey + ez * ez));
            const double normal_tol = 2 * ref_to_double(sqrtq(spread) / nl) + nc_gamma(4);
            const double normal_ratio = angle / normal_tol;
            if (!(normal_ratio <= worst_normal)) worst_normal = normal_ratio;
        }
    }
    out->samples = compared;
    nc_note(out, worst_t);
    nc_note(out, worst_point);
    nc_note(out, worst_normal);
    out->samples = compared;
    snprintf(out->note, sizeof out->note, "t %.3g, point %.3g, normal %.3g; %d skipped", worst_t,
             worst_point, worst_normal, skipped);
    CHECK_MSG(skipped < RAYS / 10, "%s: %d rays skipped near a tangency or seam", pl->cls,
              skipped);
    hr_intersection_release(&list);
    hr_scene_destroy(scene);
    hr_context_destroy(ctx);
}

#define UNIT_BOX {{-0.8, -0.8, -0.8}, {0.8, 0.8, 0.8}}

static const placement placements[] = {
    /* X01: the unit sphere at 1e6, rays from 1.1e6 away. */
    {"sphere", {1, 1, 1}, {1e6, -4e5, 2e5}, 0, 1.1e6, {0, 0, 0}, UNIT_BOX},
    /* X02: radius 1e-3 at distance 10. */
    {"sphere", {1e-3, 1e-3, 1e-3}, {6, 8, 0}, 30, 1e4, {0, 0, 0}, UNIT_BOX},
    /* X03: scale 1e-4 translated to 1e6, rays from 4 radii. */
    {"sphere", {1e-4, 1e-4, 1e-4}, {1e6, 1e6, -1e6}, 40, 4, {0, 0, 0}, UNIT_BOX},
    /* X04: scale 1e4. */
    {"sphere", {1e4, 1e4, 1e4}, {3e5, 0, 1e6}, 50, 4, {0, 0, 0}, UNIT_BOX},
    /* X05: non-uniform 1e-4, 1, 1e4, rotated: normals. */
    {"sphere", {1e-4, 1, 1e4}, {0.5, -2, 1}, 60, 4, {0, 0, 0}, UNIT_BOX},
    /* X06: the cube, non-uniform 1e-2, 1, 1e2, at 1e6. */
    {"cube", {1e-2, 1, 1e2}, {1e6, 0, -1e6}, 70, 4, {0, 0, 0}, UNIT_BOX},
    /* X07: the cylinder scaled 1e4 at 1e6. */
    {"cylinder", {1e4, 1e4, 1e4}, {-1e6, 1e6, 1e6}, 80, 4, {0, 0, 0.5},
     {{-0.8, -0.8, 0.1}, {0.8, 0.8, 0.9}}},
    /* X08: the plane rotated and at 1e6, half the rays 1e-6 above it. */
    {"plane", {1, 1, 1}, {1e6, 1e6, 1e6}, 90, 4, {0, 0, 0}, {{-2, -2, 0}, {2, 2, 0}}},
};

#define PLACEMENT_CASE(index)                                                                \
    static void run_##index(nc_result *out) { run_placement(&placements[index], out); }
PLACEMENT_CASE(0)
PLACEMENT_CASE(1)
PLACEMENT_CASE(2)
PLACEMENT_CASE(3)
PLACEMENT_CASE(4)
PLACEMENT_CASE(5)
PLACEMENT_CASE(6)
PLACEMENT_CASE(7)

/* X09: the scene's own traversal with zero direction components. The
 * generic cube untransformed beside a 4 x 4 grid of cubes of half-size 0.5
 * at spacing 2 (so the BVH has inner nodes), rays along the
 * axes starting exactly in a face plane, with every zero component of
 * origin and direction +0 or -0. Each ray runs along closed faces: 2 hits
 * per cube it passes, at exact t, the same for every sign, and
 * hr_scene_first_hit gives the first of them. (The host pads every world
 * box by 4 epsilon of its magnitude, so no ray that touches a surface
 * starts exactly on a box plane: the slab test's 0 * inf = NaN branch
 * cannot change these answers; CATALOG.md says so.) */
static void run_signed_zeros(nc_result *out)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    hr_scene *scene;
    CHECK_OK(hr_scene_create(ctx, &scene));
    hr_object_desc plain;
    memset(&plain, 0, sizeof plain);
    plain.struct_size = sizeof plain;
    plain.shape = "cube";
    CHECK_OK(hr_scene_add_object(scene, &plain, NULL));
    for (int i = 0; i < 16; i++) {
        hr_transform t;
        hr_transform_identity(&t);
        hr_transform_translate(&t, 4 + 2 * (i % 4), 2 * (i / 4), 0);
        CHECK_OK(hr_transform_scale(&t, 0.5, 0.5, 0.5));
        hr_object_desc d;
        memset(&d, 0, sizeof d);
        d.struct_size = sizeof d;
        d.shape = "cube", d.transform = t.m, d.inverse = t.inv;
        CHECK_OK(hr_scene_add_object(scene, &d, NULL));
    }
    CHECK_OK(hr_scene_commit(scene));
    static const struct {
        hr_ray ray;
        int count;
        double t0, t1; /* the first cube's entry and exit */
    } rays[] = {
        {{{1, 0.3, 5}, {0, 0, -1}}, 2, 4, 6},       /* down the face x = 1 of the plain cube */
        {{{-1, -3, 0}, {0, 2, 0}}, 2, 1, 2},        /* along its face x = -1 */
        {{{0, 1, -5}, {0, 0, 1}}, 2, 4, 6},         /* along its face y = 1 */
        {{{1, 1, -5}, {0, 0, 0.5}}, 2, 8, 12},      /* along its edge x = y = 1 */
        {{{6.5, 2, 5}, {0, 0, -1}}, 2, 4.5, 5.5},   /* down the face x = 6.5 of grid cube (1, 1) */
        {{{13, 0.5, 0}, {-1, 0, 0}}, 10, 2.5, 3.5}, /* along the faces y = 0.5 of row 0, then
                                                       through the plain cube */
        {{{4, -3, 0.5}, {0, 1, 0}}, 8, 2.5, 3.5},   /* along the faces z = 0.5 of column 0 */
    };
    hr_intersection list;
    hr_intersection_init(&list);
    for (size_t k = 0; k < sizeof rays / sizeof rays[0]; k++)
        for (int mask = 0; mask < 64; mask++) {
            hr_ray r = rays[k].ray;
            double *v[6] = {&r.origin.x, &r.origin.y, &r.origin.z, &r.dir.x, &r.dir.y, &r.dir.z};
            for (int j = 0; j < 6; j++)
                if ((mask >> j & 1) && *v[j] == 0) *v[j] = -0.0;
            CHECK_OK(hr_scene_all_hits(scene, &r, 0, INFINITY, &list));
            hr_hit first;
            int32_t found = 0;
            CHECK_OK(hr_scene_first_hit(scene, &r, 0, INFINITY, &first, &found));
            int ok = list.count == rays[k].count && found && list.hits[0].t == rays[k].t0 &&
                     list.hits[1].t == rays[k].t1 && first.t == rays[k].t0;
            for (int i = 0; ok && i < list.count; i++) ok = list.hits[i].entering == !(i % 2);
            CHECK_MSG(ok, "grid ray %zu signs %#x: %d hits, first %d at %g", k, mask,
                      (int)list.count, (int)found, found ? first.t : 0.0);
            out->samples++;
            out->events += !ok;
        }
    hr_intersection_release(&list);
    hr_scene_destroy(scene);
    hr_context_destroy(ctx);
}

#define THREE_TOLERANCES "t: 8u cond + host term; point: sqrt3 box; normal: amplified"

static const nc_case cases[] = {
    {"X01", "sphere", "unit sphere at 1e6, rays from 1.1e6 away", "far: host and module",
     THREE_TOLERANCES, run_0},
    {"X02", "sphere", "radius 1e-3 at distance 10", "object-space origin at 1e4",
     THREE_TOLERANCES, run_1},
    {"X03", "sphere", "scale 1e-4 at 1e6", "world ulp 1e-10 = object 1e-6", THREE_TOLERANCES,
     run_2},
    {"X04", "sphere", "scale 1e4 at 1e6", "large object far away", THREE_TOLERANCES, run_3},
    {"X05", "sphere", "non-uniform 1e-4, 1, 1e4, rotated", "normals through M^-T, cond 1e8",
     THREE_TOLERANCES, run_4},
    {"X06", "cube", "non-uniform 1e-2, 1, 1e2 at 1e6", "flat normals, skewed faces",
     THREE_TOLERANCES, run_5},
    {"X07", "cylinder", "scale 1e4 at 1e6", "wall and disks, large", THREE_TOLERANCES, run_6},
    {"X08", "plane", "rotated, at 1e6, rays 1e-6 above it", "nearly parallel, far",
     THREE_TOLERANCES, run_7},
    {"X09", "cube grid", "BVH rays in face planes, +-0 components", "0 * inf = NaN in box tests",
     "exact hits, the same for every sign; first hit agrees", run_signed_zeros},
};

int main(void)
{
    return nc_run_table("transforms", cases, (int)(sizeof cases / sizeof cases[0]));
}
