/* The mesh readers refuse bad files with one line naming the file, the
 * line in it, what is wrong and the token found (tests/data/meshes/bad/),
 * and never crash: every prefix of every good and bad file is read too
 * (truncated files), and so are a few generated hostile inputs. */
#define _POSIX_C_SOURCE 200809L /* mkfifo */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "hr_test.h"
#include "mesh_support.h"

static harness_module module;

typedef struct bad_file {
    const char *name;
    hr_status status;
    int line;              /* 0: no line (not a parse error) */
    const char *fragment;  /* must appear in the message */
} bad_file;

static const bad_file bad_files[] = {
    {"count_too_big.3vn", HR_ERROR_PARAMETER, 1, "expected the number of vertices (a whole number up to 4294967294) (found '100000000000...')"},
    {"count_past_file.3vn", HR_ERROR_PARAMETER, 1, "the counts (4000000 vertices, 0 normals, 1 faces) need more numbers than the rest of the file holds (found '1')"},
    {"vertex_index.3vn", HR_ERROR_PARAMETER, 6, "face 0: vertex index 9 out of range (the file has 3) (found '9')"},
    {"normal_index.3vn", HR_ERROR_PARAMETER, 6, "face 0: normal index 1 out of range (the file has 1) (found '1')"},
    {"nan.3vn", HR_ERROR_PARAMETER, 3, "vertex 1: expected a number (found 'nan')"},
    {"huge.3vn", HR_ERROR_PARAMETER, 3, "vertex 1: coordinate out of range (at most 1e+100) (found '1e999')"},
    {"short_face.3vn", HR_ERROR_PARAMETER, 6, "face 0: 4 corners need more numbers than the rest of the file holds (found '4')"},
    {"truncated.3vn", HR_ERROR_PARAMETER, 6, "face 0: expected a normal index (found end of file)"},
    {"two_corners.3vn", HR_ERROR_PARAMETER, 6, "face 0: a face needs at least 3 corners (found '2')"},
    {"no_area.3vn", HR_ERROR_PARAMETER, 0, "the mesh has no triangle with area (1 skipped)"},
    {"trailing.3vn", HR_ERROR_PARAMETER, 7, "unexpected text after the last of 1 faces (found 'extra')"},
    {"junk_index.3vn", HR_ERROR_PARAMETER, 6, "face 0: expected a normal index (found '0x')"},
    {"unknown.obj", HR_ERROR_PARAMETER, 4, "unknown OBJ statement (expected v, vn, f, or one of vt vp o g s usemtl mtllib l p) (found 'what')"},
    {"face_index.obj", HR_ERROR_PARAMETER, 4, "face corner 3: vertex index missing or out of range (3 vertices so far) (found '4')"},
    {"normal_index.obj", HR_ERROR_PARAMETER, 5, "face corner 2: normal index missing or out of range (1 normals so far) (found '2//2')"},
    {"short_face.obj", HR_ERROR_PARAMETER, 4, "a face needs at least 3 corners, this one has 2 (found 'f')"},
    {"vertex_text.obj", HR_ERROR_PARAMETER, 2, "'v': expected a number (found 'x')"},
    {"normal_extra.obj", HR_ERROR_PARAMETER, 2, "'vn': unexpected text after the coordinates (found '2')"},
    {"zero_index.obj", HR_ERROR_PARAMETER, 4, "face corner 1: vertex index missing or out of range (3 vertices so far) (found '0')"},
    {"bad_corner.obj", HR_ERROR_PARAMETER, 4, "face corner 1: nothing after '/' (found '1/')"},
    {"empty.obj", HR_ERROR_PARAMETER, 0, "the mesh has no triangle with area (0 skipped)"},
};

