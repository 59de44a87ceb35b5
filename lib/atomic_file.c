/* Writing a file all or nothing (atomic_file.h). */
#include "atomic_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "errors.h"
#include "strutil.h"

/* The process's umask, read without changing it: umask() can only be read by
 * setting it, which would race with other threads creating files. Linux
 * reports it in /proc/self/status; elsewhere assume the common 022. */
static mode_t current_umask(void)
{
    mode_t mask = 022;
    FILE *status = fopen("/proc/self/status", "r");
    if (!status) return mask;
    char line[256];
    while (fgets(line, sizeof line, status)) {
        unsigned int value;
        if (sscanf(line, "Umask: %o", &value) == 1) {
            mask = (mode_t)(value & 0777u);
            break;
        }
    }
    fclose(status);
    return mask;
}

/* mkstemp makes the file 0600; give it the permissions the target would
 * have got from a plain fopen (or keeps those of the file it replaces), so
 * writing atomically is invisible to the user. */
static mode_t mode_for(const char *target)
{
    struct stat st;
    /* Permission bits only: a set-user-ID bit must not pass to new content. */
    if (stat(target, &st) == 0 && S_ISREG(st.st_mode)) return st.st_mode & 0777;
    return (mode_t)0666 & ~current_umask();
}

/* The most of the target's name that goes into the temporary one: with the
 * 8 bytes around it, a name of NAME_MAX (255) bytes still gets a temporary
 * file (truncating a UTF-8 sequence in a hidden name is harmless). */
#define TEMP_BASE_MAX 200

/* "dir/.name.XXXXXX" for "dir/name": hidden, and in the same directory. */
static char *temp_template(const char *target)
{
    const char *slash = strrchr(target, '/');
    const char *base = slash ? slash + 1 : target;
    char *dir = hr_path_dirname(target);
    if (!dir) return NULL;
    size_t nb = strlen(base) < TEMP_BASE_MAX ? strlen(base) : TEMP_BASE_MAX;
    size_t n = strlen(dir) + nb + sizeof "/..XXXXXX";
    char *templ = malloc(n);
    if (templ) snprintf(templ, n, "%s/.%.*s.XXXXXX", dir, (int)nb, base);
    free(dir);
    return templ;
}

hr_status hr_atomic_file_open(const hr_context *ctx, const char *target, hr_atomic_file *out)
{
    memset(out, 0, sizeof *out);
    if (!target || !*target)
        return hr_error(ctx, HR_ERROR_INVALID_ARGUMENT, "cannot write an image: empty file name");
    size_t len = strlen(target);
    if (target[len - 1] == '/')
        return hr_error(ctx, HR_ERROR_IO, "cannot write '%s': the name is a directory", target);

    /* Through a symbolic link to the file it names, so the rename replaces
     * that file and the link survives. */
    struct stat link_st;
    char *destination = NULL;
    if (lstat(target, &link_st) == 0 && S_ISLNK(link_st.st_mode)) destination = realpath(target, NULL);
    if (!destination) destination = hr_strdup(target);
    char *templ = destination ? temp_template(destination) : NULL;
    if (!templ) {
        free(destination);
        return hr_error(ctx, HR_ERROR_OUT_OF_MEMORY, "cannot write '%s': out of memory", target);
    }
    int fd = mkstemp(templ);
    if (fd < 0) {
        int err = errno;
        free(templ);
        free(destination);
        return hr_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", target, strerror(err));
    }
    FILE *fp = NULL;
    if (fchmod(fd, mode_for(destination)) != 0 || !(fp = fdopen(fd, "wb"))) {
        int err = errno;
        close(fd);
        unlink(templ);
        free(templ);
        free(destination);
        return hr_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", target, strerror(err));
    }
    out->target = target;
    out->destination = destination;
    out->temp_path = templ;
    out->fp = fp;
    return HR_OK;
}

static void release(hr_atomic_file *f)
{
    free(f->temp_path);
    free(f->destination);
    memset(f, 0, sizeof *f);
}

hr_status hr_atomic_file_commit(const hr_context *ctx, hr_atomic_file *f)
{
    /* Everything must reach the disk before the rename publishes the file:
     * a crash after the rename must not leave an empty or partial image. */
    int err = 0;
    if (fflush(f->fp) != 0 || fsync(fileno(f->fp)) != 0) err = errno;
    if (fclose(f->fp) != 0 && !err) err = errno;
    f->fp = NULL;
    if (!err && rename(f->temp_path, f->destination) != 0) err = errno;
    if (err) {
        unlink(f->temp_path);
        hr_status st = hr_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", f->target, strerror(err));
        release(f);
        return st;
    }
    release(f);
    return HR_OK;
}

void hr_atomic_file_abort(hr_atomic_file *f)
{
    if (f->fp) fclose(f->fp);
    if (f->temp_path) unlink(f->temp_path);
    release(f);
}
