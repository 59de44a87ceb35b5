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
                            const char *file, hr_sdl_result *result)
{
    hr_scene *scene = NULL;
    nff_reader reader;
    memset(&reader, 0, sizeof reader);
    hr_status st = hr_scene_create(ctx, &scene);
    if (!st && file) st = hr_scene_note_file(scene, file);
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

/* `file`: the path the text was read from, NULL for text given. */
static hr_status load_text(hr_context *ctx, const char *text, size_t length, const char *name,
                           const char *file, hr_sdl_result *out)
{
    hr_sdl_result result;
    hri_load_result_empty(&result);
    hr_status st = read_scene(ctx, text, length, name, file, &result);
    hri_load_result_give(out, &result);
    return st;
}

HR_API hr_status hr_nff_load_string(hr_context *ctx, const char *text, const char *name,
                                    hr_sdl_result *out)
{
    hr_status st = hri_load_result_begin(ctx, out, "NFF");
    if (st) return st;
    if (!text) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_nff_load_string: NULL text");
    return load_text(ctx, text, strlen(text), name ? name : "<string>", NULL, out);
}

/* The file's bytes as they are (a plain NFF file), or inflated where they
 * start with gzip's magic bytes, every member in turn (as gzip -d reads
 * concatenated members). zlib's inflate on the bytes in memory, not gzread:
 * gzread ignores whatever follows the last member and names the file
 * "<fd:3>" in its messages. Only a regular file is read (text_file.h: a
 * device or a FIFO would never end), and the inflated text is held to the
 * scene size limit too, so a small gzip bomb is refused rather than
 * inflated into memory. Takes `raw` (size bytes, malloc'd). */
static hr_status inflate_file(hr_context *ctx, const char *path, unsigned char *raw, size_t size,
                              size_t limit, char **text, size_t *length)
{
    if (size < 2 || raw[0] != 0x1f || raw[1] != 0x8b) {
        *text = (char *)raw;
        *length = size;
        return HR_OK;
    }
    z_stream zs;
    memset(&zs, 0, sizeof zs);
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) {
        free(raw);
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
    }
    zs.next_in = raw;
    zs.avail_in = (uInt)size; /* at most the scene limit, 256 MiB by default */
    size_t capacity = 0;
    char *data = NULL;
    hr_status st = HR_OK;
    for (;;) {
        const size_t used = capacity - zs.avail_out;
        if (zs.avail_out == 0) {
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
            zs.next_out = (Bytef *)data + used;
            zs.avail_out = (uInt)(capacity - used);
        }
        const int code = inflate(&zs, Z_NO_FLUSH);
        if (code == Z_STREAM_END) {
            if (zs.avail_in == 0) break;
            /* Another member, or bytes that are no gzip stream. */
            if (zs.avail_in >= 2 && zs.next_in[0] == 0x1f && zs.next_in[1] == 0x8b &&
                inflateReset(&zs) == Z_OK)
                continue;
            st = hri_error_at(ctx, HR_ERROR_IO, path, 0, 0,
                              "%s: cannot read the scene file: %u bytes after the end of the gzip "
                              "stream (at byte %zu of %zu) are not a gzip member: a damaged or "
                              "appended-to file",
                              path, (unsigned)zs.avail_in, size - zs.avail_in, size);
            break;
        }
        if (code == Z_OK || (code == Z_BUF_ERROR && zs.avail_out == 0)) continue;
        if (code == Z_BUF_ERROR) /* no input left, no end of stream */
            st = hri_error_at(ctx, HR_ERROR_IO, path, 0, 0,
                              "%s: cannot read the scene file: the gzip stream is cut short (the file ends "
                              "after %zu bytes)", path,
                              size);
        else if (code == Z_MEM_ERROR)
            st = hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
        else
            st = hri_error_at(ctx, HR_ERROR_IO, path, 0, 0,
                              "%s: cannot read the scene file: bad gzip data at byte %zu: %s", path,
                              size - zs.avail_in, zs.msg ? zs.msg : "corrupt stream");
        break;
    }
    const size_t used = capacity - zs.avail_out;
    inflateEnd(&zs);
    free(raw);
    if (!st && used > limit) st = hri_scene_file_too_large(ctx, path, "scene file", limit);
    if (st) {
        free(data);
        return st;
    }
    *text = data;
    *length = used;
    return HR_OK;
}

/* The whole file (inflate_file). */
static hr_status read_file(hr_context *ctx, const char *path, char **text, size_t *length)
{
    *text = NULL;
    *length = 0;
    int fd;
    size_t file_size, limit;
    hr_status st = hri_scene_file_open(ctx, path, "scene file", &fd, &file_size, &limit);
    if (st) return st;
    /* The size stat saw (at most the limit), and one byte more to see the
     * end; a file that grew past the limit meanwhile is refused. */
    unsigned char *raw = malloc(file_size + 1);
    if (!raw) {
        close(fd);
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
    }
    size_t size = 0;
    for (;;) {
        ssize_t n = read(fd, raw + size, file_size + 1 - size);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int err = errno;
            close(fd);
            free(raw);
            return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot read the scene file: %s",
                                path, strerror(err));
        }
        if (n == 0) break;
        size += (size_t)n;
        if (size > file_size) {
            close(fd);
            free(raw);
            return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0,
                                "%s: the scene file grew while it was read", path);
        }
    }
    close(fd);
    return inflate_file(ctx, path, raw, size, limit, text, length);
}

HR_API hr_status hr_nff_load_file(hr_context *ctx, const char *path, hr_sdl_result *out)
{
    hr_status st = hri_load_result_begin(ctx, out, "NFF");
    if (st) return st;
    if (!path) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_nff_load_file: NULL path");
    char *text;
    size_t length;
    if ((st = read_file(ctx, path, &text, &length))) return st;
    st = load_text(ctx, text, length, path, path, out);
    free(text);
    return st;
}
