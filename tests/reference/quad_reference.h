/* Reference answers for the built-in shapes, computed in quad precision
 * (__float128, 113-bit significand, libquadmath) from the same double
 * inputs the modules get (the torus's quartic is solved by Sturm sequences in
 * quad, see quad_poly.h). Independent of the modules' code on purpose: each
 * surface patch is intersected on its own with the textbook formulas (which
 * quad precision makes accurate enough here; see quad_reference.c), where the
 * modules intersect spans.
 *
 * Products of two doubles are exact in quad (53 + 53 < 113 bits), so the
 * reference coefficients carry no error worth counting for the rays tested
 * (origins up to 1e6 away: the textbook discriminant then cancels about 40
 * of quad's 113 bits, leaving over 70, well beyond double's 53). */
#ifndef HR_TEST_QUAD_REFERENCE_H
#define HR_TEST_QUAD_REFERENCE_H

#include <hitray/common.h>

typedef __float128 quad;

#define REF_SPHERE 0
#define REF_PLANE 1
#define REF_SQUARE 2
#define REF_CUBE 3
#define REF_TAPERED 4 /* cylinder (s = 1), cone (s = 0), taperedCylinder */
#define REF_TORUS 5   /* s is the tube radius (0.2 for NaN) */
/* taperedTube: REF_TAPERED's frustum less the coaxial hole of radius
 * (1 - t) + (s - 1) z; surfaces 0 wall, 1 base annulus, 2 cap annulus,
 * 3 inner wall */
#define REF_TUBE 6

typedef struct ref_shape {
    int kind;
    double s; /* REF_TAPERED, REF_TUBE: radius at z = 1 */
    double t; /* REF_TUBE: the wall's thickness */
} ref_shape;

/* The reference shape of a class name ("cylinder" is s = 1, "cone" s = 0;
 * "taperedCylinder" takes `s`, "taperedTube" `s` and `t`). */
ref_shape ref_shape_of(const char *class_name, double s, double t);

typedef struct ref_hit {
    quad t;
    int surface;
    int entering;
    /* How sensitive t is to rounding: the exact root moves by at most about
     * u * condition when every input (origin, direction and, for the
     * tapered wall, the radius terms) is perturbed by a relative u (the unit
     * roundoff). |t| for a flat face; for a quadric
     * |t| + (sum_i |p_i| (|o_i| + |t d_i|) + |w| (|w0| + |omega t|)) / sqrt(disc),
     * the first-order change of Q over its slope |Q'(t)| = 2 sqrt(disc). */
    quad condition;
} ref_hit;

typedef struct ref_trace {
    int count;
    ref_hit hits[8];
    /* Smallest distance (object-space length) from any crossing, valid or
     * not, to a situation where rounding may rightly change the answer: a
     * patch edge or seam, a tangency (chord length), a grazing angle, two
     * crossings at nearly the same place. Compare only rays with a margin
     * above the rounding noise. */
    double margin;
} ref_trace;

/* Every crossing of the exact line origin + t dir (all t) with the shape's
 * surfaces, sorted by t, with entering flags from the direction against
 * the outward normal. */
void ref_trace_ray(ref_shape shape, hr_ray ray, ref_trace *out);

/* The same for a line given in quad precision (an object-space ray a test
 * carried through a transform itself, without rounding it to double). */
void ref_trace_quad_ray(ref_shape shape, const quad origin[3], const quad dir[3], ref_trace *out);

/* Euclidean distance from p to the given surface patch of the shape. */
double ref_surface_distance(ref_shape shape, int surface, hr_vec3 p);

/* Long double view of a quad, for messages. */
double ref_to_double(quad q);

#endif
