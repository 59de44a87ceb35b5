/* Flat surfaces, edges and seams (cases S01-S10 of CATALOG.md): rays
 * parallel and nearly parallel to the plane, the square's edge, the cube's
 * edges and corners, the cylinder's and cone's rims, a mesh's shared edges
 * and a CSG crease, swept across in steps of 1e-7, and signed zeros.
 *
 * What a sweep requires. Every ray of the sweep passes through the solid
 * (or, for the open square, its hit or miss is decided by the exact
 * geometry outside a band of its own rounding): no hole (a ray with too few
 * hits) and no double hit (more hits than the solid has crossings: an edge
 * entered twice), entering and leaving alternating (the harness checks this
 * on every call), and the surface that owns the entry switching exactly
 * once as the ray crosses the seam, so each crossing of the seam is counted
 * once. A sweep counts its bad rays as events: none is allowed.
 * The modules are loaded by the test host (module_harness.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"
#include "numerics_cases.h"
#include "numerics_family.h"
#include "quad_reference.h"

#define STEP 1e-7
#define HALF_STEPS 60

static hr_vec3 v3(double x, double y, double z)
{
    return harness_vec(x, y, z);
}

static hr_vec3 along(hr_vec3 p, hr_vec3 d, double s)
{
    return v3(p.x + s * d.x, p.y + s * d.y, p.z + s * d.z);
}

/* One sweep: rays origin + i STEP offset along dir, i = -HALF_STEPS ..
 * HALF_STEPS. Each must have exactly `count` hits; the entering surface of
 * the first hit must be `below` for i < 0 and `above` for i > 0 (either at
 * i = 0, the exact tie) and change only once. Returns the bad rays. */
static long sweep(const harness_shape *s, hr_vec3 origin, hr_vec3 offset, hr_vec3 dir, int count,
                  int below, int above, const char *what)
{
    long bad = 0;
    int switches = 0, last = -1;
    for (int i = -HALF_STEPS; i <= HALF_STEPS; i++) {
        const hr_vec3 o = along(origin, offset, i * STEP);
        hr_hit h[HARNESS_MAX_HITS];
        const int n = harness_hits(s, harness_ray(o.x, o.y, o.z, dir.x, dir.y, dir.z), h);
        int ok = n == count && h[0].entering;
        if (ok && i < 0) ok = h[0].surface == below;
        if (ok && i > 0) ok = h[0].surface == above;
        if (ok) {
            if (last >= 0 && h[0].surface != last) switches++;
            last = h[0].surface;
        }
        if (!ok) {
            bad++;
            CHECK_MSG(0, "%s: step %d: %d hits, first surface %d entering %d", what, i, n,
                      n ? (int)h[0].surface : -1, n ? (int)h[0].entering : -1);
        }
    }
    if (below != above && switches != 1) {
        bad++;
        CHECK_MSG(0, "%s: the entry switched surfaces %d times", what, switches);
    }
    return bad;
}

static int open_shape(harness_shape *s, const char *module, const char *cls, double param)
{
    if (harness_open(s, module, cls, param)) return 1;
    harness_close(s);
    return 0;
}

/* S01: parallel to the plane, d.z = +0 or -0, origins above, on (+0, -0)
 * and below it: no crossing, decided without dividing: no hit, no NaN. */
static void s01(nc_result *out)
{
    harness_shape s;
    if (!open_shape(&s, "plane", "plane", NAN)) return;
    static const double oz[] = {1, 1e-300, 0.0, -0.0, -1e-300, -1};
    for (size_t k = 0; k < sizeof oz / sizeof oz[0]; k++)
        for (int sign = 0; sign < 2; sign++) {
            hr_hit h[HARNESS_MAX_HITS];
            const int n = harness_trace(&s, harness_ray(0.5, -2, oz[k], 1, 3, sign ? -0.0 : 0.0),
                                        -INFINITY, INFINITY, HARNESS_ALL, h);
            nc_note(out, n == 0 ? 0 : INFINITY);
        }
    harness_close(&s);
}

/* S02: nearly parallel, d.z = +-10^-k (k = 1 .. 320, into the subnormals)
 * from heights +-1, +-1e-300: t = fl(-o.z / d.z) is one correctly rounded
 * division, within u |t| of the exact quotient (computed in quad); where
 * the quotient overflows double the hit must be dropped, not passed on as
 * infinity. */
