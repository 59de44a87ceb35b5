/* The mesh module on small meshes: a cube of 12 triangles (OBJ) agrees with
 * the cube module on thousands of random rays; the same cube in Hill's
 * .3vn format; rays swept across shared edges in 1e-7 steps and aimed
 * through vertices hit exactly once per crossing; exact edge-function
 * signs; interpolated normals from OBJ and .3vn files; the regular solids
 * against long-double clipping (t, points within their error bounds, no
 * self-hits from spawned rays); more hits than the host's free space;
 * meshes that defeat the SAH; closed meshes thinner than rounding; the
 * BVH against every triangle on triangle soups from 2^-70 to past float's
 * range, over intervals from -inf; the two-triangle filter in front of the
 * triangle test against the test itself on millions of pairs. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../shapes/mesh/mesh_triangle.h"
#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"
#include "quad_reference.h"
#include "random_rays.h"

static harness_shape cube_module;
static harness_shape cube_mesh;

static hr_vec3 unit(hr_vec3 v)
{
    double n = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return harness_vec(v.x / n, v.y / n, v.z / n);
}

static double dot(hr_vec3 a, hr_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

/* Whether the cube module's hit lies within `margin` of an edge of the cube
 * (two coordinates at +-1): there the cube's spans and the mesh's
 * perturbation may rightly disagree (a zero-length visit, or which face). */
static int near_cube_edge(const hr_hit *h, double margin)
{
    int at_face = (fabs(fabs(h->point.x) - 1) <= margin) + (fabs(fabs(h->point.y) - 1) <= margin) +
                  (fabs(fabs(h->point.z) - 1) <= margin);
    return at_face >= 2;
}

/* Thousands of random rays (random_rays.h: zero and negative-zero
 * direction components, origins snapped to face planes, random intervals):
 * the same hits from the 12-triangle cube as from the cube module, away
 * from edges. Tolerances: t within 1e-12 (|t| + 1), since both compute t
 * with a handful of roundings from the same doubles (a few 1e-16 relative),
 * and the rays are at least 1e-9 from any edge, so no grazing amplifies
 * them; points within both hits' error bounds plus 4 ulps; unit normals
 * equal within 1e-12 (both are exact axis vectors up to rounding). */
static void test_cube_agrees(void)
{
    ray_rng rng;
    rng_seed(&rng, 12);
    hr_bounds b = {{-1, -1, -1}, {1, 1, 1}};
    int compared = 0, hit_rays = 0;
    for (int i = 0; i < 20000; i++) {
        hr_ray ray = random_ray_near(&rng, &b);
        double tmin, tmax;
        random_interval(&rng, &tmin, &tmax);
        hr_hit want[HARNESS_MAX_HITS], got[HARNESS_MAX_HITS];
        /* The whole line first: a ray that passes near an edge anywhere
         * is skipped, in any interval. */
        int all = harness_trace(&cube_module, ray, -INFINITY, INFINITY, HARNESS_ALL, want);
        int skip = 0;
        for (int k = 0; k < all; k++) skip |= near_cube_edge(&want[k], 1e-9);
        if (all == 2 && fabs(want[1].t - want[0].t) < 1e-9) skip = 1;
        if (skip) continue;
        int n = harness_trace(&cube_module, ray, tmin, tmax, HARNESS_ALL, want);
        int m = harness_trace(&cube_mesh, ray, tmin, tmax, HARNESS_ALL, got);
        compared++;
        hit_rays += n > 0;
        CHECK_MSG(n == m, "ray %d: cube %d hits, mesh %d (o %.17g %.17g %.17g d %g %g %g, t in (%g, %g), mesh t %.17g)", i, n, m,
                  ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z, tmin, tmax, m ? got[0].t : 0.0);
        if (n != m) continue;
        for (int k = 0; k < n; k++) {
            CHECK_MSG(fabs(got[k].t - want[k].t) <= 1e-12 * (fabs(want[k].t) + 1),
                      "ray %d hit %d: t %.17g, cube %.17g", i, k, got[k].t, want[k].t);
            CHECK(got[k].entering == want[k].entering);
            CHECK(got[k].surface == 0);
            hr_vec3 a = unit(got[k].normal), c = unit(want[k].normal);
            CHECK_MSG(fabs(a.x - c.x) <= 1e-12 && fabs(a.y - c.y) <= 1e-12 &&
                          fabs(a.z - c.z) <= 1e-12,
                      "ray %d hit %d: normal (%g %g %g), cube (%g %g %g)", i, k, a.x, a.y, a.z, c.x,
                      c.y, c.z);
            const double tol = got[k].error + want[k].error + 4 * DBL_EPSILON * 2;
            CHECK_MSG(fabs(got[k].point.x - want[k].point.x) <= tol &&
                          fabs(got[k].point.y - want[k].point.y) <= tol &&
                          fabs(got[k].point.z - want[k].point.z) <= tol,
                      "ray %d hit %d: point off by more than %g", i, k, tol);
        }
        /* The fast paths agree with the full list. */
        hr_hit first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
        int f = harness_trace(&cube_mesh, ray, tmin, tmax, HARNESS_FIRST, first);
        int a = harness_trace(&cube_mesh, ray, tmin, tmax, HARNESS_ANY, any);
        CHECK(f == (m > 0) && a == (m > 0));
        if (f && m) CHECK(first[0].t == got[0].t && first[0].entering == got[0].entering);
        if (a && m) CHECK(any[0].t == got[0].t || (m > 1 && any[0].t == got[1].t));
        /* An any-hit answer skips the normals (only t is meaningful), but
         * its fields stay valid: the point of the crossing it names within
         * its bound, and a normal facing the ray as its entering flag says. */
        for (int k = 0; a && k < m && k < 2; k++) {
            if (any[0].t != got[k].t) continue;
            CHECK(any[0].entering == got[k].entering);
            CHECK(any[0].point.x == got[k].point.x && any[0].point.y == got[k].point.y &&
                  any[0].point.z == got[k].point.z && any[0].error == got[k].error);
            const double facing = any[0].normal.x * ray.dir.x + any[0].normal.y * ray.dir.y +
                                  any[0].normal.z * ray.dir.z;
            CHECK_MSG(any[0].entering ? facing < 0.0 : facing > 0.0,
                      "ray %d: any-hit normal (%g, %g, %g), entering %d", i, any[0].normal.x,
                      any[0].normal.y, any[0].normal.z, (int)any[0].entering);
            break;
        }
    }
    CHECK_MSG(compared > 15000 && hit_rays > 5000, "only %d rays compared, %d hitting", compared,
              hit_rays);
}

/* Rays stepped across a shared edge in 1e-7 steps, from -5e-6 to 5e-6 of
 * it (and exactly at it): every ray enters the solid once and leaves once,
 * never missing the seam, never hitting both triangles. Edges: the
 * diagonal of the cube's +z face (x = y on z = 1), and every edge of the
 * icosahedron (irrational coordinates, no axis alignment). */
static void sweep_edge(const harness_shape *s, hr_vec3 p, hr_vec3 q, hr_vec3 across, hr_vec3 dir,
                       const char *what)
{
    int bad = 0;
    for (int along = 1; along <= 3; along++) {
        const double f = along / 4.0;
        hr_vec3 on = harness_vec(p.x + f * (q.x - p.x), p.y + f * (q.y - p.y), p.z + f * (q.z - p.z));
        for (int k = -50; k <= 50; k++) {
            const double delta = k * 1e-7;
            hr_vec3 target = harness_vec(on.x + delta * across.x, on.y + delta * across.y,
                                         on.z + delta * across.z);
            hr_ray ray = harness_ray(target.x - 3 * dir.x, target.y - 3 * dir.y,
                                     target.z - 3 * dir.z, dir.x, dir.y, dir.z);
            hr_hit h[HARNESS_MAX_HITS];
            int n = harness_hits(s, ray, h);
            int ok = n == 2 && h[0].entering == 1 && h[1].entering == 0 &&
                     fabs(h[0].t - 3) <= 1e-5;
            if (!ok && bad++ < 5)
                CHECK_MSG(0, "%s: f %g step %d: %d hits (t %g, entering %d)", what, f, k, n,
                          n ? h[0].t : 0.0, n ? (int)h[0].entering : -1);
            hr_test_checks++;
        }
    }
    CHECK_MSG(bad == 0, "%s: %d rays of the sweep missed or hit twice", what, bad);
}

