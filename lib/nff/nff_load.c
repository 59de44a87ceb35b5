/* The public NFF entry points (include/hitray/nff.h): read the text (through
 * zlib, which reads gzip and plain files alike), run the reader over a new
 * scene, frame a camera if the file has no `v`. On any error the partial
 * scene is destroyed and out->scene is NULL. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "util/errors.h"
#include "sdl/load_result.h"
#include "nff/nff_reader.h"
#include "sdl/text_file.h"

static hr_status read_scene(hr_context *ctx, const char *text, size_t length, const char *name,
                            hr_sdl_result *result)
{
    hr_scene *scene = NULL;
    nff_reader reader;
    memset(&reader, 0, sizeof reader);
    hr_status st = hr_scene_create(ctx, &scene);
    if (!st) {
        nff_reader_init(&reader, ctx, scene, name, text, length);
        st = nff_reader_run(&reader);
    }
    if (!st) {
        result->scene = scene;
        result->has_camera = reader.has_camera;
        result->camera = reader.camera;
        if (!reader.has_camera) {
            st = hr_scene_frame_camera(scene, &result->camera);
            /* Framing happens after the last entity: the message names the
             * object, the place is the end of the file. */
            if (st) st = nff_error(&reader, st, nff_peek(&reader.lx), "%s", hr_context_last_error(ctx));
        }
    }
    nff_reader_release(&reader);
    if (st) {
        hr_scene_destroy(scene);
        hri_load_result_empty(result);
    }
    return st;
}

static hr_status load_text(hr_context *ctx, const char *text, size_t length, const char *name,
                           hr_sdl_result *out)
{
    hr_sdl_result result;
    hri_load_result_empty(&result);
    hr_status st = read_scene(ctx, text, length, name, &result);
    hri_load_result_give(out, &result);
    return st;
}

HR_API hr_status hr_nff_load_string(hr_context *ctx, const char *text, const char *name,
                                    hr_sdl_result *out)
{
    hr_status st = hri_load_result_begin(ctx, out, "NFF");
    if (st) return st;
    if (!text) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_nff_load_string: NULL text");
    return load_text(ctx, text, strlen(text), name ? name : "<string>", out);
}

/* The whole file, inflated if it is gzip, read in pieces. Only a regular
 * file is read (text_file.h: a device or a FIFO would never end), and the
 * inflated text is held to the scene size limit too, so a small gzip bomb
 * is refused rather than inflated into memory. */
static hr_status read_file(hr_context *ctx, const char *path, char **text, size_t *length)
{
    *text = NULL;
    *length = 0;
    int fd;
    size_t file_size, limit;
    hr_status st = hri_scene_file_open(ctx, path, "scene file", &fd, &file_size, &limit);
    if (st) return st;
    (void)file_size;
    errno = 0;
    gzFile f = gzdopen(fd, "rb");
    if (!f) {
        close(fd);
        return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot open the scene file: %s",
                           path, errno ? strerror(errno) : "out of memory");
    }
    size_t capacity = 0, used = 0;
    char *data = NULL;
    for (;;) {
        if (used == capacity) {
            if (capacity > limit) {
                st = hri_scene_file_too_large(ctx, path, "scene file", limit);
                break;
            }
            size_t grown_capacity = capacity ? 2 * capacity : 256 * 1024;
            if (grown_capacity > limit + 1) grown_capacity = limit + 1;
            char *grown = realloc(data, grown_capacity);
            if (!grown) {
                st = hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
                break;
            }
            data = grown;
            capacity = grown_capacity;
        }
        size_t want = capacity - used;
        if (want > (1u << 30)) want = 1u << 30; /* gzread takes an unsigned count */
        int n = gzread(f, data + used, (unsigned)want);
        int code = Z_OK;
        const char *why = n <= 0 ? gzerror(f, &code) : "";
        /* A stream cut short reads as an end with Z_BUF_ERROR set. */
        if (n < 0 || (code != Z_OK && code != Z_STREAM_END)) {
            st = hri_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot read the scene file: %s",
                             path, code == Z_ERRNO ? strerror(errno) : why);
            break;
        }
        if (n == 0) break;
        used += (size_t)n;
        if (used > limit) {
            st = hri_scene_file_too_large(ctx, path, "scene file", limit);
            break;
        }
    }
    gzclose(f); /* closes fd */
    if (st) {
        free(data);
        return st;
    }
    *text = data;
    *length = used;
    return HR_OK;
}

HR_API hr_status hr_nff_load_file(hr_context *ctx, const char *path, hr_sdl_result *out)
{
    hr_status st = hri_load_result_begin(ctx, out, "NFF");
    if (st) return st;
    if (!path) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_nff_load_file: NULL path");
    char *text;
    size_t length;
    if ((st = read_file(ctx, path, &text, &length))) return st;
    st = load_text(ctx, text, length, path, out);
    free(text);
    return st;
}
