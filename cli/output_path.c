/* Checking an output file's name before any work is done (cli.h): a typo
 * should cost nothing, and a long render should not end in "cannot write". */
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

int cli_has_image_extension(const char *path)
{
    static const char *const extensions[] = {".png", ".exr", ".ppm", ".pfm"};
    size_t n = strlen(path);
    for (size_t i = 0; i < sizeof extensions / sizeof extensions[0]; i++)
        if (n > 4 && strcasecmp(path + n - 4, extensions[i]) == 0) return 1;
    return 0;
}

int cli_check_writable(const char *option, const char *path)
{
    if (!*path) return cli_usage_error("%s: the file name is empty", option);
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (!slash) {
        strcpy(dir, ".");
    } else if (slash == path) {
        strcpy(dir, "/");
    } else if ((size_t)(slash - path) < sizeof dir) {
        memcpy(dir, path, (size_t)(slash - path));
        dir[slash - path] = '\0';
    } else {
        return cli_error("%s: '%s': the name is too long", option, path);
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return cli_error("cannot write '%s': no directory '%s'", path, dir);
    if (access(dir, W_OK) != 0) return cli_error("cannot write '%s': directory '%s' is not writable", path, dir);
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) return cli_error("cannot write '%s': it is a directory", path);
    return 0;
}
