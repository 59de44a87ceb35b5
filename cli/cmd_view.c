/* hitray view: hands over to the viewer program, hitray-view.
 *
 * The window needs SDL2, and `hitray` links nothing but libhitray (a
 * machine without a display, or without SDL2, still renders), so the viewer
 * is its own executable, built and installed beside this one; `hitray view
 * ARGS` runs `hitray-view ARGS` from the directory this binary lies in
 * (build/bin in the build tree, bin/ when installed), never from PATH, so
 * the two always come from the same build. */
#include <errno.h>
#include <limits.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

#define VIEWER_NAME "hitray-view"

int cmd_view(int argc, char **argv)
{
    char path[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    if (n < 0) return cli_error("view: cannot tell where this program lies (/proc/self/exe: %s)", strerror(errno));
    path[n] = '\0';
    char *slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    if (dir_len + sizeof VIEWER_NAME > sizeof path) return cli_error("view: the program's path is too long");
    memcpy(path + dir_len, VIEWER_NAME, sizeof VIEWER_NAME);
    if (access(path, X_OK) != 0)
        return cli_error("view: the viewer '%s' is not there (it is built only where SDL2 is installed, "
                         "so pip's wheels leave it out: install Debian's libsdl2-dev and build from source, "
                         "make build)",
                         path);
    /* The viewer reads argv[0] as its verb, as every cmd_* does. */
    char *viewer_argv[argc + 1];
    viewer_argv[0] = path;
    for (int i = 1; i < argc; i++) viewer_argv[i] = argv[i];
    viewer_argv[argc] = NULL;
    fflush(stdout);
    execv(path, viewer_argv);
    return cli_error("view: cannot run '%s': %s", path, strerror(errno));
}