static void test_bad_files(void)
{
    for (size_t i = 0; i < sizeof bad_files / sizeof bad_files[0]; i++) {
        const bad_file *b = &bad_files[i];
        char path[1024], error[512], expected[1200];
        mesh_data_path("bad/", path, sizeof path);
        strncat(path, b->name, sizeof path - strlen(path) - 1);
        void *shape = NULL;
        hr_status st = mesh_create_file(&module, path, &shape, error, sizeof error);
        CHECK_MSG(st == b->status && shape == NULL, "%s: status %d, expected %d", b->name, (int)st,
                  (int)b->status);
        if (b->line) snprintf(expected, sizeof expected, "%s:%d: %s", path, b->line, b->fragment);
        else snprintf(expected, sizeof expected, "%s: %s", path, b->fragment);
        CHECK_MSG(strcmp(error, expected) == 0, "%s:\n  got      %s\n  expected %s", b->name, error,
                  expected);
        if (shape) harness_find_class(&module, "mesh")->destroy(shape);
    }
}

/* Files that cannot be read: missing, a directory, no name. */
static void test_unreadable(void)
{
    char path[1024], error[512];
    void *shape = NULL;
    mesh_data_path("no_such_mesh.3vn", path, sizeof path);
    CHECK(mesh_create_file(&module, path, &shape, error, sizeof error) == HR_ERROR_IO);
    CHECK_MSG(strstr(error, "cannot read mesh file") && strstr(error, "no_such_mesh.3vn") &&
                  strstr(error, "no such file"),
              "%s", error);
    mesh_data_path("bad", path, sizeof path);
    CHECK(mesh_create_file(&module, path, &shape, error, sizeof error) == HR_ERROR_IO);
    CHECK_MSG(strstr(error, "not a regular file"), "%s", error);
    /* A FIFO with no writer: refused at once, not waited on. */
    mesh_build_path("fifo.3vn", path, sizeof path);
    remove(path);
    if (mkfifo(path, 0600) == 0) {
        CHECK(mesh_create_file(&module, path, &shape, error, sizeof error) == HR_ERROR_IO);
        CHECK_MSG(strstr(error, "not a regular file"), "%s", error);
        remove(path);
    }
    CHECK(mesh_create_file(&module, "", &shape, error, sizeof error) == HR_ERROR_PARAMETER);
    CHECK_MSG(strstr(error, "'file'"), "%s", error);
    CHECK(shape == NULL);
}

/* The message's error for `bytes` read as a mesh file `name` (scratch). */
static void error_for(const char *name, const char *bytes, char *error, size_t size)
{
    char path[1024];
    mesh_build_path(name, path, sizeof path);
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (!f) return;
    fputs(bytes, f);
    fclose(f);
    void *shape = NULL;
    CHECK(mesh_create_file(&module, path, &shape, error, size) == HR_ERROR_PARAMETER && !shape);
}

/* A message quotes a token cut short and escaped, never a line of whatever
 * file was named (issue 16: `mesh /etc/passwd` printed its first line), nor
 * bytes a terminal would act on. */
static void test_quoting(void)
{
    char error[512];
    error_for("passwd.3vn", "root:x:0:0:root:/root:/bin/bash\n", error, sizeof error);
    CHECK_MSG(strstr(error, "(found 'root:x:0:0:r...')") && !strstr(error, "/bin/bash"), "%s", error);
    error_for("escape.obj", "v 1 2 \x1b[31mred'\\\n", error, sizeof error);
    CHECK_MSG(strstr(error, "(found '\\x1b[31mred\\x27\\x5c')") && !strchr(error, 0x1b), "%s", error);
}

/* Writes `length` bytes to a scratch file and reads it as `ext`: whatever
 * the bytes, the reader returns a status, and on success a usable mesh. */
static int read_bytes(const char *bytes, size_t length, const char *ext)
{
    char path[1024], error[512];
    char name[64];
    snprintf(name, sizeof name, "mesh_fuzz%s", ext);
    mesh_build_path(name, path, sizeof path);
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    fwrite(bytes, 1, length, f);
    fclose(f);
    void *shape = NULL;
    hr_status st = mesh_create_file(&module, path, &shape, error, sizeof error);
    if (st == HR_OK) {
        const hr_shape_class *cls = harness_find_class(&module, "mesh");
        hr_bounds b;
        cls->bounds(shape, &b);
        CHECK(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z);
        cls->destroy(shape);
    } else {
        CHECK_MSG(error[0] != '\0', "status %d without a message", (int)st);
        CHECK_MSG(strncmp(error, path, strlen(path)) == 0 || st == HR_ERROR_IO,
                  "message does not name the file: %s", error);
    }
    return st == HR_OK;
}

