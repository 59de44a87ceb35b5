/* The files a scene was built from (hr_scene_file): noted by the readers
 * through the public hr_scene_note_file, and by the host for a shape's
 * create through hr_host.file_read, which finds the scene from the create
 * call it is told (hri_scene_create_begin). */
#define _POSIX_C_SOURCE 200809L /* getcwd */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/scene_internal.h"
#include "util/errors.h"
#include "util/strutil.h"

/* `path` made absolute with the working directory: a malloc'd copy, NULL
 * when out of memory or the directory cannot be named. */
static char *absolute(const char *path)
{
    if (path[0] == '/') return hri_strdup(path);
    size_t size = 256;
    for (;;) {
        char *dir = malloc(size);
        if (!dir) return NULL;
        if (getcwd(dir, size)) {
            char *full = hri_path_join(dir, path);
            free(dir);
            return full;
        }
        free(dir);
        if (errno != ERANGE || size > ((size_t)1 << 20)) return NULL;
        size *= 2;
    }
}

HR_API hr_status hr_scene_note_file(hr_scene *s, const char *path)
{
    if (!s) return HR_ERROR_INVALID_ARGUMENT;
    if (!path || !path[0]) return hri_error(s->ctx, HR_ERROR_INVALID_ARGUMENT, "hr_scene_note_file: no path");
    char *full = absolute(path);
    if (!full) return hri_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory noting the file '%s'", path);
    /* A scene reads few distinct files (one mesh file may serve many
     * objects): the newest first, where a repeat usually is. */
    for (int64_t i = s->file_count - 1; i >= 0; i--)
        if (strcmp(s->files[i], full) == 0) {
            free(full);
            return HR_OK;
        }
    if (s->file_count == s->file_cap) {
        const int64_t cap = s->file_cap ? 2 * s->file_cap : 4;
        char **grown = realloc(s->files, (size_t)cap * sizeof *grown);
        if (!grown) {
            free(full);
            return hri_error(s->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory noting the file '%s'", path);
        }
        s->files = grown, s->file_cap = cap;
    }
    s->files[s->file_count++] = full;
    return HR_OK;
}

HR_API int64_t hr_scene_file_count(const hr_scene *s)
{
    return s ? s->file_count : 0;
}

HR_API const char *hr_scene_file(const hr_scene *s, int64_t index)
{
    return s && index >= 0 && index < s->file_count ? s->files[index] : NULL;
}

void hri_scene_files_free(hr_scene *s)
{
    for (int64_t i = 0; i < s->file_count; i++) free(s->files[i]);
    free(s->files);
    s->files = NULL, s->file_count = s->file_cap = 0;
}

/* The create call in progress on this thread and its scene. */
static _Thread_local const hr_create_args *creating_args;
static _Thread_local hr_scene *creating_scene;

void hri_scene_create_begin(hr_scene *s, const hr_create_args *args)
{
    creating_scene = s, creating_args = args;
}

void hri_scene_create_end(void)
{
    creating_scene = NULL, creating_args = NULL;
}

hr_status hri_scene_create_file_read(const hr_create_args *args, const char *path)
{
    /* Only the create this thread is in, and only with its own arguments:
     * a call from anywhere else is ignored. */
    if (!args || args != creating_args || !creating_scene || !path) return HR_OK;
    hr_status st = hr_scene_note_file(creating_scene, path);
    return st == HR_ERROR_OUT_OF_MEMORY ? st : HR_OK;
}
