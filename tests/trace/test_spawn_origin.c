/* hr_hit_spawn_origin, the one rule every spawned ray leaves a surface by:
 * the distance is the hit's own error bound (times |side|_1), never less
 * and never a fixed epsilon; a hit reporting no bound gets the stand-in of
 * 8 epsilon |p|; every coordinate ends strictly on the side's side of the
 * offset point. Worked in long double (64-bit significand): the offsets
 * here are sums of two doubles, so the comparison needs no tolerance
 * beyond one rounding of the double result, which the nextafter nudge
 * exceeds. */
#include <float.h>
#include <math.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_hit hit_at(double x, double y, double z, double error)
{
    hr_hit h = {0};
    h.point.x = x;
    h.point.y = y;
    h.point.z = z;
    h.error = error;
    h.normal.z = 1.0;
    return h;
}

/* The spawned origin moved at least `distance` along `side` (unit) from
 * the point, and no coordinate against it. */
static void check_offset(const char *what, const hr_hit *h, hr_vec3 side, long double distance)
{
    const hr_vec3 o = hr_hit_spawn_origin(h, side);
    const long double along = ((long double)o.x - h->point.x) * side.x +
                              ((long double)o.y - h->point.y) * side.y +
                              ((long double)o.z - h->point.z) * side.z;
    CHECK_MSG(along >= distance, "%s: moved %Lg along the side, need %Lg", what, along, distance);
    const double p[3] = {h->point.x, h->point.y, h->point.z};
    const double q[3] = {o.x, o.y, o.z}, s[3] = {side.x, side.y, side.z};
    for (int i = 0; i < 3; i++) {
        if (s[i] > 0) CHECK_MSG(q[i] > p[i], "%s: coordinate %d not moved up", what, i);
        if (s[i] < 0) CHECK_MSG(q[i] < p[i], "%s: coordinate %d not moved down", what, i);
        if (s[i] == 0) CHECK_MSG(q[i] == p[i], "%s: coordinate %d moved off a zero side", what, i);
    }
}

/* The rule, written with libm's nextafter: the library steps by bits
 * instead (a libm call per coordinate per spawned ray was 2.6% of a
 * render), and must give the same doubles, zero, subnormals, DBL_MAX and
 * sides of every sign included. */
static hr_vec3 spawn_by_nextafter(const hr_hit *h, hr_vec3 side)
{
    hr_vec3 p = h->point;
    double err = h->error > 0.0 ? h->error : 8.0 * DBL_EPSILON * fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
    double d = err * (fabs(side.x) + fabs(side.y) + fabs(side.z));
    double c[3] = {p.x + side.x * d, p.y + side.y * d, p.z + side.z * d};
    const double s[3] = {side.x, side.y, side.z};
    for (int i = 0; i < 3; i++)
        if (s[i] != 0) c[i] = nextafter(c[i], s[i] > 0 ? INFINITY : -INFINITY);
    return (hr_vec3){c[0], c[1], c[2]};
}

static void same_as_nextafter(void)
{
    const double values[] = {0.0, -0.0, 4.9e-324, -4.9e-324, 2.2250738585072014e-308, -1e-300, 1.0,
                             -1.0, 3.5, -7e10, 1.7976931348623157e308, -1.7976931348623157e308};
    const double sides[] = {1.0, -1.0, 0.0, 0.6, -0.8};
    const double errors[] = {0.0, 1e-300, 1e-12};
    int n = (int)(sizeof values / sizeof *values), mismatches = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < 5; j++)
            for (int k = 0; k < 5; k++)
                for (int e = 0; e < 3; e++) {
                    hr_hit h = hit_at(values[i], values[(i + 3) % n], values[(i + 7) % n], errors[e]);
                    hr_vec3 side = {sides[j], sides[k], sides[(j + k) % 5]};
                    hr_vec3 a = hr_hit_spawn_origin(&h, side), b = spawn_by_nextafter(&h, side);
                    mismatches += memcmp(&a, &b, sizeof a) != 0;
                }
    CHECK_MSG(mismatches == 0, "%d spawn origins differ from the nextafter rule", mismatches);
}

int main(void)
{
    same_as_nextafter();
    const hr_vec3 up = {0, 0, 1}, down = {0, 0, -1};
    const double r = 1.0 / sqrt(3.0);
    const hr_vec3 diagonal = {r, -r, r};

    /* The bound alone sets the distance: 1e-9 along +z is exactly 1e-9
     * (|side|_1 = 1), plus the nudge. Before the stand-in became one, a
     * floor of 8 epsilon |p| = 1.8e-9 at 1e6 made it 1.8e-9. */
    hr_hit far = hit_at(1e6, -7e5, 3e5, 3.3e-10);
    check_offset("far, +z", &far, up, 3.3e-10L);
    check_offset("far, -z", &far, down, 3.3e-10L);
    const hr_vec3 o = hr_hit_spawn_origin(&far, up);
    CHECK_MSG(o.z - far.point.z < 8 * DBL_EPSILON * 1e6,
              "the offset %g is still floored at 8 epsilon |p|", o.z - far.point.z);

    /* A tilted side: the bound is per coordinate, so the distance along a
     * unit side must be error * |side|_1 to clear the error box. */
    hr_hit tilted = hit_at(0.25, 2.0, -3.0, 1e-12);
    check_offset("tilted", &tilted, diagonal, 1e-12L * (3 * r));

    /* No bound reported: the stand-in 8 epsilon |p|_max. */
    hr_hit exact = hit_at(4.0, 0.5, 0.0, 0.0);
    check_offset("zero error", &exact, up, 8.0L * DBL_EPSILON * 4.0);

    /* At the origin with no bound, the stand-in is 0: the nudge alone still
     * moves the coordinate off the surface, to the smallest subnormal. */
    hr_hit zero = hit_at(0.0, 0.0, 0.0, 0.0);
    check_offset("origin, zero error", &zero, up, 0.0L);
    CHECK(hr_hit_spawn_origin(&zero, up).z > 0.0);
    return hr_test_end();
}
