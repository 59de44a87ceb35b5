/* An image texture filtered by a pixel's footprint, end to end, against a
 * reference worked out here in long double from the pattern alone.
 *
 * A pixmap of 64 x 16 texels of a known pattern lies on Hill's square
 * (turned 30 degrees about its normal, tiled twice across u and shifted a
 * quarter in v, so the tiles' seams cross the image), seen head-on from
 * the eye at (0, 0, D). The square is then perpendicular to the view, so
 * the map from image position to the square is affine and its derivatives
 * are exact: one pixel moves the hit by D (2 tan(fov / 2) / height) along
 * the camera's u and v. Lit by the ambient term alone (ambient 1, global
 * ambient 1, no light), a pixel shows the texture's value, which at 1 spp
 * must be the trilinear mip-map look-up of the footprint:
 *   - the footprint's longer side in texels of the image, T, from the
 *     exact (s, t) derivatives (so a seam inside the footprint, where s
 *     jumps from 1 to 0, must not widen it);
 *   - level 0, bilinear, where T <= 1; else levels floor(log2 T) and the
 *     next, blended by log2 T's fraction (the top level where it passes);
 *   - level k's texels the means of the image's 2^k x 2^k blocks (a side
 *     already down to 1 averages the whole side), computed here from the
 *     pattern, not from pixmap.c's pyramid.
 * Three distances give T < 1 (bilinear, no filter), about 6 and about 16.
 * The pattern's values are multiples of 1/16, so every level is exact in
 * float; the tolerance, 2e-6, covers the image's float pixels and double
 * against long double in the coordinates. A render that ignored the
 * footprint, picked the level from the (u, v) difference across a seam, or
 * averaged its levels otherwise is off by 1e-2 or more at the pixels
 * checked. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

#define TW 64 /* the pixmap's texels */
#define TH 16
#define W 24 /* the render's pixels */
#define H 24
#define FOV 40.0L
#define TURN 30.0L       /* degrees about z */
#define U_RANGE 0.5L     /* texture parameters: u in [0, 0.5], v in [0.25, 1.25] */
#define V_MIN 0.25L
#define PI_L 3.141592653589793238462643383279502884L

/* The pattern: texel (x, y), row y from the top, channel c; multiples of
 * 1/16 with detail at every scale. */
static long double pattern(int x, int y, int c)
{
    const int k = c == 0 ? (x * 7 + y * 13) % 17 : c == 1 ? (x / 4 + y) % 16 : ((x ^ y) & 15);
    return (long double)(k > 16 ? 16 : k) / 16.0L;
}

static int level_side(int n, int k) { return (n >> k) > 0 ? n >> k : 1; }

/* Level k's texel (i, j): the mean of the image's block it covers. */
static long double level_texel(int k, int i, int j, int c)
{
    const int bw = TW / level_side(TW, k), bh = TH / level_side(TH, k);
    long double sum = 0.0L;
    for (int y = j * bh; y < (j + 1) * bh; y++)
        for (int x = i * bw; x < (i + 1) * bw; x++) sum += pattern(x, y, c);
    return sum / (long double)(bw * bh);
}

static int wrap(int x, int n) { return ((x % n) + n) % n; }

/* Bilinear between level k's texel centres at (s, t) in [0, 1)^2, t up. */
static long double bilinear(int k, long double s, long double t, int c)
{
    const int w = level_side(TW, k), h = level_side(TH, k);
    const long double gx = s * w - 0.5L, gy = (1.0L - t) * h - 0.5L;
    const long double x0 = floorl(gx), y0 = floorl(gy), ax = gx - x0, ay = gy - y0;
    const int xa = wrap((int)x0, w), xb = wrap((int)x0 + 1, w), ya = wrap((int)y0, h), yb = wrap((int)y0 + 1, h);
    const long double top = (1.0L - ax) * level_texel(k, xa, ya, c) + ax * level_texel(k, xb, ya, c);
    const long double bottom = (1.0L - ax) * level_texel(k, xa, yb, c) + ax * level_texel(k, xb, yb, c);
    return (1.0L - ay) * top + ay * bottom;
}

