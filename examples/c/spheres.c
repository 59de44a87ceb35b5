/* A complete hitray program: build a scene in code (three spheres on a floor,
 * one of them a mirror, two lights), render it and write a PNG.
 *
 *   spheres [OUT.png] [WIDTHxHEIGHT]
 *
 * It uses only the installed public API (#include <hitray/hitray.h>) and
 * links only libhitray; the shape modules are found by the library itself,
 * next to where it is installed. */
#include <stdio.h>
#include <stdlib.h>

#include <hitray/hitray.h>

/* Report a failed call with the library's message and leave. */
static int fail(hr_context *ctx, const char *what)
{
    fprintf(stderr, "spheres: %s: %s\n", what, ctx ? hr_context_last_error(ctx) : "no context");
    return 1;
}

static hr_status add_sphere(hr_scene *scene, double x, double y, double z, double radius,
                            hr_color diffuse, double reflectivity)
{
    hr_material m;
    hr_material_default(&m);
    m.ambient = (hr_color){0.2 * diffuse.r, 0.2 * diffuse.g, 0.2 * diffuse.b};
    m.diffuse = diffuse;
    m.specular = (hr_color){0.6, 0.6, 0.6};
    m.specular_exponent = 40;
    m.reflectivity = reflectivity;

    /* Hill's generic sphere (radius 1 at the origin), scaled and moved. */
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_translate(&t, x, y, z);
    hr_transform_scale(&t, radius, radius, radius);

    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "sphere";
    d.material = &m;
    d.transform = t.m;
    d.inverse = t.inv;
    return hr_scene_add_object(scene, &d, NULL);
}

static hr_status add_floor(hr_scene *scene)
{
    hr_material m;
    hr_material_default(&m);
    m.ambient = (hr_color){0.25, 0.25, 0.25};
    m.diffuse = (hr_color){0.7, 0.7, 0.65};

    /* The generic plane is z = 0; turn it to y = 0, facing up. */
    hr_transform t;
    hr_transform_identity(&t);
    hr_transform_rotate(&t, -90, 1, 0, 0);

    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "plane";
    d.material = &m;
    d.transform = t.m;
    d.inverse = t.inv;
    return hr_scene_add_object(scene, &d, NULL);
}

static hr_status add_light(hr_scene *scene, double x, double y, double z, double brightness)
{
    hr_light l = {0};
    l.struct_size = sizeof l;
    l.position = (hr_vec3){x, y, z};
    l.color = (hr_color){brightness, brightness, brightness};
    return hr_scene_add_light(scene, &l);
}

static hr_status build_scene(hr_scene *scene)
{
    hr_scene_globals g;
    hr_scene_globals_default(&g);
    g.background = (hr_color){0.05, 0.07, 0.12};
    g.max_recursion_depth = 4;
    g.min_reflectivity = 0.1;
    hr_status st = hr_scene_set_globals(scene, &g);
    if (!st) st = add_floor(scene);
    if (!st) st = add_sphere(scene, -1.6, 1.0, 0.0, 1.0, (hr_color){0.8, 0.15, 0.1}, 0.0);
    if (!st) st = add_sphere(scene, 0.6, 0.7, 1.2, 0.7, (hr_color){0.15, 0.3, 0.8}, 0.0);
    if (!st) st = add_sphere(scene, 1.4, 1.2, -1.4, 1.2, (hr_color){0.1, 0.1, 0.1}, 0.8);
    if (!st) st = add_light(scene, 6, 9, 7, 0.9);
    if (!st) st = add_light(scene, -8, 5, 3, 0.3);
    return st;
}

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "spheres.png";
    int width = 320, height = 240;
    if (argc > 2 && sscanf(argv[2], "%dx%d", &width, &height) != 2) {
        fprintf(stderr, "usage: spheres [OUT.png] [WIDTHxHEIGHT]\n");
        return 2;
    }

    hr_context *ctx = NULL;
    if (hr_context_create(&ctx) != HR_OK) return fail(NULL, "cannot create a context");
    hr_scene *scene = NULL;
    hr_image *image = NULL;
    int rc = 0;
    if (hr_scene_create(ctx, &scene) != HR_OK) rc = fail(ctx, "scene");
    else if (build_scene(scene) != HR_OK) rc = fail(ctx, "building the scene");
    else if (hr_scene_commit(scene) != HR_OK) rc = fail(ctx, "commit");

    if (!rc) {
        hr_camera cam;
        hr_camera_default(&cam);
        cam.eye = (hr_vec3){2.5, 3.0, 9.0};
        cam.look = (hr_vec3){0.0, 0.8, 0.0};
        cam.view_angle = 35;
        cam.width = width;
        cam.height = height;

        hr_render_options opts;
        hr_render_options_default(&opts);
        opts.samples_per_pixel = 4;
        hr_render_stats stats = {0};
        stats.struct_size = sizeof stats;
        if (hr_render(scene, &cam, &opts, &image, &stats) != HR_OK) rc = fail(ctx, "render");
        else if (hr_image_write(ctx, image, out, NULL) != HR_OK) rc = fail(ctx, "writing the image");
        else
            printf("wrote %s (%dx%d, %.3f s, %llu primary rays)\n", out, width, height, stats.seconds,
                   (unsigned long long)stats.primary);
    }
    hr_image_destroy(image);
    hr_scene_destroy(scene);
    hr_context_destroy(ctx);
    return rc;
}
