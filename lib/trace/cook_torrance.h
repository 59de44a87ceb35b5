/* Internal: Cook and Torrance's specular term (Hill, chapter 8; Cook and
 * Torrance, "A Reflectance Model for Computer Graphics", 1982), used by
 * shade where a material's specularFraction is above 0. */
#ifndef HITRAY_LIB_TRACE_COOK_TORRANCE_H
#define HITRAY_LIB_TRACE_COOK_TORRANCE_H

#include <hitray/common.h>

/* The largest value hri_cook_torrance returns is HR_COOK_TORRANCE_MAX: a
 * grazing view or light makes the term's 1 / (n.v) unbounded, and a colour
 * times it stays within the bound that keeps every pixel finite
 * (util/color_bounds.h). */
#include "util/color_bounds.h"

/* R_s (n.l) for unit vectors n (the normal, on the viewer's side), l (to
 * the light) and v (to the eye), in the normalised microfacet form:
 *   R_s = F D G / (4 (n.l)(n.v)),  so  R_s (n.l) = F D G / (4 (n.v))
 * with D Beckmann's distribution of roughness m (the rms slope of the
 * microfacets), exp(-tan^2(a) / m^2) / (pi m^2 cos^4(a)) at the angle a
 * between n and the half vector h (normalised: its projection on the
 * surface integrates to 1), G the geometric attenuation min(1, 2 (n.h)(n.v) / (v.h),
 * 2 (n.h)(n.l) / (v.h)), and F Fresnel's reflectance for unpolarised light
 * at relative index `eta` (the material's 1 / speedOfLight) and angle
 * acos(v.h). 0 where the light or the eye is below the surface. */
double hri_cook_torrance(hr_vec3 n, hr_vec3 l, hr_vec3 v, double m, double eta);

/* The same with F = 1: D G / (4 (n.v)), capped alike. Its integral over the
 * lights' hemisphere is the lobe's directional albedo, at most 1. */
double hri_cook_torrance_lobe(hr_vec3 n, hr_vec3 l, hr_vec3 v, double m);

/* Fresnel's reflectance of unpolarised light at cos(angle) c and relative
 * index eta (1 beyond the critical angle), in Cook and Torrance's form. */
double hri_fresnel(double c, double eta);

#endif