static int levels(void)
{
    int n = 1;
    while (level_side(TW, n - 1) > 1 || level_side(TH, n - 1) > 1) n++;
    return n;
}

/* The reference value of pixel (px, py) seen from distance d; 0 where the
 * footprint is not inside the square (then *inside is 0). `texels` gets T. */
static long double reference(long double d, int px, int py, int c, int *inside, long double *texels)
{
    const long double hh = tanl(0.5L * FOV * PI_L / 180.0L), hw = hh * W / H;
    const long double X = d * hw * (2.0L * (px + 0.5L) / W - 1.0L), Y = d * hh * (1.0L - 2.0L * (py + 0.5L) / H);
    const long double step_x = d * hw * 2.0L / W, step_y = -d * hh * 2.0L / H; /* per pixel */
    /* World to object: turned back by TURN. */
    const long double a = -TURN * PI_L / 180.0L, ca = cosl(a), sa = sinl(a);
    const long double qx = ca * X - sa * Y, qy = sa * X + ca * Y;
    const long double dqx[2] = {ca * step_x, sa * step_x}, dqy[2] = {-sa * step_y, ca * step_y};
    *inside = fabsl(qx) + fabsl(dqx[0]) + fabsl(dqy[0]) < 0.95L && fabsl(qy) + fabsl(dqx[1]) + fabsl(dqy[1]) < 0.95L;
    /* u = (x + 1) / 2, v = (y + 1) / 2; s = u / U_RANGE, t = v - V_MIN, each
     * wrapped into [0, 1). */
    long double s = 0.5L * (qx + 1.0L) / U_RANGE, t = 0.5L * (qy + 1.0L) - V_MIN;
    s -= floorl(s), t -= floorl(t);
    const long double ds[2] = {0.5L * dqx[0] / U_RANGE, 0.5L * dqy[0] / U_RANGE};
    const long double dt[2] = {0.5L * dqx[1], 0.5L * dqy[1]};
    const long double along_x = hypotl(ds[0] * TW, dt[0] * TH), along_y = hypotl(ds[1] * TW, dt[1] * TH);
    *texels = along_x > along_y ? along_x : along_y;
    if (*texels <= 1.0L) return bilinear(0, s, t, c);
    const long double lod = log2l(*texels);
    if (lod >= levels() - 1) return bilinear(levels() - 1, s, t, c);
    const int k = (int)lod;
    const long double f = lod - k;
    return (1.0L - f) * bilinear(k, s, t, c) + f * bilinear(k + 1, s, t, c);
}

