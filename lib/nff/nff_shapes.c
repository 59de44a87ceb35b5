/* NFF's spheres and cones (lib/nff/nff_reader.h), as the unit shapes of the
 * sphere and cylinder modules under a transform.
 *
 *   s x y z r        sphere: the unit sphere scaled by r, moved to (x, y, z)
 *   c bx by bz br    cone or cylinder: base point and radius,
 *     ax ay az ar      apex point and radius (on the `c` line or the two
 *                      lines after it: the words are read in order either way)
 * A cone is open, the wall alone: class openTaperedCylinder, radius 1 at
 * z = 0 and s at z = 1. Its z = 0 end is put at the end with the larger
 * radius, so s = smaller / larger is within [0, 1] and a cone whose base
 * radius is 0 (an apex at the base) is the same shape turned round. The
 * axis z runs along apex - base with its length; x and y are an orthonormal
 * pair across it, scaled by the larger radius. Radii both negative are
 * NFF's mark for a surface seen from inside only; Hill's shading lights
 * both sides of every surface, so their sizes are used. */
#include <math.h>
#include <string.h>

#include "nff/nff_reader.h"

/* A transform's 16 doubles, row-major, from its columns x, y, z and the
 * origin. */
static void frame(double m[16], hr_vec3 x, hr_vec3 y, hr_vec3 z, hr_vec3 o)
{
    const double rows[16] = {x.x, y.x, z.x, o.x, x.y, y.y, z.y, o.y,
                             x.z, y.z, z.z, o.z, 0.0, 0.0, 0.0, 1.0};
    memcpy(m, rows, sizeof rows);
}

hr_status nff_read_sphere(nff_reader *r, nff_word s)
{
    double v[4];
    nff_word at[4];
    hr_status st = nff_read_numbers(r, s, "x y z radius", 4, v, at);
    if (st) return st;
    if (!(v[3] > 0.0))
        return nff_error(r, HR_ERROR_SDL, at[3], "the radius %g of 's' must be > 0", v[3]);
    double m[16];
    frame(m, (hr_vec3){v[3], 0, 0}, (hr_vec3){0, v[3], 0}, (hr_vec3){0, 0, v[3]},
          (hr_vec3){v[0], v[1], v[2]});
    return nff_add_object(r, s, "sphere", NULL, 0, m);
}

static hr_vec3 sub(hr_vec3 a, hr_vec3 b) { return (hr_vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static hr_vec3 scale(hr_vec3 a, double s) { return (hr_vec3){a.x * s, a.y * s, a.z * s}; }
static double dot(hr_vec3 a, hr_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static hr_vec3 cross(hr_vec3 a, hr_vec3 b)
{
    return (hr_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/* Two unit vectors across the unit vector w, from the axis w is least
 * along, so the cross product is well conditioned. */
static void across(hr_vec3 w, hr_vec3 *u, hr_vec3 *v)
{
    const double ax = fabs(w.x), ay = fabs(w.y), az = fabs(w.z);
    const hr_vec3 helper = ax <= ay && ax <= az ? (hr_vec3){1, 0, 0}
                           : ay <= az          ? (hr_vec3){0, 1, 0}
                                               : (hr_vec3){0, 0, 1};
    hr_vec3 c = cross(helper, w);
    *u = scale(c, 1.0 / sqrt(dot(c, c)));
    *v = cross(w, *u);
}

hr_status nff_read_cone(nff_reader *r, nff_word c)
{
    double v[8];
    nff_word at[8];
    hr_status st = nff_read_numbers(
        r, c, "base x y z radius, apex x y z radius; on one line or two", 8, v, at);
    if (st) return st;
    hr_vec3 base = {v[0], v[1], v[2]}, apex = {v[4], v[5], v[6]};
    double rb = v[3], ra = v[7];
    if (rb < 0.0 && ra < 0.0) rb = -rb, ra = -ra;
    if (rb < 0.0 || ra < 0.0)
        return nff_error(r, HR_ERROR_SDL, c,
                         "the radii %g and %g of 'c' must be both >= 0 (or both negative: "
                         "seen from inside)",
                         v[3], v[7]);
    if (rb == 0.0 && ra == 0.0)
        return nff_error(r, HR_ERROR_SDL, c, "the radii of 'c' are both 0: it has no surface");
    if (ra > rb) { /* the larger radius at z = 0 */
        hr_vec3 p = base;
        base = apex, apex = p;
        double t = rb;
        rb = ra, ra = t;
    }
    const hr_vec3 axis = sub(apex, base);
    const double length = sqrt(dot(axis, axis));
    if (!(length > 0.0) || !isfinite(length))
        return nff_error(r, HR_ERROR_SDL, c,
                         length > 0.0 ? "the axis of 'c' is too long to measure"
                                      : "the base and apex points of 'c' are the same point: "
                                        "it has no axis");
    hr_vec3 u, w = scale(axis, 1.0 / length), vv;
    across(w, &u, &vv);
    double m[16];
    frame(m, scale(u, rb), scale(vv, rb), axis, base);
    hr_param s;
    memset(&s, 0, sizeof s);
    s.name = "s";
    s.type = HR_PARAM_NUMBER;
    s.number = ra / rb;
    return nff_add_object(r, c, "openTaperedCylinder", &s, 1, m);
}
