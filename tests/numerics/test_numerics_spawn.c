/* Self-intersection and shadow acne through the whole library (cases P01-P11
 * and A01-A03 of CATALOG.md).
 *
 * Self-intersection, as pbrt tests it. Every shape class is placed under
 * transforms with scales 1e-4 .. 1e4 (uniform and non-uniform, rotated) and
 * translations up to 1e6. Primary rays hit it anywhere, and (every other
 * one) just inside a seam: an edge, a rim, the cone's apex, a mesh vertex,
 * the CSG crease. From each hit of a primary ray, rays are spawned
 * with hr_hit_spawn_origin (the renderer's own offset, from the hit's error
 * bound): SPAWN_OUT rays into the hemisphere of the facing normal (a quarter
 * of them within 1e-3 .. 1e-7 of the tangent plane, where rounding bites)
 * and SPAWN_TO rays toward random points of the object's neighbourhood (each
 * leaving on the side its direction points to). A spawned ray hits its own
 * surface when its first hit says the origin was left on the wrong side:
 * - an open surface, or a convex solid left outward: any hit at all;
 * - a non-convex solid (torus, CSG union, which may be legitimately hit
 *   again elsewhere) left outward: a first hit that leaves the solid (the
 *   origin was still inside); entering flags are exact for these shapes
 *   (the harness checks they alternate), so this tells a self-hit from a
 *   true re-entry however close it is, with no distance threshold;
 * - any solid entered (the ray points inside): a first hit that enters (the
 *   origin was still outside), or no hit at all.
 * A hit nearer a seam than its spawn offset may leave the origin on the
 * wrong side of the seam's other surface, which no offset along one normal
 * can avoid: such self-hits are counted apart (seam_distance, spawn_from).
 * The shell: the same scene with a second object enclosing the first at a
 * gap of at least 1e-5 object units everywhere (object units: Hill's
 * generic shapes have size 1, so the gap is 1e-5 of the object's size in
 * every transform). Every outward ray must start inside the shell (its
 * first crossing of the shell leaves it). Where the gap in world units is
 * smaller than the spawn offset (the hit's world error bound projected on
 * the normal), the ray starts
 * beyond the shell and cannot: the test counts those rays, prints the
 * smallest gap/offset ratio, and requires the shell where it exceeds 2.
 *
 * Shadow acne: a plane, a sphere and a cube lit by a light nearly in the
 * tangent plane (1e-3 above the plane and the cube's top, grazing the
 * sphere's terminator), at scene scales 1e-4, 1 and 1e4 and 1e6 away.
 * Each pixel's colour from hr_scene_shade is compared with the colour the
 * same pixel has when nothing can shadow it: a single convex object with the
 * light on the front side of the surface cannot shadow that point, so any
 * lit pixel (Lambert term > 0 by a margin, see CATALOG.md) that shade
 * darkens is acne. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "numerics_cases.h"
#include "quad_reference.h"
#include "random_rays.h"

#define SPAWN_OUT 1000
#define SPAWN_TO 1000
#define HITS_PER_TRANSFORM 2
#define TRANSFORMS 12

/* --- Scenes ------------------------------------------------------------------- */

enum shell_kind { SHELL_SCALE, SHELL_TUBE, SHELL_LIFT, SHELL_CYLINDER };
/* Where a shape's error bounds are most strained: every other hit point is
 * taken within 1e-6 .. 1e-12 of one of these. */
enum seam_kind { SEAM_NONE, SEAM_EDGES, SEAM_RIMS, SEAM_APEX, SEAM_VERTEX, SEAM_CREASE };
enum convexity { OPEN, CONVEX, NONCONVEX };

typedef struct spawn_shape {
    const char *label;
    const char *cls;   /* class name, or "union" for the CSG case */
    double param;      /* taperedCylinder's s, torus's tube; NaN: none */
    const char *file;  /* mesh file under tests/data/meshes, or NULL */
    int convexity;
    int shell;
    hr_vec3 centre; /* SHELL_SCALE: the interior point the shell is scaled about */
    double sigma;   /* SHELL_SCALE: 1 + sigma, the smallest gap being 1e-5 */
    hr_bounds box;  /* object-space box the random targets are drawn around */
    int seams;      /* enum seam_kind */
} spawn_shape;

#define SHELL_GAP 1e-5

