/* A watertight ray/triangle test in the style of Woop, Benthin and Wald,
 * "Watertight Ray/Triangle Intersection" (JCGT 2013), in double precision.
 *
 * The ray is moved to the origin, its axes permuted so that its largest
 * direction component is z, and the scene sheared so that the ray becomes
 * the +z axis (mesh_ray_init). Each vertex is transformed by the same
 * arithmetic whichever triangle it belongs to, so two triangles sharing an
 * edge see bit-identical 2D corners; the three 2D edge functions
 * U = cross(C, B), V = cross(A, C), W = cross(B, A) of a shared edge are
 * then exact negatives of each other in the two triangles.
 *
 * Two steps go beyond the paper's test:
 * - Exact signs. Each edge function is computed in double with a bound on
 *   its rounding error; when the value is within that bound (the paper's
 *   "exactly 0" case, widened to every case rounding could get wrong) it is
 *   recomputed exactly with error-free products and a four-term expansion
 *   (Shewchuk's), so its sign is the sign of the exact 2D determinant of
 *   the rounded corners, at every scale: where products would underflow
 *   (corners within about 1e-150 of the ray) or overflow, the factors are
 *   first scaled by powers of two (mesh_exact_difference). Exact signs make the edges of a vertex fan agree with each
 *   other, not only pairwise.
 * - Ties broken by symbolic perturbation. An edge function that is exactly
 *   zero (the ray runs through the edge's line) takes the sign it would have
 *   if the ray were moved by (eps, eps^2) in the sheared plane: sign(X.y -
 *   Y.y), or sign(Y.x - X.x) when those are equal, for F = cross(X, Y). The
 *   same perturbation applies to every triangle, so a ray through an edge
 *   hits exactly one of two triangles that face the same way, and a ray
 *   through a vertex hits exactly one triangle of a fan around it.
 * The triangle is hit when the three (perturbed) signs agree; the hit is
 * entering when they are positive (the geometric normal (B-A) x (C-A)
 * points against the ray). */
#ifndef HITRAY_MESH_TRIANGLE_H
#define HITRAY_MESH_TRIANGLE_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <hitray/common.h>
#include <hitray/shape_kit_cpu.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#define MESH_UNIT_ROUNDOFF (DBL_EPSILON * 0.5)
#define MESH_GAMMA(n) (((n) * MESH_UNIT_ROUNDOFF) / (1.0 - (n) * MESH_UNIT_ROUNDOFF))

/* fmax and fmin as the compiler can inline them (baseline x86-64 makes
 * fmax a libm call, ten of them a hit): the same answer, a NaN operand
 * giving the other operand. */
static inline double mesh_max(double a, double b)
{
    return a > b || b != b ? a : b;
}
static inline double mesh_min(double a, double b)
{
    return a < b || b != b ? a : b;
}

/* nextafter(x, INFINITY) from x's bits, as the compiler can inline it
 * (nextafter is a libm call, made for every hit that narrows a first-hit
 * search): the next double up; -0 and +0 go to the smallest subnormal,
 * -DBL_TRUE_MIN to -0, and +inf and NaN stay as they are. */
static inline double mesh_next_up(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    if ((bits & 0x7fffffffffffffffull) >= 0x7ff0000000000000ull) {
        /* -inf steps to -DBL_MAX; +inf and NaN stay. */
        return bits == 0xfff0000000000000ull ? -DBL_MAX : x;
    }
    if ((bits & 0x7fffffffffffffffull) == 0) return DBL_TRUE_MIN;
    bits += (bits >> 63) ? (uint64_t)-1 : 1;
    memcpy(&x, &bits, sizeof x);
    return x;
}

/* The ray as the test needs it (accel's walk takes the hr_ray). */
typedef struct mesh_ray {
    double o[3], d[3];
    int kx, ky, kz;
    double sx, sy, sz;
} mesh_ray;

/* 0 when the direction is the zero vector (no hit possible). */
static inline int mesh_ray_init(mesh_ray *r, const hr_ray *ray)
{
    r->o[0] = ray->origin.x, r->o[1] = ray->origin.y, r->o[2] = ray->origin.z;
    r->d[0] = ray->dir.x, r->d[1] = ray->dir.y, r->d[2] = ray->dir.z;
    int kz = 0;
    for (int a = 1; a < 3; a++)
        if (fabs(r->d[a]) > fabs(r->d[kz])) kz = a;
    if (r->d[kz] == 0.0) return 0;
    /* The next axes in turn, (kz + 1) % 3 and (kz + 2) % 3, without the
     * divisions (this runs for every query). */
    int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    /* Keep the permutation's handedness once z is flipped by sz < 0. */
    if (r->d[kz] < 0.0) {
        int t = kx;
        kx = ky, ky = t;
    }
    r->kx = kx, r->ky = ky, r->kz = kz;
    r->sx = r->d[kx] / r->d[kz];
    r->sy = r->d[ky] / r->d[kz];
    r->sz = 1.0 / r->d[kz];
    return 1;
}

