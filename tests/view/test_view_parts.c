/* The viewer's parts that know no window (view/view.h): the pass plan, the
 * camera keys against Hill's definitions computed here in long double, the
 * printed camera line, the status line and the display's sRGB codes. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"
#include "view.h"

static void check_plan(int32_t block, int32_t spp, int n, const view_pass *want)
{
    view_pass got[VIEW_MAX_PASSES];
    int count = view_pass_plan(block, spp, got);
    CHECK_MSG(count == n, "plan(%d, %d): %d passes, expected %d", (int)block, (int)spp, count, n);
    for (int i = 0; i < n && i < count; i++)
        CHECK_MSG(got[i].block_size == want[i].block_size && got[i].samples_per_pixel == want[i].samples_per_pixel,
                  "plan(%d, %d)[%d] = (%d, %d), expected (%d, %d)", (int)block, (int)spp, i,
                  (int)got[i].block_size, (int)got[i].samples_per_pixel, (int)want[i].block_size,
                  (int)want[i].samples_per_pixel);
}

static void test_plans(void)
{
    /* Hill's halving, the last pass at full quality. */
    check_plan(1, 1, 5, (const view_pass[]){{16, 1}, {8, 1}, {4, 1}, {2, 1}, {1, 1}});
    check_plan(1, 4, 6, (const view_pass[]){{16, 1}, {8, 1}, {4, 1}, {2, 1}, {1, 1}, {1, 4}});
    /* --block: refining stops there. */
    check_plan(8, 1, 2, (const view_pass[]){{16, 1}, {8, 1}});
    check_plan(8, 3, 3, (const view_pass[]){{16, 1}, {8, 1}, {8, 3}});
    check_plan(3, 1, 4, (const view_pass[]){{16, 1}, {8, 1}, {4, 1}, {3, 1}});
    check_plan(16, 1, 1, (const view_pass[]){{16, 1}});
    check_plan(32, 2, 1, (const view_pass[]){{32, 2}});
    check_plan(4096, 65536, 1, (const view_pass[]){{4096, 65536}});
}

/* --- camera moves, by Hill's definitions in long double --- */

typedef struct lvec {
    long double x, y, z;
} lvec;

