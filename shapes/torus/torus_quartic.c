/* The torus's ray equation and its three root solvers (torus_quartic.h).
 *
 * 1. The frame. The direction d is scaled by 2^k (exact) so that its largest
 *    component lies in [1, 2): e = 2^k d. The origin is moved along the line
 *    to the point nearest the centre, u_c = -(o.e)/(e.e), with one rounding
 *    per coordinate: o' = fma(u_c, e, o). Near the torus |o'| <= 1 + r, so
 *    that rounding is u |o'| absolute whatever |o| was: a ray from 1e6 away
 *    is solved as accurately as one from nearby. The shift is kept as an
 *    unevaluated sum (shift_high + shift_low) and t = (shift + u) 2^k is
 *    formed once at the end. (For |o| beyond ~1e15 one shift leaves o' more
 *    than a unit from the nearest point; a second or third shift follows.)
 *
 * 2. The quartic. Along p(u) = o' + u e, with G(u) = a u^2 + 2 b u + g0
 *    (a = e.e, b = o'.e, g0 = |o'|^2 - 1 - r^2) and Z(u) = o'z + u ez,
 *      f(u) = G^2 + 4 (Z^2 - r^2) = c4 u^4 + c3 u^3 + c2 u^2 + c1 u + c0,
 *      c4 = a^2, c3 = 4 a b, c2 = 4 b^2 + 2 a g0 + 4 ez^2,
 *      c1 = 4 b g0 + 8 o'z ez, c0 = g0^2 + 4 (o'z^2 - r^2).
 *    b is ~0 after the shift (so the quartic is nearly depressed already);
 *    g0 and o'z^2 - r^2 are compensated sums, accurate where they cancel.
 *    The expanded coefficients serve the closed form, the derivatives and
 *    Horner's cheap f; where accuracy decides (the last Newton steps, a
 *    tangent or not) f is evaluated at the point instead (torus_eval): p by
 *    FMA, then G and Z^2 - r^2 compensated, which keeps its error relative
 *    to the tube's size, where Horner's is relative to 1.
 *
 * 3. Every root lies where the line is inside both the bounding sphere
 *    |p| <= 1 + r and the slab |z| <= r. Both are grown by 2^-20 so that the
 *    ends of [lo, hi] are clearly outside the torus (f > 0 there): a tangent
 *    at the outer equator or on top is then an interior minimum of f. A line
 *    that misses the grown sphere or slab is a miss without solving.
 *
 * The solvers:
 * - ferrari: depress the monic quartic, take the largest root of Ferrari's
 *   resolvent cubic (trigonometric or Cardano form), split into two
 *   quadratics solved without cancellation. About 40 flops and a cbrt or
 *   acos and cos; roots lose accuracy near tangency and for thin tubes (the
 *   resolvent's root carries an absolute error that the split amplifies),
 *   and a pair of close roots can vanish into a slightly negative
 *   discriminant, or a spurious pair appear.
 * - ferrari-newton: the same, then up to four Newton steps on each root with
 *   the accurate evaluation of f (keeping the best). Recovers full accuracy
 *   wherever the closed form found the root, but cannot restore a pair that
 *   the closed form lost.
 * - bracketing (after Yuksel, "High-Performance Polynomial Root Finding for
 *   Graphics", 2022; our own code): the roots of f'' (a quadratic) split
 *   [lo, hi] into pieces where f' is monotone; a sign change of f' on a
 *   piece brackets one critical point of f, found by safeguarded Newton on
 *   f'; the critical points split [lo, hi] into pieces where f is monotone,
 *   so a sign change of f brackets exactly one root and no sign change means
 *   none. Each root is approached by safeguarded Newton on Horner's f and
 *   finished by Newton on torus_eval. A critical point where |f| is within the bound of its own rounding
 *   error (torus_eval) is a tangent: a double root, reported as two
 *   crossings at one t. Nothing is missed; pieces wholly before tmin are not
 *   searched and a first-hit query stops at its first root.
 * The measured cost and accuracy of each: bench/results/RESULTS.md, "Torus root
 * solvers". */
#include "torus_quartic.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include <hitray/shape_kit_cpu.h>
#include <hitray/shape_kit_math.h>

