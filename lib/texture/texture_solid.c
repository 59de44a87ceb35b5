/* Hill's solid textures (chapter 8): each a function of a point in the
 * object's own space and the material's parameters, and one row of the
 * table at the end. A new solid texture is a function here and a row
 * there; the SDL reader, the checks and the docs' list follow the table.
 *
 * Each texture blends between two colours, A and B, which multiply the
 * material's ambient and diffuse colours (so colour 1 1 1 leaves them as
 * they are). Parameters the material leaves out take the defaults of the
 * table, chosen to look right on Hill's generic shapes (a unit sphere, a
 * unit cube, a plane seen from a few units away). */
#include <math.h>

#include <hitray/shape_kit_cpu.h>

#include "texture/texture.h"
#include "util/color_bounds.h"
#include "geometry/vec.h"

#define PI 3.14159265358979323846

#define COLOR_PARAMS(prefix, r, g, b)                                          \
    {prefix " red", r, HR_TEXTURE_PARAM_ANY, -HR_MAX_COLOR, HR_MAX_COLOR},       \
        {prefix " green", g, HR_TEXTURE_PARAM_ANY, -HR_MAX_COLOR, HR_MAX_COLOR}, \
        {prefix " blue", b, HR_TEXTURE_PARAM_ANY, -HR_MAX_COLOR, HR_MAX_COLOR}

/* Colour A where `t` is 1, colour B where it is 0; the colours are the
 * parameters from `first` on. */
static hr_color blend(const double *p, int first, double t)
{
    const double *a = p + first, *b = p + first + 3;
    return rgb(b[0] + t * (a[0] - b[0]), b[1] + t * (a[1] - b[1]), b[2] + t * (a[2] - b[2]));
}

/* floor(x) mod 2, as 0 or 1, exact for every double: with k = floor(x),
 * k / 2 is exact (an odd k below 2^53 halves to a representable k' + 0.5;
 * from 2^53 on every double is even), so k - 2 floor(k / 2) is exactly 0
 * or 1. (fmod gives the same, some ten times slower.) */
static inline __attribute__((always_inline)) int parity(double x)
{
    const double k = floor(x);
    return k - 2.0 * floor(0.5 * k) == 1.0;
}

/* The mean over [x - h, x + h] of the square wave (-1)^floor(x), h >= 0.
 * Its integral from 0 is the triangle wave T(x) = 1 - |x mod 2 - 1| (x mod 2
 * exact: triangle_wave), so the mean is (T(x + h) - T(x - h)) / 2h, in
 * closed form. T's rounding (about u |x|, from x and x +- h) over 2h is the mean's
 * error; below h = 2^-26 max(1, |x|) that could pass 2^-26, and the wave
 * is taken at x alone (the point sample, exact: see parity). */
/* The triangle wave T(x) = 1 - |x mod 2 - 1|, x mod 2 taken as
 * x - 2 floor(x / 2), exact (x / 2 and 2 floor(x / 2) are, and their
 * difference is a multiple of x's ulp under 2) but for a subnormal x / 2,
 * where it may give 2 for 0, the same T; and far cheaper than fmod. */
static inline __attribute__((always_inline)) double triangle_wave(double x)
{
    return 1.0 - fabs(x - 2.0 * floor(0.5 * x) - 1.0);
}

static inline __attribute__((always_inline)) double square_wave_mean(double x, double h)
{
    const double size = fabs(x) > 1.0 ? fabs(x) : 1.0; /* fmax, without its call */
    if (!(h > 0x1p-26 * size)) return parity(x) ? -1.0 : 1.0;
    return (triangle_wave(x + h) - triangle_wave(x - h)) / (2.0 * h);
}

/* -1, Hill's checkerboard ("jump"): A where floor(x/s) + floor(y/s) +
 * floor(z/s) is even, B where it is odd: cubes of side s, alternating, so
 * any plane through the object shows squares.
 *
 * Box-filtered in closed form: (-1)^(floor x + floor y + floor z) is the
 * product of one square wave per axis, so its mean over a box is the
 * product of the three axes' means (square_wave_mean), and the share of A
 * is (1 + that) / 2. With half = 0 every axis is point-sampled: the parity
 * of the sum, as Hill's jump. */
