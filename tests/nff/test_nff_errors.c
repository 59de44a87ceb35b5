/* Every error of the NFF reader: the status, the message (file:line:col
 * and what was expected), the place kept for hr_context_last_error_info,
 * and no scene. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static hr_context *ctx;

typedef struct bad_case {
    const char *text;
    hr_status status;
    const char *message; /* the whole message after "bad.nff:" */
} bad_case;

#define VIEW "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
#define FILL "f 1 1 1 1 0 1 0 0\n"

static const bad_case cases[] = {
    /* Numbers and entities. */
    {"s 0 0 x 1\n", HR_ERROR_SDL,
     "1:7: expected 4 numbers after 's' (x y z radius), found 'x'"},
    {"s 0 0 0\n", HR_ERROR_SDL,
     "1:1: expected 4 numbers after 's' (x y z radius), found end of file"},
    {"s 0 0 0 1e999\n", HR_ERROR_SDL,
     "1:9: number '1e999' after 's' is beyond the range of a double"},
    {"s 0 0 0 0x10\n", HR_ERROR_SDL,
     "1:9: expected 4 numbers after 's' (x y z radius), found '0x10'"},
    {"s 0 0 0 nan\n", HR_ERROR_SDL,
     "1:9: expected 4 numbers after 's' (x y z radius), found 'nan'"},
    {"# fine\nsphere 0 0 0 1\n", HR_ERROR_SDL,
     "2:1: expected an NFF entity (v, b, l, f, c, s, p, pp or a # comment), found 'sphere'"},
    {"1 2 3\n", HR_ERROR_SDL,
     "1:1: expected an NFF entity (v, b, l, f, c, s, p, pp or a # comment), found '1'"},
    {"s 0 0 0 -1\n", HR_ERROR_SDL, "1:9: the radius -1 of 's' must be > 0"},
    /* The viewpoint. */
    {"v\nfrom 0 0 5\nup 0 1 0\n", HR_ERROR_SDL,
     "3:1: expected 'at' in the 'v' block begun at line 1 (from, at, up, angle, hither, "
     "resolution, in that order), found 'up'"},
    {"v\nfrom 0 0 5\n", HR_ERROR_SDL,
     "1:1: expected 'at' in the 'v' block begun at line 1 (from, at, up, angle, hither, "
     "resolution, in that order), found end of file"},
    {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8.5 8\n",
     HR_ERROR_SDL,
     "1:1: 'resolution' 8.5 8 of the 'v' block must be two whole numbers in [1, 65536]"},
    {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither -1\nresolution 8 8\n", HR_ERROR_SDL,
     "1:1: 'hither' -1 of the 'v' block must be >= 0"},
    {"v\nfrom 0 0 5\nat 0 0 0\nup 0 0 1\nangle 45\nhither 1\nresolution 8 8\n", HR_ERROR_SDL,
     "1:1: the 'v' block cannot make rays: up vector is zero or parallel to the view direction"},
    {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\nhither 1\nresolution 8 8\n", HR_ERROR_SDL,
     "1:1: the 'v' block cannot make rays: view angle 180 must be in (0, 180) degrees"},
    /* Colours, lights, materials. */
    {"b 0 0\n", HR_ERROR_SDL, "1:1: expected 3 numbers after 'b' (r g b), found end of file"},
    {"b 0 2e6 0\n", HR_ERROR_SDL, "1:1: the colour 0 2e+06 0 of 'b' is beyond +-1e+06"},
    {"l 1 2\n", HR_ERROR_SDL,
     "1:1: expected 3 numbers after 'l' (x y z [r g b]), found end of file"},
    {"l 1 2 3 1 1\n", HR_ERROR_SDL,
     "1:1: expected 3 numbers after 'l' (x y z r g b: the colour on the line of the "
     "position), found end of file"},
    {"l 1 2 3 1 x 1\n", HR_ERROR_SDL,
     "1:11: expected 3 numbers after 'l' (x y z r g b: the colour on the line of the "
     "position), found 'x'"},
    {"l 1 2 3 5e6 1 1\n", HR_ERROR_SDL, "1:1: the colour 5e+06 1 1 of 'l' is beyond +-1e+06"},
    {"f 1 1 1 1 0 1 0\n", HR_ERROR_SDL,
     "1:1: expected 8 numbers after 'f' (r g b Kd Ks Shine T ior), found end of file"},
    {"f 1 1 1 -1 0 1 0 0\n", HR_ERROR_SDL, "1:9: 'Kd' = -1 of 'f' must be >= 0"},
    {"f 1 1 1 1 0 1 0.5 0\n", HR_ERROR_SDL,
     "1:19: 'ior' = 0 of 'f' must be > 0 for a transmitting material (T = 0.5)"},
    {"f 1 1 1 1 2 1 0 0\n", HR_ERROR_SDL, "1:1: material: reflectivity 2 must be within [0, 1]"},
    {"f 1 1 1 1 0 2e6 0 0\n", HR_ERROR_SDL,
     "1:1: material: specularExponent 2e+06 must be within [0, 1e+06]"},
    /* Cones. */
    {FILL "c 0 0 0 1 0 0 1\n", HR_ERROR_SDL,
     "2:1: expected 8 numbers after 'c' (base x y z radius, apex x y z radius; on one line or "
     "two), found end of file"},
    {FILL "c 0 0 0 0 0 0 1 0\n", HR_ERROR_SDL,
     "2:1: the radii of 'c' are both 0: it has no surface"},
    {FILL "c 0 0 0 1 0 0 1 -1\n", HR_ERROR_SDL,
     "2:1: the radii 1 and -1 of 'c' must be both >= 0 (or both negative: seen from inside)"},
    {FILL "c\n1 2 3 1\n1 2 3 0.5\n", HR_ERROR_SDL,
     "2:1: the base and apex points of 'c' are the same point: it has no axis"},
    {FILL "c 0 0 -1e308 1 0 0 1e308 1\n", HR_ERROR_SDL,
     "2:1: the axis of 'c' is too long to measure"},
    /* Polygons. */
    {FILL "p 2\n0 0 0\n1 0 0\n", HR_ERROR_SDL,
     "2:3: expected a whole number in [3, 4294967294] after 'p' (the number of vertices), "
     "found '2'"},
    {FILL "p 3.5\n", HR_ERROR_SDL,
     "2:3: expected a whole number in [3, 4294967294] after 'p' (the number of vertices), "
     "found '3.5'"},
    {FILL "p 2000000000\n0 0 0\n", HR_ERROR_SDL,
     "2:1: 'p 2000000000': 2000000000 vertices need at least 11999999999 bytes, and the file "
     "has 7 left"},
    {FILL "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0\n", HR_ERROR_SDL,
     "2:1: expected 6 numbers after 'pp' (x y z nx ny nz of each vertex), found end of file"},
    {FILL "p 3\n0 0 0\n1 0 0\n0 1 q\n", HR_ERROR_SDL,
     "5:5: expected 3 numbers after 'p' (x y z of each vertex), found 'q'"},
    /* Not text. */
    {"s 0 0 0 1\n\x01\x02", HR_ERROR_SDL,
     "2:1: expected an NFF entity (v, b, l, f, c, s, p, pp or a # comment), found '\\x01\\x02'"},
    /* A file's bytes reach the terminal escaped: here, an escape sequence
     * that would turn the text red, and one that sets the window's title. */
    {"s 0 0 0 1\nsph\x1b[31mere", HR_ERROR_SDL,
     "2:1: expected an NFF entity (v, b, l, f, c, s, p, pp or a # comment), found "
     "'sph\\x1b[31mere'"},
    {"\x1b]0;owned\x07", HR_ERROR_SDL,
     "1:1: expected an NFF entity (v, b, l, f, c, s, p, pp or a # comment), found "
     "'\\x1b]0;owned\\x07'"},
};