static const char *const solver_names[TORUS_SOLVER_COUNT] = {"ferrari", "ferrari-newton",
                                                             "bracketing"};

const char *torus_solver_name(int solver)
{
    return solver >= 0 && solver < TORUS_SOLVER_COUNT ? solver_names[solver] : NULL;
}

int torus_solver_find(const char *name)
{
    for (int i = 0; name && i < TORUS_SOLVER_COUNT; i++)
        if (strcmp(name, solver_names[i]) == 0) return i;
    return -1;
}

void torus_geometry_make(double r, torus_geometry *out)
{
    out->r = r;
    out->r_high = shape_two_product(r, r, &out->r_low);
}

/* Growth of the bounding sphere and slab (relative to 1 + r): far above the
 * rounding of f, far below anything a renderer could see. */
#define BOUND_GROWTH 0x1p-20

typedef struct torus_frame {
    const torus_geometry *g;
    hr_vec3 o, e;                 /* p(u) = o + u e */
    double o_norm2;               /* |o|^2 */
    double shift_high, shift_low; /* t = (shift + u) * scale */
    double scale;                 /* a power of two */
    double c[5];                  /* f(u) = sum c[k] u^k */
    double c_size[5];             /* the sums of the magnitudes of c[k]'s terms */
    double lo, hi;                /* every root lies in [lo, hi] */
} torus_frame;

static inline double compensated_dot(hr_vec3 a, hr_vec3 b, double start)
{
    shape_sum s = shape_sum_start(start);
    shape_sum_add_product(&s, a.x, b.x);
    shape_sum_add_product(&s, a.y, b.y);
    shape_sum_add_product(&s, a.z, b.z);
    return shape_sum_value(s);
}

/* z^2 - r^2, compensated (it cancels on top of the tube). */
static inline double z2_minus_r2(const torus_geometry *g, double z)
{
    shape_sum s = shape_sum_start(-g->r_high);
    shape_sum_add_product(&s, z, z);
    s.low -= g->r_low;
    return shape_sum_value(s);
}

/* |p|^2 - 1 - r^2, compensated (it cancels near the ring). */
static inline __attribute__((always_inline)) double g_of(const torus_geometry *g, hr_vec3 p)
{
    shape_sum s = shape_sum_start(-1.0);
    s.low -= g->r_low;
    shape_sum_add_product(&s, -g->r_high, 1.0);
    shape_sum_add_product(&s, p.x, p.x);
    shape_sum_add_product(&s, p.y, p.y);
    shape_sum_add_product(&s, p.z, p.z);
    return shape_sum_value(s);
}

/* The frame of a ray, its quartic and its bracket; 0 when the line misses the
 * bounding sphere or slab (or the ray is unusable: zero, NaN, overflowing).
 * It and torus_eval, which run for every ray, are built with
 * SHAPE_FMA_DISPATCH, and the compensated sums they use are inlined into them,
 * so that their fma() is one instruction where the CPU has FMA. */