static const spawn_shape shapes[] = {
    {"sphere", "sphere", NAN, NULL, CONVEX, SHELL_SCALE, {0, 0, 0}, 1e-5,
     {{-1, -1, -1}, {1, 1, 1}}, SEAM_NONE},
    {"plane", "plane", NAN, NULL, OPEN, SHELL_LIFT, {0, 0, 0}, 0, {{-2, -2, -1}, {2, 2, 1}},
     SEAM_NONE},
    {"square", "square", NAN, NULL, OPEN, SHELL_LIFT, {0, 0, 0}, 0, {{-1, -1, -1}, {1, 1, 1}},
     SEAM_EDGES},
    {"cube", "cube", NAN, NULL, CONVEX, SHELL_SCALE, {0, 0, 0}, 1e-5, {{-1, -1, -1}, {1, 1, 1}},
     SEAM_EDGES},
    {"cylinder", "cylinder", NAN, NULL, CONVEX, SHELL_CYLINDER, {0, 0, 0}, 0,
     {{-1, -1, 0}, {1, 1, 1}}, SEAM_RIMS},
    /* Support distances from the centre: cone 0.25 (base), tapered 0.5 (base and cap), icosahedron
     * 0.795 (inradius), the union 0.75 (at the crease): sigma = 1e-5 / that. */
    {"cone", "cone", NAN, NULL, CONVEX, SHELL_SCALE, {0, 0, 0.25}, 4e-5, {{-1, -1, 0}, {1, 1, 1}},
     SEAM_APEX},
    {"taperedCylinder", "taperedCylinder", 0.5, NULL, CONVEX, SHELL_SCALE, {0, 0, 0.5}, 2e-5,
     {{-1, -1, 0}, {1, 1, 1}}, SEAM_RIMS},
    {"torus", "torus", 0.2, NULL, NONCONVEX, SHELL_TUBE, {0, 0, 0}, 0,
     {{-1.2, -1.2, -0.2}, {1.2, 1.2, 0.2}}, SEAM_NONE},
    {"icosahedron", "icosahedron", NAN, NULL, CONVEX, SHELL_SCALE, {0, 0, 0}, 1.3e-5,
     {{-1, -1, -1}, {1, 1, 1}}, SEAM_VERTEX},
    {"mesh cube.obj", "mesh", NAN, "cube.obj", CONVEX, SHELL_SCALE, {0, 0, 0}, 1e-5,
     {{-1, -1, -1}, {1, 1, 1}}, SEAM_EDGES},
    {"union", "union", NAN, NULL, NONCONVEX, SHELL_SCALE, {0, 0, 0}, 1.4e-5,
     {{-1.5, -1, -1}, {1.5, 1, 1}}, SEAM_CREASE},
};

/* Adds one object of `cls` (with its number parameter or mesh file) under
 * `t`; returns its index or -1. */
static int64_t add_leaf(hr_scene *s, const char *cls, double param, const char *file,
                        const hr_transform *t)
{
    hr_param p;
    memset(&p, 0, sizeof p);
    char path[512];
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = cls;
    d.transform = t ? t->m : NULL;
    d.inverse = t ? t->inv : NULL;
    if (file) {
        snprintf(path, sizeof path, "%s/tests/data/meshes/%s", HR_TEST_SOURCE_DIR, file);
        p.name = "file", p.type = HR_PARAM_STRING, p.string = path;
        d.params = &p, d.param_count = 1;
    } else if (!isnan(param)) {
        p.name = strcmp(cls, "torus") == 0 ? "tube" : "s";
        p.type = HR_PARAM_NUMBER, p.number = param;
        d.params = &p, d.param_count = 1;
    }
    int64_t index = -1;
    const hr_status st = hr_scene_add_object(s, &d, &index);
    CHECK_MSG(st == HR_OK, "add %s: %s", cls, hr_context_last_error(hr_scene_context(s)));
    return st == HR_OK ? index : -1;
}

/* The shape under `t`; *first and *last receive the range of object
 * indices its hits may carry (a boolean's hits name its leaves). */
static void add_shape(hr_scene *s, const spawn_shape *sh, double param, const hr_transform *t,
                      int64_t *first, int64_t *last)
{
    if (strcmp(sh->cls, "union") != 0) {
        *first = *last = add_leaf(s, sh->cls, param, sh->file, t);
        return;
    }
    /* Two unit spheres at x = -0.5 and 0.5, joined, then moved as one. */
    hr_transform left, right;
    hr_transform_identity(&left);
    hr_transform_translate(&left, -0.5, 0, 0);
    hr_transform_identity(&right);
    hr_transform_translate(&right, 0.5, 0, 0);
    const int64_t a = add_leaf(s, "sphere", NAN, NULL, &left);
    const int64_t b = add_leaf(s, "sphere", NAN, NULL, &right);
    hr_param p[2];
    memset(p, 0, sizeof p);
    p[0].name = "a", p[0].type = HR_PARAM_OBJECT, p[0].object = a;
    p[1].name = "b", p[1].type = HR_PARAM_OBJECT, p[1].object = b;
    hr_object_desc d;
    memset(&d, 0, sizeof d);
    d.struct_size = sizeof d;
    d.shape = "union";
    d.params = p, d.param_count = 2;
    d.transform = t->m, d.inverse = t->inv;
    CHECK_MSG(hr_scene_add_object(s, &d, NULL) == HR_OK, "union: %s",
              hr_context_last_error(hr_scene_context(s)));
    *first = a, *last = b;
}

