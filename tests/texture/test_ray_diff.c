/* Ray differentials (lib/trace/ray_diff.c, compiled into this test) against
 * finite differences of neighbouring rays, through a mirror sphere and a
 * glass sphere onto a floor.
 *
 * A camera (a pinhole, as lib/geometry/camera_frame.h has it) looks at a
 * unit sphere above the floor y = 0. For each pixel of a grid over the
 * sphere, the path camera -> sphere -> floor (the mirror: one reflection;
 * the glass: refraction in and out, Hill's speed 2/3) is traced in long
 * double, and the floor point's derivatives with respect to the pixel's x
 * and y are taken by central differences of neighbouring rays, h = 2^-16
 * pixels apart. The differentials follow the same path in double with the
 * library's transfer, reflection and refraction, given the sphere's exact
 * normal derivative (dn = dp / r on a sphere of radius r).
 *
 * Tolerance: the central difference's error is h^2 / 6 times the third
 * derivative. Near the sphere's rim, where a reflected ray reaches the
 * floor far off, the footprint grows by a factor of ten over a pixel or
 * two, and at h = 2^-12 that error reached 8e-6 of the footprint there;
 * at 2^-16 it is 256 times less, and long double's rounding over h
 * (2^-64 / 2^-16, times the points' size over the footprint's) stays under
 * 1e-12. The differentials' own rounding is a few ulps of double per step.
 * Paths that graze the sphere or the floor (cosines under 0.05) are left
 * out. We allow 1e-6 of the footprint's length (the worst seen: 3e-8).
 * Checked to fail: a reflection without the normal's derivative (the
 * mirror sphere's footprint then off by a factor of several). */
#include <math.h>
#include <stdio.h>

#include "hr_test.h"
#include "geometry/vec.h"
#include "trace/ray_diff.h"

typedef long double ld;
typedef struct {
    ld x, y, z;
} lv;

