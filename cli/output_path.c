/* Checking an output file's name before any work is done (cli.h): a typo
 * should cost nothing, and a long render should not end in "cannot write". */
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

/* Every --format name, as one phrase for messages ("png, exr, ppm or pfm"). */
static void format_names(char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int32_t code = HR_FORMAT_PNG; hr_image_format_name(code) && used < size; code++) {
        const char *sep = code == HR_FORMAT_PNG ? "" : hr_image_format_name(code + 1) ? ", " : " or ";
        int n = snprintf(buf + used, size - used, "%s%s", sep, hr_image_format_name(code));
        if (n < 0) return;
        used += (size_t)n;
    }
}

int cli_output_format(const char *option, const char *path, const char *format_name, int32_t *format)
{
    char known[256];
    int32_t by_name = path ? hr_image_format_from_path(path) : HR_FORMAT_AUTO;
    if (format_name) {
        *format = hr_image_format_from_name(format_name);
        if (*format == HR_FORMAT_AUTO) {
            format_names(known, sizeof known);
            return cli_usage_error("--format: unknown format '%s' (use %s)", format_name, known);
        }
        /* A file named .jpg holding a PNG would lie about its content. */
        if (by_name != HR_FORMAT_AUTO && by_name != *format)
            return cli_usage_error("%s: '%s' names a %s file, not %s (--format %s)", option, path,
                                   hr_image_format_name(by_name), format_name, format_name);
        return 0;
    }
    if (path && !strcmp(path, "-")) {
        *format = HR_FORMAT_PNG;
        return 0;
    }
    *format = by_name;
    if (*format != HR_FORMAT_AUTO) return 0;
    hr_image_format_list(known, sizeof known);
    return cli_usage_error("%s: cannot tell the format of '%s' from its extension (use %s, or --format)", option,
                           path, known);
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