static void s02(nc_result *out)
{
    harness_shape s;
    if (!open_shape(&s, "plane", "plane", NAN)) return;
    static const double oz[] = {1, -1, 1e-300, -1e-300};
    for (int k = 1; k <= 320; k++)
        for (size_t j = 0; j < sizeof oz / sizeof oz[0]; j++)
            for (int sign = -1; sign <= 1; sign += 2) {
                const double dz = sign * pow(10, -k);
                if (dz == 0) continue;
                const hr_ray r = harness_ray(0.25, 0.5, oz[j], 1, -1, dz);
                const quad exact = -(quad)oz[j] / (quad)dz;
                hr_hit h[HARNESS_MAX_HITS];
                const int n = harness_trace(&s, r, -INFINITY, INFINITY, HARNESS_ALL, h);
                const double e = ref_to_double(exact);
                if (!isfinite(e) || !isfinite(0.25 + e) || !isfinite(e * -1)) {
                    nc_note(out, n == 0 ? 0 : INFINITY);
                    continue;
                }
                if (n != 1) {
                    /* Only a point that overflows may be dropped: |t| near DBL_MAX. */
                    nc_note(out, fabs(e) > 1e300 && n == 0 ? 0 : INFINITY);
                    continue;
                }
                const double err = ref_to_double(h[0].t - exact);
                nc_note(out, fabs(err) / (NC_U * fabs(e)));
            }
    harness_close(&s);
}

/* S03: the square's edge x = 1 and its corner, swept: o = (x0 + i 1e-7,
 * 0.3, 1) + t (0.5, 0.25, -1) lands at x = x0 + 0.5 + i 1e-7. The hit must
 * be there exactly when the landing point (computed in quad) is inside,
 * outside the band of the point's own rounding (the hit error,
 * shape_ray_point_error: a wrong answer scores distance / band). */
static void s03(nc_result *out)
{
    harness_shape s;
    if (!open_shape(&s, "square", "square", NAN)) return;
    for (int corner = 0; corner < 2; corner++)
        for (int i = -HALF_STEPS; i <= HALF_STEPS; i++) {
            const double c = i * STEP;
            const hr_ray r = corner ? harness_ray(0.5 + c, 0.75 + c, 1, 0.5, 0.25, -1)
                                    : harness_ray(0.5 + c, 0.3, 1, 0.5, 0.25, -1);
            const quad t = (quad)r.origin.z / 1;
            const quad x = (quad)r.origin.x + t * r.dir.x, y = (quad)r.origin.y + t * r.dir.y;
            const quad ax = x < 0 ? -x : x, ay = y < 0 ? -y : y;
            const int inside = ax <= 1 && ay <= 1;
            const double distance = ref_to_double(ax > ay ? ax - 1 : ay - 1);
            hr_hit h[HARNESS_MAX_HITS];
            const int n = harness_hits(&s, r, h);
            const double band = nc_gamma(4) * 2; /* gamma(4) (|o| + |t d|), both about 1 */
            if (n == inside) nc_note(out, 0);
            else nc_note(out, fabs(distance) / band);
        }
    harness_close(&s);
}

/* Cube faces: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z. */

/* S04: the cube's edges and a corner. Lines y = x + c (z = 0.3) coming
 * down the diagonal enter through +y for c > 0 and +x for c < 0; lines
 * through the corner region (1, 1, 1) - (c, 2c, 0) along (-1, -1, -1) and
 * lines down the edge x = y = 1 along (-1, -1, -0.5): every one is a
 * chord of the cube, 2 hits, the entry owned by one face at a time. */
static void s04(nc_result *out)
{
    harness_shape s;
    if (!open_shape(&s, "cube", "cube", NAN)) return;
    long bad = 0;
    bad += sweep(&s, v3(2, 2, 0.3), v3(0, 1, 0), v3(-1, -1, 0), 2, 0, 2, "cube edge +x/+y");
    bad += sweep(&s, v3(2, 2, 0.3), v3(0, 1, 0), v3(-0.7, -0.7, 0), 2, 0, 2, "cube edge, |d| 0.99");
    bad += sweep(&s, v3(-2, 0.3, 2), v3(0, 0, 1), v3(1, 0, -1), 2, 1, 4, "cube edge -x/+z");
    bad += sweep(&s, v3(2, 2, 2), v3(-1, 1, 0), v3(-1, -1, -1), 2, 0, 2, "cube corner x/y");
    bad += sweep(&s, v3(3, 3, 1.5), v3(0, 1, 0), v3(-1, -1, -0.5), 2, 0, 2, "cube edge, oblique");
    out->events += bad;
    out->samples += 5 * (2 * HALF_STEPS + 1);
    harness_close(&s);
}

