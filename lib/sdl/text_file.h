/* Internal: reading a scene file (SDL, NFF) whole, with limits, so that no
 * path makes a reader hang or exhaust memory.
 *
 * - Only a regular file is read (after following links): a device such as
 *   /dev/zero or /dev/urandom never ends, a FIFO blocks until someone
 *   writes, a directory has no text. The file is opened without blocking, so
 *   a FIFO with no writer is refused at once rather than waited on.
 * - Reading stops at the first NUL byte: a text file has none, and a binary
 *   file is refused at the line and column of the first.
 * - A file larger than the scene size limit is refused before it is read
 *   (and reading stops there if it grows meanwhile). The limit is
 *   HR_SCENE_FILE_MAX_BYTES unless the environment variable
 *   HITRAY_MAX_SCENE_BYTES gives another (a byte count, decimal; docs/limits.md).
 *
 * Every error names the file and is recorded on the context; `what` names
 * the kind of file in messages ("scene file"). */
#ifndef HITRAY_LIB_SDL_TEXT_FILE_H
#define HITRAY_LIB_SDL_TEXT_FILE_H

#include <stddef.h>

#include <hitray/hitray.h>

/* 256 MiB: the largest scene shipped is a few kilobytes, a generated one
 * with a million objects about 50 MB; meshes live in files of their own. */
#define HR_SCENE_FILE_MAX_BYTES ((size_t)256 << 20)
#define HR_SCENE_FILE_MAX_BYTES_ENV "HITRAY_MAX_SCENE_BYTES"

/* The limit in force: HITRAY_MAX_SCENE_BYTES if set, else the default. A
 * value that is not a positive decimal byte count is an error naming the
 * variable. */
hr_status hri_scene_file_limit(const hr_context *ctx, size_t *out);

/* The regular file at `path` opened for reading (the checks above but the
 * NUL byte's), for a reader that reads it its own way (gzip): *fd_out (the
 * caller closes it), its size, and the limit in force, which a reader that
 * inflates applies to what it inflates. */
hr_status hri_scene_file_open(const hr_context *ctx, const char *path, const char *what, int *fd_out,
                             size_t *size_out, size_t *limit_out);
/* The error for a scene text beyond `limit` bytes. */
hr_status hri_scene_file_too_large(const hr_context *ctx, const char *path, const char *what,
                                  size_t limit);

/* The whole regular file at `path` into a malloc'd buffer (*text, freed by
 * the caller; NUL-terminated, *length bytes before the terminator). */
hr_status hri_scene_file_read(const hr_context *ctx, const char *path, const char *what, char **text,
                             size_t *length);

#endif