/* The shell's transform and parameter: enclosing the shape at a gap of at
 * least SHELL_GAP object units (see the header and CATALOG.md). */
static void shell_of(const spawn_shape *sh, const hr_transform *t, hr_transform *out,
                     double *param)
{
    *out = *t;
    *param = sh->param;
    switch (sh->shell) {
    case SHELL_TUBE: *param = sh->param + SHELL_GAP; break;
    case SHELL_LIFT: hr_transform_translate(out, 0, 0, SHELL_GAP); break;
    case SHELL_CYLINDER:
        /* z in [-gap, 1 + gap], radius 1 + gap: the gap is exactly 1e-5 on every face. */
        hr_transform_translate(out, 0, 0, -SHELL_GAP);
        hr_transform_scale(out, 1 + SHELL_GAP, 1 + SHELL_GAP, 1 + 2 * SHELL_GAP);
        break;
    default:
        hr_transform_translate(out, sh->centre.x, sh->centre.y, sh->centre.z);
        hr_transform_scale(out, 1 + sh->sigma, 1 + sh->sigma, 1 + sh->sigma);
        hr_transform_translate(out, -sh->centre.x, -sh->centre.y, -sh->centre.z);
        break;
    }
}

/* Transform k of the sweep: the extremes first, then random ones. */
static hr_transform transform_of(int k, ray_rng *rng)
{
    static const double fixed[5][6] = {
        /* sx, sy, sz, tx, ty, tz */
        {1, 1, 1, 0.3, -0.2, 0.1},
        {1e-4, 1e-4, 1e-4, 1e6, -7e5, 3e5},
        {1e4, 1e4, 1e4, 1e6, 1e6, -1e6},
        {1e-4, 1, 1e4, -1e6, 2e5, 1e6},
        {1e4, 1e-2, 1, 10, -20, 5},
    };
    double v[6];
    if (k < 5) {
        memcpy(v, fixed[k], sizeof v);
    } else {
        const double common = pow(10, rng_uniform(rng, -4, 4));
        for (int i = 0; i < 3; i++) {
            v[i] = rng_chance(rng, 0.5) ? common : pow(10, rng_uniform(rng, -4, 4));
            v[3 + i] = rng_uniform(rng, -1e6, 1e6);
        }
    }
    const hr_vec3 axis = rng_unit_vector(rng);
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, v[3], v[4], v[5]);
    hr_transform_rotate(&t, rng_uniform(rng, 0, 360), axis.x, axis.y, axis.z);
    hr_transform_scale(&t, v[0], v[1], v[2]);
    return t;
}

/* --- Spawned rays --------------------------------------------------------------- */