SHAPE_FMA_DISPATCH(int, frame_make, (const torus_geometry *g, const hr_ray *ray, torus_frame *fr), (g, ray, fr))
{
    const hr_vec3 d = ray->dir;
    int k; /* max |d_i| = f 2^k, f in [0.5, 1) */
    if (!shape_vec3_scale_exponent(d, &k)) return 0;
    /* Both without the libm calls (frexp, ldexp) on every ray. */
    fr->scale = shape_ldexp(1.0, 1 - k);
    if (!isfinite(fr->scale)) return 0;
    const hr_vec3 e = shape_vec3(d.x * fr->scale, d.y * fr->scale, d.z * fr->scale);
    hr_vec3 o = ray->origin;
    if (!shape_vec3_is_finite(o)) return 0;

    /* a in [1, 3] needs no compensation; nor does the b that picks the
     * shift (any shift is exact: only o' is rounded). The b of the quartic,
     * ~0 after the shift, is compensated. */
    const double a = e.x * e.x + e.y * e.y + e.z * e.z;
    double shift_high = 0.0, shift_low = 0.0;
    double b = o.x * e.x + o.y * e.y + o.z * e.z;
    for (int pass = 0; pass < 3; pass++) {
        const double uc = -b / a;
        if (!isfinite(uc)) return 0;
        o = shape_vec3(fma(uc, e.x, o.x), fma(uc, e.y, o.y), fma(uc, e.z, o.z));
        double low;
        shift_high = shape_two_sum(shift_high, uc, &low);
        shift_low += low;
        b = compensated_dot(o, e, 0.0);
        if (fabs(b) <= 0.5 * a) break;
    }
    fr->g = g;
    fr->o = o;
    fr->e = e;
    fr->o_norm2 = o.x * o.x + o.y * o.y + o.z * o.z;
    fr->shift_high = shift_high;
    fr->shift_low = shift_low;

    /* The bracket: inside the grown sphere and slab. */
    const double r = g->r;
    const double sphere = (1.0 + r) * (1.0 + BOUND_GROWTH);
    const double c_sphere = fr->o_norm2 - sphere * sphere; /* the sphere is grown: no need */
    double ends[2];
    const double disc = b * b - a * c_sphere;
    if (shape_solve_half_quadratic(a, b, c_sphere, disc, ends) != 2) return 0;
    double lo = ends[0], hi = ends[1];
    const double slab = r + BOUND_GROWTH * (1.0 + r);
    if (e.z == 0.0) {
        if (!(fabs(o.z) <= slab)) return 0;
    } else {
        const double z0 = (-slab - o.z) / e.z, z1 = (slab - o.z) / e.z;
        lo = fmax(lo, fmin(z0, z1));
        hi = fmin(hi, fmax(z0, z1));
    }
    if (!(lo < hi)) return 0;
    fr->lo = lo;
    fr->hi = hi;

    const double g0 = g_of(g, o);
    const double w0 = z2_minus_r2(g, o.z);
    fr->c[4] = a * a;
    fr->c[3] = 4.0 * a * b;
    fr->c[2] = 4.0 * b * b + 2.0 * a * g0 + 4.0 * e.z * e.z;
    fr->c[1] = 4.0 * b * g0 + 8.0 * o.z * e.z;
    fr->c[0] = g0 * g0 + 4.0 * w0;
    const double ab = fabs(b), ag0 = fabs(g0);
    fr->c_size[4] = fr->c[4];
    fr->c_size[3] = fabs(fr->c[3]);
    fr->c_size[2] = 4.0 * b * b + 2.0 * a * ag0 + 4.0 * e.z * e.z;
    fr->c_size[1] = 4.0 * ab * ag0 + 8.0 * fabs(o.z * e.z);
    fr->c_size[0] = g0 * g0 + 4.0 * fabs(w0);
    for (int i = 0; i < 5; i++)
        if (!isfinite(fr->c[i]) || !isfinite(fr->c_size[i])) return 0;
    return 1;
}

static double frame_t(const torus_frame *fr, double u)
{
    return ((fr->shift_low + u) + fr->shift_high) * fr->scale;
}

/* f(u) evaluated at the point, with f'(u) and a bound on the rounding error of
 * f (including the rounding of o when the frame was made), so that a
 * computed |f| below it may be an exact zero.
 * Error budget, with u the unit roundoff and S = |p|^2: each p_i = fma(...)
 * is within u |p_i| (and the frame's o within u |o_i|), which moves G by at
 * most 2 u (S + |o| |p|) <= u (3 S + |o|^2), plus u |G| for its compensated
 * sum; Z^2 - r^2 moves by 2 u |Z| (|Z| + r) plus 3 u |W|, W = Z^2 - r^2;
 * f = G^2 + 4 W adds 2 |G| dG and u |f|. Summed and doubled for the
 * second-order terms and the bound's own rounding:
 *   E = 4 u (|G| (3 S + |o|^2 + 2 |G|) + 4 |Z| (|Z| + r) + 8 |W|). */