static const hr_texture_param checker_params[] = {
    {"size", 1.0, HR_TEXTURE_PARAM_POSITIVE, 0.0, 1e300},
    COLOR_PARAMS("colour A", 1.0, 1.0, 1.0),
    COLOR_PARAMS("colour B", 0.1, 0.1, 0.1),
};
static inline __attribute__((always_inline)) hr_color checkerboard_box_body(const double *p, hr_vec3 q,
                                                                           hr_vec3 half)
{
    const double s = p[0];
    const double mean = square_wave_mean(q.x / s, half.x / s) *
                        square_wave_mean(q.y / s, half.y / s) *
                        square_wave_mean(q.z / s, half.z / s);
    return blend(p, 1, 0.5 * (1.0 + mean));
}
/* The filtered checkerboard's cost is mostly floor, six a box: baseline
 * x86-64 has no instruction for it (a dozen, with a branch), SSE4.1 has
 * one (roundsd), exact as floor is. Where the CPU has it (probed as AVX2,
 * which implies it, shape_kit_cpu.h) the same code runs compiled for it:
 * the same values bit for bit (no FMA: the target adds no contraction). */
#if defined(__GNUC__) && defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__))
#define CHECKER_AVX2 1
__attribute__((target("avx2"), noinline)) static hr_color checkerboard_box_avx2(const double *p, hr_vec3 q,
                                                                               hr_vec3 half)
{
    return checkerboard_box_body(p, q, half);
}
/* A whole footprint in one call, its pieces' boxes inlined. */
__attribute__((target("avx2"), noinline)) static hr_color
checkerboard_footprint_avx2(const double *p, const hri_footprint_pieces *f)
{
    return hri_footprint_mean(checkerboard_box_body, p, f);
}
#endif
static hr_color checkerboard_box(const double *p, hr_vec3 q, hr_vec3 half)
{
#ifdef CHECKER_AVX2
    if (shape_cpu_has_avx2()) return checkerboard_box_avx2(p, q, half);
#endif
    return checkerboard_box_body(p, q, half);
}
static hr_color checkerboard_footprint(const double *p, const hri_footprint_pieces *f)
{
#ifdef CHECKER_AVX2
    if (shape_cpu_has_avx2()) return checkerboard_footprint_avx2(p, f);
#endif
    return hri_footprint_mean(checkerboard_box_body, p, f);
}
static hr_color checkerboard(const double *p, hr_vec3 q)
{
    return checkerboard_box(p, q, v3(0.0, 0.0, 0.0));
}

/* -2, Hill's wood grain: rings about the z axis, r / M apart, whose radius
 * wobbles k rings with the angle about the axis (N times around) and turns
 * with the height (B radians per unit of z):
 *   rings(r / M + k sin(N theta + B z)),
 * A on the even rings, B on the odd ones. */
static const hr_texture_param wood_params[] = {
    {"ring spacing", 0.1, HR_TEXTURE_PARAM_POSITIVE, 0.0, 1e300},
    {"wobble", 0.4, HR_TEXTURE_PARAM_ANY, -1e6, 1e6},
    {"wobbles around", 4.0, HR_TEXTURE_PARAM_WHOLE, 0.0, 1e6},
    {"twist", 2.0, HR_TEXTURE_PARAM_ANY, -1e6, 1e6},
    COLOR_PARAMS("colour A", 0.85, 0.6, 0.35),
    COLOR_PARAMS("colour B", 0.45, 0.25, 0.1),
};
/* Filtered, the rings are box-filtered across themselves: the ring number
 * is taken as linear over the box, and the square wave of its parity is
 * averaged over the box's half-width in ring numbers, sum_i |d ring / d x_i|
 * half_i (exact where the box spans one axis across straight rings; a box
 * filter of the same width elsewhere). Where rings are finer than the box
 * the mean tends to 0 and the colour to (A + B) / 2; on the axis, where
 * they wobble infinitely fast, the colour is that mean. */
static hr_color wood_box(const double *p, hr_vec3 q, hr_vec3 half)
{
    const double r = hypot(q.x, q.y);
    const double theta = atan2(q.y, q.x);
    const double phase = p[2] * theta + p[3] * q.z;
    const double ring = r / p[0] + p[1] * sin(phase);
    double width = 0.0;
    if (half.x > 0.0 || half.y > 0.0 || half.z > 0.0) {
        const double turn = p[1] * cos(phase) * p[2] / (r * r); /* d ring / d theta over r^2 */
        const double gx = q.x / (r * p[0]) - turn * q.y;
        const double gy = q.y / (r * p[0]) + turn * q.x;
        const double gz = p[1] * cos(phase) * p[3];
        width = fabs(gx) * half.x + fabs(gy) * half.y + fabs(gz) * half.z;
        if (!(width < 1e300)) return blend(p, 4, 0.5);
    }
    return blend(p, 4, 0.5 * (1.0 + square_wave_mean(ring, width)));
}
static hr_color wood(const double *p, hr_vec3 q)
{
    return wood_box(p, q, v3(0.0, 0.0, 0.0));
}

