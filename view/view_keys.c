/* Camera keys: Hill's slide, roll, pitch and yaw (chapter 7) as moves of
 * hr_camera (view.h). The window maps key codes to actions; this file knows
 * no window library. */
#include <math.h>
#include <stdio.h>

#include "view.h"

const char view_keys_help[] =
    "keys (each move cancels the render and starts the refinement again):\n"
    "  W / S        slide forward / back (along the view direction, -n)\n"
    "  A / D        slide left / right (along u)\n"
    "  R / F        slide up / down (along v)\n"
    "  Left / Right yaw: turn left / right (about v)\n"
    "  Up / Down    pitch: look up / down (about u)\n"
    "  Q / E        roll left / right (about n)\n"
    "  [ / ]        halve / double the slide step and the angle\n"
    "  C            print the camera as an SDL 'camera' line and as the --camera\n"
    "               option\n"
    "  P            save the picture shown (-o FILE, numbered once it exists)\n"
    "               and print its camera line\n"
    "  H            print these keys\n"
    "  Esc          quit\n";

/* The angle moves by factors of two from 5 degrees: 5 / 2^20 to 80. */
#define VIEW_MIN_DEGREES (5.0 / 1048576.0)
#define VIEW_MAX_DEGREES 80.0

view_steps view_steps_for(const hr_camera *cam)
{
    double dx = cam->eye.x - cam->look.x, dy = cam->eye.y - cam->look.y, dz = cam->eye.z - cam->look.z;
    return (view_steps){sqrt(dx * dx + dy * dy + dz * dz) / 20.0, 5.0};
}

int view_apply(view_action action, hr_camera *cam, view_steps *steps)
{
    const double d = steps->slide, a = steps->degrees;
    switch (action) {
    /* n points from the scene back to the eye, so forward is -n. */
    case VIEW_FORWARD: hr_camera_slide(cam, 0, 0, -d); return 1;
    case VIEW_BACK: hr_camera_slide(cam, 0, 0, d); return 1;
    case VIEW_LEFT: hr_camera_slide(cam, -d, 0, 0); return 1;
    case VIEW_RIGHT: hr_camera_slide(cam, d, 0, 0); return 1;
    case VIEW_UP: hr_camera_slide(cam, 0, d, 0); return 1;
    case VIEW_DOWN: hr_camera_slide(cam, 0, -d, 0); return 1;
    /* Hill's yaw turns n toward u: the view (-n) swings toward -u, left. */
    case VIEW_YAW_LEFT: hr_camera_yaw(cam, a); return 1;
    case VIEW_YAW_RIGHT: hr_camera_yaw(cam, -a); return 1;
    /* Pitch turns v toward n: the view swings toward v, up. */
    case VIEW_PITCH_UP: hr_camera_pitch(cam, a); return 1;
    case VIEW_PITCH_DOWN: hr_camera_pitch(cam, -a); return 1;
    /* Roll turns u toward v: the camera tips left, the picture turns right. */
    case VIEW_ROLL_LEFT: hr_camera_roll(cam, a); return 1;
    case VIEW_ROLL_RIGHT: hr_camera_roll(cam, -a); return 1;
    /* Bounded, so no number of presses makes a step of 0 or of infinity
     * (an eye at infinity has no rays). */
    case VIEW_FINER:
        if (steps->degrees > VIEW_MIN_DEGREES) steps->slide *= 0.5, steps->degrees *= 0.5;
        return 0;
    case VIEW_COARSER:
        if (steps->degrees < VIEW_MAX_DEGREES) steps->slide *= 2.0, steps->degrees *= 2.0;
        return 0;
    default: return 0;
    }
}

void view_camera_line(const hr_camera *cam, char *buf, size_t size)
{
    snprintf(buf, size, "camera %.17g %.17g %.17g  %.17g %.17g %.17g  %.17g %.17g %.17g  %.17g", cam->eye.x,
             cam->eye.y, cam->eye.z, cam->look.x, cam->look.y, cam->look.z, cam->up.x, cam->up.y, cam->up.z,
             cam->view_angle);
}

void view_camera_option(const hr_camera *cam, char *buf, size_t size)
{
    snprintf(buf, size, "--camera %.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", cam->eye.x,
             cam->eye.y, cam->eye.z, cam->look.x, cam->look.y, cam->look.z, cam->up.x, cam->up.y, cam->up.z,
             cam->view_angle);
}