static char *slurp(const char *path, size_t *length)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buffer = malloc(1 << 16);
    *length = buffer ? fread(buffer, 1, 1 << 16, f) : 0;
    fclose(f);
    return buffer;
}

/* Every prefix of the good files: each is either a valid mesh or an error
 * naming the file; none crashes (the sanitizer build checks reads past the
 * end). */
static void test_prefixes(void)
{
    static const char *const files[] = {"cube.obj", "cube.3vn", "smooth_square.obj",
                                        "tetra_hill.3vn"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[1024];
        size_t length = 0;
        char *text = slurp(mesh_data_path(files[i], path, sizeof path), &length);
        CHECK(text != NULL);
        if (!text) continue;
        const char *ext = strstr(files[i], ".obj") ? ".obj" : ".3vn";
        int ok = 0;
        for (size_t n = 0; n <= length; n++) ok += read_bytes(text, n, ext) == 1;
        CHECK(read_bytes(text, length, ext) == 1);
        CHECK_MSG(ok >= 1, "%s: no prefix read", files[i]);
        free(text);
    }
}

/* Hostile inputs: enormous counts in a tiny file, a face of a billion
 * corners, deep runs of slashes, NUL bytes, a polygon whose every corner
 * is the same vertex. */
static void test_hostile(void)
{
    static const char *const hill[] = {
        "4294967294 4294967294 4294967294\n",
        "3 0 1\n0 0 0 1 0 0 0 1 0\n1000000000 0 1 2\n",
        "3 1 1\n0 0 0 1 0 0 0 1 0 0 0 1\n3 0 0 0 0 0 0\n",
        "3 1 1\n0 0 0 1 0 0 0 1 0 0 0 1\n3 0 1 2 0 0 0\n   \n\n",
        "-3 1 1\n",
        "3.0 1 1\n",
        "",
    };
    for (size_t i = 0; i < sizeof hill / sizeof hill[0]; i++)
        read_bytes(hill[i], strlen(hill[i]), ".3vn");
    static const char *const obj[] = {
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1////// 2 3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1 2 3 1 2 3\n",
        "v 1e-300 0 0\nv 1e100 0 0\nv 0 -1e100 0\nf 1 2 3\n",
        "v\n",
        "f\n",
        "#\n#\n",
        "v 0 0 0 1 1 1 1 1\n",
    };
    for (size_t i = 0; i < sizeof obj / sizeof obj[0]; i++)
        read_bytes(obj[i], strlen(obj[i]), ".obj");
    /* Windows line ends and a byte order mark are fine. */
    const char crlf[] = "\xEF\xBB\xBFv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n";
    CHECK(read_bytes(crlf, sizeof crlf - 1, ".obj") == 1);
    const char crlf_hill[] = "\xEF\xBB\xBF" "3 1 1\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n3 0 1 2 0 0 0\r\n";
    CHECK(read_bytes(crlf_hill, sizeof crlf_hill - 1, ".3vn") == 1);
    const char nul[] = "v 0 0 0\nv 1 0\0 0\nv 0 1 0\nf 1 2 3\n";
    read_bytes(nul, sizeof nul - 1, ".obj");
    /* The all-same-vertex polygon, and the near-duplicate negatives, give a
     * status, not a mesh of nothing. */
    CHECK(read_bytes(obj[4], strlen(obj[4]), ".obj") == 1);
}

/* Mutations of the good files with a fixed seed: bytes replaced by the
 * characters that matter to the readers (digits, signs, points, slashes,
 * line ends, keywords' letters, NUL), bytes deleted and duplicated. Each is
 * read; none may crash or leak (the sanitizer build checks). */