static double dot3(hr_vec3 a, hr_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static hr_vec3 scaled(hr_vec3 v, double s)
{
    hr_vec3 r = {v.x * s, v.y * s, v.z * s};
    return r;
}

static hr_vec3 plus(hr_vec3 a, hr_vec3 b)
{
    hr_vec3 r = {a.x + b.x, a.y + b.y, a.z + b.z};
    return r;
}

static hr_vec3 minus(hr_vec3 a, hr_vec3 b)
{
    return plus(a, scaled(b, -1));
}

/* A random direction on the side of the unit `side`; a quarter of them
 * grazing, 1e-3 .. 1e-7 of the normal part kept. */
static hr_vec3 hemisphere(ray_rng *rng, hr_vec3 side)
{
    hr_vec3 v = rng_unit_vector(rng);
    double along = dot3(v, side);
    if (along < 0) v = plus(v, scaled(side, -2 * along)), along = -along;
    if (rng_chance(rng, 0.25)) {
        const double keep = pow(10, rng_uniform(rng, -7, -3));
        v = plus(v, scaled(side, (keep - 1) * along));
    }
    return v;
}

typedef struct spawn_world {
    hr_scene *alone, *shelled;
    int64_t first, last;             /* the shape's object indices (a union's leaves) */
    int64_t shell_first, shell_last; /* the shell's, in `shelled` */
} spawn_world;

static int is_own(const spawn_world *w, const hr_hit *h)
{
    return h->object >= w->first && h->object <= w->last;
}

static int is_shell(const spawn_world *w, const hr_hit *h)
{
    return h->object >= w->shell_first && h->object <= w->shell_last;
}

typedef struct spawn_tally {
    long rays, self_hits, shell_missed, shell_unreachable, unreachable_points;
    long band_points, band_self_hits; /* hit points within the seam band, and their self-hits */
    double min_gap_ratio;
} spawn_tally;

/* One spawned ray, from `hit` toward `dir`: is its first hit in the scene
 * without the shell a hit of its own surface (see the header)? */
static int self_hit(const spawn_shape *sh, const spawn_world *w, const hr_hit *hit, hr_vec3 dir,
                    hr_intersection *list)
{
    const int outward = dot3(dir, hit->normal) > 0;
    const hr_vec3 side = outward ? hit->normal : scaled(hit->normal, -1);
    const hr_ray ray = {hr_hit_spawn_origin(hit, side), dir};
    CHECK_OK(hr_scene_all_hits(w->alone, &ray, 0, INFINITY, list));
    const hr_hit *first = list->count ? &list->hits[0] : NULL;
    if (first && !is_own(w, first)) return 1; /* nothing else is in the scene */
    if (sh->convexity == OPEN) return first != NULL;
    if (outward) return sh->convexity == CONVEX ? first != NULL : first && !first->entering;
    return !first || first->entering;
}

static void count_self_hit(const spawn_shape *sh, const spawn_world *w, const hr_hit *hit,
                           int in_band, hr_vec3 dir, hr_intersection *list, spawn_tally *tally)
{
    tally->rays++;
    if (!self_hit(sh, w, hit, dir, list)) return;
    if (in_band) {
        tally->band_self_hits++;
        return;
    }
    if (tally->self_hits++ < 3)
        printf("  %s: a ray spawned from (%.17g, %.17g, %.17g) along (%.17g, %.17g, %.17g) "
               "hits its own surface (error %.3g)\n",
               sh->label, hit->point.x, hit->point.y, hit->point.z, dir.x, dir.y, dir.z,
               hit->error);
}

/* Did an outward ray, traced in the scene with the shell, start inside the
 * shell? Its first crossing of the shell must leave it. A convex shape (or
 * a plane) must meet nothing before; a non-convex one may pass through its
 * own surface first (a ray leaving a saddle of the torus nearly tangentially
 * stays within the gap and comes back in without reaching the shell); that
 * its first own hit enters is self_hit's check. */
static int shell_found(const spawn_shape *sh, const spawn_world *w, const hr_intersection *list)
{
    for (int32_t i = 0; i < list->count; i++) {
        const hr_hit *h = &list->hits[i];
        if (is_shell(w, h)) return !h->entering;
        if (sh->convexity != NONCONVEX) return 0;
    }
    return 0;
}

/* The distance (object units) from an object-space point of the surface to
 * the nearest seam of the shape: an edge of the cube or square, a rim, the
 * cone's apex or base rim, a vertex of the icosahedron, the union's crease;
 * infinity for a shape without one. */
static double seam_distance(const spawn_shape *sh, hr_vec3 p)
{
    const double rho = sqrt(p.x * p.x + p.y * p.y);
    switch (sh->seams) {
    case SEAM_EDGES: {
        double m[3] = {1 - fabs(p.x), 1 - fabs(p.y), 1 - fabs(p.z)};
        if (sh->convexity == OPEN) return fmin(m[0], m[1]);
        /* On a face one of them is ~0; the edge is where a second one is. */
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2 - i; j++)
                if (fabs(m[j]) > fabs(m[j + 1])) {
                    const double tmp = m[j];
                    m[j] = m[j + 1], m[j + 1] = tmp;
                }
        return hypot(m[0], m[1]);
    }
    case SEAM_RIMS: {
        const double top = isnan(sh->param) ? 1 : sh->param;
        return fmin(hypot(rho - 1, p.z), hypot(rho - top, p.z - 1));
    }
    case SEAM_APEX: return fmin(hypot(rho, p.z - 1), hypot(rho - 1, p.z));
    case SEAM_VERTEX: {
        const double g = (1 + sqrt(5.0)) / 2, k = 1 / sqrt(1 + g * g);
        double best = INFINITY;
        for (int c = 0; c < 3; c++)
            for (int s = 0; s < 4; s++) {
                /* (0, +-1, +-g) k and its cyclic shifts */
                const double v[3] = {0, (s & 1 ? -1 : 1) * k, (s & 2 ? -g : g) * k};
                const double q[3] = {v[(3 - c) % 3], v[(4 - c) % 3], v[(5 - c) % 3]};
                best = fmin(best, sqrt((p.x - q[0]) * (p.x - q[0]) + (p.y - q[1]) * (p.y - q[1]) +
                                       (p.z - q[2]) * (p.z - q[2])));
            }
        return best;
    }
    case SEAM_CREASE: return hypot(p.x, hypot(p.y, p.z) - sqrt(0.75));
    default: return INFINITY;
    }
}