static void test_edge_sweeps(void)
{
    /* The cube's +z face is split along (-1,-1,1)-(1,1,1). */
    sweep_edge(&cube_mesh, harness_vec(-1, -1, 1), harness_vec(1, 1, 1), unit(harness_vec(1, -1, 0)),
               harness_vec(0.1, -0.2, -1), "cube diagonal");
    sweep_edge(&cube_mesh, harness_vec(-1, -1, 1), harness_vec(1, 1, 1), unit(harness_vec(1, -1, 0)),
               harness_vec(0, 0, -1), "cube diagonal, straight down");
    harness_shape ico;
    if (!harness_open(&ico, "mesh", "icosahedron", NAN)) return;
    const double phi = (1 + sqrt(5.0)) / 2, r = sqrt(1 + phi * phi);
    /* Edges of the icosahedron: pairs of vertices at distance 2 / r. */
    hr_vec3 v[12];
    int n = 0;
    for (int shift = 0; shift < 3; shift++)
        for (int s = 0; s < 4; s++) {
            double c[3] = {0, (s & 1 ? -1 : 1) / r, (s & 2 ? -phi : phi) / r};
            v[n++] = harness_vec(c[(3 - shift) % 3], c[(4 - shift) % 3], c[(5 - shift) % 3]);
        }
    int edges = 0;
    for (int i = 0; i < 12; i++)
        for (int j = i + 1; j < 12; j++) {
            hr_vec3 d = harness_vec(v[j].x - v[i].x, v[j].y - v[i].y, v[j].z - v[i].z);
            if (fabs(sqrt(dot(d, d)) - 2 / r) > 1e-9) continue;
            edges++;
            hr_vec3 mid = unit(harness_vec(v[i].x + v[j].x, v[i].y + v[j].y, v[i].z + v[j].z));
            hr_vec3 e = unit(d);
            hr_vec3 across = harness_vec(mid.y * e.z - mid.z * e.y, mid.z * e.x - mid.x * e.z,
                                         mid.x * e.y - mid.y * e.x);
            /* Toward the centre, tilted so the ray is not symmetric. */
            hr_vec3 dir = harness_vec(-mid.x + 0.1 * e.x, -mid.y + 0.1 * e.y, -mid.z + 0.1 * e.z);
            char what[64];
            snprintf(what, sizeof what, "icosahedron edge %d-%d", i, j);
            sweep_edge(&ico, v[i], v[j], across, dir, what);
        }
    CHECK_MSG(edges == 30, "%d icosahedron edges", edges);
    harness_close(&ico);
}

/* Rays through vertices: the octahedron's (+-1, 0, 0), ... are exact, and
 * a ray from (3, 0.5, 0.25) + t (-2, -0.5, -0.25) runs exactly through
 * (1, 0, 0) at t = 1 into the solid: four faces meet there, and the ray
 * enters once, then leaves once. A ray touching only that vertex (from
 * (1, 1, 0.5) along (0, -1, -0.5): |x| + |y| + |z| > 1 elsewhere) is
 * either missed or entered and left at the vertex. The icosahedron's
 * vertices, aimed at from several sides, likewise give one entry each. */
static void test_vertices(void)
{
    harness_shape octa;
    if (!harness_open(&octa, "mesh", "octahedron", NAN)) return;
    hr_hit h[HARNESS_MAX_HITS];
    int n = harness_hits(&octa, harness_ray(3, 0.5, 0.25, -2, -0.5, -0.25), h);
    CHECK_MSG(n == 2, "through the vertex: %d hits", n);
    if (n == 2) {
        CHECK(h[0].t == 1 && h[0].entering == 1 && h[1].entering == 0);
        CHECK_NEAR(h[0].point.x, 1, h[0].error + 1e-15);
    }
    /* All six vertices, each from 8 directions, rays through them exactly. */
    const double vx[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int i = 0; i < 6; i++)
        for (int s = 0; s < 8; s++) {
            const double off[3] = {s & 1 ? 0.5 : -0.25, s & 2 ? 0.375 : -0.125, s & 4 ? 0.75 : -0.5};
            hr_vec3 o = harness_vec(3 * vx[i][0] + off[0], 3 * vx[i][1] + off[1], 3 * vx[i][2] + off[2]);
            hr_ray ray = harness_ray(o.x, o.y, o.z, vx[i][0] - o.x, vx[i][1] - o.y, vx[i][2] - o.z);
            n = harness_hits(&octa, ray, h);
            CHECK_MSG(n == 2 && h[0].entering == 1 && h[0].t == 1,
                      "octahedron vertex %d side %d: %d hits", i, s, n);
        }
    n = harness_hits(&octa, harness_ray(1, 1, 0.5, 0, -1, -0.5), h);
    CHECK_MSG(n == 0 || (n == 2 && h[0].entering == 1 && h[1].entering == 0 &&
                         fabs(h[0].t - 1) < 1e-12 && fabs(h[1].t - 1) < 1e-12),
              "touching the vertex: %d hits", n);
    harness_close(&octa);

    harness_shape ico;
    if (!harness_open(&ico, "mesh", "icosahedron", NAN)) return;
    const double phi = (1 + sqrt(5.0)) / 2, r = sqrt(1 + phi * phi);
    ray_rng rng;
    rng_seed(&rng, 5);
    for (int shift = 0; shift < 3; shift++)
        for (int s = 0; s < 4; s++) {
            double c[3] = {0, (s & 1 ? -1 : 1) / r, (s & 2 ? -phi : phi) / r};
            hr_vec3 v = harness_vec(c[(3 - shift) % 3], c[(4 - shift) % 3], c[(5 - shift) % 3]);
            for (int k = 0; k < 20; k++) {
                hr_vec3 wobble = rng_unit_vector(&rng);
                hr_vec3 o = harness_vec(3 * v.x + wobble.x, 3 * v.y + wobble.y, 3 * v.z + wobble.z);
                hr_ray ray = harness_ray(o.x, o.y, o.z, -o.x + 0.1 * v.x, -o.y + 0.1 * v.y,
                                         -o.z + 0.1 * v.z);
                /* Aim through the vertex itself: direction v - o. */
                ray.dir = harness_vec(v.x - o.x, v.y - o.y, v.z - o.z);
                n = harness_hits(&ico, ray, h);
                /* Into the solid (the angle to the vertex's outward direction
                 * is wide enough for every wobble) unless it only touches. */
                CHECK_MSG(n == 0 || (n == 2 && h[0].entering == 1 && h[1].entering == 0),
                          "icosahedron vertex: %d hits", n);
                if (dot(unit(ray.dir), unit(v)) < -0.95)
                    CHECK_MSG(n == 2 && fabs(h[0].t - 1) < 1e-12, "straight through a vertex: %d", n);
            }
        }
    harness_close(&ico);
}

/* Lines through the octahedron that cross an edge within about 1e-18 of
 * t = 0 (a fuzz input: from (1.3e-18, -0.5, -0.5) along (1 + 2^-52, 3,
 * 1.625), the line meets the edge x = 0, y + z = -1 at t = -1.3e-18).
 * The edge's triangles agree exactly which of them it crosses, but that
 * one is the face x <= 0, and its t rounds to 0: the mesh walks the line
 * in two halves, t < 0 reversed and t >= 0, and the half from 0 culls the
 * box x <= 0 (the ray is at x > 0 for every t >= 0) while the reversed
 * half left a t of 0 to it. The entering crossing was lost: one hit over
 * the whole line, leaving. Both directions, origins on either side of the
 * edge's plane and a subnormal one: entered first, left last, once each,
 * and the first hit is the list's first. */
static void test_edge_crossing_at_zero(void)
{
    harness_shape octa;
    if (!harness_open(&octa, "mesh", "octahedron", NAN)) return;
    const double xs[4] = {0x1.312p-59, -0x1.312p-59, 0x1p-1074, -0x1p-1074};
    for (int k = 0; k < 4; k++)
        for (int back = 0; back < 2; back++) {
            const double s = back ? -1.0 : 1.0;
            hr_ray ray = harness_ray(xs[k], -0.5, -0.5, s * 0x1.0000000000001p+0, s * 3.0, s * 1.625);
            hr_hit h[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS];
            const int n = harness_trace(&octa, ray, -INFINITY, INFINITY, HARNESS_ALL, h);
            CHECK_MSG(n == 2 && h[0].entering == 1 && h[1].entering == 0,
                      "edge crossing near t = 0, origin x %a, %s: %d hits", xs[k], back ? "back" : "ahead", n);
            /* The crossing near 0 is within its error of t = -1.3e-18 (or
             * 0), the other at |t| = 2 / 5.625. */
            if (n == 2) {
                const double near = back ? h[1].t : h[0].t, far = back ? h[0].t : h[1].t;
                CHECK_NEAR(near, 0.0, 1e-15);
                CHECK_NEAR(far, s * 2.0 / 5.625, 1e-15);
                const int nf = harness_trace(&octa, ray, -INFINITY, INFINITY, HARNESS_FIRST, first);
                CHECK(nf == 1 && first[0].t == h[0].t);
            }
        }
    harness_close(&octa);
}