/* Always inlined where the axes are constants (the leaf loops of
 * mesh_trace.c, one for each order of axes mesh_ray_init can choose), so
 * that a corner's permuted components are registers rather than an array
 * indexed at run time; the arithmetic is the same for any axes. */
#define MESH_AXES_INLINE static inline __attribute__((always_inline))

/* A vertex in the ray's sheared space: x and y, and p[kz] in out[2], which
 * mesh_shear_z turns into z (needed only once the edges agree). kx, ky and
 * kz are the ray's (r->kx, r->ky, r->kz). */
MESH_AXES_INLINE void mesh_shear(const mesh_ray *r, const hr_vec3 *v, double out[3], int kx, int ky,
                                 int kz)
{
    const double p[3] = {v->x - r->o[0], v->y - r->o[1], v->z - r->o[2]};
    out[0] = p[kx] - r->sx * p[kz];
    out[1] = p[ky] - r->sy * p[kz];
    out[2] = p[kz];
}

static inline void mesh_shear_z(const mesh_ray *r, double out[3])
{
    out[2] = r->sz * out[2];
}

static inline double mesh_two_sum(double a, double b, double *error)
{
    double s = a + b;
    double bv = s - a, av = s - bv;
    *error = (a - av) + (b - bv);
    return s;
}

/* a b - c d, exactly rounded in sign: a b = p1 + e1 and c d = p2 + e2
 * exactly (FMA), and the four terms are summed into a non-overlapping
 * expansion h0..h3 of increasing magnitude (Shewchuk's Grow-Expansion).
 * The value returned has the sign of the largest non-zero component, which
 * is the sign of the exact sum, and is zero only when that sum is. Kept
 * out of line: it is the rare path, and inlined it kept the common one
 * (mesh_edge_function) from being inlined into the triangle test. */
/* x and y times the power of two that brings the larger magnitude into
 * [1, 2): exact (a subnormal scaled up loses nothing), and the same factor
 * for both keeps the sign of a b - c d when (x, y) is (a, c), (b, d), (a, d)
 * or (b, c). Returns the exponent the pair was scaled by. */
static inline int mesh_scale_pair(double *x, double *y)
{
    const double big = mesh_max(fabs(*x), fabs(*y));
    if (!(big > 0.0) || !isfinite(big)) return 0;
    const int e = ilogb(big);
    *x = ldexp(*x, -e), *y = ldexp(*y, -e);
    return e;
}

static __attribute__((noinline, unused)) double mesh_exact_difference(double a, double b,
                                                                      double c, double d)
{
    /* The products' error terms (FMA) are exact only where the products
     * neither overflow nor come within 2^53 of the subnormals: corners
     * within 1e-150 of the ray, or a mesh of 1e-300 sized triangles, made
     * the signs of a closed mesh's edges disagree and a ray through it
     * cross one face alone. There the factors are scaled by powers of two
     * first: (a, c) and (b, d) into [1, 2), which leaves one product at
     * least 1 unless a and d are large and b and c small (or the other way
     * round), which (b, c) (or (a, d)) scaled the same way mends. The
     * value returned then has the exact sign and the magnitude of the
     * scaled difference taken back, or the smallest double of that sign
     * where that underflows. */
    const double tiny = 0x1p-900, huge = 0x1p+1000;
    if (isfinite(a) && isfinite(b) && isfinite(c) && isfinite(d) &&
        (!(fabs(a * b) < huge && fabs(c * d) < huge) || (fabs(a * b) < tiny && fabs(c * d) < tiny))) {
        if (a * b == 0.0 && c * d == 0.0 && (a == 0.0 || b == 0.0) && (c == 0.0 || d == 0.0))
            return 0.0;
        int e = mesh_scale_pair(&a, &c) + mesh_scale_pair(&b, &d);
        if (fabs(a * b) < tiny && fabs(c * d) < tiny)
            e += fabs(a) >= 1.0 ? mesh_scale_pair(&b, &c) : mesh_scale_pair(&a, &d);
        const double scaled = mesh_exact_difference(a, b, c, d);
        if (scaled == 0.0) return 0.0;
        const double back = ldexp(scaled, e);
        return back != 0.0 ? back : copysign(DBL_TRUE_MIN, scaled);
    }
    const double p1 = a * b, e1 = fma(a, b, -p1);
    const double p2 = c * d, e2 = fma(c, d, -p2);
    double h0, h1, h2, q;
    q = mesh_two_sum(-p2, p1, &h0);                 /* [h0, q] */
    double r0, r1;
    double q2 = mesh_two_sum(e1, h0, &r0);
    q2 = mesh_two_sum(q2, q, &r1);                  /* [r0, r1, q2] */
    double s0, s1, s2;
    double q3 = mesh_two_sum(-e2, r0, &s0);
    q3 = mesh_two_sum(q3, r1, &s1);
    q3 = mesh_two_sum(q3, q2, &s2);                 /* [s0, s1, s2, q3] */
    h0 = s0, h1 = s1, h2 = s2;
    double top = q3 != 0.0 ? q3 : h2 != 0.0 ? h2 : h1 != 0.0 ? h1 : h0;
    double value = ((h0 + h1) + h2) + q3;
    return (value > 0.0) == (top > 0.0) && value != 0.0 ? value : top;
}

