/* A small program that uses the disk plugin through hitray's C API.
 *
 *   disk_demo RADIUS hit OX,OY,OZ DX,DY,DZ
 *       A scene holding only a disk of RADIUS (identity transform); print
 *       the first hit of the ray origin + t dir, t > 0, as
 *         t T point X Y Z normal X Y Z entering 0|1
 *       or "no hit". Numbers have 17 significant digits, so they read back
 *       exactly.
 *   disk_demo RADIUS render OUT.png [WIDTHxHEIGHT]
 *       Render a ball resting above a disk of RADIUS laid flat as a floor.
 *
 * Why a program and not an SDL file: hitray's SDL reader knows Hill's fixed
 * set of object keywords (docs/sdl.md), so a class a plugin adds can only be
 * used from the API for now. The shape is named by its class name, "disk",
 * with its parameter "radius"; the library finds disk.so on its module search
 * path (HITRAY_SHAPE_PATH, see README.md). Exit status 1 on any error, with
 * the library's message, which names the refused parameter. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <hitray/hitray.h>

static int usage(void)
{
    fprintf(stderr, "usage: disk_demo RADIUS hit OX,OY,OZ DX,DY,DZ\n"
                    "       disk_demo RADIUS render OUT.png [WIDTHxHEIGHT]\n");
    return 2;
}

/* Report a failed call with the library's message; the exit status. */
static int fail(hr_context *ctx, const char *what)
{
    fprintf(stderr, "disk_demo: %s: %s\n", what, ctx ? hr_context_last_error(ctx) : "no context");
    return 1;
}

static int parse_vec3(const char *text, hr_vec3 *out)
{
    char extra;
    return sscanf(text, "%lf,%lf,%lf%c", &out->x, &out->y, &out->z, &extra) == 3;
}

/* The plugin's shape is added like any built-in one: by class name, with
 * named parameters. A radius the class refuses fails here. */
static hr_status add_disk(hr_scene *scene, double radius, const hr_transform *t, const hr_material *m)
{
    hr_param param = {0};
    param.name = "radius";
    param.type = HR_PARAM_NUMBER;
    param.number = radius;

    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "disk";
    d.param_count = 1;
    d.params = &param;
    d.material = m;
    d.transform = t ? t->m : NULL;
    d.inverse = t ? t->inv : NULL;
    return hr_scene_add_object(scene, &d, NULL);
}

static int print_first_hit(hr_context *ctx, hr_scene *scene, const hr_ray *ray)
{
    hr_hit hit;
    int32_t found = 0;
    if (hr_scene_first_hit(scene, ray, 0.0, INFINITY, &hit, &found) != HR_OK) return fail(ctx, "tracing");
    if (!found) {
        printf("no hit\n");
        return 0;
    }
    printf("t %.17g point %.17g %.17g %.17g normal %.17g %.17g %.17g entering %d\n", hit.t, hit.point.x,
           hit.point.y, hit.point.z, hit.normal.x, hit.normal.y, hit.normal.z, (int)hit.entering);
    return 0;
}

/* The floor disk (z = 0 turned to y = 0, facing up), a ball over it, one
 * light: enough to see the disk's outline, its shading and a shadow on it. */
static hr_status build_render_scene(hr_scene *scene, double radius)
{
    hr_transform floor;
    hr_transform_identity(&floor);
    hr_status st = hr_transform_rotate(&floor, -90, 1, 0, 0);
    hr_material floor_material;
    hr_material_default(&floor_material);
    floor_material.ambient = (hr_color){0.2, 0.2, 0.18};
    floor_material.diffuse = (hr_color){0.75, 0.7, 0.6};
    if (!st) st = add_disk(scene, radius, &floor, &floor_material);

    hr_transform ball;
    hr_transform_identity(&ball);
    hr_transform_translate(&ball, 0.0, 0.7 * radius, 0.0);
    if (!st) st = hr_transform_scale(&ball, 0.5 * radius, 0.5 * radius, 0.5 * radius);
    hr_material ball_material;
    hr_material_default(&ball_material);
    ball_material.diffuse = (hr_color){0.8, 0.15, 0.1};
    ball_material.specular = (hr_color){0.5, 0.5, 0.5};
    ball_material.specular_exponent = 40;
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "sphere";
    d.material = &ball_material;
    d.transform = ball.m;
    d.inverse = ball.inv;
    if (!st) st = hr_scene_add_object(scene, &d, NULL);

    hr_light light = {0};
    light.struct_size = sizeof light;
    light.position = (hr_vec3){3.0 * radius, 6.0 * radius, 4.0 * radius};
    light.color = (hr_color){0.9, 0.9, 0.9};
    if (!st) st = hr_scene_add_light(scene, &light);
    return st;
}

static int render(hr_context *ctx, hr_scene *scene, const char *out, int width, int height)
{
    hr_camera cam;
    hr_camera_default(&cam);
    cam.width = width;
    cam.height = height;
    /* Frame the disk and the ball automatically, whatever the radius. */
    if (hr_scene_frame_camera(scene, &cam) != HR_OK) return fail(ctx, "framing the camera");

    hr_render_options opts;
    hr_render_options_default(&opts);
    hr_image *image = NULL;
    int rc = 0;
    if (hr_render(scene, &cam, &opts, &image, NULL) != HR_OK) rc = fail(ctx, "render");
    else if (hr_image_write(ctx, image, out, NULL) != HR_OK) rc = fail(ctx, "writing the image");
    else printf("wrote %s (%dx%d)\n", out, width, height);
    hr_image_destroy(image);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 3) return usage();
    char *end;
    const double radius = strtod(argv[1], &end);
    if (end == argv[1] || *end) return usage();
    const int want_hit = strcmp(argv[2], "hit") == 0 && argc == 5;
    const int want_render = strcmp(argv[2], "render") == 0 && (argc == 4 || argc == 5);
    hr_ray ray = {{0, 0, 0}, {0, 0, 0}};
    int width = 160, height = 120;
    if (want_hit && !(parse_vec3(argv[3], &ray.origin) && parse_vec3(argv[4], &ray.dir))) return usage();
    if (want_render && argc == 5 && sscanf(argv[4], "%dx%d", &width, &height) != 2) return usage();
    if (!want_hit && !want_render) return usage();

    hr_context *ctx = NULL;
    if (hr_context_create(&ctx) != HR_OK) return fail(NULL, "cannot create a context");
    hr_scene *scene = NULL;
    int rc = 0;
    if (hr_scene_create(ctx, &scene) != HR_OK) rc = fail(ctx, "scene");
    else if ((want_hit ? add_disk(scene, radius, NULL, NULL) : build_render_scene(scene, radius)) != HR_OK)
        rc = fail(ctx, "building the scene");
    else if (hr_scene_commit(scene) != HR_OK) rc = fail(ctx, "commit");
    else rc = want_hit ? print_first_hit(ctx, scene, &ray) : render(ctx, scene, argv[3], width, height);
    hr_scene_destroy(scene);
    hr_context_destroy(ctx);
    return rc;
}