static void check_case(const bad_case *c)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    hr_status st = hr_nff_load_string(ctx, c->text, "bad.nff", &r);
    const char *msg = hr_context_last_error(ctx);
    char expected[1024];
    snprintf(expected, sizeof expected, "bad.nff:%s", c->message);
    CHECK_MSG(st == c->status, "%s: status %d (expected %d): %s", c->message, (int)st,
              (int)c->status, msg);
    CHECK_MSG(strcmp(msg, expected) == 0, "\n  got      %s\n  expected %s", msg, expected);
    CHECK(r.scene == NULL);
    /* The place is kept apart too: the line and column of the message. */
    hr_error_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    if (hr_context_last_error_info(ctx, &info) == HR_OK) {
        int line = 0, column = 0;
        sscanf(c->message, "%d:%d", &line, &column);
        CHECK_MSG(info.line == line && info.column == column && info.file &&
                      strcmp(info.file, "bad.nff") == 0,
                  "%s: info %s:%d:%d", c->message, info.file ? info.file : "(null)",
                  (int)info.line, (int)info.column);
    }
}

/* The entry points' own refusals. */
static void test_arguments(void)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_nff_load_string(NULL, "", NULL, &r) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_nff_load_string(ctx, NULL, NULL, &r) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(hr_nff_load_file(ctx, NULL, &r) == HR_ERROR_INVALID_ARGUMENT);
    hr_sdl_result tiny;
    memset(&tiny, 0, sizeof tiny);
    tiny.struct_size = 4;
    CHECK(hr_nff_load_string(ctx, "", NULL, &tiny) == HR_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(hr_context_last_error(ctx), "NFF: the result is NULL") != NULL);
    CHECK(hr_nff_load_file(ctx, HR_TEST_SOURCE_DIR "/tests/data/scenes/nff/missing.nff", &r) ==
          HR_ERROR_IO);
    CHECK(strstr(hr_context_last_error(ctx), "missing.nff: cannot open the scene file") != NULL);
    CHECK(r.scene == NULL);
    /* A directory opens but cannot be read. */
    CHECK(hr_nff_load_file(ctx, HR_TEST_SOURCE_DIR "/tests/data/scenes/nff", &r) == HR_ERROR_IO);
    CHECK(r.scene == NULL);
}

