/* Hill's generic torus: the ring (radius 1) lies in the xy-plane about the z
 * axis, the tube has radius `tube` (default 0.2, as in Hill's drawing). A
 * closed solid with one surface.
 *
 * Hit: every crossing along the ray, up to four, sorted, entering and
 * leaving alternately; the quartic and its solvers are in torus_quartic.c,
 * which also explains how far rays, thin tubes and tangents are handled. A
 * tangent the solver recognises is a zero-length visit: two crossings at one
 * t (in then out when the ray touches from outside, out then in when it
 * touches the surface from inside the tube).
 *
 * Point: origin + t dir, then re-projected onto the surface, as the sphere
 * and the cylinder wall do: c = (x, y, 0) / rho is the nearest point of the
 * ring circle, v = p - c = (k x, k y, z) with k = (rho - 1) / rho computed
 * from the compensated rho^2 - 1 (it cancels for thin tubes), and the point
 * is c + tube v / |v|. The outward normal is v / |v|.
 * Error of the re-projected point: c has relative error theta_3 (rho^2 two
 * roundings, sqrt one, the division one: it is a point within gamma(4) of
 * the unit circle, in the meridian plane of p); v / |v| is a unit vector of
 * that meridian plane to within gamma(7) in length (k, the products, |v|
 * and the division) and a rounding u off the plane; the final fma adds
 * u (1 + tube). The exact surface point c_exact + tube (v / |v|)_exact is
 * therefore within gamma(4) + tube (gamma(7) + u) + u (1 + tube) <=
 * gamma(9) (1 + tube) per coordinate; we report gamma(10) (1 + tube), the
 * extra gamma for evaluating the bound. As for the sphere, this bounds the
 * distance to the surface (what the host needs to offset new rays), not the
 * slip along it that the error of t causes.
 * A point on the z axis or on the ring circle itself cannot be a true hit
 * (the tube is at least 1e-6 off both); if a solver's rounding ever gives
 * one, a fixed ring direction or the radial direction stands in, so no
 * input can make a zero normal. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/shape_module.h>

#include <hitray/shape_kit.h>
#include "../common/shape_builtin.h"
#include "torus_quartic.h"

/* A tube of radius 1 closes the hole (a horn torus) and a larger one makes a
 * self-intersecting spindle torus, whose implicit equation no longer bounds
 * the solid swept by the tube: refused. 1e-6 is the thinnest tube the
 * tests check against the quad reference (test_shape_torus.c); thinner
 * ones are refused rather than left unchecked. */
#define TUBE_MIN 1e-6
#define TUBE_MAX 0.999

typedef struct torus_shape {
    const hr_host *host;
    torus_geometry geometry;
    int solver;
} torus_shape;

SHAPE_FMA_DISPATCH_VOID(torus_fill, (const void *shape, const hr_ray *ray, hr_hit *hit), (shape, ray, hit))
{
    const torus_shape *torus = shape;
    const double r = torus->geometry.r;
    const hr_vec3 p = shape_ray_at(ray, hit->t);
    const double rho = sqrt(p.x * p.x + p.y * p.y);
    double cx = 1.0, cy = 0.0, k = 0.0;
    if (rho > 0.0) {
        shape_sum rho2_minus_1 = shape_sum_start(-1.0);
        shape_sum_add_product(&rho2_minus_1, p.x, p.x);
        shape_sum_add_product(&rho2_minus_1, p.y, p.y);
        /* The ring direction from (x, y) rescaled, as the sphere does: below
         * 1e-154 their squares are subnormal and rho loses digits, which
         * would put c, and the point, off the ring circle. (k may keep the
         * plain rho: any unit n of the meridian plane puts c + tube n on
         * the surface.) */
        const hr_vec3 q = shape_vec3_rescaled(shape_vec3(p.x, p.y, 0.0));
        const double rho_q = sqrt(q.x * q.x + q.y * q.y);
        cx = q.x / rho_q;
        cy = q.y / rho_q;
        k = shape_sum_value(rho2_minus_1) / ((rho + 1.0) * rho);
    }
    /* v rescaled before its length is taken: near the ring circle it is
     * tiny, and subnormal squares gave a normal longer than 1 in z, so a
     * thin tube's point left the tube. */
    hr_vec3 v = shape_vec3_rescaled(rho > 0.0 ? shape_vec3(p.x * k, p.y * k, p.z)
                                              : shape_vec3(p.x - 1.0, p.y, p.z));
    double length = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(length > 0.0)) {
        v = shape_vec3(cx, cy, 0.0);
        length = 1.0;
    }
    const hr_vec3 n = shape_vec3(v.x / length, v.y / length, v.z / length);
    hit->point = shape_vec3(fma(r, n.x, cx), fma(r, n.y, cy), r * n.z);
    hit->normal = n;
    hit->error = shape_gamma(10) * (1.0 + r);
}