/* Rays spawned from one world-space hit. */
static void spawn_from(const spawn_shape *sh, const spawn_world *w, const hr_hit *hit,
                       const hr_transform *t, ray_rng *rng, hr_intersection *list,
                       spawn_tally *tally)
{
    /* The seam band: where the hit point is nearer a seam than its own
     * error and its spawn offset (mapped into object space by |M^-1|), the
     * offset, made along this surface's normal, may leave the origin on
     * the wrong side of the other surface of the seam: there either answer
     * is right (CATALOG.md, "seams"), and self-hits are counted apart. */
    const hr_vec3 p_obj = hr_transform_point(t->inv, hit->point);
    const hr_vec3 shifted = minus(hr_hit_spawn_origin(hit, hit->normal), hit->point);
    double to_object = 0;
    for (int r = 0; r < 3; r++)
        to_object = fmax(to_object, fabs(t->inv[4 * r]) + fabs(t->inv[4 * r + 1]) +
                                        fabs(t->inv[4 * r + 2]));
    const double reach = fmax(fabs(shifted.x), fmax(fabs(shifted.y), fabs(shifted.z)));
    const double band = 2 * to_object * (reach + hit->error);
    const int in_band = seam_distance(sh, p_obj) <= band;
    tally->band_points += in_band;
    /* The facing side: primary rays come from outside (or above a plane). */
    const hr_vec3 n = hit->normal;
    const hr_vec3 offset_point = hr_hit_spawn_origin(hit, n);
    const hr_vec3 moved = minus(offset_point, hit->point);
    const double offset = sqrt(dot3(moved, moved));
    /* The world gap to the shell along the (unit) normal, from the hit
     * point itself: the first hit of the shell on that line. */
    const hr_ray probe = {hit->point, n};
    CHECK_OK(hr_scene_all_hits(w->shelled, &probe, 0, INFINITY, list));
    double gap = 0;
    for (int32_t i = 0; i < list->count && gap == 0; i++)
        if (is_shell(w, &list->hits[i])) gap = list->hits[i].t;
    const double ratio = gap / offset;
    if (ratio < tally->min_gap_ratio) tally->min_gap_ratio = ratio;
    for (int i = 0; i < SPAWN_OUT; i++) {
        const hr_vec3 dir = hemisphere(rng, n);
        count_self_hit(sh, w, hit, in_band, dir, list, tally);
        const hr_ray out = {hr_hit_spawn_origin(hit, n), dir};
        CHECK_OK(hr_scene_all_hits(w->shelled, &out, 0, INFINITY, list));
        if (shell_found(sh, w, list)) continue;
        /* A gap under twice the offset (the offset is along the normal, the
         * probe's own t has rounding of the same size) may leave the
         * origin beyond the shell: counted, not failed. */
        if (ratio <= 2) {
            tally->shell_unreachable++;
        } else {
            tally->shell_missed++;
            if (tally->shell_missed <= 3)
                printf("  %s: a ray spawned from (%.17g, %.17g, %.17g) along (%.17g, %.17g, "
                       "%.17g) does not start inside the shell (gap/offset %.3g)\n",
                       sh->label, hit->point.x, hit->point.y, hit->point.z, dir.x, dir.y, dir.z,
                       ratio);
        }
    }
    /* Which bound sets the offset: the hit's error, or hr_hit_spawn_origin's
     * stand-in of 8 epsilon |p| for a hit that reports none (CATALOG.md,
     * "the shell"). */
    const int stand_in = !(hit->error > 0);
    const double bound = stand_in ? 8 * DBL_EPSILON *
                                        fmax(fabs(hit->point.x),
                                             fmax(fabs(hit->point.y), fabs(hit->point.z)))
                                  : hit->error;
    if (ratio <= 2 && tally->unreachable_points++ < 2)
        printf("  %s: at (%.6g, %.6g, %.6g) the gap %.3g is %.3g offsets (offset %.3g, from %s "
               "%.3g)\n",
               sh->label, hit->point.x, hit->point.y, hit->point.z, gap, ratio, offset,
               stand_in ? "the stand-in for a zero error" : "the hit error", bound);
    for (int i = 0; i < SPAWN_TO; i++) {
        const hr_vec3 q = {rng_uniform(rng, 2 * sh->box.lo.x, 2 * sh->box.hi.x),
                           rng_uniform(rng, 2 * sh->box.lo.y, 2 * sh->box.hi.y),
                           rng_uniform(rng, 2 * sh->box.lo.z - 0.5, 2 * sh->box.hi.z + 0.5)};
        const hr_vec3 dir = minus(hr_transform_point(t->m, q), hit->point);
        if (dir.x == 0 && dir.y == 0 && dir.z == 0) continue;
        count_self_hit(sh, w, hit, in_band, dir, list, tally);
    }
}