/* A gzip stream cut short is an I/O error, not a scene of what came out. */
static void test_truncated_gzip(void)
{
    static const unsigned char truncated[] = {0x1f, 0x8b, 0x08, 0x00, 0x00, 0x00, 0x00,
                                              0x00, 0x00, 0x03, 0x2b, 0x56, 0x30, 0x50};
    const char *path = HR_TEST_BINARY_DIR "/tests/truncated_nff.gz";
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    fwrite(truncated, 1, sizeof truncated, f);
    fclose(f);
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_nff_load_file(ctx, path, &r) == HR_ERROR_IO);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "cannot read the scene file") != NULL, "%s",
              hr_context_last_error(ctx));
    CHECK(r.scene == NULL);
    remove(path);
}

/* A polygon at +-1e308: its Newell normal overflowed to NaN and it was
 * dropped as having no area ("the scene has no objects", exit 0), where one
 * at 1e300 was refused. Both now reach the mesh, which names the line. */
static void test_polygon_near_double_max(void)
{
    const char *values[] = {"1e308", "1e300"};
    for (int i = 0; i < 2; i++) {
        char text[256];
        snprintf(text, sizeof text, "s 0 0 0 1\np 3\n%s 0 0\n0 %s 0\n-%s -%s 0\n", values[i], values[i],
                 values[i], values[i]);
        hr_sdl_result r;
        memset(&r, 0, sizeof r);
        r.struct_size = sizeof r;
        const hr_status st = hr_nff_load_string(ctx, text, "far.nff", &r);
        const char *msg = hr_context_last_error(ctx);
        CHECK_MSG(st == HR_ERROR_PARAMETER && strstr(msg, "far.nff:2:1: ") == msg &&
                      strstr(msg, "beyond the coordinates a mesh takes"),
                  "%s: status %d: %s", values[i], (int)st, msg);
        if (r.scene) hr_scene_destroy(r.scene);
    }
}

/* A whole gzip stream followed by bytes that are no gzip member (a file
 * appended to, or damaged) is refused, naming the file and where the junk
 * starts; two members are read as one text, as gzip -d does; zlib's own
 * name for the stream ("<fd:3>") appears nowhere. */
static void test_gzip_trailing_bytes(void)
{
    static const unsigned char member[] = {0x1f, 0x8b, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02,
                                           0xff, 0x2b, 0x56, 0x30, 0x00, 0x43, 0x43, 0x2e, 0x00,
                                           0xeb, 0xc6, 0x20, 0x1d, 0x0a, 0x00, 0x00, 0x00};
    const char *path = HR_TEST_BINARY_DIR "/tests/trailing_nff.gz";
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    fwrite(member, 1, sizeof member, f);
    fwrite(member, 1, sizeof member, f);
    fclose(f);
    CHECK_MSG(hr_nff_load_file(ctx, path, &r) == HR_OK, "%s", hr_context_last_error(ctx));
    int64_t objects = -1;
    if (r.scene) {
        objects = hr_scene_object_count(r.scene);
        hr_scene_destroy(r.scene);
    }
    CHECK_MSG(objects == 2, "two members give %lld objects", (long long)objects);
    f = fopen(path, "ab");
    CHECK(f != NULL);
    if (!f) return;
    fputs("junk", f);
    fclose(f);
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_nff_load_file(ctx, path, &r) == HR_ERROR_IO);
    const char *msg = hr_context_last_error(ctx);
    CHECK_MSG(strstr(msg, "trailing_nff.gz: cannot read the scene file: 4 bytes after the end of the gzip "
                          "stream (at byte 52 of 56)") != NULL,
              "%s", msg);
    CHECK(r.scene == NULL);
    /* A corrupt member: zlib's reason, the file's name, no "<fd:". */
    f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    unsigned char bad[sizeof member];
    memcpy(bad, member, sizeof member);
    bad[10] = 0xff; /* an invalid block type */
    fwrite(bad, 1, sizeof bad, f);
    fclose(f);
    CHECK(hr_nff_load_file(ctx, path, &r) == HR_ERROR_IO);
    msg = hr_context_last_error(ctx);
    CHECK_MSG(strstr(msg, "trailing_nff.gz: cannot read the scene file: bad gzip data") != NULL &&
                  !strstr(msg, "<fd:"),
              "%s", msg);
    remove(path);
}

