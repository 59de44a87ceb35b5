/* What hr_sdl_load_file refuses to read (lib/sdl/text_file.h; issue 16, defect
 * 2): a device that never ends (/dev/zero, /dev/urandom), a FIFO (whose open
 * would wait for a writer), a file larger than the scene size limit, and a
 * binary file, at its first NUL byte. Each is refused at once with an error
 * naming the file; none is read to its end first. */
#define _POSIX_C_SOURCE 200809L /* mkfifo, setenv */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sdl_test_support.h"

static hr_context *ctx;

static hr_status load(const char *path)
{
    hr_sdl_result r;
    memset(&r, 0, sizeof r);
    r.struct_size = sizeof r;
    hr_status st = hr_sdl_load_file(ctx, path, &r);
    CHECK_MSG(st != HR_OK || r.scene != NULL, "%s: no scene and no error", path);
    if (st == HR_OK) hr_scene_destroy(r.scene);
    else CHECK(r.scene == NULL);
    return st;
}

static void expect_refused(const char *path, hr_status status, const char *words)
{
    CHECK_MSG(load(path) == status, "%s: %s", path, hr_context_last_error(ctx));
    const char *msg = hr_context_last_error(ctx);
    CHECK_MSG(strstr(msg, path) && strstr(msg, words), "%s: message '%s' lacks '%s'", path, msg,
              words);
}

static void write_file(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    CHECK(f && fwrite(text, 1, n, f) == n);
    if (f) fclose(f);
}

int main(void)
{
    ctx = sdl_test_context(SDL_STUB_SHAPES);
    char dir[] = "/tmp/hitray_sdl_limits_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char path[256];

    /* Devices: were they read, /dev/zero would grow memory without end. */
    if (access("/dev/zero", R_OK) == 0) expect_refused("/dev/zero", HR_ERROR_IO, "not a regular file (a device)");
    if (access("/dev/urandom", R_OK) == 0) expect_refused("/dev/urandom", HR_ERROR_IO, "not a regular file");

    /* A FIFO with no writer: refused at once, not waited on. */
    snprintf(path, sizeof path, "%s/fifo.sdl", dir);
    CHECK(mkfifo(path, 0600) == 0);
    expect_refused(path, HR_ERROR_IO, "not a regular file (a FIFO)");
    remove(path);

    /* The size limit and its override. */
    snprintf(path, sizeof path, "%s/big.sdl", dir);
    char text[3000];
    memset(text, ' ', sizeof text);
    memcpy(text + sizeof text - 7, "sphere\n", 7);
    write_file(path, text, sizeof text);
    CHECK_OK(load(path));
    setenv("HITRAY_MAX_SCENE_BYTES", "2999", 1);
    expect_refused(path, HR_ERROR_IO, "larger than 2999 bytes, the scene size limit (set HITRAY_MAX_SCENE_BYTES");
    setenv("HITRAY_MAX_SCENE_BYTES", "3000", 1);
    CHECK_OK(load(path));
    const char *bad[] = {"0", "-5", "12k", "abc", " 7"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        setenv("HITRAY_MAX_SCENE_BYTES", bad[i], 1);
        CHECK_MSG(load(path) == HR_ERROR_INVALID_ARGUMENT, "HITRAY_MAX_SCENE_BYTES=%s accepted", bad[i]);
        CHECK(strstr(hr_context_last_error(ctx), "HITRAY_MAX_SCENE_BYTES") != NULL);
    }
    unsetenv("HITRAY_MAX_SCENE_BYTES");

    /* A binary file stops at its first NUL, placed by line and column. */
    const char binary[] = "sphere\n\x7f" "ELF\0\0\0\0";
    write_file(path, binary, sizeof binary - 1);
    CHECK(load(path) == HR_ERROR_SDL);
    hr_error_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    CHECK_OK(hr_context_last_error_info(ctx, &info));
    CHECK_MSG(info.line == 2 && info.column == 5, "NUL placed at %d:%d", (int)info.line, (int)info.column);
    CHECK(strstr(info.message, "unexpected NUL byte") != NULL);
    remove(path);

    /* A link to a device is followed and refused the same way. */
    snprintf(path, sizeof path, "%s/zero.sdl", dir);
    if (symlink("/dev/zero", path) == 0) {
        expect_refused(path, HR_ERROR_IO, "not a regular file");
        remove(path);
    }
    rmdir(dir);
    hr_context_destroy(ctx);
    return hr_test_end();
}