/* A point just inside a seam of the shape (object space), 10^-(6 .. 12)
 * from it, for a primary ray to aim at: the hit lands that close to an edge
 * (the cube's, the square's, cube.obj's), a rim (the cylinder's, the
 * tapered one's), the cone's apex or base rim, a vertex of the
 * icosahedron, or the crease of the union. */
static hr_vec3 seam_target(const spawn_shape *sh, ray_rng *rng)
{
    const double in = 1 - pow(10, -rng_uniform(rng, 6, 12));
    const double phi = rng_uniform(rng, 0, 6.283185307179586);
    const double sx = rng_chance(rng, 0.5) ? 1 : -1, sy = rng_chance(rng, 0.5) ? 1 : -1;
    const double along = rng_uniform(rng, -1, 1);
    switch (sh->seams) {
    case SEAM_EDGES: {
        if (sh->convexity == OPEN) return (hr_vec3){sx * in, along, 0};
        const int axis = (int)rng_uniform(rng, 0, 3) % 3;
        const hr_vec3 e[3] = {{along, sx * in, sy * in}, {sx * in, along, sy * in},
                              {sx * in, sy * in, along}};
        return e[axis];
    }
    case SEAM_RIMS: {
        const int cap = rng_chance(rng, 0.5);
        const double r = cap ? (isnan(sh->param) ? 1 : sh->param) : 1;
        return (hr_vec3){r * in * cos(phi), r * in * sin(phi), cap ? in : 1 - in};
    }
    case SEAM_APEX:
        if (rng_chance(rng, 0.5)) return (hr_vec3){0, 0, in};
        return (hr_vec3){in * cos(phi), in * sin(phi), 1 - in};
    case SEAM_VERTEX: {
        const double g = (1 + sqrt(5.0)) / 2, k = in / sqrt(1 + g * g);
        return (hr_vec3){0, sx * k, sy * g * k};
    }
    case SEAM_CREASE:
        return (hr_vec3){0, sqrt(0.75) * in * cos(phi), sqrt(0.75) * in * sin(phi)};
    default:
        return (hr_vec3){rng_uniform(rng, sh->box.lo.x, sh->box.hi.x),
                         rng_uniform(rng, sh->box.lo.y, sh->box.hi.y),
                         rng_uniform(rng, sh->box.lo.z, sh->box.hi.z)};
    }
}

static int spawn_world_make(hr_context *ctx, const spawn_shape *sh, const hr_transform *t,
                            spawn_world *w)
{
    memset(w, 0, sizeof *w);
    CHECK_OK(hr_scene_create(ctx, &w->alone));
    CHECK_OK(hr_scene_create(ctx, &w->shelled));
    int64_t first, last; /* the same indices as in `alone`: added in the same order */
    add_shape(w->alone, sh, sh->param, t, &w->first, &w->last);
    add_shape(w->shelled, sh, sh->param, t, &first, &last);
    hr_transform st;
    double param;
    shell_of(sh, t, &st, &param);
    if (sh->shell == SHELL_LIFT)
        w->shell_first = w->shell_last = add_leaf(w->shelled, "plane", NAN, NULL, &st);
    else
        add_shape(w->shelled, sh, param, &st, &w->shell_first, &w->shell_last);
    return w->first >= 0 && w->shell_first >= 0 && hr_scene_commit(w->alone) == HR_OK &&
           hr_scene_commit(w->shelled) == HR_OK;
}

static void spawn_world_free(spawn_world *w)
{
    hr_scene_destroy(w->alone);
    hr_scene_destroy(w->shelled);
}

