/* Opening a mesh file: the name resolved against the scene's directory,
 * the whole file read into memory, and the reader chosen by the name:
 * Wavefront OBJ for ".obj" (any case), Hill's chapter-6 format otherwise
 * (his files end in ".3vn"). */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mesh.h"
#include "mesh_file.h"

/* Files larger than this are refused before reading (a mesh of ten million
 * triangles in OBJ is well under it). */
#define MESH_MAX_FILE_BYTES ((size_t)1 << 32)

static const char *describe_errno(int e)
{
    switch (e) {
    case ENOENT: return "no such file";
    case EACCES: return "permission denied";
    case EISDIR: return "it is a directory";
    case ENOTDIR: return "a part of the path is not a directory";
    case ENAMETOOLONG: return "the name is too long";
    case ELOOP: return "too many symbolic links";
    default: return "it cannot be opened";
    }
}

static int ends_with_obj(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".obj") == 0;
}

/* Reads the whole regular file at `path` into a block from the host. */
static hr_status read_all(const hr_host *host, const char *path, char **text, size_t *length,
                          char *error, size_t error_size)
{
    *text = NULL;
    *length = 0;
    /* O_NONBLOCK: a FIFO with no writer is refused below instead of
     * waited on (fopen would block in open). */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    FILE *f = fd >= 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        int err = errno;
        if (fd >= 0) close(fd);
        snprintf(error, error_size, "cannot read mesh file '%s': %s", path, describe_errno(err));
        return HR_ERROR_IO;
    }
    struct stat info;
    if (fstat(fileno(f), &info) != 0 || !S_ISREG(info.st_mode)) {
        fclose(f);
        snprintf(error, error_size, "cannot read mesh file '%s': not a regular file", path);
        return HR_ERROR_IO;
    }
    if ((uint64_t)info.st_size > MESH_MAX_FILE_BYTES) {
        fclose(f);
        snprintf(error, error_size, "mesh file '%s' is larger than %zu bytes", path,
                 MESH_MAX_FILE_BYTES);
        return HR_ERROR_IO;
    }
    size_t size = (size_t)info.st_size;
    char *buffer = host->alloc(size + 1);
    if (!buffer) {
        fclose(f);
        return HR_ERROR_OUT_OF_MEMORY;
    }
    size_t got = size ? fread(buffer, 1, size, f) : 0;
    int failed = ferror(f);
    fclose(f);
    if (failed || got != size) {
        host->free(buffer);
        snprintf(error, error_size, "cannot read mesh file '%s': read error", path);
        return HR_ERROR_IO;
    }
    *text = buffer;
    *length = size;
    return HR_OK;
}

hr_status mesh_load_file(const hr_create_args *args, const char *file, mesh **out)
{
    const hr_host *host = args->host;
    const char *base_dir = args->base_dir;
    char *error = args->error;
    const size_t error_size = args->error_size;
    *out = NULL;
    if (!file || !file[0]) {
        snprintf(error, error_size, "'file': no mesh file named");
        return HR_ERROR_PARAMETER;
    }
    const int relative = file[0] != '/' && base_dir && base_dir[0];
    const size_t n = strlen(file) + (relative ? strlen(base_dir) + 1 : 0) + 1;
    char *path = host->alloc(n);
    if (!path) return HR_ERROR_OUT_OF_MEMORY;
    if (relative) snprintf(path, n, "%s/%s", base_dir, file);
    else snprintf(path, n, "%s", file);
    char *text;
    size_t length;
    hr_status st = read_all(host, path, &text, &length, error, error_size);
    /* The scene lists the files it was built from (a shipped scene carries
     * exactly those): an older host has no such service. */
    if (st == HR_OK && HR_HOST_HAS(host, file_read) && host->file_read &&
        (st = host->file_read(args, path)) != HR_OK)
        host->free(text);
    if (st == HR_OK) {
        mesh_builder b;
        mesh_builder_init(&b, host);
        st = ends_with_obj(path) ? mesh_read_obj(&b, text, length, path, error, error_size)
                                 : mesh_read_3vn(&b, text, length, path, error, error_size);
        host->free(text);
        if (st == HR_OK) {
            char why[256] = "";
            st = mesh_builder_finish(&b, out, why, sizeof why);
            if (st == HR_ERROR_PARAMETER) snprintf(error, error_size, "%s: %s", path, why);
        }
        mesh_builder_release(&b);
    }
    if (st == HR_ERROR_OUT_OF_MEMORY && error[0] == '\0')
        snprintf(error, error_size, "%s: out of memory", path);
    host->free(path);
    return st;
}
