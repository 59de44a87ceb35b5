/* Internal: writing a file all or nothing.
 *
 * The data goes to a temporary file in the target's own directory (so the
 * final rename stays on one filesystem and is atomic), and only a complete,
 * synced file is put in place. Where the filesystem has O_TMPFILE the
 * temporary file has no name until it is complete (linkat gives it one
 * just before the rename), so a process killed while writing, even by
 * SIGKILL, leaves nothing behind; elsewhere it is a hidden ".name.XXXXXX"
 * beside the target. A failure removes the temporary file and leaves the
 * target as it was.
 *
 * The target, links followed, must be a regular file or not exist: a link
 * to a device (/dev/full) or a FIFO is refused rather than replaced, and so
 * is a read-only file (no write permission for the caller, or none at all:
 * replacing it would defeat the protection). A symbolic link to a file is
 * written through: the file it points to is replaced and the link stays (a
 * dangling link is replaced itself). */
#ifndef HITRAY_LIB_IMAGE_ATOMIC_FILE_H
#define HITRAY_LIB_IMAGE_ATOMIC_FILE_H

#include <stdio.h>

#include <hitray/hitray.h>

typedef struct hr_atomic_file {
    const char *target; /* the path the caller asked for (not owned) */
    char *destination;  /* where the rename goes: the target, or the file a
                           symbolic link named as target points to (owned) */
    char *temp_path;    /* the temporary file's name (owned); NULL while it
                           has none (O_TMPFILE) */
    FILE *fp;           /* open for writing on the temporary file */
    int finished;       /* flushed and synced: only publishing is left */
} hr_atomic_file;

/* Create the temporary file for `target`. On failure nothing is left on
 * disk, `*out` needs no cleanup, and the error names `target`. */
hr_status hri_atomic_file_open(const hr_context *ctx, const char *target, hr_atomic_file *out);

/* Flush and sync the temporary file: every failure of the disk (full, I/O
 * error) shows here, before anything is put in place. On failure `f` is
 * released (as by abort). */
hr_status hri_atomic_file_finish(const hr_context *ctx, hr_atomic_file *f);

/* Put a finished file in place (name it, rename it onto the target). Either
 * way `f` is released. */
hr_status hri_atomic_file_publish(const hr_context *ctx, hr_atomic_file *f);

/* Give up: close and remove the temporary file, release `f`. */
void hri_atomic_file_abort(hr_atomic_file *f);

#endif