static void run_spawn(const spawn_shape *sh, nc_result *out)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0x5e1f0000) + (uint64_t)(sh - shapes));
    hr_intersection list;
    hr_intersection_init(&list);
    spawn_tally tally = {0, 0, 0, 0, 0, 0, 0, INFINITY};
    int points = 0;
    for (int k = 0; k < TRANSFORMS; k++) {
        const hr_transform t = transform_of(k, &rng);
        spawn_world w;
        if (!spawn_world_make(ctx, sh, &t, &w)) {
            spawn_world_free(&w);
            continue;
        }
        int got = 0;
        for (int attempt = 0; attempt < 200 && got < HITS_PER_TRANSFORM; attempt++) {
            /* Primary rays built in object space (from 4 away, above the
             * plane for the flat shapes) and carried to the world. */
            hr_vec3 u = rng_unit_vector(&rng);
            if (sh->convexity == OPEN) u.z = fabs(u.z) + 0.2;
            const hr_vec3 from = plus(sh->centre, scaled(u, 4 / sqrt(dot3(u, u))));
            /* The first hit point anywhere, the second near a seam. */
            const spawn_shape anywhere = {.box = sh->box, .seams = SEAM_NONE};
            const hr_vec3 to = seam_target(got ? sh : &anywhere, &rng);
            const hr_vec3 wf = hr_transform_point(t.m, from);
            const hr_ray primary = {wf, minus(hr_transform_point(t.m, to), wf)};
            hr_hit hit;
            int32_t found = 0;
            CHECK_OK(hr_scene_first_hit(w.alone, &primary, 0, INFINITY, &hit, &found));
            if (!found) continue;
            got++;
            spawn_from(sh, &w, &hit, &t, &rng, &list, &tally);
        }
        points += got;
        spawn_world_free(&w);
    }
    out->samples = tally.rays;
    out->events = tally.self_hits + tally.shell_missed;
    snprintf(out->note, sizeof out->note,
             "%d hit points, %ld self-hits, %ld in the seam band from %ld points; shell missed "
             "%ld, unreachable %ld, min gap/offset %.3g",
             points, tally.self_hits, tally.band_self_hits, tally.band_points, tally.shell_missed,
             tally.shell_unreachable, tally.min_gap_ratio);
    CHECK_MSG(points >= TRANSFORMS * HITS_PER_TRANSFORM / 2, "%s: only %d hit points", sh->label,
              points);
    hr_intersection_release(&list);
    hr_context_destroy(ctx);
}

#define SPAWN_CASE(index)                                                                   \
    static void run_spawn_##index(nc_result *out) { run_spawn(&shapes[index], out); }
SPAWN_CASE(0)
SPAWN_CASE(1)
SPAWN_CASE(2)
SPAWN_CASE(3)
SPAWN_CASE(4)
SPAWN_CASE(5)
SPAWN_CASE(6)
SPAWN_CASE(7)
SPAWN_CASE(8)
SPAWN_CASE(9)
SPAWN_CASE(10)

/* --- Shadow acne ------------------------------------------------------------------ */

#define ACNE_SIZE 48
/* Lambert terms below this are left out: there the sign of s . m may differ
 * between the test's normal and shade's own, computed from the spawned
 * origin, by the offset over the light's distance (< 1e-12 here). */
#define LAMBERT_MARGIN 1e-9

typedef struct acne_scene {
    const char *cls;
    hr_vec3 light; /* object space */
    hr_vec3 eye, look;
} acne_scene;

/* The colour shade must give at a lit point: ambient (0.1 0.1 0.1 global
 * ambient times the material's 0.1) plus diffuse 0.8 times Lambert times
 * the light's 1: any shadow leaves the ambient part only. */
static void run_acne(const acne_scene *a, nc_result *out)
{
    static const double scales[4][4] = {{1, 0, 0, 0}, {1e-4, 0, 0, 0}, {1e4, 0, 0, 0},
                                        {1, 1e6, -1e6, 5e5}};
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    long darkened = 0, lit = 0;
    for (int k = 0; k < 4; k++) {
        hr_transform t;
        hr_transform_identity(&t);
        hr_transform_translate(&t, scales[k][1], scales[k][2], scales[k][3]);
        hr_transform_rotate(&t, 23, 1, 2, 3);
        hr_transform_scale(&t, scales[k][0], scales[k][0], scales[k][0]);
        hr_scene *s;
        CHECK_OK(hr_scene_create(ctx, &s));
        hr_material m;
        hr_material_default(&m);
        hr_object_desc d;
        memset(&d, 0, sizeof d);
        d.struct_size = sizeof d;
        d.shape = a->cls, d.material = &m, d.transform = t.m, d.inverse = t.inv;
        CHECK_OK(hr_scene_add_object(s, &d, NULL));
        hr_light light;
        memset(&light, 0, sizeof light);
        light.struct_size = sizeof light;
        light.position = hr_transform_point(t.m, a->light);
        light.color = (hr_color){1, 1, 1};
        CHECK_OK(hr_scene_add_light(s, &light));
        CHECK_OK(hr_scene_commit(s));
        const hr_vec3 eye = hr_transform_point(t.m, a->eye);
        for (int py = 0; py < ACNE_SIZE; py++)
            for (int px = 0; px < ACNE_SIZE; px++) {
                /* A grid of rays from the eye over the object's front. */
                const hr_vec3 target = {a->look.x + 2.4 * (px + 0.5) / ACNE_SIZE - 1.2,
                                        a->look.y + 2.4 * (py + 0.5) / ACNE_SIZE - 1.2, a->look.z};
                const hr_ray ray = {eye, minus(hr_transform_point(t.m, target), eye)};
                hr_hit h;
                int32_t found = 0;
                CHECK_OK(hr_scene_first_hit(s, &ray, 0, INFINITY, &h, &found));
                if (!found) continue;
                hr_vec3 nrm = h.normal;
                if (dot3(nrm, ray.dir) > 0) nrm = scaled(nrm, -1);
                const hr_vec3 to_light = minus(light.position, h.point);
                const double lambert = dot3(nrm, to_light) / sqrt(dot3(to_light, to_light));
                if (!(lambert > LAMBERT_MARGIN)) continue;
                hr_color c;
                CHECK_OK(hr_scene_shade(s, &ray, 0, &c));
                lit++;
                /* Unshadowed: 0.01 + 0.8 lambert; shadowed: 0.01. */
                if (!(c.r > 0.01 + 0.4 * lambert)) darkened++;
            }
        hr_scene_destroy(s);
    }
    out->samples = lit;
    out->events = darkened;
    snprintf(out->note, sizeof out->note, "%ld lit pixels over 4 scales, %ld darkened", lit,
             darkened);
    hr_context_destroy(ctx);
}

