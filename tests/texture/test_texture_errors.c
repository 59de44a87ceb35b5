/* Every error of textures and pixmaps, from SDL (at file:line:col, naming
 * what is wrong) and from the C API: a missing, unreadable, corrupt or
 * oversized image file, a pixmap number out of range or made twice, a
 * texture with no such solid texture or no pixmap, parameters out of
 * range or too many, an image texture on a class without (u, v). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <hitray/hitray.h>

#include "hr_test.h"
#include "texture_support.h"

static void expect(hr_context *ctx, const char *text, const char *dir, hr_status status,
                   const char *where, const char *what)
{
    const char *m = tx_load_error(ctx, text, dir, status);
    CHECK_MSG(strncmp(m, where, strlen(where)) == 0 && strstr(m, what) != NULL,
              "for %s: message '%s' lacks '%s' ... '%s'", text, m, where, what);
}

static void write_file(const char *dir, const char *name, const void *bytes, size_t n)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    CHECK(fwrite(bytes, 1, n, f) == n);
    fclose(f);
}

static void write_png(hr_context *ctx, const char *dir, const char *name, int32_t w, int32_t h)
{
    hr_image *img;
    CHECK_OK(hr_image_create(ctx, w, h, 3, &img));
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    CHECK_OK(hr_image_write(ctx, img, path, NULL));
    hr_image_destroy(img);
}

int main(void)
{
    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    char *dir = tx_temp_dir();
    if (!dir) return hr_test_end();
    write_png(ctx, dir, "ok.png", 2, 2);
    write_png(ctx, dir, "wide.png", HR_IMAGE_READ_MAX_SIDE + 1, 1);
    write_file(dir, "text.png", "not an image\n", 13);
    static const unsigned char corrupt[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R', 1, 2};
    write_file(dir, "corrupt.png", corrupt, sizeof corrupt);
    static const unsigned char bad_jpeg[] = {0xff, 0xd8, 0xff, 0xe0, 0, 16, 'J', 'F', 'I', 'F', 0};
    write_file(dir, "bad.jpg", bad_jpeg, sizeof bad_jpeg);

    /* makePixmap. */
    expect(ctx, "makePixmap 1 missing.png", dir, HR_ERROR_IO, "test.sdl:1:14: ",
           "makePixmap 1: cannot open image");
    expect(ctx, "makePixmap 1 missing.png", dir, HR_ERROR_IO, "test.sdl:1:14: ", "missing.png");
    expect(ctx, "makePixmap 1 text.png", dir, HR_ERROR_IO, "test.sdl:1:14: ",
           "is not a PNG, BMP or JPEG file");
    expect(ctx, "makePixmap 1 corrupt.png", dir, HR_ERROR_IO, "test.sdl:1:14: ", "cannot read PNG");
    expect(ctx, "makePixmap 1 bad.jpg", dir, HR_ERROR_IO, "test.sdl:1:14: ", "cannot read JPEG");
    expect(ctx, "makePixmap 1 wide.png", dir, HR_ERROR_UNSUPPORTED, "test.sdl:1:14: ",
           "is 65537 x 1 pixels");
    expect(ctx, "makePixmap 1 .", dir, HR_ERROR_IO, "test.sdl:1:14: ", "/.': a directory");
    char fifo[4096];
    snprintf(fifo, sizeof fifo, "%s/fifo.png", dir);
    CHECK(mkfifo(fifo, 0600) == 0);
    expect(ctx, "makePixmap 1 fifo.png", dir, HR_ERROR_IO, "test.sdl:1:14: ", "not a regular file");
    expect(ctx, "makePixmap 0 ok.png", dir, HR_ERROR_SDL, "test.sdl:1:12: ", "");
    expect(ctx, "makePixmap 1.5 ok.png", dir, HR_ERROR_SDL, "test.sdl:1:12: ", "");
    expect(ctx, "makePixmap 1 ok.png\nmakePixmap 1 ok.png", dir, HR_ERROR_INVALID_ARGUMENT,
           "test.sdl:2:14: ", "pixmap 1 is made already");
    expect(ctx, "makePixmap 2", dir, HR_ERROR_SDL, "test.sdl:1:13: ",
           "expected a file name after 'makePixmap 2', found end of file");

    /* texture and parameters. */
    expect(ctx, "texture -9 sphere", dir, HR_ERROR_SDL, "test.sdl:1:1: ",
           "there is no solid texture -9 (there are -1 checkerboard, -2 wood, -3 marble)");
    expect(ctx, "makePixmap 1 ok.png\ntexture 2\nsphere", dir, HR_ERROR_PARAMETER, "test.sdl:3:1: ",
           "image texture 2 needs pixmap 2, which is not made");
    expect(ctx, "texture -1 parameters 1 0\ncube", dir, HR_ERROR_PARAMETER, "test.sdl:2:1: ",
           "texture -1 (checkerboard): parameter 1 (size) is 0 and must be positive");
    expect(ctx, "texture -1 parameters 8 1 1 1 1 1 1 1 1 sphere", dir, HR_ERROR_PARAMETER,
           "test.sdl:1:", "texture -1 (checkerboard) takes at most 7 parameters, not 8");
    expect(ctx, "texture -2 parameters 3 .1 .4 2.5 sphere", dir, HR_ERROR_PARAMETER, "test.sdl:1:",
           "parameter 3 (wobbles around) is 2.5 and must be a whole number");
    expect(ctx, "texture -3 parameters 4 1 1 1 17 sphere", dir, HR_ERROR_PARAMETER, "test.sdl:1:",
           "parameter 4 (octaves) is 17 and is out of range (within [1, 16])");
    expect(ctx, "texture -1 parameters 2 1 2e6 sphere", dir, HR_ERROR_PARAMETER, "test.sdl:1:",
           "parameter 2 (colour A red) is 2e+06 and is out of range");
    expect(ctx, "texture -1 parameters 1 1e308 cube", dir, HR_ERROR_PARAMETER, "test.sdl:1:",
           "parameter 1 (size) is 1e+308 and is out of range (at most 1e+300)");
    expect(ctx, "texture -3 parameters 1 1000000.001 sphere", dir, HR_ERROR_PARAMETER, "test.sdl:1:",
           "parameter 1 (veins per unit) is 1000000.001 and is out of range (within [-1e+06, 1e+06])");
    expect(ctx, "makePixmap 1 ok.png texture 1 parameters 2 0 0 sphere", dir, HR_ERROR_PARAMETER,
           "test.sdl:1:", "image texture 1: the (u, v) range [0, 0] x [0, 1] must not be empty");
    expect(ctx, "makePixmap 1 ok.png texture 1 parameters 5 0 1 0 1 0.5 sphere", dir,
           HR_ERROR_PARAMETER, "test.sdl:1:", "parameter 5 (nearest) is 0.5 and must be a whole number");

    /* A class that gives no (u, v) under an image texture: refused, named. */
    char text[8192];
    snprintf(text, sizeof text, "makePixmap 1 ok.png texture 1\nmesh %s/tests/data/meshes/cube.obj",
             HR_TEST_SOURCE_DIR);
    expect(ctx, text, dir, HR_ERROR_PARAMETER, "test.sdl:2:1: ",
           "shape 'mesh' (module '");
    expect(ctx, text, dir, HR_ERROR_PARAMETER, "test.sdl:2:1: ",
           "gives no (u, v) on this object's surface (its data has none: a mesh file without "
           "texture coordinates, say), so it cannot carry image texture 1");
    expect(ctx, "makePixmap 1 ok.png texture 1\ntetrahedron", dir, HR_ERROR_PARAMETER, "test.sdl:2:1: ",
           "shape 'tetrahedron' (module '");
    expect(ctx, "makePixmap 1 ok.png texture 1\ntetrahedron", dir, HR_ERROR_PARAMETER, "test.sdl:2:1: ",
           "gives no (u, v) on its surface, so it cannot carry image texture 1");
    /* A solid texture needs no (u, v): the same mesh takes one. */
    snprintf(text, sizeof text, "texture -3\nmesh %s/tests/data/meshes/cube.obj", HR_TEST_SOURCE_DIR);
    CHECK(strcmp(tx_load_error(ctx, text, dir, HR_OK), "") == 0);

    /* The C API: a material with an unknown solid texture. */
    hr_scene *s;
    CHECK_OK(hr_scene_create(ctx, &s));
    hr_material m;
    hr_material_default(&m);
    m.texture = -4;
    hr_object_desc d = {0};
    d.struct_size = sizeof d;
    d.shape = "sphere";
    d.material = &m;
    CHECK(hr_scene_add_object(s, &d, NULL) == HR_ERROR_PARAMETER);
    CHECK(strstr(hr_context_last_error(ctx), "shape 'sphere': there is no solid texture -4") != NULL);
    CHECK(hr_scene_object_count(s) == 0);
    hr_image *img = NULL;
    CHECK(hr_image_read(ctx, "/nonexistent/x.png", &img) == HR_ERROR_IO && img == NULL);
    hr_scene_destroy(s);

    char cmd[8192];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    free(dir);
    hr_context_destroy(ctx);
    return hr_test_end();
}
