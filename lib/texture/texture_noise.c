/* Hill's lattice noise and turbulence (chapter 8): pseudo-random values at
 * the integer lattice points, blended smoothly between them.
 *
 * The value at a lattice point is a fixed integer hash of its coordinates
 * (a multiply-xorshift mix of 64 bits), not rand(): the same on every
 * machine, for every thread count, with no table to set up and nothing
 * shared, so a lookup is reentrant. The blend is trilinear with the weights
 * smoothed by 3t^2 - 2t^3, so the noise has no creases at the lattice
 * planes. Every operation is exact or correctly rounded IEEE arithmetic (no
 * libm call), so the noise is the same bits everywhere. */
#include <math.h>
#include <stdint.h>

#include "texture/texture.h"
#include "geometry/vec.h"

/* Lattice coordinates are taken modulo 2^32 (exact in double): past that
 * the noise repeats, and no coordinate overflows the integer conversion. */
#define LATTICE_PERIOD 4294967296.0

static uint64_t mix(uint64_t h)
{
    h ^= h >> 31;
    h *= 0x7fb5d329728ea185u;
    h ^= h >> 27;
    h *= 0x81dadef4bc2dd44du;
    h ^= h >> 33;
    return h;
}

/* In [0, 1): the top 53 bits of the hash. The coordinates are 32-bit, so
 * the corner past cell 2^32 - 1 is cell 0, as the period says. */
static double lattice(uint32_t i, uint32_t j, uint32_t k)
{
    uint64_t h = mix(i + 0x9e3779b97f4a7c15u);
    h = mix(h ^ (j + 0x632be59bd9b4e019u));
    h = mix(h ^ (k + 0x8cb92ba72f3d8dd7u));
    return (double)(h >> 11) * 0x1p-53;
}

/* The lattice cell of x (its low corner, modulo the period) and where x
 * lies in it, in [0, 1). */
static uint32_t cell(double x, double *frac)
{
    /* A coordinate scaled past double's range (the noise scale times a
     * point near 1e308) has no cell: it takes cell 0's corner, not a NaN
     * fraction and an undefined conversion. */
    if (!isfinite(x)) {
        *frac = 0.0;
        return 0;
    }
    double f = floor(x);
    *frac = x - f;
    /* Where x - floor(x) rounds up to 1 (x just below a whole number). */
    if (!(*frac < 1.0)) *frac = 0x1.fffffffffffffp-1;
    double m = fmod(f, LATTICE_PERIOD);
    if (m < 0) m += LATTICE_PERIOD;
    return (uint32_t)m;
}

static double smooth(double t) { return t * t * (3.0 - 2.0 * t); }

double hri_noise(hr_vec3 p)
{
    double fx, fy, fz;
    uint32_t i = cell(p.x, &fx), j = cell(p.y, &fy), k = cell(p.z, &fz);
    const double wx = smooth(fx), wy = smooth(fy), wz = smooth(fz);
    double along_z[2];
    for (int dz = 0; dz < 2; dz++) {
        double along_y[2];
        for (int dy = 0; dy < 2; dy++) {
            double a = lattice(i, j + (uint32_t)dy, k + (uint32_t)dz);
            double b = lattice(i + 1u, j + (uint32_t)dy, k + (uint32_t)dz);
            along_y[dy] = a + wx * (b - a);
        }
        along_z[dz] = along_y[0] + wy * (along_y[1] - along_y[0]);
    }
    double n = along_z[0] + wz * (along_z[1] - along_z[0]);
    /* A convex blend of values in [0, 1) stays in [0, 1) but for rounding. */
    return n < 1.0 ? n : 0x1.fffffffffffffp-1;
}

double hri_turbulence(hr_vec3 p, int32_t octaves)
{
    double sum = 0.0, weight = 0.5, total = 0.0;
    for (int32_t o = 0; o < octaves; o++) {
        sum += weight * hri_noise(p);
        total += weight;
        p = v3_scale(p, 2.0);
        weight *= 0.5;
    }
    return total > 0.0 ? sum / total : 0.0;
}