/* a b - c d with the sign of the exact value: the double result when it
 * exceeds its rounding error bound (fl(fl(ab) - fl(cd)) is within
 * gamma(2) (|ab| + |cd|) of the exact value; gamma(3) also covers
 * rounding the bound), otherwise the exact evaluation. */
static inline double mesh_edge_function(double a, double b, double c, double d)
{
    const double ab = a * b, cd = c * d;
    const double e = ab - cd;
    /* The bound is relative: below 2^-960 a product may have lost bits to
     * underflow that no relative bound covers, so the exact path decides. */
    if (fabs(e) > MESH_GAMMA(3) * (fabs(ab) + fabs(cd)) && fabs(e) > 0x1p-960) return e;
    return mesh_exact_difference(a, b, c, d);
}

/* Sign of F = cross(X, Y) at the perturbed ray (eps, eps^2) when F is
 * exactly zero at the ray: F(p) = F(0) + cross(p, X - Y). */
static inline int mesh_tie_sign(const double x[3], const double y[3])
{
    if (x[1] != y[1]) return x[1] > y[1] ? 1 : -1;
    if (x[0] != y[0]) return y[0] > x[0] ? 1 : -1;
    return 0;
}

static inline int mesh_sign_of(double f, const double x[3], const double y[3])
{
    return f > 0.0 ? 1 : f < 0.0 ? -1 : mesh_tie_sign(x, y);
}

/* What the test returns on a hit: t, the barycentric weights of A, B, C
 * (b[0] for A) and whether the ray enters (normal against the ray). */
typedef struct mesh_triangle_hit {
    double t;
    double t_error; /* bound on the rounding error of t (mesh_t_error) */
    double b[3];
    int entering;
} mesh_triangle_hit;

/* A bound on the rounding error of t = T / det, after pbrt-v4's (Pharr,
 * Jakob and Humphreys, "Physically Based Rendering", 4th ed., 6.8.7), with
 * two refinements for far-away triangles:
 * - a sheared x' = p[kx] - sx p[kz] is off by gamma(5) (|x'| + 2 |sx p[kz]|)
 *   at most, and sx p[kz] = d[kx] z', so the bound uses |d[kx]| |z'|
 *   where pbrt uses |z'| (for a ray along an axis the shear adds nothing);
 * - t = sum b_i z_i with weights b_i = U_i / det that sum to one, so errors
 *   in the edge functions move t by at most their relative size times the
 *   spread of the z_i (the triangle's depth along the ray), not times
 *   max |z_i|.
 * A hit within this of tmin may really lie before it; it is refused, as pbrt
 * refuses hits that may lie behind the origin, so a ray that starts on the
 * mesh does not find the triangle it starts on.
 * Always inlined: every triangle the ray crosses inside the interval needs
 * it, and GCC kept it a call from the six leaf loops of mesh_trace.c (what
 * the call cost: bench/results/RESULTS.md, "mesh_t_error always inlined"). */
