/* The public NFF entry points (include/hitray/nff.h): read the text (through
 * zlib, which reads gzip and plain files alike), run the reader over a new
 * scene, frame a camera if the file has no `v`. On any error the partial
 * scene is destroyed and out->scene is NULL. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "errors.h"
#include "load_result.h"
#include "nff_reader.h"

/* The largest text read: far above the SPD's largest (a few MiB at size
 * factor 4, hundreds at the largest factors), and a bound on what a small
 * gzip file can inflate to. */
#define NFF_MAX_TEXT ((size_t)1 << 32)

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
        if (!reader.has_camera) st = hr_scene_frame_camera(scene, &result->camera);
    }
    nff_reader_release(&reader);
    if (st) {
        hr_scene_destroy(scene);
        hr_load_result_empty(result);
    }
    return st;
}

static hr_status load_text(hr_context *ctx, const char *text, size_t length, const char *name,
                           hr_sdl_result *out)
{
    hr_sdl_result result;
    hr_load_result_empty(&result);
    hr_status st = read_scene(ctx, text, length, name, &result);
    hr_load_result_give(out, &result);
    return st;
}

HR_API hr_status hr_nff_load_string(hr_context *ctx, const char *text, const char *name,
                                    hr_sdl_result *out)
{
    hr_status st = hr_load_result_begin(ctx, out, "NFF");
    if (st) return st;
    if (!text) return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_nff_load_string: NULL text");
    return load_text(ctx, text, strlen(text), name ? name : "<string>", out);
}

/* The whole file, inflated if it is gzip, read in pieces: its size is not
 * asked first, so pipes work too. */
static hr_status read_file(hr_context *ctx, const char *path, char **text, size_t *length)
{
    *text = NULL;
    *length = 0;
    errno = 0;
    gzFile f = gzopen(path, "rb");
    if (!f)
        return hr_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot open the scene file: %s",
                           path, errno ? strerror(errno) : "out of memory");
    size_t capacity = 0, used = 0;
    char *data = NULL;
    hr_status st = HR_OK;
    for (;;) {
        if (used == capacity) {
            size_t grown_capacity = capacity ? 2 * capacity : 256 * 1024;
            char *grown = grown_capacity <= NFF_MAX_TEXT ? realloc(data, grown_capacity) : NULL;
            if (!grown) {
                st = grown_capacity <= NFF_MAX_TEXT
                         ? hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path)
                         : hr_error_at(ctx, HR_ERROR_IO, path, 0, 0,
                                       "%s: the scene is larger than %zu bytes", path,
                                       NFF_MAX_TEXT);
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
            st = hr_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot read the scene file: %s",
                             path, code == Z_ERRNO ? strerror(errno) : why);
            break;
        }
        if (n == 0) break;
        used += (size_t)n;
    }
    gzclose(f);
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
    hr_status st = hr_load_result_begin(ctx, out, "NFF");
    if (st) return st;
    if (!path) return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_nff_load_file: NULL path");
    char *text;
    size_t length;
    if ((st = read_file(ctx, path, &text, &length))) return st;
    st = load_text(ctx, text, length, path, out);
    free(text);
    return st;
}