/* S05: grazing a face from within its plane: o = (-2, 1 + c, 0.3) + t (1,
 * 0, 0). The faces are closed, so for c <= 0 the ray is inside the slab
 * |y| <= 1 and crosses the cube (enter -x at t = 1, leave +x at t = 3),
 * for c > 0 it misses: the count changes exactly at c = 0. With d.y = +0
 * and -0, and o.y exactly 1. */
static void s05(nc_result *out)
{
    harness_shape s;
    if (!open_shape(&s, "cube", "cube", NAN)) return;
    for (int sign = 0; sign < 2; sign++)
        for (int i = -HALF_STEPS; i <= HALF_STEPS; i++) {
            const double c = i * STEP;
            hr_hit h[HARNESS_MAX_HITS];
            const int n = harness_hits(&s, harness_ray(-2, 1 + c, 0.3, 1, sign ? -0.0 : 0.0, 0), h);
            const int ok = c <= 0 ? n == 2 && h[0].t == 1 && h[1].t == 3 && h[0].surface == 1 &&
                                        h[1].surface == 0
                                  : n == 0;
            CHECK_MSG(ok, "face graze c = %g: %d hits", c, n);
            out->samples++;
            out->events += !ok;
        }
    harness_close(&s);
}

/* S06: signed zeros. Each ray and its copies with zero components of the
 * origin and direction flipped to -0 give bit-identical hits: cube, plane,
 * square. */
static void s06(nc_result *out)
{
    static const struct {
        const char *cls;
        hr_ray ray;
    } rays[] = {
        {"cube", {{0, 0, 5}, {0, 0, -1}}},
        {"cube", {{1, 0, 5}, {0, 0, -1}}},
        {"cube", {{-3, 0, 0}, {1, 0, 0}}},
        {"plane", {{0, 0, 5}, {0, 0, -1}}},
        {"plane", {{0.5, 0, -1}, {0, 0, 2}}},
        {"square", {{1, 0, 1}, {0, 0, -1}}},
        {"square", {{0, -1, -1}, {0, 0, 1}}},
    };
    for (size_t k = 0; k < sizeof rays / sizeof rays[0]; k++) {
        harness_shape s;
        if (!open_shape(&s, rays[k].cls, rays[k].cls, NAN)) continue;
        nf_signed_zeros(&s, rays[k].ray, out);
        harness_close(&s);
    }
}

/* Tapered-cylinder surfaces: 0 wall, 1 base, 2 cap. */

/* The rim of radius `r` at height z, at azimuth phi, swept vertically by a
 * ray coming down inward at slope `slope`: below the rim it meets the wall
 * (or the base, for the base rim), above it the cap (or the wall). */
static long rim_sweeps(const harness_shape *s, double r, double z, double run, int below,
                       int above, hr_vec3 rise, const char *what)
{
    long bad = 0;
    for (int k = 0; k < 24; k++) {
        const double phi = k * (6.283185307179586 / 24) + 0.1;
        const hr_vec3 radial = v3(cos(phi), sin(phi), 0);
        const hr_vec3 dir = v3(-radial.x * run + rise.x, -radial.y * run, rise.z);
        const hr_vec3 rim = v3(r * radial.x, r * radial.y, z);
        bad += sweep(s, along(rim, dir, -1), v3(0, 0, 1), dir, 2, below, above, what);
    }
    return bad;
}

/* S07: the cylinder's cap and base rims at 24 azimuths: a ray down and in
 * at 45 degrees meets the wall below the cap rim and the cap above it; a
 * ray up and in meets the base below the base rim and the wall above it. */
