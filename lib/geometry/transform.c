/* Hill's transform pairs (include/hitray/transform.h). Each step multiplies
 * the matrix on the right and the inverse on the left by the step's exact
 * inverse, so M * M^-1 stays as close to identity as the steps allow. */
#include <math.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "util/errors.h"
#include "geometry/transform_inline.h"
#include "geometry/vec.h"

static void mat_identity(double m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1.0;
}

/* r = a * b (r may alias neither). Each entry is summed as
 * ((((0 + a_i0 b_0j) + a_i1 b_1j) + a_i2 b_2j) + a_i3 b_3j): the same
 * operations in the same order as the textbook triple loop (the leading
 * 0 + keeps a -0 sum +0, as that loop's does). With SSE2 two entries of a
 * row go together, each lane rounding as the scalar code does. */
static void mat_mul(double r[16], const double a[16], const double b[16])
{
#ifdef __SSE2__
    for (int i = 0; i < 4; i++) {
        __m128d left = _mm_setzero_pd(), right = _mm_setzero_pd();
        for (int k = 0; k < 4; k++) {
            const __m128d aik = _mm_set1_pd(a[4 * i + k]);
            left = _mm_add_pd(left, _mm_mul_pd(aik, _mm_loadu_pd(b + 4 * k)));
            right = _mm_add_pd(right, _mm_mul_pd(aik, _mm_loadu_pd(b + 4 * k + 2)));
        }
        _mm_storeu_pd(r + 4 * i, left);
        _mm_storeu_pd(r + 4 * i + 2, right);
    }
#else
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += a[4 * i + k] * b[4 * k + j];
            r[4 * i + j] = s;
        }
#endif
}

/* The pair after a step: t * step and step^-1 * t^-1. */
static void stepped(const hr_transform *t, const double step[16], const double step_inv[16],
                    double m[16], double inv[16])
{
    mat_mul(m, t->m, step);
    mat_mul(inv, step_inv, t->inv);
}

/* t <- t * step; t^-1 <- step^-1 * t^-1. */
static void apply_step(hr_transform *t, const double step[16], const double step_inv[16])
{
    double m[16], inv[16];
    stepped(t, step, step_inv, m, inv);
    memcpy(t->m, m, sizeof m);
    memcpy(t->inv, inv, sizeof inv);
}

/* apply_step for the calls that can refuse: a step whose own inverse is not
 * representable (a factor of 1e-310 has none in double) is refused like a
 * zero factor, and so is a step after which the pair over- or underflows
 * (scale 1e-200 twice: M ~ 1e-400 = 0, M^-1 ~ 1e400 = inf), so the error
 * names the step that caused it. A refused step leaves `t` as it was. */
static hr_status checked_step(hr_transform *t, const double step[16], const double step_inv[16])
{
    if (!doubles_are_finite(step, 16) || !doubles_are_finite(step_inv, 16)) return HR_ERROR_NUMERIC;
    double m[16], inv[16];
    stepped(t, step, step_inv, m, inv);
    if (!doubles_are_finite(m, 16) || !doubles_are_finite(inv, 16)) return HR_ERROR_NUMERIC;
    memcpy(t->m, m, sizeof m);
    memcpy(t->inv, inv, sizeof inv);
    return HR_OK;
}

HR_API void hr_transform_identity(hr_transform *t)
{
    if (!t) return;
    mat_identity(t->m);
    mat_identity(t->inv);
}

/* The products of a translation or scale step with a finite pair, as
 * mat_mul gives them, bit for bit, without its 128 multiplications (most of
 * the time of a scene of many small objects, each placed by a few steps).
 * In mat_mul's sum ((((0 + p0) + p1) + p2) + p3) every product with a zero
 * of the step is a zero (the pair is finite), and adding zeros to the
 * leading +0 leaves +0, so an entry with one nonzero product x is x + 0.0
 * (x, or +0 for x = -0), and the translation column's sum keeps mat_mul's
 * order. For a pair that is not finite (inf * 0 is NaN there) the steps
 * take mat_mul itself. test_transform_steps compares the two. */