/* Plane z = 0 and light 1e-3 above it, 100 away: Lambert ~1e-5. */
static const acne_scene acne_plane = {"plane", {100, 0, 1e-3}, {0, -3, 2}, {0, 0, 0}};
/* Sphere with the light far along x: the terminator x = 0 is in view. */
static const acne_scene acne_sphere = {"sphere", {1e3, 0, 0}, {0, 0, 5}, {0, 0, 0}};
/* Cube top z = 1 and a light 1e-3 above its plane, 100 away. */
static const acne_scene acne_cube = {"cube", {100, 0, 1 + 1e-3}, {0, -2, 5}, {0, 0, 1}};

static void run_acne_plane(nc_result *out) { run_acne(&acne_plane, out); }
static void run_acne_sphere(nc_result *out) { run_acne(&acne_sphere, out); }
static void run_acne_cube(nc_result *out) { run_acne(&acne_cube, out); }

#define ZERO_SELF_HITS "zero self-hits; the shell found wherever gap > 2 offsets"

static const nc_case cases[] = {
    {"P01", "sphere", "self-intersection, 8 transforms", "re-projected point, error gamma(6)",
     ZERO_SELF_HITS, run_spawn_0},
    {"P02", "plane", "self-intersection, 8 transforms", "flat, error from t's roundings",
     ZERO_SELF_HITS, run_spawn_1},
    {"P03", "square", "self-intersection, 8 transforms", "as the plane, with edges",
     ZERO_SELF_HITS, run_spawn_2},
    {"P04", "cube", "self-intersection, 8 transforms", "edges and faces", ZERO_SELF_HITS,
     run_spawn_3},
    {"P05", "cylinder", "self-intersection, 8 transforms", "wall re-projection and disks",
     ZERO_SELF_HITS, run_spawn_4},
    {"P06", "cone", "self-intersection, 8 transforms", "apex", ZERO_SELF_HITS, run_spawn_5},
    {"P07", "taperedCylinder", "self-intersection, s = 0.5", "tapered wall", ZERO_SELF_HITS,
     run_spawn_6},
    {"P08", "torus", "self-intersection, tube 0.2", "non-convex, quartic", ZERO_SELF_HITS,
     run_spawn_7},
    {"P09", "icosahedron", "self-intersection", "triangles, barycentric points",
     ZERO_SELF_HITS, run_spawn_8},
    {"P10", "mesh cube.obj", "self-intersection", "an OBJ file's triangles", ZERO_SELF_HITS,
     run_spawn_9},
    {"P11", "union", "self-intersection, two spheres joined", "non-convex CSG crease",
     ZERO_SELF_HITS, run_spawn_10},
    {"A01", "plane", "light 1e-3 above the plane", "grazing light, tiny Lambert",
     "zero lit pixels darkened", run_acne_plane},
    {"A02", "sphere", "light at the terminator", "grazing at the terminator",
     "zero lit pixels darkened", run_acne_sphere},
    {"A03", "cube", "light 1e-3 above the top face", "grazing light on a face",
     "zero lit pixels darkened", run_acne_cube},
};

int main(void)
{
    return nc_run_table("spawn", cases, (int)(sizeof cases / sizeof cases[0]));
}