SHAPE_FMA_DISPATCH(double, torus_eval, (const torus_frame *fr, double u, double *deriv, double *bound),
                   (fr, u, deriv, bound))
{
    const hr_vec3 o = fr->o, e = fr->e;
    const hr_vec3 p = shape_vec3(fma(u, e.x, o.x), fma(u, e.y, o.y), fma(u, e.z, o.z));
    const double G = g_of(fr->g, p);
    const double W = z2_minus_r2(fr->g, p.z);
    if (deriv) *deriv = 4.0 * G * (p.x * e.x + p.y * e.y + p.z * e.z) + 8.0 * p.z * e.z;
    if (bound) {
        const double S = p.x * p.x + p.y * p.y + p.z * p.z;
        const double aG = fabs(G), aZ = fabs(p.z);
        *bound = 4.0 * SHAPE_UNIT_ROUNDOFF *
                 (aG * (3.0 * S + fr->o_norm2 + 2.0 * aG) + 4.0 * aZ * (aZ + fr->g->r) +
                  8.0 * fabs(W));
    }
    return fma(G, G, 4.0 * W);
}

/* A bound on the rounding of Horner's f from the expanded coefficients:
 * each coefficient is a sum of at most three rounded products, within 4 u of
 * the sum of its terms' magnitudes (c_size), and Horner adds 2 n = 8
 * roundings; 16 u covers both with room for the second-order terms. */
static inline double horner_bound(const torus_frame *fr, double au)
{
    const double *m = fr->c_size;
    return 16.0 * SHAPE_UNIT_ROUNDOFF * ((((m[4] * au + m[3]) * au + m[2]) * au + m[1]) * au + m[0]);
}

/* f(u) and f'(u) by Horner from the expanded coefficients (a third of
 * torus_eval's cost), with horner_bound. Good enough to bracket and
 * approach a root; the last steps use torus_eval, whose error is relative
 * to the tube (see polish_root). */
static inline double eval_f_horner(const torus_frame *fr, double u, double *deriv, double *bound)
{
    const double *c = fr->c;
    *deriv = ((4.0 * c[4] * u + 3.0 * c[3]) * u + 2.0 * c[2]) * u + c[1];
    *bound = horner_bound(fr, fabs(u));
    return (((c[4] * u + c[3]) * u + c[2]) * u + c[1]) * u + c[0];
}

/* f'(u) and f''(u) by Horner from the expanded coefficients, with a bound on
 * the rounding of f' (as horner_bound: 4 u for the coefficients, 2 n = 6
 * roundings for Horner, rounded up to 12 u). */
static inline double eval_df(const torus_frame *fr, double u, double *deriv, double *bound)
{
    const double *c = fr->c, *m = fr->c_size;
    const double au = fabs(u);
    *deriv = (12.0 * c[4] * u + 6.0 * c[3]) * u + 2.0 * c[2];
    *bound = 12.0 * SHAPE_UNIT_ROUNDOFF *
             (((4.0 * m[4] * au + 3.0 * m[3]) * au + 2.0 * m[2]) * au + m[1]);
    return ((4.0 * c[4] * u + 3.0 * c[3]) * u + 2.0 * c[2]) * u + c[1];
}

typedef double (*eval_fn)(const torus_frame *fr, double u, double *deriv, double *bound);

/* A Newton step from a value within its rounding bound is noise over f':
 * one about the size of the noise itself (below 2^-26 of |x| + 1, where f'
 * is anything but tiny) takes the root to where the noise is centred; a
 * longer one says f' is ~0 there. */
#define SETTLED_STEP 0x1p-26

/* The one root of a function monotone on [x0, x1], given its values f0, f1
 * there, nonzero and of opposite signs: Newton steps from the regula falsi
 * point, replaced by bisection whenever a step leaves the bracket (which
 * shrinks at every evaluation), until the value is within its rounding
 * bound (no step can then do better than noise: one last Newton step takes
 * the root to where the noise is centred), or the step or the bracket is
 * down to rounding.
 * Next to a near-double root (a ray grazing the torus so closely that its
 * two crossings are 1e-8 apart) f' is ~1e-14 where f reaches its noise, and
 * that last step would land anywhere in the bracket, far from the root (an
 * exit 6e-8 behind a ray's origin came out 0.04 ahead of it). There the
 * search goes on with `precise` (NULL: none), a more accurate evaluation of
 * the same function, from the same point (Horner's f is noise at 1e-14 near
 * the tube, torus_eval's at 1e-16), and stops at x, without the step, once
 * that too is noise. */
