/* Reading a scene file whole, with limits (text_file.h). */
#include "sdl/text_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/env_bytes.h"
#include "util/errors.h"

hr_status hri_scene_file_limit(const hr_context *ctx, size_t *out)
{
    uint64_t v;
    hr_status st = hri_env_bytes(ctx, HR_SCENE_FILE_MAX_BYTES_ENV, "the largest scene file read",
                                HR_SCENE_FILE_MAX_BYTES, HR_SCENE_FILE_MAX_BYTES, SIZE_MAX / 2, &v);
    *out = (size_t)v;
    return st;
}

static hr_status too_large(const hr_context *ctx, const char *path, const char *what, size_t limit)
{
    return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0,
                       "%s: the %s is larger than %zu bytes, the scene size limit (set %s to "
                       "raise it)",
                       path, what, limit, HR_SCENE_FILE_MAX_BYTES_ENV);
}

/* The line and column (1-based, in bytes) of offset `at` in `text`. */
static void place_of(const char *text, size_t at, int32_t *line, int32_t *column)
{
    int64_t l = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < at; i++)
        if (text[i] == '\n') l++, line_start = i + 1;
    int64_t c = (int64_t)(at - line_start) + 1;
    *line = l > INT32_MAX ? INT32_MAX : (int32_t)l;
    *column = c > INT32_MAX ? INT32_MAX : (int32_t)c;
}

static hr_status read_open_file(const hr_context *ctx, int fd, const char *path, const char *what,
                                size_t limit, size_t size_hint, char **text, size_t *length)
{
    /* Room for the whole file as stat saw it plus one byte, so a file that
     * did not change is read in one call and its end seen by the next. */
    size_t capacity = (size_hint < limit ? size_hint : limit) + 1;
    if (capacity < 4096) capacity = 4096;
    size_t used = 0;
    char *data = malloc(capacity + 1);
    if (!data) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
    for (;;) {
        if (used == capacity) {
            if (capacity > limit) {
                free(data);
                return too_large(ctx, path, what, limit);
            }
            size_t grown_capacity = capacity > limit / 2 ? limit + 1 : 2 * capacity;
            char *grown = realloc(data, grown_capacity + 1);
            if (!grown) {
                free(data);
                return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory reading '%s'", path);
            }
            data = grown;
            capacity = grown_capacity;
        }
        ssize_t n = read(fd, data + used, capacity - used);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            int err = errno;
            free(data);
            return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot read the %s: %s", path,
                               what, strerror(err));
        }
        if (n == 0) break;
        const char *nul = memchr(data + used, '\0', (size_t)n);
        if (nul) {
            int32_t line, column;
            place_of(data, (size_t)(nul - data), &line, &column);
            free(data);
            return hri_error_at(ctx, HR_ERROR_SDL, path, line, column,
                               "%s:%d:%d: unexpected NUL byte (is this a text file?)", path,
                               (int)line, (int)column);
        }
        used += (size_t)n;
        if (used > limit) {
            free(data);
            return too_large(ctx, path, what, limit);
        }
    }
    data[used] = '\0';
    *text = data;
    *length = used;
    return HR_OK;
}

hr_status hri_scene_file_open(const hr_context *ctx, const char *path, const char *what, int *fd_out,
                             size_t *size_out, size_t *limit_out)
{
    *fd_out = -1;
    size_t limit;
    hr_status st = hri_scene_file_limit(ctx, &limit);
    if (st) return st;
    /* O_NONBLOCK: opening a FIFO with no writer would otherwise wait for one. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot open the %s: %s", path, what,
                           strerror(errno));
    struct stat info;
    if (fstat(fd, &info) != 0) {
        int err = errno;
        close(fd);
        return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0, "%s: cannot read the %s: %s", path, what,
                           strerror(err));
    }
    if (!S_ISREG(info.st_mode)) {
        close(fd);
        return hri_error_at(ctx, HR_ERROR_IO, path, 0, 0,
                           "%s: cannot read the %s: not a regular file (%s)", path, what,
                           S_ISDIR(info.st_mode)    ? "a directory"
                           : S_ISFIFO(info.st_mode) ? "a FIFO"
                           : S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode) ? "a device"
                                                                            : "a special file");
    }
    if ((uint64_t)info.st_size > (uint64_t)limit) {
        close(fd);
        return too_large(ctx, path, what, limit);
    }
    *fd_out = fd;
    *size_out = (size_t)info.st_size;
    *limit_out = limit;
    return HR_OK;
}

hr_status hri_scene_file_too_large(const hr_context *ctx, const char *path, const char *what,
                                  size_t limit)
{
    return too_large(ctx, path, what, limit);
}

hr_status hri_scene_file_read(const hr_context *ctx, const char *path, const char *what, char **text,
                             size_t *length)
{
    *text = NULL;
    *length = 0;
    int fd;
    size_t size, limit;
    hr_status st = hri_scene_file_open(ctx, path, what, &fd, &size, &limit);
    if (st) return st;
    st = read_open_file(ctx, fd, path, what, limit, size, text, length);
    close(fd);
    return st;
}