static void translated(hr_transform *t, double dx, double dy, double dz)
{
    double *m = t->m, *inv = t->inv;
    const double d[3] = {dx, dy, dz};
    for (int i = 0; i < 4; i++) {
        double *row = m + 4 * i;
        const double c = (((0.0 + row[0] * dx) + row[1] * dy) + row[2] * dz) + row[3];
        row[0] += 0.0, row[1] += 0.0, row[2] += 0.0;
        row[3] = c;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) inv[4 * i + j] = (inv[4 * i + j] + 0.0) + -d[i] * inv[12 + j];
    for (int j = 0; j < 4; j++) inv[12 + j] += 0.0;
}
static void scaled(hr_transform *t, const double s[3], const double si[3])
{
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 3; j++) t->m[4 * i + j] = t->m[4 * i + j] * s[j] + 0.0;
        t->m[4 * i + 3] += 0.0;
    }
    for (int j = 0; j < 4; j++) {
        for (int i = 0; i < 3; i++) t->inv[4 * i + j] = si[i] * t->inv[4 * i + j] + 0.0;
        t->inv[12 + j] += 0.0;
    }
}

HR_API void hr_transform_translate(hr_transform *t, double dx, double dy, double dz)
{
    if (!t) return;
    if (doubles_are_finite(t->m, 16) && doubles_are_finite(t->inv, 16) && isfinite(dx) && isfinite(dy) &&
        isfinite(dz)) {
        translated(t, dx, dy, dz);
        return;
    }
    double s[16], si[16];
    mat_identity(s);
    mat_identity(si);
    s[3] = dx, s[7] = dy, s[11] = dz;
    si[3] = -dx, si[7] = -dy, si[11] = -dz;
    apply_step(t, s, si);
}

HR_API hr_status hr_transform_scale(hr_transform *t, double sx, double sy, double sz)
{
    if (!t) return HR_ERROR_INVALID_ARGUMENT;
    if (sx == 0.0 || sy == 0.0 || sz == 0.0 || !isfinite(sx) || !isfinite(sy) || !isfinite(sz))
        return HR_ERROR_NUMERIC;
    const double inverse[3] = {1.0 / sx, 1.0 / sy, 1.0 / sz};
    if (doubles_are_finite(t->m, 16) && doubles_are_finite(t->inv, 16)) {
        /* checked_step's refusals: an inverse that is not finite, or a pair
         * that over- or underflows; t is left as it was. */
        if (!doubles_are_finite(inverse, 3)) return HR_ERROR_NUMERIC;
        hr_transform next = *t;
        scaled(&next, (const double[3]){sx, sy, sz}, inverse);
        if (!doubles_are_finite(next.m, 16) || !doubles_are_finite(next.inv, 16)) return HR_ERROR_NUMERIC;
        *t = next;
        return HR_OK;
    }
    double s[16], si[16];
    mat_identity(s);
    mat_identity(si);
    s[0] = sx, s[5] = sy, s[10] = sz;
    si[0] = inverse[0], si[5] = inverse[1], si[10] = inverse[2];
    return checked_step(t, s, si);
}

/* Rodrigues' rotation matrix about a unit axis; its inverse is its
 * transpose, which is exact. Multiples of 90 degrees use exact sines and
 * cosines so axis-aligned rotations keep zeros exact. */