static inline double bracketed_root(const torus_frame *fr, eval_fn fn, eval_fn precise,
                                    double x0, double x1, double f0, double f1)
{
    double lo = x0, hi = x1;
    const int rising = f1 > 0.0;
    double x = x0 - f0 * ((x1 - x0) / (f1 - f0));
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    /* A flag rather than assigning `precise` to `fn`: inlined at its call
     * sites, both calls are then direct. */
    int use_precise = 0;
    for (int i = 0; i < 80; i++) {
        double dfx, bound;
        const double fx = use_precise ? precise(fr, x, &dfx, &bound) : fn(fr, x, &dfx, &bound);
        if (fx == 0.0) return x;
        double next = x - fx / dfx;
        if (fabs(fx) <= bound) {
            if (next >= lo && next <= hi && fabs(next - x) <= SETTLED_STEP * (fabs(x) + 1.0))
                return next;
            if (!precise || use_precise) return x;
            use_precise = 1; /* the sign of fx is noise too: the bracket stays */
            continue;
        }
        if ((fx > 0.0) == rising) hi = x;
        else lo = x;
        const int inside = next >= lo && next <= hi;
        if (inside && next == x) return next;
        if (!inside) next = 0.5 * (lo + hi);
        const double step = fabs(next - x);
        x = next;
        if (step <= DBL_EPSILON * (fabs(x) + 0x1p-40)) break;
        if (hi - lo <= DBL_EPSILON * (fabs(lo) + fabs(hi)) + 0x1p-60) break;
    }
    return x;
}

/* Newton steps on the accurate f from a root found with Horner's f, which
 * is within Horner's noise of it: at most three, stopping once |f| is
 * within its rounding bound, never leaving [lo, hi], and only while |f|
 * falls (where f is nearly flat, next to a near-double root, a step from a
 * value near the noise can jump far from the root). */
static double polish_root(const torus_frame *fr, double u, double lo, double hi)
{
    double df, bound;
    double fx = torus_eval(fr, u, &df, &bound);
    for (int i = 0; i < 3 && fabs(fx) > bound; i++) {
        const double next = u - fx / df;
        if (!(next >= lo && next <= hi) || next == u) break;
        double next_df, next_bound;
        const double next_f = torus_eval(fr, next, &next_df, &next_bound);
        if (!(fabs(next_f) < fabs(fx))) break;
        u = next, fx = next_f, df = next_df, bound = next_bound;
    }
    return u;
}

/* --- Output ------------------------------------------------------------------ */

typedef struct collector {
    const torus_frame *fr;
    double tmin, tmax;
    int first_only;
    int done; /* no later root can be wanted */
    torus_roots *out;
} collector;

static void emit(collector *col, double u, int entering)
{
    if (col->done) return;
    const double t = frame_t(col->fr, u);
    if (!(t < col->tmax)) {
        if (t >= col->tmax) col->done = 1;
        return;
    }
    if (!(t > col->tmin) || col->out->count >= 4) return;
    col->out->t[col->out->count] = t;
    col->out->entering[col->out->count] = entering;
    col->out->count++;
    if (col->first_only) col->done = 1;
}

/* --- Bracketing ------------------------------------------------------------- */

static int sign_of(double v)
{
    return (v > 0.0) - (v < 0.0);
}

/* [lo, hi] split at the critical points of f: x[0] = lo, x[n-1] = hi, and
 * between them one point per sign change of f' on the pieces where f' is
 * monotone (split at the roots of f''), sorted. Returns n (2 to 5). */
