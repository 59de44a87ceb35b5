/* Helpers shared by the SDL reader tests: a context with in-process stub
 * shapes (so the reader is tested whatever shape modules exist yet), loading
 * helpers, and a check of an error's status, place and message. */
#ifndef HR_SDL_TEST_SUPPORT_H
#define HR_SDL_TEST_SUPPORT_H

#include <hitray/hitray.h>

#include "hr_test.h"

/* Stub classes to register (bit set). Stubs are found before any module. */
#define SDL_STUB_SHAPES 1 /* sphere cube square plane cylinder cone: box [-1,1]^3
                             (plane: unbounded); taperedCylinder s: x, y in
                             [-max(1,s), max(1,s)], z in [0,1]; s must be >= 0 */
#define SDL_STUB_CSG 2    /* union intersection difference: objects a, b */
#define SDL_STUB_MESH 4   /* mesh file: always refuses, naming file and base_dir:
                             "stub mesh: file 'F' in 'D'" */

/* A new context with the stubs asked for; aborts the test if it fails. */
hr_context *sdl_test_context(int stubs);
/* 1 if a shape class of this name can be found (stub or module). */
int sdl_test_has_class(hr_context *ctx, const char *name);

/* The name every string is loaded under, so messages start "t.dat:". */
#define SDL_TEST_NAME "t.dat"

/* Load `text`; on failure report it (with the caller's line) and return
 * NULL. The caller destroys result->scene. */
hr_scene *sdl_test_load_at(const char *file, int line, hr_context *ctx, const char *text,
                           hr_sdl_result *result);
#define LOAD_OK(ctx, text, result) sdl_test_load_at(__FILE__, __LINE__, ctx, text, result)

/* Expect loading `text` to fail with `status`, the error placed at
 * err_line:err_col (the message starting "t.dat:L:C: " and the error info
 * saying the same), no scene returned, and the message containing every
 * string of the NULL-terminated list that follows. */
void sdl_test_expect_error_at(const char *file, int line, hr_context *ctx, const char *text,
                              hr_status status, int err_line, int err_col, ...);
#define EXPECT_ERROR(ctx, text, status, err_line, err_col, ...)                          \
    sdl_test_expect_error_at(__FILE__, __LINE__, ctx, text, status, err_line, err_col,   \
                             __VA_ARGS__, (const char *)NULL)

/* Object `index` of `scene` (struct_size set; zeroed if the call fails). */
hr_object_info sdl_test_object(const hr_scene *scene, int64_t index);

/* Every entry of a 4x4 row-major matrix within `tol`. */
void sdl_test_check_matrix_at(const char *file, int line, const double got[16],
                              const double want[16], double tol, const char *what);
#define CHECK_MATRIX(got, want, tol, what)                                               \
    sdl_test_check_matrix_at(__FILE__, __LINE__, got, want, tol, what)

#define CHECK_COLOR(c, r_, g_, b_, tol)                                                  \
    do {                                                                                 \
        CHECK_NEAR((c).r, r_, tol);                                                      \
        CHECK_NEAR((c).g, g_, tol);                                                      \
        CHECK_NEAR((c).b, b_, tol);                                                      \
    } while (0)

/* Seconds on a monotonic-enough clock (C11 timespec_get). */
double sdl_test_seconds(void);

#endif