/* A line in the plane of a face with a t error bound past the doubles (a
 * fuzz input): from (a, 1, a), a = 1.0e-300, within 1e-300 of the vertex
 * (0, 1, 0), along (-2^-1074, a, a). In rational arithmetic on the doubles
 * it misses the solid by 2^-1074 (|x| + |y| + |z| is 1 + 2^-1074 at
 * t = -1, its least); the sheared corners, rounded, put it through the
 * edge (0, 1, 0)-(1, 0, 0) at t = -1, where it leaves the face x + y + z = 1
 * and enters x + y - z = 1, in whose plane it runs: that crossing has
 * det = 4.9e-24 against corners 1e300 deep, and its t error bound overflowed
 * to +inf, so the whole line (tmin = -inf, t - tmin = +inf) refused it as
 * lying within its error of tmin: one hit, leaving. Either way along the
 * line: no hit, or entered and left once, and the first hit is the list's
 * first. */
static void test_face_plane_t_error_past_doubles(void)
{
    harness_shape octa;
    if (!harness_open(&octa, "mesh", "octahedron", NAN)) return;
    const double a = 0x1.56e1fc2f8f359p-997;
    for (int back = 0; back < 2; back++) {
        const double s = back ? -1.0 : 1.0;
        hr_ray ray = harness_ray(a, 1.0, a, s * -0x1p-1074, s * a, s * a);
        hr_hit h[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS];
        const int n = harness_trace(&octa, ray, -INFINITY, INFINITY, HARNESS_ALL, h);
        CHECK_MSG(n == 0 || (n == 2 && h[0].entering == 1 && h[1].entering == 0),
                  "line in a face's plane by the vertex, %s: %d hits, the first %s", back ? "back" : "ahead",
                  n, n ? (h[0].entering ? "entering" : "leaving") : "none");
        if (n == 2) {
            CHECK_NEAR(h[0].t, -s, 1e-15);
            CHECK_NEAR(h[1].t, -s, 1e-15);
            const int nf = harness_trace(&octa, ray, -INFINITY, INFINITY, HARNESS_FIRST, first);
            CHECK(nf == 1 && first[0].t == h[0].t && first[0].entering == 1);
        }
    }
    harness_close(&octa);
}

/* The same cube in Hill's format: four-corner faces fanned, normals from
 * the file (here equal to the geometric ones). */
static void test_hill_cube(void)
{
    char path[1024];
    harness_shape hill;
    if (!mesh_open_file(&hill, mesh_data_path("cube.3vn", path, sizeof path))) return;
    hr_bounds b;
    hill.cls->bounds(hill.shape, &b);
    CHECK(b.lo.x == -1 && b.lo.y == -1 && b.lo.z == -1 && b.hi.x == 1 && b.hi.y == 1 && b.hi.z == 1);
    ray_rng rng;
    rng_seed(&rng, 3);
    hr_bounds cb = {{-1, -1, -1}, {1, 1, 1}};
    for (int i = 0; i < 2000; i++) {
        hr_ray ray = random_ray_near(&rng, &cb);
        hr_hit a[HARNESS_MAX_HITS], c[HARNESS_MAX_HITS];
        int n = harness_hits(&hill, ray, a);
        int m = harness_hits(&cube_mesh, ray, c);
        /* Both fan the faces along the same diagonals, so the answers agree
         * bit for bit except for the normals' length. */
        CHECK_MSG(n == m, "ray %d: .3vn %d hits, .obj %d", i, n, m);
        for (int k = 0; k < n && n == m; k++) {
            CHECK(a[k].t == c[k].t && a[k].entering == c[k].entering);
            hr_vec3 x = unit(a[k].normal), y = unit(c[k].normal);
            CHECK(fabs(x.x - y.x) < 1e-15 && fabs(x.y - y.y) < 1e-15 && fabs(x.z - y.z) < 1e-15);
        }
    }
    harness_close(&hill);
}

/* Hill's tetrahedron file: vertices (+-1, +-1, +-1), the built-in
 * tetrahedron scaled by sqrt(3); per-vertex normals interpolated. */
static void test_hill_tetrahedron(void)
{
    char path[1024];
    harness_shape file, built;
    if (!mesh_open_file(&file, mesh_data_path("tetra_hill.3vn", path, sizeof path))) return;
    if (!harness_open(&built, "mesh", "tetrahedron", NAN)) return;
    ray_rng rng;
    rng_seed(&rng, 4);
    hr_bounds fb;
    file.cls->bounds(file.shape, &fb);
    const double s = sqrt(3.0);
    int smooth = 0, mismatched = 0;
    for (int i = 0; i < 3000; i++) {
        hr_ray ray = random_ray_near(&rng, &fb);
        hr_ray scaled = harness_ray(ray.origin.x / s, ray.origin.y / s, ray.origin.z / s,
                                    ray.dir.x / s, ray.dir.y / s, ray.dir.z / s);
        hr_hit a[HARNESS_MAX_HITS], c[HARNESS_MAX_HITS];
        int n = harness_hits(&file, ray, a);
        int m = harness_hits(&built, scaled, c);
        /* Scaling rounds the inputs, so a ray within rounding of an edge
         * may be owned differently: allow a handful of such rays. */
        if (n != m) {
            mismatched++;
            continue;
        }
        for (int k = 0; k < n; k++) {
            /* Same t: the rays are the same line with directions scaled alike. */
            CHECK_MSG(fabs(a[k].t - c[k].t) <= 1e-12 * (1 + fabs(c[k].t)), "t %.17g vs %.17g",
                      a[k].t, c[k].t);
            CHECK(a[k].entering == c[k].entering);
            /* The shading normal leans toward the corners' normals, on the
             * outer side of the face. */
            CHECK(dot(a[k].normal, c[k].normal) > 0);
            smooth += fabs(dot(unit(a[k].normal), unit(c[k].normal))) < 1 - 1e-6;
        }
    }
    CHECK_MSG(smooth > 100, "only %d hits with an interpolated normal", smooth);
    CHECK_MSG(mismatched <= 3, "%d rays hit the file's tetrahedron differently", mismatched);
    harness_close(&file);
    harness_close(&built);
}

/* smooth_square.obj: normals (x/2, y/2, 1) at the corners interpolate to
 * exactly that at every point, from above (entering) and below (leaving,
 * the normal still on the geometric +z side). Within 1e-12: barycentric
 * weights carry a few roundings. */
static void test_obj_normals(void)
{
    char path[1024];
    harness_shape sq;
    if (!mesh_open_file(&sq, mesh_data_path("smooth_square.obj", path, sizeof path))) return;
    ray_rng rng;
    rng_seed(&rng, 8);
    for (int i = 0; i < 500; i++) {
        double x = rng_uniform(&rng, -0.99, 0.99), y = rng_uniform(&rng, -0.99, 0.99);
        for (int side = 0; side < 2; side++) {
            double z = side ? -2 : 2;
            hr_hit h[HARNESS_MAX_HITS];
            int n = harness_hits(&sq, harness_ray(x + 0.1, y - 0.2, z, -0.05, 0.1, -z / 2), h);
            CHECK(n == 1);
            if (n != 1) continue;
            CHECK(h[0].entering == !side);
            hr_vec3 p = h[0].point;
            hr_vec3 want = unit(harness_vec(p.x / 2, p.y / 2, 1)), got = unit(h[0].normal);
            CHECK_MSG(fabs(want.x - got.x) < 1e-12 && fabs(want.y - got.y) < 1e-12 &&
                          fabs(want.z - got.z) < 1e-12,
                      "normal (%g %g %g) at (%g %g)", got.x, got.y, got.z, p.x, p.y);
            CHECK(p.z == 0 || fabs(p.z) <= h[0].error);
        }
    }
    harness_close(&sq);
}

/* The regular solids: closed, vertices on the unit sphere, and random rays
 * give the span a long-double clip against the face planes gives (the
 * planes are the supporting planes in the directions of the dual solid's
 * vertices). Compared where the span is longer than 1e-6 (no grazing):
 * t within 1e-12 (|t| + 1). */
typedef struct plane {
    long double n[3], offset;
} plane;