/* Files are read as SDL files are (lib/sdl/text_file.h): a device or a FIFO is
 * refused at once, not read for ever, and a gzip file whose text inflates
 * past the scene size limit is refused rather than inflated into memory. */
static void test_file_limits(void)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_nff_load_file(ctx, "/dev/zero", &r) == HR_ERROR_IO);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "not a regular file (a device)") != NULL, "%s",
              hr_context_last_error(ctx));
    const char *fifo = HR_TEST_BINARY_DIR "/tests/fifo.nff";
    remove(fifo);
    if (mkfifo(fifo, 0600) == 0) {
        CHECK(hr_nff_load_file(ctx, fifo, &r) == HR_ERROR_IO);
        CHECK_MSG(strstr(hr_context_last_error(ctx), "not a regular file (a FIFO)") != NULL, "%s",
                  hr_context_last_error(ctx));
        remove(fifo);
    }
    /* 200,000 comment bytes in a gzip of about a kilobyte, under a limit
     * of 100,000. */
    const char *path = HR_TEST_BINARY_DIR "/tests/bomb.nff.gz";
    gzFile g = gzopen(path, "wb9");
    CHECK(g != NULL);
    if (!g) return;
    char line[1001];
    memset(line, '#', sizeof line - 1);
    line[sizeof line - 2] = '\n';
    line[sizeof line - 1] = '\0';
    for (int i = 0; i < 200; i++) gzputs(g, line);
    gzclose(g);
    setenv("HITRAY_MAX_SCENE_BYTES", "100000", 1);
    CHECK(hr_nff_load_file(ctx, path, &r) == HR_ERROR_IO);
    CHECK_MSG(strstr(hr_context_last_error(ctx), "larger than 100000 bytes, the scene size limit") !=
                  NULL,
              "%s", hr_context_last_error(ctx));
    unsetenv("HITRAY_MAX_SCENE_BYTES");
    CHECK(hr_nff_load_file(ctx, path, &r) == HR_OK && r.scene != NULL);
    hr_scene_destroy(r.scene);
    remove(path);
}

/* A concave polygon of more vertices than ear clipping is given time for
 * is refused, naming its line, before it is cut. */
static void test_huge_concave_polygon(void)
{
    const int n = 20000;
    const size_t size = 64 + (size_t)n * 48;
    char *text = malloc(size);
    CHECK(text != NULL);
    if (!text) return;
    size_t used = (size_t)snprintf(text, size, "f 1 1 1 1 0 1 0 0\np %d\n", n);
    for (int i = 0; i < n && used < size; i++) {
        const double a = 6.283185307179586 * i / n, r = i % 2 ? 0.5 : 1.0;
        used += (size_t)snprintf(text + used, size - used, "%.9f %.9f 0\n", r * cos(a),
                                 r * sin(a));
    }
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    CHECK(hr_nff_load_string(ctx, text, "star.nff", &r) == HR_ERROR_SDL);
    CHECK_MSG(strcmp(hr_context_last_error(ctx),
                     "star.nff:2:1: 'p 20000' is a concave polygon of more than 16384 vertices, "
                     "which ear clipping would take too long over: split it") == 0,
              "%s", hr_context_last_error(ctx));
    CHECK(r.scene == NULL);
    free(text);
}

int main(void)
{
    CHECK_OK(hr_context_create(&ctx));
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_case(&cases[i]);
    test_arguments();
    test_file_limits();
    test_truncated_gzip();
    test_gzip_trailing_bytes();
    test_polygon_near_double_max();
    test_huge_concave_polygon();
    hr_context_destroy(ctx);
    return hr_test_end();
}