HR_API hr_status hr_transform_rotate(hr_transform *t, double degrees, double ux, double uy,
                                     double uz)
{
    if (!t) return HR_ERROR_INVALID_ARGUMENT;
    double len = sqrt(ux * ux + uy * uy + uz * uz);
    if (!(len > 0.0) || !isfinite(len) || !isfinite(degrees)) return HR_ERROR_NUMERIC;
    ux /= len, uy /= len, uz /= len;
    double c, s;
    double turns = degrees / 90.0;
    if (turns == floor(turns) && fabs(turns) < 1e15) {
        static const double cos_q[4] = {1, 0, -1, 0}, sin_q[4] = {0, 1, 0, -1};
        long q = (long)fmod(turns, 4.0);
        if (q < 0) q += 4;
        c = cos_q[q], s = sin_q[q];
    } else {
        double rad = degrees * (3.14159265358979323846 / 180.0);
        c = cos(rad), s = sin(rad);
    }
    double k = 1.0 - c;
    double r[16] = {c + ux * ux * k,      ux * uy * k - uz * s, ux * uz * k + uy * s, 0,
                    uy * ux * k + uz * s, c + uy * uy * k,      uy * uz * k - ux * s, 0,
                    uz * ux * k - uy * s, uz * uy * k + ux * s, c + uz * uz * k,      0,
                    0,                    0,                    0,                    1};
    double ri[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) ri[4 * i + j] = r[4 * j + i];
    return checked_step(t, r, ri);
}

HR_API void hr_transform_compose(hr_transform *t, const hr_transform *other)
{
    if (!t || !other) return;
    apply_step(t, other->m, other->inv);
}

/* Inverse of an affine matrix: invert the 3x3 part by cofactors (in long
 * double, so a badly scaled matrix loses less), then the translation. */
HR_API hr_status hr_transform_from_matrix(hr_transform *t, const double m[16])
{
    if (!t || !m) return HR_ERROR_INVALID_ARGUMENT;
    for (int i = 0; i < 16; i++)
        if (!isfinite(m[i])) return HR_ERROR_NUMERIC;
    if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) return HR_ERROR_NUMERIC;
    long double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
                i = m[10];
    long double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
    long double det = a * A + b * B + c * C;
    if (det == 0 || !isfinite(det)) return HR_ERROR_NUMERIC;
    long double inv3[9] = {A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
                           B / det, (a * i - c * g) / det,  -(a * f - c * d) / det,
                           C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
    /* Refuse what is singular in practice, judged by the condition number
     * ||A|| ||A^-1|| (max-row-sum norms), not by the determinant: diag(1e6,
     * 1e-6, 1) is perfectly invertible with det 1e0 while a scaled rotation
     * may have a tiny one. Past 1e15 (eps * cond > 0.1) the inverse carries
     * no correct digit. */
    long double norm = 0, norm_inv = 0;
    for (int r = 0; r < 3; r++) {
        long double row = 0, row_inv = 0;
        for (int k = 0; k < 3; k++) {
            row += fabsl((long double)m[4 * r + k]);
            row_inv += fabsl(inv3[3 * r + k]);
        }
        if (row > norm) norm = row;
        if (row_inv > norm_inv) norm_inv = row_inv;
    }
    if (!(norm * norm_inv <= 1e15L)) return HR_ERROR_NUMERIC;
    double inv[16];
    for (int r = 0; r < 3; r++) {
        long double tr = 0;
        for (int k = 0; k < 3; k++) {
            inv[4 * r + k] = (double)inv3[3 * r + k];
            tr -= inv3[3 * r + k] * (long double)m[4 * k + 3];
        }
        inv[4 * r + 3] = (double)tr;
    }
    inv[12] = inv[13] = inv[14] = 0.0;
    inv[15] = 1.0;
    /* Well conditioned but tiny (all factors ~1e-310): the inverse is not
     * representable in double. */
    if (!doubles_are_finite(inv, 16)) return HR_ERROR_NUMERIC;
    memcpy(t->m, m, sizeof t->m);
    memcpy(t->inv, inv, sizeof t->inv);
    return HR_OK;
}

HR_API hr_vec3 hr_transform_point(const double m[16], hr_vec3 p) { return hri_xform_point(m, p); }

HR_API hr_vec3 hr_transform_vector(const double m[16], hr_vec3 v) { return hri_xform_vector(m, v); }

HR_API hr_vec3 hr_transform_normal(const double inv[16], hr_vec3 n) { return hri_xform_normal(inv, n); }
