/* Internal: ray differentials (Igehy, "Tracing Ray Differentials",
 * SIGGRAPH 1999). A ray's differentials are the derivatives of its origin
 * and of its unit direction with respect to the image's x and y, one pixel
 * per unit: how far the neighbouring pixels' rays are from it. Carried
 * from the camera through every hit (transfer to the surface, reflection,
 * refraction), they give each hit its footprint, dp/dx and dp/dy: the
 * pixel's extent on the surface, which a texture is averaged over.
 *
 * Only a scene with a texture traces them (hr_scene effects has
 * HR_EFFECT_TEXTURE, and the render's texture filter is on): every other
 * render runs the shading it ran before, without them. */
#ifndef HITRAY_LIB_TRACE_RAY_DIFF_H
#define HITRAY_LIB_TRACE_RAY_DIFF_H

#include <hitray/hitray.h>

typedef struct hr_ray_diff {
    hr_vec3 dodx, dddx; /* d origin / dx, d (unit direction) / dx */
    hr_vec3 dody, dddy; /* the same for y */
} hr_ray_diff;

/* The differentials of a camera ray from `eye` along `w` (unnormalised,
 * the direction before normalising) whose derivatives with respect to the
 * image's x and y are dwdx and dwdy; the origin is the same for every
 * pixel (a pinhole). */
hr_ray_diff hri_ray_diff_camera(hr_vec3 w, hr_vec3 dwdx, hr_vec3 dwdy);

/* Transfer to a hit: the footprint (dpdx, dpdy) on the plane through the
 * hit with normal n, of a ray with unit direction `dir` whose hit lies a
 * distance `dist` along it. */
void hri_ray_diff_transfer(const hr_ray_diff *rd, hr_vec3 dir, double dist, hr_vec3 n, hr_vec3 *dpdx,
                           hr_vec3 *dpdy);

/* The reflected ray's differentials at a hit with footprint (dpdx, dpdy),
 * unit direction `dir` arriving, unit normal m facing it (m . dir < 0),
 * and m's derivatives dmdx, dmdy along the footprint (0 on a plane). */
hr_ray_diff hri_ray_diff_reflect(const hr_ray_diff *rd, hr_vec3 dir, hr_vec3 m, hr_vec3 dmdx, hr_vec3 dmdy,
                                 hr_vec3 dpdx, hr_vec3 dpdy);

/* The transmitted ray's, for the ratio of speeds `eta` (c2 / c1) and
 * cos_t > 0, the cosine of the transmitted angle (no total internal
 * reflection). */
hr_ray_diff hri_ray_diff_refract(const hr_ray_diff *rd, hr_vec3 dir, hr_vec3 m, hr_vec3 dmdx, hr_vec3 dmdy,
                                 hr_vec3 dpdx, hr_vec3 dpdy, double eta, double cos_t);

/* All scaled by s (a pixel of n samples: s = 1 / sqrt(n), each sample's
 * share of it; a block of b pixels: b). */
hr_ray_diff hri_ray_diff_scale(hr_ray_diff rd, double sx, double sy);

#endif
