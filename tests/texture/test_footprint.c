/* The filtered checkerboard over a pixel's footprint (lib/texture/texture.c,
 * hri_texture_color_filtered, compiled into this test with the solid
 * textures) against numerical integration of the point texture over the
 * same footprint: the parallelogram p + s dp/dx + t dp/dy, s and t in
 * [-1/2, 1/2], on a floor (the plane y = 0.5, normal +y, the object's
 * space the world's).
 *
 * Reference: the midpoint rule on an N x N grid of (s, t), N = 1500, summed
 * in long double, of the checkerboard with A white and B black (the red
 * channel is A's share). Its error: a grid cell that no square's edge
 * crosses is exact; one that an edge crosses is off by at most 1 / N^2.
 * An edge line crosses at most 2N cells of the grid, and the footprint
 * holds at most E = (|a_x| + |b_x| + 1)(|a_z| + |b_z| + 1) * 2 pieces of
 * edge lines (each unit square of its box has two), so the rule is within
 * 2 E / N.
 *
 * - Footprints along the axes (the box around them is the parallelogram):
 *   the closed form is exact; we allow the rule's bound plus 1e-6.
 * - Footprints that lean (a floor's receding lines off the picture's
 *   centre: dp/dy with an x part as large as dp/dx's, or six times it):
 *   the box around the parallelogram is far larger than it, and the
 *   parallelogram is cut into pieces, each filtered by its own box
 *   (footprint_cuts). We require the result within 0.05 of the integral
 *   (plus the rule's bound) everywhere sampled, and at least twice as
 *   close to it, over all the cases, as the one box around the whole
 *   footprint is: what the cutting is for. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"
#include "texture/texture.h"
#include "geometry/vec.h"

#define N 1500

static hr_texture checker_texture(void)
{
    hr_texture t;
    memset(&t, 0, sizeof t);
    t.kind = hri_solid_texture_find(-1);
    const double params[7] = {1.0, 1, 1, 1, 0, 0, 0};
    memcpy(t.params, params, sizeof params);
    for (int i = 0; i < 4; i++) t.to_object[5 * i] = t.to_world[5 * i] = 1.0;
    return t;
}

static double integral(const hr_texture *t, hr_vec3 p, hr_vec3 a, hr_vec3 b)
{
    long double sum = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            const double s = (i + 0.5) / N - 0.5, u = (j + 0.5) / N - 0.5;
            sum += t->kind->solid(t->params, v3_madd(v3_madd(p, a, s), b, u)).r;
        }
    return (double)(sum / ((long double)N * N));
}

static double rule_bound(hr_vec3 a, hr_vec3 b)
{
    const double edges = 2.0 * (fabs(a.x) + fabs(b.x) + 1.0) * (fabs(a.z) + fabs(b.z) + 1.0);
    return 2.0 * edges / N;
}

static double filtered(const hr_texture *t, hr_vec3 p, hr_vec3 a, hr_vec3 b)
{
    hr_hit h;
    memset(&h, 0, sizeof h);
    h.point = p;
    h.normal = v3(0, 1, 0);
    return hri_texture_color_filtered(t, NULL, NULL, &h, a, b).r;
}

int main(void)
{
    hr_texture t = checker_texture();
    CHECK(t.kind && t.kind->solid_box);
    if (!t.kind) return hr_test_end();
    const hr_vec3 points[] = {{0.1, 0.5, 0.2}, {-1.37, 0.5, 2.71}, {5.5, 0.5, -3.25}, {0.999, 0.5, -0.001}};
    /* Along the axes: exact. */
    const hr_vec3 straight[][2] = {{{0.3, 0, 0}, {0, 0, 0.7}}, {{1.6, 0, 0}, {0, 0, 0.25}},
                                   {{0, 0, 2.3}, {0.8, 0, 0}}};
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 4; i++) {
            const hr_vec3 a = straight[k][0], b = straight[k][1];
            const double want = integral(&t, points[i], a, b), got = filtered(&t, points[i], a, b);
            CHECK_MSG(fabs(got - want) <= rule_bound(a, b) + 1e-6, "straight %d at %d: %.9g, integral %.9g", k, i,
                      got, want);
        }
    /* Leaning: within 0.05, and closer than the one box. */
    const hr_vec3 leaning[][2] = {{{0.3, 0, 0}, {0.3, 0, 0.9}},  {{0.2, 0, 0}, {1.2, 0, 1.5}},
                                  {{0.5, 0, 0.1}, {-0.6, 0, 1.1}}, {{0.15, 0, 0}, {0.9, 0, 2.4}}};
    double cut_error = 0.0, box_error = 0.0;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 4; i++) {
            const hr_vec3 a = leaning[k][0], b = leaning[k][1], p = points[i];
            const double want = integral(&t, p, a, b), got = filtered(&t, p, a, b);
            const hr_vec3 half = v3(0.5 * (fabs(a.x) + fabs(b.x)), 0.0, 0.5 * (fabs(a.z) + fabs(b.z)));
            const double box = t.kind->solid_box(t.params, p, half).r;
            CHECK_MSG(fabs(got - want) <= 0.05 + rule_bound(a, b), "leaning %d at %d: %.6g, integral %.6g", k, i,
                      got, want);
            cut_error += fabs(got - want);
            box_error += fabs(box - want);
        }
    printf("leaning footprints: mean error %.4f cut, %.4f one box\n", cut_error / 16, box_error / 16);
    CHECK_MSG(2.0 * cut_error <= box_error, "cut %.4f, one box %.4f", cut_error / 16, box_error / 16);
    return hr_test_end();
}
