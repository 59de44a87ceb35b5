/* Cook-Torrance's lobe (lib/trace/cook_torrance.c, compiled into this test)
 * on its own: the term against its formula in long double at sampled
 * angles, roughnesses and indices, and a white furnace: with F = 1 the
 * lobe's directional albedo, the integral of R_s (n.l) over the lights'
 * hemisphere, is at most 1 at every view angle and roughness in [0.05, 1]
 * (a lobe that reflects more than it receives fails it by up to 27%). */
#include <math.h>
#include <stdio.h>

#include "trace/cook_torrance.h"
#include "hr_test.h"

#define PI_L 3.14159265358979323846264338327950288L

typedef struct {
    long double x, y, z;
} vec_l;

static long double dot_l(vec_l a, vec_l b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static vec_l unit_l(long double theta, long double phi)
{
    return (vec_l){sinl(theta) * cosl(phi), sinl(theta) * sinl(phi), cosl(theta)};
}

static hr_vec3 to_d(vec_l a) { return (hr_vec3){(double)a.x, (double)a.y, (double)a.z}; }

/* Fresnel from Snell's law and the s- and p-polarised reflectances (the
 * library uses Cook and Torrance's form), 1 beyond the critical angle. */
static long double fresnel_l(long double ci, long double eta)
{
    const long double st = sqrtl(1.0L - ci * ci) / eta;
    if (st >= 1.0L) return 1.0L;
    const long double ct = sqrtl(1.0L - st * st);
    const long double rs = (ci - eta * ct) / (ci + eta * ct);
    const long double rp = (eta * ci - ct) / (eta * ci + ct);
    return 0.5L * (rs * rs + rp * rp);
}

/* F D G / (4 (n.v)) with n = +z, in long double from the angle itself. */
static long double lobe_l(vec_l l, vec_l v, long double m, long double eta, int with_fresnel)
{
    const long double nl = l.z, nv = v.z;
    if (!(nl > 0 && nv > 0)) return 0;
    vec_l h = {l.x + v.x, l.y + v.y, l.z + v.z};
    const long double len = sqrtl(dot_l(h, h));
    h = (vec_l){h.x / len, h.y / len, h.z / len};
    const long double nh = h.z, vh = dot_l(v, h);
    if (!(nh > 0 && vh > 0)) return 0;
    const long double alpha = acosl(fminl(nh, 1.0L));
    const long double D = expl(-powl(tanl(alpha) / m, 2)) / (PI_L * m * m * powl(cosl(alpha), 4));
    const long double G = fminl(1.0L, fminl(2 * nh * nv / vh, 2 * nh * nl / vh));
    return (with_fresnel ? fresnel_l(vh, eta) : 1.0L) * D * G / (4.0L * nv);
}

/* The term at sampled directions: relative 1e-10, the rounding of double
 * through exp(-tan^2 / m^2) (an argument up to some 700, each unit of it
 * costing a relative 1e-16) and acos near 0 in the reference. */
static void test_term_against_formula(void)
{
    static const double ms[] = {0.05, 0.12, 0.3, 0.6, 1.0, 2.5};
    static const double etas[] = {1.2, 1.5, 2.5, 5.0};
    const hr_vec3 n = {0, 0, 1};
    int compared = 0;
    for (int a = 0; a < 9; a++)
        for (int b = 0; b < 9; b++)
            for (int p = 0; p < 5; p++) {
                const vec_l v = unit_l((a * 10 + 1.5L) * PI_L / 180, 0);
                const vec_l l = unit_l((b * 10 + 3.25L) * PI_L / 180, p * 0.7L);
                for (int k = 0; k < 6; k++)
                    for (int e = 0; e < 4; e++) {
                        const long double want = lobe_l(l, v, ms[k], etas[e], 1);
                        const double got = hri_cook_torrance(n, to_d(l), to_d(v), ms[k], etas[e]);
                        if (want < 1e-250L) {
                            CHECK_MSG(got < 1e-240, "%.17g for %.3Lg", got, want);
                            continue;
                        }
                        CHECK_MSG(fabsl(got - want) <= 1e-10L * want, "v %d l %d phi %d m %g eta %g: %.17g, %.17Lg",
                                  a, b, p, ms[k], etas[e], got, want);
                        const double lobe = hri_cook_torrance_lobe(n, to_d(l), to_d(v), ms[k]);
                        const long double want1 = lobe_l(l, v, ms[k], etas[e], 0);
                        CHECK(fabsl(lobe - want1) <= 1e-10L * want1);
                        compared++;
                    }
            }
    CHECK(compared > 4000);
}

/* Gauss-Legendre's 8 nodes and weights on [-1, 1]. */
static const long double GL_X[4] = {0.183434642495649804939476142360184L, 0.525532409916328985817739049189246L,
                                    0.796666477413626739591553936475830L, 0.960289856497536231683560868569473L};
static const long double GL_W[4] = {0.362683783378361982965150449277196L, 0.313706645877887287337962201986601L,
                                    0.222381034453374470544355994426241L, 0.101228536290376259152531354309962L};

/* The directional albedo at view angle theta_v, by composite Gauss-Legendre
 * in half-vector space: l = 2 (v.h) h - v, d(omega_l) = 4 (v.h) d(omega_h);
 * h's slope tan(theta_h) = m t, t in [0, 6] (Beckmann's slopes beyond 6 m
 * carry exp(-36) of it), azimuth over [0, pi] twice (the lobe is mirror
 * symmetric about the plane of v and n). `lib` picks the library's double
 * term or the long double formula; the sum is long double either way. */
static long double albedo(long double theta_v, long double m, int panels, int lib)
{
    const vec_l v = unit_l(theta_v, 0);
    const hr_vec3 n = {0, 0, 1};
    const long double t_max = 6.0L;
    long double sum = 0;
    for (int i = 0; i < panels; i++)
        for (int gi = 0; gi < 8; gi++) {
            const long double xi = gi < 4 ? -GL_X[3 - gi] : GL_X[gi - 4];
            const long double wi = gi < 4 ? GL_W[3 - gi] : GL_W[gi - 4];
            const long double t = (i + 0.5L + 0.5L * xi) * t_max / panels;
            const long double th = atanl(m * t), dth = m / (1 + m * m * t * t) * (0.5L * t_max / panels) * wi;
            for (int j = 0; j < panels; j++)
                for (int gj = 0; gj < 8; gj++) {
                    const long double xj = gj < 4 ? -GL_X[3 - gj] : GL_X[gj - 4];
                    const long double wj = gj < 4 ? GL_W[3 - gj] : GL_W[gj - 4];
                    const long double ph = (j + 0.5L + 0.5L * xj) * PI_L / panels;
                    const long double dph = (0.5L * PI_L / panels) * wj;
                    const vec_l h = unit_l(th, ph);
                    const long double vh = dot_l(v, h);
                    if (!(vh > 0)) continue;
                    const vec_l l = {2 * vh * h.x - v.x, 2 * vh * h.y - v.y, 2 * vh * h.z - v.z};
                    if (!(l.z > 0)) continue;
                    const long double f = lib ? (long double)hri_cook_torrance_lobe(n, to_d(l), to_d(v), (double)m)
                                              : lobe_l(l, v, m, 1, 0);
                    sum += 2 * f * 4 * vh * sinl(th) * dth * dph;
                }
        }
    return sum;
}

static void test_white_furnace(void)
{
    static const double ms[] = {0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0};
    static const double views[] = {0, 15, 30, 45, 60, 70, 80, 85, 89};
    long double most = 0;
    for (int k = 0; k < 7; k++)
        for (int a = 0; a < 9; a++) {
            const long double tv = views[a] * PI_L / 180;
            const long double ref = albedo(tv, ms[k], 24, 0), coarse = albedo(tv, ms[k], 12, 0);
            const long double lib = albedo(tv, ms[k], 24, 1);
            /* The quadrature's error, bounded by its change from 12 to 24
             * panels (the integrand has kinks where G's minimum switches
             * and where l meets the horizon, so the rule converges
             * algebraically, not spectrally: some 1e-4 at worst, where
             * the kinks fall inside the lobe, 300 times below what a
             * lobe 4 / pi too bright adds). */
            const long double quad = fabsl(ref - coarse);
            CHECK_MSG(quad < 1e-3L, "m %g view %g: quadrature moved %.3Lg", ms[k], views[a], quad);
            CHECK_MSG(ref <= 1.0L + quad, "m %g view %g: albedo %.9Lf", ms[k], views[a], ref);
            CHECK_MSG(ref > 0.0L, "m %g view %g: albedo %.9Lf", ms[k], views[a], ref);
            /* The library's double term, summed on the same nodes, within
             * its pointwise 1e-10 (relative) of the reference. */
            CHECK_MSG(fabsl(lib - ref) <= 1e-10L * ref + 1e-15L, "m %g view %g: %.15Lf, reference %.15Lf", ms[k],
                      views[a], lib, ref);
            if (ref > most) most = ref;
        }
    /* Head-on and smooth, next to nothing is lost: the test has teeth (a
     * lobe 4 / pi too bright gives 1.27 here). */
    CHECK_MSG(most > 0.95L, "largest albedo %.6Lf", most);
}

int main(void)
{
    test_term_against_formula();
    test_white_furnace();
    return hr_test_end();
}