static lv lv_make(ld x, ld y, ld z) { return (lv){x, y, z}; }
static lv lv_add(lv a, lv b) { return lv_make(a.x + b.x, a.y + b.y, a.z + b.z); }
static lv lv_sub(lv a, lv b) { return lv_make(a.x - b.x, a.y - b.y, a.z - b.z); }
static lv lv_scale(lv a, ld s) { return lv_make(a.x * s, a.y * s, a.z * s); }
static ld lv_dot(lv a, lv b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static lv lv_unit(lv a) { return lv_scale(a, 1.0L / sqrtl(lv_dot(a, a))); }
static hr_vec3 to_d(lv a) { return v3((double)a.x, (double)a.y, (double)a.z); }

#define W 64
#define H 48
static const lv EYE = {0.0L, 1.5L, 5.0L};
static const lv CENTRE = {0.0L, 1.25L, 0.0L};
#define HALF_W 0.32L
#define HALF_H 0.24L
#define SPEED (2.0L / 3.0L)

/* The camera's unnormalised direction through pixel (px, py), and its
 * derivatives: u = +x, v = +y, n = +z (looking down -z). */
static lv camera_w(ld px, ld py)
{
    return lv_make(HALF_W * (2.0L * px / W - 1.0L), HALF_H * (1.0L - 2.0L * py / H), -1.0L);
}
static const lv DWDX = {2.0L * HALF_W / W, 0.0L, 0.0L};
static const lv DWDY = {0.0L, -2.0L * HALF_H / H, 0.0L};

/* The nearer (or, from inside, the far) hit of the unit sphere along a unit d. */
static int sphere_hit(lv o, lv d, int inside, ld *t)
{
    const lv oc = lv_sub(o, CENTRE);
    const ld b = lv_dot(oc, d), c = lv_dot(oc, oc) - 1.0L;
    const ld disc = b * b - c;
    if (disc < 0) return 0;
    *t = inside ? -b + sqrtl(disc) : -b - sqrtl(disc);
    return *t > 1e-9L;
}

typedef struct {
    lv point;     /* on the floor */
    int ok;       /* the path exists and grazes nothing */
    lv hits[3];   /* the sphere's points, then the floor's */
    ld dists[3];  /* the distance along each leg */
    lv dirs[3];   /* each leg's unit direction */
    int legs;
} path;

/* The path of pixel (px, py): glass = 0, a reflection; 1, two refractions. */
static path trace(ld px, ld py, int glass)
{
    path p = {0};
    lv o = EYE, d = lv_unit(camera_w(px, py));
    ld t;
    if (!sphere_hit(o, d, 0, &t)) return p;
    lv hit = lv_add(o, lv_scale(d, t));
    lv n = lv_sub(hit, CENTRE);
    ld c = -lv_dot(d, n);
    if (c < 0.05L) return p;
    p.hits[0] = hit, p.dists[0] = t, p.dirs[0] = d;
    p.legs = 1;
    if (!glass) {
        d = lv_add(d, lv_scale(n, 2.0L * c));
    } else {
        ld eta = SPEED, ct2 = 1.0L - eta * eta * (1.0L - c * c);
        d = lv_add(lv_scale(d, eta), lv_scale(n, eta * c - sqrtl(ct2)));
        o = hit;
        if (!sphere_hit(o, d, 1, &t)) return p;
        hit = lv_add(o, lv_scale(d, t));
        lv m = lv_scale(lv_sub(hit, CENTRE), -1.0L); /* facing the ray, inside */
        c = -lv_dot(d, m);
        eta = 1.0L / SPEED;
        ct2 = 1.0L - eta * eta * (1.0L - c * c);
        if (c < 0.05L || ct2 < 0.0025L) return p; /* grazing or totally reflected */
        p.hits[1] = hit, p.dists[1] = t, p.dirs[1] = d;
        p.legs = 2;
        d = lv_add(lv_scale(d, eta), lv_scale(m, eta * c - sqrtl(ct2)));
    }
    o = hit;
    if (!(d.y < -0.05L)) return p; /* the floor, not too grazing */
    t = -o.y / d.y;
    p.point = lv_add(o, lv_scale(d, t));
    p.hits[p.legs] = p.point, p.dists[p.legs] = t, p.dirs[p.legs] = d;
    p.legs++;
    p.ok = 1;
    return p;
}

/* The differentials along the same path, in double, by the library. */
static void differentials(const path *p, ld px, ld py, int glass, hr_vec3 *dpdx, hr_vec3 *dpdy)
{
    hr_ray_diff rd = hri_ray_diff_camera(to_d(camera_w(px, py)), to_d(DWDX), to_d(DWDY));
    for (int leg = 0; leg < p->legs; leg++) {
        const hr_vec3 dir = to_d(p->dirs[leg]);
        const int floor = leg == p->legs - 1;
        const hr_vec3 n = floor ? v3(0, 1, 0) : to_d(lv_sub(p->hits[leg], CENTRE));
        hri_ray_diff_transfer(&rd, dir, (double)p->dists[leg], n, dpdx, dpdy);
        if (floor) return;
        /* The facing normal and its derivatives: dn = dp on the unit sphere. */
        const double side = v3_dot(dir, n) < 0 ? 1.0 : -1.0;
        const hr_vec3 m = v3_scale(n, side);
        const hr_vec3 dmx = v3_scale(*dpdx, side), dmy = v3_scale(*dpdy, side);
        if (!glass) {
            rd = hri_ray_diff_reflect(&rd, dir, m, dmx, dmy, *dpdx, *dpdy);
        } else {
            const double eta = (double)(leg == 0 ? SPEED : 1.0L / SPEED);
            const double c = -v3_dot(dir, m);
            const double ct = sqrt(1.0 - eta * eta * (1.0 - c * c));
            rd = hri_ray_diff_refract(&rd, dir, m, dmx, dmy, *dpdx, *dpdy, eta, ct);
        }
    }
}

static int compare(int glass)
{
    const ld h = 1.0L / 65536.0L;
    int checked = 0;
    double worst = 0.0;
    for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
            const ld x = px + 0.5L, y = py + 0.5L;
            path p = trace(x, y, glass);
            path xa = trace(x + h, y, glass), xb = trace(x - h, y, glass);
            path ya = trace(x, y + h, glass), yb = trace(x, y - h, glass);
            if (!p.ok || !xa.ok || !xb.ok || !ya.ok || !yb.ok) continue;
            const lv fx = lv_scale(lv_sub(xa.point, xb.point), 1.0L / (2.0L * h));
            const lv fy = lv_scale(lv_sub(ya.point, yb.point), 1.0L / (2.0L * h));
            hr_vec3 dx, dy;
            differentials(&p, x, y, glass, &dx, &dy);
            const double size = fmax(v3_length(to_d(fx)), v3_length(to_d(fy)));
            const double ex = v3_length(v3_sub(dx, to_d(fx))) / size;
            const double ey = v3_length(v3_sub(dy, to_d(fy))) / size;
            if (ex > worst) worst = ex;
            if (ey > worst) worst = ey;
            CHECK_MSG(ex <= 1e-6 && ey <= 1e-6,
                      "%s pixel (%d, %d): dp/dx (%g %g %g) vs differences (%g %g %g), dp/dy (%g %g %g) vs "
                      "(%g %g %g)",
                      glass ? "glass" : "mirror", px, py, dx.x, dx.y, dx.z, (double)fx.x, (double)fx.y,
                      (double)fx.z, dy.x, dy.y, dy.z, (double)fy.x, (double)fy.y, (double)fy.z);
            checked++;
        }
    printf("%s: %d pixels, worst relative error %.3g\n", glass ? "glass sphere" : "mirror sphere", checked,
           worst);
    return checked;
}

/* The camera's own: d (unit w) / dx against differences of unit directions. */
static void test_camera(void)
{
    const ld h = 1.0L / 65536.0L;
    for (int i = 0; i < 5; i++) {
        const ld x = 3.5L + 13 * i, y = 40.5L - 9 * i;
        hr_ray_diff rd = hri_ray_diff_camera(to_d(camera_w(x, y)), to_d(DWDX), to_d(DWDY));
        lv fx = lv_scale(lv_sub(lv_unit(camera_w(x + h, y)), lv_unit(camera_w(x - h, y))), 1.0L / (2 * h));
        lv fy = lv_scale(lv_sub(lv_unit(camera_w(x, y + h)), lv_unit(camera_w(x, y - h))), 1.0L / (2 * h));
        CHECK(v3_length(v3_sub(rd.dddx, to_d(fx))) <= 1e-7 * v3_length(to_d(fx)));
        CHECK(v3_length(v3_sub(rd.dddy, to_d(fy))) <= 1e-7 * v3_length(to_d(fy)));
        CHECK(v3_length(rd.dodx) == 0.0 && v3_length(rd.dody) == 0.0);
    }
}

int main(void)
{
    test_camera();
    /* Enough of each sphere's image takes each path for the test to mean something. */
    CHECK(compare(0) >= 100);
    CHECK(compare(1) >= 100);
    return hr_test_end();
}