static void test_mutations(void)
{
    static const char *const files[] = {"cube.obj", "cube.3vn", "smooth_square.obj",
                                        "tetra_hill.3vn"};
    static const char alphabet[] = "0123456789-+.e/ \n\r#vnft9\0";
    uint64_t state = 0x243f6a8885a308d3u;
    int read_ok = 0, total = 0;
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[1024];
        size_t length = 0;
        char *text = slurp(mesh_data_path(files[i], path, sizeof path), &length);
        if (!text) continue;
        const char *ext = strstr(files[i], ".obj") ? ".obj" : ".3vn";
        char *copy = malloc(2 * length + 16);
        for (int round = 0; round < 400 && copy; round++) {
            memcpy(copy, text, length);
            size_t n = length;
            for (int edits = 1 + round % 4; edits > 0 && n > 0; edits--) {
                state = state * 6364136223846793005u + 1442695040888963407u;
                size_t at = (size_t)(state >> 33) % n;
                int kind = (int)((state >> 20) % 3);
                if (kind == 0) {
                    copy[at] = alphabet[(state >> 40) % (sizeof alphabet - 1)];
                } else if (kind == 1) {
                    memmove(copy + at, copy + at + 1, n - at - 1);
                    n--;
                } else {
                    memmove(copy + at + 1, copy + at, n - at);
                    n++;
                }
            }
            read_ok += read_bytes(copy, n, ext) == 1;
            total++;
        }
        free(copy);
        free(text);
    }
    printf("mutations: %d of %d still read as meshes\n", read_ok, total);
    CHECK(total == 1600);
}

/* hr_host.file_read: called once, after the file is read, with create's
 * own arguments and the path opened; its failure fails create (out of
 * memory, no shape); a host from before it (a smaller struct_size) is never
 * asked. */
static int files_told;
static char told_path[1024];
static hr_status tell_ok(const hr_create_args *args, const char *path)
{
    files_told++;
    snprintf(told_path, sizeof told_path, "%s", args && args->host && path ? path : "");
    return HR_OK;
}
static hr_status tell_fails(const hr_create_args *args, const char *path)
{
    (void)args, (void)path;
    files_told++;
    return HR_ERROR_OUT_OF_MEMORY;
}

static void test_file_read_service(void)
{
    char path[1024], error[512];
    mesh_data_path("cube.obj", path, sizeof path);
    hr_host host = *harness_host();
    const hr_shape_class *cls = harness_find_class(&module, "mesh");
    struct {
        hr_status (*tell)(const hr_create_args *, const char *);
        uint32_t size;
        hr_status want;
        int told;
    } cases[] = {
        {tell_ok, sizeof(hr_host), HR_OK, 1},
        {tell_fails, sizeof(hr_host), HR_ERROR_OUT_OF_MEMORY, 1},
        {tell_fails, (uint32_t)offsetof(hr_host, file_read), HR_OK, 0},
    };
    for (int i = 0; i < 3; i++) {
        host.file_read = cases[i].tell;
        host.struct_size = cases[i].size;
        files_told = 0, told_path[0] = '\0';
        void *shape = NULL;
        hr_status st = mesh_create_file_on(&module, &host, path, &shape, error, sizeof error);
        CHECK_MSG(st == cases[i].want && (shape != NULL) == (st == HR_OK) && files_told == cases[i].told,
                  "case %d: status %d, %d calls: %s", i, (int)st, files_told, error);
        if (i == 0) CHECK_MSG(strcmp(told_path, path) == 0, "told '%s'", told_path);
        if (st != HR_OK) CHECK_MSG(strstr(error, "out of memory") != NULL, "case %d: %s", i, error);
        if (shape) cls->destroy(shape);
    }
}

int main(void)
{
    if (!harness_load("mesh", &module)) return hr_test_end() | 1;
    test_bad_files();
    test_unreadable();
    test_quoting();
    test_prefixes();
    test_hostile();
    test_mutations();
    test_file_read_service();
    harness_unload(&module);
    return hr_test_end();
}
