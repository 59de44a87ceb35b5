/* Cook and Torrance's specular term (lib/trace/cook_torrance.h). */
#include "trace/cook_torrance.h"

#include <math.h>

#include "geometry/vec.h"

#define PI 3.14159265358979323846

double hri_fresnel(double c, double eta)
{
    const double g2 = eta * eta + c * c - 1.0;
    if (!(g2 > 0.0)) return 1.0; /* total internal reflection */
    const double g = sqrt(g2);
    const double a = (g - c) / (g + c);
    const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

/* D G / (4 (n.v)) and the half vector's v.h, or 0 where the light, the eye
 * or the half vector is below the surface. */
static double microfacet_lobe(hr_vec3 n, hr_vec3 l, hr_vec3 v, double m, double *vh_out)
{
    const double nl = v3_dot(n, l), nv = v3_dot(n, v);
    if (!(nl > 0.0 && nv > 0.0)) return 0.0;
    const hr_vec3 h = v3_normalize(v3_add(l, v));
    const double nh = v3_dot(n, h), vh = v3_dot(v, h);
    if (!(nh > 0.0 && vh > 0.0)) return 0.0;
    /* Beckmann, normalised so that its projection on the surface integrates
     * to 1 over the hemisphere: exp(-tan^2(a) / m^2) / (pi m^2 cos^4(a)),
     * cos(a) = n.h. With it the denominator is 4 (n.l)(n.v) (the Jacobian
     * of the half vector, pbrt and Walter et al.), not Cook and Torrance's
     * pi (n.l)(n.v), which goes with their unnormalised D and would make
     * the lobe 4 / pi of itself, reflecting more than it receives. */
    const double c2 = nh * nh, m2 = m * m;
    const double d = exp(-(1.0 - c2) / (c2 * m2)) / (PI * m2 * c2 * c2);
    const double g = fmin(1.0, fmin(2.0 * nh * nv / vh, 2.0 * nh * nl / vh));
    *vh_out = vh;
    return d * g / (4.0 * nv);
}

double hri_cook_torrance_lobe(hr_vec3 n, hr_vec3 l, hr_vec3 v, double m)
{
    double vh;
    const double r = microfacet_lobe(n, l, v, m, &vh);
    return r < HR_COOK_TORRANCE_MAX ? r : HR_COOK_TORRANCE_MAX;
}

double hri_cook_torrance(hr_vec3 n, hr_vec3 l, hr_vec3 v, double m, double eta)
{
    double vh = 0.0;
    const double lobe = microfacet_lobe(n, l, v, m, &vh);
    if (!(lobe > 0.0)) return 0.0;
    const double r = hri_fresnel(vh, eta) * lobe;
    return r < HR_COOK_TORRANCE_MAX ? r : HR_COOK_TORRANCE_MAX;
}
