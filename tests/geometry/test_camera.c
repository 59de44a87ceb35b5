/* Hill's camera: rays through pixel centres, the view angle, and the moves. */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

int main(void)
{
    hr_camera c;
    hr_camera_default(&c);
    c.width = 4, c.height = 2, c.view_angle = 90.0;
    c.eye = (hr_vec3){0, 0, 0}, c.look = (hr_vec3){0, 0, -1}, c.up = (hr_vec3){0, 1, 0};
    CHECK_OK(hr_camera_validate(NULL, &c));
    hr_ray r;
    /* The image centre looks straight at the look-at point. */
    CHECK_OK(hr_camera_ray(&c, 2.0, 1.0, &r));
    CHECK_NEAR(r.dir.x, 0, 1e-15);
    CHECK_NEAR(r.dir.y, 0, 1e-15);
    CHECK_NEAR(r.dir.z, -1, 1e-15);
    /* 90 degrees vertical: the top edge is at 45 degrees, H = tan(45) = 1;
     * aspect 2 so W = 2. Pixel (0,0)'s centre (0.5, 0.5) is at x = -1.5,
     * y = 0.5 on the plane z = -1. */
    CHECK_OK(hr_camera_ray(&c, 0.5, 0.5, &r));
    double len = sqrt(1.5 * 1.5 + 0.5 * 0.5 + 1.0);
    CHECK_NEAR(r.dir.x, -1.5 / len, 1e-15);
    CHECK_NEAR(r.dir.y, 0.5 / len, 1e-15);
    CHECK_NEAR(r.dir.z, -1.0 / len, 1e-15);
    /* The top edge of the image at 45 degrees up. */
    CHECK_OK(hr_camera_ray(&c, 2.0, 0.0, &r));
    CHECK_NEAR(r.dir.y, -r.dir.z, 1e-15);

    /* slide along n moves eye and look together. */
    hr_camera s = c;
    hr_camera_slide(&s, 0, 0, 2);
    CHECK_NEAR(s.eye.z, 2, 1e-15);
    CHECK_NEAR(s.look.z, 1, 1e-15);
    /* yaw 90 turns the view from -z to -x (a left turn about v = +y). */
    hr_camera y = c;
    hr_camera_yaw(&y, 90);
    CHECK_OK(hr_camera_ray(&y, 2.0, 1.0, &r));
    CHECK_NEAR(r.dir.x, -1, 1e-15);
    CHECK_NEAR(r.dir.z, 0, 1e-15);
    /* pitch 90 looks straight up. */
    hr_camera p = c;
    hr_camera_pitch(&p, 90);
    CHECK_OK(hr_camera_ray(&p, 2.0, 1.0, &r));
    CHECK_NEAR(r.dir.y, 1, 1e-15);
    /* roll 90 turns the up vector from +y to -x... (u = +x rotates to +y). */
    hr_camera rl = c;
    hr_camera_roll(&rl, 90);
    CHECK_NEAR(rl.up.x, -1, 1e-15);
    CHECK_NEAR(rl.up.y, 0, 1e-15);

    /* Refusals name the field. */
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    hr_camera bad = c;
    bad.up = (hr_vec3){0, 0, 1};
    CHECK(hr_camera_validate(ctx, &bad) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "up vector") != NULL);
    bad = c;
    bad.view_angle = 180;
    CHECK(hr_camera_validate(ctx, &bad) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "view angle") != NULL);
    bad = c;
    bad.look = bad.eye;
    CHECK(hr_camera_validate(ctx, &bad) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "same point") != NULL);
    /* An eye at 1e308: the length of eye - look is not a double, its
     * direction is (it was called "up vector parallel"); the camera looks
     * down -z as it does from 10. */
    hr_camera far = c;
    far.eye = (hr_vec3){0, 0, 1e308}, far.look = (hr_vec3){0, 0, 0};
    CHECK_MSG(hr_camera_validate(ctx, &far) == HR_OK, "%s", hr_context_last_error(ctx));
    CHECK_OK(hr_camera_ray(&far, 2.0, 1.0, &r));
    CHECK(r.dir.x == 0.0 && r.dir.y == 0.0 && r.dir.z == -1.0);
    far.up = (hr_vec3){0, 1e300, 0}; /* a huge up is a direction too */
    CHECK_MSG(hr_camera_validate(ctx, &far) == HR_OK, "%s", hr_context_last_error(ctx));
    far.up = (hr_vec3){0, 1e-300, 0}; /* and a tiny one */
    CHECK_MSG(hr_camera_validate(ctx, &far) == HR_OK, "%s", hr_context_last_error(ctx));
    /* eye - look overflowing is said as such. */
    far.eye = (hr_vec3){0, 0, 1e308}, far.look = (hr_vec3){0, 0, -1e308}, far.up = c.up;
    CHECK(hr_camera_validate(ctx, &far) == HR_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "too far apart") != NULL, "%s", hr_context_last_error(ctx));
    bad = c;
    bad.up = (hr_vec3){0, 0, 0};
    CHECK(hr_camera_validate(ctx, &bad) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "up vector is zero") != NULL);
    hr_context_destroy(ctx);
    return hr_test_end();
}