static void s07(nc_result *out)
{
    harness_shape s;
    if (!open_shape(&s, "cylinder", "cylinder", NAN)) return;
    long bad = rim_sweeps(&s, 1, 1, 1, 0, 2, v3(0, 0, -1), "cylinder cap rim");
    bad += rim_sweeps(&s, 1, 0, 1, 1, 0, v3(0, 0, 1), "cylinder base rim");
    out->events += bad;
    out->samples += 48 * (2 * HALF_STEPS + 1);
    harness_close(&s);
}

/* S08: the tapered cylinder's (s = 0.5) cap rim, and the cone's base rim,
 * where the wall is slanted: the cone's ray must close in on the wall
 * faster than it does (run 2, rise 1), or it would stay outside. */
static void s08(nc_result *out)
{
    harness_shape tapered, cone;
    if (!open_shape(&tapered, "cylinder", "taperedCylinder", 0.5)) return;
    if (!open_shape(&cone, "cylinder", "cone", NAN)) {
        harness_close(&tapered);
        return;
    }
    long bad = rim_sweeps(&tapered, 0.5, 1, 1, 0, 2, v3(0, 0, -1), "tapered cap rim");
    bad += rim_sweeps(&cone, 1, 0, 2, 1, 0, v3(0, 0, 1), "cone base rim");
    out->events += bad;
    out->samples += 48 * (2 * HALF_STEPS + 1);
    harness_close(&tapered);
    harness_close(&cone);
}

/* S09: meshes. The icosahedron's edge from (0, 1, g) to (0, -1, g) (g the
 * golden ratio, then scaled onto the unit sphere) and its vertex (0, 1, g),
 * rays along -m (m the edge midpoint or the vertex) swept across, from 2
 * and (the edge) from 1e6 away; and the
 * diagonal shared by the two triangles of a face of cube.obj. Triangles
 * meeting at an edge must hand over without a hole or a double hit
 * (mesh_triangle.h's watertight test); the mesh is one surface, so only
 * the count and the alternation are checked. */
static void s09(nc_result *out)
{
    harness_shape ico, cube;
    if (!open_shape(&ico, "mesh", "icosahedron", NAN)) return;
    char path[512];
    if (!mesh_open_file(&cube, mesh_data_path("cube.obj", path, sizeof path))) {
        harness_close(&cube);
        harness_close(&ico);
        return;
    }
    const double g = (1 + sqrt(5.0)) / 2, scale = 1 / sqrt(1 + g * g);
    const hr_vec3 mid = v3(0, 0, g * scale), vertex = v3(0, scale, g * scale);
    long bad = 0;
    bad += sweep(&ico, along(mid, mid, 2), v3(1, 0, 0), v3(-mid.x, -mid.y, -mid.z), 2, 0, 0,
                 "icosahedron edge");
    bad += sweep(&ico, along(mid, mid, 1e6), v3(1, 0, 0), v3(-mid.x, -mid.y, -mid.z), 2, 0, 0,
                 "icosahedron edge from 1e6");
    bad += sweep(&ico, along(vertex, vertex, 2), v3(1, 0.3, 0), v3(-vertex.x, -vertex.y, -vertex.z),
                 2, 0, 0, "icosahedron vertex");
    bad += sweep(&ico, along(vertex, vertex, 2), v3(0, 0.6, -1),
                 v3(-vertex.x, -vertex.y, -vertex.z),
                 2, 0, 0, "icosahedron vertex, other way");
    /* cube.obj's +z face is split along a diagonal: sweep across it. */
    bad += sweep(&cube, v3(0.2, 0.2, 3), v3(1, -1, 0), v3(0.05, -0.1, -1), 2, 0, 0,
                 "cube.obj face diagonal");
    bad += sweep(&cube, v3(2, 2, 2), v3(-1, 1, 0), v3(-1, -1, -1), 2, 0, 0, "cube.obj corner");
    out->events += bad;
    out->samples += 6 * (2 * HALF_STEPS + 1);
    harness_close(&cube);
    harness_close(&ico);
}

/* S10: a CSG crease. The union of two unit spheres at x = -0.5 and 0.5
 * meets itself on the circle x = 0, y^2 + z^2 = 0.75; lines x = c, z = 0
 * (or z = 0.4) along -y cross it: always one solid chord (enter, leave), the
 * entry owned by the sphere on the side of c, switching once. The host's
 * trace_child (module_harness.c) names each leaf's hits by its object
 * number: 1 for the left sphere, 2 for the right. */