static hr_scene *square_scene(hr_context *ctx)
{
    hr_scene *scene = NULL;
    hr_image *pixmap = NULL;
    CHECK_OK(hr_scene_create(ctx, &scene));
    CHECK_OK(hr_image_create(ctx, TW, TH, 3, &pixmap));
    float *texels = hr_image_data(pixmap);
    for (int y = 0; y < TH; y++)
        for (int x = 0; x < TW; x++)
            for (int c = 0; c < 3; c++) texels[(y * TW + x) * 3 + c] = (float)pattern(x, y, c);
    CHECK_OK(hr_scene_set_pixmap(scene, 1, pixmap));
    hr_image_destroy(pixmap);
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.background = (hr_color){0, 0, 0};
    g.global_ambient = (hr_color){1, 1, 1};
    CHECK_OK(hr_scene_set_globals(scene, &g));
    hr_material m;
    hr_material_default(&m);
    m.ambient = (hr_color){1, 1, 1};
    m.diffuse = (hr_color){0, 0, 0};
    m.texture = 1;
    const double params[4] = {0.0, (double)U_RANGE, (double)V_MIN, (double)(V_MIN + 1.0L)};
    m.parameters = params, m.parameter_count = 4;
    const double c = cos((double)(TURN * PI_L / 180.0L)), s = sin((double)(TURN * PI_L / 180.0L));
    const double turn[16] = {c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    hr_object_desc desc = {.struct_size = sizeof desc, .shape = "square", .material = &m, .transform = turn};
    CHECK_MSG(hr_scene_add_object(scene, &desc, NULL) == HR_OK, "%s", hr_context_last_error(ctx));
    CHECK_OK(hr_scene_commit(scene));
    return scene;
}

int main(void)
{
    hr_context *ctx = NULL;
    CHECK_OK(hr_context_create(&ctx));
    hr_scene *scene = square_scene(ctx);
    const long double distances[3] = {0.5L, 3.0L, 8.0L};
    int checked[3] = {0, 0, 0}, seams = 0;
    long double least[3] = {1e30L, 1e30L, 1e30L}, most[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        hr_camera cam;
        hr_camera_default(&cam);
        cam.width = W, cam.height = H, cam.view_angle = (double)FOV;
        cam.eye = (hr_vec3){0, 0, (double)distances[k]};
        cam.look = (hr_vec3){0, 0, 0};
        cam.up = (hr_vec3){0, 1, 0};
        hr_render_options o;
        hr_render_options_default(&o);
        o.width = W, o.height = H, o.samples_per_pixel = 1, o.threads = 1;
        o.texture_filter = HR_TEXTURE_FILTER_FOOTPRINT;
        hr_image *img = NULL;
        CHECK_MSG(hr_render(scene, &cam, &o, &img, NULL) == HR_OK, "render: %s", hr_context_last_error(ctx));
        if (!img) continue;
        const float *got = hr_image_data(img);
        for (int py = 0; py < H; py++)
            for (int px = 0; px < W; px++) {
                int inside = 0;
                long double texels = 0.0L, want[3];
                for (int c = 0; c < 3; c++) want[c] = reference(distances[k], px, py, c, &inside, &texels);
                if (!inside) continue;
                checked[k]++;
                least[k] = texels < least[k] ? texels : least[k];
                most[k] = texels > most[k] ? texels : most[k];
                /* A seam of s inside the footprint: s within a footprint of 0 or 1. */
                const long double hh = tanl(0.5L * FOV * PI_L / 180.0L);
                const long double X = distances[k] * hh * (2.0L * (px + 0.5L) / W - 1.0L);
                const long double Y = distances[k] * hh * (1.0L - 2.0L * (py + 0.5L) / H);
                const long double qx = cosl(TURN * PI_L / 180.0L) * X + sinl(TURN * PI_L / 180.0L) * Y;
                seams += fabsl(qx) < distances[k] * hh * 2.0L / W;
                for (int c = 0; c < 3; c++) {
                    const long double err = fabsl((long double)got[(py * W + px) * 3 + c] - want[c]);
                    CHECK_MSG(err <= 2e-6L, "distance %g, pixel (%d, %d) channel %d: %.9g, want %.9Lg (T = %.4Lg)",
                              (double)distances[k], px, py, c, (double)got[(py * W + px) * 3 + c], want[c],
                              texels);
                }
            }
        hr_image_destroy(img);
    }
    /* Each distance checked many pixels, in the regime it is for. */
    CHECK_MSG(checked[0] > 100 && most[0] < 1.0L, "near: %d pixels, T up to %Lg", checked[0], most[0]);
    CHECK_MSG(checked[1] > 100 && least[1] > 4.0L && most[1] < 8.0L, "middle: %d pixels, T %Lg..%Lg", checked[1],
              least[1], most[1]);
    CHECK_MSG(checked[2] > 20 && least[2] > 8.0L, "far: %d pixels, T from %Lg", checked[2], least[2]);
    CHECK_MSG(seams > 4, "only %d pixels on a seam", seams);
    hr_scene_destroy(scene);
    hr_context_destroy(ctx);
    return hr_test_end();
}