/* -3, Hill's marble: veins across z (f of them per unit) bent by his
 * turbulence of the point scaled by `noise scale`, of `octaves` layers,
 * with strength A: the undulating sine
 *   t = sqrt(|sin(pi f z + A turb(scale * p))|)
 * blends B (t = 0, in the veins, where the sine crosses 0) to A (t = 1);
 * the square root keeps the veins thin. */
static const hr_texture_param marble_params[] = {
    {"veins per unit", 1.5, HR_TEXTURE_PARAM_ANY, -1e6, 1e6},
    {"noise scale", 2.0, HR_TEXTURE_PARAM_POSITIVE, 0.0, 1e6},
    {"turbulence", 5.0, HR_TEXTURE_PARAM_ANY, -1e6, 1e6},
    {"octaves", 5.0, HR_TEXTURE_PARAM_WHOLE, 1.0, 16.0},
    COLOR_PARAMS("colour A", 0.95, 0.94, 0.9),
    COLOR_PARAMS("colour B", 0.3, 0.3, 0.38),
};
/* The mean of sqrt|sin| over a period, (1/pi) int_0^pi sqrt(sin x) dx
 * (to 30 digits by mpmath's quad). */
#define MARBLE_MEAN 0.762759763501813188062325980964
/* Filtered, the veins fade toward their mean where they are finer than
 * the box: the phase's spread over the box is estimated as the vein
 * term's, 2 pi f half_z, plus the turbulence's, its strength times the
 * noise scale times octaves / 2 (each octave's slope, frequency times
 * weight, is about the first's, and the sum of weights about 2) across the
 * box's widest side; t fades linearly to the mean as that spread reaches
 * pi, one period of |sin|. A band limit of the same kind as the wood's,
 * not an exact average: the turbulence has no closed form. */
static hr_color marble_box(const double *p, hr_vec3 q, hr_vec3 half)
{
    const double turb = hri_turbulence(v3_scale(q, p[1]), (int32_t)p[3]);
    /* The phase overflows for z near double's range: a vein there (sin of
     * an infinite phase is NaN, which would reach the pixel). */
    const double phase = PI * p[0] * q.z + p[2] * turb;
    double t = isfinite(phase) ? sqrt(fabs(sin(phase))) : 0.0;
    if (half.x > 0.0 || half.y > 0.0 || half.z > 0.0) {
        const double widest = fmax(half.x, fmax(half.y, half.z));
        const double spread = 2.0 * PI * fabs(p[0]) * half.z + fabs(p[2]) * p[1] * 0.5 * p[3] * 2.0 * widest;
        const double fade = spread < PI ? spread / PI : 1.0;
        t += fade * (MARBLE_MEAN - t);
    }
    return blend(p, 4, t);
}
static hr_color marble(const double *p, hr_vec3 q)
{
    return marble_box(p, q, v3(0.0, 0.0, 0.0));
}

#define ROW(id, name, params, fn, box, footprint)                                        \
    {id, name, params, (int32_t)(sizeof params / sizeof params[0]), fn, box, footprint}
/* Numbered from -1 down without gaps: hr_solid_texture_name promises it. */
static const hr_texture_kind solid_textures[] = {
    ROW(-1, "checkerboard", checker_params, checkerboard, checkerboard_box, checkerboard_footprint),
    ROW(-2, "wood", wood_params, wood, wood_box, NULL),
    ROW(-3, "marble", marble_params, marble, marble_box, NULL),
};
#define SOLID_COUNT ((int32_t)(sizeof solid_textures / sizeof solid_textures[0]))

const hr_texture_kind *hri_solid_texture_find(int32_t id)
{
    for (int32_t i = 0; i < SOLID_COUNT; i++)
        if (solid_textures[i].id == id) return &solid_textures[i];
    return NULL;
}

HR_API const char *hr_solid_texture_name(int32_t texture)
{
    const hr_texture_kind *kind = hri_solid_texture_find(texture);
    return kind ? kind->name : NULL;
}

/* Image textures: the part of (u, v) the image covers (it repeats beyond
 * it, so u from 0 to 0.25 tiles it four times across), and the filter. */
static const hr_texture_param image_params[] = {
    {"u min", 0.0, HR_TEXTURE_PARAM_ANY, -1e300, 1e300},
    {"u max", 1.0, HR_TEXTURE_PARAM_ANY, -1e300, 1e300},
    {"v min", 0.0, HR_TEXTURE_PARAM_ANY, -1e300, 1e300},
    {"v max", 1.0, HR_TEXTURE_PARAM_ANY, -1e300, 1e300},
    {"nearest", 0.0, HR_TEXTURE_PARAM_WHOLE, 0.0, 1.0},
};
const hr_texture_kind hri_image_texture_kind = ROW(1, "image", image_params, NULL, NULL, NULL);