static void s10(nc_result *out)
{
    harness_shape sphere;
    if (!open_shape(&sphere, "sphere", "sphere", NAN)) return;
    harness_module csg;
    if (!harness_load("csg", &csg)) {
        harness_close(&sphere);
        return;
    }
    const hr_shape_class *cls = harness_find_class(&csg, "union");
    const harness_child left = {&sphere, {-0.5, 0, 0}, 1, 1}, right = {&sphere, {0.5, 0, 0}, 1, 2};
    const harness_child *children[2] = {&left, &right};
    static const char *const names[2] = {"a", "b"};
    harness_shape u;
    memset(&u, 0, sizeof u);
    u.module = csg;
    u.cls = cls;
    char error[256];
    long bad = 1;
    if (cls && harness_create_composite(cls, names, children, 2, &u.shape, error, sizeof error) ==
                   HR_OK) {
        bad = 0;
        for (int zi = 0; zi < 2; zi++)
            for (int i = -HALF_STEPS; i <= HALF_STEPS; i++) {
                /* The composite's own hit call: its hits name their leaves,
                 * which harness_trace (made for leaf shapes) would refuse. */
                const double c = i * STEP;
                hr_intersection list = {calloc(HR_MIN_HIT_CAPACITY, sizeof(hr_hit)), 0,
                                        HR_MIN_HIT_CAPACITY};
                hr_hit_args args;
                memset(&args, 0, sizeof args);
                args.shape = u.shape;
                args.ray = harness_ray(c, 3, zi * 0.4, 0, -1, 0);
                args.tmin = 0, args.tmax = INFINITY, args.out = &list;
                CHECK_OK(u.cls->hit(&args));
                const hr_hit *h = list.hits;
                const int n = list.count;
                int ok = n == 2 && h[0].entering && !h[1].entering;
                if (ok && i != 0) ok = h[0].object == (c < 0 ? 1 : 2) && h[1].object == h[0].object;
                free(list.hits);
                if (!ok) {
                    bad++;
                    CHECK_MSG(0, "union crease c = %g z = %g: %d hits", c, zi * 0.4, n);
                }
            }
        u.cls->destroy(u.shape);
    } else {
        CHECK_MSG(0, "union: %s", error);
    }
    out->events += bad;
    out->samples += 2 * (2 * HALF_STEPS + 1);
    harness_unload(&csg);
    harness_close(&sphere);
}

#define NO_HOLES "no hole, no double hit, one switch of the entering surface"

static const nc_case cases[] = {
    {"S01", "plane", "d.z = +-0 from above, on and below", "0/0 or x/0 if divided",
     "no hit, never NaN", s01},
    {"S02", "plane", "d.z = +-1e-1 .. 1e-320", "t overflows, subnormal d",
     "|t - t_ref| <= u |t|; overflowing hits dropped", s02},
    {"S03", "square", "edge x = 1 and corner swept by 1e-7", "inside test on a rounded point",
     "hit iff inside, outside gamma(4) (|o| + |t d|)", s03},
    {"S04", "cube", "edges and a corner swept by 1e-7", "two slabs end at the same t", NO_HOLES,
     s04},
    {"S05", "cube", "in the plane of a face, y = 1 + c, d.y = +-0", "closed faces, zero d",
     "2 hits for c <= 0, none above", s05},
    {"S06", "cube/plane/square", "signed zeros in origin and direction", "-0 / +0 branches",
     "bit-identical hits", s06},
    {"S07", "cylinder", "cap and base rims at 24 azimuths, 1e-7 steps", "disk/wall seam",
     NO_HOLES, s07},
    {"S08", "taperedCylinder", "s = 0.5 cap rim, cone base rim", "slanted wall at the seam",
     NO_HOLES, s08},
    {"S09", "mesh", "icosahedron edge and vertex, cube.obj face diagonal", "shared triangle edges",
     "2 hits every step", s09},
    {"S10", "union", "CSG crease of two spheres", "two leaves' surfaces meet", NO_HOLES, s10},
};

int main(void)
{
    return nc_run_table("sweeps", cases, (int)(sizeof cases / sizeof cases[0]));
}
