/* Several files written all or nothing (include/hitray/image.h): a list of
 * finished, unpublished atomic files, published together. */
#include <stdlib.h>
#include <string.h>

#include "image/atomic_file.h"
#include "util/errors.h"
#include "image/image_writers.h"

struct hr_file_batch {
    hr_context *ctx;
    hr_atomic_file *files;
    int32_t count, capacity;
};

HR_API hr_status hr_file_batch_create(hr_context *ctx, hr_file_batch **out)
{
    if (!out) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "file batch: NULL output");
    *out = NULL;
    if (!ctx) return HR_ERROR_INVALID_ARGUMENT;
    hr_file_batch *b = calloc(1, sizeof *b);
    if (!b) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    b->ctx = ctx;
    *out = b;
    return HR_OK;
}

/* Room for one more file; the target strings are the caller's, so each
 * file keeps its own copy (the atomic file only borrows `target`). */
static hr_atomic_file *next_slot(hr_file_batch *b)
{
    if (b->count == b->capacity) {
        int32_t cap = b->capacity ? 2 * b->capacity : 4;
        hr_atomic_file *grown = cap > b->capacity ? realloc(b->files, (size_t)cap * sizeof *grown) : NULL;
        if (!grown) return NULL;
        b->files = grown;
        b->capacity = cap;
    }
    return &b->files[b->count];
}

/* The caller's path outlives nothing here: the file's target becomes its
 * destination copy, which the atomic file owns. */
static void keep(hr_file_batch *b, hr_atomic_file *f)
{
    f->target = f->destination;
    b->count++;
}

HR_API hr_status hr_file_batch_add_image(hr_file_batch *batch, const hr_image *image, const char *path,
                                         const hr_image_write_options *options)
{
    if (!batch) return HR_ERROR_INVALID_ARGUMENT;
    hr_atomic_file *f = next_slot(batch);
    if (!f) return hri_error(batch->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    hr_status st = hri_image_write_unpublished(batch->ctx, image, path, options, f);
    if (st == HR_OK) keep(batch, f);
    return st;
}

HR_API hr_status hr_file_batch_add_bytes(hr_file_batch *batch, const char *path, const void *data, size_t size)
{
    if (!batch) return HR_ERROR_INVALID_ARGUMENT;
    if (!path || !*path) return hri_error(batch->ctx, HR_ERROR_INVALID_ARGUMENT, "file batch: empty file name");
    if (!data && size) return hri_error(batch->ctx, HR_ERROR_INVALID_ARGUMENT, "file batch: NULL data");
    hr_atomic_file *f = next_slot(batch);
    if (!f) return hri_error(batch->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    hr_status st = hri_atomic_file_open(batch->ctx, path, f);
    if (st) return st;
    if (size && fwrite(data, 1, size, f->fp) != size) {
        st = hri_error(batch->ctx, HR_ERROR_IO, "cannot write '%s': write error", path);
        hri_atomic_file_abort(f);
        return st;
    }
    if ((st = hri_atomic_file_finish(batch->ctx, f))) return st;
    keep(batch, f);
    return HR_OK;
}

HR_API hr_status hr_file_batch_commit(hr_file_batch *batch)
{
    if (!batch) return HR_ERROR_INVALID_ARGUMENT;
    hr_status st = HR_OK;
    for (int32_t i = 0; i < batch->count; i++) {
        if (st) hri_atomic_file_abort(&batch->files[i]);
        else st = hri_atomic_file_publish(batch->ctx, &batch->files[i]);
    }
    batch->count = 0;
    return st;
}

HR_API void hr_file_batch_destroy(hr_file_batch *batch)
{
    if (!batch) return;
    for (int32_t i = 0; i < batch->count; i++) hri_atomic_file_abort(&batch->files[i]);
    free(batch->files);
    free(batch);
}
