/* The public ways to raise an error and a warning on a context
 * (hr_context_set_error, hr_context_warn): what a program's own code built
 * on hitray uses so that its errors reach the program as the library's do,
 * and what the SDL and NFF readers, clients of the public API, go through. */
#include <string.h>

#include <hitray/hitray.h>

#include "hr_test.h"

static int error_calls;
static hr_status error_status;
static char error_message[4096];
static void on_error(void *user, hr_status status, const char *message)
{
    (void)user;
    error_calls++;
    error_status = status;
    strcpy(error_message, message);
}

static int warning_calls;
static hr_warning seen;
static char warning_message[4096];
static char warning_file[1024];
static void on_warning(void *user, const hr_warning *w)
{
    (void)user;
    warning_calls++;
    seen = *w;
    strcpy(warning_message, w->message);
    strcpy(warning_file, w->file);
}

static hr_error_info last_info(hr_context *ctx)
{
    hr_error_info info = {.struct_size = sizeof info};
    CHECK_OK(hr_context_last_error_info(ctx, &info));
    return info;
}

/* The parts come back as given, the callback sees the message, the status
 * is returned. */
static void test_parts(hr_context *ctx)
{
    error_calls = 0;
    CHECK(hr_context_set_error(ctx, HR_ERROR_SDL, "scene.obj", 12, 7,
                               "scene.obj:12:7: expected a number") == HR_ERROR_SDL);
    hr_error_info info = last_info(ctx);
    CHECK(info.status == HR_ERROR_SDL);
    CHECK(strcmp(info.message, "scene.obj:12:7: expected a number") == 0);
    CHECK(strcmp(info.file, "scene.obj") == 0);
    CHECK(info.line == 12 && info.column == 7);
    CHECK(strcmp(hr_context_last_error(ctx), info.message) == 0);
    CHECK(error_calls == 1 && error_status == HR_ERROR_SDL);
    CHECK(strcmp(error_message, info.message) == 0);

    /* Not in a file: NULL file and a NULL message read as "". */
    CHECK(hr_context_set_error(ctx, HR_ERROR_IO, NULL, 0, 0, NULL) == HR_ERROR_IO);
    info = last_info(ctx);
    CHECK(info.status == HR_ERROR_IO && strcmp(info.message, "") == 0);
    CHECK(strcmp(info.file, "") == 0 && info.line == 0 && info.column == 0);
    CHECK(error_calls == 2);
}

/* This thread's last error passed on: the strings hr_context_last_error_info
 * gave may be handed back, the message with more said or as it is. */
static void test_passed_on(hr_context *ctx)
{
    hr_context_set_error(ctx, HR_ERROR_SDL, "a.sdl", 3, 4, "a.sdl:3:4: unknown word 'shpere'");
    hr_error_info info = last_info(ctx);
    CHECK(hr_context_set_error(ctx, HR_ERROR_MODULE, info.file, info.line, info.column,
                               info.message) == HR_ERROR_MODULE);
    info = last_info(ctx);
    CHECK(info.status == HR_ERROR_MODULE);
    CHECK(strcmp(info.message, "a.sdl:3:4: unknown word 'shpere'") == 0);
    CHECK(strcmp(info.file, "a.sdl") == 0 && info.line == 3 && info.column == 4);
    /* A tail of the message it already holds. */
    CHECK(hr_context_set_error(ctx, HR_ERROR_SDL, NULL, 0, 0, info.message + 11) == HR_ERROR_SDL);
    CHECK(strcmp(hr_context_last_error(ctx), "unknown word 'shpere'") == 0);
}

/* A message or a file longer than a context keeps is cut, not refused. */
static void test_cut(hr_context *ctx)
{
    static char longer[5000];
    memset(longer, 'x', sizeof longer - 1);
    hr_context_set_error(ctx, HR_ERROR_SDL, longer, 1, 1, longer);
    hr_error_info info = last_info(ctx);
    CHECK(strlen(info.message) == 2047);
    CHECK(strlen(info.file) == 511);
    CHECK(strlen(error_message) == 2047);
}

static void test_warning(hr_context *ctx)
{
    warning_calls = 0;
    hr_context_warn(ctx, HR_WARNING_EMPTY_SCENE, NULL, 0, 0, "nothing to see");
    CHECK(warning_calls == 0); /* no callback set: it goes nowhere */
    hr_context_set_warning_callback(ctx, on_warning, NULL);
    hr_context_warn(ctx, HR_WARNING_BELOW_THRESHOLD, "b.nff", 5, 2, "b.nff:5:2: too small");
    CHECK(warning_calls == 1);
    CHECK(seen.struct_size == sizeof(hr_warning) && seen.code == HR_WARNING_BELOW_THRESHOLD);
    CHECK(strcmp(warning_message, "b.nff:5:2: too small") == 0);
    CHECK(strcmp(warning_file, "b.nff") == 0 && seen.line == 5 && seen.column == 2);
    hr_context_warn(ctx, HR_WARNING_EMPTY_SCENE, NULL, 0, 0, NULL);
    CHECK(warning_calls == 2 && strcmp(warning_message, "") == 0 && strcmp(warning_file, "") == 0);
    /* A warning is not an error: the last error stays. */
    hr_context_set_error(ctx, HR_ERROR_IO, NULL, 0, 0, "still here");
    hr_context_warn(ctx, HR_WARNING_EMPTY_SCENE, NULL, 0, 0, "a warning");
    CHECK(strcmp(hr_context_last_error(ctx), "still here") == 0);
}

/* Control bytes (an escape sequence, a bell) are kept as \xNN, in errors
 * and warnings alike, whoever built the message: a word of a scene file
 * from elsewhere must not reach a terminal that would act on it. The
 * newline and the tab stay. */
static void test_escaped(hr_context *ctx)
{
    hr_context_set_error(ctx, HR_ERROR_SDL, "e.sdl", 1, 1, "e.sdl:1:1: 'sph\x1b[31mere'\x1b]0;t\x07\x7f\tx\ny");
    CHECK_MSG(strcmp(hr_context_last_error(ctx), "e.sdl:1:1: 'sph\\x1b[31mere'\\x1b]0;t\\x07\\x7f\tx\ny") == 0,
              "%s", hr_context_last_error(ctx));
    CHECK(strcmp(error_message, hr_context_last_error(ctx)) == 0);
    hr_context_warn(ctx, HR_WARNING_EMPTY_SCENE, NULL, 0, 0, "\x1b[2J");
    CHECK_MSG(strcmp(warning_message, "\\x1b[2J") == 0, "%s", warning_message);
    /* A message of control bytes that would be four times as long is cut
     * whole escapes at a time, within the slot. */
    static char bells[3000];
    memset(bells, '\a', sizeof bells - 1);
    hr_context_set_error(ctx, HR_ERROR_SDL, NULL, 0, 0, bells);
    const char *kept = hr_context_last_error(ctx);
    CHECK(strlen(kept) <= 2047 && strlen(kept) % 4 == 0 && strncmp(kept, "\\x07\\x07", 8) == 0);
}

int main(void)
{
    /* No context: nothing recorded, the status still returned. */
    CHECK(hr_context_set_error(NULL, HR_ERROR_IO, "f", 1, 1, "m") == HR_ERROR_IO);
    hr_context_warn(NULL, HR_WARNING_EMPTY_SCENE, NULL, 0, 0, "m");

    hr_context *ctx;
    CHECK_OK(hr_context_create(&ctx));
    hr_context_set_error_callback(ctx, on_error, NULL);
    test_parts(ctx);
    test_passed_on(ctx);
    test_cut(ctx);
    test_warning(ctx);
    test_escaped(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