static int dual_planes(int solid, const hr_vec3 *verts, int nv, plane *out)
{
    const long double phi = (1 + sqrtl(5.0L)) / 2;
    long double dirs[20][3];
    int nd = 0;
    if (solid == 0) { /* tetrahedron: opposite its own vertices */
        const int t[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
        for (int i = 0; i < 4; i++)
            for (int a = 0; a < 3; a++) dirs[nd + i][a] = -t[i][a];
        nd = 4;
    } else if (solid == 1) { /* octahedron: the cube's corners */
        for (int s = 0; s < 8; s++) {
            dirs[nd][0] = s & 1 ? -1 : 1, dirs[nd][1] = s & 2 ? -1 : 1, dirs[nd][2] = s & 4 ? -1 : 1;
            nd++;
        }
    } else { /* dodecahedron <-> icosahedron */
        const int ico_dual = solid == 3;
        if (ico_dual)
            for (int s = 0; s < 8; s++) {
                dirs[nd][0] = s & 1 ? -1 : 1, dirs[nd][1] = s & 2 ? -1 : 1, dirs[nd][2] = s & 4 ? -1 : 1;
                nd++;
            }
        for (int shift = 0; shift < 3; shift++)
            for (int s = 0; s < 4; s++) {
                /* The dual in the matching orientation has (0, phi, 1), not
                 * (0, 1, phi): the face of the dodecahedron on the edge
                 * (0, +-1/phi, phi) has its centre along (1, 0, phi). */
                long double c[3] = {0, s & 1 ? -phi : phi,
                                    ico_dual ? (s & 2 ? -1 : 1) / phi : (s & 2 ? -1 : 1)};
                dirs[nd][0] = c[(3 - shift) % 3], dirs[nd][1] = c[(4 - shift) % 3];
                dirs[nd][2] = c[(5 - shift) % 3];
                nd++;
            }
    }
    for (int i = 0; i < nd; i++) {
        long double len = sqrtl(dirs[i][0] * dirs[i][0] + dirs[i][1] * dirs[i][1] + dirs[i][2] * dirs[i][2]);
        long double best = -1;
        for (int a = 0; a < 3; a++) out[i].n[a] = dirs[i][a] / len;
        for (int k = 0; k < nv; k++) {
            long double d = out[i].n[0] * verts[k].x + out[i].n[1] * verts[k].y + out[i].n[2] * verts[k].z;
            if (d > best) best = d;
        }
        out[i].offset = best;
    }
    return nd;
}

static void test_solids(void)
{
    static const char *const names[4] = {"tetrahedron", "octahedron", "dodecahedron", "icosahedron"};
    static const int vertex_counts[4] = {4, 6, 20, 12};
    const double phi = (1 + sqrt(5.0)) / 2;
    for (int solid = 0; solid < 4; solid++) {
        harness_shape s;
        if (!harness_open(&s, "mesh", names[solid], NAN)) continue;
        CHECK(s.cls->flags == HR_SHAPE_CLOSED && s.cls->param_count == 0);
        /* The vertices, as the module writes them down (for the planes). */
        hr_vec3 v[20];
        int nv = 0;
        if (solid == 0) {
            const double t[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
            for (int i = 0; i < 4; i++) v[nv++] = unit(harness_vec(t[i][0], t[i][1], t[i][2]));
        } else if (solid == 1) {
            for (int a = 0; a < 3; a++)
                for (int sg = -1; sg <= 1; sg += 2) {
                    double c[3] = {0, 0, 0};
                    c[a] = sg;
                    v[nv++] = harness_vec(c[0], c[1], c[2]);
                }
        } else if (solid == 2) {
            for (int sg = 0; sg < 8; sg++)
                v[nv++] = unit(harness_vec(sg & 1 ? -1 : 1, sg & 2 ? -1 : 1, sg & 4 ? -1 : 1));
            for (int shift = 0; shift < 3; shift++)
                for (int sg = 0; sg < 4; sg++) {
                    double c[3] = {0, (sg & 1 ? -1 : 1) / phi, sg & 2 ? -phi : phi};
                    v[nv++] = unit(harness_vec(c[(3 - shift) % 3], c[(4 - shift) % 3], c[(5 - shift) % 3]));
                }
        } else {
            for (int shift = 0; shift < 3; shift++)
                for (int sg = 0; sg < 4; sg++) {
                    double c[3] = {0, sg & 1 ? -1 : 1, sg & 2 ? -phi : phi};
                    v[nv++] = unit(harness_vec(c[(3 - shift) % 3], c[(4 - shift) % 3], c[(5 - shift) % 3]));
                }
        }
        CHECK(nv == vertex_counts[solid]);
        plane planes[20];
        int np = dual_planes(solid, v, nv, planes);
        hr_bounds b;
        s.cls->bounds(s.shape, &b);
        CHECK(b.hi.x <= 1 && b.lo.x >= -1 && b.hi.x > 0.5);
        ray_rng rng;
        rng_seed(&rng, 100 + (uint64_t)solid);
        int compared = 0, corner_spawns = 0;
        for (int i = 0; i < 5000; i++) {
            hr_ray ray = random_ray_near(&rng, &b);
            long double t_in = -INFINITY, t_out = INFINITY;
            const long double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
            const long double d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
            for (int p = 0; p < np; p++) {
                long double nd = planes[p].n[0] * d[0] + planes[p].n[1] * d[1] + planes[p].n[2] * d[2];
                long double no = planes[p].n[0] * o[0] + planes[p].n[1] * o[1] + planes[p].n[2] * o[2];
                if (nd == 0) {
                    if (no > planes[p].offset) t_in = INFINITY;
                    continue;
                }
                long double t = (planes[p].offset - no) / nd;
                if (nd < 0 && t > t_in) t_in = t;
                if (nd > 0 && t < t_out) t_out = t;
            }
            hr_hit h[HARNESS_MAX_HITS];
            int n = harness_hits(&s, ray, h); /* the harness checks alternation */
            long double len = sqrtl(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (fabsl(t_out - t_in) <= 1e-6L / len) continue; /* grazing, or missing by a hair */
            int want = 0;
            if (t_in < t_out) want = (t_in > 0) + (t_out > 0);
            compared++;
            CHECK_MSG(n == want, "%s ray %d: %d hits, expected %d (t_in %.17Lg t_out %.17Lg)", names[solid], i, n, want, t_in, t_out);
            if (n != want || n == 0) continue;
            /* Each point is on the surface within its error bound (per
             * coordinate, so sqrt(3) of it as a distance), plus 4e-16 for
             * the module's vertices, which are the exact ones rounded to
             * double (their planes move by a few 1e-17 to 1e-16). */
            for (int k = 0; k < n; k++) {
                long double nearest = INFINITY;
                for (int p = 0; p < np; p++) {
                    long double dist = fabsl(planes[p].n[0] * h[k].point.x + planes[p].n[1] * h[k].point.y +
                                             planes[p].n[2] * h[k].point.z - planes[p].offset);
                    if (dist < nearest) nearest = dist;
                }
                CHECK_MSG(nearest <= sqrtl(3.0L) * h[k].error + 4e-16L,
                          "%s ray %d: point %.3Lg from the surface, error bound %g", names[solid], i,
                          nearest, h[k].error);
            }
            /* Rays spawned from each hit the way the host does (the origin
             * moved off the surface by the error bound, along the normal)
             * and leaving a convex solid never hit it again; nor do rays
             * spawned inward hit anything but the far side. */
            for (int k = 0; k < n; k++) {
                const hr_vec3 nn = unit(h[k].normal);
                const double off = 2 * sqrt(3.0) * h[k].error;
                for (int side = -1; side <= 1; side += 2) {
                    hr_vec3 w = rng_unit_vector(&rng);
                    if (dot(w, nn) * side < 0) w = harness_vec(-w.x, -w.y, -w.z);
                    if (fabs(dot(w, nn)) < 1e-3) continue;
                    hr_hit again[HARNESS_MAX_HITS];
                    int m = harness_hits(&s, harness_ray(h[k].point.x + side * off * nn.x,
                                                         h[k].point.y + side * off * nn.y,
                                                         h[k].point.z + side * off * nn.z, w.x, w.y,
                                                         w.z),
                                         again);
                    /* Inward, the ray leaves once; or, from within the offset of
                     * an edge, it may already be outside the neighbour face. */
                    if (side > 0) CHECK_MSG(m == 0, "%s ray %d: a spawned ray hit again", names[solid], i);
                    else if (m == 0) corner_spawns++;
                    else CHECK_MSG(m == 1 && again[0].entering == 0,
                                   "%s ray %d: an inward spawned ray: %d hits", names[solid], i, m);
                }
            }
            hr_hit first[HARNESS_MAX_HITS], any[HARNESS_MAX_HITS];
            CHECK(harness_trace(&s, ray, 0, INFINITY, HARNESS_FIRST, first) == 1 &&
                  first[0].t == h[0].t && first[0].entering == h[0].entering);
            CHECK(harness_trace(&s, ray, 0, INFINITY, HARNESS_ANY, any) == 1);
            if (n == 2) {
                CHECK_NEAR(h[0].t, (double)t_in, 1e-12 * (1 + fabsl(t_in)));
                CHECK_NEAR(h[1].t, (double)t_out, 1e-12 * (1 + fabsl(t_out)));
            } else {
                CHECK(h[0].entering == 0);
                CHECK_NEAR(h[0].t, (double)t_out, 1e-12 * (1 + fabsl(t_out)));
            }
        }
        CHECK_MSG(compared > 4000, "%s: %d rays compared", names[solid], compared);
        CHECK_MSG(corner_spawns < 10, "%s: %d inward spawned rays found nothing", names[solid],
                  corner_spawns);
        harness_close(&s);
    }
}

/* 40 parallel squares, one ray through all: 80 triangles tested, 40 hits,
 * more than the host's promised free space, so the module asks the host to
 * grow the list; sorted, all entering (the squares face the ray). */
static void test_many_hits(void)
{
    char path[1024];
    mesh_build_path("mesh_stack.obj", path, sizeof path);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    for (int i = 0; i < 40; i++) {
        fprintf(f, "v -1 -1 %d\nv 1 -1 %d\nv 1 1 %d\nv -1 1 %d\n", i, i, i, i);
        fprintf(f, "f %d %d %d %d\n", 4 * i + 1, 4 * i + 2, 4 * i + 3, 4 * i + 4);
    }
    fclose(f);
    harness_shape stack;
    if (!mesh_open_file(&stack, path)) return;
    hr_intersection list = {NULL, 0, 0};
    CHECK_OK(harness_host()->reserve(NULL, &list, HR_MIN_HIT_CAPACITY));
    hr_hit_args args;
    memset(&args, 0, sizeof args);
    args.shape = stack.shape;
    args.ray = harness_ray(0.25, 0.125, 100, 0.001, 0.002, -1);
    args.tmin = 0;
    args.tmax = INFINITY;
    args.out = &list;
    CHECK_OK(stack.cls->hit(&args));
    CHECK_MSG(list.count == 40, "%d hits", (int)list.count);
    for (int i = 0; i < list.count; i++) {
        CHECK(list.hits[i].entering == 1); /* normals +z, the ray goes down */
        if (i) CHECK(list.hits[i - 1].t <= list.hits[i].t);
        CHECK_NEAR(list.hits[i].t, 100 - (39 - i), 1e-12 * 100);
    }
    free(list.hits);
    harness_close(&stack);
}

/* a, b, c, d with c d within a few ulps of a b, or exactly equal. */
static void cancelling_products(ray_rng *rng, double *a, double *b, double *c, double *d)
{
    *a = rng_uniform(rng, -2, 2), *b = rng_uniform(rng, -2, 2);
    *c = rng_uniform(rng, 0.5, 2) * (rng_chance(rng, 0.5) ? -1 : 1);
    *d = *a * *b / *c; /* c d = a b within an ulp or two */
    const int nudge = (int)(rng_next(rng) % 7) - 3;
    for (int k = 0; k < abs(nudge); k++) *d = nextafter(*d, nudge > 0 ? INFINITY : -INFINITY);
    if (rng_chance(rng, 0.1)) *c = *a, *d = *b; /* exactly zero */
}

/* The edge functions' signs are exact: a b - c d against __float128, where
 * both products are exact (106 bits < 113) and so is the sign of their
 * difference, on inputs built to cancel (c d within a few ulps of a b, and
 * exactly equal), where plain double arithmetic gets the sign wrong. */
static void test_exact_signs(void)
{
    ray_rng rng;
    rng_seed(&rng, 21);
    int wrong_plain = 0;
    for (int i = 0; i < 200000; i++) {
        double a, b, c, d;
        cancelling_products(&rng, &a, &b, &c, &d);
        const quad exact = (quad)a * b - (quad)c * d;
        const int want = exact > 0 ? 1 : exact < 0 ? -1 : 0;
        const double got = mesh_edge_function(a, b, c, d);
        const int sign = got > 0 ? 1 : got < 0 ? -1 : 0;
        CHECK_MSG(sign == want, "%.17g * %.17g - %.17g * %.17g: sign %d, exact %d", a, b, c, d,
                  sign, want);
        const double plain = a * b - c * d;
        wrong_plain += (plain > 0 ? 1 : plain < 0 ? -1 : 0) != want;
    }
    /* The cases are hard ones: plain evaluation must get some wrong. */
    CHECK_MSG(wrong_plain > 1000, "only %d plain signs wrong: the inputs do not cancel", wrong_plain);
}

/* The same at every scale: the factors (a, c) and (b, d) scaled by powers
 * of two from 2^-1074 to products near 2^1000, so that products underflow
 * (corners within 1e-150 of the ray: a tetrahedron with vertices 1e-300
 * apart crossed once, from outside, by the fuzzer's ray) or come near
 * overflow. The sign wanted is the exact one of the scaled doubles (in
 * __float128, whose exponent holds every product). */
static void test_exact_signs_at_any_scale(void)
{
    ray_rng rng;
    rng_seed(&rng, 22);
    int tiny_products = 0;
    for (int i = 0; i < 200000; i++) {
        double a, b, c, d;
        cancelling_products(&rng, &a, &b, &c, &d);
        if (rng_chance(&rng, 0.2)) { /* one product far smaller than the other */
            const double t = b;
            b = d, d = t;
        }
        const int k1 = (int)(rng_next(&rng) % 2075) - 1074;
        int k2 = (int)(rng_next(&rng) % 2075) - 1074;
        if (k1 + k2 > 1000) k2 = 1000 - k1;
        a = ldexp(a, k1), c = ldexp(c, k1), b = ldexp(b, k2), d = ldexp(d, k2);
        if (rng_chance(&rng, 0.1)) { /* (b, c) small instead */
            const double t = ldexp(1.0, -(int)(rng_next(&rng) % 600));
            b *= t, c *= t;
        }
        const quad exact = (quad)a * b - (quad)c * d;
        const int want = exact > 0 ? 1 : exact < 0 ? -1 : 0;
        const double got = mesh_edge_function(a, b, c, d);
        const int sign = got > 0 ? 1 : got < 0 ? -1 : 0;
        CHECK_MSG(sign == want, "%a * %a - %a * %a: sign %d, exact %d", a, b, c, d, sign, want);
        tiny_products += fabs(a * b) < 0x1p-960 && fabs(c * d) < 0x1p-960 && want != 0;
    }
    CHECK_MSG(tiny_products > 10000, "only %d cases with both products tiny", tiny_products);
}

/* mesh_next_up (the step a first-hit search narrows tmax by) is
 * nextafter(x, INFINITY) on every kind of double: zeros, subnormals, the
 * largest finite values, infinities, NaN, and random bit patterns of both
 * signs. Compared by bits, so -0 and +0 are told apart. */
static int same_bits(double a, double b)
{
    if (isnan(a) && isnan(b)) return 1;
    return memcmp(&a, &b, sizeof a) == 0;
}

static void test_next_up(void)
{
    static const double special[] = {0.0, -0.0, DBL_TRUE_MIN, -DBL_TRUE_MIN, DBL_MIN, -DBL_MIN,
                                     DBL_MIN - DBL_TRUE_MIN, -(DBL_MIN - DBL_TRUE_MIN), 1.0, -1.0,
                                     DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, NAN, 0x1p-1022, -0x1p-1021};
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++) {
        const double x = special[i], want = nextafter(x, INFINITY), got = mesh_next_up(x);
        CHECK_MSG(same_bits(got, want), "mesh_next_up(%a) = %a, nextafter %a", x, got, want);
    }
    ray_rng rng;
    rng_seed(&rng, 23);
    long wrong = 0;
    for (int i = 0; i < 1000000; i++) {
        const uint64_t bits = rng_next(&rng);
        double x;
        memcpy(&x, &bits, sizeof x);
        const double want = nextafter(x, INFINITY), got = mesh_next_up(x);
        if (!same_bits(got, want) && ++wrong <= 5)
            CHECK_MSG(0, "mesh_next_up(%a) = %a, nextafter %a", x, got, want);
    }
    CHECK_MSG(wrong == 0, "%ld of 10^6 random doubles step differently", wrong);
}

/* The module's table: eight classes, complete vtables, one surface each;
 * the solids closed and without parameters; `mesh` takes one required
 * string `file` (the name the SDL reader and the Python binding use);
 * `triangleMesh`, sixth, takes the arrays points, triangles (required) and
 * normals; then the buckyball, closed, and the teapot, open, with its one
 * optional number `tessellation` (test_shape_teapot looks further). */
static void test_classes(void)
{
    const hr_module_info *info = cube_mesh.module.info;
    CHECK(info->abi_version == HR_SHAPE_ABI_VERSION && strcmp(info->name, "mesh") == 0);
    CHECK(info->class_count == 8);
    static const char *const names[8] = {"mesh",         "tetrahedron", "octahedron",
                                         "dodecahedron", "icosahedron", "triangleMesh",
                                         "buckyball",    "teapot"};
    static const int32_t param_counts[8] = {1, 0, 0, 0, 0, 3, 0, 1};
    for (int i = 0; i < 8 && i < info->class_count; i++) {
        const hr_shape_class *c = info->classes[i];
        CHECK(strcmp(c->name, names[i]) == 0);
        CHECK(c->struct_size == sizeof(hr_shape_class) && c->surface_count == 1);
        CHECK(c->create && c->destroy && c->bounds && c->hit && c->first_hit && c->any_hit);
        CHECK(c->help && c->help[0]);
        const int32_t flags = i == 0 || i == 5 ? 0 : i == 7 ? HR_SHAPE_SDL_BARE : HR_SHAPE_CLOSED;
        CHECK(c->flags == flags);
        CHECK(c->param_count == param_counts[i]);
    }
    const hr_shape_class *m = info->classes[0];
    CHECK(strcmp(m->params[0].name, "file") == 0 && m->params[0].type == HR_PARAM_STRING &&
          m->params[0].required == 1);
    if (info->class_count < 6) return;
    const hr_shape_class *t = info->classes[5];
    static const char *const arrays[3] = {"points", "triangles", "normals"};
    for (int i = 0; i < 3; i++)
        CHECK(strcmp(t->params[i].name, arrays[i]) == 0 &&
              t->params[i].type == HR_PARAM_NUMBERS && t->params[i].required == (i < 2));
}

/* Every hit of `ray` over (0, inf), through the class's hit function with a
 * list the module must grow (the harness allows only 8). */
static int all_hits(const harness_shape *s, hr_ray ray, int32_t mode, hr_intersection *list)
{
    list->count = 0;
    hr_hit_args args;
    memset(&args, 0, sizeof args);
    args.shape = s->shape;
    args.ray = ray;
    args.tmin = 0;
    args.tmax = INFINITY;
    args.out = list;
    hr_hit_fn fn = mode == HR_TRACE_ALL ? s->cls->hit : mode == HR_TRACE_FIRST ? s->cls->first_hit
                                                                               : s->cls->any_hit;
    CHECK_OK(fn(&args));
    for (int i = 1; i < list->count; i++) CHECK(list->hits[i - 1].t <= list->hits[i].t);
    return list->count;
}

/* Meshes that defeat the SAH: 2000 copies of one triangle (every centroid
 * the same: median splits), and 201 squares at x = 1.5^i (the binned SAH
 * peels them off one at a time, so past 48 levels the build switches to
 * median splits). Both build, and rays find every copy and every square,
 * nearest first. */
static void test_degenerate_bvh(void)
{
    char path[1024];
    mesh_build_path("mesh_copies.obj", path, sizeof path);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fprintf(f, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for (int i = 0; i < 2000; i++) fprintf(f, "f 1 2 3\n");
    fclose(f);
    hr_intersection list = {NULL, 0, 0};
    CHECK_OK(harness_host()->reserve(NULL, &list, HR_MIN_HIT_CAPACITY));
    harness_shape copies;
    if (mesh_open_file(&copies, path)) {
        CHECK(all_hits(&copies, harness_ray(0.25, 0.25, 1, 0.01, 0.02, -1), HR_TRACE_ALL, &list) == 2000);
        CHECK(all_hits(&copies, harness_ray(0.25, 0.25, 1, 0.01, 0.02, -1), HR_TRACE_FIRST, &list) == 1);
        CHECK(all_hits(&copies, harness_ray(0.25, 0.25, -1, 0, 0, -1), HR_TRACE_ALL, &list) == 0);
        harness_close(&copies);
    }
    mesh_build_path("mesh_spread.obj", path, sizeof path);
    f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    double x = 1;
    for (int i = 0; i <= 200; i++, x *= 1.5)
        fprintf(f, "v %.17g 0 0\nv %.17g 0 1\nv %.17g 1 1\nv %.17g 1 0\nf -4 -3 -2 -1\n", x, x, x, x);
    fclose(f);
    harness_shape spread;
    if (mesh_open_file(&spread, path)) {
        CHECK(all_hits(&spread, harness_ray(-1, 0.25, 0.5, 1, 0, 0), HR_TRACE_ALL, &list) == 201);
        CHECK(all_hits(&spread, harness_ray(-1, 0.25, 0.5, 1, 0, 0), HR_TRACE_FIRST, &list) == 1 &&
              list.hits[0].t == 2);
        CHECK(all_hits(&spread, harness_ray(-1, 0.25, 0.5, 1, 0, 0), HR_TRACE_ANY, &list) == 1);
        /* From beyond the 100th square, backwards: the 100th first. */
        const double x100 = pow(1.5, 100);
        CHECK(all_hits(&spread, harness_ray(x100 * 1.25, 0.75, 0.5, -1, 0, 0), HR_TRACE_FIRST, &list) == 1 &&
              fabs(list.hits[0].t - x100 * 0.25) <= 1e-12 * x100);
        CHECK(all_hits(&spread, harness_ray(x100 * 1.25, 0.75, 0.5, -1, 0, 0), HR_TRACE_ALL, &list) == 101);
        harness_close(&spread);
    }
    free(list.hits);
}

/* Closed meshes thinner than rounding can resolve (flat tetrahedra 1e-17
 * to 1e-15 thick, tilted): their two crossings are a few ulps apart, yet
 * every ray through one enters before it leaves (the list of a closed mesh
 * is made to alternate). The faces are wound outward and every edge is
 * shared, so the module takes the file as closed. */
static void test_thin_closed(double thickness)
{
    char path[1024];
    mesh_build_path("mesh_thin.obj", path, sizeof path);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fprintf(f, "v 0 0 0.3\nv 1 0 0.1\nv 0 1 0.5\nv 0.25 0.25 %.17g\n"
               "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n", 0.3 + thickness);
    fclose(f);
    harness_shape thin;
    if (!mesh_open_file(&thin, path)) return;
    ray_rng rng;
    rng_seed(&rng, 9);
    int two = 0;
    for (int i = 0; i < 2000; i++) {
        double x = rng_uniform(&rng, 0.05, 0.4), y = rng_uniform(&rng, 0.05, 0.4);
        hr_ray ray = harness_ray(x + rng_uniform(&rng, -0.5, 0.5), y + rng_uniform(&rng, -0.5, 0.5),
                                 1, 0, 0, -1);
        ray.dir = harness_vec(x - ray.origin.x, y - ray.origin.y, -1);
        hr_hit h[HARNESS_MAX_HITS];
        int n = harness_hits(&thin, ray, h);
        CHECK_MSG(n == 0 || n == 2, "%d hits", n);
        if (n == 2) {
            two++;
            CHECK_MSG(h[0].entering == 1 && h[1].entering == 0 && h[0].t <= h[1].t,
                      "ray %d: entering %d then %d", i, (int)h[0].entering, (int)h[1].entering);
        }
    }
    CHECK(two > 1500);
    harness_close(&thin);
}

/* One triangle's hit in the brute-force list: ordered by t, entering
 * first, then the lower index in the file (the mesh's tie rule). */
typedef struct soup_hit {
    double t;
    int entering;
    int index;
} soup_hit;

static int compare_soup_hits(const void *a, const void *b)
{
    const soup_hit *x = a, *y = b;
    if (x->t != y->t) return x->t < y->t ? -1 : 1;
    if (x->entering != y->entering) return x->entering > y->entering ? -1 : 1;
    return (x->index > y->index) - (x->index < y->index);
}

/* Whether a hit's normal is (up to its side) the per-face normal n. */
static int normal_is(hr_vec3 got, hr_vec3 n)
{
    const hr_vec3 u = unit(got);
    return fabs(fabs(dot(u, n)) - 1.0) < 1e-9;
}

/* The BVH finds exactly what testing every triangle finds: a soup of
 * random triangles of all sizes (an open surface, so no reordering) scaled
 * by a power of two, random rays scaled with it (so t is unchanged) and
 * random intervals, a quarter of them from -inf (the walk's two halves of
 * the line) and some from up to 2^1000 behind the origin; the sorted lists
 * of t agree bit for bit with the same watertight test run on each
 * triangle in turn, the first hit is the smallest of them and the any hit
 * finds one of them when there is one. Scales beyond float's range give the BVH
 * infinite boxes. Exact ties: a quarter of the triangles are coincident
 * copies of earlier ones, and every face has its own normal, so the
 * first hit's normal and the order of the all-hits list show which of the
 * copies won each tie: the lower index in the file. */
static void soup_matches_brute_force(uint64_t seed, int tris, int rays, double scale)
{
    hr_vec3 *v = malloc(3 * (size_t)tris * sizeof *v);
    hr_vec3 *normal = malloc((size_t)tris * sizeof *normal);
    soup_hit *want = malloc((size_t)tris * sizeof *want);
    char path[1024];
    mesh_build_path("mesh_soup.obj", path, sizeof path);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL && v != NULL && want != NULL && normal != NULL);
    if (!f || !v || !want || !normal) {
        if (f) fclose(f);
        free(v);
        free(want);
        free(normal);
        return;
    }
    ray_rng rng;
    rng_seed(&rng, seed);
    int copies = 0;
    for (int t = 0; t < tris; t++) {
        hr_vec3 c = harness_vec(rng_uniform(&rng, -10, 10), rng_uniform(&rng, -10, 10),
                                rng_uniform(&rng, -10, 10));
        const double size = exp2(rng_uniform(&rng, -8, 3));
        const int copy_of = t > 0 && rng_chance(&rng, 0.25) ? (int)rng_uniform(&rng, 0, t) : -1;
        for (int k = 0; k < 3; k++) {
            hr_vec3 w = rng_unit_vector(&rng);
            v[3 * t + k] = harness_vec(scale * (c.x + size * w.x), scale * (c.y + size * w.y),
                                       scale * (c.z + size * w.z));
            if (copy_of >= 0 && copy_of < t) v[3 * t + k] = v[3 * copy_of + k];
            fprintf(f, "v %.17g %.17g %.17g\n", v[3 * t + k].x, v[3 * t + k].y, v[3 * t + k].z);
        }
        copies += copy_of >= 0;
        normal[t] = rng_unit_vector(&rng);
        fprintf(f, "vn %.17g %.17g %.17g\n", normal[t].x, normal[t].y, normal[t].z);
        fprintf(f, "f -3//-1 -2//-1 -1//-1\n");
    }
    fclose(f);
    harness_shape soup;
    if (!mesh_open_file(&soup, path)) {
        free(v);
        free(want);
        free(normal);
        return;
    }
    hr_intersection list = {NULL, 0, 0};
    CHECK_OK(harness_host()->reserve(NULL, &list, HR_MIN_HIT_CAPACITY));
    hr_bounds b = {{-10, -10, -10}, {10, 10, 10}};
    int hits = 0, failures = 0, ties = 0;
    for (int i = 0; i < rays; i++) {
        hr_ray ray = random_ray_near(&rng, &b);
        ray.origin.x *= scale, ray.origin.y *= scale, ray.origin.z *= scale;
        ray.dir.x *= scale, ray.dir.y *= scale, ray.dir.z *= scale;
        double tmin, tmax;
        random_interval(&rng, &tmin, &tmax);
        /* The first soup keeps the intervals it always had; the others
         * also start at -inf, or far behind the origin (accel's walk moves
         * the origin back to a negative tmin). */
        if (scale != 1.0 && rng_chance(&rng, 0.25)) tmin = -INFINITY;
        else if (scale != 1.0 && rng_chance(&rng, 0.25)) tmin = -exp2(rng_uniform(&rng, 0, 1000));
        mesh_ray r;
        int n = 0;
        if (mesh_ray_init(&r, &ray))
            for (int t = 0; t < tris; t++) {
                mesh_triangle_hit th;
                if (mesh_triangle_test(&r, &v[3 * t], &v[3 * t + 1], &v[3 * t + 2], tmin, tmax, &th))
                    want[n].t = th.t, want[n].entering = th.entering, want[n++].index = t;
            }
        qsort(want, (size_t)n, sizeof *want, compare_soup_hits);
        for (int k = 1; k < n; k++) ties += want[k].t == want[k - 1].t;
        hr_hit_args args;
        memset(&args, 0, sizeof args);
        args.shape = soup.shape;
        args.ray = ray;
        args.tmin = tmin;
        args.tmax = tmax;
        args.out = &list;
        list.count = 0;
        int ok = soup.cls->hit(&args) == HR_OK && list.count == n;
        for (int k = 0; k < n && k < list.count; k++)
            ok &= list.hits[k].t == want[k].t && normal_is(list.hits[k].normal, normal[want[k].index]);
        list.count = 0;
        ok &= soup.cls->first_hit(&args) == HR_OK && list.count == (n > 0) &&
              (n == 0 || (list.hits[0].t == want[0].t && normal_is(list.hits[0].normal, normal[want[0].index])));
        list.count = 0;
        /* The any hit (an open mesh's: leaves in any order) is one of the
         * hits, bit for bit. */
        int found = 0;
        ok &= soup.cls->any_hit(&args) == HR_OK && list.count == (n > 0);
        for (int k = 0; k < n && list.count > 0; k++) found |= list.hits[0].t == want[k].t;
        ok &= n == 0 || found;
        if (!ok && failures++ < 10)
            CHECK_MSG(0, "scale %g, ray %d (interval %g, %g): the BVH's hits differ from every "
                         "triangle's %d", scale, i, tmin, tmax, n);
        hits += n;
    }
    CHECK_MSG(failures == 0, "scale %g: %d of %d rays differ", scale, failures, rays);
    CHECK_MSG(hits > rays / 3, "scale %g: only %d hits in all", scale, hits);
    CHECK_MSG(copies > tris / 8 && ties > rays / 50, "scale %g: %d copies, %d exact ties", scale, copies, ties);
    free(list.hits);
    free(v);
    free(want);
    free(normal);
    harness_close(&soup);
}

static void test_bvh_matches_brute_force(void)
{
    soup_matches_brute_force(31, 3000, 3000, 1.0);
    /* Tiny, huge, and past float's range (infinite float boxes); at the
     * walk's culling range (2^64, ACCEL_CULL_RANGE), and coordinates near
     * float's range, up to 10 * 2^124 (below FLT_MAX, 2^128) and across it
     * at 10 * 2^125, where the boxes' float bounds round to FLT_MAX or
     * infinity. */
    const double scales[] = {0x1p-70, 0x1p70, 0x1p130, 0x1p61, 0x1p64, 0x1p124, 0x1p125};
    for (size_t k = 0; k < sizeof scales / sizeof *scales; k++)
        soup_matches_brute_force(77 + k, 1000, HR_TEST_SANITIZED ? 3000 : 30000, scales[k]);
}


/* mesh_triangle_pair_fails (the leaf loop's filter) against the test it
 * stands in front of (lanes it fails, and its agreeing lanes finished by
 * mesh_filter_finish, bit for bit), and the AVX2 filter (where the CPU has
 * it) against it lane for lane: a lane it calls certain to fail must fail
 * mesh_triangle_test_axes over every interval, here the widest ones. Pairs
 * of random triangles around random rays at scales from 2^-60 to 2^60 and
 * 1e-300 to 1e300; pairs sharing an edge that the ray runs through (aimed
 * at a point of it, at a shared vertex exactly, or with axis-parallel rays
 * and triangles in axis planes, where edge functions are exactly zero);
 * degenerate triangles (collinear or repeated corners); non-finite
 * corners. The filter must also reject most random pairs, and the test
 * must hit some lanes the filter let through. */
#if MESH_FILTER_AVX2
/* The four-lane filter has to be called from AVX2 code. */
__attribute__((target("avx2"))) static unsigned quad_fails(const mesh_ray *r, const hr_vec3 *v,
                                                           const uint32_t *const c[4], mesh_lanes *out)
{
    return mesh_triangle_quad_fails(r, v, c, out, r->kx, r->ky, r->kz);
}

/* Whether lane a of x and lane b of y hold the same values, bit for bit. */
static int same_lane(const mesh_lanes *x, int a, const mesh_lanes *y, int b)
{
    for (int k = 0; k < 3; k++)
        if (!same_bits(x->x[k][a], y->x[k][b]) || !same_bits(x->y[k][a], y->y[k][b]) ||
            !same_bits(x->z[k][a], y->z[k][b]) || !same_bits(x->e[k][a], y->e[k][b]))
            return 0;
    return 1;
}
#endif

static void test_pair_filter(void)
{
    ray_rng rng;
    rng_seed(&rng, 77);
    long pairs = 0, filtered = 0, hits = 0, wrong = 0, quads_compared = 0, quads_differing = 0;
    long agreeing = 0, finished_differing = 0;
    const double intervals[3][2] = {{-INFINITY, INFINITY}, {-1e300, 1e300}, {0.0, INFINITY}};
    for (int i = 0; i < 1500000; i++) {
        const int kind = (int)(rng_next(&rng) % 8);
        const double scale = kind == 7 ? (rng_chance(&rng, 0.5) ? 1e300 : 1e-300)
                                       : ldexp(1.0, (int)(rng_next(&rng) % 121) - 60);
        hr_vec3 o = {rng_uniform(&rng, -2, 2) * scale, rng_uniform(&rng, -2, 2) * scale,
                     rng_uniform(&rng, -2, 2) * scale};
        hr_vec3 d = rng_unit_vector(&rng);
        if (kind == 5) { /* along an axis, or in an axis plane */
            if (rng_chance(&rng, 0.5)) d.x = 0.0;
            if (rng_chance(&rng, 0.5)) d.y = rng_chance(&rng, 0.5) ? 0.0 : -0.0;
            if (d.x == 0 && d.y == 0) d.z = rng_chance(&rng, 0.5) ? 1.0 : -1.0;
        }
        /* Six corners: two triangles around the point the ray reaches at
         * t = 1 (its direction at the scale). */
        d.x *= scale, d.y *= scale, d.z *= scale;
        const hr_vec3 at = {o.x + d.x, o.y + d.y, o.z + d.z};
        hr_vec3 v[6];
        for (int k = 0; k < 6; k++)
            v[k] = (hr_vec3){at.x + rng_uniform(&rng, -1, 1) * scale, at.y + rng_uniform(&rng, -1, 1) * scale,
                             at.z + rng_uniform(&rng, -1, 1) * scale};
        uint32_t c[6] = {0, 1, 2, 3, 4, 5};
        if (kind == 1 || kind == 2) { /* a shared edge 1-2, the second wound the other way */
            c[3] = 2, c[4] = 1;
            if (kind == 1) { /* aimed at a point of the edge */
                const double u = rng_uniform(&rng, 0, 1);
                const hr_vec3 e = {v[1].x + u * (v[2].x - v[1].x), v[1].y + u * (v[2].y - v[1].y),
                                   v[1].z + u * (v[2].z - v[1].z)};
                d = (hr_vec3){e.x - o.x, e.y - o.y, e.z - o.z};
            } else { /* through corner 1 exactly: o = v1 - d with d a small power of two per axis */
                d = (hr_vec3){ldexp(1.0, (int)(rng_next(&rng) % 5)) * scale,
                              -ldexp(1.0, (int)(rng_next(&rng) % 5)) * scale, scale};
                o = (hr_vec3){v[1].x - d.x, v[1].y - d.y, v[1].z - d.z};
            }
        }
        if (kind == 3) { /* degenerate: collinear, and a repeated corner */
            v[2] = (hr_vec3){2 * v[1].x - v[0].x, 2 * v[1].y - v[0].y, 2 * v[1].z - v[0].z};
            c[4] = c[3];
        }
        if (kind == 4) { /* a non-finite corner */
            const double bad = rng_chance(&rng, 0.5) ? NAN : rng_chance(&rng, 0.5) ? INFINITY : -INFINITY;
            if (rng_chance(&rng, 0.5)) v[0].x = bad;
            else v[4].z = bad;
        }
        if (kind == 5) { /* triangles in the axis plane through the point */
            for (int k = 0; k < 6; k++) v[k].z = at.z;
        }
        if (kind == 6) { /* sharing corner 0 with the ray through it */
            c[3] = 0;
            o = (hr_vec3){v[0].x - d.x, v[0].y - d.y, v[0].z - d.z};
        }
        mesh_ray r;
        const hr_ray ray = {o, d};
        if (!mesh_ray_init(&r, &ray)) continue;
        const uint32_t *const lanes[2] = {c, c + 3};
        mesh_lanes lanes_at;
        const unsigned fails = mesh_triangle_pair_fails(&r, v, lanes, &lanes_at, r.kx, r.ky, r.kz);
        pairs++;
#if MESH_FILTER_AVX2
        /* The four-lane filter on the two triangles and again swapped:
         * the same answer lane by lane. */
        if (mesh_filter_avx2_usable()) {
            const uint32_t *const four_lanes[4] = {c, c + 3, c + 3, c};
            mesh_lanes quad_at;
            const unsigned four = quad_fails(&r, v, four_lanes, &quad_at);
            /* Agreeing lanes hold the pair filter's values. */
            for (int lane = 0; lane < 4; lane++) {
                const int from = lane == 0 || lane == 3 ? 0 : 1;
                if (four >> (4 + lane) & 1 && fails >> (4 + from) & 1 && !same_lane(&quad_at, lane, &lanes_at, from))
                    quads_differing++;
            }
            const unsigned want = (fails & 1) | (fails & 2) | (fails >> 1 & 1) << 2 | (fails & 1) << 3 |
                                  (fails >> 4 & 3) << 4 | (fails >> 5 & 1) << 6 | (fails >> 4 & 1) << 7;
            quads_compared++;
            if (four != want && quads_differing++ < 5)
                fprintf(stderr, "quad filter: kind %d: %x where the pair filter gives %x\n", kind, four, want);
        }
#endif
        for (int lane = 0; lane < 2; lane++) {
            const uint32_t *t = c + 3 * lane;
            int hit = 0;
            for (int k = 0; k < 3; k++) {
                mesh_triangle_hit th;
                hit |= mesh_triangle_test(&r, &v[t[0]], &v[t[1]], &v[t[2]], intervals[k][0], intervals[k][1], &th);
            }
            hits += hit;
            if (fails >> (4 + lane) & 1) {
                /* An agreeing lane: the rest of the test on the filter's
                 * values, against the whole test, field by field. */
                agreeing++;
                for (int k = 0; k < 3; k++) {
                    mesh_triangle_hit want_th, got_th;
                    memset(&want_th, 0, sizeof want_th), memset(&got_th, 0, sizeof got_th);
                    const int want_hit = mesh_triangle_test(&r, &v[t[0]], &v[t[1]], &v[t[2]], intervals[k][0],
                                                            intervals[k][1], &want_th);
                    int got_hit = mesh_filter_finish(&r, &lanes_at, lane, intervals[k][0], intervals[k][1], &got_th);
                    if (got_hit == MESH_HIT_ASK_PLACE)
                        got_hit = mesh_resolve_place(&r, &v[t[0]], &v[t[1]], &v[t[2]], intervals[k][0]);
                    const int same = want_hit == got_hit &&
                                     (!want_hit || (same_bits(want_th.t, got_th.t) &&
                                                    same_bits(want_th.t_error, got_th.t_error) &&
                                                    same_bits(want_th.b[0], got_th.b[0]) &&
                                                    same_bits(want_th.b[1], got_th.b[1]) &&
                                                    same_bits(want_th.b[2], got_th.b[2]) &&
                                                    want_th.entering == got_th.entering));
                    if (!same && finished_differing++ < 5)
                        fprintf(stderr, "pair filter: kind %d lane %d: the agreeing lane's finish differs\n", kind,
                                lane);
                }
            }
            if (fails >> lane & 1) {
                filtered++;
                if (hit && wrong++ < 5)
                    fprintf(stderr, "pair filter: kind %d lane %d filtered, yet the test hits\n", kind, lane);
            }
        }
    }
    fprintf(stderr, "pair filter: %ld pairs, %ld lanes filtered, %ld lanes hit, %ld wrongly filtered\n", pairs,
            filtered, hits, wrong);
    CHECK(wrong == 0);
    CHECK(filtered > pairs / 2 && hits > pairs / 20);
    fprintf(stderr, "pair filter: %ld agreeing lanes finished, %ld differing from the test\n", agreeing,
            finished_differing);
    CHECK(finished_differing == 0 && agreeing > pairs / 10);
    fprintf(stderr, "quad filter: %ld compared with the pair filter, %ld differing%s\n", quads_compared,
            quads_differing, quads_compared ? "" : " (no AVX2 here)");
    CHECK(quads_differing == 0);
}

int main(void)
{
    char path[1024];
    if (!harness_open(&cube_module, "cube", "cube", NAN)) return hr_test_end() | 1;
    if (!mesh_open_file(&cube_mesh, mesh_data_path("cube.obj", path, sizeof path)))
        return hr_test_end() | 1;
    test_classes();
    test_exact_signs();
    test_exact_signs_at_any_scale();
    test_next_up();
    test_pair_filter();
    test_cube_agrees();
    test_edge_sweeps();
    test_vertices();
    test_edge_crossing_at_zero();
    test_face_plane_t_error_past_doubles();
    test_hill_cube();
    test_hill_tetrahedron();
    test_obj_normals();
    test_solids();
    test_many_hits();
    test_degenerate_bvh();
    test_bvh_matches_brute_force();
    test_thin_closed(1e-17);
    test_thin_closed(1e-16);
    test_thin_closed(1e-15);
    harness_close(&cube_mesh);
    harness_close(&cube_module);
    return hr_test_end();
}
