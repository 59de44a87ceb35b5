/* transformed_bounds, the class entry that bounds a shape under an affine
 * map tighter than the map of its object-space box, for the classes that
 * have it (sphere, cylinder, cone, taperedCylinder, openTaperedCylinder):
 * under random
 * rotations, non-uniform scales and shears, at scales from 1e-6 to 1e6 and
 * a million units away,
 * - the box holds the mapped shape: points sampled densely on the surface
 *   (the wall, both end disks' rims, the sphere), mapped in __float128, lie
 *   inside it;
 * - the box is tight: no wider, per side, than the exact box of the mapped
 *   shape (computed in __float128 from the same formulas: an ellipsoid's
 *   reach is the row norm, a disk's the norm of the row's first two terms)
 *   by more than 64 ulps of the magnitudes involved, where the mapped
 *   corners of the object box are up to sqrt(2) (a disk) or sqrt(3) (the
 *   sphere) times wider. */
#include <float.h>
#include <math.h>
#include <quadmath.h>
#include <stdint.h>
#include <stdio.h>

#include "hr_test.h"
#include "module_harness.h"

typedef __float128 quad;

static uint64_t seed = 77;
static double uniform(void)
{
    seed ^= seed >> 12, seed ^= seed << 25, seed ^= seed >> 27;
    return (double)((seed * 2685821657736338717ull) >> 11) * 0x1p-53;
}
static double between(double a, double b) { return a + (b - a) * uniform(); }

/* A random affine map: a random linear part (rotation-like, scaled and
 * sheared) of size `scale`, translated by up to `offset`. */
static void random_map(double m[16], double scale, double offset)
{
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) m[4 * i + j] = scale * between(-1, 1);
        m[4 * i + 3] = offset * between(-1, 1);
    }
    m[12] = m[13] = m[14] = 0, m[15] = 1;
}

static void map_point(const double m[16], const quad p[3], quad out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + (quad)m[4 * i + 3];
}

/* The surface point of parameters (u, v) in [0, 1)^2: the sphere, or for
 * the tapered family (radius 1 at z = 0, s at z = 1) the wall and the two
 * rims. */
static void surface_point(int sphere, double s, double u, double v, int which, quad p[3])
{
    const quad a = 2 * M_PIq * u;
    if (sphere) {
        const quad z = 2 * (quad)v - 1, r = sqrtq(1 - z * z);
        p[0] = r * cosq(a), p[1] = r * sinq(a), p[2] = z;
        return;
    }
    const quad z = which == 0 ? (quad)v : which == 1 ? 0 : 1;
    const quad r = 1 + (s - 1) * z;
    p[0] = r * cosq(a), p[1] = r * sinq(a), p[2] = z;
}

static int run_class(const harness_module *mod, const char *name, int sphere, double s)
{
    const hr_shape_class *cls = harness_find_class(mod, name);
    CHECK_MSG(cls && HR_CLASS_HAS(cls, transformed_bounds) && cls->transformed_bounds,
              "%s: no transformed_bounds", name);
    if (!cls || !cls->transformed_bounds) return 0;
    char error[256];
    void *shape = NULL;
    const char *names[] = {"s"};
    const double values[] = {s};
    CHECK(harness_create(cls, names, values, cls->param_count > 0 ? 1 : 0, &shape, error,
                         sizeof error) == HR_OK);
    /* The surface sampled once: a 100 x 50 grid on the sphere or the wall,
     * 400 points on each rim. */
    enum { GRID_U = 100, GRID_V = 50, RIM = 400 };
    static quad points[GRID_U * GRID_V + 2 * RIM][3];
    int n = 0;
    for (int iu = 0; iu < GRID_U; iu++)
        for (int iv = 0; iv < GRID_V; iv++)
            surface_point(sphere, s, (iu + 0.5) / GRID_U, iv / (GRID_V - 1.0), 0, points[n++]);
    for (int which = 1; !sphere && which <= 2; which++)
        for (int iu = 0; iu < RIM; iu++) surface_point(sphere, s, (iu + 0.5) / RIM, 0, which, points[n++]);
    int outside = 0, loose = 0;
    const double scales[] = {1e-6, 1.0, 1e6}, offsets[] = {0.0, 10.0, 1e6};
    for (int sc = 0; sc < 3; sc++)
        for (int of = 0; of < 3; of++)
            for (int trial = 0; trial < 20; trial++) {
                double m[16];
                random_map(m, scales[sc], offsets[of] * (of == 2 ? 1.0 : scales[sc]));
                hr_bounds b;
                cls->transformed_bounds(shape, m, &b);
                const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
                for (int k = 0; k < n; k++) {
                    quad q[3];
                    map_point(m, points[k], q);
                    for (int i = 0; i < 3; i++) outside += q[i] < lo[i] || q[i] > hi[i];
                }
                /* Tightness against the exact box. */
                for (int i = 0; i < 3; i++) {
                    const double *row = m + 4 * i;
                    quad exact_lo, exact_hi, mag;
                    if (sphere) {
                        quad reach = sqrtq((quad)row[0] * row[0] + (quad)row[1] * row[1] +
                                           (quad)row[2] * row[2]);
                        exact_lo = row[3] - reach, exact_hi = row[3] + reach;
                        mag = fabsq(row[3]) + reach;
                    } else {
                        quad reach = sqrtq((quad)row[0] * row[0] + (quad)row[1] * row[1]);
                        quad base = row[3], cap = (quad)row[2] + row[3];
                        exact_lo = fminq(base - reach, cap - s * reach);
                        exact_hi = fmaxq(base + reach, cap + s * reach);
                        mag = fabsq(row[2]) + fabsq(row[3]) + (1 + s) * reach;
                    }
                    const quad allowed = 64 * DBL_EPSILON * mag;
                    loose += exact_lo - lo[i] > allowed || hi[i] - exact_hi > allowed;
                    outside += lo[i] > exact_lo || hi[i] < exact_hi;
                }
            }
    fprintf(stderr, "%s (s = %g): %d coordinates outside, %d sides loose\n", name, s, outside, loose);
    CHECK_MSG(outside == 0, "%s: %d mapped surface coordinates outside the box", name, outside);
    CHECK_MSG(loose == 0, "%s: %d sides looser than 64 ulps", name, loose);
    cls->destroy(shape);
    return 1;
}

int main(void)
{
    harness_module sphere, cylinder;
    if (harness_load("sphere", &sphere)) {
        run_class(&sphere, "sphere", 1, 0);
        harness_unload(&sphere);
    }
    if (harness_load("cylinder", &cylinder)) {
        run_class(&cylinder, "cylinder", 0, 1.0);
        run_class(&cylinder, "cone", 0, 0.0);
        run_class(&cylinder, "taperedCylinder", 0, 0.3);
        run_class(&cylinder, "taperedCylinder", 0, 4.0);
        run_class(&cylinder, "openTaperedCylinder", 0, 0.5);
        harness_unload(&cylinder);
    }
    return hr_test_end();
}
