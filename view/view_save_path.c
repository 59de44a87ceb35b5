/* Where the P key saves (view.h): the -o name, or the first numbered name
 * beside it that no file has, so that no picture is overwritten. */
#include <stdio.h>
#include <string.h>

#include "view.h"

/* Numbers tried before giving up: a directory with this many pictures of
 * one name is not one to write more into blindly. */
#define VIEW_MAX_NUMBER 100000

int view_save_path(const char *path, int (*exists)(const char *path, void *user), void *user, char *out,
                   size_t size)
{
    size_t len = strlen(path);
    if (len >= size) return 0;
    if (!exists(path, user)) {
        memcpy(out, path, len + 1);
        return 1;
    }
    /* The number goes before the extension: the last '.' of the file's
     * name, unless the name starts with it (".png" alone is a name). */
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    size_t stem = dot && dot > base ? (size_t)(dot - path) : len;
    for (int n = 2; n <= VIEW_MAX_NUMBER; n++) {
        int written = snprintf(out, size, "%.*s-%d%s", (int)stem, path, n, path + stem);
        if (written < 0 || (size_t)written >= size) return 0;
        if (!exists(out, user)) return 1;
    }
    return 0;
}