static inline __attribute__((always_inline)) double mesh_t_error(const mesh_ray *r, const double A[3],
                                                                 const double B[3], const double C[3],
                                                                 double U, double V, double W,
                                                                 double det)
{
    const double max_z = mesh_max(fabs(A[2]), mesh_max(fabs(B[2]), fabs(C[2])));
    const double spread_z = mesh_max(A[2], mesh_max(B[2], C[2])) - mesh_min(A[2], mesh_min(B[2], C[2]));
    const double max_x = mesh_max(fabs(A[0]), mesh_max(fabs(B[0]), fabs(C[0])));
    const double max_y = mesh_max(fabs(A[1]), mesh_max(fabs(B[1]), fabs(C[1])));
    const double delta_z = MESH_GAMMA(3) * max_z;
    /* |d| max_z first: it is |sx p[kz]|, a sheared size; doubling |d|
     * first overflowed for a direction near DBL_MAX, and inf * 0 made the
     * bound NaN. */
    const double delta_x = MESH_GAMMA(5) * (max_x + 2.0 * (fabs(r->d[r->kx]) * max_z));
    const double delta_y = MESH_GAMMA(5) * (max_y + 2.0 * (fabs(r->d[r->ky]) * max_z));
    const double delta_e =
        2.0 * (MESH_GAMMA(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
    const double max_e = mesh_max(fabs(U), mesh_max(fabs(V), fabs(W)));
    const double bound =
        3.0 * (MESH_GAMMA(3) * max_e * max_z + 2.0 * delta_e * spread_z + delta_z * max_e) / fabs(det);
    /* A bound past the doubles' range says that t may lie anywhere; as
     * +inf it also refused the crossing for lying "within its error" of a
     * tmin of -inf (t - tmin = +inf), where nothing lies before: a closed
     * mesh's whole line lost one crossing of a pair (a ray in the plane of
     * a face, det 5e-24 against sheared corners 1e300 deep: a fuzz input).
     * So it is the largest double, which every finite distance to a finite
     * tmin stays within. */
    return bound == INFINITY ? DBL_MAX : bound;
}

/* A lower bound on the exact t of a crossing from the sheared depths of
 * the corners alone: t is a weighted mean of the exact depths (the weights
 * are the barycentric ones, which sum to one), each computed depth lies
 * within delta_z = gamma(3) max_z of its exact value (mesh_t_error), and
 * twice that, with 2^-1073 for a depth that underflowed, covers the
 * rounding of the difference. Where the ray runs nearly in the triangle's
 * plane its t error is as long as the triangle, yet the crossing still
 * lies in the triangle: a ray 3 units from an octahedron's face, in its
 * plane, crossed it at t = 3.53 with a t error of 367, and the rule "within
 * its t error of tmin = 0" alone refused that entering crossing while
 * keeping its leaving pair (a fuzz input). The depths are finite wherever
 * t is (each enters T, and 0 times an infinite one is NaN). */
static inline __attribute__((always_inline)) double mesh_depth_least(const double A[3], const double B[3],
                                                                     const double C[3])
{
    const double max_z = mesh_max(fabs(A[2]), mesh_max(fabs(B[2]), fabs(C[2])));
    const double min_z = mesh_min(A[2], mesh_min(B[2], C[2]));
    return min_z - (2.0 * (MESH_GAMMA(3) * max_z) + 0x1p-1073);
}

/* A lower bound on the exact t of a crossing from where the line runs
 * over the triangle: the crossing point lies in the triangle, so it lies on
 * the inner side of each edge within the triangle's plane, and a line that
 * runs nearly in that plane (where t's error bound is as long as the
 * triangle) is over the triangle only for a well-conditioned stretch of t.
 * For corners p relative to the origin (as the test translates them), edge
 * k from q to q' and n = (p1 - p0) x (p2 - p0), m = n x (q' - q) points
 * into the triangle in its plane, and a point t d of the line is on m's
 * side where t (m.d) >= m.q: with m.d > 0, t >= m.q / m.d. Each such edge
 * bounds t from below; where the line meets the plane at a steep angle, m.d
 * is small against its error and the edge says nothing (the t error is
 * small there). Error bounds, generously: with M the largest |corner
 * coordinate| and D the largest |direction component|, the coordinates of
 * n, m are at most 8 M^2, 32 M^3, so |m.q| <= 96 M^4 and |m.d| <= 96 M^3 D;
 * the corners' translation (u M each, u = 2^-53) and some twenty
 * roundings move them by less than 2^-41 M^4 and 2^-41 M^3 D. Outside
 * 2^-200 <= M, D <= 2^200 the powers could leave the doubles' range: no
 * bound (-inf). A ray in the plane of an octahedron's face, whose line
 * runs over the face from t = 3.53 to 3.75 but whose corners lie at depths
 * 1.75 to 3.75, crossed it at 3.53 with a t error of 367: from tmin =
 * 2.96 the depths allowed a crossing before tmin, and the pair was split
 * again (a fuzz input). */
static inline double mesh_prism_least(const mesh_ray *r, const hr_vec3 *a, const hr_vec3 *b, const hr_vec3 *c)
{
    const hr_vec3 *v[3] = {a, b, c};
    double p[3][3];
    double big = 0.0;
    for (int i = 0; i < 3; i++) {
        p[i][0] = v[i]->x - r->o[0], p[i][1] = v[i]->y - r->o[1], p[i][2] = v[i]->z - r->o[2];
        for (int k = 0; k < 3; k++) big = mesh_max(big, fabs(p[i][k]));
    }
    const double speed = mesh_max(fabs(r->d[0]), mesh_max(fabs(r->d[1]), fabs(r->d[2])));
    if (!(big >= 0x1p-200 && big <= 0x1p200 && speed >= 0x1p-200 && speed <= 0x1p200)) return -INFINITY;
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double big3 = big * big * big;
    const double error_q = 0x1p-41 * big3 * big, error_d = 0x1p-41 * big3 * speed;
    double least = -INFINITY;
    for (int k = 0; k < 3; k++) {
        const double *q = p[k], *q2 = p[k == 2 ? 0 : k + 1];
        const double e[3] = {q2[0] - q[0], q2[1] - q[1], q2[2] - q[2]};
        const double m[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
        const double md = m[0] * r->d[0] + m[1] * r->d[1] + m[2] * r->d[2];
        if (!(md > error_d)) continue;
        const double mq = m[0] * q[0] + m[1] * q[1] + m[2] * q[2];
        /* The least of (m.q)/(m.d) over both within their errors, less
         * two roundings of the division. */
        const double top = mq - error_q;
        const double bound = top / (top >= 0.0 ? md + error_d : md - error_d);
        const double below = bound - fabs(bound) * 0x1p-50;
        if (below > least) least = below;
    }
    return least;
}

/* What mesh_triangle_finish answers for a crossing within its t error of
 * tmin whose place, the corners' depths, does not clear tmin, where the
 * stretch of the line over the triangle (mesh_prism_least) may: the hit
 * is filled in, and the caller, who has the corners, decides
 * (mesh_resolve_place). The stretch costs some sixty operations, and a
 * ray leaving the triangle it starts on (every shadow and reflected ray
 * meets its own triangle so) would pay them for nothing: it is asked only
 * where t lies more than 2^-40 of the triangle's depth past tmin, which a
 * crossing a rounding from the ray's start does not. (The corners passed
 * down into the finish instead cost the gears render 1.1% more
 * instructions.) */
#define MESH_HIT_ASK_PLACE 2

/* The place part of mesh_hit_past on the sheared corners A, B, C: 1 where
 * their depths clear tmin, MESH_HIT_ASK_PLACE where the stretch may, else
 * 0. */
static inline int mesh_place_clears(const double A[3], const double B[3], const double C[3], double t, double tmin)
{
    if (mesh_depth_least(A, B, C) > tmin) return 1;
    const double spread = mesh_max(A[2], mesh_max(B[2], C[2])) - mesh_min(A[2], mesh_min(B[2], C[2]));
    return t - tmin > 0x1p-40 * spread ? MESH_HIT_ASK_PLACE : 0;
}

/* A test's answer with MESH_HIT_ASK_PLACE decided on triangle (a, b, c):
 * 0 or 1. Out of line and cold: it is rare. */
static __attribute__((noinline, cold, unused)) int mesh_resolve_place(const mesh_ray *r, const hr_vec3 *a,
                                                                       const hr_vec3 *b, const hr_vec3 *c,
                                                                       double tmin)
{
    return mesh_prism_least(r, a, b, c) > tmin;
}

/* Whether a hit of triangle (a, b, c) at t with t error t_error lies past
 * tmin: by more than its t error, or wherever in its triangle it lies
 * (mesh_place_clears, then mesh_resolve_place). The one rule for tmin, in the test
 * (mesh_triangle_finish, on the depths it has) and in the marks of
 * mesh_trace.c, which shear the corners again as the test does (the same
 * operations, so the same depths); needed only within the t error, which
 * is rare. */
static inline int mesh_hit_past(const mesh_ray *r, const hr_vec3 *a, const hr_vec3 *b, const hr_vec3 *c,
                                double t, double t_error, double tmin)
{
    if (!(t - tmin <= t_error)) return 1;
    double A[3], B[3], C[3];
    mesh_shear(r, a, A, r->kx, r->ky, r->kz);
    mesh_shear(r, b, B, r->kx, r->ky, r->kz);
    mesh_shear(r, c, C, r->kx, r->ky, r->kz);
    mesh_shear_z(r, A);
    mesh_shear_z(r, B);
    mesh_shear_z(r, C);
    const int place = mesh_place_clears(A, B, C, t, tmin);
    return place == MESH_HIT_ASK_PLACE ? mesh_resolve_place(r, a, b, c, tmin) : place;
}

/* The test's last steps, once the edge functions U, V, W of the sheared
 * corners A, B, C (x, y and p[kz], see mesh_shear) agree in sign: depth, t
 * and its error, the weights. One piece of code for the scalar test and
 * for the filters' agreeing lanes (mesh_filter_finish). */
static inline __attribute__((always_inline)) int
mesh_triangle_finish(const mesh_ray *r, double A[3], double B[3], double C[3], double U, double V, double W,
                     double tmin, double tmax, mesh_triangle_hit *out)
{
    mesh_shear_z(r, A);
    mesh_shear_z(r, B);
    mesh_shear_z(r, C);
    /* t and the weights depend on U, V, W only through their ratios: where
     * all three are tiny (the exact path's smallest double of a sign, for a
     * corner within 1e-150 of the ray) they are scaled up by one power of
     * two first, so that T does not underflow to a t of 0. */
    const double max_uvw = mesh_max(fabs(U), mesh_max(fabs(V), fabs(W)));
    if (max_uvw < 0x1p-900 && max_uvw > 0.0) {
        const int e = ilogb(max_uvw);
        U = ldexp(U, -e), V = ldexp(V, -e), W = ldexp(W, -e);
    }
    /* Same signs (zeros count as either): the sum is zero only when all
     * three are, a triangle seen edge on. */
    const double det = U + V + W;
    if (det == 0.0) return 0;
    const double T = U * A[2] + V * B[2] + W * C[2];
    const double t = T / det;
    if (!(t > tmin && t < tmax)) return 0;
    const double t_error = mesh_t_error(r, A, B, C, U, V, W, det);
    /* mesh_hit_past, on the depths at hand. */
    int answer = 1;
    if (__builtin_expect(t - tmin <= t_error, 0) && !(answer = mesh_place_clears(A, B, C, t, tmin))) return 0;
    out->t = t;
    out->t_error = t_error;
    out->b[0] = U / det;
    out->b[1] = V / det;
    out->b[2] = W / det;
    out->entering = det > 0.0;
    return answer;
}

/* The watertight test of triangle (A, B, C) against the ray, for hits
 * with tmin < t < tmax, with the ray's axes (r->kx, r->ky, r->kz) given:
 * see MESH_AXES_INLINE. */
MESH_AXES_INLINE int mesh_triangle_test_axes(const mesh_ray *r, const hr_vec3 *a, const hr_vec3 *b,
                                             const hr_vec3 *c, double tmin, double tmax,
                                             mesh_triangle_hit *out, int kx, int ky, int kz)
{
    /* Each corner and edge function only when the edges before agree
     * (most triangles a ray is tested against lie beside it); the edge
     * signs need x and y alone. */
    double A[3], B[3], C[3];
    mesh_shear(r, b, B, kx, ky, kz);
    mesh_shear(r, c, C, kx, ky, kz);
    const double U = mesh_edge_function(C[0], B[1], C[1], B[0]);
    const int su = mesh_sign_of(U, C, B);
    if (su == 0) return 0;
    mesh_shear(r, a, A, kx, ky, kz);
    const double V = mesh_edge_function(A[0], C[1], A[1], C[0]);
    if (mesh_sign_of(V, A, C) != su) return 0;
    const double W = mesh_edge_function(B[0], A[1], B[1], A[0]);
    if (mesh_sign_of(W, B, A) != su) return 0;
    const int answer = mesh_triangle_finish(r, A, B, C, U, V, W, tmin, tmax, out);
    return __builtin_expect(answer == MESH_HIT_ASK_PLACE, 0) ? mesh_resolve_place(r, a, b, c, tmin) : answer;
}

/* A filter's agreeing lanes (bit 4 + k of its answer), lane k: the
 * sheared corners A, B, C (x, y, p[kz]) and U, V, W, for mesh_filter_finish. */
typedef struct mesh_lanes {
    double x[3][4], y[3][4], z[3][4], e[3][4];
} mesh_lanes;

/* mesh_triangle_test_axes's answer for agreeing lane k: the rest of the
 * test on the lane's values, which are the scalar test's; or
 * MESH_HIT_ASK_PLACE, for the caller to decide on the lane's triangle
 * (mesh_resolve_place). */
static inline __attribute__((always_inline)) int mesh_filter_finish(const mesh_ray *r, const mesh_lanes *l, int k,
                                                                    double tmin, double tmax,
                                                                    mesh_triangle_hit *out)
{
    double A[3] = {l->x[0][k], l->y[0][k], l->z[0][k]};
    double B[3] = {l->x[1][k], l->y[1][k], l->z[1][k]};
    double C[3] = {l->x[2][k], l->y[2][k], l->z[2][k]};
    return mesh_triangle_finish(r, A, B, C, l->e[0][k], l->e[1][k], l->e[2][k], tmin, tmax, out);
}

/* Two or four triangles' first steps at once, as a filter in front of the
 * test, triangle k having corners c[k][0], c[k][1], c[k][2] into v. In
 * SSE2 lanes (two triangles) or AVX2 lanes (four, mesh_triangle_quad_fails,
 * for CPUs that have AVX2, chosen at run time) the test's own operations
 * in its order (the shear of each corner, and the three edge functions'
 * products, difference and error bound; no FMA in any), so each lane
 * holds the scalar path's values bit for bit. A lane whose three
 * differences all exceed their bounds (and 2^-960) has them as mesh_edge_function's
 * results (no tie and no exact evaluation); then
 * - if their signs do not all agree, the scalar test returns 0 at the
 *   first edge that disagrees: bit k, certain to fail;
 * - if they agree, the scalar test goes on to mesh_triangle_finish with
 *   these values: bit 4 + k, the lane's values in *out (when out is not
 *   NULL) for mesh_filter_finish.
 * Any other lane (a bound not passed, a NaN) is the test's from the start.
 * The edges and corners the scalar test would not reach are worked out
 * too: a few wasted operations against one corner's loads and shears for
 * several triangles. Without SSE2: 0, every lane the test's.
 * test_shape_mesh compares both filters with the test, bit for bit.
 *
 * One body for both widths: MESH_FILTER_BODY(P), over the vector type
 * P##VT and its operations P##SET1, SUB, MUL, ADD, MAX, AND, ANDNOT, OR, XOR,
 * GT, MASK, STORE and ABS_MASK, and P##LOAD(k, field), the field of corner
 * k of every lane: MESH_SSE2_ and MESH_AVX2_. */
#define MESH_FILTER_BODY(P)                                                                         \
    const P##VT o_[3] = {P##SET1(r->o[0]), P##SET1(r->o[1]), P##SET1(r->o[2])};                   \
    const P##VT sx_ = P##SET1(r->sx), sy_ = P##SET1(r->sy);                                        \
    /* Corner k of every triangle sheared (mesh_shear), written out corner                         \
     * by corner so that all stay in registers. */                                                 \
    P##VT x_[3], y_[3], z_[3];                                                                     \
    MESH_FILTER_CORNER(P, 0);                                                                      \
    MESH_FILTER_CORNER(P, 1);                                                                      \
    MESH_FILTER_CORNER(P, 2);                                                                      \
    const P##VT abs_ = P##ABS_MASK, gamma3_ = P##SET1(MESH_GAMMA(3)), zero_ = P##SET1(0.0);        \
    P##VT u_, v_, w_, clean_u, pos_u, clean_v, pos_v, clean_w, pos_w;                              \
    MESH_FILTER_EDGE(P, x_[2], y_[1], y_[2], x_[1], u_, clean_u, pos_u); /* U = cross(C, B) */     \
    MESH_FILTER_EDGE(P, x_[0], y_[2], y_[0], x_[2], v_, clean_v, pos_v); /* V = cross(A, C) */     \
    MESH_FILTER_EDGE(P, x_[1], y_[0], y_[1], x_[0], w_, clean_w, pos_w); /* W = cross(B, A) */     \
    const P##VT clean_ = P##AND(clean_u, P##AND(clean_v, clean_w));                                \
    const P##VT differ_ = P##OR(P##XOR(pos_u, pos_v), P##XOR(pos_u, pos_w));                       \
    const unsigned agrees_ = (unsigned)P##MASK(P##ANDNOT(differ_, clean_));                        \
    if (agrees_ && out) {                                                                          \
        for (int k_ = 0; k_ < 3; k_++) {                                                           \
            P##STORE(out->x[k_], x_[k_]), P##STORE(out->y[k_], y_[k_]), P##STORE(out->z[k_], z_[k_]); \
        }                                                                                          \
        P##STORE(out->e[0], u_), P##STORE(out->e[1], v_), P##STORE(out->e[2], w_);                 \
    }                                                                                              \
    return (unsigned)P##MASK(P##AND(clean_, differ_)) | agrees_ << 4;
#define MESH_FILTER_CORNER(P, k)                                                                    \
    do {                                                                                           \
        const P##VT p_[3] = {P##SUB(P##LOAD(k, x), o_[0]), P##SUB(P##LOAD(k, y), o_[1]),           \
                             P##SUB(P##LOAD(k, z), o_[2])};                                        \
        x_[k] = P##SUB(p_[kx], P##MUL(sx_, p_[kz]));                                               \
        y_[k] = P##SUB(p_[ky], P##MUL(sy_, p_[kz]));                                               \
        z_[k] = p_[kz];                                                                            \
    } while (0)
/* mesh_edge_function(a, b, c, d): the difference, and whether it passes
 * its bound; then its sign. */
#define MESH_FILTER_EDGE(P, a, b, c, d, e_, clean, positive)                                        \
    do {                                                                                           \
        const P##VT ab_ = P##MUL(a, b), cd_ = P##MUL(c, d);                                        \
        e_ = P##SUB(ab_, cd_);                                                                     \
        const P##VT bound_ = P##MAX(P##SET1(0x1p-960),                                             \
                                    P##MUL(gamma3_, P##ADD(P##AND(ab_, abs_), P##AND(cd_, abs_)))); \
        clean = P##GT(P##AND(e_, abs_), bound_);                                                   \
        positive = P##GT(e_, zero_);                                                               \
    } while (0)

#if defined(__SSE2__)
#define MESH_SSE2_VT __m128d
#define MESH_SSE2_SET1 _mm_set1_pd
#define MESH_SSE2_SUB _mm_sub_pd
#define MESH_SSE2_MUL _mm_mul_pd
#define MESH_SSE2_ADD _mm_add_pd
#define MESH_SSE2_MAX _mm_max_pd
#define MESH_SSE2_AND _mm_and_pd
#define MESH_SSE2_ANDNOT _mm_andnot_pd
#define MESH_SSE2_STORE _mm_storeu_pd
#define MESH_SSE2_OR _mm_or_pd
#define MESH_SSE2_XOR _mm_xor_pd
#define MESH_SSE2_GT _mm_cmpgt_pd
#define MESH_SSE2_MASK _mm_movemask_pd
#define MESH_SSE2_ABS_MASK _mm_castsi128_pd(_mm_set1_epi64x(INT64_MAX))
#define MESH_SSE2_LOAD(k, f) _mm_loadh_pd(_mm_load_sd(&v[c[0][k]].f), &v[c[1][k]].f)
#endif

MESH_AXES_INLINE unsigned mesh_triangle_pair_fails(const mesh_ray *r, const hr_vec3 *v, const uint32_t *const c[2],
                                                   mesh_lanes *out, int kx, int ky, int kz)
{
#if defined(__SSE2__)
    MESH_FILTER_BODY(MESH_SSE2_)
#else
    (void)r, (void)v, (void)c, (void)out, (void)kx, (void)ky, (void)kz;
    return 0;
#endif
}

#if defined(__SSE2__) && defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define MESH_FILTER_AVX2 1
#include <immintrin.h>
#define MESH_AVX2_VT __m256d
#define MESH_AVX2_SET1 _mm256_set1_pd
#define MESH_AVX2_SUB _mm256_sub_pd
#define MESH_AVX2_MUL _mm256_mul_pd
#define MESH_AVX2_ADD _mm256_add_pd
#define MESH_AVX2_MAX _mm256_max_pd
#define MESH_AVX2_AND _mm256_and_pd
#define MESH_AVX2_ANDNOT _mm256_andnot_pd
#define MESH_AVX2_STORE _mm256_storeu_pd
#define MESH_AVX2_OR _mm256_or_pd
#define MESH_AVX2_XOR _mm256_xor_pd
#define MESH_AVX2_GT(a, b) _mm256_cmp_pd(a, b, _CMP_GT_OQ) /* false on NaN, as SSE2's cmpgt */
#define MESH_AVX2_MASK _mm256_movemask_pd
#define MESH_AVX2_ABS_MASK _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX))
#define MESH_AVX2_LOAD(k, f)                                                                         \
    _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadh_pd(_mm_load_sd(&v[c[0][k]].f), &v[c[1][k]].f)), \
                         _mm_loadh_pd(_mm_load_sd(&v[c[2][k]].f), &v[c[3][k]].f), 1)
/* Four lanes. Always inlined, so callable from AVX2 code only
 * (__attribute__((target("avx2"))), after mesh_filter_avx2_usable). */
__attribute__((target("avx2"))) static inline __attribute__((always_inline)) unsigned
mesh_triangle_quad_fails(const mesh_ray *r, const hr_vec3 *v, const uint32_t *const c[4], mesh_lanes *out, int kx,
                         int ky, int kz)
{
    MESH_FILTER_BODY(MESH_AVX2_)
}
/* A load and a test after the first call (shape_kit_cpu.h). */
static inline int mesh_filter_avx2_usable(void) { return shape_cpu_has_avx2(); }
#else
#define MESH_FILTER_AVX2 0
#endif

/* The same with the ray's own axes. */
static inline int mesh_triangle_test(const mesh_ray *r, const hr_vec3 *a, const hr_vec3 *b,
                                     const hr_vec3 *c, double tmin, double tmax,
                                     mesh_triangle_hit *out)
{
    return mesh_triangle_test_axes(r, a, b, c, tmin, tmax, out, r->kx, r->ky, r->kz);
}

#endif