static lvec lv(hr_vec3 v) { return (lvec){v.x, v.y, v.z}; }
static lvec lsub(lvec a, lvec b) { return (lvec){a.x - b.x, a.y - b.y, a.z - b.z}; }
static lvec ladd(lvec a, lvec b) { return (lvec){a.x + b.x, a.y + b.y, a.z + b.z}; }
static lvec lscale(lvec a, long double s) { return (lvec){a.x * s, a.y * s, a.z * s}; }
static long double llen(lvec a) { return sqrtl(a.x * a.x + a.y * a.y + a.z * a.z); }
static lvec lunit(lvec a) { return lscale(a, 1.0L / llen(a)); }
static lvec lcross(lvec a, lvec b)
{
    return (lvec){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

typedef struct lcam {
    lvec eye, look, up;
} lcam;

/* Hill's axes: n from the look-at point to the eye, u = up x n, v = n x u. */
static void axes(const lcam *c, lvec *u, lvec *v, lvec *n)
{
    *n = lunit(lsub(c->eye, c->look));
    *u = lunit(lcross(c->up, *n));
    *v = lcross(*n, *u);
}

/* Turn a toward b by `degrees` (Hill's roll, pitch and yaw), then store the
 * axes back, keeping the eye-look distance; up becomes v. */
static lcam turned(lcam c, int which, long double degrees)
{
    lvec u, v, n;
    axes(&c, &u, &v, &n);
    long double r = degrees * 3.14159265358979323846264338327950288L / 180.0L, cs = cosl(r), sn = sinl(r);
    lvec *a = which == 0 ? &u : which == 1 ? &v : &n; /* roll: u to v; pitch: v to n; yaw: n to u */
    lvec *b = which == 0 ? &v : which == 1 ? &n : &u;
    lvec na = ladd(lscale(*a, cs), lscale(*b, sn)), nb = ladd(lscale(*a, -sn), lscale(*b, cs));
    *a = na, *b = nb;
    long double dist = llen(lsub(c.eye, c.look));
    c.look = lsub(c.eye, lscale(n, dist));
    c.up = v;
    return c;
}

static lcam slid(lcam c, long double du, long double dv, long double dn)
{
    lvec u, v, n;
    axes(&c, &u, &v, &n);
    lvec d = ladd(ladd(lscale(u, du), lscale(v, dv)), lscale(n, dn));
    c.eye = ladd(c.eye, d), c.look = ladd(c.look, d);
    return c;
}

/* Each component within a few rounding errors of the operations (about 30
 * double operations, each within half an ulp of magnitude at most the
 * scene's extent) of the long double answer: 64 ulps of that extent. */
static void check_camera(const char *what, const hr_camera *got, const lcam *want)
{
    const long double scale = 16.0L; /* the test camera's coordinates are below 16 */
    const double tol = (double)(scale * 64.0L * DBL_EPSILON);
    const hr_vec3 g[3] = {got->eye, got->look, got->up};
    const lvec w[3] = {want->eye, want->look, want->up};
    for (int i = 0; i < 3; i++) {
        CHECK_MSG(fabs(g[i].x - (double)w[i].x) <= tol && fabs(g[i].y - (double)w[i].y) <= tol &&
                      fabs(g[i].z - (double)w[i].z) <= tol,
                  "%s: %s = (%.17g, %.17g, %.17g), expected (%.17Lg, %.17Lg, %.17Lg)", what,
                  i == 0 ? "eye" : i == 1 ? "look" : "up", g[i].x, g[i].y, g[i].z, w[i].x, w[i].y, w[i].z);
    }
}

static void test_moves(void)
{
    hr_camera cam;
    hr_camera_default(&cam);
    cam.eye = (hr_vec3){7, 4.2, 10}, cam.look = (hr_vec3){0, 1.1, 0}, cam.up = (hr_vec3){0, 1, 0};
    view_steps steps = view_steps_for(&cam);
    long double dist = sqrtl(7.0L * 7.0L + 3.1L * 3.1L + 10.0L * 10.0L);
    CHECK_NEAR(steps.slide, (double)(dist / 20.0L), 4 * DBL_EPSILON);
    CHECK(steps.degrees == 5.0);

    lcam want = {lv(cam.eye), lv(cam.look), lv(cam.up)};
    const long double d = steps.slide;
    struct {
        view_action action;
        int turn;        /* -1: a slide */
        long double deg; /* turn */
        long double du, dv, dn;
        const char *name;
    } moves[] = {
        {VIEW_FORWARD, -1, 0, 0, 0, -d, "forward"},  {VIEW_YAW_LEFT, 2, 5, 0, 0, 0, "yaw left"},
        {VIEW_RIGHT, -1, 0, d, 0, 0, "right"},       {VIEW_PITCH_UP, 1, 5, 0, 0, 0, "pitch up"},
        {VIEW_UP, -1, 0, 0, d, 0, "up"},             {VIEW_ROLL_LEFT, 0, 5, 0, 0, 0, "roll left"},
        {VIEW_BACK, -1, 0, 0, 0, d, "back"},         {VIEW_YAW_RIGHT, 2, -5, 0, 0, 0, "yaw right"},
        {VIEW_LEFT, -1, 0, -d, 0, 0, "left"},        {VIEW_PITCH_DOWN, 1, -5, 0, 0, 0, "pitch down"},
        {VIEW_DOWN, -1, 0, 0, -d, 0, "down"},        {VIEW_ROLL_RIGHT, 0, -5, 0, 0, 0, "roll right"},
    };
    for (size_t i = 0; i < sizeof moves / sizeof moves[0]; i++) {
        CHECK(view_apply(moves[i].action, &cam, &steps) == 1);
        want = moves[i].turn < 0 ? slid(want, moves[i].du, moves[i].dv, moves[i].dn)
                                 : turned(want, moves[i].turn, moves[i].deg);
        check_camera(moves[i].name, &cam, &want);
    }
    /* The view direction after a yaw left turns toward -u: from looking
     * down -z with +y up, yaw left looks toward -x. */
    hr_camera straight;
    hr_camera_default(&straight);
    view_steps s2 = view_steps_for(&straight);
    view_apply(VIEW_YAW_LEFT, &straight, &s2);
    CHECK(straight.look.x < straight.eye.x);
    hr_camera_default(&straight);
    view_apply(VIEW_PITCH_UP, &straight, &s2);
    CHECK(straight.look.y > straight.eye.y);

    /* Step changes move nothing, and stay finite and non-zero however
     * often they are pressed. */
    hr_camera before = cam;
    for (int i = 0; i < 2000; i++) CHECK(view_apply(VIEW_COARSER, &cam, &steps) == 0);
    CHECK(memcmp(&before, &cam, sizeof cam) == 0);
    CHECK(steps.degrees <= 80.0 && isfinite(steps.slide));
    for (int i = 0; i < 4000; i++) view_apply(VIEW_FINER, &cam, &steps);
    CHECK(steps.degrees > 0.0 && steps.slide > 0.0);
    CHECK(view_apply(VIEW_PRINT_CAMERA, &cam, &steps) == 0 && view_apply(VIEW_NONE, &cam, &steps) == 0);
}

static void test_camera_line(void)
{
    hr_camera cam;
    hr_camera_default(&cam);
    cam.eye = (hr_vec3){0.1, -1.0 / 3.0, 1e-300}, cam.look = (hr_vec3){6.02e23, 0, -0.0};
    cam.up = (hr_vec3){nextafter(1.0, 2.0), 2, 3}, cam.view_angle = 38.123456789012345;
    char line[512];
    view_camera_line(&cam, line, sizeof line);
    double v[10];
    CHECK(sscanf(line, "camera %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                 &v[6], &v[7], &v[8], &v[9]) == 10);
    const double want[10] = {cam.eye.x, cam.eye.y, cam.eye.z, cam.look.x, cam.look.y, cam.look.z,
                             cam.up.x, cam.up.y, cam.up.z, cam.view_angle};
    for (int i = 0; i < 10; i++) CHECK_MSG(v[i] == want[i], "value %d read back as %.17g", i, v[i]);
}

/* The --camera form of a camera: the same ten numbers, read back exactly,
 * comma-separated as the option takes them. */
static void test_camera_option(void)
{
    hr_camera cam;
    hr_camera_default(&cam);
    cam.eye = (hr_vec3){0.1, -1.0 / 3.0, 1e-300}, cam.look = (hr_vec3){6.02e23, 0, -0.0};
    cam.up = (hr_vec3){nextafter(1.0, 2.0), 2, 3}, cam.view_angle = 38.123456789012345;
    char option[512];
    view_camera_option(&cam, option, sizeof option);
    double v[10];
    CHECK(sscanf(option, "--camera %lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4],
                 &v[5], &v[6], &v[7], &v[8], &v[9]) == 10);
    CHECK(strchr(option, ' ') == strrchr(option, ' ')); /* one blank: a single shell word after the name */
    const double want[10] = {cam.eye.x, cam.eye.y, cam.eye.z, cam.look.x, cam.look.y, cam.look.z,
                             cam.up.x, cam.up.y, cam.up.z, cam.view_angle};
    for (int i = 0; i < 10; i++) CHECK_MSG(v[i] == want[i], "value %d read back as %.17g", i, v[i]);
}

/* The names P saves to, against a set of names that "exist". */
static int in_list(const char *path, void *user)
{
    for (const char *const *name = user; *name; name++)
        if (!strcmp(*name, path)) return 1;
    return 0;
}

static void check_save_path(const char *path, const char *const *taken, const char *want)
{
    char out[64];
    int ok = view_save_path(path, in_list, (void *)taken, out, sizeof out);
    if (!want) CHECK_MSG(!ok, "%s: gave %s", path, out);
    else CHECK_MSG(ok && !strcmp(out, want), "%s: gave %s, not %s", path, ok ? out : "nothing", want);
}

static void test_save_path(void)
{
    static const char *const none[] = {NULL};
    static const char *const first[] = {"hitray-view.png", NULL};
    static const char *const three[] = {"out/shot.exr", "out/shot-2.exr", "out/shot-3.exr", NULL};
    static const char *const bare[] = {"dir.x/picture", ".png", NULL};
    check_save_path("hitray-view.png", none, "hitray-view.png");
    check_save_path("hitray-view.png", first, "hitray-view-2.png");
    check_save_path("out/shot.exr", three, "out/shot-4.exr");
    check_save_path("dir.x/picture", bare, "dir.x/picture-2"); /* the directory's dot is no extension */
    check_save_path(".png", bare, ".png-2");
    /* A name that does not fit: no name, rather than a cut one. */
    check_save_path("a-name-of-sixty-four-characters-or-more-is-longer-than-the-buffer.png", none, NULL);
    static const char *const full[] = {"abcdefghijklmnopqrstuvwxyz-0123456789-abcdefghijklmnopqrstu.png", NULL};
    check_save_path(full[0], full, NULL); /* 63 characters fit, the number does not */
}

static void test_status(void)
{
    view_pass plan[VIEW_MAX_PASSES];
    int passes = view_pass_plan(1, 1, plan);
    view_status s;
    memset(&s, 0, sizeof s);
    s.scene_name = "demo.sdl", s.plan = plan, s.passes = passes, s.width = 160, s.height = 120;
    s.steps = (view_steps){0.625, 5};
    char text[1024];
    view_status_text(&s, text, sizeof text);
    CHECK_MSG(!strcmp(text, "hitray view: demo.sdl | pass 1 of 5: block 16 0% | step 0.625, 5 deg | H: keys"), "%s",
              text);

    /* The block-16 pass (10 x 8 = 80 camera rays) took 0.01 s; half of the
     * block-8 pass (300 rays) is done; then 1200, 4800 and 19200 rays. */
    s.has_frame = 1;
    s.last.pass = 0, s.last.passes = passes, s.last.settings = plan[0];
    s.last.stats.seconds = 0.01, s.last.stats.primary = 80, s.last.stats.shadow = 20;
    s.last.stats.effects = HR_EFFECT_DIFFUSE | HR_EFFECT_SHADOWS;
    s.running_pass = 1, s.running_fraction = 0.5;
    view_status_text(&s, text, sizeof text);
    /* Left: (150 + 1200 + 4800 + 19200) x 0.01 / 80 = 3.16875 s. */
    CHECK_MSG(!strcmp(text, "hitray view: demo.sdl | pass 2 of 5: block 8 50% | 10 k rays/s | effects: diffuse, "
                            "shadows | final in ~3.2 s | step 0.625, 5 deg | H: keys"),
              "%s", text);

    s.running_pass = passes, s.last.pass = passes - 1, s.last.since_restart = 1.5;
    s.last.stats.primary = 4000000, s.last.stats.shadow = 0, s.last.stats.seconds = 2.0;
    s.last.stats.effects = 0;
    view_status_text(&s, text, sizeof text);
    CHECK_MSG(!strcmp(text, "hitray view: demo.sdl | final pass (5 of 5) | 2.00 M rays/s | effects: none | final "
                            "pass after 1.50 s | step 0.625, 5 deg | H: keys"),
              "%s", text);

    s.error = "render: camera: eye and look-at point coincide";
    view_status_text(&s, text, sizeof text);
    CHECK(!strcmp(text, "hitray view: demo.sdl | render failed: render: camera: eye and look-at point coincide"));

    /* A short buffer is cut, never overrun. */
    char small[24];
    memset(small, 'x', sizeof small);
    view_status_text(&s, small, 20);
    CHECK(strlen(small) == 19 && small[20] == 'x');
}

/* The sRGB code by the formula, in long double. */
static int code_by_formula(float linear)
{
    long double v = linear > 0 ? (linear < 1 ? linear : 1) : 0;
    long double e = v <= 0.0031308L ? 12.92L * v : 1.055L * powl(v, 1.0L / 2.4L) - 0.055L;
    return (int)floorl(e * 255.0L + 0.5L);
}

static void test_pixels(void)
{
    enum { N = 4096 };
    hr_image *image = NULL;
    CHECK_OK(hr_image_create(NULL, N, 2, 3, &image));
    if (!image) return;
    float *px = hr_image_data(image);
    /* Every 2^-12 step of [0, 1] and a little past it, then the odd ones. */
    for (int i = 0; i < 3 * N; i++) px[i] = (float)i / (float)(3 * N - 8);
    const float odd[] = {0.0f, -0.0f, -1.0f, NAN, INFINITY, -INFINITY, 2.0f, 1e-30f, 1.0f, 0.5f};
    for (size_t i = 0; i < sizeof odd / sizeof odd[0]; i++) px[3 * N + i] = odd[i];
    static uint8_t out[2 * 3 * N + 16];
    view_pixels_srgb8(px, 3 * N, N, 2, out, 3 * N + 16); /* a pitch longer than the row */
    int mismatches = 0;
    for (int i = 0; i < 3 * N; i++) {
        float v = px[i];
        int want = code_by_formula(v);
        /* Where the exact encoded value lies within 1e-9 of a rounding
         * boundary the two computations may round either way. */
        long double e = v <= 0.0031308f ? 12.92L * v : 1.055L * powl(v < 1 ? v : 1, 1.0L / 2.4L) - 0.055L;
        long double frac = e * 255.0L + 0.5L - floorl(e * 255.0L + 0.5L);
        if (out[i] != want && frac > 1e-9L && frac < 1 - 1e-9L) mismatches++;
    }
    CHECK_MSG(mismatches == 0, "%d of %d codes differ from the sRGB formula", mismatches, 3 * N);
    const uint8_t *row = out + 3 * N + 16;
    const uint8_t want_odd[] = {0, 0, 0, 0, 255, 0, 255, 0, 255, 188};
    for (size_t i = 0; i < sizeof want_odd; i++)
        CHECK_MSG(row[i] == want_odd[i], "odd value %zu: code %d, expected %d", i, row[i], want_odd[i]);
    /* A tile inside the image (rows a stride apart, from its own corner):
     * the same codes as the whole image's conversion has there. */
    uint8_t tile[2 * 3 * 5];
    view_pixels_srgb8(px + 3 * 7, 3 * N, 5, 2, tile, 3 * 5);
    CHECK(memcmp(tile, out + 3 * 7, 3 * 5) == 0);
    CHECK(memcmp(tile + 3 * 5, out + 3 * N + 16 + 3 * 7, 3 * 5) == 0);
    hr_image_destroy(image);
}

int main(void)
{
    test_plans();
    test_moves();
    test_camera_line();
    test_camera_option();
    test_save_path();
    test_status();
    test_pixels();
    return hr_test_end();
}
