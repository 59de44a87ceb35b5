/* Internal: error messages of the SDL reader. Every message starts with
 * "file:line:col: " and says what was expected and what was found; inside an
 * expanded macro it first names each `use` and the definition it expanded:
 *   scene.dat:30:1: in macro 'leg' (defined at scene.dat:3:5): scene.dat:3:22: expected ...
 * The line and column kept for hr_context_last_error_info are the first ones
 * of the message: the place in the file's own text where the error arose. */
#ifndef HITRAY_LIB_SDL_DIAG_H
#define HITRAY_LIB_SDL_DIAG_H

#include <stddef.h>

#include "util/errors.h"
#include "sdl/sdl_source.h"

/* Raise `status` on the source's context for the token `at`; returns it. */
hr_status sdl_error(const sdl_source *src, hr_status status, sdl_located at, const char *fmt,
                    ...) HR_PRINTF(4, 5);

/* The same place and macro levels for a warning (HR_WARNING_*) to the
 * context's warning callback. */
void sdl_warning(const sdl_source *src, int32_t code, sdl_located at, const char *fmt, ...)
    HR_PRINTF(4, 5);

/* When `keyword` came from a macro body and `found` (an argument it wanted)
 * did not come from that same expansion, the arguments ran on past the end
 * of the body: writes " (the arguments of 'K' in macro 'M', defined at
 * f:L:C, run on past the end of its body)" to buf; otherwise "". Returns buf. */
const char *sdl_describe_run_on(const sdl_source *src, sdl_located keyword, sdl_located found,
                                char *buf, size_t size);

/* A token for "found ...": 'word' (long words shortened), '{', '}', or
 * "end of file". Writes into buf and returns it. */
const char *sdl_describe(const sdl_token *token, char *buf, size_t size);

#endif