static hr_status torus_trace(const hr_hit_args *args, int32_t mode)
{
    const torus_shape *torus = args->shape;
    torus_roots roots;
    const int count = torus_solve(&torus->geometry, torus->solver, &args->ray, args->tmin,
                                  args->tmax, mode != HR_TRACE_ALL, &roots);
    shape_crossing crossings[4];
    for (int i = 0; i < count; i++) {
        crossings[i].t = roots.t[i];
        crossings[i].surface = 0;
        crossings[i].entering = roots.entering[i];
    }
    return shape_report(args, mode, crossings, count, torus_fill);
}

SHAPE_DEFINE_HIT_MODES(torus, torus_trace)

static void torus_bounds(const void *shape, hr_bounds *out)
{
    const double r = ((const torus_shape *)shape)->geometry.r;
    out->lo = shape_vec3(-1.0 - r, -1.0 - r, -r);
    out->hi = shape_vec3(1.0 + r, 1.0 + r, r);
}

static hr_status refuse(const hr_create_args *args, const char *message, const char *value)
{
    if (args->error && args->error_size) snprintf(args->error, args->error_size, message, value);
    return HR_ERROR_PARAMETER;
}

/* The host has checked the range of `tube` already; the module still
 * refuses what it cannot draw, in case a host (or a test) passes something
 * else. */
static hr_status torus_create(const hr_create_args *args, void **out_shape)
{
    const hr_param *tube_param = shape_param(args, "tube"), *solver_param = shape_param(args, "solver");
    const double tube = tube_param ? tube_param->number : 0.2;
    const char *solver_name = solver_param && solver_param->string ? solver_param->string : "";
    if (!(tube >= TUBE_MIN && tube <= TUBE_MAX)) {
        char value[40];
        snprintf(value, sizeof value, "%g", tube);
        return refuse(args,
                      "parameter 'tube' = %s must be in [1e-06, 0.999]: a tube of radius 1 "
                      "or more would close the hole (horn and spindle tori are not drawn)",
                      value);
    }
    int solver = TORUS_SOLVER_DEFAULT;
    if (solver_name[0]) {
        solver = torus_solver_find(solver_name);
        if (solver < 0)
            return refuse(args,
                          "parameter 'solver' = '%s' is not a solver: use 'ferrari', "
                          "'ferrari-newton' or 'bracketing' (the default)",
                          solver_name);
    }
    torus_shape *shape = args->host->alloc(sizeof *shape);
    if (!shape) return HR_ERROR_OUT_OF_MEMORY;
    shape->host = args->host;
    torus_geometry_make(tube, &shape->geometry);
    shape->solver = solver;
    *out_shape = shape;
    return HR_OK;
}

static void torus_destroy(void *shape)
{
    if (!shape) return;
    const hr_host *host = ((torus_shape *)shape)->host;
    host->free(shape);
}

/* What each solver costs and how accurate it is, measured, is in
 * bench/results/RESULTS.md ("Torus root solvers"). */
static const hr_param_spec torus_params[] = {
    {"tube", HR_PARAM_NUMBER, 0, 0.2, TUBE_MIN, TUBE_MAX,
     "tube radius (the ring radius is 1); below 1: a tube of 1 or more would close the hole", 0},
    {"solver", HR_PARAM_STRING, 0, 0.0, 0.0, 0.0,
     "root solver: 'bracketing' (default; derivative bracketing) finds every root and tangent; "
     "'ferrari-newton' (closed form + Newton) is as accurate where it finds the roots but may "
     "invent or lose a close pair; 'ferrari' (closed form) errs most near tangents; costs and "
     "errors measured: bench/results/RESULTS.md", 0},
};

/* (u, v): Hill's two angles as fractions of a turn: u about the z axis
 * from +x (around the ring), v about the tube's own centre circle, 0 on
 * the outer equator, 1/4 on top (+z), in [0, 1). */
static int32_t torus_uv(const void *shape, const hr_hit *hit, double uv[2])
{
    (void)shape;
    SHAPE_UV_PROBE(hit, uv);
    const hr_vec3 p = hit->point;
    uv[0] = shape_turn(p.y, p.x);
    uv[1] = shape_turn(p.z, hypot(p.x, p.y) - 1.0);
    return 1;
}

static const char *const torus_surface_names[1] = {"torus"};

SHAPE_CLASS(torus, .flags = HR_SHAPE_CLOSED | HR_SHAPE_SDL_BARE, .name = "torus",
            .help = "ring radius 1 in the xy-plane about z, tube radius `tube` (default 0.2)",
            SHAPE_PARAMS(torus_params), .surface_count = 1, .surface_names = torus_surface_names,
            .create = torus_create, .destroy = torus_destroy, .surface_uv = torus_uv);
SHAPE_MODULE_OF(torus, "Hill's generic torus: ring radius 1 about z, tube radius a parameter",
                SHAPE_BUILTIN_METADATA);
