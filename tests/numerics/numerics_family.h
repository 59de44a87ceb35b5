/* Families of object-space rays compared with the quad-precision
 * references (quad_reference.c), for the catalogue's object-space programs.
 *
 * How one ray is scored (nf_compare_ray):
 * - the hit count, surfaces and entering flags must be the reference's,
 *   unless the ray is within the family's band of a degenerate situation
 *   (a tangency, a seam): there only an even difference (a missed or an
 *   extra touch) is allowed. A wrong count at distance x from the
 *   degeneracy scores x / band, so a count that goes wrong outside the band
 *   fails, and one inside it scores 0;
 * - t within NF_T_FACTOR u * condition of the reference root (the derivation
 *   is test_shape_accuracy.c's: a computed root is the exact root of inputs
 *   perturbed by a few u, which moves it by u * condition to first order),
 *   scored as |t - t_ref| / (NF_T_FACTOR u condition). */
#ifndef HR_TEST_NUMERICS_FAMILY_H
#define HR_TEST_NUMERICS_FAMILY_H

#include "module_harness.h"
#include "numerics_cases.h"
#include "quad_reference.h"
#include "random_rays.h"

#define NF_T_FACTOR 8.0

/* A ray, its distance from the family's degeneracy and the band within
 * which either answer is right. A NaN distance means: use the reference's
 * margin, with the band at least the distance the rounding of t itself
 * moves a crossing by (NF_T_FACTOR u condition |d|, the largest over the
 * roots); `band` can raise it (a near-tangent miss has no root whose
 * condition would say how close it is). */
typedef struct nf_probe {
    hr_ray ray;
    double distance, band;
} nf_probe;

typedef void (*nf_probe_fn)(ray_rng *rng, int i, nf_probe *out);

quad nf_qabs(quad x);

void nf_compare_ray(const harness_shape *s, ref_shape ref, const nf_probe *p, nc_result *out);

/* `rays` probes of `make` on class `cls` of `module` (parameter s: the
 * taper or the tube, NaN for the default), seeded with `seed`. */
void nf_run_family(const char *module, const char *cls, double s, nf_probe_fn make, int rays,
                   uint64_t seed, nc_result *out);

/* Signed zeros: the ray and each copy with some of the zero components of
 * its origin and direction flipped to -0 must give bit-identical hits (t,
 * surface, entering, point), and at least one; scores 0 or infinity per
 * copy. */
void nf_signed_zeros(const harness_shape *s, hr_ray ray, nc_result *out);

#endif
