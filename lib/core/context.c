/* The context: its state, search directories, version (hr_context_create,
 * which gives it the host table, is trace/host_services.c). Module loading and
 * class lookup live in module_loader.c; errors in errors.c. */
#include <stdlib.h>
#include <string.h>

#include "core/context_internal.h"
#include "util/errors.h"
#include "core/module_loader.h"
#include "util/strutil.h"

hr_context *hri_context_new(void)
{
    hr_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx) return NULL;
    if (pthread_mutex_init(&ctx->lock, NULL) != 0) {
        free(ctx);
        return NULL;
    }
    if (pthread_key_create(&ctx->error_key, free) != 0) {
        pthread_mutex_destroy(&ctx->lock);
        free(ctx);
        return NULL;
    }
    return ctx;
}

HR_API void hr_context_destroy(hr_context *ctx)
{
    if (!ctx) return;
    hri_modules_unload_all(ctx);
    for (int32_t i = 0; i < ctx->dir_count; i++) free(ctx->dirs[i]);
    free(ctx->dirs);
    /* Only the calling thread's slot can be reached; other threads' slots are
     * freed by the key's destructor when they exit. */
    free(pthread_getspecific(ctx->error_key));
    pthread_setspecific(ctx->error_key, NULL);
    pthread_key_delete(ctx->error_key);
    pthread_mutex_destroy(&ctx->lock);
    free(ctx);
}

HR_API hr_status hr_context_set_scene_memory(hr_context *ctx, uint64_t bytes)
{
    if (!ctx) return HR_ERROR_INVALID_ARGUMENT;
    ctx->scene_memory = bytes;
    return HR_OK;
}

HR_API hr_status hr_context_add_shape_dir(hr_context *ctx, const char *dir)
{
    if (!ctx) return HR_ERROR_INVALID_ARGUMENT;
    if (!dir || !*dir) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "empty shape directory");
    char *copy = hri_strdup(dir);
    if (!copy) return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    pthread_mutex_lock(&ctx->lock);
    char **dirs = realloc(ctx->dirs, (size_t)(ctx->dir_count + 1) * sizeof *dirs);
    if (!dirs) {
        pthread_mutex_unlock(&ctx->lock);
        free(copy);
        return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    dirs[ctx->dir_count++] = copy;
    ctx->dirs = dirs;
    /* A directory added after a scan is read on the next lookup miss. */
    ctx->scanned = 0;
    pthread_mutex_unlock(&ctx->lock);
    return HR_OK;
}

HR_API void hr_version(int32_t *major, int32_t *minor, int32_t *patch)
{
    if (major) *major = HR_VERSION_MAJOR;
    if (minor) *minor = HR_VERSION_MINOR;
    if (patch) *patch = HR_VERSION_PATCH;
}