static int critical_points(const torus_frame *fr, double x[5])
{
    const double *c = fr->c;
    const double lo = fr->lo, hi = fr->hi;
    double split[4];
    int n_split = 0;
    split[n_split++] = lo;
    double s[2];
    const double half_b = 1.5 * c[3], qa = 6.0 * c[4]; /* f''/2 = qa u^2 + 2 half_b u + c2 */
    const double disc = shape_difference_of_products(half_b, half_b, qa, c[2]);
    const int n_roots = shape_solve_half_quadratic(qa, half_b, c[2], disc, s);
    for (int i = 0; i < n_roots; i++)
        if (s[i] > split[n_split - 1] && s[i] < hi) split[n_split++] = s[i];
    split[n_split++] = hi;

    int n = 0;
    x[n++] = lo;
    double slope, bound;
    double left = eval_df(fr, split[0], &slope, &bound);
    for (int i = 0; i + 1 < n_split; i++) {
        const double right = eval_df(fr, split[i + 1], &slope, &bound);
        if (left != 0.0 && right != 0.0 && (left < 0.0) != (right < 0.0)) {
            const double root =
                bracketed_root(fr, eval_df, NULL, split[i], split[i + 1], left, right);
            if (root > x[n - 1] && root < hi) x[n++] = root;
        } else if (right == 0.0 && i + 2 < n_split && split[i + 1] > x[n - 1]) {
            x[n++] = split[i + 1]; /* f' touches zero at a root of f'' */
        }
        left = right;
    }
    x[n++] = hi;
    return n;
}

static void solve_bracketing(const torus_frame *fr, collector *col)
{
    double x[5];
    const int n = critical_points(fr, x);

    /* f at the ends: outside the grown sphere or slab, positive (2^-20 of
     * growth puts f there far above any rounding). At the critical points:
     * Horner's sign where it is clear of its bound, else the accurate value,
     * where a value within its own bound counts as zero: a tangent. */
    double f[5];
    f[0] = f[n - 1] = 1.0;
    for (int j = 1; j + 1 < n; j++) {
        double slope, bound;
        f[j] = eval_f_horner(fr, x[j], &slope, &bound);
        if (fabs(f[j]) > bound) continue;
        f[j] = torus_eval(fr, x[j], NULL, &bound);
        if (fabs(f[j]) <= bound) f[j] = 0.0;
    }

    /* In order along the ray: a zero at a critical point is a touch (the
     * sign is the same on both sides) or, rarely, a crossing at a stationary
     * point; a sign change across a piece is one crossing. */
    int left = 1; /* the sign of f before the point or piece at hand */
    for (int j = 0; j < n && !col->done; j++) {
        if (j > 0 && j + 1 < n && f[j] == 0.0) {
            int right = 0;
            for (int k = j + 1; k < n && right == 0; k++) right = sign_of(f[k]);
            if (right == left) { /* in and out, or out and in */
                emit(col, x[j], left > 0);
                emit(col, x[j], left < 0);
            } else {
                emit(col, x[j], left > 0);
            }
            left = right;
        }
        if (j + 1 == n) break;
        const double f_start = f[j], f_end = f[j + 1];
        if (f_start != 0.0 && f_end != 0.0 && (f_start < 0.0) != (f_end < 0.0)) {
            if (frame_t(fr, x[j]) >= col->tmax) break;
            /* A piece wholly before tmin holds no wanted root. */
            if (frame_t(fr, x[j + 1]) > col->tmin) {
                const double root =
                    bracketed_root(fr, eval_f_horner, torus_eval, x[j], x[j + 1], f_start, f_end);
                emit(col, polish_root(fr, root, x[j], x[j + 1]), f_start > 0.0);
            }
        }
        if (f_end != 0.0) left = sign_of(f_end);
    }
}

/* --- Ferrari ------------------------------------------------------------------ */

/* The largest real root of x^3 + a2 x^2 + a1 x + a0. */
static double cubic_largest_root(double a2, double a1, double a0)
{
    const double third = a2 / 3.0;
    const double Q = (a2 * a2 - 3.0 * a1) / 9.0;
    const double R = (2.0 * a2 * a2 * a2 - 9.0 * a2 * a1 + 27.0 * a0) / 54.0;
    const double Q3 = Q * Q * Q;
    if (R * R < Q3) {
        const double theta = acos(shape_clamp(R / sqrt(Q3), -1.0, 1.0));
        return -2.0 * sqrt(Q) * cos((theta + 2.0 * 3.14159265358979323846) / 3.0) - third;
    }
    const double A = -copysign(cbrt(fabs(R) + sqrt(R * R - Q3)), R);
    const double B = A != 0.0 ? Q / A : 0.0;
    return A + B - third;
}

