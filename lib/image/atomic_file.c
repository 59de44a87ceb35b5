/* Writing a file all or nothing (atomic_file.h). */
#include "image/atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "util/errors.h"
#include "util/strutil.h"

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
    char *dir = hri_path_dirname(target);
    if (!dir) return NULL;
    size_t nb = strlen(base) < TEMP_BASE_MAX ? strlen(base) : TEMP_BASE_MAX;
    size_t n = strlen(dir) + nb + sizeof "/..XXXXXX";
    char *templ = malloc(n);
    if (templ) snprintf(templ, n, "%s/.%.*s.XXXXXX", dir, (int)nb, base);
    free(dir);
    return templ;
}

/* The target as it is now, links followed: absent, or a regular file the
 * caller may write. Anything else is refused rather than replaced. */
static hr_status check_target(const hr_context *ctx, const char *target)
{
    struct stat st;
    if (stat(target, &st) != 0) return HR_OK; /* absent (or a dangling link): created */
    if (!S_ISREG(st.st_mode))
        return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': not a regular file (%s)", target,
                        S_ISDIR(st.st_mode)    ? "a directory"
                        : S_ISFIFO(st.st_mode) ? "a FIFO"
                        : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                     : "a special file");
    /* access() grants root everything; a file nobody may write is read-only
     * for root too, as far as replacing it goes. */
    if ((st.st_mode & 0222) == 0 || access(target, W_OK) != 0)
        return hri_error(ctx, HR_ERROR_IO,
                        "cannot write '%s': the file is read-only (mode %04o); make it writable "
                        "or remove it first",
                        target, (unsigned)(st.st_mode & 07777));
    return HR_OK;
}

/* An unnamed file in `dir` (O_TMPFILE), or -1 where the filesystem or the
 * kernel has none. */
static int open_unnamed(const char *destination)
{
#ifdef O_TMPFILE
    char *dir = hri_path_dirname(destination);
    if (!dir) return -1;
    int fd = open(dir, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
    free(dir);
    return fd;
#else
    (void)destination;
    return -1;
#endif
}

hr_status hri_atomic_file_open(const hr_context *ctx, const char *target, hr_atomic_file *out)
{
    memset(out, 0, sizeof *out);
    if (!target || !*target)
        return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "cannot write an image: empty file name");
    size_t len = strlen(target);
    if (target[len - 1] == '/')
        return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': the name is a directory", target);
    hr_status checked = check_target(ctx, target);
    if (checked) return checked;

    /* Through a symbolic link to the file it names, so the rename replaces
     * that file and the link survives. */
    struct stat link_st;
    char *destination = NULL;
    if (lstat(target, &link_st) == 0 && S_ISLNK(link_st.st_mode)) destination = realpath(target, NULL);
    if (!destination) destination = hri_strdup(target);
    if (!destination) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "cannot write '%s': out of memory", target);
    char *templ = NULL;
    int fd = open_unnamed(destination);
    if (fd < 0) {
        templ = temp_template(destination);
        if (!templ) {
            free(destination);
            return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "cannot write '%s': out of memory", target);
        }
        fd = mkstemp(templ);
    }
    if (fd < 0) {
        int err = errno;
        free(templ);
        free(destination);
        return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", target, strerror(err));
    }
    FILE *fp = NULL;
    if (fchmod(fd, mode_for(destination)) != 0 || !(fp = fdopen(fd, "wb"))) {
        int err = errno;
        close(fd);
        if (templ) unlink(templ);
        free(templ);
        free(destination);
        return hri_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", target, strerror(err));
    }
    out->target = target;
    out->destination = destination;
    out->temp_path = templ;
    out->fp = fp;
    return HR_OK;
}

static void release(hr_atomic_file *f)
{
    if (f->fp) fclose(f->fp);
    free(f->temp_path);
    free(f->destination);
    memset(f, 0, sizeof *f);
}

static hr_status fail(const hr_context *ctx, hr_atomic_file *f, int err)
{
    hr_status st = hri_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", f->target, strerror(err));
    hri_atomic_file_abort(f);
    return st;
}

hr_status hri_atomic_file_finish(const hr_context *ctx, hr_atomic_file *f)
{
    /* Everything must reach the disk before the rename publishes the file:
     * a crash after the rename must not leave an empty or partial image. */
    if (fflush(f->fp) != 0 || fsync(fileno(f->fp)) != 0) return fail(ctx, f, errno);
    f->finished = 1;
    return HR_OK;
}

/* Give the unnamed file a name beside its target: a hidden one no other
 * file has, made through /proc/self/fd (linkat with AT_EMPTY_PATH needs a
 * privilege). It exists only until the rename that follows. */
static int name_unnamed(hr_atomic_file *f)
{
    char *templ = temp_template(f->destination);
    if (!templ) return ENOMEM;
    size_t n = strlen(templ);
    char proc[64];
    snprintf(proc, sizeof proc, "/proc/self/fd/%d", fileno(f->fp));
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    unsigned long long seed = (unsigned long long)ts.tv_nsec ^ ((unsigned long long)getpid() << 20);
    static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    int err = EEXIST;
    for (int attempt = 0; attempt < 100 && err == EEXIST; attempt++) {
        for (size_t i = n - 6; i < n; i++) {
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            templ[i] = letters[(seed >> 33) % (sizeof letters - 1)];
        }
        err = linkat(AT_FDCWD, proc, AT_FDCWD, templ, AT_SYMLINK_FOLLOW) == 0 ? 0 : errno;
    }
    if (err) {
        free(templ);
        return err;
    }
    f->temp_path = templ;
    return 0;
}

hr_status hri_atomic_file_publish(const hr_context *ctx, hr_atomic_file *f)
{
    int err = 0;
    if (!f->temp_path) err = name_unnamed(f);
    if (!err && rename(f->temp_path, f->destination) != 0) err = errno;
    if (err) return fail(ctx, f, err);
    free(f->temp_path);
    f->temp_path = NULL; /* in place: nothing to remove */
    if (fclose(f->fp) != 0) err = errno; /* the data is synced: only report */
    f->fp = NULL;
    hr_status st = err ? hri_error(ctx, HR_ERROR_IO, "cannot write '%s': %s", f->target, strerror(err)) : HR_OK;
    release(f);
    return st;
}

void hri_atomic_file_abort(hr_atomic_file *f)
{
    if (f->fp) fclose(f->fp); /* an unnamed file goes with its last descriptor */
    f->fp = NULL;
    if (f->temp_path) unlink(f->temp_path);
    release(f);
}
