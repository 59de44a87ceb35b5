/* Internal: writing a file all or nothing.
 *
 * The data goes to a uniquely named temporary file in the target's own
 * directory (so the final rename stays on one filesystem and is atomic), and
 * only a complete, flushed file is renamed over the target. A failure removes
 * the temporary file and leaves the target as it was. A target that is a
 * symbolic link to an existing file is written through: the file it points
 * to is replaced and the link stays (a dangling link is replaced itself). */
#ifndef HITRAY_LIB_ATOMIC_FILE_H
#define HITRAY_LIB_ATOMIC_FILE_H

#include <stdio.h>

#include <hitray/hitray.h>

typedef struct hr_atomic_file {
    const char *target; /* the path the caller asked for (not owned) */
    char *destination;  /* where the rename goes: the target, or the file a
                           symbolic link named as target points to (owned) */
    char *temp_path;    /* the temporary file beside it (owned) */
    FILE *fp;           /* open for writing on the temporary file */
} hr_atomic_file;

/* Create the temporary file for `target`. On failure nothing is left on
 * disk, `*out` needs no cleanup, and the error names `target`. */
hr_status hr_atomic_file_open(const hr_context *ctx, const char *target, hr_atomic_file *out);

/* Flush, sync and close the temporary file, then rename it onto the target.
 * On failure the temporary file is removed. Either way `f` is released. */
hr_status hr_atomic_file_commit(const hr_context *ctx, hr_atomic_file *f);

/* Give up: close and remove the temporary file, release `f`. */
void hr_atomic_file_abort(hr_atomic_file *f);

#endif