/* Real roots of y^2 + beta y + gamma, appended to y[]. */
static int monic_quadratic(double beta, double gamma, double *y)
{
    const double half_b = 0.5 * beta;
    double roots[2];
    const int n = shape_solve_half_quadratic(1.0, half_b, gamma, half_b * half_b - gamma, roots);
    if (n != 2) return 0;
    y[0] = roots[0];
    y[1] = roots[1];
    return 2;
}

static int ferrari_roots(const torus_frame *fr, double u[4])
{
    const double *c = fr->c;
    const double A = c[3] / c[4], B = c[2] / c[4], C = c[1] / c[4], D = c[0] / c[4];
    const double A4 = 0.25 * A, A4s = A4 * A4;
    /* y = u + A/4: y^4 + p y^2 + q y + r0. */
    const double p = B - 6.0 * A4s;
    const double q = C - 2.0 * B * A4 + 8.0 * A4s * A4;
    const double r0 = D - C * A4 + B * A4s - 3.0 * A4s * A4s;
    double y[4];
    int n = 0;
    double m = 0.0;
    if (q != 0.0) m = cubic_largest_root(p, 0.25 * p * p - r0, -0.125 * q * q);
    if (q != 0.0 && m > 0.0 && isfinite(m)) {
        /* h = q / (2 s) is also +-sqrt((m + p/2)^2 - r0): the quotient is
         * inaccurate when m is tiny (the cubic formula gives it with an
         * absolute, not relative, error), the square root when it cancels;
         * take the square root unless (m + p/2)^2 is within 2 |r0|. */
        const double s = sqrt(2.0 * m), base = 0.5 * p + m;
        const double h2 = base * base - r0;
        const double h = h2 > 2.0 * fabs(r0) ? copysign(sqrt(h2), q) : 0.5 * q / s;
        n += monic_quadratic(s, base - h, y + n);
        n += monic_quadratic(-s, base + h, y + n);
    } else { /* biquadratic: z = y^2 */
        double z[2];
        if (monic_quadratic(p, r0, z) == 2)
            for (int i = 0; i < 2; i++)
                if (z[i] >= 0.0) {
                    y[n++] = -sqrt(z[i]);
                    y[n++] = sqrt(z[i]);
                }
    }
    int count = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(y[i])) u[count++] = y[i] - A4;
    return count;
}

/* Up to four Newton steps on the accurate f, keeping the best iterate and
 * stopping once |f| is within its rounding bound. */
static double newton_polish(const torus_frame *fr, double u)
{
    double best = u, best_f = INFINITY;
    for (int i = 0; i < 5; i++) {
        double df, bound;
        const double fx = torus_eval(fr, u, &df, &bound);
        if (fabs(fx) < best_f) {
            best_f = fabs(fx);
            best = u;
        }
        if (fabs(fx) <= bound || i == 4) break;
        const double next = u - fx / df;
        if (!isfinite(next) || next == u) break;
        u = next;
    }
    return best;
}

static void sort_small(double *v, int n)
{
    for (int i = 1; i < n; i++) {
        const double x = v[i];
        int j = i;
        while (j > 0 && v[j - 1] > x) {
            v[j] = v[j - 1];
            j--;
        }
        v[j] = x;
    }
}

static void solve_ferrari(const torus_frame *fr, int polish, collector *col)
{
    double u[4];
    int n = ferrari_roots(fr, u);
    if (polish)
        for (int i = 0; i < n; i++) u[i] = newton_polish(fr, u[i]);
    sort_small(u, n);
    /* The line starts and ends outside: crossings alternate from entering. */
    for (int i = 0; i < n && !col->done; i++) emit(col, u[i], i % 2 == 0);
}

int torus_solve(const torus_geometry *g, int solver, const hr_ray *ray, double tmin, double tmax,
                int first_only, torus_roots *out)
{
    out->count = 0;
    torus_frame fr;
    if (!frame_make(g, ray, &fr)) return 0;
    collector col = {&fr, tmin, tmax, first_only, 0, out};
    switch (solver) {
    case TORUS_SOLVER_FERRARI: solve_ferrari(&fr, 0, &col); break;
    case TORUS_SOLVER_FERRARI_NEWTON: solve_ferrari(&fr, 1, &col); break;
    default: solve_bracketing(&fr, &col); break;
    }
    return out->count;
}
