/* Ray differentials (lib/trace/ray_diff.h): Igehy's transfer, reflection
 * and refraction, written for a unit direction D and a unit normal m that
 * faces the ray, as shade.c traces them. */
#include <math.h>

#include "trace/ray_diff.h"
#include "geometry/vec.h"

/* d(w / |w|) for a change dw of w: the part of dw across w, over |w|;
 * d is w / |w| and inv 1 / |w|, worked out once for both of a ray's. */
static hr_vec3 unit_derivative(hr_vec3 d, double inv, hr_vec3 dw)
{
    return v3_scale(v3_madd(dw, d, -v3_dot(d, dw)), inv);
}

hr_ray_diff hri_ray_diff_camera(hr_vec3 w, hr_vec3 dwdx, hr_vec3 dwdy)
{
    const double inv = 1.0 / v3_length(w);
    const hr_vec3 d = v3_scale(w, inv);
    hr_ray_diff rd;
    rd.dodx = rd.dody = v3(0.0, 0.0, 0.0);
    rd.dddx = unit_derivative(d, inv, dwdx);
    rd.dddy = unit_derivative(d, inv, dwdy);
    return rd;
}

/* Igehy's transfer: the point moves with the origin and the direction,
 * dp' = do + dist dD, and along the ray by dt = -(dp' . n) / (D . n), to
 * stay on the surface's tangent plane. A ray grazing the plane (D . n = 0)
 * keeps dp', the best it has. */
static hr_vec3 transfer(hr_vec3 dodx, hr_vec3 dddx, hr_vec3 dir, double dist, hr_vec3 n)
{
    const hr_vec3 dp = v3_madd(dodx, dddx, dist);
    const double dn = v3_dot(dir, n);
    if (dn == 0.0) return dp;
    return v3_madd(dp, dir, -v3_dot(dp, n) / dn);
}

void hri_ray_diff_transfer(const hr_ray_diff *rd, hr_vec3 dir, double dist, hr_vec3 n, hr_vec3 *dpdx,
                           hr_vec3 *dpdy)
{
    *dpdx = transfer(rd->dodx, rd->dddx, dir, dist, n);
    *dpdy = transfer(rd->dody, rd->dddy, dir, dist, n);
}

/* R = D + 2 c m with c = -D . m:
 * dR = dD + 2 (dc m + c dm), dc = -(dD . m + D . dm). */
static hr_vec3 reflect_d(hr_vec3 dd, hr_vec3 dir, hr_vec3 m, hr_vec3 dm)
{
    const double c = -v3_dot(dir, m);
    const double dc = -(v3_dot(dd, m) + v3_dot(dir, dm));
    return v3_add(dd, v3_scale(v3_add(v3_scale(m, dc), v3_scale(dm, c)), 2.0));
}

hr_ray_diff hri_ray_diff_reflect(const hr_ray_diff *rd, hr_vec3 dir, hr_vec3 m, hr_vec3 dmdx, hr_vec3 dmdy,
                                 hr_vec3 dpdx, hr_vec3 dpdy)
{
    hr_ray_diff out;
    out.dodx = dpdx;
    out.dody = dpdy;
    out.dddx = reflect_d(rd->dddx, dir, m, dmdx);
    out.dddy = reflect_d(rd->dddy, dir, m, dmdy);
    return out;
}

/* T = eta D + (eta c - ct) m, ct = sqrt(1 - eta^2 (1 - c^2)):
 * dT = eta dD + (eta dc - dct) m + (eta c - ct) dm, dct = eta^2 c dc / ct. */
static hr_vec3 refract_d(hr_vec3 dd, hr_vec3 dir, hr_vec3 m, hr_vec3 dm, double eta, double ct)
{
    const double c = -v3_dot(dir, m);
    const double dc = -(v3_dot(dd, m) + v3_dot(dir, dm));
    const double dct = eta * eta * c * dc / ct;
    return v3_add(v3_add(v3_scale(dd, eta), v3_scale(m, eta * dc - dct)), v3_scale(dm, eta * c - ct));
}

hr_ray_diff hri_ray_diff_refract(const hr_ray_diff *rd, hr_vec3 dir, hr_vec3 m, hr_vec3 dmdx, hr_vec3 dmdy,
                                 hr_vec3 dpdx, hr_vec3 dpdy, double eta, double cos_t)
{
    hr_ray_diff out;
    out.dodx = dpdx;
    out.dody = dpdy;
    out.dddx = refract_d(rd->dddx, dir, m, dmdx, eta, cos_t);
    out.dddy = refract_d(rd->dddy, dir, m, dmdy, eta, cos_t);
    return out;
}

hr_ray_diff hri_ray_diff_scale(hr_ray_diff rd, double sx, double sy)
{
    rd.dodx = v3_scale(rd.dodx, sx);
    rd.dddx = v3_scale(rd.dddx, sx);
    rd.dody = v3_scale(rd.dody, sy);
    rd.dddy = v3_scale(rd.dddy, sy);
    return rd;
}
